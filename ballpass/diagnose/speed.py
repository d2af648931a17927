"""Shaft speed from the signal: the comb of shaft harmonics in the spectrum.

A stored speed can be wrong by a few percent (the CWRU file 12k_FE_OR014@3_0 is named 0
hp, 1797 rpm, but holds the 1 hp test at 1774 rpm, which its shaft comb confirms) or
missing (the loaders then fill a nominal speed). The fault lines of a bearing are fixed
multiples of the shaft speed, so a 1.3 % error moves 3xBPFI of a 6205 by 6 Hz, outside
any slip search. A rotating machine's spectrum carries the shaft harmonics ``k x fr``
(unbalance, misalignment, looseness: Randall, *Vibration-based Condition Monitoring*,
2011, ch. 1); the speed whose harmonic comb stands highest above the spectrum's
background, within a few percent of the stated speed, is the shaft speed (a harmonic-
comb search, the discrete analogue of reading the first order of an order spectrum). A
fault's own harmonics can form a comb too (the 6203's BPFO / 3 lies 1.8 % above its
shaft speed): the diagnoser does not use a correction that loses 3 dB of fault evidence
(:func:`ballpass.diagnose.envelope_evidence`).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.fft
import scipy.ndimage

__all__ = ["estimate_shaft_speed"]

#: Harmonics of the shaft speed in the comb.
_ORDERS = 10
#: Half-width of the running-median background of the spectrum, Hz.
_BACKGROUND_HZ = 5.0


def estimate_shaft_speed(x: np.ndarray, fs: float, rpm, *, tolerance: float = 0.04):
    """Shaft speed of each row from its harmonic comb, searched within ``+-tolerance``.

    The Hann-windowed power spectrum of each row is zero-padded to a quarter of a
    bin; for each candidate speed ``fr`` in ``rpm/60 (1 +- tolerance)`` (steps of a
    quarter bin at the 10th harmonic) the comb level is the median over ``k = 1..10``
    of ``10 log10(P(k fr) / background)``, the background the running median of ``P``
    over +-5 Hz: most harmonics must be present (a fault's own harmonics hit only a
    few of them). The candidate with the highest comb wins.

    Parameters
    ----------
    x : ndarray, shape (n_signals, n_samples)
        Signals, validated, any unit.
    fs : float
        Sampling frequency, Hz.
    rpm : ndarray, shape (n_signals,)
        Stated shaft speed, rev/min.
    tolerance : float, optional
        Relative half-width of the search (default 0.04: the CWRU rig's speeds at
        0-3 hp span 1730-1797 rpm, 3.8 %).

    Returns
    -------
    rpm_found : ndarray, shape (n_signals,)
        Speed whose comb stands highest, rev/min.
    comb_db : ndarray, shape (n_signals,)
        Its comb level (median over the harmonics), dB above the background.
    stated_db : ndarray, shape (n_signals,)
        The comb level at the stated speed, dB.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.diagnose.speed import estimate_shaft_speed
    >>> fs, fr = 12_000.0, 29.95
    >>> t = np.arange(120_000) / fs
    >>> x = sum(np.cos(2 * np.pi * k * fr * t) / k for k in range(1, 8))
    >>> x = x + np.random.default_rng(0).standard_normal(t.size)
    >>> found, comb, stated = estimate_shaft_speed(x[None], fs, np.array([1774.0]))
    >>> bool(abs(found[0] - 1797.0) < 2), bool(comb[0] > stated[0] + 10)
    (True, True)
    """
    n = x.shape[-1]
    pad = 4 * n
    w = np.hanning(n)
    df = fs / pad
    top = min(0.5 * fs, (_ORDERS + 1) * (1 + tolerance) * float(np.max(rpm)) / 60.0)
    n_keep = min(pad // 2 + 1, math.ceil(top / df) + 2)
    spec = scipy.fft.rfft((x - x.mean(axis=-1, keepdims=True)) * w, n=pad, axis=-1)[:, :n_keep]
    power = spec.real**2 + spec.imag**2
    half = max(2, round(_BACKGROUND_HZ / df))
    background = scipy.ndimage.median_filter(power, size=(1, 2 * half + 1), mode="nearest")
    level = 10 * np.log10((power + 1e-300) / (background + 1e-300))

    fr0 = np.asarray(rpm, float) / 60.0
    step = 0.25 * (fs / n) / (_ORDERS * fr0.max())
    scales = np.arange(1 - tolerance, 1 + tolerance + 0.5 * step, step)
    scales = np.append(scales, 1.0)  # the stated speed itself
    k = np.arange(1, _ORDERS + 1)
    f = fr0[:, None, None] * scales[None, :, None] * k  # (n, S, K)
    idx = np.rint(f / df).astype(np.int64)
    inside = idx < n_keep
    rows = np.arange(len(x))[:, None, None]
    comb = np.where(inside, level[rows, np.minimum(idx, n_keep - 1)], np.nan)
    comb = np.nanmedian(comb, axis=-1)  # (n, S)
    best = np.nanargmax(comb[:, :-1], axis=1)
    i = np.arange(len(x))
    return 60.0 * fr0 * scales[best], comb[i, best], comb[:, -1]
