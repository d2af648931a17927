"""Drawn grid axes: distributions instead of lists, ``[dataset] draws``, seeds, columns."""

import json
import math

import numpy as np
import pytest
import scipy.signal
import scipy.stats

from ballpass.cli import main
from ballpass.datasets import generate, info, load, read_grid, regenerate
from ballpass.datasets.grid import draw_seed, drawn_axes

# One outer-race point drawn many times: read_grid builds no simulation, so a few
# thousand draws cost milliseconds.
N_DRAWS = 2000


def drawn(axis: str, dist: dict, n: int = N_DRAWS, fault="outer", **extra) -> np.ndarray:
    """The values of ``axis`` over ``n`` draws of one grid point."""
    g = read_grid({"dataset": {"fs": 12000, "draws": n, "seed": 3},
                   "grid": {"bearing": "6205", "fault": fault, "rpm": 1797,
                            "resonance_hz": 3000, axis: dist, **extra}})
    return np.array([r.columns[axis] if axis in r.columns else _scene_value(r.scene, axis)
                     for r in g.runs])


def _scene_value(scene: dict, axis: str) -> float:
    fault_field = {"fault_width_mm": "width_mm", "fault_angle_deg": "angle_deg"}
    return scene["fault"][fault_field[axis]] if axis in fault_field else scene[axis]


# ------------------------------------------------------------------ the distributions
def test_uniform_and_log_uniform_follow_their_laws():
    # Kolmogorov-Smirnov against the stated law at alpha = 1e-3 (fixed seed: the test
    # is deterministic; a correct sampler fails it for one seed in 1000). Planted: a
    # log_uniform drawn flat in the load (not in its log) gives p ~ 1e-80.
    res = drawn("resonance_hz", {"uniform": [2500, 4500]})
    assert res.min() >= 2500 and res.max() < 4500
    assert scipy.stats.kstest(res, scipy.stats.uniform(2500, 2000).cdf).pvalue > 1e-3
    load = drawn("radial_load_n", {"log_uniform": [100, 2000]})
    assert load.min() >= 100 and load.max() <= 2000
    assert scipy.stats.kstest(np.log(load),
                              scipy.stats.uniform(np.log(100), np.log(20)).cdf).pvalue > 1e-3
    assert scipy.stats.kstest(load, scipy.stats.uniform(100, 1900).cdf).pvalue < 1e-6


def test_normal_and_choice_follow_their_laws():
    slip = drawn("slip", {"normal": [0.01, 0.002]})
    # the mean within 4 standard errors (sigma / sqrt(n) = 4.5e-5); the sample standard
    # deviation within 4 of its standard errors (sigma / sqrt(2 n) = 3.2e-5)
    assert abs(slip.mean() - 0.01) < 4 * 0.002 / math.sqrt(N_DRAWS)
    assert abs(slip.std(ddof=1) - 0.002) < 4 * 0.002 / math.sqrt(2 * N_DRAWS)
    angle = drawn("fault_angle_deg", {"choice": [0, 90, 180]})
    values, counts = np.unique(angle, return_counts=True)
    assert values.tolist() == [0, 90, 180]
    # equally likely: chi-square against 1/3 each at alpha = 1e-3
    assert scipy.stats.chisquare(counts).pvalue > 1e-3


def test_each_draw_comes_from_its_own_stored_seed():
    dists = {"resonance_hz": {"uniform": [2500, 4500]},
             "radial_load_n": {"log_uniform": [100, 2000]},
             "noise_slope_db_oct": {"normal": [-3, 1]}}
    g = read_grid({"dataset": {"fs": 12000, "draws": 3, "repeats": 2, "seed": 11},
                   "grid": {"bearing": "6205", "fault": ["healthy", "inner"], "rpm": 1797,
                            "noise_rms": 0.1, **dists}})
    assert g.n_runs == 2 * 3 * 2
    for r in g.runs:
        draw_id = r.run_id // 2                          # two repeats per draw
        assert r.columns["draw"] == draw_id % 3
        assert r.columns["draw_seed"] == draw_seed(11, draw_id)
        rng = np.random.default_rng(r.columns["draw_seed"])
        # the values again from the stored seed alone, in the grid's axis order
        again = {k: g.distributions[k].draw(rng) for k in g.distributions}
        assert again == {k: r.scene[k] for k in dists}
    # repeats of one draw share its values, not their seeds; draws differ
    first, second, third = g.runs[0], g.runs[1], g.runs[2]
    assert first.scene["resonance_hz"] == second.scene["resonance_hz"]
    assert first.seed != second.seed
    assert third.scene["resonance_hz"] != first.scene["resonance_hz"]
    # the draws are a stream apart from the runs' noise seeds
    assert {r.columns["draw_seed"] for r in g.runs}.isdisjoint({r.seed for r in g.runs})


def test_a_drawn_axis_adds_no_points_and_round_trips():
    g = read_grid({"dataset": {"fs": 12000, "draws": 4},
                   "grid": {"bearing": "6205", "fault": ["healthy", "outer", "ball"],
                            "fault_width_mm": {"uniform": [0.18, 0.71]},
                            "fault_engagement": {"uniform": [0.2, 0.7]},
                            "rpm": [1730, 1797], "snr_db": {"uniform": [0, 20]},
                            "resonance_hz": 3000}})
    assert g.n_runs == 3 * 2 * 4                    # (healthy, outer, ball) x 2 speeds x 4
    again = read_grid(json.loads(json.dumps(g.as_dict())))
    assert again == g and again.runs == g.runs
    ball = [r.scene["fault"] for r in g.runs if (r.scene.get("fault") or {}).get("kind")
            == "ball"]
    assert all(0.2 <= f["engagement"] < 0.7 for f in ball)
    outer = [r.scene["fault"] for r in g.runs if (r.scene.get("fault") or {}).get("kind")
             == "outer"]
    assert all("engagement" not in f for f in outer)   # race faults take no engagement
    assert drawn_axes(g) == drawn_axes(g.as_dict()) == {
        "fault_width_mm": "uniform 0.18 - 0.71", "fault_engagement": "uniform 0.2 - 0.7",
        "snr_db": "uniform 0 - 20"}


def test_realism_axes_reach_the_scene():
    g = read_grid({"dataset": {"fs": 12000},
                   "grid": {"bearing": "6205", "fault": "outer", "rpm": 1797,
                            "resonance_hz": 3000, "resonance2_hz": [4200], "resonance2_gain": [0.5],
                            "shaft_harmonic_2x": [0.3], "noise_slope_db_oct": [-6],
                            "sensor_angle_deg": [180]}})
    scene = g.runs[0].build_scene()
    assert scene.resonances == ((4200.0, 0.05, 0.5),)   # damping: the documented default
    assert scene.shaft_harmonics == (0.0, 0.3)
    assert scene.noise_slope_db_oct == -6.0
    assert scene.sensors[0].angle_deg == 180.0


# ------------------------------------------------------------------ validation
@pytest.mark.parametrize("axis, dist, message", [
    ("resonance_hz", {"uniform": [4000, 3000]}, "lo must be below hi"),
    ("resonance_hz", {"uniform": [2000, 6000]}, "6000 is outside the allowed range [100, 5400]"),
    ("radial_load_n", {"log_uniform": [0, 1000]}, "log_uniform needs lo > 0"),
    ("slip", {"normal": [0.01, 0]}, "sigma must be > 0"),
    ("slip", {"normal": [0.01, 0.01]}, "refused rather than clipped"),
    ("fault_engagement", {"uniform": [0.5, 1.5]}, "outside the allowed range (0, 1]"),
    ("fault_angle_deg", {"choice": [0, 0]}, "duplicate values"),
    ("resonance_hz", {"uniform": [2000]}, "takes two numbers"),
    ("resonance_hz", {"uniform": [2000, "x"]}, "finite numbers"),
    ("bearing", {"choice": ["6205", "6203"]}, "cannot be drawn"),
    ("resonance_hz", {"gaussian": [3000, 100]}, "distribution"),
])
def test_bad_distributions_are_refused_before_work(axis, dist, message):
    grid = {"dataset": {"fs": 12000},
            "grid": {"bearing": "6205", "fault": ["outer", "ball"], "rpm": 1797,
                     "resonance_hz": 3000, axis: dist}}
    with pytest.raises(ValueError, match=f"grid.{axis}") as exc:
        read_grid(grid)
    assert message in str(exc.value)


def test_a_draw_a_scene_would_refuse_is_refused_before_work():
    # a ball defect wider than the 6205's 7.94 mm ball: only the top of the range fails
    with pytest.raises(ValueError, match="fault_width_mm=9.0"):
        read_grid({"grid": {"bearing": "6205", "fault": "ball", "rpm": 1797,
                            "fault_width_mm": {"uniform": [0.2, 9.0]}}})


def test_draws_and_realism_axes_are_checked():
    base = {"bearing": "6205", "fault": "outer", "rpm": 1797, "resonance_hz": 3000}
    with pytest.raises(ValueError, match="dataset.draws = 3 needs a drawn axis"):
        read_grid({"dataset": {"draws": 3}, "grid": base})
    with pytest.raises(ValueError, match="dataset.draws must be an int >= 1"):
        read_grid({"dataset": {"draws": 0}, "grid": base})
    with pytest.raises(ValueError, match="resonance2_gain needs grid.resonance2_hz"):
        read_grid({"grid": {**base, "resonance2_gain": [0.5]}})
    with pytest.raises(ValueError, match="sensor_angle_deg sets the angle of the one sensor"):
        read_grid({"grid": {**base, "sensor": ["loaded", "unloaded"],
                            "sensor_angle_deg": {"uniform": [150, 210]}}})


# ------------------------------------------------------------------ datasets
DRAWN_GRID = {
    "dataset": {"duration_s": 0.5, "fs": 12000, "draws": 3, "model": "impulse", "seed": 5},
    "grid": {"bearing": "6205", "fault": ["healthy", "outer"], "rpm": 1797,
             "resonance_hz": {"uniform": [2200, 4600]},
             "noise_rms": {"log_uniform": [0.005, 0.02]},
             "sensor_angle_deg": {"uniform": [150, 210]}},
}


def test_drawn_values_are_columns_the_signals_show_and_regenerate(tmp_path):
    out = tmp_path / "drawn"
    generate(DRAWN_GRID, out, progress=False)
    X, meta = load(out)
    assert len(X) == 2 * 3
    assert {"draw", "draw_seed", "sensor_angle_deg"} <= set(meta.columns)
    assert meta["resonance_hz"].nunique() == 6 and meta["sensor"].eq("sensor").all()
    for i, row in meta.iterrows():
        scene = json.loads(row["scene"])
        assert scene["resonance_hz"] == row["resonance_hz"]
        assert scene["sensors"][0]["angle_deg"] == row["sensor_angle_deg"]
        assert (regenerate(row) == X[i]).all()          # bit for bit from its row
    # The signal shows the drawn value: the fault's impacts ring at the drawn resonance.
    # Welch bins are 11.7 Hz wide and the impulse response's peak sits within 3 % of
    # its resonance; the drawn values are 240 Hz (10 % of the range) apart or more only
    # by chance, so compare each row with its own value. Planted: a column written
    # from the draw but a scene built from the representative (3400 Hz) fails 2 of 3.
    for x, (_, row) in zip(X, meta.iterrows(), strict=True):
        if row["label"] == "outer":
            f, p = scipy.signal.welch(x, 12000, nperseg=1024)
            assert f[np.argmax(p)] == pytest.approx(row["resonance_hz"], rel=0.03)


def test_info_and_dry_run_show_the_ranges(tmp_path, capsys):
    grid = json.loads(json.dumps(DRAWN_GRID))
    grid["dataset"]["duration_s"] = 0.1
    out = tmp_path / "ds"
    generate(grid, out, progress=False)
    # the stored grid (with its distributions) is the grid: a re-run resumes, all done
    again = generate(grid, out, progress=False)
    assert again.rows_written == 0 and again.shards_skipped > 0
    assert info(out)["drawn"] == {"resonance_hz": "uniform 2200 - 4600",
                                  "noise_rms": "log_uniform 0.005 - 0.02",
                                  "sensor_angle_deg": "uniform 150 - 210"}
    assert main(["info", str(out)]) == 0
    assert "drawn     resonance_hz: uniform 2200 - 4600" in capsys.readouterr().out
    toml = tmp_path / "g.toml"
    toml.write_text(
        '[dataset]\nduration_s = 0.1\nfs = 12000\ndraws = 3\nmodel = "impulse"\n'
        '[grid]\nbearing = "6205"\nfault = ["healthy", "outer"]\nrpm = 1797\n'
        "resonance_hz = { uniform = [2200, 4600] }\nnoise_rms = [0.01]\n")
    assert main(["generate", str(toml), "--dry-run"]) == 0
    shown = capsys.readouterr().out
    assert "drawn     resonance_hz: uniform 2200 - 4600 (3 draw(s) per grid point)" in shown
    assert "6 runs" in shown

