"""Squared envelope spectra of many bands of one signal, at the cost of each band.

:func:`ballpass.features.envelope_spectrum` band-passes the whole signal, takes its
analytic signal and the spectrum of the squared envelope: three transforms of the full
length per band. A search over the bands of Antoni's 1/3-binary tree (the envelope
diagnoser's) then costs ``n_bands x n_samples``, and a 48 kHz record pays 16 times what
the same record at 12 kHz does (four times the samples, about four times the bands).

The same spectrum comes from the band alone (Randall & Antoni 2011, section 3.3:
demodulation is a frequency shift of the band to 0 Hz). The signal's spectrum is taken
once; a band's complex envelope keeps only the bins its filter passes (the zero-phase
Butterworth response of :func:`ballpass.features.bandpass`, ``|H(f)|^2``, down to
:data:`STOP_GAIN`), shifted to 0 Hz and brought back to the time domain on just enough
samples to hold its squared modulus without aliasing (twice the band's bins plus the
Hann window's spread). The squared envelope is invariant to the shift, so the spectrum
is that of :func:`~ballpass.features.envelope_spectrum`, filtered circularly instead of
with ``sosfiltfilt``'s padded edges (the Hann window tapers the record's ends, where
the two differ). A band costs in proportion to its width, so the whole tree costs a few
transforms of the full length, whatever the rate.
"""

from __future__ import annotations

import numpy as np
import scipy.fft
import scipy.signal

from ._validation import check_band, check_fs, check_signals
from .envelope import _window

__all__ = ["BandDemodulator", "STOP_GAIN", "butterworth_gain"]

#: Bins where the zero-phase band-pass passes less than this amplitude gain (-100 dB in
#: power) are left out of a band's complex envelope: what they would add to the squared
#: envelope is at most 1e-5 of what the band carries, far below a spectrum line's
#: relative precision on a one-second record.
STOP_GAIN = 1e-5


class BandDemodulator:
    """Squared envelope spectra (SES) of any band of signals, spectrum computed once.

    Parameters
    ----------
    x : array_like, shape (n_signals, n_samples) or (n_samples,)
        Signals, any unit.
    fs : float
        Sampling frequency, Hz.
    max_hz : float or None, optional
        Highest SES frequency wanted, Hz (default ``None``: up to each band's width);
        bins above it are not returned.
    prewhiten : bool, optional
        Cepstrum pre-whitening (unit spectral magnitude) before the band-pass
        (default False), as :func:`ballpass.features.cepstrum_prewhiten`.
    order : int, optional
        Butterworth order of the band-pass, as :func:`ballpass.features.bandpass`
        (default 4).

    Attributes
    ----------
    power : ndarray, shape (n_signals, n_samples // 2 + 1)
        Power spectrum of the mean-removed raw signals (before pre-whitening).
    df : float
        SES resolution ``fs / n_samples``, Hz.

    Examples
    --------
    The same SES as :func:`ballpass.features.envelope_spectrum` (an AM tone, 10 Hz
    modulation of a 2 kHz carrier):

    >>> import numpy as np
    >>> from ballpass.features import envelope_spectrum
    >>> from ballpass.features.demodulate import BandDemodulator
    >>> fs = 12_000.0
    >>> t = np.arange(12_000) / fs
    >>> x = (1 + 0.5 * np.cos(2 * np.pi * 10 * t)) * np.cos(2 * np.pi * 2000 * t)
    >>> freqs, ses = BandDemodulator(x, fs, max_hz=100.0).ses((1500.0, 2500.0))
    >>> ref = envelope_spectrum(x, fs, (1500.0, 2500.0))[1]
    >>> ses.shape, bool(np.allclose(ses[0], ref[: freqs.size], atol=1e-6))
    ((1, 101), True)
    """

    def __init__(self, x, fs: float, *, max_hz=None, prewhiten: bool = False,
                 order: int = 4):
        self.fs = check_fs(fs)
        xv = check_signals(x)
        self.n = xv.shape[-1]
        self.df = self.fs / self.n
        spectrum = scipy.fft.rfft(xv - xv.mean(axis=-1, keepdims=True), axis=-1)
        self.power = spectrum.real**2 + spectrum.imag**2
        if prewhiten:
            magnitude = np.sqrt(self.power)
            spectrum = np.divide(spectrum, magnitude, out=np.zeros_like(spectrum),
                                 where=magnitude > 0)
        self._spectrum = spectrum
        self._freqs = scipy.fft.rfftfreq(self.n, 1.0 / self.fs)
        self.max_hz = None if max_hz is None else float(max_hz)
        self.order = order

    def _squared(self, band):
        """Squared envelope of ``band`` on just enough samples for its SES up to
        ``max_hz``: ``(e (n_signals, m), reach in bins, SES bins wanted)``."""
        lo, hi = check_band(band, self.fs)
        a, b = _reach_bins(lo, hi, self.fs, self.order, self.df, self._freqs.size)
        gain = butterworth_gain(self._freqs[a:b], lo, hi, self.fs, self.order)
        weight = 2.0 * gain
        weight[(np.arange(a, b) == 0) | (2 * np.arange(a, b) == self.n)] *= 0.5  # as hilbert
        reach = b - a  # the squared envelope's spectrum spans +-reach bins
        n_bins = reach + 1 if self.max_hz is None else int(self.max_hz / self.df) + 1
        # Samples: the squared envelope's spectrum spans +-reach bins; on m samples a
        # line at f > m/2 folds to m - f, so bins up to n_bins stay clean for
        # m > reach + n_bins (and the Hann window's +-1 bin).
        m = scipy.fft.next_fast_len(reach + min(n_bins, reach + 1) + 4)
        z = scipy.fft.ifft(self._spectrum[:, a:b] * weight, n=m, axis=-1) * (m / self.n)
        return z.real**2 + z.imag**2, reach, n_bins

    def squared_envelope(self, band) -> tuple[float, np.ndarray]:
        """Squared envelope of the signals in ``band``, resampled to the fewest samples
        that hold its spectrum up to ``max_hz`` (the same envelope :meth:`ses` reads).

        Returns
        -------
        rate : float
            Sampling rate of the envelope, Hz.
        e : ndarray, shape (n_signals, m)
            Squared envelope, unit^2, over the whole record.
        """
        e, _, _ = self._squared(band)
        return e.shape[-1] * self.df, e

    def ses(self, band) -> tuple[np.ndarray, np.ndarray]:
        """SES of the signals demodulated in ``band``.

        Parameters
        ----------
        band : (float, float)
            Demodulation band ``(lo, hi)``, Hz.

        Returns
        -------
        freqs : ndarray, shape (n_bins,)
            Hz, from 0 in steps of :attr:`df`, up to ``max_hz`` (or the band's reach).
        ses : ndarray, shape (n_signals, n_bins)
            One-sided amplitude of the squared envelope, unit^2, as
            :func:`ballpass.features.envelope_spectrum`.
        """
        e, reach, n_bins = self._squared(band)
        m = e.shape[-1]
        w = _window("hann", m)
        e = e - np.sum(e * w, axis=-1, keepdims=True) / w.sum()
        amp = np.zeros((len(e), n_bins))
        kept = min(n_bins, reach + 1, self.n // 2 + 1)  # beyond the reach the SES is 0
        amp[:, :kept] = np.abs(scipy.fft.rfft(e * w, axis=-1)[:, :kept]) * (2.0 / w.sum())
        if self.n % 2 == 0 and kept == self.n // 2 + 1:
            amp[:, kept - 1] *= 0.5
        return np.arange(n_bins) * self.df, amp


def _warped(f, fs: float):
    """Analogue frequency of the bilinear transform with pre-warping, rad/s."""
    return 2.0 * fs * np.tan(np.pi * np.asarray(f, dtype=float) / fs)


def butterworth_gain(freqs, lo: float, hi: float, fs: float, order: int) -> np.ndarray:
    """Amplitude gain of :func:`ballpass.features.bandpass` (zero-phase Butterworth):
    ``|H(f)|^2 = 1 / (1 + p^(2 order))``, ``p`` the low-pass prototype's frequency.

    ``scipy.signal.butter(..., fs=fs)`` pre-warps the band edges for the bilinear
    transform, so with ``W(f) = 2 fs tan(pi f / fs)``: ``p = (W^2 - W(lo) W(hi)) / (W
    (W(hi) - W(lo)))`` (band-pass), ``W / W(hi)`` (``lo = 0``), ``W(lo) / W``
    (``hi = fs / 2``); 1 for the full band.

    Examples
    --------
    >>> import numpy as np, scipy.signal
    >>> from ballpass.features.demodulate import butterworth_gain
    >>> f = np.linspace(0.0, 6000.0, 601)
    >>> sos = scipy.signal.butter(4, (2000, 4000), "bandpass", fs=12_000, output="sos")
    >>> ref = np.abs(scipy.signal.sosfreqz(sos, worN=f, fs=12_000)[1]) ** 2
    >>> bool(np.allclose(butterworth_gain(f, 2000, 4000, 12_000, 4), ref, atol=1e-12))
    True
    """
    nyquist = 0.5 * fs
    if lo <= 0.0 and hi >= nyquist:
        return np.ones(np.shape(freqs))
    w = _warped(np.minimum(freqs, nyquist * (1.0 - 1e-12)), fs)
    with np.errstate(divide="ignore", invalid="ignore"):
        if lo <= 0.0:
            p = w / _warped(hi, fs)
        elif hi >= nyquist:
            p = _warped(lo, fs) / w
        else:
            w1, w2 = _warped(lo, fs), _warped(hi, fs)
            p = (w**2 - w1 * w2) / (w * (w2 - w1))
        return 1.0 / (1.0 + np.abs(p) ** (2 * order))


def _reach_bins(lo: float, hi: float, fs: float, order: int, df: float, n_bins: int):
    """Bins ``[a, b)`` where the band-pass gain is at least :data:`STOP_GAIN`."""
    nyquist = 0.5 * fs
    p = (1.0 / STOP_GAIN - 1.0) ** (1.0 / (2 * order))  # prototype frequency at the gain
    w1, w2 = _warped(max(lo, 0.0), fs), _warped(min(hi, nyquist * (1.0 - 1e-12)), fs)
    if lo <= 0.0:
        bottom, top = 0.0, w2 * p
    elif hi >= nyquist:
        bottom, top = w1 / p, np.inf
    else:
        root = np.sqrt((p * (w2 - w1)) ** 2 + 4.0 * w1 * w2)
        bottom, top = 0.5 * (root - p * (w2 - w1)), 0.5 * (root + p * (w2 - w1))
    to_hz = fs / np.pi
    f_lo = to_hz * np.arctan(bottom / (2.0 * fs))
    f_hi = to_hz * np.arctan(top / (2.0 * fs))
    a = max(0, int(np.floor(f_lo / df)))
    b = min(n_bins, int(np.ceil(f_hi / df)) + 1)
    return a, b
