"""envelope_analysis: the one-call SES agrees with the Butterworth SES, band and indicators
are those of the separate functions, and BPFO stands out where the closed form puts it."""

from pathlib import Path

import matplotlib
import numpy as np
import pytest
import scipy.fft
import scipy.signal

import ballpass as bp
from ballpass import features as F
from ballpass.features.analysis import _ses_from_spectrum

matplotlib.use("Agg")

FS, RPM = 48_000.0, 1797.0
CWRU = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "cwru"


def outer_race(seed=0, n=48_000, f_res=15_000.0, noise=0.3):
    """Impacts at the closed-form BPFO of a 6205 ringing a resonance (3 % damping)."""
    bpfo = bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfo
    t = np.arange(n) / FS
    pulses = np.zeros(n)
    pulses[np.floor(np.arange(0, n / FS, 1 / bpfo) * FS).astype(int)] = 1.0
    ring = np.exp(-2 * np.pi * 0.03 * f_res * t[:400]) * np.sin(2 * np.pi * f_res * t[:400])
    x = np.convolve(pulses, ring)[:n]
    return x + noise * np.random.default_rng(seed).standard_normal(n), bpfo


def test_ses_matches_butterworth_ses_and_bpfo_stands_out():
    x, bpfo = outer_race()
    res = F.envelope_analysis(x, FS, rpm=RPM, bearing="6205")
    freqs, ses = F.squared_envelope_spectrum(x, FS, band=res.band)
    np.testing.assert_array_equal(res.freqs, freqs)
    # Both apply the same zero-phase Butterworth gain |H|^2 (sosfiltfilt in time, a
    # product here); they differ by sosfiltfilt's end transients, about a filter
    # impulse response (< 1 ms for this 2 kHz band) at each end, where the Hann window
    # of the spectrum is below 1e-4: measured 2e-5 of the largest line.
    assert np.max(np.abs(res.ses - ses)) <= 1e-3 * ses.max()
    # What the signal shows: the SES's strongest line among the fault families
    # (below 3 x BPFI) is the closed-form BPFO, within one 1 Hz bin.
    fam = freqs < 3 * bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfi
    assert abs(freqs[fam][np.argmax(res.ses[fam])] - bpfo) <= 1.0
    assert res.fault_bands["bpfo_1"] > 10.0 > res.fault_bands["bpfi_1"]


def zero_phase_gain(n, band):
    """|H|^2 of the order-4 Butterworth band-pass (low-pass from 0 Hz) on the rFFT bins."""
    lo, hi = band
    if lo == 0 and hi == FS / 2:
        return np.ones(n // 2 + 1)
    args = (hi, "lowpass") if lo == 0 else ((lo, hi), "bandpass")
    sos = scipy.signal.butter(4, *args, fs=FS, output="sos")
    return np.abs(scipy.signal.sosfreqz(sos, worN=scipy.fft.rfftfreq(n, 1 / FS), fs=FS)[1]) ** 2


@pytest.mark.parametrize(
    ("n", "band"),
    [(48_000, (14_000.0, 16_000.0)), (48_000, (375.0, 750.0)), (4001, (0.0, 24_000.0)),
     (4001, (6000.0, 12_000.0)), (1000, (0.0, 3000.0))],
)
def test_decimated_band_signal_is_the_full_length_one(n, band):
    """The SES from the band signal sampled at m << n points equals the SES of the
    full-length band signal (the filter's zero-phase gain applied to the whole spectrum,
    scipy.signal.hilbert, the SES of the unfiltered result), also for an odd n, a band
    from 0 Hz and the full band (the m = n path)."""
    x = np.random.default_rng(1).standard_normal(n)
    x -= x.mean()
    y = scipy.fft.irfft(scipy.fft.rfft(x) * zero_phase_gain(n, band), n)
    ref = F.squared_envelope_spectrum(y, FS, band=(0.0, FS / 2))[1]
    ses = _ses_from_spectrum(scipy.fft.rfft(x), n, FS, band)
    assert ses.shape == ref.shape
    # The bins left out pass < 1e-6 of their amplitude (analysis._GAIN_FLOOR), so the
    # SES moves by < 1e-5 of its largest line; aliasing from too few samples (m < 2 L)
    # or an unsquared envelope miss by more than 10 %.
    assert np.max(np.abs(ses - ref)) <= 1e-5 * ref.max()


def test_band_kurtogram_and_indicators_are_those_of_the_separate_functions():
    x = np.stack([outer_race()[0], outer_race(seed=2, f_res=6000.0)[0],
                  np.random.default_rng(3).standard_normal(48_000)])
    res = F.envelope_analysis(x, FS)
    kurt = F.fast_kurtogram(x, FS)
    np.testing.assert_array_equal(res.band, kurt.best_band)
    np.testing.assert_array_equal(res.kurtogram.kurtosis, kurt.kurtosis)
    assert len({tuple(b) for b in res.band}) == 3  # each row demodulated in its own band
    ind = F.indicators(x)
    assert res.indicators.keys() == ind.keys()
    for name, value in ind.items():
        np.testing.assert_array_equal(res.indicators[name], value)
    assert res.fault_bands is None and res.frequencies is None
    # rows are analysed as single signals, each in its band (catches one band for all)
    for row, b, ses in zip(x, res.band, res.ses, strict=True):
        single = F.envelope_analysis(row, FS)
        assert single.band == tuple(b)
        np.testing.assert_allclose(ses, single.ses, rtol=0, atol=1e-12 * ses.max())
    # the sample axis may be another one
    res_t = F.envelope_analysis(x.T, FS, axis=0)
    np.testing.assert_allclose(res_t.ses.T, res.ses, rtol=0, atol=1e-12 * res.ses.max())


def test_fault_bands_track_the_butterworth_features():
    """The feature table's fault-band levels moved to envelope_analysis: they stay within
    0.2 dB of fault_band_features (Butterworth in the time domain). The difference is the
    mean of x (kept by an unfiltered full band) and sosfiltfilt's end transients, longest
    for narrow bands; over the 185 one-second CWRU records the median difference is
    5e-5 dB, the largest 0.13 dB."""
    x = np.stack([outer_race(seed=s)[0] for s in range(2)]
                 + [np.random.default_rng(s).standard_normal(48_000) for s in range(2)])
    rpm = np.array([RPM, 1750.0, 1797.0, 1500.0])
    res = F.envelope_analysis(x, FS, rpm=rpm, bearing="6205")
    ref = F.fault_band_features(x, FS, "6205", rpm)
    for name, value in ref.items():
        np.testing.assert_allclose(res.fault_bands[name], value, rtol=0, atol=0.2, err_msg=name)


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_fault_bands_track_on_real_recordings():
    files = sorted(CWRU.glob("12k_DE_*.mat"))[:6]
    X, meta = bp.datasets.load_cwru(files, fs=12_000)
    X, rpm = X[::4], meta.rpm.to_numpy()[::4]  # a few segments of each record
    res = F.envelope_analysis(X, 12_000.0, rpm=rpm, bearing="6205")
    ref = F.fault_band_features(X, 12_000.0, "6205", rpm)
    for name, value in ref.items():  # tolerance: see the test above
        np.testing.assert_allclose(res.fault_bands[name], value, rtol=0, atol=0.2, err_msg=name)


def test_bad_input_is_refused_before_work():
    x = np.zeros(1000)
    with pytest.raises(ValueError, match="rpm and bearing go together"):
        F.envelope_analysis(x, FS, rpm=1797.0)
    with pytest.raises(ValueError, match="rpm and bearing go together"):
        F.envelope_analysis(x, FS, bearing="6205")
    with pytest.raises(TypeError, match="bearing"):
        F.envelope_analysis(x, FS, rpm=1797.0, bearing=6205)
    with pytest.raises(ValueError, match="rpm must be finite and > 0"):
        F.envelope_analysis(x, FS, rpm=-1.0, bearing="6205")
    with pytest.raises(ValueError, match="rpm must be a scalar or broadcast"):
        F.envelope_analysis(np.zeros((2, 1000)), FS, rpm=[1.0, 2.0, 3.0], bearing="6205")
    with pytest.raises(ValueError, match="^fs must be"):
        F.envelope_analysis(x, 0.0)
    with pytest.raises(ValueError, match="NaN or inf"):
        F.envelope_analysis(np.full(1000, np.nan), FS)
    with pytest.raises(ValueError, match="no signals"):
        F.envelope_analysis(np.zeros((0, 1000)), FS)


def test_plot_draws_ses_and_kurtogram():
    x, _ = outer_race(n=12_000)
    res = F.envelope_analysis(x, FS, rpm=RPM, bearing="6205")
    fig = res.plot()
    assert len(fig.axes) == 3  # SES, kurtogram and its colour bar
    assert "BPFO 107.4 Hz" in [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    # the spectrum names the band it was computed in, the kurtogram outlines that band as
    # its best (no dashed second band): the two panels agree
    lo, hi = res.band
    assert f"band {lo:.0f}–{hi:.0f} Hz" in fig.axes[0].get_title(loc="left")
    assert f"best band {lo:.0f}–{hi:.0f} Hz" in fig.axes[1].get_title()
    assert "dashed" not in fig.axes[1].get_title()
    with pytest.raises(ValueError, match="one signal"):
        F.envelope_analysis(np.zeros((2, 1000)), FS).plot()
