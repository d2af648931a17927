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


def test_every_defect_line_in_view_is_marked():
    """4 x BPFO (430 Hz) lies inside the view of 3 harmonics of BPFI (535 Hz): it is
    marked, as are 3 x 2xBSF; shaft and cage keep ``harmonics`` markers."""
    f = np.arange(2001) * 0.5
    freqs = bp.Bearing.catalog("6205").frequencies(1797 / 60)
    ax = plot.envelope_spectrum(f, np.exp(-f / 100), frequencies=freqs, harmonics=3)
    marker_x = [line.get_xdata()[0] for line in ax.lines[1:]]
    fmax = ax.get_xlim()[1]
    for name in ("bpfo", "bpfi", "ball_defect"):
        f0 = getattr(freqs, name)
        expected = [h * f0 for h in range(1, int(fmax // f0) + 1)]
        assert all(np.isclose(marker_x, x).any() for x in expected), name
    assert sum(np.isclose(marker_x, h * freqs.shaft).any() for h in range(1, 18)) == 3


def test_overview_outlines_the_band_its_spectrum_used(tmp_path):
    """The SES panel and the kurtogram agree: a given band is outlined dashed on the
    kurtogram and named in both titles; without one the kurtogram's best band (above
    the fault lines, a bearing being known) is the SES's band."""
    rng = np.random.default_rng(0)
    t = np.arange(12_000) / 12_000.0
    phase = (t * 107.4) % 1 / 107.4
    x = np.exp(-600 * phase) * np.sin(2 * np.pi * 3000 * phase) + 0.05 * rng.standard_normal(t.size)
    given = plot.signal_overview(x, 12_000.0, bearing="6205", shaft_hz=29.95, band=(4000, 5500))
    ses_ax, k_ax = given.axes[1], given.axes[2]
    assert "4000–5500 Hz: given" in ses_ax.get_title(loc="left")
    assert "dashed: band used, 4000–5500 Hz" in k_ax.get_title()
    dashed = [p for p in k_ax.patches if p.get_linestyle() == "--"]
    assert len(dashed) == 1 and dashed[0].get_x() == 4000 and dashed[0].get_width() == 1500
    auto = plot.signal_overview(x, 12_000.0, bearing="6205", shaft_hz=29.95)
    ses_ax, k_ax = auto.axes[1], auto.axes[2]
    lo, hi = bp.features.envelope_analysis(x, 12_000.0, rpm=1797, bearing="6205").band
    rule = f"{lo:.0f}–{hi:.0f} Hz: the kurtogram's best above the fault lines"
    assert rule in ses_ax.get_title(loc="left")
    assert f"best band {lo:.0f}–{hi:.0f} Hz" in k_ax.get_title()
    assert "dashed" not in k_ax.get_title()
    assert any("grey: no content" in text.get_text() for text in k_ax.texts)


def test_spectrum_psd_and_spectrogram_read_what_the_signal_holds():
    fs = 12_000.0
    t = np.arange(12_000) / fs
    # amplitude spectrum: a 1.5 unit sine at 1 kHz (on a bin) reads 1.5 at 1 kHz
    f, a = plot.spectrum(1.5 * np.sin(2 * np.pi * 1000 * t), fs).lines[0].get_data()
    assert f[np.argmax(a)] == 1000.0 and a.max() == pytest.approx(1.5, rel=1e-9)
    # PSD: Parseval, the density of a sine of amplitude 2 plus unit white noise
    # integrates to A^2/2 + 1 = 3 (Welch's estimate: within 5 % over 12 000 samples)
    x = 2 * np.sin(2 * np.pi * 1000 * t) + np.random.default_rng(1).standard_normal(t.size)
    f, p = plot.psd(x, fs).lines[0].get_data()
    assert np.sum(p) * (f[1] - f[0]) == pytest.approx(3.0, rel=0.05)
    # spectrogram: the ridge of a linear chirp 500 -> 2500 Hz follows 500 + 2000 t
    ax = plot.spectrogram(np.sin(2 * np.pi * (500 * t + 1000 * t**2)), fs, colorbar=False)
    mesh = ax.collections[0]
    power_db = np.asarray(mesh.get_array())  # (n_freqs, n_times)
    corners = mesh.get_coordinates()  # cell edges: times along axis 1, freqs along axis 0
    times = 0.5 * (corners[0, 1:, 0] + corners[0, :-1, 0])
    freqs = 0.5 * (corners[1:, 0, 1] + corners[:-1, 0, 1])
    ridge = freqs[np.argmax(power_db, axis=0)]
    # one bin (fs / 256 = 47 Hz) plus the chirp's sweep over a segment (2000 Hz/s x 21 ms)
    assert np.all(np.abs(ridge - (500 + 2000 * times)) < 47 + 43)
    with pytest.raises(ValueError, match="^x must be one finite signal"):
        plot.spectrum(np.ones(5), fs)
    with pytest.raises(ValueError, match="^nperseg"):
        plot.psd(x, fs, nperseg=10**9)
