"""Nonsense refused with a message naming the argument (issue 16, items 5 and 6), the
documented behaviour where refusing would be wrong, and the CLI's progress and notices."""

import logging
import sys
import warnings

import numpy as np
import pytest

import ballpass as bp
from ballpass import features as F
from ballpass.cli import main
from ballpass.commands import _output
from ballpass.datasets import read_grid


def test_bearing_arguments_are_type_checked():
    base = dict(name="x", n_elements=9, element_diameter_mm=7.94, pitch_diameter_mm=39.04)
    for key, value in (("contact_angle_deg", "10"), ("inner_conformity", None),
                       ("poisson_ratio", "0.3"), ("radial_clearance_mm", [0.01])):
        with pytest.raises(TypeError, match=f"^{key} must be a number, got"):
            bp.Bearing(**base | {key: value})
    # a NumPy integer is an int like any other
    assert bp.Bearing(**base | {"n_elements": np.int64(9)}).n_elements == 9


def test_spectral_kurtosis_on_a_too_short_signal_names_nperseg():
    """scipy said "Parameter n must be >= ceil(m_num/2) = 2048!"."""
    with pytest.raises(ValueError, match=r"at least two full segments of nperseg = 4096 "
                                         r"samples .* got 100 samples"):
        F.spectral_kurtosis(np.ones(100), 1000.0, nperseg=4096)


def test_a_band_must_be_wide_enough_to_filter():
    x = np.random.default_rng(0).standard_normal(4800)
    with pytest.raises(ValueError, match=r"band must be at least fs/1000 = 12 Hz wide"):
        F.envelope_spectrum(x, 12_000.0, band=(3000.0, 3000.000000001))
    F.envelope_spectrum(x, 12_000.0, band=(3000.0, 3012.0))  # the narrowest accepted


def test_scene_refuses_a_resonance_below_100_hz_and_an_unloaded_bearing():
    with pytest.raises(ValueError, match=r"^resonance_hz must be a finite number in \[100"):
        bp.Scene("6205", resonance_hz=1e-3)
    bp.Scene("6205", resonance_hz=100.0, fs=12_000.0)
    with pytest.raises(ValueError, match="radial_load_n=0 with gravity=False"):
        bp.Scene("6205", radial_load_n=0.0, gravity=False)
    bp.Scene("6205", radial_load_n=0.0)  # gravity alone loads it


def test_grid_segments_need_64_samples():
    grid = {"dataset": {"duration_s": 1.0, "fs": 12_000, "segment_s": 1e-9},
            "grid": {"fault": ["healthy"], "resonance_hz": [3000]}}
    with pytest.raises(ValueError, match=r"^dataset\.segment_s must give at least 64"):
        read_grid(grid)


def test_indicators_of_a_silent_signal_are_finite_and_documented():
    """No NaN, no warning: kurtosis 0 (unreachable by a varying signal, kurtosis >= 1)
    marks the dead channel; factors 1, the value of any non-zero constant."""
    x = np.zeros((3, 500))
    x[1] = np.random.default_rng(1).standard_normal(500)
    x[2] = 2.5
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ind = F.indicators(x)
    assert all(np.isfinite(v).all() for v in ind.values())
    assert ind["kurtosis"][0] == ind["kurtosis"][2] == 0.0 and ind["kurtosis"][1] > 2.5
    assert ind["crest_factor"][0] == ind["crest_factor"][2] == 1.0
    assert ind["rms"][2] == 2.5 and ind["skewness"][0] == 0.0
    noise = x[1]
    with pytest.raises(ValueError, match="healthy has rms, peak, peak_to_peak, kurtosis"):
        F.indicator_ratios(noise, np.zeros(500))


# ---------------------------------------------------------------- CLI behaviour
def test_simulate_writes_signal_and_figure_or_neither(tmp_path, monkeypatch, capsys):
    """A figure that fails to save leaves no .npz behind (it used to: rc 1, file kept)."""
    def broken(fig, path, dpi=120):
        def write(tmp):
            raise OSError(28, "No space left on device")
        return write

    monkeypatch.setattr(_output, "figure_writer", broken)
    argv = ["simulate", "--duration", "0.01", "--fs", "12000", "--resonance", "3000",
            "--out", str(tmp_path / "s.npz"), "--plot", str(tmp_path / "s.png")]
    assert main(argv) == 2
    assert "No space left on device" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []
    monkeypatch.undo()
    assert main(argv) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.npz", "s.png"]


def test_compile_notice_only_without_a_current_cache(tmp_path, monkeypatch, capsys):
    argv = ["simulate", "--duration", "0.01", "--out", str(tmp_path / "s.npz")]
    assert main(argv) == 0
    capsys.readouterr()
    assert _output.kernels_cached()  # the run above compiled (or loaded) and cached them
    assert main(argv) == 0
    assert "compiling" not in capsys.readouterr().err
    monkeypatch.setattr(_output, "kernels_cached", lambda: False)
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("ballpass: compiling the simulator")


def test_an_empty_numba_cache_dir_is_announced(tmp_path, monkeypatch):
    """With NUMBA_CACHE_DIR set numba keeps kernels there only; kernels in the package's
    __pycache__ (there after any run of the tests) made the command say nothing while a
    fresh NUMBA_CACHE_DIR compiled for 25 s (generate quick --jobs 2, 2-core machine)."""
    assert main(["simulate", "--duration", "0.01", "--out", str(tmp_path / "s.npz")]) == 0
    assert _output.kernels_cached()   # in __pycache__ (or the cache dir the run uses)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "empty-cache"))
    assert not _output.kernels_cached()


def test_compile_notice_is_one_line_not_two(tmp_path, monkeypatch, capsys, caplog):
    """A fresh install: the command's notice and the library's logger said the same
    thing twice (found running the README's first command in a new virtualenv)."""
    sim = bp.simulate  # the callable subpackage
    monkeypatch.setattr(_output, "kernels_cached", lambda: False)
    monkeypatch.setattr(sim, "has_compiled_kernels", lambda: False)
    monkeypatch.setattr(sim, "_compile_checked", False)  # a new process
    with caplog.at_level(logging.WARNING, logger="ballpass"):
        assert main(["simulate", "--duration", "0.01", "--out", str(tmp_path / "s.npz")]) == 0
    said = capsys.readouterr().err + "".join(r.getMessage() for r in caplog.records)
    assert said.count("compiling") == 1, said


def test_progress_bars_on_a_terminal_unless_quiet(monkeypatch, capsys):
    class Args:
        quiet = False

    monkeypatch.setattr(sys.stderr, "isatty", lambda: False, raising=False)
    assert not _output.show_progress(Args())
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    assert _output.show_progress(Args())
    Args.quiet = True
    assert not _output.show_progress(Args())
    from ballpass.commands.features import Signal, feature_rows

    x = np.random.default_rng(0).standard_normal(2400)
    feature_rows([Signal("a", x, 12_000.0), Signal("b", x, 12_000.0)], progress=True)
    assert "features" in capsys.readouterr().err


def test_generate_says_it_compiles_before_the_first_dataset(tmp_path, monkeypatch, capsys):
    grid = tmp_path / "g.toml"
    grid.write_text('[dataset]\nduration_s = 0.01\nfs = 12000\n[grid]\nbearing = ["6205"]\n'
                    'fault = ["outer"]\nrpm = [1797]\nresonance_hz = [3000]\n')
    monkeypatch.setattr(_output, "kernels_cached", lambda: False)
    assert main(["generate", str(grid), "--out", str(tmp_path / "ds"), "--no-progress"]) == 0
    assert capsys.readouterr().err.startswith("ballpass: compiling the simulator")


# found by benchmarks/abuse_sweep.py: each was accepted, or refused in a library's words
@pytest.mark.parametrize("call, error, says", [
    # options of another separation method were ignored, whatever their value
    (lambda x: F.separate_discrete(x, 12_000.0, 1797, order="abc"), TypeError,
     "order must be an int"),
    (lambda x: F.separate_discrete(x, 12_000.0, 1797, nperseg=-1), ValueError,
     "nperseg must be an int >= 16"),
    (lambda x: F.separate_discrete(x, 12_000.0, 1797, delay=2.5), TypeError,
     "delay must be an int"),
    # "could not convert string to float: 'abc'", "must be real number, not str"
    (lambda x: F.fault_band_features(x, 12_000.0, "6205", "abc"), TypeError,
     "rpm must be a number"),
    (lambda x: F.separate_discrete(x, 12_000.0, "abc"), TypeError, "rpm must be a number"),
    (lambda x: F.fast_kurtogram(x, 12_000.0, floor_db="abc"), TypeError,
     "floor_db must be a number of dB"),
    # truthy values taken for True
    (lambda x: F.envelope(x, 12_000.0, prewhiten="no"), TypeError,
     "prewhiten must be True or False, got 'no'"),
    (lambda x: F.envelope_spectrum(x, 12_000.0, squared=2), TypeError,
     "squared must be True or False, got 2"),
    (lambda x: F.fault_band_features(x, 12_000.0, "6205", 1797, shaft_guard="no"),
     TypeError, "shaft_guard must be True or False"),
])
def test_bad_options_are_named(call, error, says):
    x = np.random.default_rng(0).standard_normal(6000)
    with pytest.raises(error, match=says):
        call(x)
