"""Cyclic coherence integrated over a band: the enhanced envelope spectrum (EES).

A localized bearing fault makes the vibration cyclostationary: the random ringing of
each impact is modulated at the fault rate, so the spectrum at ``f`` correlates with
the spectrum at ``f - alpha`` for the cyclic frequencies ``alpha`` of the fault
(Antoni 2007; Randall & Antoni 2011, section 3.5). The cyclic coherence

``gamma(alpha, f) = S(alpha, f) / sqrt(S(0, f) S(0, f - alpha))``

normalizes that spectral correlation by the power at both frequencies, so a weak
band counts as much as a strong one; its squared magnitude averaged over a band of
carrier frequencies is the *enhanced envelope spectrum* (Borghesani, Pennacchi &
Chatterton 2014; Mauricio et al. 2020 read their IESFOgram from it). Where the
squared envelope spectrum's background is a single periodogram bin, exponentially
distributed, the EES averages many carrier bins: its background is far flatter, and
a line a squared envelope leaves in the noise can stand out of it.

Estimator: the fast spectral correlation of Antoni, Xin & Hamzaoui (2017). A short-time
Fourier transform (Hann window of ``nperseg`` samples, hop ``nperseg / 4``, phases
referred to absolute time) is taken once; for each whole shift ``p`` of its bin width
``df_w``, the products ``X_k(f) conj(X_k(f - p df_w))`` over the frames ``k``, Fourier
transformed over ``k``, give the spectral correlation for every cyclic frequency
within ``df_w / 2`` of ``p df_w``, at the record's full resolution ``fs / n``. The
cost is a few transforms of the frame sequence per shift, whatever the resolution.

References
----------
J. Antoni, "Cyclic spectral analysis of rolling-element bearing signals: facts and
fictions", JSV 304 (2007) 497-529. J. Antoni, G. Xin, N. Hamzaoui, "Fast computation
of the spectral correlation", MSSP 92 (2017) 248-277. P. Borghesani, P. Pennacchi,
S. Chatterton, "The relationship between kurtosis- and envelope-based indexes for
the diagnostic of rolling element bearings", MSSP 43 (2014) 25-43. R. B. Randall,
J. Antoni, "Rolling element bearing diagnostics - A tutorial", MSSP 25 (2011) 485-520.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.fft

from ._validation import check_band, check_fs, check_positive_int, check_signals

__all__ = ["enhanced_envelope_spectrum", "default_nperseg"]


def default_nperseg(fs: float) -> int:
    """Window length of the short-time transform, samples: the power of two nearest
    ``fs / 64`` (a carrier resolution of about 190 Hz at 12 kHz and at 48 kHz alike,
    fine enough to average ten or more bins over a 2 kHz band).

    Examples
    --------
    >>> from ballpass.features.cyclic import default_nperseg
    >>> default_nperseg(12_000.0), default_nperseg(48_000.0)
    (256, 1024)
    """
    return int(2 ** round(math.log2(check_fs(fs) / 64.0)))


def enhanced_envelope_spectrum(x, fs: float, band, *, max_alpha: float,
                               nperseg: int | None = None):
    """Squared cyclic coherence averaged over the carrier band ``band``: the EES.

    ``EES(alpha) = mean over f in band of |gamma(alpha, f)|^2`` with ``gamma`` the
    cyclic coherence (module notes), on cyclic frequencies ``0 .. max_alpha`` in steps
    of about ``fs / n_samples`` (the squared envelope spectrum's resolution). On
    stationary noise ``|gamma|^2`` has the mean ``1 / K`` (``K`` the effective number
    of frames), whatever ``alpha``: the background is flat and no band dominates by its
    power.

    Parameters
    ----------
    x : array_like, shape (n_signals, n_samples) or (n_samples,)
        Signals, any unit.
    fs : float
        Sampling frequency, Hz.
    band : (float, float)
        Carrier band ``(lo, hi)``, Hz, ``0 <= lo < hi <= fs / 2``.
    max_alpha : float
        Highest cyclic frequency wanted, Hz, in ``(0, hi - lo]``. A cyclic frequency
        ``p df_w + delta`` (``|delta| <= df_w / 2``, ``df_w = fs / nperseg``) is read
        from carrier pairs ``p`` window bins apart; the Hann window's overlap lowers a
        line at ``|delta| = df_w / 2`` by at most 1.4 dB, and leaves the background as
        it is.
    nperseg : int, optional
        Short-time window, samples (default :func:`default_nperseg`); at least 16.

    Returns
    -------
    alpha : ndarray, shape (n_alpha,)
        Cyclic frequencies, Hz.
    ees : ndarray, shape (n_signals, n_alpha)
        Band-averaged squared cyclic coherence, dimensionless in [0, 1]; ``ees[:, 0]``
        is close to 1 (the frames' power, tapered, against its plain mean).

    Examples
    --------
    Noise modulated at 37 Hz stands out of the EES at 37 Hz:

    >>> import numpy as np
    >>> from ballpass.features.cyclic import enhanced_envelope_spectrum
    >>> fs = 12_000.0
    >>> t = np.arange(24_000) / fs
    >>> noise = np.random.default_rng(0).standard_normal(t.size)
    >>> x = (1 + 0.5 * np.cos(2 * np.pi * 37 * t)) * noise
    >>> alpha, ees = enhanced_envelope_spectrum(x, fs, (1000, 5000), max_alpha=100.0)
    >>> float(alpha[np.argmax(ees[0, 10:]) + 10]).__round__()
    37
    """
    fs = check_fs(fs)
    xv = check_signals(x)
    lo, hi = check_band(band, fs)
    nw = default_nperseg(fs) if nperseg is None else check_positive_int("nperseg", nperseg, 16)
    n = xv.shape[-1]
    if nw > n // 4:
        raise ValueError(f"nperseg must be at most a quarter of the record ({n // 4} samples),"
                         f" got {nw}")
    hop = nw // 4
    frame_rate = fs / hop
    df_w = fs / nw
    if (isinstance(max_alpha, bool) or not isinstance(max_alpha, (int, float))
            or not 0 < max_alpha <= hi - lo):
        raise ValueError(f"max_alpha must be in (0, {hi - lo:g}] Hz (the band's width: "
                         f"a cyclic frequency pairs two carriers of the band), got {max_alpha!r}")
    k = (n - nw) // hop + 1
    starts = np.arange(k) * hop
    frames = xv[:, starts[:, None] + np.arange(nw)]                   # (m, K, nw)
    frames = frames - frames.mean(axis=-1, keepdims=True)
    window = np.hanning(nw + 2)[1:-1]
    spec = scipy.fft.rfft(frames * window, axis=-1)                   # (m, K, nw/2+1)
    bins = np.arange(spec.shape[-1])
    # Phases referred to absolute time: frame k starts at sample k * hop.
    spec *= np.exp(-2j * np.pi * np.outer(starts, bins) / nw)[None]
    power = np.mean(np.abs(spec) ** 2, axis=1) + np.finfo(float).tiny  # (m, bins)
    taper = np.hanning(k + 2)[1:-1]
    n_fft = scipy.fft.next_fast_len(max(k, round(n / hop)))
    step = frame_rate / n_fft
    alpha = np.arange(0.0, max_alpha + 0.5 * step, step)
    ees = np.zeros((len(xv), alpha.size))
    in_band = (bins * df_w >= lo) & (bins * df_w <= hi)
    for p in range(0, int(math.floor(max_alpha / df_w + 0.5)) + 1):
        j = np.flatnonzero(in_band & (bins - p >= 0))
        if j.size == 0:
            continue
        prod = spec[:, :, j] * np.conj(spec[:, :, j - p]) * taper[None, :, None]
        corr = scipy.fft.fft(prod, n=n_fft, axis=1) / taper.sum()    # (m, n_fft, J)
        gamma2 = np.abs(corr) ** 2 / (power[:, None, j] * power[:, None, j - p])
        # Cyclic frequencies this shift serves: within half a carrier bin of p df_w.
        mine = np.flatnonzero(np.abs(alpha - p * df_w) <= 0.5 * df_w)
        if mine.size == 0:
            continue
        # In absolute-time frames, E[X_k(f) conj(X_k(f - p df_w))] turns at the rate
        # alpha - p df_w over k: alpha appears at beta = alpha - p df_w (mod frame rate).
        idx = np.rint(((alpha[mine] - p * df_w) % frame_rate) / step).astype(np.int64) % n_fft
        ees[:, mine] = gamma2[:, idx, :].mean(axis=-1)
    return alpha, ees
