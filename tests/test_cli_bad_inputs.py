"""Every subcommand on bad inputs: one error line, a non-zero exit, no traceback, no file.

Issue 16: output paths are checked before any work (so a bad one writes nothing and
costs no simulation), and raw library messages (scipy, numpy, numba) are turned into
errors that name the argument.
"""

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.io

import ballpass as bp
from ballpass.cli import main
from ballpass.signalio import write_signal

DATA = Path(__file__).parent / "data"


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    """A 3-row simulated dataset (healthy, outer, inner) for the benchmark cases."""
    grid = {"dataset": {"duration_s": 0.05, "fs": 12_000, "repeats": 1, "seed": 3},
            "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"],
                     "fault_width_mm": [0.5], "rpm": [1797], "radial_load_n": [500],
                     "resonance_hz": [3000], "sensor": ["loaded"]}}
    out = tmp_path_factory.mktemp("bad") / "ds"
    bp.datasets.generate(grid, out, n_jobs=1, progress=False)
    return out


@pytest.fixture()
def workdir(tmp_path, monkeypatch, dataset):
    """A folder with a good signal, bad files and a file in the way of folders."""
    write_signal(tmp_path / "sig.npz", np.sin(np.arange(4800) / 3.0), 12_000.0,
                 meta={"rpm": 1797.0, "bearing": "6205"})
    (tmp_path / "text.npz").write_text("this is not an archive\n")
    np.savez(tmp_path / "complex.npz", accel=np.ones((1, 100)) * (1 + 1j), fs=1000.0)
    good = (DATA / "cwru_mat" / "12k_DE_IR007_0.mat").read_bytes()
    (tmp_path / "truncated.mat").write_bytes(good[: len(good) // 2])
    scipy.io.savemat(tmp_path / "other.mat", {"signal": np.zeros(100), "fs": 1000.0})
    (tmp_path / "afile").write_text("in the way")
    (tmp_path / "empty").mkdir()
    (tmp_path / "sigs").mkdir()
    shutil.copy(tmp_path / "sig.npz", tmp_path / "sigs")
    (tmp_path / "a.npz").mkdir()  # a folder named like a file
    (tmp_path / "broken").mkdir()
    shutil.copy(tmp_path / "truncated.mat", tmp_path / "broken")
    (tmp_path / "ds").symlink_to(dataset)
    # a machine's healthy recording (2 s of noise) and its manifest, for `twin`
    np.save(tmp_path / "healthy.npy", np.random.default_rng(0).standard_normal(24_000))
    (tmp_path / "healthy.csv").write_text("path,fs,rpm,bearing\nhealthy.npy,12000,900,6205\n")
    monkeypatch.chdir(tmp_path)
    return tmp_path


SIM = ["simulate", "--duration", "0.01"]
CASES = [
    # simulate: output paths (checked before the simulation), then the scene
    (SIM + ["--out", "afile/x.npz"], "afile is a file"),
    (SIM + ["--out", "/proc/ballpass-test/x.npz"], "cannot write"),
    (SIM + ["--out", "x.txt"], "--out must end in .npz, .csv or .parquet"),
    (SIM + ["--out", "a.npz"], "is a folder"),
    (SIM + ["--out", "x.npz", "--plot", "afile/p.png"], "--plot afile/p.png"),
    (SIM + ["--out", "x.npz", "--plot", "p.gif"], "--plot must end in"),
    (SIM + ["--out", "x.npz", "--resonance", "1e-3"], "resonance_hz"),
    (SIM + ["--out", "x.npz", "--duration", "0"], "duration_s"),
    (SIM + ["--out", "x.npz", "--bearing", "nope"], "--bearing: unknown bearing 'nope'"),
    (SIM + ["--out", "x.npz", "--model", "nope"], "--model: model must be 'auto' or one of"),
    (SIM + ["--out", "x.npz", "--solver", "rk9"], "--solver: solver must be 'auto' or one"),
    (SIM + ["--out", "x.npz", "--width", "-1"], "width_mm"),
    (["simulate", "--fault", "healthy", "--width", "5", "--out", "x.npz"],
     "--width describes a fault; a healthy bearing has none"),
    (SIM + ["--out", "x.npz", "--rpm", "1", "2", "3"], "--rpm takes"),
    # features: unreadable inputs, bad outputs, nonsense options
    (["features", "text.npz"], "not a NumPy .npz archive"),
    (["features", "complex.npz"], "complex"),
    (["features", "truncated.mat"], "not a readable MATLAB"),
    (["features", "missing.npz"], "no such"),
    (["features", "empty"], "neither a dataset nor a folder of recordings"),
    (["features", "sigs"], "give its signal files as inputs (sigs/*.npz)"),
    (["features", "broken"], "none of its .mat files could be read"),
    (["features", "other.mat"], "other.mat is neither a CWRU recording"),
    (["features", "sig.npz", "--out", "afile/f.csv"], "afile is a file"),
    (["features", "sig.npz", "--out", "f.xlsx"], ".csv or .parquet"),
    (["features", "sig.npz", "--plot", "afile"], "is a file, not a folder"),
    (["features", "sig.npz", "--segment", "1e-9"], "--segment must give at least 64"),
    (["features", "sig.npz", "--band", "1000", "1000.000001"], "band must be at least"),
    # plot
    (["plot", "sig.npz", "--out", "afile/fig.png"], "afile is a file"),
    (["plot", "sig.npz", "--out", "afile"], "is a file, not a folder"),
    (["plot", "text.npz", "--out", "figs"], "not a NumPy .npz archive"),
    (["plot", "sig.npz", "--max-figures", "0"], "--max-figures"),
    (["plot", "sig.npz", "--out", "fig.npz"], "--out must be a folder, got 'fig.npz'"),
    (["features", "sig.npz", "--plot", "fig.png"], "--plot must be a folder, got 'fig.png'"),
    (["benchmark", "ds", "--out", "report.md"], "--out must be a folder, got 'report.md'"),
    # benchmark
    (["benchmark", "ds", "--out", "afile/rep"], "afile is a file"),
    (["benchmark", "ds", "--out", "rep", "--folds", "1"], "n_splits (--folds) must be"),
    (["benchmark", "ds", "--out", "rep", "--real", "missing"], "no such file or folder"),
    (["benchmark", "ds", "--out", "rep", "--real", "broken"],
     "broken: none of its .mat files could be read"),
    (["benchmark", "ds", "--out", "rep", "--models", "nope"], "models must be"),
    (["benchmark", "nowhere", "--out", "rep"], "nowhere"),
    # work-precision: outputs first (the sweep takes seconds to minutes)
    (["work-precision", "--no-scipy", "--csv", "afile/t.csv"], "afile is a file"),
    (["work-precision", "--no-scipy", "--plot", "afile/p.png"], "afile is a file"),
    (["work-precision", "--no-scipy", "--csv", "t.txt"], "--csv must end in .csv"),
    (["work-precision", "--no-scipy", "--csv", "same.csv", "--plot", "same.csv"],
     "--plot must end in"),
    (["work-precision", "--no-scipy", "--repeats", "0"], "--repeats"),
    (["work-precision", "--scipy", "RK45", "rk45"], "--scipy takes RK45, DOP853"),
    (["work-precision", "--scipy-time-limit", "0"], "--scipy-time-limit must be > 0"),
    (["work-precision", "--no-scipy", "--snr", "10"], "--snr 10: work-precision compares"),
    # bifurcation: outputs and the swept parameter before any simulation
    (["bifurcation", "--parameter", "rpm", "--values", "1000", "--out", "afile/b.csv"],
     "afile is a file"),
    (["bifurcation", "--parameter", "rpm", "--values", "1000", "--out", "b.txt"],
     "--out must end in .csv"),
    (["bifurcation", "--parameter", "rpm", "--values", "1000", "--out", "b.csv", "--plot",
      "afile/p.png"], "afile is a file"),
    (["bifurcation", "--parameter", "nope", "--values", "1", "--out", "b.csv"],
     "parameter must be one of"),
    (["bifurcation", "--parameter", "rpm", "--values", "-5", "--out", "b.csv"],
     "rpm must be a finite number"),
    # the others
    (["bearings", "--bearing", "nope"], "nope"),
    (["models", "--needs", "gear_mesh", "rotor_dynamics"], "no model represents"),
    (["models", "--needs", "envelope", "--bearing", "nope"], "unknown bearing 'nope'"),
    (["models", "--bearing", "6203"], "give --needs too"),
    (["simulate", "--needs", "gear_mesh", "--out", "x.npz"], "has no gear pair"),
    (["info", "nowhere"], "nowhere"),
    (["generate", "missing.toml", "--out", "new"], "GRID missing.toml: no such file"),
    (["generate", "nowhere/grid", "--out", "new"], "GRID nowhere/grid: no such file"),
    # found walking the README as a new user: the refusal named an argument of the
    # library (rpm, draws, duration_s, seed, manifest) or none, not the one typed
    (["twin", "healthy.csv", "--rpm", "-5", "--out", "t.toml"],
     "--rpm: rpm must be shaft speeds > 0"),
    (["twin", "healthy.csv", "--rpm", "900", "--draws", "0", "--out", "t.toml"],
     "--draws: draws must be an int >= 1"),
    (["twin", "healthy.csv", "--rpm", "900", "--duration", "10", "--out", "t.toml"],
     "--duration: duration_s = 10 s is longer than the shortest recording (2 s)"),
    (["twin", "healthy.csv", "--rpm", "900", "--seed", "-1", "--out", "t.toml"],
     "--seed: seed must be an int >= 0"),
    (["twin", "missing.csv", "--rpm", "900", "--out", "t.toml"],
     "MANIFEST: manifest: no such file"),
    (["twin", "healthy.csv", "--rpm", "900", "--out", "t.txt"], "--out must end in .toml"),
    (["twin", "healthy.npy", "--rpm", "900", "--out", "t.toml"],
     "MANIFEST healthy.npy is a recording, not a table of them: list the machine's"),
    (["twin", "other.mat", "--rpm", "900", "--out", "t.toml"],
     "(a row: other.mat,<fs Hz>,<rpm>,<bearing>)"),
    (["diagnose", "sig.npz", "--baseline", "missing.npz"],
     "--baseline: no such file or folder: missing.npz"),
    # the library's refusal of a value the command passed on named no option
    (["features", "sig.npz", "--band", "5000", "1000"], "--band: band must satisfy 0 <= lo"),
    (["plot", "sig.npz", "--band", "5000", "1000"], "--band: band must satisfy 0 <= lo"),
    (["diagnose", "sig.npz", "--line-hz", "-1"], "--line-hz: line_hz must be None or a"),
]


def _files(folder: Path) -> set:
    return {p.relative_to(folder) for p in folder.rglob("*") if "ds" not in p.parts}


@pytest.mark.parametrize(("argv", "message"), CASES, ids=[" ".join(c[0]) for c in CASES])
def test_bad_input_is_one_clear_line_and_writes_nothing(workdir, capsys, argv, message):
    before = _files(workdir)
    code = main(argv)
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if "error:" in line]
    assert code != 0
    assert len(errors) == 1 and errors[0].startswith(f"ballpass {argv[0]}: error: "), err
    assert message in errors[0], err
    assert "Traceback" not in err
    assert _files(workdir) == before


@pytest.mark.parametrize("argv", [["generate", "grid.toml", "--out", "ds", "--jobs", "0"],
                                  ["bifurcation", "--jobs", "x", "--out", "b.csv"]])
def test_jobs_is_refused_naming_the_option(capsys, argv):
    # the library's message named n_jobs, an argument nobody typed
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert "argument --jobs" in err and "-1 (every core)" in err and "n_jobs" not in err


@pytest.mark.parametrize(("argv", "says"), [
    (["models", "--needs"], "argument --needs: expected at least one argument"),
    (["features", "x.npz", "--channel", "XX"], "argument --channel: invalid choice: 'XX'"),
    (["simulate", "--rpm", "fast"], "argument --rpm"),
    (["generate"], "the following arguments are required: GRID"),
    (["nonsense"], "argument COMMAND: invalid choice: 'nonsense'"),
])
def test_a_usage_error_is_one_line_too(capsys, argv, says):
    """argparse printed its usage block before the error line: three to seven lines,
    where the README promises one (found walking the README as a new user)."""
    with pytest.raises(SystemExit) as exit_:
        main(argv)
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and says in err and "--help` lists the options" in err, err


def test_models_prints_nothing_before_refusing(capsys):
    """The table is not printed ahead of an error about the scene of --needs."""
    assert main(["models", "--needs", "envelope", "--bearing", "nope"]) == 2
    assert capsys.readouterr().out == ""


def test_no_traceback_from_the_installed_command(workdir):
    """The same through a real process: stderr is the one line, nothing else."""
    for argv in (["features", "text.npz"], ["simulate", "--out", "afile/x.npz"]):
        proc = subprocess.run([sys.executable, "-m", "ballpass", *argv], capture_output=True,
                              text=True, cwd=workdir, timeout=120)
        assert proc.returncode == 2
        assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr


def test_numba_cache_failure_names_numba_cache_dir(workdir, capsys, monkeypatch):
    """Read-only HOME and package folder: numba's "no locator available" becomes advice.
    (Raised by a stand-in: the tests run as a user for whom nothing is read-only.)"""
    def no_locator(*args, **kwargs):
        raise RuntimeError("cannot cache function 'rk4': no locator available for file "
                           "'/usr/lib/ballpass/simulate/_integrators.py'")

    monkeypatch.setattr(bp, "simulate", no_locator)
    assert main(["simulate", "--duration", "0.01", "--out", "x.npz"]) == 2
    err = capsys.readouterr().err
    assert "NUMBA_CACHE_DIR" in err and err.count("\n") <= 2  # the compile notice + error
    assert not (workdir / "x.npz").exists()


def test_a_bug_keeps_its_traceback(monkeypatch):
    """Only bad inputs become messages: an unexpected RuntimeError still propagates."""
    def bug(*args, **kwargs):
        raise RuntimeError("internal")

    monkeypatch.setattr(bp, "simulate", bug)
    with pytest.raises(RuntimeError, match="internal"):
        main(["simulate", "--duration", "0.01", "--out", "x.npz"])


OUTPUT_MESSAGES = ("afile is a file", "cannot write", "must end in", "is a folder",
                   "is a file, not a folder", "must be a folder")
OUTPUT_CASES = [c for c in CASES if any(m in c[1] for m in OUTPUT_MESSAGES)]


@pytest.mark.parametrize(("argv", "message"), OUTPUT_CASES,
                         ids=[" ".join(c[0]) for c in OUTPUT_CASES])
def test_output_paths_are_checked_before_any_work(workdir, capsys, monkeypatch, argv,
                                                  message):
    """The work itself (simulating, reading the inputs, loading the dataset) is replaced
    by a tripwire: a bad output path must be refused before it is reached."""
    import importlib

    import ballpass.commands.features as features_cmd
    import ballpass.datasets

    wp = importlib.import_module("ballpass.simulate.work_precision")

    def tripwire(*args, **kwargs):
        raise AssertionError("work started before the output path was checked")

    monkeypatch.setattr(bp, "simulate", tripwire)
    monkeypatch.setattr(wp, "work_precision", tripwire)
    monkeypatch.setattr(features_cmd, "load_inputs", tripwire)
    monkeypatch.setattr(ballpass.datasets, "load", tripwire)
    assert main(argv) == 2
    assert message in capsys.readouterr().err
