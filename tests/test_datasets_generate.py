"""Dataset generation end to end: CLI, storage, determinism, resume, Dask, refusals.

Signals are tiny (0.05 s at 12 kHz, resonance 3 kHz) so the whole file runs in seconds.
Every comparison of signals is exact (``np.array_equal``): a dataset row is a pure
function of its stored scene and seed, so regenerating it, resuming a killed run or
running the shards on another executor must reproduce it bit for bit.
"""

import importlib
import json
import math
import os
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from ballpass.cli import main
from ballpass.datasets import (
    dry_run,
    generate,
    info,
    load,
    load_features,
    read_grid,
    regenerate,
)
from ballpass.datasets._shard import FEATURE_KEYS, feature_columns
from ballpass.datasets.grid import run_seed

GRID_TOML = """\
[dataset]
duration_s = 0.05
fs = 12000
repeats = 2
seed = 3
shard_size = 4

[grid]
bearing = ["6205"]
fault = ["healthy", "outer", "inner", "ball"]
fault_width_mm = [0.2, 0.5]
rpm = [1797, [1700, 1800]]
snr_db = [inf, 10]
resonance_hz = [3000]
sensor = ["loaded", "unloaded"]
"""
# (healthy + 3 faults x 2 widths) points x 2 rpm x 2 snr x 2 repeats; one row per sensor
N_RUNS = (1 + 3 * 2) * 2 * 2 * 2
N_ROWS = N_RUNS * 2


@pytest.fixture(scope="module")
def grid_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("grid") / "small.toml"
    path.write_text(GRID_TOML)
    return path


@pytest.fixture(scope="module")
def local_dataset(grid_file, tmp_path_factory):
    """The small grid generated through the CLI with two local worker processes."""
    out = tmp_path_factory.mktemp("local") / "ds"
    assert main(["generate", str(grid_file), "--out", str(out), "--jobs", "2",
                 "--no-progress"]) == 0
    return out


def test_cli_progress_bar_only_on_a_terminal(tmp_path, capsys):
    """stderr captured (not a terminal, as in a log file): no progress bar in it."""
    small = tmp_path / "tiny.toml"
    small.write_text(GRID_TOML.replace('fault = ["healthy", "outer", "inner", "ball"]',
                                       'fault = ["healthy"]'))
    assert main(["generate", str(small), "--out", str(tmp_path / "ds")]) == 0
    err = capsys.readouterr().err
    assert "generate:" not in err and "%|" not in err, err


def test_cli_end_to_end(local_dataset, capsys):
    X, meta = load(local_dataset)
    assert len(meta) == N_ROWS == read_grid(tomllib.loads(GRID_TOML)).n_rows
    assert X.shape == (N_ROWS, 600) and X.dtype == np.float32
    assert np.isfinite(X).all() and (X.std(axis=1) > 0).all()
    assert meta.label.value_counts().to_dict() == {"healthy": 16, "outer": 32, "inner": 32,
                                                   "ball": 32}
    faulty = meta[meta.label != "healthy"]
    assert set(faulty.fault_width_mm) == {0.2, 0.5} and meta[meta.label == "healthy"
                                                             ].fault_width_mm.isna().all()
    assert set(meta.snr_db) == {np.inf, 10.0}
    assert set(meta.rpm) == {1797.0, 1750.0}          # the ramp's mean speed
    assert set(meta.rpm_end) == {1797.0, 1800.0}
    assert (meta.model == "sr5").all() and (meta.group == meta.run_id).all()
    # one simulation per run, one row per sensor, rows of one run share run_id and seed
    per_run = meta.groupby("run_id")
    assert (per_run.sensor.apply(list) == pd.Series([["loaded", "unloaded"]] * N_RUNS)).all()
    assert (per_run.seed.nunique() == 1).all()
    assert all(meta.seed == [run_seed(3, r) for r in meta.run_id])
    assert not meta.duplicated(["run_id", "sensor", "segment"]).any()
    # a shard is plain Parquet: pandas reads it without ballpass
    shard = pd.read_parquet(local_dataset / "part-00000.parquet")
    assert len(shard) == 4 * 2 and len(shard.signal.iloc[0]) == 600
    assert pq.read_schema(local_dataset / "part-00000.parquet").field("signal").type.list_size \
        == 600
    manifest = json.loads((local_dataset / "_manifest.json").read_text())
    assert manifest["status"] == "complete" and manifest["root_seed"] == 3
    assert manifest["units"]["signal"] == "m/s^2"

    assert main(["info", str(local_dataset)]) == 0
    out = capsys.readouterr().out
    assert f"rows      {N_ROWS} of {N_ROWS}" in out and "600 samples at 12000 Hz" in out


def test_load_columns_and_filters(local_dataset):
    X, meta = load(local_dataset, columns=["label", "rpm"],
                   filters=[("sensor", "==", "unloaded"), ("label", "in", ["outer", "ball"])])
    assert list(meta.columns) == ["label", "rpm"]
    assert len(meta) == X.shape[0] == 32
    with pytest.raises(ValueError, match="unknown column"):
        load(local_dataset, columns=["nope"])
    d = info(local_dataset)
    assert d["n_rows"] == N_ROWS and d["labels"]["healthy"] == 16


def test_regenerate_is_exact(local_dataset):
    X, meta = load(local_dataset)
    # noise-free and noisy, constant speed and ramp, both sensors, each fault kind
    picks = meta.groupby(["label", "snr_db", "rpm", "sensor"]).head(1).index[::3]
    assert len(picks) >= 8
    for i in picks:
        assert np.array_equal(regenerate(meta.loc[i]), X[i])


def test_segments_share_the_run_group(tmp_path):
    grid = read_grid({"dataset": {"duration_s": 0.05, "fs": 12000, "segment_s": 0.02},
                      "grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [[1700, 1800]],
                               "resonance_hz": [3000]}})
    generate(grid, tmp_path / "seg", progress=False)
    X, meta = load(tmp_path / "seg")
    assert X.shape == (2, 240)                          # 600 samples -> 2 x 240, rest dropped
    assert list(meta.segment) == [0, 1] and meta.group.nunique() == 1
    assert list(meta.start_s) == [0.0, 0.02]
    # mean speed over each segment: the ramp's value at the segment's mid-time
    assert np.allclose(meta.rpm, [1700 + 100 * 0.01 / 0.05, 1700 + 100 * 0.03 / 0.05],
                       rtol=1e-12)
    assert np.array_equal(regenerate(meta.iloc[1]), X[1])


def test_dask_local_cluster_gives_the_same_rows(local_dataset, grid_file, tmp_path, capsys):
    """``--scheduler ADDRESS`` runs the shards on a Dask cluster through its executor."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        assert main(["generate", str(grid_file), "--out", str(tmp_path / "dask"),
                     "--scheduler", cluster.scheduler_address, "--no-progress"]) == 0
    assert f"{N_ROWS} rows; wrote {N_ROWS} rows" in capsys.readouterr().out
    X_local, meta_local = load(local_dataset)
    X_dask, meta_dask = load(tmp_path / "dask")
    assert np.array_equal(X_local, X_dask)
    pd.testing.assert_frame_equal(meta_local, meta_dask)


def test_kill_and_resume(tmp_path):
    """SIGKILL a generation mid-run, rerun: only missing shards are made, nothing doubles."""
    grid = tmp_path / "kill.toml"
    grid.write_text(GRID_TOML.replace("shard_size = 4", "shard_size = 1")
                    .replace("duration_s = 0.05", "duration_s = 0.1"))
    out = tmp_path / "ds"
    n_shards = read_grid(grid).n_shards
    proc = subprocess.Popen([sys.executable, "-m", "ballpass", "generate", str(grid), "--out",
                             str(out), "--no-progress"], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    while len(list(out.glob("part-*.parquet"))) < 3:
        assert proc.poll() is None, proc.stderr.read().decode()
        assert time.monotonic() < deadline
        time.sleep(0.002)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    before = {p.name: p.stat().st_mtime_ns for p in out.glob("part-*.parquet")}
    assert 3 <= len(before) < n_shards
    assert json.loads((out / "_manifest.json").read_text())["status"] == "running"

    summary = generate(grid, out, progress=False)
    assert summary.shards_written == n_shards - len(before)
    assert summary.n_rows == N_ROWS
    after = {p.name: p.stat().st_mtime_ns for p in out.glob("part-*.parquet")}
    assert len(after) == n_shards
    assert all(after[name] == mtime for name, mtime in before.items())   # kept, not redone
    assert not list(out.glob(".*.tmp"))
    for path in out.glob("part-*.parquet"):
        pq.read_table(path)                                               # every shard readable
    X, meta = load(out)
    assert len(meta) == N_ROWS and not meta.duplicated(["run_id", "sensor", "segment"]).any()
    assert sorted(meta.run_id.unique()) == list(range(N_RUNS))
    i = int(np.flatnonzero(meta.run_id == min(int(n[5:10]) for n in before))[0])
    assert np.array_equal(regenerate(meta.iloc[i]), X[i])
    assert json.loads((out / "_manifest.json").read_text())["status"] == "complete"


@pytest.mark.parametrize("text, key", [
    (GRID_TOML.replace("snr_db", "noise"), "noise"),
    (GRID_TOML.replace("[0.2, 0.5]", "[]"), "grid.fault_width_mm is an empty list"),
    (GRID_TOML.replace("rpm = [1797, [1700, 1800]]",
                       "rpm = {start = 1800, stop = 1700, step = 10}"), "grid.rpm: range stop"),
    (GRID_TOML.replace("repeats = 2", 'repeats = "2"'), "dataset.repeats"),
    (GRID_TOML.replace("resonance_hz = [3000]", 'resonance_hz = ["3 kHz"]'), "grid.resonance_hz"),
    (GRID_TOML.replace("[grid]", "[grid"), "not a valid TOML grid file"),
    (GRID_TOML.replace("seed = 3", 'seed = 3\nsolver = "euler"'),
     "dataset.solver: unknown solver 'euler'"),
    (GRID_TOML.replace("seed = 3", 'seed = 3\nmodel = "sr9"'), "model 'sr9'"),
    (GRID_TOML.replace("rpm =", "fault_engagement = [0.5, 2]\nrpm ="),
     "grid.fault_engagement[1] = 2 is outside (0, 1]"),
    (GRID_TOML.replace("rpm =", "fault_spin_drift_deg = [30, 91]\nrpm ="),
     "grid.fault_spin_drift_deg[1] = 91 is outside [0, 90]"),
    # the impulse model would ignore the clearance: rows labelled -3 um without a preload
    (GRID_TOML.replace("seed = 3", 'seed = 3\nmodel = "impulse"')
     .replace("rpm =", "clearance_um = [-3]\nrpm =").replace("[inf, 10]", "[inf]"),
     "model 'impulse' (run 0, healthy) does not represent mounted_clearance"),
])
def test_bad_grid_refused_before_any_work(tmp_path, capsys, text, key):
    grid = tmp_path / "bad.toml"
    grid.write_text(text)
    out = tmp_path / "ds"
    assert main(["generate", str(grid), "--out", str(out), "--no-progress"]) == 2
    assert key in capsys.readouterr().err
    assert not out.exists()


def test_unwritable_folder_refused(tmp_path, grid_file):
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    with pytest.raises(PermissionError, match="cannot write to output folder"):
        generate(grid_file, blocker / "ds", progress=False)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file"]


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0,
                    reason="root can write to read-only folders")
def test_read_only_folder_refused(tmp_path, grid_file):
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o555)
    try:
        with pytest.raises(PermissionError, match="cannot write to output folder"):
            generate(grid_file, locked / "ds", progress=False)
        assert not list(locked.iterdir())
    finally:
        locked.chmod(0o755)


def test_other_grid_or_foreign_folder_refused(local_dataset, grid_file, tmp_path):
    manifest = (local_dataset / "_manifest.json").read_bytes()
    other = tomllib.loads(GRID_TOML)
    other["dataset"]["seed"] = 4
    with pytest.raises(ValueError, match="already holds a dataset of another grid"):
        generate(other, local_dataset, progress=False)
    assert (local_dataset / "_manifest.json").read_bytes() == manifest
    foreign = tmp_path / "foreign"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("mine")
    with pytest.raises(FileExistsError, match="not an empty folder or a ballpass dataset"):
        generate(grid_file, foreign, progress=False)
    assert sorted(p.name for p in foreign.iterdir()) == ["notes.txt"]


@pytest.mark.skipif(os.name != "posix", reason="flock is POSIX")
def test_concurrent_generate_refused(local_dataset, grid_file):
    import fcntl

    with open(local_dataset / ".lock", "a") as fh:     # another generate holds the folder
        fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        with pytest.raises(FileExistsError, match="being generated by another process"):
            generate(grid_file, local_dataset, progress=False)


def test_rerun_of_complete_dataset_does_nothing(local_dataset, grid_file):
    mtimes = {p: p.stat().st_mtime_ns for p in Path(local_dataset).glob("part-*.parquet")}
    summary = generate(grid_file, local_dataset, n_jobs=2, progress=False)
    assert summary.rows_written == 0 and summary.shards_skipped == len(mtimes)
    assert all(p.stat().st_mtime_ns == m for p, m in mtimes.items())


def test_dry_run_counts_and_writes_nothing(local_dataset, grid_file, tmp_path):
    est = dry_run(grid_file, out_dir=tmp_path / "none")
    assert (est.n_rows, est.n_runs, est.n_shards, est.shards_done) == (N_ROWS, N_RUNS, 14, 0)
    assert est.time_s > 0 and est.size_bytes > N_ROWS * 600 * 4 * 0.5
    assert not (tmp_path / "none").exists()
    assert dry_run(grid_file, out_dir=local_dataset).shards_done == 14


def test_feature_table(tmp_path):
    """--features writes one feature row per signal, equal to the features of the stored
    signals (exactly: the same float32 input through the same functions)."""
    grid = tmp_path / "f.toml"
    grid.write_text(GRID_TOML.replace('"ball"]', ']').replace("[0.2, 0.5]", "[0.5]")
                    .replace("snr_db = [inf, 10]", "snr_db = [10]").replace("repeats = 2",
                                                                             "repeats = 1"))
    out = tmp_path / "ds"
    assert main(["generate", str(grid), "--out", str(out), "--no-progress"]) == 0
    assert not (out / "_features").exists()
    summary = generate(grid, out, features=True, progress=False)   # added to a finished dataset
    assert summary.rows_written == 0 and summary.feature_shards_written == 2
    X, meta = load(out)
    table = load_features(out)
    assert len(table) == len(meta) == 12
    assert list(table.columns[: len(FEATURE_KEYS)]) == list(FEATURE_KEYS)
    pd.testing.assert_frame_equal(table[list(FEATURE_KEYS)], meta[list(FEATURE_KEYS)])
    for name, value in feature_columns(X, 12000.0, meta.bearing, meta.rpm).items():
        assert np.array_equal(table[name].to_numpy(), value, equal_nan=True), name
    assert info(out)["features"]


def test_dataset_written_before_the_engagement_column_resumes_and_loads(tmp_path,
                                                                         monkeypatch):
    """A dataset half-written by a ballpass without the ``fault_engagement`` column (its
    grid has no such axis) resumes under this one: the same grid, run ids and seeds; the
    new shards carry the column, and ``load`` gives the old rows the engagement they were
    simulated with (1: the grid could not set another), whichever shard comes first."""
    # the module that writes the shards' columns
    generate_module = importlib.import_module("ballpass.datasets._shard")

    grid = {"dataset": {"duration_s": 0.05, "fs": 12000, "shard_size": 1, "model": "impulse"},
            "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "ball"], "rpm": [1797],
                     "resonance_hz": [3000]}}
    out = tmp_path / "ds"
    old_columns = tuple(c for c in generate_module.COLUMNS if c != "fault_engagement")
    with monkeypatch.context() as m:
        m.setattr(generate_module, "COLUMNS", old_columns)
        generate(grid, out, progress=False)
    assert "fault_engagement" not in pq.read_schema(out / "part-00000.parquet").names
    X_old, meta_old = load(out)
    assert meta_old.fault_engagement.tolist()[1:] == [1.0, 1.0]
    assert np.isnan(meta_old.fault_engagement[0])                      # healthy
    # shards lost (a kill, a damaged file) and made again: read after old shards (whose
    # schema then decides), then first (the old shards read the column as null)
    for lost in ("part-00002.parquet", "part-00000.parquet"):
        (out / lost).unlink()
        with pytest.warns(UserWarning, match="is missing; generating it again"):
            assert generate(grid, out, progress=False).shards_written == 1
        assert "fault_engagement" in pq.read_schema(out / lost).names
        X, meta = load(out)
        assert np.array_equal(X, X_old)
        pd.testing.assert_frame_equal(meta, meta_old)


def test_clearance_axis_is_stored_and_simulated(tmp_path):
    """A preload from the grid reaches the signal (the stored row is the simulation of a
    scene with that clearance, and differs from the same run at the catalogue clearance)
    and the ``clearance_um`` column (NaN: the catalogue clearance). Catches an axis that
    is validated and stored but never passed to the simulator."""
    grid = {"dataset": {"duration_s": 0.1, "fs": 12000, "model": "sr5"},
            "grid": {"bearing": ["6205"], "fault": ["outer"], "fault_angle_deg": [180],
                     "rpm": [1797], "resonance_hz": [3000], "clearance_um": [-10.0]}}
    generate(grid, tmp_path / "pre", progress=False)
    X, meta = load(tmp_path / "pre")
    assert meta.clearance_um.tolist() == [-10.0]
    assert list(meta.columns).index("clearance_um") == list(meta.columns).index(
        "radial_load_n") + 1
    scene = json.loads(meta.scene[0])
    assert scene["clearance_um"] == -10.0
    assert np.array_equal(regenerate(meta.iloc[0]), X[0])
    del grid["grid"]["clearance_um"]
    generate(grid, tmp_path / "free", progress=False)
    X_free, meta_free = load(tmp_path / "free")
    assert np.isnan(meta_free.clearance_um[0])
    # a 12 o'clock fault under a 10 um preload strikes; at the catalogue clearance it is
    # out of the load zone (tests/test_silent_faults.py): the signals must differ
    assert not np.allclose(X[0], X_free[0])


def test_dataset_written_before_the_clearance_column_loads(tmp_path, monkeypatch):
    """Rows of a dataset written before the ``clearance_um`` column load with it as NaN
    (the catalogue clearance, the only one that grid could give), in its place."""
    generate_module = importlib.import_module("ballpass.datasets._shard")
    grid = {"dataset": {"duration_s": 0.05, "fs": 12000, "model": "impulse"},
            "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797],
                     "resonance_hz": [3000]}}
    monkeypatch.setattr(generate_module, "COLUMNS",
                        tuple(c for c in generate_module.COLUMNS if c != "clearance_um"))
    generate(grid, tmp_path / "old", progress=False)
    assert "clearance_um" not in pq.read_schema(tmp_path / "old" / "part-00000.parquet").names
    _, meta = load(tmp_path / "old")
    assert meta.clearance_um.isna().all() and len(meta) == 2
    assert list(meta.columns).index("clearance_um") == list(meta.columns).index(
        "radial_load_n") + 1


@pytest.mark.parametrize("noise", [{"snr_db": 12.0}, {"noise_rms": 0.4}])
def test_every_parameter_column_holds_its_axis_value(tmp_path, noise):
    """One run whose every numeric axis has its own value, unlike any default and any
    other axis's: each column must hold its axis's value (a swapped pair of columns, a
    unit converted twice or a value read from the wrong field shows), and the scene
    stored with the row, from which regenerate() rebuilds the signal, must say the
    same. The noise axes are exclusive, hence one run each; the other is stored as "no
    noise" (inf dB, 0 m/s^2)."""
    values = {"fault_width_mm": 0.31, "fault_depth_mm": 0.07, "fault_angle_deg": 25.0,
              "rpm": 1650.0, "radial_load_n": 420.0, "clearance_um": 7.0, "slip": 0.013,
              "resonance_hz": 3300.0, "resonance_damping": 0.045, **noise}
    grid = {"dataset": {"duration_s": 0.05, "fs": 12000, "seed": 3, "model": "sr5"},
            "grid": {"bearing": ["6205"], "fault": ["outer"], "sensor": ["loaded"],
                     **{key: [value] for key, value in values.items()}}}
    generate(grid, tmp_path, progress=False)
    _, meta = load(tmp_path)
    row = meta.iloc[0]
    absent = {"snr_db": math.inf, "noise_rms": 0.0}
    for key, value in {**absent, **values}.items():
        assert row[key] == value, key
    assert (row.rpm_start, row.rpm_end, row.label) == (1650.0, 1650.0, "outer")
    scene = json.loads(row.scene)
    fault = scene.pop("fault")
    assert {f"fault_{k}": fault[k] for k in ("width_mm", "depth_mm", "angle_deg")} == {
        k: values[k] for k in ("fault_width_mm", "fault_depth_mm", "fault_angle_deg")}
    assert {k: scene[k] for k in values if not k.startswith("fault_")} == {
        k: v for k, v in values.items() if not k.startswith("fault_")}
