"""A tampered ``_manifest.json``: nothing outside the dataset folder is read, written or
deleted because of it, and what it says is checked against the shards themselves.

A dataset folder can come from anyone (a shared drive, a download), so its manifest is
input like any other. The dataset is tiny (3 shards of one 0.05 s impulse-model run).
"""

import contextlib
import json
import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest

from ballpass.cli import main
from ballpass.datasets import dry_run, generate, info, load
from ballpass.datasets.store import CorruptShardError

GRID = {
    "dataset": {"duration_s": 0.05, "fs": 12000, "seed": 3, "shard_size": 1,
                "model": "impulse"},
    "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"], "rpm": [1797],
             "resonance_hz": [3000]},
}


def files(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("tamper") / "ds"
    generate(GRID, out, progress=False)
    return out, load(out)[0]


@pytest.fixture
def copy(reference, tmp_path):
    out = tmp_path / "ds"
    shutil.copytree(reference[0], out)
    return out


def edit(folder: Path, change) -> None:
    manifest = json.loads((folder / "_manifest.json").read_text())
    change(manifest)
    (folder / "_manifest.json").write_text(json.dumps(manifest))


def every_reader_refuses(folder: Path, capsys, match: str, error=ValueError) -> None:
    """load, info, dry_run, generate (resume) and `ballpass info` all refuse, one line."""
    for call in (lambda: load(folder), lambda: info(folder),
                 lambda: dry_run(GRID, out_dir=folder),
                 lambda: generate(GRID, folder, progress=False)):
        with pytest.raises(error, match=match):
            call()
    assert main(["info", str(folder)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err


def outside_targets(tmp_path: Path, folder: Path) -> list[str]:
    """Names a tampered entry 1 may give: a canary beside the folder, by a relative and
    an absolute path, a sub-folder, another pattern, another shard's name."""
    return ["../canary.parquet", str(tmp_path / "canary.parquet"), "sub/part-00001.parquet",
            "data-00001.parquet", "part-00002.parquet", "part-1.parquet", ""]


@pytest.mark.parametrize("target", range(7))
def test_shard_names_outside_the_writer_pattern_touch_nothing(copy, tmp_path, capsys,
                                                              target):
    # the canary stands where "../x" and the absolute path point: a damaged shard there
    # used to be deleted and regenerated (run as root, any file on the machine)
    canary = tmp_path / "canary.parquet"
    canary.write_bytes(b"canary: must survive, unread")
    (copy / "sub").mkdir()
    (copy / "sub" / "part-00001.parquet").write_bytes(b"sub-folder canary")
    (copy / "data-00001.parquet").write_bytes(b"other-pattern canary")
    name = outside_targets(tmp_path, copy)[target]
    edit(copy, lambda m: m["shards"][1].update(file=name))
    before = files(copy)
    with contextlib.suppress(Exception):       # first as the attacker hopes, then checked
        generate(GRID, copy, progress=False)
    assert canary.read_bytes() == b"canary: must survive, unread"
    every_reader_refuses(copy, capsys, "shard entry 1 names file .* ballpass writes shard 1 "
                         "as 'part-00001.parquet'.* nothing was read, written or deleted")
    assert canary.read_bytes() == b"canary: must survive, unread"
    assert files(copy) == before                       # the folder too is untouched


def test_duplicate_entry_refused(copy, capsys):
    edit(copy, lambda m: m["shards"].insert(1, dict(m["shards"][0])))   # "9 of 8" before
    every_reader_refuses(copy, capsys, r"'part-00000.parquet' \(listed twice\)")


def test_altered_row_counts_are_not_reported_as_fact(copy, capsys):
    def shard_count(m):
        m["shards"][1]["n_rows"] = 5
        m["n_rows"] = 7

    edit(copy, shard_count)
    for reader in (load, info):
        with pytest.raises(CorruptShardError, match="part-00001.parquet holds 1 rows where "
                                                    "the manifest records 5"):
            reader(copy)
    with pytest.raises(ValueError, match="shard entry 1 .* is not what its grid plans"):
        generate(GRID, copy, progress=False)

    edit(copy, lambda m: m.update(n_rows=9))                # the total alone
    every_reader_refuses(copy, capsys, "records n_rows = 9 but its shards hold 7 rows")


def test_unknown_format_version_refused_with_what_to_do(copy, capsys):
    edit(copy, lambda m: m.update(format_version=99))
    every_reader_refuses(copy, capsys, "format_version 99; this ballpass reads format "
                         "versions 1 to 2.*pip install -U ballpass")


@pytest.mark.parametrize("change, says", [
    # found by benchmarks/abuse_sweep.py: each was a ZeroDivisionError, KeyError or
    # AttributeError traceback (`ballpass info` included) before the fields were checked
    (lambda m: m.update(fs=0), r"fs is '0', not a positive number"),
    (lambda m: m.update(fs="fast"), r"fs is 'fast', not a positive number"),
    (lambda m: m.pop("fs"), r"has no 'fs': the manifest is damaged"),
    (lambda m: m.pop("n_rows"), r"has no 'n_rows'"),
    (lambda m: m.pop("signal_length"), r"has no 'signal_length'"),
    (lambda m: m.update(signal_length=0), r"signal_length is '0', not a whole number >= 1"),
    (lambda m: m.pop("grid"), r"has no 'grid'"),
    (lambda m: m.update(grid="x"), r"grid is 'x', not a table with 'dataset' and 'grid'"),
])
def test_missing_or_mistyped_fields_are_named(copy, capsys, change, says):
    edit(copy, change)
    every_reader_refuses(copy, capsys, says)


def test_json_nested_too_deeply_is_refused_not_a_recursion_error(copy, capsys):
    (copy / "_manifest.json").write_text("[" * 100_000 + "]" * 100_000)
    every_reader_refuses(copy, capsys, "nested too deeply")


def test_stray_copy_of_a_shard_never_duplicates_rows_after_resume(reference, copy):
    # the run was killed before shard 2; someone drops a copy of shard 0 under its name
    def unfinished(m):
        m["shards"][2].update(complete=False, sha256=None, bytes=0)
        m["status"] = "running"

    edit(copy, unfinished)
    shutil.copy(copy / "part-00000.parquet", copy / "part-00002.parquet")
    shutil.copy(copy / "part-00000.parquet", copy / "part-00007.parquet")   # beyond the grid
    with pytest.warns(UserWarning) as caught:
        generate(GRID, copy, progress=False)
    said = " ".join(str(w.message) for w in caught)
    assert "part-00002.parquet holds rows of runs outside this shard's runs" in said
    with pytest.warns(UserWarning, match="part-00007.parquet, which its manifest does not list"):
        X, meta = load(copy)
    assert meta["run_id"].tolist() == [0, 1, 2]
    assert np.array_equal(X, reference[1])


def test_info_says_interrupted_for_a_dead_run(copy):
    edit(copy, lambda m: m.update(status="running"))     # as a killed generate leaves it
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert info(copy)["status"] == "interrupted"
    import fcntl

    with open(copy / ".lock", "a") as fh:                # a live generate holds the lock
        fcntl.flock(fh, fcntl.LOCK_EX)
        assert info(copy)["status"] == "running"


@pytest.mark.parametrize("link", ["_features", "part-00001.parquet"])
def test_symbolic_links_in_the_folder_are_never_followed_to_delete(copy, tmp_path, link):
    """A `_features` folder or a shard that is a link to elsewhere: a resume would
    delete the damaged shards through it (outside the folder); refused, canary kept."""
    outside = tmp_path / "outside"
    outside.mkdir()
    canary = outside / "part-00001.parquet"
    canary.write_bytes(b"canary")
    if link == "_features":
        edit(copy, lambda m: m["shards"][1].update(features_complete=False))
    else:
        (copy / link).unlink()
    (copy / link).symlink_to(outside if link == "_features" else canary)
    with pytest.raises(ValueError, match=f"symbolic links \\({link}\\)"):
        generate(GRID, copy, progress=False)
    assert canary.read_bytes() == b"canary"
    if link != "_features":
        with pytest.raises(CorruptShardError, match="is a symbolic link"):
            load(copy)
