"""Statistical condition indicators of a vibration signal.

The time-domain statistics vibration engineers trend: level (RMS, peak,
peak-to-peak) and shape (crest factor, kurtosis, skewness, shape, impulse and
clearance factors). Kurtosis is Pearson's (3 for Gaussian noise, 1.5 for a sine), as
condition monitoring uses it, i.e. ``scipy.stats.kurtosis(fisher=False)``. The
faulty/healthy ratio of each indicator is the statistic of Nabhan & Rashed (2020) (an MSC-ADAMS
inner-race study, figs. 11-12): RMS ratios rise with speed and fault size, crest-factor
ratios may miss the fault.
"""

from __future__ import annotations

import numpy as np

from ._validation import check_signal, from_unit_scale, to_unit_scale

__all__ = ["INDICATORS", "indicators", "indicator_ratios"]

#: Names of the indicators, in the order :func:`indicators` returns them.
INDICATORS = (
    "rms",
    "peak",
    "peak_to_peak",
    "crest_factor",
    "kurtosis",
    "skewness",
    "shape_factor",
    "impulse_factor",
    "clearance_factor",
)


def indicators(x, *, axis: int = -1) -> dict[str, np.ndarray]:
    """Statistical indicators of each signal.

    With ``a = |x|`` and means over the samples:

    ======================  =======================================  =================
    ``rms``                 ``sqrt(mean(x^2))``                      unit of x
    ``peak``                ``max(a)``                               unit of x
    ``peak_to_peak``        ``max(x) - min(x)``                      unit of x
    ``crest_factor``        ``peak / rms``                           sine: sqrt(2)
    ``kurtosis``            ``mean((x-mu)^4) / sigma^4`` (Pearson)    Gaussian: 3
    ``skewness``            ``mean((x-mu)^3) / sigma^3``             symmetric: 0
    ``shape_factor``        ``rms / mean(a)``                        sine: pi/(2 sqrt 2)
    ``impulse_factor``      ``peak / mean(a)``                       sine: pi/2
    ``clearance_factor``    ``peak / mean(sqrt(a))^2``
    ======================  =======================================  =================

    RMS and the peak values include any mean (DC) of ``x``; kurtosis and skewness are
    central moments (biased estimators), computed as :func:`scipy.stats.kurtosis`
    (``fisher=False``) and :func:`scipy.stats.skew` compute them, to the last bit.

    A constant signal (all zeros: a dead or disconnected sensor) has no shape; its
    moments are 0/0. It gets, without NaN or warning: ``kurtosis = 0`` (a value no
    varying signal can take, since Pearson's kurtosis is >= 1: a marker of a dead
    channel), ``skewness = 0``, and crest, shape, impulse and clearance factors 1 (their
    value for any non-zero constant, kept as the constant shrinks to 0). A signal whose
    variance is lost in the rounding of its mean (``var <= (eps * mean)^2``, where
    scipy.stats returns NaN) gets ``kurtosis = skewness = 0`` too.

    The indicators are computed on a copy of each signal scaled exactly (by a power of
    two) to unit peak, so the shape indicators are the same at any scale (1e-300 or
    1e200 m/s^2) and the level ones are finite wherever the float range holds them.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s), e.g. acceleration in m/s^2. At least 2 samples, finite.
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    dict of str to ndarray of shape (...)
        One entry per name in :data:`INDICATORS`; NumPy scalars for a single signal.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import indicators
    >>> t = np.arange(1000) / 1000.0
    >>> ind = indicators(3.0 * np.sin(2 * np.pi * 5 * t))
    >>> round(float(ind["crest_factor"]), 4), round(float(ind["kurtosis"]), 4)
    (1.4142, 1.5)
    """
    return _indicators(check_signal(x, axis))


def _indicators(x: np.ndarray) -> dict[str, np.ndarray]:
    """:func:`indicators` of validated ``x`` (float64, samples last), computed on a copy
    scaled exactly to unit peak (:func:`to_unit_scale`): the same shape indicators at any
    scale (a signal of 1e200 squared overflows, one of 1e-300 underflows)."""
    x, k = to_unit_scale(x)
    a = np.abs(x)
    top, bottom = x.max(axis=-1), x.min(axis=-1)
    rms = np.sqrt(np.mean(x * x, axis=-1))
    peak = np.maximum(top, -bottom)
    mean_abs = a.mean(axis=-1)
    # Central moments as scipy.stats._moment forms them (exponentiation by squaring).
    mean = x.mean(axis=-1, keepdims=True)
    d = x - mean
    d2 = d * d
    m2 = d2.mean(axis=-1)
    m3 = (d2 * d).mean(axis=-1)
    m4 = (d2 * d2).mean(axis=-1)
    # scipy.stats's test for a variance lost in rounding (NaN there; 0 here, see above)
    shapeless = m2 <= (np.finfo(float).eps * mean[..., 0]) ** 2
    constant = top == bottom
    with np.errstate(divide="ignore", invalid="ignore"):
        out = {
            "rms": rms,
            "peak": peak,
            "peak_to_peak": top - bottom,
            "crest_factor": peak / rms,
            "kurtosis": np.where(shapeless, 0.0, m4 / m2**2.0),
            "skewness": np.where(shapeless, 0.0, m3 / m2**1.5),
            "shape_factor": rms / mean_abs,
            "impulse_factor": peak / mean_abs,
            "clearance_factor": peak / np.mean(np.sqrt(a), axis=-1) ** 2,
        }
    if constant.any():  # the convention of the docstring instead of 0/0
        for name in ("crest_factor", "shape_factor", "impulse_factor", "clearance_factor"):
            out[name] = np.where(constant, 1.0, out[name])
    for name in ("rms", "peak", "peak_to_peak"):   # back in the unit of x
        out[name] = from_unit_scale(out[name], k[..., 0], 1)
    return {name: value[()] for name, value in out.items()}


def indicator_ratios(faulty, healthy, *, axis: int = -1) -> dict[str, np.ndarray]:
    """Faulty/healthy ratio of each indicator (Nabhan & Rashed's detection statistic).

    A ratio well above 1 flags the fault; Nabhan & Rashed (2020) finds the RMS ratio the most
    reliable, the crest-factor ratio unreliable. Skewness is near 0 for a healthy
    bearing, so its ratio is unstable; it is returned for completeness.

    Parameters
    ----------
    faulty : array_like, shape (..., n_samples)
        Signal(s) of the bearing under test.
    healthy : array_like, shape (..., n_samples_h)
        Reference signal(s) of a healthy bearing at the same operating point; the
        leading shapes must broadcast, the lengths may differ.
    axis : int, optional
        Sample axis of both (default -1).

    Returns
    -------
    dict of str to ndarray
        ``indicators(faulty)[k] / indicators(healthy)[k]`` for each indicator ``k``.

    Raises
    ------
    ValueError
        A healthy indicator exactly 0 (a constant or all-zero reference, or a
        skewness of exactly 0): the ratio would be inf or NaN.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import indicator_ratios
    >>> rng = np.random.default_rng(0)
    >>> healthy = rng.standard_normal(10_000)
    >>> faulty = 2 * healthy
    >>> round(float(indicator_ratios(faulty, healthy)["rms"]), 6)
    2.0
    """
    num = indicators(faulty, axis=axis)
    den = indicators(healthy, axis=axis)
    zero = [name for name in INDICATORS if np.any(den[name] == 0)]
    if zero:
        raise ValueError(f"healthy has {', '.join(zero)} exactly 0 (a silent or constant "
                         "reference, or a perfectly symmetric one for skewness): the "
                         "faulty/healthy ratio is undefined")
    return {name: num[name] / den[name] for name in INDICATORS}
