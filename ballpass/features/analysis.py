"""Envelope analysis of a signal in one call: kurtogram, band, SES, indicators, fault bands.

What a diagnosis, a feature table or an overview figure needs from a signal, computed
once and sharing the work: the fast kurtogram's spectrum of the signal also gives the
squared envelope spectrum (SES) in the chosen band, without filtering in the time
domain, and the band-limited analytic signal is formed at the rate its bandwidth
needs rather than at ``fs``.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import scipy.fft
import scipy.signal

from ._validation import check_fs, check_rpm, check_signal, from_unit_scale, to_unit_scale
from .bands import as_bearing, fault_band_levels, highest_fault_line
from .envelope import _amplitude_spectrum, _sos
from .indicators import _indicators
from .kurtogram import FLOOR_DB, MIN_BANDWIDTH_HZ, KurtogramResult, _default_nlevel, _kurtogram

__all__ = ["EnvelopeAnalysis", "envelope_analysis"]

#: Butterworth order of the demodulation filter, as :func:`envelope_spectrum`'s default.
_ORDER = 4
#: Bins where the filter's zero-phase gain ``|H|^2`` is below this are left out of the
#: band signal: they pass less than 1e-6 of their amplitude, so the SES changes by less
#: than 1e-6 of the skirts' content (measured: no change at the 1e-5 level against a
#: floor of 1e-10), while the band signal of a 2 kHz band at 48 kHz shrinks from
#: 17 800 to 9 700 bins.
_GAIN_FLOOR = 1e-6


@dataclass(frozen=True, eq=False)
class EnvelopeAnalysis:
    """Result of :func:`envelope_analysis`.

    Attributes
    ----------
    kurtogram : KurtogramResult
        Fast kurtogram of the signal(s) (:func:`fast_kurtogram`, default settings).
    band : tuple of float or ndarray of shape (..., 2)
        Demodulation band ``(lo, hi)``, Hz: the kurtogram's ``best_band``.
    freqs : ndarray, shape (n_samples // 2 + 1,)
        Envelope frequencies of ``ses``, Hz (resolution ``fs / n_samples``).
    ses : ndarray, shape (..., n_samples // 2 + 1)
        Squared envelope spectrum in ``band`` (frequencies along the input's ``axis``),
        one-sided amplitude, unit^2 (Hann window, mean removed; the normalisation of
        :func:`envelope_spectrum`).
    indicators : dict of str to ndarray of shape (...)
        :func:`indicators` of the signal(s).
    fault_bands : dict of str to ndarray of shape (...) or None
        :func:`fault_band_levels` of ``ses`` (dB) when ``rpm`` and ``bearing`` were
        given, else None.
    fs : float
        Sampling frequency, Hz.
    frequencies : BearingFrequencies or None
        Fault frequencies (Hz) of the bearing at the mean of ``rpm``, for markers;
        None without a bearing.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import envelope_analysis
    >>> res = envelope_analysis(np.random.default_rng(0).standard_normal(12_000), 12_000.0)
    >>> res.ses.shape, res.fault_bands is None, round(float(res.indicators["kurtosis"]), 1)
    ((6001,), True, 3.0)
    """

    kurtogram: KurtogramResult
    band: tuple[float, float] | np.ndarray
    freqs: np.ndarray
    ses: np.ndarray
    indicators: dict
    fault_bands: dict | None
    fs: float
    frequencies: object = None

    def plot(self, *, harmonics: int = 3, fig=None):
        """SES with the fault-frequency markers beside the kurtogram, of one signal.

        Parameters
        ----------
        harmonics : int, optional
            Harmonics of each fault line to mark (default 3).
        fig : matplotlib.figure.Figure, optional
            Figure to draw on (default: a new one).

        Returns
        -------
        matplotlib.figure.Figure

        Examples
        --------
        >>> import numpy as np
        >>> from ballpass.features import envelope_analysis
        >>> x = np.random.default_rng(0).standard_normal(12_000)
        >>> fig = envelope_analysis(x, 12_000.0, rpm=1797, bearing="6205").plot()
        >>> len(fig.axes)                                # SES, kurtogram, colour bar
        3
        """
        from matplotlib.figure import Figure

        from ..plot import _ses_beside_kurtogram

        if self.ses.ndim != 1:
            raise ValueError(f"plot draws one signal's analysis; got SES of shape {self.ses.shape}")
        fig = Figure(figsize=(11, 4), layout="constrained") if fig is None else fig
        _ses_beside_kurtogram(*fig.subplots(1, 2, width_ratios=(1.5, 1)), self.freqs, self.ses,
                             self.kurtogram, [self.band], frequencies=self.frequencies,
                             harmonics=harmonics)
        return fig


@functools.lru_cache(maxsize=64)
def _band_weights(n: int, fs: float, lo: float, hi: float) -> tuple[int, np.ndarray]:
    """Weights of the rFFT bins of ``n`` samples that give the band's analytic signal:
    ``(first bin, weights)`` over the bins where the gain ``|H|^2`` of the
    forward-backward Butterworth filter of :func:`bandpass` is at least
    :data:`_GAIN_FLOOR`, each ``|H|^2`` times the analytic signal's factor (1 at 0 Hz
    and Nyquist, 2 between; ``scipy.signal.hilbert``). Cached: a signal length and rate
    have few distinct bands."""
    sos = _sos(lo, hi, fs, _ORDER)
    n_bins = n // 2 + 1
    if sos is None:
        gain, first = np.ones(n_bins), 0
    else:
        _, h = scipy.signal.sosfreqz(sos, worN=np.arange(n_bins) * (fs / n), fs=fs)
        gain = h.real**2 + h.imag**2
        keep = np.flatnonzero(gain >= _GAIN_FLOOR)
        first, gain = int(keep[0]), gain[keep[0] : keep[-1] + 1]
    k = np.arange(first, first + gain.size)
    weights = gain * np.where((k == 0) | (2 * k == n), 1.0, 2.0)
    weights.flags.writeable = False  # shared by every call with this band
    return first, weights


def _ses_from_spectrum(spectrum: np.ndarray, n: int, fs: float, band) -> np.ndarray:
    """SES of one signal, shape ``(n // 2 + 1,)``, from ``spectrum = rfft(x - mean)``.

    Zero-phase filtering is a product with ``|H|^2`` in the frequency domain; the
    analytic signal keeps the positive bins, doubled (``scipy.signal.hilbert``). The
    squared envelope of a band ``L`` bins wide has its spectrum within ``L`` bins of
    0 Hz, so the band is shifted to 0 Hz and the analytic signal sampled at ``m >= 2 L
    + 2`` points instead of ``n``: at ``t_j = j n / m`` it is ``(m / n) ifft_m``, and
    the Hann-windowed amplitude spectrum of the ``m`` samples equals that of the ``n``
    samples bin for bin (a periodic Hann window sampled at ``t_j`` is the ``m``-point
    one), zero above ``m / 2``.
    """
    first, weights = _band_weights(n, fs, float(band[0]), float(band[1]))
    m = scipy.fft.next_fast_len(2 * weights.size + 2)
    if m >= n:  # a wide band: no saving, sample at fs
        m = n
    c = scipy.fft.ifft(spectrum[first : first + weights.size] * weights, n=m, overwrite_x=True)
    parts = c.view(np.float64)  # real, imaginary, real, ...: |c|^2 in place
    parts *= parts
    power = parts[::2] + parts[1::2]
    power *= (m / n) ** 2
    ses = np.zeros(n // 2 + 1)
    amp = _amplitude_spectrum(power, "hann", fs * m / n)[1]
    ses[: amp.size] = amp
    return ses


def envelope_analysis(x, fs: float, *, rpm=None, bearing=None, axis: int = -1):
    """Kurtogram, demodulation band, squared envelope spectrum and indicators at once.

    The steps of envelope analysis (Randall & Antoni 2011, sections 3.2-3.4) with the
    work shared between them:

    1. :func:`fast_kurtogram` (default settings) chooses the band (``best_band``);
       with ``rpm`` and ``bearing`` its lower edge must lie above the highest line the
       fault-band levels read (three harmonics of the highest defect frequency plus a
       shaft-order sideband), so the band carries the fault lines as modulation;
    2. the SES in that band reuses the kurtogram's FFT of the signal: the band-pass
       is the zero-phase Butterworth filter of :func:`envelope_spectrum` (order 4,
       gain ``|H|^2``) applied as a product in the frequency domain, and the band's
       analytic signal is formed at the rate its bandwidth needs (see Notes);
    3. :func:`indicators` of the signal;
    4. with ``rpm`` and ``bearing``, :func:`fault_band_levels` of the SES.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s), e.g. acceleration in m/s^2; at least 2 samples, finite.
    fs : float
        Sampling frequency, Hz.
    rpm : float or array_like of shape (...), optional
        Shaft speed, rev/min, one for all signals or one per signal; with ``bearing``.
    bearing : str or Bearing, optional
        Catalogue name (``"6205"``) or a :class:`ballpass.Bearing`; with ``rpm``.
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    EnvelopeAnalysis
        ``.kurtogram``, ``.band`` (Hz), ``.freqs`` and ``.ses``, ``.indicators``,
        ``.fault_bands`` (dB, or None), ``.plot()``.

    Raises
    ------
    ValueError, TypeError
        Bad ``x``, ``fs``, ``rpm`` or ``bearing``, or only one of ``rpm`` and
        ``bearing``, before any work.

    See Also
    --------
    fast_kurtogram, squared_envelope_spectrum, indicators, fault_band_levels

    Notes
    -----
    The SES is :func:`squared_envelope_spectrum` ``(x, fs, band=result.band)`` computed
    with circular instead of padded filtering, after removing the mean of ``x`` (as the
    kurtogram does). The two differ only through ``sosfiltfilt``'s start and end
    transients, which the Hann window of the spectrum mostly suppresses, and, for a
    band reaching 0 Hz, through the mean of ``x``.

    References
    ----------
    .. [1] R. B. Randall, J. Antoni, "Rolling element bearing diagnostics - A tutorial",
       MSSP 25 (2011) 485-520.
    .. [2] J. Antoni, "Fast computation of the kurtogram for the detection of transient
       faults", MSSP 21 (2007) 108-124.

    Examples
    --------
    Impacts at the BPFO of a 6205 at 1796 rpm ringing a 3 kHz resonance, in noise:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.features import envelope_analysis
    >>> fs, rpm = 12_000.0, 1796.0
    >>> bpfo = bp.Bearing.catalog("6205").frequencies(rpm / 60).bpfo
    >>> t = np.arange(12_000) / fs
    >>> phase = (t * bpfo) % 1.0 / bpfo                  # time since the last impact, s
    >>> x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    >>> x += 0.2 * np.random.default_rng(0).standard_normal(t.size)
    >>> res = envelope_analysis(x, fs, rpm=rpm, bearing="6205")
    >>> lo, hi = res.band
    >>> bool(lo <= 3000 <= hi), bool(res.fault_bands["bpfo_1"] > 10 > res.fault_bands["bpfi_1"])
    (True, True)
    >>> peak = res.freqs[np.argmax(res.ses)]             # the strongest SES line: BPFO
    >>> bool(abs(peak - bpfo) <= 1.0)
    True
    """
    fs = check_fs(fs)
    xv = check_signal(x, axis, nonempty=True)
    if (rpm is None) != (bearing is None):
        raise ValueError(
            f"rpm and bearing go together (the fault lines need both): got rpm={rpm!r}, "
            f"bearing={bearing!r}"
        )
    if bearing is not None:
        bearing = as_bearing(bearing)
        rpm = check_rpm(rpm, xv.shape[:-1])

    n = xv.shape[-1]
    fault_hz = None if bearing is None else highest_fault_line(bearing, rpm, fs)
    scaled, k = to_unit_scale(xv)    # exact; the SES of 1e200 m/s^2 would overflow
    kurt, spectrum = _kurtogram(scaled, fs, _default_nlevel(n), MIN_BANDWIDTH_HZ, FLOOR_DB,
                                fault_hz)
    bands = np.reshape(kurt.best_band, (-1, 2))
    flat = spectrum.reshape(-1, spectrum.shape[-1])
    ses = np.stack(
        [_ses_from_spectrum(row, n, fs, b) for row, b in zip(flat, bands, strict=True)]
    ).reshape(xv.shape[:-1] + (n // 2 + 1,))
    freqs = scipy.fft.rfftfreq(n, 1.0 / fs)
    fault_bands = frequencies = None
    if bearing is not None:
        fault_bands = fault_band_levels(freqs, ses, bearing, rpm)
        frequencies = bearing.frequencies(float(np.mean(rpm)) / 60.0)
    return EnvelopeAnalysis(
        kurtogram=kurt,
        band=kurt.best_band,
        freqs=freqs,
        ses=np.moveaxis(from_unit_scale(ses, k, 2), -1, axis),
        indicators=_indicators(xv),
        fault_bands=fault_bands,
        fs=fs,
        frequencies=frequencies,
    )
