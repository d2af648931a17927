"""Dataset grids: expansion, seeds and validation (no simulation runs here)."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from ballpass.datasets import Grid, example_grid, read_grid
from ballpass.datasets.grid import count_points, run_seed

BASE = {
    "dataset": {"duration_s": 0.05, "fs": 12000, "repeats": 2, "seed": 7},
    "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"],
             "fault_width_mm": [0.2, 0.5], "fault_depth_mm": [0.1], "rpm": [1797],
             "resonance_hz": [3000], "sensor": ["loaded", "unloaded"]},
}


def with_(table, **changes):
    """BASE with keys of one table replaced (a value of None removes the key)."""
    out = json.loads(json.dumps(BASE))
    out[table].update(changes)
    out[table] = {k: v for k, v in out[table].items() if v is not None}
    return out


def test_healthy_rows_do_not_multiply_over_fault_sizes():
    g = read_grid(BASE)
    # (1 healthy + 2 faults x 2 widths) points x 2 repeats; one row per sensor
    assert g.n_runs == 5 * 2
    assert g.n_rows == 5 * 2 * 2
    labels = [r.build_scene().label for r in g.runs]
    assert labels.count("healthy") == 2
    widths = {r.build_scene().fault.width_mm for r in g.runs if r.scene.get("fault")}
    assert widths == {0.2, 0.5}


def test_run_seeds_are_seedsequence_children_and_unique():
    g = read_grid(BASE)
    children = np.random.SeedSequence(7).spawn(g.n_runs)
    for run, child in zip(g.runs, children, strict=True):
        expected = int(child.generate_state(1, np.uint64)[0] >> np.uint64(1))
        assert run.seed == expected == run_seed(7, run.run_id)
        assert run.build_scene().seed == run.seed
    assert len({r.seed for r in g.runs}) == g.n_runs
    assert [r.repeat for r in g.runs[:4]] == [0, 1, 0, 1]


def test_ranges_include_stop_and_ramps():
    g = read_grid(with_("grid", rpm={"start": 500, "stop": 3000, "step": 500}))
    assert g.axes["rpm"] == [500.0, 1000.0, 1500.0, 2000.0, 2500.0, 3000.0]
    g = read_grid(with_("grid", fault_width_mm={"start": 0.1, "stop": 0.3, "step": 0.1}))
    assert g.axes["fault_width_mm"] == [0.1, 0.2, 0.3]   # no float drift (0.30000000000000004)
    g = read_grid(with_("grid", rpm=[[1000, 1500], 1797]))
    assert g.runs[0].build_scene().speed.rpm_end == 1500.0


def test_segments_and_shards():
    g = read_grid(with_("dataset", duration_s=0.05, segment_s=0.02, shard_size=3))
    assert g.signal_length == 240 and g.n_segments == 2      # 600 samples, remainder dropped
    assert g.n_rows == g.n_runs * 2 * 2
    assert g.n_shards == math.ceil(g.n_runs / 3)
    assert [len(g.shard_runs(i)) for i in range(g.n_shards)] == [3, 3, 3, 1]


def test_as_dict_round_trips_through_json():
    g = read_grid(with_("grid", snr_db=[math.inf, 10], sensor=["loaded", {"angle_deg": 90}],
                        model=["sr5", "sr4"]))
    d = json.loads(json.dumps(g.as_dict(), allow_nan=False))
    assert d["grid"]["snr_db"] == ["inf", 10.0]
    g2 = read_grid(d)
    assert g2 == g and g2.runs == g.runs
    assert g.runs[0].build_scene().snr_db is None        # inf = noise-free
    assert [s.name for s in g.runs[0].build_scene().sensors] == ["loaded", "sensor_90deg"]
    assert [r.model for r in g.runs[:4]] == ["sr5", "sr5", "sr4", "sr4"]


def test_toml_file(tmp_path):
    path = tmp_path / "g.toml"
    path.write_text('[dataset]\nfs = 12000\nduration_s = 0.05\n[grid]\nbearing = ["6205"]\n'
                    'fault = ["healthy"]\nrpm = { start = 1700, stop = 1800, step = 50 }\n'
                    'resonance_hz = [3000]\n')
    g = read_grid(path)
    assert isinstance(g, Grid) and g.n_runs == 3
    assert read_grid(g) is g


@pytest.mark.parametrize("grid, message", [
    (with_("grid", speed=[1]), r"unknown grid axis.*'speed'"),
    (with_("dataset", fps=1), r"unknown \[dataset\] key.*'fps'"),
    (with_("grid", rpm=[]), r"grid.rpm is an empty list"),
    (with_("grid", rpm={"start": 3000, "stop": 500, "step": 500}), r"grid.rpm: range stop"),
    (with_("grid", rpm={"start": 500, "stop": 3000, "step": -500}), r"grid.rpm: range step"),
    (with_("grid", rpm={"start": 500, "stop": 3000}), r"grid.rpm: a range is a table"),
    (with_("grid", rpm=["fast"]), r"grid.rpm\[0\] must be a number"),
    (with_("grid", rpm=[-100]), r"rpm must be a finite number in \(0"),
    (with_("grid", fault=["cage"]), r"grid.fault\[0\] must be one of"),
    (with_("grid", bearing=[6205]), r"grid.bearing\[0\] must be a catalogue"),
    (with_("grid", bearing=["nope"]), r"unknown bearing 'nope'"),
    (with_("grid", sensor=["top"]), r"grid.sensor\[0\]"),
    (with_("grid", rpm=[1797, 1797.0]), r"grid.rpm has duplicate values"),
    (with_("grid", resonance_hz=[15000]), r"resonance_hz=15000 lies above 0.45\*fs"),
    (with_("grid", fault_width_mm=[20.0]), r"fault_width_mm=20.0.*element spacing"),
    (with_("grid", rpm=None), r"missing required axis.*'rpm'"),
    (with_("dataset", repeats=0), r"dataset.repeats must be an int >= 1"),
    (with_("dataset", repeats=1.5), r"dataset.repeats must be an int"),
    (with_("dataset", fs="12k"), r"dataset.fs must be a positive number"),
    (with_("dataset", segment_s=1.0), r"dataset.segment_s=1 s is longer"),
    (with_("dataset", model="sr5") | {"grid": {**BASE["grid"], "model": ["sr4"]}},
     r"either as \[dataset\] model or as the grid.model axis"),
    ({**BASE, "extra": {}}, r"unknown table"),
])
def test_bad_grids_name_the_key(grid, message):
    with pytest.raises(ValueError, match=message):
        read_grid(grid)


def test_malformed_toml_names_the_file(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text("[grid]\nrpm = [1797,\n")
    with pytest.raises(ValueError, match=r"bad.toml: not a valid TOML grid file"):
        read_grid(path)


def test_noise_floor_and_resonance_damping_axes():
    g = read_grid(with_("grid", noise_rms=[0.0, 0.6], resonance_damping=[0.01, 0.05]))
    # (1 healthy + 2 x 2 faults) x 2 noise x 2 damping points x 2 repeats
    assert g.n_runs == 5 * 4 * 2
    scenes = [r.build_scene() for r in g.runs]
    assert {s.noise_rms for s in scenes} == {0.0, 0.6}
    assert {s.resonance_damping for s in scenes} == {0.01, 0.05}
    # an absolute noise floor and an SNR on the same point contradict each other
    with pytest.raises(ValueError, match="snr_db or noise_rms"):
        read_grid(with_("grid", noise_rms=[0.6], snr_db=[20]))


# ------------------------------------------------------------- fault_engagement axis
def test_fault_engagement_multiplies_ball_points_only():
    g = read_grid(with_("grid", fault=["healthy", "outer", "inner", "ball"],
                        fault_engagement=[0.3, 0.6, 1.0]))
    # per repeat: 1 healthy + 2 widths x (outer + inner) + 2 widths x 3 engagements (ball)
    assert g.n_runs == (1 + 2 * 2 + 2 * 3) * 2
    faults = [r.scene.get("fault") for r in g.runs[::2]]
    kinds = [f and f["kind"] for f in faults]
    assert kinds == [None] + ["outer"] * 2 + ["inner"] * 2 + ["ball"] * 6
    # race faults keep Fault's default (a race defect is on its track on every pass):
    # their scenes do not even carry the key, exactly as without the axis
    assert all("engagement" not in f for f in faults[1:5])
    # ball points: engagement varies fastest, inside each width
    assert [(f["width_mm"], f["engagement"]) for f in faults[5:]] == [
        (w, e) for w in (0.2, 0.5) for e in (0.3, 0.6, 1.0)]
    # the value reaches the run's Fault
    assert [r.build_scene().fault.engagement for r in g.runs[10::2]] == [0.3, 0.6, 1.0] * 2
    # the size check counts the points (without building them) the same way
    assert count_points(g.axes) == g.n_runs // 2


def test_fault_engagement_range_and_sizes():
    g = read_grid(with_("grid", fault=["healthy", "ball"],
                        fault_engagement={"start": 0.2, "stop": 0.7, "step": 0.1}))
    assert g.axes["fault_engagement"] == [0.2, 0.3, 0.4, 0.5, 0.6, 0.7]
    # (1 healthy + 2 widths x 6 engagements) x 2 repeats, one row per sensor
    assert g.n_runs == (1 + 2 * 6) * 2 and g.n_rows == g.n_runs * 2
    assert read_grid(g.as_dict()).runs == g.runs


def test_grids_without_the_axis_keep_their_runs():
    # golden: the runs of a grid as read by ballpass before the axis existed (provenance
    # in tests/data/README.md). Run ids, seeds and the stored grid decide whether a
    # dataset of that grid resumes; they must not move.
    golden = json.loads((Path(__file__).parent / "data" / "grid_runs_d875a80.json").read_text())
    g = read_grid(golden["grid"])
    assert g.as_dict() == golden["as_dict"]
    assert [[r.run_id, r.repeat, r.seed, r.scene.get("fault"), r.scene["rpm"]]
            for r in g.runs] == golden["runs"]


@pytest.mark.parametrize("value, shown", [(0.0, "0"), (1.5, "1.5"), (-0.2, "-0.2"),
                                          (math.nan, "nan")])
def test_bad_fault_engagement_is_refused_with_its_range(value, shown):
    bad = with_("grid", fault=["ball"], fault_engagement=[0.5, value])
    with pytest.raises(ValueError, match=rf"grid.fault_engagement\[1\] = {shown} is outside "
                                         r"\(0, 1\]"):
        read_grid(bad)


def test_fault_engagement_needs_a_ball_fault():
    with pytest.raises(ValueError, match=r"grid.fault_engagement applies to ball faults only"):
        read_grid(with_("grid", fault_engagement=[0.5]))       # healthy, outer, inner
    with pytest.raises(ValueError, match=r"grid.fault_engagement\[0\] must be a number"):
        read_grid(with_("grid", fault=["ball"], fault_engagement=["often"]))


def test_sim2real_example_counts_as_its_comment_says():
    path = example_grid("sim2real_cwru")
    g = read_grid(path)
    assert g.n_runs == 4 * 40 == 160                   # 4 kinds x 40 draws
    # ball defects draw their spin-axis drift, race faults keep a fixed axis (a race
    # defect is always on the track), healthy runs have no fault
    drift = {r.scene["fault"]["kind"]: r.scene["fault"].get("spin_drift_deg")
             for r in g.runs if "fault" in r.scene}
    assert drift["outer"] is None and drift["inner"] is None
    assert 0.0 <= drift["ball"] <= 90.0
    # every range in the file carries its source in a comment above it
    text = path.read_text()
    assert len(g.distributions) >= 15
    for axis in g.distributions:
        above = text[:text.index(f"\n{axis} =")].rsplit("\n", 3)
        assert any(line.startswith("#") for line in above), axis


# ------------------------------------------------------------------ clearance_um axis
def test_clearance_axis_reaches_every_scene():
    g = read_grid(with_("grid", clearance_um=[-5.0, 10.0]))
    # (1 healthy + 2 x 2 faults) x 2 clearances x 2 repeats: healthy rows multiply too
    assert g.n_runs == 5 * 2 * 2
    assert {r.build_scene().clearance_um for r in g.runs} == {-5.0, 10.0}
    # left out: the catalogue clearance, and scenes without the key (run ids unchanged)
    assert all("clearance_um" not in r.scene for r in read_grid(BASE).runs)


@pytest.mark.parametrize("value, match", [
    (-80.0, r"clearance_um=-80.0.*\): clearance_um must be a finite number in \(-50, 200\)"),
    ("tight", r"grid.clearance_um\[0\] must be a number"),
])
def test_bad_clearance_is_refused_naming_the_axis(value, match):
    with pytest.raises(ValueError, match=match):
        read_grid(with_("grid", clearance_um=[value]))
