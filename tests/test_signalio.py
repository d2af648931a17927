"""Signal files: npz / csv / parquet round trips, atomic writes, validation."""

import numpy as np
import pytest

from ballpass.signalio import SUFFIXES, read_signal, write_signal


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
