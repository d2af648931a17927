"""``ballpass features`` and ``ballpass plot`` end to end (in process, via the dispatcher)."""

import io
import json
import sys

import numpy as np
import pandas as pd
import pytest
import scipy.io

import ballpass as bp
from ballpass.cli import main
from ballpass.signalio import read_signal, write_signal

FS = 12_000.0
RPM = 1797.0


def impacts(rate, n=12_000, seed=0):
    """Impacts at `rate` Hz ringing 3 kHz, in noise, m/s^2."""
    t = np.arange(n) / FS
    phase = (t * rate) % 1.0 / rate
    x = np.exp(-600 * phase) * np.sin(2 * np.pi * 3_000 * phase)
    return x + 0.1 * np.random.default_rng(seed).standard_normal(n)


@pytest.fixture
def outer_file(tmp_path):
    bpfo = bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfo
    accel = np.stack([impacts(bpfo), 0.5 * impacts(bpfo, seed=1)])
    return write_signal(
        tmp_path / "outer.npz",
        accel,
        FS,
        channels=["loaded", "unloaded"],
        meta={"bearing": "6205", "rpm": RPM, "label": "outer"},
    )


def test_signal_file_to_csv_and_parquet(tmp_path, outer_file, capsys):
    assert main(["features", str(outer_file), "--out", str(tmp_path / "t.csv")]) == 0
    table = pd.read_csv(tmp_path / "t.csv")
    assert table.source.tolist() == ["outer_loaded", "outer_unloaded"]
    assert (table.label == "outer").all() and (table.rpm == RPM).all()
    assert (table.bpfo_1 > 10).all() and (table.bpfo_1 > table.bpfi_1 + 5).all()
    assert ((table.band_lo_hz <= 3000) & (table.band_hi_hz >= 3000)).all()
    assert "2 signal(s)" in capsys.readouterr().out
    # Parquet output and the other input formats give the same numbers.
    sig = read_signal(outer_file)
    other = write_signal(
        tmp_path / "outer.parquet", sig.accel, sig.fs, channels=sig.channels, meta=sig.meta
    )
    assert main(["features", str(other), "-o", str(tmp_path / "t.parquet")]) == 0
    pq = pd.read_parquet(tmp_path / "t.parquet")
    np.testing.assert_allclose(pq.bpfo_1, table.bpfo_1, rtol=1e-9)


def test_stdout_overrides_and_segments(outer_file, capsys):
    assert (
        main(
            [
                "features",
                str(outer_file),
                "--rpm",
                "1500",
                "--segment",
                "0.5",
                "--band",
                "2000",
                "4000",
            ]
        )
        == 0
    )
    out = capsys.readouterr().out
    table = pd.read_csv(io.StringIO(out))
    assert len(table) == 4 and table.segment.tolist() == [0, 1, 0, 1]
    assert (table.rpm == 1500).all() and (table.band_lo_hz == 2000).all()
    assert (table.bpfo_1 < 6).all()  # the wrong speed misses the BPFO line


def write_cwru(folder, name, record, n, rpm=1797):
    """A file with CWRU's layout: values in g, record-numbered variables."""
    path = folder / f"{name}.mat"
    g = impacts(162.2, n=n) / 9.80665
    scipy.io.savemat(
        path,
        {
            f"X{record:03d}_DE_time": g[:, None],
            f"X{record:03d}RPM": np.array([[rpm]], dtype=np.uint16),
        },
    )
    return path


def test_cwru_mat_inputs(tmp_path, capsys):
    ir = write_cwru(tmp_path, "12k_DE_IR007_0", 105, 24_000)
    normal = write_cwru(tmp_path, "Normal_0_48k", 97, 48_000, rpm=1796)
    assert main(["features", str(ir), str(normal), "--segment", "1"]) == 0
    table = pd.read_csv(io.StringIO(capsys.readouterr().out))
    assert table.label.tolist() == ["inner", "inner", "healthy"]
    assert table.fs.tolist() == [12_000.0, 12_000.0, 48_000.0]  # the 48 kHz pitfall
    # each row says its file, and the segments of one record share a group to split by
    assert table.file.tolist() == [ir.name, ir.name, normal.name]
    assert table.group[0] == table.group[1] != table.group[2]
    assert (table.bearing == 6205).all()
    # g -> m/s^2: the rms of the loaded signal, not 1/9.81 of it
    np.testing.assert_allclose(
        table.rms[0], np.sqrt(np.mean(impacts(162.2)[:12_000] ** 2)), rtol=1e-6
    )
    assert table.bpfi_1[0] > 10


def test_plots(tmp_path, outer_file, capsys):
    assert (
        main(
            [
                "features",
                str(outer_file),
                "--out",
                str(tmp_path / "t.csv"),
                "--plot",
                str(tmp_path / "figs"),
            ]
        )
        == 0
    )
    assert sorted(p.name for p in (tmp_path / "figs").iterdir()) == [
        "outer_loaded.png",
        "outer_unloaded.png",
    ]
    assert main(["plot", str(outer_file), "--out", str(tmp_path / "p")]) == 0
    assert len(list((tmp_path / "p").glob("*.png"))) == 2
    one = write_signal(tmp_path / "one.csv", impacts(100.0), FS)
    assert main(["plot", str(one), "--out", str(tmp_path / "one.png")]) == 0
    assert (tmp_path / "one.png").stat().st_size > 10_000
    assert main(["plot", str(outer_file), "--out", str(tmp_path / "x.png")]) == 2
    assert "give a folder" in capsys.readouterr().err
    # another figure format is written in that format, not made a folder of that name
    assert main(["plot", str(one), "--out", str(tmp_path / "one.pdf")]) == 0
    assert (tmp_path / "one.pdf").read_bytes()[:5] == b"%PDF-"


def test_dataset_folder(tmp_path, monkeypatch, capsys):
    """A dataset folder goes through ballpass.datasets.load (stubbed here)."""
    import ballpass.datasets

    folder = tmp_path / "ds"
    folder.mkdir()
    (folder / "manifest.json").write_text(json.dumps({}))
    X = np.stack([impacts(107.4), impacts(162.2)]).astype(np.float32)
    meta = pd.DataFrame(
        {
            "label": ["outer", "inner"],
            "bearing": ["6205", "6205"],
            "rpm": [RPM, RPM],
            "fs": [FS, FS],
            "group": ["a", "b"],
        }
    )
    monkeypatch.setattr(ballpass.datasets, "load", lambda path: (X, meta), raising=False)
    assert main(["features", str(folder)]) == 0
    table = pd.read_csv(io.StringIO(capsys.readouterr().out))
    assert table.group.tolist() == ["a", "b"]
    assert table.bpfo_1[0] > table.bpfo_1[1] and table.bpfi_1[1] > table.bpfi_1[0]
    monkeypatch.delattr(ballpass.datasets, "load", raising=False)
    assert main(["features", str(folder)]) == 2
    assert "no ballpass.datasets.load" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["features", "signal.txt"], "no such file"),
        (["features", "{tmp}"], "without _manifest.json"),
        (["features", "{sig}", "--out", "t.xlsx"], ".csv or .parquet"),
        (["features", "{sig}", "--band", "5000", "9000"], "band must satisfy"),
        (["features", "{odd}"], "x.xlsx: a recording must be a .npz, .parquet, .csv, .npy, "
                                ".wav or .mat file"),
        (["features", "{cut}"], "x.wav: not a readable WAV file"),
    ],
)
def test_errors(tmp_path, outer_file, capsys, argv, message):
    odd, cut = tmp_path / "x.xlsx", tmp_path / "x.wav"
    odd.write_bytes(b"PK")
    cut.write_bytes(b"RIFF")
    argv = [a.format(tmp=tmp_path, sig=outer_file, odd=odd, cut=cut) for a in argv]
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_help_has_examples_and_pitfalls(capsys):
    for command in ("features", "plot"):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        text = capsys.readouterr().out
        assert "examples:" in text and f"ballpass {command} " in text
    with pytest.raises(SystemExit):
        main(["features", "--help"])
    text = capsys.readouterr().out
    assert "48 kHz" in text and "9.80665" in text


def test_plot_shows_progress_on_a_terminal_only(tmp_path, capsys, monkeypatch):
    one = write_signal(tmp_path / "one.npz", impacts(100.0), FS)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)  # captured stderr as a terminal
    assert main(["plot", str(one), "--out", str(tmp_path / "a")]) == 0
    assert "plot:" in capsys.readouterr().err  # the bar, "plot: 100%|..."
    assert main(["plot", str(one), "--out", str(tmp_path / "b"), "--quiet"]) == 0
    assert "plot:" not in capsys.readouterr().err


def test_fs_for_a_signal_file_is_not_silently_dropped(outer_file, capsys):
    """A signal file carries its rate: a --fs that contradicts it is an error, one that
    agrees is accepted."""
    assert main(["features", str(outer_file), "--fs", "1000"]) == 2
    assert ("outer.npz: fs 1000 Hz given, but the file states 12000 Hz"
            in capsys.readouterr().err)
    assert main(["features", str(outer_file), "--fs", str(FS)]) == 0
    assert set(pd.read_csv(io.StringIO(capsys.readouterr().out)).fs) == {FS}
