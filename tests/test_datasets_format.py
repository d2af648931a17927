"""The dataset folder as other tools see it: plain Parquet readers, the first on-disk
layout, the simulator fingerprint, and determinism of the parallel path.

Signals are tiny (0.02 s at 12 kHz) so the file runs in a few seconds. Signal
comparisons are exact: a stored row is a pure function of its scene and seed.
"""

import io
import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.dataset as pads
import pytest

from ballpass.datasets import generate, info, load, load_features, read_grid

V1 = Path(__file__).parent / "data" / "dataset_v1"

GRID = {
    "dataset": {"duration_s": 0.02, "fs": 12000, "seed": 11, "shard_size": 2},
    "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"],
             "fault_width_mm": [0.5], "rpm": [1700, 1797], "resonance_hz": [3000],
             "sensor": ["loaded", "unloaded"]},
}
N_ROWS = 3 * 2 * 2   # 3 points x 2 rpm, one row per sensor


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    out = tmp_path_factory.mktemp("fmt") / "ds"
    generate(GRID, out, features=True, progress=False)
    return out


def snapshot(folder: Path) -> dict:
    """Every file under ``folder``: relative name -> (bytes, mtime_ns)."""
    return {str(p.relative_to(folder)): (p.read_bytes(), p.stat().st_mtime_ns)
            for p in sorted(folder.rglob("*")) if p.is_file()}


def by_row(frame: pd.DataFrame) -> pd.DataFrame:
    return frame.sort_values(["run_id", "sensor"]).reset_index(drop=True)


def test_layout_hides_everything_but_the_signal_shards(dataset):
    names = sorted(p.name for p in dataset.iterdir())
    assert names == [".lock", "_features", "_manifest.json", "part-00000.parquet",
                     "part-00001.parquet", "part-00002.parquet"]
    manifest = json.loads((dataset / "_manifest.json").read_text())
    assert manifest["format_version"] == 2
    assert all(len(s["sha256"]) == 64 and len(s["features_sha256"]) == 64
               for s in manifest["shards"])


def test_cli_features_reads_the_new_layout(dataset, capsys):
    from ballpass.cli import main

    assert main(["features", str(dataset)]) == 0
    table = pd.read_csv(io.StringIO(capsys.readouterr().out))
    assert len(table) == N_ROWS


def test_pandas_and_pyarrow_read_the_folder(dataset):
    X, meta = load(dataset)
    frame = by_row(pd.read_parquet(dataset))      # the folder itself, no glob
    assert len(frame) == N_ROWS and "rms" not in frame   # no feature-table rows or columns
    ours = by_row(meta.assign(signal=list(X)))
    assert np.array_equal(np.stack(frame.signal), np.stack(ours.signal))
    pd.testing.assert_frame_equal(frame.drop(columns="signal"), ours.drop(columns="signal"))
    table = pads.dataset(dataset).to_table()
    assert table.num_rows == N_ROWS and table.schema.field("signal").type.list_size == 240


def test_duckdb_reads_the_shards(dataset):
    duckdb = pytest.importorskip("duckdb")
    rows = duckdb.sql(f"SELECT run_id, sensor, signal FROM read_parquet('{dataset}/*.parquet') "
                      "ORDER BY run_id, sensor").fetchall()
    X, meta = load(dataset)
    order = by_row(meta.assign(i=np.arange(len(meta)))).i
    assert len(rows) == N_ROWS
    assert np.array_equal(np.array([r[2] for r in rows], dtype=np.float32), X[order])


def test_polars_reads_the_shards(dataset):
    pl = pytest.importorskip("polars")
    frame = pl.read_parquet(f"{dataset}/*.parquet").sort(["run_id", "sensor"])
    X, meta = load(dataset)
    order = by_row(meta.assign(i=np.arange(len(meta)))).i
    assert frame.height == N_ROWS
    assert np.array_equal(frame["signal"].to_numpy(), X[order])


def test_first_layout_still_loads(tmp_path):
    """tests/data/dataset_v1 was written by the first layout (manifest.json, features/)."""
    X, meta = load(V1)
    assert X.shape == (3, 240) and X.dtype == np.float32 and np.isfinite(X).all()
    assert list(meta.label) == ["healthy", "outer", "inner"]
    table = load_features(V1)
    assert list(table.label) == ["healthy", "outer", "inner"] and "kurtosis" in table
    d = info(V1)
    assert d["n_rows"] == 3 and d["features"] and d["status"] == "complete"
    # resuming it is refused: it carries no simulator fingerprint; nothing is touched
    old = tmp_path / "v1"
    shutil.copytree(V1, old)
    before = snapshot(old)
    with pytest.raises(ValueError, match="before datasets recorded a simulator fingerprint"):
        generate(V1.with_suffix(".toml"), old, progress=False)
    assert snapshot(old) == before


@pytest.mark.parametrize("change, expected", [
    ("sources", "simulator_sources: "),
    ("numba", "numba: "),
    ("defaults", "scenes: "),
])
def test_changed_simulator_refuses_resume_and_touches_nothing(dataset, monkeypatch, change,
                                                              expected):
    import numba

    import ballpass.scene
    import ballpass.simulate

    if change == "sources":
        monkeypatch.setattr(ballpass.simulate, "source_fingerprint", lambda: "0" * 64)
    elif change == "numba":
        monkeypatch.setattr(numba, "__version__", "0.0.1")
    else:   # a changed Scene default (here the repr every point's scene is hashed from)
        monkeypatch.setattr(ballpass.scene.Scene, "__repr__", lambda self: "Scene(changed)")
    before = snapshot(dataset)
    with pytest.raises(ValueError, match="another simulator") as err:
        generate(GRID, dataset, progress=False)
    message = str(err.value)
    assert expected in message and "untouched" in message and "new --out folder" in message
    assert snapshot(dataset) == before


def test_grid_refusal_lists_the_keys_that_differ(dataset):
    other = json.loads(json.dumps(GRID))
    other["dataset"]["seed"] = 12
    other["grid"]["rpm"] = [1700]
    before = snapshot(dataset)
    with pytest.raises(ValueError, match="another grid") as err:
        generate(other, dataset, progress=False)
    assert "dataset.seed: 11 -> 12" in str(err.value)
    assert "grid.rpm: [1700.0, 1797.0] -> [1700.0]" in str(err.value)
    assert "grid.fault" not in str(err.value)
    assert snapshot(dataset) == before


def test_one_and_two_jobs_write_identical_files(dataset, tmp_path):
    """The forked worker pool writes byte-identical shards (same SHA-256) to the in-process
    path: the dataset does not depend on n_jobs."""
    generate(GRID, tmp_path / "two", n_jobs=2, features=True, progress=False)
    one = json.loads((dataset / "_manifest.json").read_text())["shards"]
    two = json.loads((tmp_path / "two" / "_manifest.json").read_text())["shards"]
    assert [(s["sha256"], s["features_sha256"]) for s in one] == \
        [(s["sha256"], s["features_sha256"]) for s in two]
    for name in ("part-00000.parquet", "_features/part-00002.parquet"):
        assert (dataset / name).read_bytes() == (tmp_path / "two" / name).read_bytes()
    assert read_grid(GRID).n_rows == N_ROWS


def test_damaged_feature_shard_named_and_remade(dataset, tmp_path):
    out = tmp_path / "ds"
    shutil.copytree(dataset, out)
    name = "_features/part-00001.parquet"
    good = (out / name).read_bytes()
    (out / name).write_bytes(good[: len(good) // 2])
    with pytest.raises(ValueError, match="part-00001.parquet has .* bytes where the manifest"):
        load_features(out)
    with pytest.warns(UserWarning, match="part-00001.parquet"):
        summary = generate(GRID, out, progress=False)     # no features=True: still remade
    assert summary.rows_written == 0 and summary.feature_shards_written == 1
    assert (out / name).read_bytes() == good
