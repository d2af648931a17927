"""Datasets under abuse: corrupted, truncated and deleted shards, damaged manifests,
grids too large to build, runaway worker counts, a killed parent, bad rows and filters.

Each case ends in a clear error (or a repair) before any work, and leaves nothing
behind. Signals are short (0.5 s at 12 kHz, so that the middle of a shard lies in its
signal pages) and the file runs in about 15 s.
"""

import importlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from _processes import children

from ballpass import Scene
from ballpass._resources import available_memory, simulation_bytes
from ballpass.cli import main
from ballpass.datasets import dry_run, generate, info, load, read_grid, regenerate
from ballpass.datasets.store import CorruptShardError

GEN = sys.modules["ballpass.datasets.generate"]   # the module (the package exports the function)

GRID = {
    "dataset": {"duration_s": 0.5, "fs": 12000, "seed": 2, "shard_size": 1},
    "grid": {"bearing": ["6205"], "fault": ["outer", "inner", "ball"], "fault_width_mm": [0.5],
             "rpm": [1797], "resonance_hz": [3000]},
}


def files(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The small grid's dataset: (folder, X, files) to copy and damage."""
    out = tmp_path_factory.mktemp("abuse") / "ds"
    generate(GRID, out, progress=False)
    return out, load(out)[0], files(out)


@pytest.fixture
def copy(reference, tmp_path):
    import shutil

    out = tmp_path / "ds"
    shutil.copytree(reference[0], out)
    return out


# ----------------------------------------------------------------------------- corruption
def damage(path: Path, how: str) -> None:
    data = bytearray(path.read_bytes())
    if how == "flip":            # 200 bytes in the middle, inside the signal pages
        import pyarrow.parquet as pq

        mid = len(data) // 2
        chunk = pq.read_metadata(path).row_group(0).column(0)      # the signal column
        assert chunk.path_in_schema == "signal.list.element"
        assert chunk.data_page_offset < mid < mid + 200 < chunk.data_page_offset + \
            chunk.total_compressed_size
        data[mid:mid + 200] = bytes(b ^ 0xFF for b in data[mid:mid + 200])
        path.write_bytes(bytes(data))
    elif how == "truncate":
        path.write_bytes(bytes(data[: len(data) // 2]))
    else:
        path.unlink()


@pytest.mark.parametrize("how, says", [("flip", "is corrupted: its SHA-256 differs"),
                                       ("truncate", "truncated or altered"),
                                       ("delete", "is missing")])
def test_damaged_shard_is_named_by_load_info_and_cli_and_resume_repairs_it(
        reference, copy, capsys, how, says):
    _, X_ref, files_ref = reference
    damage(copy / "part-00001.parquet", how)
    for reader in (load, info):
        with pytest.raises(CorruptShardError, match=says) as err:
            reader(copy)
        assert "part-00001.parquet" in str(err.value) and "ballpass generate" in str(err.value)
    assert main(["info", str(copy)]) == 2
    err = capsys.readouterr().err
    assert "part-00001.parquet" in err and "Traceback" not in err and err.count("\n") == 1

    with pytest.warns(UserWarning, match="part-00001.parquet"):
        summary = generate(GRID, copy, progress=False)
    assert summary.shards_written == 1 and summary.shards_skipped == 2
    X, _ = load(copy)
    assert np.array_equal(X, X_ref)                      # regenerated bit for bit
    now = files(copy)
    assert now["part-00001.parquet"] == files_ref["part-00001.parquet"]
    assert now.keys() == files_ref.keys()


def test_manifest_without_shards_is_refused(copy):
    manifest = json.loads((copy / "_manifest.json").read_text())
    manifest["shards"] = []
    (copy / "_manifest.json").write_text(json.dumps(manifest))
    for reader in (load, info):
        with pytest.raises(ValueError, match="lists no shards"):
            reader(copy)
    del manifest["shards"]
    (copy / "_manifest.json").write_text(json.dumps(manifest))
    with pytest.raises(ValueError, match="lists no shards"):
        load(copy)


def test_unknown_filter_column_and_bad_rows(reference):
    folder = reference[0]
    with pytest.raises(ValueError, match="filters: unknown column 'nope'"):
        load(folder, filters=[("nope", "==", 1)])
    with pytest.raises(ValueError, match=r"each term must be \(column, op, value\)"):
        load(folder, filters=[("label", "==")])
    with pytest.raises(ValueError, match="row lacks"):
        regenerate({"scene": "{}"})
    _, meta = load(folder)
    row = meta.iloc[0].to_dict()
    with pytest.raises(ValueError, match=r"row\['scene'\] = '\{\}' is not a stored dataset"):
        regenerate({**row, "scene": "{}"})
    with pytest.raises(ValueError, match=r"row\['scene'\] = 'not json'"):
        regenerate({**row, "scene": "not json"})
    with pytest.raises(ValueError, match="do not name a row"):
        regenerate({**row, "sensor": "unloaded"})


def test_unreachable_scheduler_fails_fast(tmp_path, capsys, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setattr(sys.modules["ballpass.commands.generate"], "SCHEDULER_TIMEOUT_S", 1)
    grid = tmp_path / "g.toml"
    grid.write_text('[grid]\nbearing = ["6205"]\nfault = ["outer"]\nrpm = [1797]\n')
    t = time.perf_counter()
    assert main(["generate", str(grid), "--out", str(tmp_path / "ds"),
                 "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert time.perf_counter() - t < 5      # the 1 s timeout, not distributed's 30 s
    err = capsys.readouterr().err
    assert "no Dask scheduler answered" in err and "Traceback" not in err
    assert not (tmp_path / "ds").exists()


# ----------------------------------------------------------------------------- size
HUGE = [
    ({"dataset": {"repeats": 1_000_000_000}}, "runs"),
    ({"grid": {"rpm": {"start": 1, "stop": 100000, "step": 0.0001}}}, "Use a larger step"),
    ({"grid": {"rpm": list(range(1, 1001)), "radial_load_n": list(range(1, 1001)),
               "resonance_hz": list(range(1000, 2000))}}, "at most 10,000,000 runs"),
    ({"dataset": {"duration_s": 3600, "fs": 1e6},
      "grid": {"resonance_hz": [3000]}}, "of memory"),
]


#: an hour at 1 MHz needs about 317 GB to simulate; skip on a machine that has it free
BIG_MACHINE = available_memory() > simulation_bytes(3_600_000_000, 1)


@pytest.mark.parametrize("change, says", HUGE)
def test_huge_grids_refused_fast_with_numbers(tmp_path, capsys, change, says):
    if says == "of memory" and BIG_MACHINE:
        pytest.skip("this machine has the memory for an hour at 1 MHz")
    grid = {"dataset": {**GRID["dataset"], **change.get("dataset", {})},
            "grid": {**GRID["grid"], **change.get("grid", {})}}
    lines = ["[dataset]", *(f"{k} = {json.dumps(v)}" for k, v in grid["dataset"].items()),
             "[grid]", *(f"{k} = {json.dumps(v)}" for k, v in grid["grid"].items())]
    path = tmp_path / "huge.toml"
    path.write_text("\n".join(lines).replace('{"start": 1, "stop": 100000, "step": 0.0001}',
                                             "{start = 1, stop = 100000, step = 0.0001}"))
    for extra in ([], ["--dry-run"]):
        t = time.perf_counter()
        assert main(["generate", str(path), "--out", str(tmp_path / "ds"), *extra]) == 2
        assert time.perf_counter() - t < 5      # counted, not built (this took minutes)
        err = capsys.readouterr().err
        assert says in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["huge.toml"]


@pytest.mark.skipif(BIG_MACHINE, reason="this machine has the memory for an hour at 1 MHz")
def test_scene_too_long_for_memory_refused_at_once():
    t = time.perf_counter()
    with pytest.raises(ValueError, match=r"duration_s=3600 s at fs=1e\+06 Hz .* of memory"):
        Scene(bearing="6205", duration_s=3600, fs=1e6)
    assert time.perf_counter() - t < 1


def test_disk_and_memory_checked_before_any_work(tmp_path, monkeypatch):
    out = tmp_path / "ds"
    monkeypatch.setattr(GEN, "free_disk", lambda path: 1000)
    with pytest.raises(ValueError, match=r"of disk for 3 rows .* 1.0 kB free.*--force"):
        generate(GRID, out, progress=False)
    with pytest.raises(ValueError, match="of disk"):
        dry_run(GRID, out_dir=out)
    assert not out.exists()
    monkeypatch.undo()
    monkeypatch.setattr(GEN, "available_memory", lambda: 1000)
    with pytest.raises(ValueError, match=r"of memory for 1 worker.* 1.0 kB is available"):
        generate(GRID, out, progress=False)
    assert not out.exists()
    with pytest.warns(UserWarning, match="Starting anyway"):
        assert generate(GRID, out, progress=False, force=True).n_rows == 3


# ----------------------------------------------------------------------------- workers
def test_worker_request_capped_at_cores_and_shards(tmp_path, monkeypatch):
    started = []
    workers = importlib.import_module("ballpass.datasets._workers")
    pool = workers._pool
    monkeypatch.setattr(workers, "_pool", lambda n: started.append(n) or pool(n))
    cores = workers.available_cores()
    with pytest.warns(UserWarning, match=f"n_jobs=1000 is more than the {cores} cores"):
        generate(GRID, tmp_path / "ds", n_jobs=1000, progress=False)
    assert started == ([min(cores, 3)] if cores > 1 else [])   # 1 worker: in process
    one_shard = {**GRID, "dataset": {**GRID["dataset"], "shard_size": 3}}
    generate(one_shard, tmp_path / "one", n_jobs=2, progress=False)
    assert len(started) == (1 if cores > 1 else 0)               # 1 shard: no pool




def alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_sigkill_of_generate_leaves_no_worker_and_nothing_in_dev_shm(tmp_path):
    grid = tmp_path / "g.toml"
    grid.write_text("[dataset]\nduration_s = 0.2\nfs = 12000\nrepeats = 20\nshard_size = 1\n"
                    '[grid]\nbearing = ["6205"]\nfault = ["outer", "inner"]\nrpm = [1797]\n'
                    "resonance_hz = [3000]\n")
    shm_before = set(os.listdir("/dev/shm"))
    out = tmp_path / "ds"
    proc = subprocess.Popen([sys.executable, "-m", "ballpass", "generate", str(grid), "--out",
                             str(out), "--jobs", "2", "--no-progress"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while not (len(children(proc.pid)) >= 2 and list(out.glob("part-*.parquet"))):
        assert proc.poll() is None, proc.stderr.read().decode()
        assert time.monotonic() < deadline
        time.sleep(0.01)
    workers = children(proc.pid)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    deadline = time.monotonic() + 5            # "within seconds"
    while any(alive(w) for w in workers) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not [w for w in workers if alive(w)]
    shards = sorted(p.name for p in out.glob("part-*.parquet"))
    time.sleep(0.5)
    assert sorted(p.name for p in out.glob("part-*.parquet")) == shards   # nobody writes
    new = set(os.listdir("/dev/shm")) - shm_before
    pids = [str(p) for p in (proc.pid, *workers)]
    # joblib/loky named their leftovers after the parent (joblib_memmapping_folder_<pid>_...,
    # sem.loky-<pid>-...); multiprocessing unlinks its semaphores at creation
    assert not [n for n in new if any(p in n for p in pids) or n.startswith("sem.mp-")]
    assert len(shards) < read_grid(grid).n_shards
    assert generate(grid, out, progress=False).n_rows == read_grid(grid).n_rows   # resumes
