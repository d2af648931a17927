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
(:func:`ballpass.diagnose.envelope_evidence`), and on records too short for the evidence
to tell (under 2 s) it checks only the corrections no divisor of a fault rate explains
(:func:`fault_comb`: on a 6205, whose defect rates are far from whole multiples of its
shaft speed, every correction within 4 % at 1797 rpm).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.fft
import scipy.ndimage

__all__ = ["estimate_shaft_speed", "fault_comb"]

#: Harmonics of the shaft speed in the comb.
_ORDERS = 10
#: Half-width of the running-median background of the spectrum, Hz.
_BACKGROUND_HZ = 5.0
#: Largest divisor ``m`` of a fault rate whose comb (harmonics of rate / m) can pass for
#: the shaft's: the comb level is the median of its ``_ORDERS`` harmonics, and the
#: fault's lines (rate, 2 x rate, ...) must make at least two of them.
_FAULT_DIVISORS = _ORDERS // 2
#: A raw-spectrum line lifts a comb harmonic this many bins away (the Hann main lobe).
_LOBE_BINS = 2.0


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


def fault_comb(ratio, rates, low: float, high: float, df: float, stated_hz):
    """Whether a speed correction could be a fault's own comb taken for the shaft's.

    A fault repeating at ``c`` shaft orders puts raw-spectrum lines at ``c, 2c, ...``
    orders; at a speed of ``c / m`` orders (``m`` = 1..5) they are every ``m``-th
    harmonic of the comb, at least two of its ten. A correction by ``ratio`` (the comb's
    speed over the stated one) is such a comb when ``ratio`` lies within
    ``c / m x [1 - low, 1 + high]`` (the fault's slip search), widened by the Hann main
    lobe of the raw spectrum (``_LOBE_BINS`` bins of ``df`` at the comb's ``m``-th
    harmonic). On a 6205 the nearest, 2xBSF / 5 = 0.943 and BPFI / 5 = 1.083 orders,
    lie 1.3 % and 2.1 % beyond +-4 % with the slip search: none is within 4 % where the
    lobe is narrower than that (one second at 1797 rpm: 1.3 %); at 600 rpm on one second
    the lobe (2 bins of 1 Hz at 5 x 10 Hz) is 4 %, and corrections beyond -1.3 % and
    +2.1 % count as a fault's. On a 6203 (3.053, 4.947, 3.988) BPFO / 3, BPFI / 5 and
    2xBSF / 4 lie within 2 % of the shaft speed.

    Parameters
    ----------
    ratio : array_like, shape (n,)
        Comb speed over stated speed.
    rates : sequence of float
        Fault rates, shaft orders (BPFO, BPFI, 2xBSF).
    low, high : float
        Relative slip searched below and above the kinematic rates.
    df : float
        Raw-spectrum resolution, Hz (1 / record length).
    stated_hz : array_like, shape (n,)
        Stated shaft speed, Hz.

    Returns
    -------
    ndarray of bool, shape (n,)

    Examples
    --------
    The 6203's BPFO / 3 lies 1.8 % above its shaft speed; no 6205 fault rate comes
    within 4 %:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.diagnose.speed import fault_comb
    >>> def rates(name):
    ...     f = bp.Bearing.catalog(name).frequencies(1.0)
    ...     return [f.bpfo, f.bpfi, f.ball_defect]
    >>> fault_comb([1.018, 1.0], rates("6203"), 0.02, 0.005, 0.1, [30.0, 30.0]).tolist()
    [True, True]
    >>> bool(fault_comb(np.linspace(0.96, 1.04, 81), rates("6205"), 0.02, 0.005, 0.1,
    ...                 np.full(81, 30.0)).any())
    False
    """
    ratio = np.asarray(ratio, dtype=float)[:, None, None]
    m = np.arange(1, _FAULT_DIVISORS + 1, dtype=float)
    c = np.asarray(rates, dtype=float)[:, None] / m  # (rates, m): the combs' speeds, orders
    lobe = _LOBE_BINS * df / (m * np.asarray(stated_hz, dtype=float)[:, None, None])
    inside = (ratio >= c * (1.0 - low) - lobe) & (ratio <= c * (1.0 + high) + lobe)
    return inside.any(axis=(1, 2))
