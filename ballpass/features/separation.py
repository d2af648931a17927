"""Discrete/random separation: remove the deterministic (periodic) part of a signal,
such as gear-mesh lines, before envelope analysis of the bearing's cyclostationary
impacts.

In a gearbox the mesh and its shaft-rate modulation are phase-locked to the shafts
and appear as discrete spectral lines; a bearing fault is cyclostationary (random slip
jitters its impacts) and ends up in the residual. Three methods (Randall & Antoni 2011,
section 4):

``"tsa"``
    Time-synchronous average subtraction: the signal is resampled at uniform shaft
    angle, averaged over the complete revolutions of each shaft and the average,
    evaluated back at every sample's angle, is subtracted. Needs the speed of each
    shaft (``rpm``, constant or a profile, or a tachometer). Exact for lines at
    harmonics of the given shafts; the random part leaks into the average by about
    1/sqrt(revolutions).
``"lp"``
    Linear prediction: an autoregressive model of order ``order`` (Yule-Walker) predicts
    the signal from its past; the prediction is the discrete part, the prediction error
    the residual. Needs no speed, but whitens the residual (a stationary random part is
    not kept as is; impulses are, sharpened).
``"drs"``
    Discrete/random separation (Antoni & Randall 2004): the discrete part is what the
    signal shares with a copy of itself delayed by ``delay`` samples, longer than the
    random part's memory. Here the zero-phase gain is the coherence of the signal and
    its delayed copy (Welch averages over Hann segments of ``nperseg``, 3/4 overlap),
    ~1 at discrete lines and ~0 elsewhere once freed of its two biases for a random
    part: 1/K of a K-average estimate, and the window-overlap share of a delay shorter
    than a segment (a copy delayed by half a Hann segment shares 17 % of white noise
    with the signal inside each segment, which a gain |S_xy| / S_xx then passes as
    "discrete"). Needs no speed. Even with the spectra known exactly, a gain of
    resolution fs / nperseg notches the random part around every line it removes: how
    close DRS comes to exact removal is set by the number of shaft revolutions in the
    record (see the separation page of the documentation).

``method="auto"`` is ``"tsa"`` when a speed or a tachometer is given, otherwise ``"drs"``.

References
----------
.. [1] J. Antoni, R. B. Randall, "Unsupervised noise cancellation for vibration signals:
   part II - a novel frequency-domain algorithm", MSSP 18 (2004) 103-117.
.. [2] R. B. Randall, J. Antoni, "Rolling element bearing diagnostics - a tutorial",
   MSSP 25 (2011) 485-520, section 4.
"""

from __future__ import annotations

import math
import numbers

import numpy as np
import scipy.interpolate
import scipy.linalg
from scipy import signal as _signal

from ._validation import check_fs, check_positive_int, check_signal
from .order import shaft_revolutions

__all__ = ["separate_discrete", "SEPARATION_METHODS", "separated_rows", "check_separate"]

SEPARATION_METHODS = ("auto", "tsa", "lp", "drs")
#: upsampling before the angular resampling of "tsa": keeps the cubic-spline
#: interpolation error of content near Nyquist below ~1e-4 (interpolation at a quarter
#: of the upsampled rate's Nyquist)
_TSA_UPSAMPLE = 4


def _speeds(rpm) -> list:
    """``rpm`` as a list of speeds: one number or profile per shaft."""
    if rpm is None:
        return []
    if isinstance(rpm, numbers.Real) and not isinstance(rpm, bool):
        return [float(rpm)]
    if isinstance(rpm, (list, tuple)):
        return list(rpm)
    try:
        arr = np.asarray(rpm, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"rpm must be a number, a speed profile or an array of them, got "
                        f"{rpm!r}") from None
    return [arr] if arr.ndim == 1 else list(arr)


def _tsa_periodic(x: np.ndarray, fs: float, revs: np.ndarray, n_per_rev: int) -> np.ndarray:
    """The part of ``x`` (..., n) periodic in the shaft angle ``revs`` (n,), revolutions:
    the synchronous average over the complete revolutions, at each sample's angle."""
    n = x.shape[-1]
    xu = _signal.resample_poly(x, _TSA_UPSAMPLE, 1, axis=-1, padtype="line")
    tu = np.arange(xu.shape[-1]) / (fs * _TSA_UPSAMPLE)
    t = np.arange(n) / fs
    revs_u = np.interp(tu, t, revs)
    n_revs = math.floor(revs[-1] - revs[0])
    grid = revs[0] + np.arange(n_revs * n_per_rev) / n_per_rev
    xa = scipy.interpolate.CubicSpline(tu, xu, axis=-1)(np.interp(grid, revs_u, tu))
    template = xa.reshape(*x.shape[:-1], n_revs, n_per_rev).mean(axis=-2)
    closed = np.concatenate((template, template[..., :1]), axis=-1)
    spline = scipy.interpolate.CubicSpline(np.arange(n_per_rev + 1) / n_per_rev, closed,
                                           axis=-1, bc_type="periodic")
    return spline(np.mod(revs - revs[0], 1.0))


def _lp(x: np.ndarray, order: int) -> np.ndarray:
    """Prediction error of a Yule-Walker AR(order) model of each row of ``x``."""
    out = np.empty_like(x)
    for idx in np.ndindex(x.shape[:-1]):
        row = x[idx] - x[idx].mean()
        spec = np.fft.rfft(row, n=2 * row.size)  # zero-padded: linear, not circular
        r = np.fft.irfft(np.abs(spec) ** 2)[:order + 1] / row.size
        if r[0] == 0.0:
            out[idx] = 0.0
            continue
        a = scipy.linalg.solve_toeplitz(r[:order], r[1:order + 1])
        err = np.concatenate(([1.0], -a))
        out[idx] = _signal.lfilter(err, [1.0], row)
        # the first samples have no full past: predict them backwards from the future
        # (the Yule-Walker model of a stationary signal is the same in both directions)
        out[idx][:order] = _signal.lfilter(err, [1.0], row[::-1])[::-1][:order]
    return out


def _overlap_correlation(nperseg: int, lag: int) -> float:
    """Normalized overlap sum w(n) w(n + lag) / sum w(n)^2 of the Hann window: the part
    of a white random signal that its own copy ``lag`` samples later shares within one
    Welch segment (0 from ``lag >= nperseg``)."""
    if lag >= nperseg:
        return 0.0
    w = _signal.get_window("hann", nperseg)
    return float(np.dot(w[lag:], w[:nperseg - lag]) / np.dot(w, w))


def _welch_averages(n_used: int, nperseg: int) -> tuple[int, float]:
    """(segments, equivalent independent averages) of a Welch estimate over ``n_used``
    samples with Hann segments of ``nperseg`` overlapping by 3/4: Welch (1967), K over
    1 + 2 sum_j (1 - j/K) rho_j^2 with rho_j the overlap correlation j steps apart."""
    step = nperseg // 4
    k = (n_used - nperseg) // step + 1
    rho2 = sum((1 - j / k) * _overlap_correlation(nperseg, j * step) ** 2
               for j in range(1, min(k, 4)))
    return k, k / (1 + 2 * rho2)


def _drs_gain(x: np.ndarray, nperseg: int, delay: int) -> np.ndarray:
    """Zero-phase DRS gain (..., nperseg // 2 + 1), the estimated fraction of each
    frequency's amplitude that is discrete: the coherence between ``x`` and its copy
    ``delay`` samples later, freed of its two biases for a random part (the 1/K of a
    K-average estimate and the window-overlap share of ``delay < nperseg``)."""
    n = x.shape[-1]
    a, b = x[..., delay:], x[..., :n - delay]
    kw = dict(nperseg=nperseg, noverlap=3 * nperseg // 4, window="hann", axis=-1)
    _f, s_ab = _signal.csd(a, b, **kw)
    _f, s_aa = _signal.welch(a, **kw)
    _f, s_bb = _signal.welch(b, **kw)
    tiny = np.finfo(float).tiny
    coh2 = np.abs(s_ab) ** 2 / np.maximum(s_aa * s_bb, tiny)
    _k, k_eff = _welch_averages(n - delay, nperseg)
    # an uncorrelated bin's squared coherence estimate averages 1/K_eff
    coh = np.sqrt(np.clip((coh2 - 1 / k_eff) / (1 - 1 / k_eff), 0.0, 1.0))
    # a random part shares rho of itself with its copy inside a segment when delay < nperseg
    rho = _overlap_correlation(nperseg, delay)
    return np.clip((coh - rho) / (1 - rho), 0.0, 1.0)


def _apply_gain(x: np.ndarray, gain: np.ndarray, nperseg: int) -> np.ndarray:
    """Each row of ``x`` through the zero-phase FIR filter of the gain (..., nperseg // 2
    + 1): odd length nperseg - 1, Hann-windowed, centred by "same" convolution."""
    half = nperseg // 2 - 1
    hh = np.fft.irfft(gain, n=nperseg, axis=-1)
    h = np.concatenate((hh[..., -half:], hh[..., :half + 1]), axis=-1) * np.hanning(2 * half + 1)
    if x.ndim == 1:
        return _signal.oaconvolve(x, h, mode="same")
    return np.stack([_signal.oaconvolve(x[idx], h[idx], mode="same")
                     for idx in np.ndindex(x.shape[:-1])]).reshape(x.shape)


def _drs_nperseg(fs: float, n: int) -> int:
    """Default Welch segment of DRS: the power of 2 nearest fs / 2 (a resolution of
    about 2 Hz, so that the Hann main lobe of 4 bins fits between the harmonics of a
    shaft down to ~8 Hz), but at most what leaves 4 segments (3/4 overlap) after a
    delay of one segment: 11/4 segments in the record."""
    return min(2 ** round(math.log2(fs / 2.0)), 2 ** math.floor(math.log2(n / 2.75)))


def separate_discrete(x, fs: float, rpm=None, method: str = "auto", *, tacho=None,
                      pulses_per_rev: int = 1, order: int = 100, nperseg: int | None = None,
                      delay: int | None = None, axis: int = -1) -> tuple[np.ndarray, np.ndarray]:
    """Split signals into their discrete (periodic, deterministic) and random parts.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s), any unit.
    fs : float
        Sampling frequency, Hz.
    rpm : float, array_like or sequence, optional
        Speed of the shaft(s) whose periodic parts are removed, rev/min (> 0): one
        number or profile (n_samples,) for one shaft, or a sequence of them, one per
        shaft (a gear pair turns two: each shaft's periodic part is removed in turn).
        Used by ``"tsa"``.
    method : {"auto", "tsa", "lp", "drs"}, optional
        See the module docstring. ``"auto"``: ``"tsa"`` with a speed or a tachometer,
        otherwise ``"drs"``.
    tacho : array_like (n_samples,), optional
        Tachometer of one shaft instead of ``rpm`` (``"tsa"``), ``pulses_per_rev``
        pulses per revolution.
    pulses_per_rev : int, optional
        Tachometer pulses per revolution (default 1).
    order : int, optional
        AR order of ``"lp"``, >= 1 (default 100, as Sawalhi & Randall use for gearbox
        signals).
    nperseg : int, optional
        Welch segment of ``"drs"``, >= 16 (default the power of 2 nearest fs / 2, a
        resolution of about 2 Hz, at most the power of 2 that leaves 4 segments after
        the delay: n_samples / 2.75). DRS must resolve the lines: shaft harmonics closer
        than about 4 fs / nperseg are only partly removed.
    delay : int, optional
        Delay of ``"drs"``, samples, >= 1, longer than the random part's memory
        (default nperseg: the segments of the signal and of its delayed copy share no
        sample). ``nperseg + delay + 3 * (nperseg // 4)`` must not exceed n_samples.
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    discrete, residual : ndarray, shape of ``x``
        ``discrete + residual == x``.

    Raises
    ------
    ValueError, TypeError
        Bad arguments, before any work: unknown method, ``"tsa"`` without a speed,
        a record shorter than two revolutions, ``"drs"`` with fewer than 4 Welch
        segments after its delay.

    Examples
    --------
    A 50 Hz shaft's harmonics plus white noise: the residual is the noise.

    >>> import numpy as np
    >>> from ballpass.features import separate_discrete
    >>> fs = 10_000.0
    >>> t = np.arange(20_000) / fs
    >>> periodic = np.sin(2 * np.pi * 50 * t) + 0.5 * np.sin(2 * np.pi * 450 * t)
    >>> noise = 0.1 * np.random.default_rng(0).standard_normal(t.size)
    >>> discrete, residual = separate_discrete(periodic + noise, fs, rpm=3000)
    >>> bool(np.std(residual - noise) < 0.2 * np.std(noise))
    True
    """
    fs = check_fs(fs)
    xv = check_signal(x, axis, min_samples=16)
    if not isinstance(method, str) or method not in SEPARATION_METHODS:
        raise ValueError(f"method must be one of {SEPARATION_METHODS}, got {method!r}")
    # every option is checked, also those the method does not use: a bad value is a
    # mistake to report, not to ignore
    order = check_positive_int("order", order, 1)
    if nperseg is not None:
        nperseg = check_positive_int("nperseg", nperseg, 16)
    if delay is not None:
        delay = check_positive_int("delay", delay, 1)
    n = xv.shape[-1]
    speeds = _speeds(rpm)
    if rpm is not None and tacho is not None:
        raise ValueError("give rpm or tacho, not both")
    if method == "auto":
        method = "tsa" if (speeds or tacho is not None) else "drs"
    if method == "tsa":
        if not speeds and tacho is None:
            raise ValueError("method='tsa' needs the shaft speed: give rpm (rev/min) or tacho")
        angles = ([shaft_revolutions(n, fs, rpm=s)[1] for s in speeds] if speeds else [None])
        if tacho is not None:
            t_p, r_p = shaft_revolutions(n, fs, tacho=tacho, pulses_per_rev=pulses_per_rev)
            angles = [scipy.interpolate.PchipInterpolator(t_p, r_p, extrapolate=True)(
                np.arange(n) / fs)]
        for revs in angles:
            if revs[-1] - revs[0] < 2.0:
                raise ValueError(f"method='tsa' needs at least 2 shaft revolutions in the "
                                 f"record, got {revs[-1] - revs[0]:.3g} (longer signal or "
                                 "higher rpm)")
        residual = xv.copy()
        for revs in angles:
            slowest = np.min(np.diff(revs)) * fs  # rev/s
            # at least the upsampled rate at the slowest speed: no angular aliasing
            n_per_rev = 2 * math.ceil(_TSA_UPSAMPLE * fs / (2 * slowest))
            residual = residual - _tsa_periodic(residual, fs, revs, n_per_rev)
    elif method == "lp":
        if order >= n // 2:
            raise ValueError(f"order must be < n_samples / 2 = {n // 2}, got {order}")
        residual = _lp(xv, order)
    else:
        if nperseg is None:
            nperseg = _drs_nperseg(fs, n)
            if nperseg < 16:
                raise ValueError(f"method='drs' needs at least 44 samples, got {n}")
        nperseg = check_positive_int("nperseg", nperseg, 16)
        delay = nperseg if delay is None else check_positive_int("delay", delay, 1)
        if nperseg + delay + 3 * (nperseg // 4) > n:
            raise ValueError(f"nperseg + delay + 3 * (nperseg // 4) (4 Welch segments after "
                             f"the delay) must not exceed n_samples = {n}, got nperseg = "
                             f"{nperseg}, delay = {delay}")
        residual = xv - _apply_gain(xv, _drs_gain(xv, nperseg, delay), nperseg)
    discrete = xv - residual
    return np.moveaxis(discrete, -1, axis), np.moveaxis(residual, -1, axis)


def check_separate(separate, other_shafts) -> str | None:
    """Validate the ``separate``/``other_shafts`` options of the diagnoser and the
    fault-band features; returns the method (``None`` = no separation)."""
    if separate is not False and separate is not True and separate not in ("tsa", "lp", "drs"):
        raise ValueError(f"separate must be False, True, 'tsa', 'lp' or 'drs', got {separate!r}")
    try:
        ratios = np.asarray(other_shafts, dtype=float).ravel()
    except (TypeError, ValueError):
        raise TypeError(f"other_shafts must be a sequence of speed ratios, got "
                        f"{other_shafts!r}") from None
    if not (np.isfinite(ratios).all() and (ratios > 0).all()):
        raise ValueError(f"other_shafts must be speed ratios > 0, got {other_shafts!r}")
    if separate is False:
        return None
    return "tsa" if separate is True else separate


def separated_rows(X: np.ndarray, fs: float, rpm_rows: np.ndarray, separate,
                   other_shafts=()) -> np.ndarray:
    """Residual of each row of ``X`` (n_signals, n_samples) after
    :func:`separate_discrete`: ``"tsa"`` removes the shaft at each row's rpm and the
    ``other_shafts`` (speed ratios to it); ``"lp"``/``"drs"`` need no speed. ``X``
    unchanged when ``separate`` is False."""
    method = check_separate(separate, other_shafts)
    if method is None:
        return X
    if method != "tsa":
        return separate_discrete(X, fs, method=method)[1]
    ratios = [1.0, *np.asarray(other_shafts, dtype=float).ravel()]
    return np.stack([separate_discrete(row, fs, rpm=[r * s for s in ratios])[1]
                     for row, r in zip(X, np.broadcast_to(rpm_rows, (len(X),)), strict=True)])
