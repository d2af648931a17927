"""BandDemodulator: the squared envelope spectrum of a band from the band's bins alone."""

import numpy as np
import pytest
import scipy.signal

from ballpass.features import envelope_spectrum
from ballpass.features.demodulate import BandDemodulator, butterworth_gain


def test_am_tone_closed_form():
    # 2 (1 + 0.5 cos 2 pi 10 t) cos 2 pi 200 t: squared envelope 4.5 + 4 cos(10 Hz)
    # + 0.5 cos(20 Hz), so the SES reads 4 at 10 Hz and 0.5 at 20 Hz (exact bins, a
    # cosine on a bin reads its amplitude). Catches a wrong scale (m / n) or a lost
    # factor 2 of the analytic signal (both change these numbers by 2x or more).
    fs = 1000.0
    t = np.arange(1000) / fs
    x = 2.0 * (1 + 0.5 * np.cos(2 * np.pi * 10 * t)) * np.cos(2 * np.pi * 200 * t)
    freqs, ses = BandDemodulator(x, fs, max_hz=50.0).ses((100.0, 300.0))
    assert freqs[10] == 10.0 and freqs[20] == 20.0
    # 1e-5: the band-pass gain at 190-210 Hz is 1 within 1e-7, at the 20 Hz line's
    # 180-220 Hz within 2e-6; the rest is rounding.
    assert ses[0, 10] == pytest.approx(4.0, rel=1e-5)
    assert ses[0, 20] == pytest.approx(0.5, rel=1e-5)


@pytest.mark.parametrize("fs, n", [(12_000.0, 12_000), (48_000.0, 48_001), (51_200.0, 25_600)])
@pytest.mark.parametrize("prewhiten", [False, True])
def test_same_spectrum_as_envelope_spectrum(fs, n, prewhiten):
    # Impacts at 107 Hz ringing 3 kHz in noise, with a strong 30 Hz shaft line far
    # out of band. The full-length route (sosfiltfilt, Hilbert, FFT) is the reference;
    # the two differ only by sosfiltfilt's padded edges against circular filtering,
    # which the Hann window tapers away: 1e-4 of the spectrum's peak bounds that on
    # these signals (measured up to 2e-7 for bands above 1 kHz). Catches aliasing of
    # the squared envelope (too few samples: errors of order 1) and a wrong band gain.
    rng = np.random.default_rng(3)
    t = np.arange(n) / fs
    phase = (t * 107.0) % 1.0 / 107.0
    x = rng.standard_normal((2, n)) + 5.0 * np.sin(2 * np.pi * 30 * t)
    x[0] += 3.0 * np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    demod = BandDemodulator(x, fs, max_hz=800.0, prewhiten=prewhiten)
    for band in [(2000.0, 4000.0), (fs / 8, fs / 4), (1000.0, 1750.0), (fs / 4, fs / 2)]:
        freqs, ses = demod.ses(band)
        ref_f, ref = envelope_spectrum(x, fs, band, prewhiten=prewhiten)
        assert np.array_equal(freqs, ref_f[: freqs.size])
        err = np.abs(ses - ref[:, : freqs.size]).max() / ref[:, 1 : freqs.size].max()
        assert err < 1e-4, (band, err)


@pytest.mark.parametrize("band", [(0.0, 1000.0), (2000.0, 4000.0), (4000.0, 6000.0)])
def test_butterworth_gain_is_the_zero_phase_response(band):
    # sosfiltfilt applies |H|^2; the closed form must match scipy's own design
    # (low-pass, band-pass, high-pass) to rounding.
    fs = 12_000.0
    f = np.linspace(0.0, 5999.0, 6000)
    lo, hi = band
    if lo == 0.0:
        sos = scipy.signal.butter(4, hi, "lowpass", fs=fs, output="sos")
    elif hi == fs / 2:
        sos = scipy.signal.butter(4, lo, "highpass", fs=fs, output="sos")
    else:
        sos = scipy.signal.butter(4, band, "bandpass", fs=fs, output="sos")
    ref = np.abs(scipy.signal.sosfreqz(sos, worN=f, fs=fs)[1]) ** 2
    assert np.allclose(butterworth_gain(f, lo, hi, fs, 4), ref, rtol=0, atol=1e-12)


def test_bad_band_refused():
    with pytest.raises(ValueError, match="band must satisfy"):
        BandDemodulator(np.zeros(1000), 1000.0).ses((100.0, 600.0))
