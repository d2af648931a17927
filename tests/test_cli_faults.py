"""The CLI under faults: corrupted and unusable signal files, Ctrl-C and SIGTERM, output
cut short by its reader. Each ends in one line (or silence) and a fixed exit code, never
a traceback; interrupted work leaves nothing half-written and no worker behind.
"""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from _processes import children, default_sigint

from ballpass.cli import EXIT_BROKEN_PIPE, EXIT_INTERRUPTED, main
from ballpass.signalio import read_signal, write_signal

ROOT = Path(__file__).resolve().parents[1]
FS = 12_000.0


def ballpass(*argv, **popen):
    """``python -m ballpass ARGV`` from the worktree, as a user runs it."""
    return subprocess.Popen([sys.executable, "-m", "ballpass", *map(str, argv)], cwd=ROOT,
                            stderr=subprocess.PIPE, text=True, preexec_fn=default_sigint,
                            **popen)


def noise(n: int, channels: int = 1, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).standard_normal((channels, n))


# ----------------------------------------------------------------------------- files
def test_parquet_signal_with_flipped_bytes_is_refused_naming_the_file(tmp_path, capsys):
    import pyarrow.parquet as pq

    path = write_signal(tmp_path / "rec.parquet", noise(24_000), FS,
                        meta={"bearing": "6205", "rpm": 1797})
    chunk = pq.read_metadata(path).row_group(0).column(1)          # the channel's pages
    assert chunk.path_in_schema == "accel"
    data = bytearray(path.read_bytes())
    start = chunk.dictionary_page_offset or chunk.data_page_offset
    mid = start + chunk.total_compressed_size // 2
    assert mid + 64 < start + chunk.total_compressed_size
    data[mid:mid + 64] = bytes(b ^ 0xFF for b in data[mid:mid + 64])
    path.write_bytes(bytes(data))
    # without the page CRCs these bytes decode as garbage values (up to 1e181 or so)
    with pytest.raises(ValueError, match=r"rec.parquet: not a readable .parquet signal "
                                         r"file \(.*CRC"):
        read_signal(path)
    for command in ("features", "plot"):
        extra = ["--out", tmp_path / "fig.png"] if command == "plot" else []
        assert main([command, str(path), *map(str, extra)]) == 2
        err = capsys.readouterr().err
        assert "rec.parquet" in err and "CRC" in err and err.count("\n") == 1
    assert not (tmp_path / "fig.png").exists()


@pytest.mark.parametrize("n, says", [
    (5, r"5 samples, too short to analyse: .* at least 64 samples \(0.00533 s at 12000 Hz\)"),
    (63, "63 samples, too short"),
    (12_000, r"1 NaN or inf sample\(s\), the first at sample 100 \(0.00833333 s\)"),
])
def test_short_or_nan_signal_refused_by_features_and_plot_naming_the_file(
        tmp_path, capsys, n, says):
    x = noise(n)
    if n == 12_000:
        x[0, 100] = np.nan
    path = write_signal(tmp_path / "bad.npz", x, FS, meta={"bearing": "6205", "rpm": 1797})
    for argv in (["features", path], ["plot", path, "--out", tmp_path / "figs"],
                 ["diagnose", path]):
        assert main([str(a) for a in argv]) == 2
        err = capsys.readouterr().err
        assert f"{path}: " in err and err.count("\n") == 1, err
        assert __import__("re").search(says, err), err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.npz"]


def test_signal_of_the_minimum_length_is_analysed(tmp_path, capsys):
    path = write_signal(tmp_path / "ok.npz", noise(64), FS)
    assert main(["features", str(path)]) == 0
    assert capsys.readouterr().out.count("\n") == 2           # header and one row


# ----------------------------------------------------------------------------- signals
def test_keyboard_interrupt_in_any_command_is_one_line_and_exit_130(monkeypatch, capsys):
    commands = sys.modules["ballpass.commands.simulate"]

    def interrupted(args):
        exc = KeyboardInterrupt()
        exc.add_note("3 of 8 shards written, rerun to resume")
        raise exc

    monkeypatch.setattr(commands, "run", interrupted)
    assert main(["simulate", "--out", "x.npz"]) == EXIT_INTERRUPTED == 130
    assert capsys.readouterr().err == ("ballpass simulate: interrupted; 3 of 8 shards "
                                       "written, rerun to resume\n")




def test_an_interrupt_a_library_turns_into_another_error_is_still_an_interrupt(
        monkeypatch, capsys):
    """Ctrl-C landing in numpy's comparison of structured arrays (the kurtogram's
    np.unique(axis=0)) comes out as "TypeError: Cannot compare structured arrays":
    `features` ended with exit 2 and that error (the adversarial sweep's interrupt cases,
    1 of 6 timings, on main too). The handler remembers the stop: exit 130, one line."""
    import signal

    from ballpass.commands import features as commands

    def swallowed(args):
        try:
            signal.raise_signal(signal.SIGINT)   # Ctrl-C, through the installed handler
        except KeyboardInterrupt:
            raise TypeError("Cannot compare structured arrays unless they have a common "
                            "dtype.") from None

    monkeypatch.setattr(commands, "run", swallowed)
    # Python's own Ctrl-C handler, as in a terminal: a shell without job control starts
    # a background job (`pytest &`) with SIGINT ignored, which main leaves alone
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        assert main(["features", "x.npz"]) == EXIT_INTERRUPTED
        assert capsys.readouterr().err == "ballpass features: interrupted\n"
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # restored
    finally:
        signal.signal(signal.SIGINT, inherited)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.parametrize("how", ["ctrl-c", "sigterm"])
def test_interrupted_generate_stops_its_workers_and_says_how_far_it_got(tmp_path, how):
    grid = tmp_path / "g.toml"
    grid.write_text("[dataset]\nduration_s = 0.2\nfs = 12000\nrepeats = 100\nshard_size = 1\n"
                    'model = "impulse"\n[grid]\nbearing = ["6205"]\nfault = ["outer", '
                    '"inner"]\nrpm = [1797]\nresonance_hz = [3000]\n')
    out = tmp_path / "ds"
    proc = ballpass("generate", grid, "--out", out, "--jobs", "2", "--no-progress",
                    stdout=subprocess.PIPE, start_new_session=True)
    deadline = time.monotonic() + 120
    while not (len(children(proc.pid)) >= 2 and list(out.glob("part-*.parquet"))):
        assert proc.poll() is None, proc.stderr.read()
        assert time.monotonic() < deadline
        time.sleep(0.01)
    workers = children(proc.pid)
    if how == "ctrl-c":              # the terminal sends SIGINT to the whole group
        os.killpg(proc.pid, signal.SIGINT)
    else:                            # `kill PID` reaches the parent only
        os.kill(proc.pid, signal.SIGTERM)
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == EXIT_INTERRUPTED, stderr
    import re

    said = re.fullmatch(r"ballpass generate: interrupted; (\d+) of 200 shards written, "
                        r"rerun to resume\n", stderr)
    assert said, stderr
    assert stdout == ""
    time.sleep(0.5)
    # the workers were stopped, not left to finish the queue, and the count said is what
    # is in place (kept on resume), also the shards a worker finished before the parent
    # heard of them: with the impulse model's 0.2 s rows a worker finishes several
    assert len(list(out.glob("part-*.parquet"))) == int(said[1]) < 200
    assert not [w for w in workers if Path(f"/proc/{w}").exists()
                and Path(f"/proc/{w}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"]
    assert not [p for p in out.iterdir() if p.name.endswith(".tmp")]   # no half shard
    info = subprocess.run([sys.executable, "-m", "ballpass", "info", str(out)], cwd=ROOT,
                          capture_output=True, text=True)
    assert "interrupted)" in info.stdout.splitlines()[0]


# ----------------------------------------------------------------------------- pipes
def test_output_cut_short_by_its_reader_ends_quietly(tmp_path):
    path = write_signal(tmp_path / "two.npz", noise(4096, channels=2), FS,
                        meta={"bearing": "6205", "rpm": 1797})
    for argv in (["features", path], ["bearings"]):
        proc = ballpass(*argv, stdout=subprocess.PIPE)
        proc.stdout.close()                     # like `| head -0`: the reader is gone
        stderr = proc.stderr.read()
        assert proc.wait(timeout=60) == EXIT_BROKEN_PIPE, stderr
        assert stderr == ""                     # no "Broken pipe", no traceback


# ----------------------------------------------------------------------------- messages
@pytest.mark.parametrize("command", ["features", "plot", "diagnose"])
def test_bad_rpm_is_named_as_the_user_typed_it(tmp_path, capsys, command):
    path = write_signal(tmp_path / "s.npz", noise(4096), FS, meta={"bearing": "6205"})
    extra = ["--out", str(tmp_path / "p.png")] if command == "plot" else []
    assert main([command, str(path), "--rpm", "-1", *extra]) == 2
    err = capsys.readouterr().err
    assert "--rpm must be a finite speed > 0 rev/min, got -1" in err and "shaft_hz" not in err


def test_rpm_stored_in_a_file_is_named_with_the_file(tmp_path, capsys):
    path = write_signal(tmp_path / "s.npz", noise(4096), FS, meta={"rpm": -5.0})
    assert main(["features", str(path)]) == 2
    assert f"{path}: its rpm, -5.0, is not a speed > 0" in capsys.readouterr().err


def test_binary_grid_file_is_not_a_toml_text_file(tmp_path, capsys):
    grid = tmp_path / "grid.toml"
    grid.write_bytes(bytes(range(200, 256)) * 4)
    assert main(["generate", str(grid), "--out", str(tmp_path / "ds")]) == 2
    err = capsys.readouterr().err
    assert f"{grid}: not a TOML text file (byte 0xc8 at position 0 is not UTF-8)" in err
    assert "codec" not in err


def test_full_disk_names_the_file(tmp_path, capsys, monkeypatch):
    import errno

    import pandas as pd

    def full(self, *args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))   # as write(2) says it

    monkeypatch.setattr(pd.DataFrame, "to_csv", full)
    path = write_signal(tmp_path / "s.npz", noise(4096), FS)
    out = tmp_path / "table.csv"
    assert main(["features", str(path), "--out", str(out)]) == 2
    assert capsys.readouterr().err == (f"ballpass features: error: {out}: No space left on "
                                       "device\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.npz"]   # nothing half-written


def test_benchmark_split_that_cannot_be_formed_is_one_line(tmp_path, capsys):
    from ballpass.datasets import generate

    grid = {"dataset": {"duration_s": 0.25, "fs": 12000, "seed": 3, "repeats": 4,
                        "model": "impulse"},
            "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"],
                     "rpm": [1797], "resonance_hz": [3000]}}
    generate(grid, tmp_path / "ds", progress=False)
    out = tmp_path / "report"
    assert main(["benchmark", str(tmp_path / "ds"), "--splits", "speed", "--out", str(out),
                 "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "no split could be formed" in err and "speed: the dataset has a single value" in err
    assert not out.exists()


@pytest.mark.parametrize("option, value, field", [
    ("--width", "-1", "width_mm"), ("--depth", "0", "depth_mm"), ("--load", "-5", "radial_load_n"),
    ("--duration", "inf", "duration_s"), ("--resonance", "0", "resonance_hz"),
    ("--damping", "2", "resonance_damping"), ("--fs", "nan", "fs"), ("--rpm", "0", "rpm"),
    ("--seed", "-1", "seed"),
])
def test_scene_options_are_named_as_typed(tmp_path, capsys, option, value, field):
    # found by benchmarks/abuse_sweep.py: "width_mm must be ..." for --width -1
    assert main(["simulate", option, value, "--out", str(tmp_path / "x.npz")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"ballpass simulate: error: {option}: {field} ") and err.count("\n") == 1


@pytest.mark.parametrize("argv, says", [
    (["work-precision", "--repeats", "1000000000"], "--repeats must be an int from 1 to 100"),
    (["bifurcation", "--parameter", "rpm", "--values", *map(str, range(500, 10_502)),
      "--out", "b.csv"], "--values takes at most 10,000 values"),
])
def test_counts_that_would_run_for_ever_are_refused(tmp_path, capsys, monkeypatch, argv, says):
    # found by benchmarks/abuse_sweep.py: both ran for hours (one run per repeat or value)
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    assert says in capsys.readouterr().err
