"""``ballpass diagnose`` end to end (in process, via the dispatcher)."""

import numpy as np
import pandas as pd

import ballpass as bp
from ballpass.cli import main
from ballpass.signalio import write_signal

FS = 12_000.0
RPM = 1797.0


def impacts(rate, n=24_000, seed=0):
    """Impacts at `rate` Hz ringing 3 kHz, modulated at the shaft speed, in noise, m/s^2."""
    t = np.arange(n) / FS
    phase = (t * rate) % 1.0 / rate
    zone = 1.0 + np.cos(2 * np.pi * RPM / 60 * t)
    x = zone * np.exp(-600 * phase) * np.sin(2 * np.pi * 3_000 * phase)
    return x + 0.2 * np.random.default_rng(seed).standard_normal(n)


def faulty_and_healthy(folder, fault: str):
    """One file ``two.npz`` with channels ``faulty`` (impacts at the 6205's ``fault``
    frequency, "bpfo" or "bpfi") and ``healthy`` (white noise)."""
    rate = getattr(bp.Bearing.catalog("6205").frequencies(RPM / 60), fault)
    noise = np.random.default_rng(3).standard_normal(24_000)
    return write_signal(folder / "two.npz", np.stack([impacts(rate), noise]), FS,
                        channels=["faulty", "healthy"], meta={"bearing": "6205", "rpm": RPM})


def test_verdicts_printed_and_tabled(tmp_path, capsys):
    """An inner-race signal and pure noise, one file: the verdicts are the diagnoser's
    (catches a table that mixes up rows or families, or a verdict taken from the wrong
    family), and the table carries the evidence that decided them."""
    path = faulty_and_healthy(tmp_path, "bpfi")
    out = tmp_path / "v.csv"
    assert main(["diagnose", str(path), "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "two_faulty: inner (grade" in printed and "two_healthy: healthy (grade" in printed
    assert "1xBPFI" in printed  # the decisive lines are listed
    table = pd.read_csv(out)
    assert table.prediction.tolist() == ["inner", "healthy"]
    assert table.inner_db[0] > table.inner_threshold_db[0] > max(table.outer_db[0],
                                                                table.ball_db[0])
    assert (table[["outer_db", "inner_db", "ball_db"]].iloc[1] < 6.0).all()
    assert table.band_lo_hz[0] <= 3_000 <= table.band_hi_hz[0]
    assert (table.rpm_used == RPM).all() and (table.bearing.astype(str) == "6205").all()


def test_unknown_speed_is_refused_naming_the_option(tmp_path, capsys):
    path = write_signal(tmp_path / "x.npz", impacts(100.0)[None], FS, channels=["a"],
                        meta={"bearing": "6205"})
    assert main(["diagnose", str(path)]) != 0
    assert "shaft speed (--rpm)" in capsys.readouterr().err
    # given on the command line, it runs
    assert main(["diagnose", str(path), "--rpm", str(RPM), "--quiet"]) == 0


def test_plot_writes_one_figure_per_signal(tmp_path, capsys):
    """--plot DIR: one PNG per signal, named after it; a file given as DIR is refused
    before any work."""
    path = faulty_and_healthy(tmp_path, "bpfo")
    figs = tmp_path / "figs"
    assert main(["diagnose", str(path), "--plot", str(figs), "--quiet"]) == 0
    assert sorted(p.name for p in figs.iterdir()) == ["two_faulty.png", "two_healthy.png"]
    assert all(p.read_bytes()[:4] == b"\x89PNG" for p in figs.iterdir())
    capsys.readouterr()
    assert main(["diagnose", str(path), "--plot", str(path)]) != 0
    assert "--plot" in capsys.readouterr().err
    # a folder named like a file is refused, and a failed run leaves no folder behind
    assert main(["diagnose", str(path), "--plot", str(tmp_path / "x.png")]) != 0
    assert main(["diagnose", str(tmp_path / "missing.npz"), "--plot",
                 str(tmp_path / "new")]) != 0
    assert not (tmp_path / "x.png").exists() and not (tmp_path / "new").exists()


def test_too_short_segments_are_refused_naming_the_option(tmp_path, capsys):
    # A 6205's cage turns at 0.398 x 29.95 Hz: two cage periods last 0.168 s.
    path = write_signal(tmp_path / "x.npz", impacts(100.0)[None], FS, channels=["a"],
                        meta={"bearing": "6205", "rpm": RPM})
    assert main(["diagnose", str(path), "--segment", "0.1"]) != 0
    err = capsys.readouterr().err
    assert "--segment" in err and "0.168 s" in err and "X rows" not in err
    # a whole record that short is the record's fault: no --segment to blame
    short = write_signal(tmp_path / "short.npz", impacts(100.0)[None, :1200], FS,
                         channels=["a"], meta={"bearing": "6205", "rpm": RPM})
    assert main(["diagnose", str(short)]) != 0
    err = capsys.readouterr().err
    assert "0.168 s" in err and "needs at least that much of the record" in err
    assert "--segment" not in err


def test_segments_come_with_their_whole_record(tmp_path, capsys):
    """--segment: each record is also diagnosed whole, printed with the tally of its
    segments' verdicts, and tabled with scope "record" (catches a tally counting another
    record's segments: the healthy record's segments are all healthy)."""
    path = faulty_and_healthy(tmp_path, "bpfi")
    out = tmp_path / "v.csv"
    assert main(["diagnose", str(path), "--segment", "0.5", "--out", str(out),
                 "--quiet"]) == 0
    printed = capsys.readouterr().out
    assert "two_faulty, whole record (2 s): inner (grade" in printed
    assert "two_healthy, whole record (2 s): healthy (grade" in printed
    assert "its 4 segments: 4 healthy" in printed.split("two_healthy, whole record")[1]
    table = pd.read_csv(out)
    assert table.scope.tolist() == ["segment"] * 8 + ["record"] * 2
    assert table[table.scope == "record"].prediction.tolist() == ["inner", "healthy"]


def ringing(rate, n, amplitude, seed):
    """Impacts at ``rate`` Hz of ``amplitude`` ringing 3 kHz in unit white noise, m/s^2."""
    t = np.arange(n) / FS
    phase = (t * rate) % 1.0 / rate
    x = amplitude * np.exp(-600 * phase) * np.sin(2 * np.pi * 3_000 * phase)
    return x + np.random.default_rng(seed).standard_normal(n)


def test_baseline_thresholds_keep_a_machines_own_line_healthy(tmp_path, capsys):
    """A machine whose healthy vibration carries a line at BPFO (9-11 dB of outer-race
    evidence on 2 s, above the 6 dB default): without a baseline it is called "outer";
    with a 10 s healthy recording of it as --baseline, a new healthy record is healthy
    and a real fault (18-19 dB) is still named. The threshold is the one
    ``baseline_thresholds`` gives for windows as long as the diagnosed signals (catches
    the baseline fitted whole, or ignored)."""
    bpfo = bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfo
    meta = {"bearing": "6205", "rpm": RPM}
    healthy = ringing(bpfo, 120_000, 1.5, seed=99)
    base = write_signal(tmp_path / "base.npz", healthy[None], FS, channels=["h"], meta=meta)
    new = write_signal(tmp_path / "new.npz", np.stack([ringing(bpfo, 24_000, 1.5, seed=5),
                                                       ringing(bpfo, 24_000, 8.0, seed=6)]),
                       FS, channels=["own_line", "fault"], meta=meta)
    plain, calibrated = tmp_path / "plain.csv", tmp_path / "calibrated.csv"
    assert main(["diagnose", str(new), "-q", "--out", str(plain)]) == 0
    assert pd.read_csv(plain).prediction.tolist() == ["outer", "outer"]
    assert main(["diagnose", str(new), "-q", "--baseline", str(base),
                 "--out", str(calibrated)]) == 0
    table = pd.read_csv(calibrated)
    assert table.prediction.tolist() == ["healthy", "outer"]
    expected = bp.diagnose.baseline_thresholds([(healthy, FS, RPM)], "6205", 2.0)
    for family in ("outer", "inner", "ball"):
        np.testing.assert_allclose(table[f"{family}_threshold_db"], expected[family])
    assert "baseline (base), 6205 on 2 s windows" in capsys.readouterr().out
    # a baseline of another bearing is refused before any work, naming the option
    other = write_signal(tmp_path / "other.npz", healthy[None], FS, channels=["h"],
                         meta={"bearing": "6203", "rpm": RPM})
    assert main(["diagnose", str(new), "-q", "--baseline", str(other)]) != 0
    assert "--baseline holds no healthy recording of bearing 6205" in capsys.readouterr().err


def test_line_hz_and_the_stated_false_alarm_probability(tmp_path, capsys):
    """``--line-hz`` reaches the diagnoser (a bad value is refused naming it), and the
    table carries each verdict's false-alarm probability (at most the default 1e-3)."""
    path = faulty_and_healthy(tmp_path, "bpfo")
    out = tmp_path / "v.csv"
    assert main(["diagnose", str(path), "--line-hz", "50", "--out", str(out), "--quiet"]) == 0
    table = pd.read_csv(out)
    assert table.prediction.tolist() == ["outer", "healthy"]
    assert (table.false_alarm_probability <= 1e-3).all()
    capsys.readouterr()
    assert main(["diagnose", str(path), "--line-hz", "-50", "--quiet"]) != 0
    assert "line_hz must be" in capsys.readouterr().err
