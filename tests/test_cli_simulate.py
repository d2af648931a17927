"""``ballpass simulate`` end to end: file formats, metadata, plot."""

import numpy as np
import pytest

import ballpass as bp
from ballpass.cli import main
from ballpass.signalio import read_signal

ARGS = ["simulate", "--fault", "inner", "--rpm", "1500", "--duration", "0.2", "--fs", "12000",
        "--resonance", "3000", "--seed", "4"]


@pytest.mark.parametrize("suffix", [".npz", ".csv", ".parquet"])
def test_simulate_writes_the_same_signal_as_the_api(tmp_path, suffix, capsys):
    out = tmp_path / f"sig{suffix}"
    assert main([*ARGS, "--out", str(out)]) == 0
    assert "inner" in capsys.readouterr().out
    sig = read_signal(out)
    expected = bp.simulate(bp.Scene(bearing="6205", rpm=1500.0, fault=bp.Fault("inner"),
                                    duration_s=0.2, fs=12_000.0, resonance_hz=3000.0, seed=4))
    assert sig.fs == 12_000.0
    # .npz and .parquet keep float64 exactly; .csv is text with 9 significant digits
    # (relative rounding 5e-9 of each value)
    rtol = 1e-8 if suffix == ".csv" else 0.0
    np.testing.assert_allclose(sig.accel[0], expected.accel, rtol=rtol, atol=0.0)


def test_simulate_plot_and_two_sensors(tmp_path):
    out, png = tmp_path / "s.npz", tmp_path / "s.png"
    assert main([*ARGS, "--sensors", "loaded", "unloaded", "--out", str(out),
                 "--plot", str(png)]) == 0
    sig = read_signal(out)
    assert sig.accel.shape == (2, 2400) and list(sig.channels) == ["loaded", "unloaded"]
    assert sig.meta["label"] == "inner"
    assert sig.meta["frequencies_hz"]["bpfi"] == pytest.approx(5.4152 * 25.0, rel=1e-4)
    assert png.stat().st_size > 10_000  # a real figure, not an empty canvas


def test_simulate_refuses_bad_input_with_the_argument_named(tmp_path, capsys):
    code = main(["simulate", "--fs", "12000", "--out", str(tmp_path / "x.npz")])
    assert code == 2
    assert "resonance_hz=15000 lies above 0.45*fs" in capsys.readouterr().err
    assert not (tmp_path / "x.npz").exists()


def test_written_files_follow_the_umask_like_any_other(tmp_path):
    import os

    old = os.umask(0o022)
    try:
        out = tmp_path / "s.npz"
        assert main([*ARGS, "--out", str(out)]) == 0
    finally:
        os.umask(old)
    # the atomic write's temporary file must not leave the result private (0600)
    assert out.stat().st_mode & 0o777 == 0o644
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]


def test_needs_picks_the_model_and_the_signal_matches_the_api(tmp_path, capsys):
    out = tmp_path / "env.npz"
    assert main([*ARGS, "--needs", "envelope", "--out", str(out)]) == 0
    assert "model impulse" in capsys.readouterr().out  # envelope alone: the cheapest model
    sig = read_signal(out)
    expected = bp.simulate(bp.Scene(bearing="6205", rpm=1500.0, fault=bp.Fault("inner"),
                                    duration_s=0.2, fs=12_000.0, resonance_hz=3000.0, seed=4,
                                    needs=("envelope",)))
    assert sig.meta["info"]["model"] == expected.info["model"] == "impulse"
    np.testing.assert_array_equal(sig.accel[0], expected.accel)  # npz keeps float64


def test_models_lists_the_registry_and_what_auto_picks(capsys):
    assert main(["models"]) == 0
    out = capsys.readouterr().out
    names = [line.split()[0] for line in out.splitlines()[2:] if line.strip()]
    assert names == list(bp.simulate.MODELS)  # cheapest first, every model once
    assert main(["models", "--needs", "ball_dynamics"]) == 0
    assert "model='auto' runs multibody" in capsys.readouterr().out
    # csv stays machine-readable: the answer to --needs goes to stderr
    assert main(["models", "--format", "csv", "--needs", "envelope"]) == 0
    captured = capsys.readouterr()
    assert captured.out.splitlines()[0] == "model,relative_cost,solvers,represents,reference"
    assert "runs impulse" in captured.err
