"""Figures: markers, labels and the overview figure (Agg, no pixel comparison)."""

import matplotlib
import numpy as np
import pytest

import ballpass as bp
from ballpass import plot

matplotlib.use("Agg")


def test_envelope_spectrum_markers_and_harmonics():
    f = np.arange(2001) * 0.5
    freqs = bp.Bearing.catalog("6205").frequencies(1797 / 60)
    ax = plot.envelope_spectrum(f, np.exp(-f / 100), frequencies=freqs, harmonics=3)
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend == [
        "shaft 29.9 Hz",
        "FTF 11.9 Hz",
        "BPFO 107.4 Hz",
        "BPFI 162.2 Hz",
        "2×BSF 141.2 Hz",
    ]
    marker_x = sorted(round(line.get_xdata()[0], 1) for line in ax.lines[1:])
    assert round(3 * freqs.bpfi, 1) in marker_x  # third harmonic of the highest line drawn
    assert ax.get_xlim()[1] == pytest.approx(1.1 * 3 * freqs.bpfi)
    with pytest.raises(ValueError, match="^lines"):
        plot.envelope_spectrum(f, f, frequencies=freqs, lines=["nope"])
    with pytest.raises(ValueError, match="^amp"):
        plot.envelope_spectrum(f, f[:-1])


def test_waveform_channels_and_times():
    ax = plot.waveform(np.zeros((2, 100)), 100.0, channels=["a", "b"])
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["a", "b"]
    ax = plot.waveform(np.zeros(5), np.arange(5) * 0.1)
    assert ax.get_xlim() == (0.0, pytest.approx(0.4))
    with pytest.raises(ValueError, match="^fs_or_t"):
        plot.waveform(np.zeros(5), 0.0)


def test_signal_overview_two_channels(tmp_path):
    rng = np.random.default_rng(0)
    t = np.arange(12_000) / 12_000.0
    phase = (t * 107.4) % 1 / 107.4
    x = np.exp(-600 * phase) * np.sin(2 * np.pi * 3000 * phase)
    accel = np.stack([x, 0.3 * x]) + 0.05 * rng.standard_normal((2, t.size))
    fig = plot.signal_overview(
        accel,
        12_000.0,
        bearing=bp.Bearing.catalog("6205"),
        shaft_hz=29.95,
        path=tmp_path / "o.png",
        channels=["loaded", "unloaded"],
    )
    assert (tmp_path / "o.png").stat().st_size > 20_000
    ses_ax = fig.axes[1]
    assert "loaded" in [t.get_text() for t in ses_ax.get_legend().get_texts()]
    with pytest.raises(ValueError, match="bearing and shaft_hz"):
        plot.signal_overview(accel, 12_000.0, bearing="6205")
