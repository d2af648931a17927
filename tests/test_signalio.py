"""Signal files: npz / csv / parquet round trips, atomic writes, validation."""

import os
from pathlib import Path

import numpy as np
import pytest

from ballpass.signalio import (
    SUFFIXES,
    atomic_write,
    atomic_write_many,
    check_output_path,
    read_signal,
    write_signal,
)


@pytest.mark.parametrize("suffix", SUFFIXES)
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_round_trip(tmp_path, suffix, dtype):
    """npz and parquet store the array exactly; CSV writes 9 significant digits, which
    is exact for float32 and 5e-9 relative for float64."""
    accel = np.random.default_rng(0).standard_normal((2, 500)).astype(dtype)
    meta = {
        "rpm": np.float64(1797.0),
        "bearing": "6205",
        "scene": {"fault": None},
        "angles": np.arange(3),
    }
    path = write_signal(
        tmp_path / f"run{suffix}", accel, 12_000.0, channels=["loaded", "unloaded"], meta=meta
    )
    sig = read_signal(path)
    assert sig.fs == 12_000.0
    assert sig.channels == ("loaded", "unloaded")
    assert sig.meta == {
        "rpm": 1797.0,
        "bearing": "6205",
        "scene": {"fault": None},
        "angles": [0, 1, 2],
    }
    if suffix == ".csv":
        np.testing.assert_allclose(sig.accel, accel, rtol=5e-9, atol=1e-12)
    else:
        assert sig.accel.dtype == dtype
        np.testing.assert_array_equal(sig.accel, accel)
    np.testing.assert_array_equal(sig.channel("unloaded"), sig.accel[1])
    assert [p.name for p in tmp_path.iterdir()] == [f"run{suffix}"]  # no temporaries left


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_one_channel_defaults(tmp_path, suffix):
    sig = read_signal(write_signal(tmp_path / f"s{suffix}", np.arange(10.0), 100.0))
    assert sig.accel.shape == (1, 10) and sig.channels == ("accel",) and sig.meta == {}


def test_csv_layout_and_files_from_other_tools(tmp_path):
    path = write_signal(tmp_path / "s.csv", np.ones((2, 3)), 1000.0, meta={"rpm": 60})
    lines = path.read_text().splitlines()
    assert lines[:3] == ["# fs=1000.0", '# meta={"rpm": 60}', "t_s,accel_0,accel_1"]
    assert lines[4].startswith("0.001,1,1")
    # A CSV without the comment lines: fs from the t_s column.
    foreign = tmp_path / "foreign.csv"
    foreign.write_text("t_s,x\n0.0,1\n0.0005,2\n0.001,3\n")
    sig = read_signal(foreign)
    assert sig.fs == pytest.approx(2000.0) and sig.channels == ("x",)


def test_parquet_without_metadata(tmp_path):
    import pyarrow as pa
    import pyarrow.parquet as pq

    pq.write_table(
        pa.table({"t_s": [0.0, 0.01, 0.02], "a": [1.0, 2.0, 3.0]}), tmp_path / "p.parquet"
    )
    sig = read_signal(tmp_path / "p.parquet")
    assert sig.fs == pytest.approx(100.0) and sig.channels == ("a",)


def test_atomic_write_leaves_old_file_on_failure(tmp_path):
    path = write_signal(tmp_path / "s.npz", np.ones(4), 10.0)
    with pytest.raises(TypeError, match="JSON"):
        write_signal(path, np.zeros(4), 10.0, meta={"bad": object()})
    assert read_signal(path).accel.sum() == 4.0  # untouched
    assert [p.name for p in tmp_path.iterdir()] == ["s.npz"]


@pytest.mark.parametrize(
    ("args", "kwargs", "error", "match"),
    [
        (("s.txt", np.ones(3), 10.0), {}, ValueError, r"\.npz, \.csv, \.parquet"),
        (("s.npz", np.ones(3), 0.0), {}, ValueError, "^fs"),
        (("s.npz", np.ones((2, 2, 2)), 10.0), {}, ValueError, "^accel"),
        (("s.npz", np.ones((1, 0)), 10.0), {}, ValueError, "^accel"),
        (("s.npz", np.array(["a"]), 10.0), {}, TypeError, "^accel"),
        (("s.npz", np.ones((2, 3)), 10.0), {"channels": ["a"]}, ValueError, "^channels"),
        (("s.npz", np.ones((2, 3)), 10.0), {"channels": ["a", "a"]}, ValueError, "^channels"),
        (("s.csv", np.ones(3), 10.0), {"channels": ["t_s"]}, ValueError, "^channels"),
    ],
)
def test_write_errors(tmp_path, args, kwargs, error, match):
    with pytest.raises(error, match=match):
        write_signal(tmp_path / args[0], *args[1:], **kwargs)


def test_read_errors(tmp_path):
    with pytest.raises(ValueError, match="path must end in"):
        read_signal(tmp_path / "x.mat")
    with pytest.raises(FileNotFoundError):
        read_signal(tmp_path / "x.npz")
    np.savez(tmp_path / "other.npz", data=np.ones(3))
    with pytest.raises(ValueError, match="not a ballpass"):
        read_signal(tmp_path / "other.npz")


def test_unreadable_files_are_clear_errors(tmp_path):
    """A text file named .npz (numpy would talk about allow_pickle), a truncated
    archive, a complex signal (numpy would drop the imaginary part with a warning)."""
    (tmp_path / "text.npz").write_text("hello")
    with pytest.raises(ValueError, match=r"^text\.npz: .*not a NumPy \.npz archive"):
        read_signal(tmp_path / "text.npz")
    good = write_signal(tmp_path / "good.npz", np.ones(1000), 10.0).read_bytes()
    (tmp_path / "cut.npz").write_bytes(good[: len(good) // 2])
    with pytest.raises(ValueError, match=r"^cut\.npz: not a readable \.npz"):
        read_signal(tmp_path / "cut.npz")
    np.savez(tmp_path / "c.npz", accel=np.ones((1, 5)) * 1j, fs=10.0)
    with pytest.raises(TypeError, match="complex"):
        read_signal(tmp_path / "c.npz")
    (tmp_path / "junk.parquet").write_bytes(b"PAR1 junk")
    with pytest.raises(ValueError, match=r"^junk\.parquet: not a readable"):
        read_signal(tmp_path / "junk.parquet")


def test_atomic_write_reraises_the_original_error_even_if_cleanup_fails(tmp_path,
                                                                        monkeypatch):
    """The cleanup's own error (here: the temporary file cannot be removed) must not
    replace the error that made the write fail."""
    def fail(tmp):
        tmp.write_text("half")
        raise KeyError("the original")

    def unlink(self, missing_ok=False):
        raise PermissionError("cleanup failed too")

    monkeypatch.setattr(Path, "unlink", unlink)
    with pytest.raises(KeyError, match="the original"):
        atomic_write(tmp_path / "x.csv", fail)
    assert not (tmp_path / "x.csv").exists()


def test_atomic_write_many_is_all_or_nothing(tmp_path):
    old = write_signal(tmp_path / "a.npz", np.ones(4), 10.0)

    def broken(tmp):
        raise OSError("disk full")

    with pytest.raises(OSError, match="disk full"):
        atomic_write_many([(old, lambda tmp: tmp.write_bytes(b"new")),
                           (tmp_path / "b.png", broken)])
    assert read_signal(old).accel.sum() == 4.0 and sorted(os.listdir(tmp_path)) == ["a.npz"]


def test_check_output_path(tmp_path):
    (tmp_path / "afile").write_text("x")
    (tmp_path / "d.csv").mkdir()
    ok = check_output_path(tmp_path / "new" / "deeper" / "t.csv", suffixes=(".csv",))
    assert ok.name == "t.csv" and not (tmp_path / "new").exists()  # nothing created
    cases = [
        (dict(path=tmp_path / "afile" / "t.csv"), ValueError, "afile is a file"),
        (dict(path=tmp_path / "t.txt", suffixes=(".csv", ".parquet")), ValueError,
         r"must end in \.csv or \.parquet"),
        (dict(path=tmp_path / "d.csv"), ValueError, "is a folder, not a file"),
        (dict(path=tmp_path / "afile", folder=True), ValueError, "is a file, not a folder"),
        (dict(path=Path("/proc/ballpass-test/t.csv")), PermissionError, "cannot write in"),
    ]
    for kwargs, error, match in cases:
        with pytest.raises(error, match=match):
            check_output_path(option="--out", **kwargs)
    assert sorted(os.listdir(tmp_path)) == ["afile", "d.csv"]


@pytest.mark.parametrize("keep", [0.05, 0.5, 0.999])
def test_truncated_csv_is_refused_naming_the_file(tmp_path, keep):
    """A ballpass CSV cut short mid-line (a full disk, a copy interrupted) used to be
    read as a shorter signal, its last sample a cut-off number (found by
    benchmarks/abuse_sweep.py). Cut at a line end it stays indistinguishable from a
    shorter recording; mid-line it is refused."""
    path = write_signal(tmp_path / "sig.csv", np.arange(1000.0) / 7.0, 1000.0)
    data = path.read_bytes()
    cut = int(len(data) * keep)
    cut -= data[cut - 1:cut] == b"\n"          # mid-line, not just after a line break
    path.write_bytes(data[:cut])
    with pytest.raises(ValueError, match="sig.csv ends in the middle of a line: the file "
                                         "is truncated"):
        read_signal(path)
