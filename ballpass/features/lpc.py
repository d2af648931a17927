"""All-pole (autoregressive, linear-prediction) models of a signal's spectrum.

A stationary signal that is a structure's response to broadband excitation has the
spectrum of the structure's transmission path; an autoregressive model of order p,

    x[n] = -a_1 x[n-1] - ... - a_p x[n-p] + e[n],    e white of variance sigma^2,

fits that spectrum with p poles, ``sigma^2 / |A(e^{jw})|^2``: the resonances of the path
are the poles of ``1 / A(z)``. The coefficients come from the autocorrelation method
(the Yule-Walker equations, solved by the Levinson-Durbin recursion), which always
gives a stable filter; the order is the minimum of Akaike's information criterion,
``N ln sigma_p^2 + 2 p`` (Akaike 1974), up to a cap set by the sampling rate.

References: J. Makhoul, "Linear prediction: a tutorial review", Proc. IEEE 63 (1975)
561-580; H. Akaike, "A new look at the statistical model identification", IEEE Trans.
Automatic Control 19 (1974) 716-723; N. Sawalhi, R. B. Randall, "Spectral kurtosis
enhancement using autoregressive models", ACAM 2005 (AR models of healthy bearing
signals).

Examples
--------
>>> import numpy as np, scipy.signal
>>> from ballpass.features.lpc import ar_fit, ar_resonances
>>> f_n, zeta, fs = 3000.0, 0.02, 48_000.0           # one mode: Hz, damping ratio, Hz
>>> pole = np.exp(2 * np.pi * f_n / fs * (-zeta + 1j * np.sqrt(1 - zeta**2)))
>>> a = np.poly([pole, pole.conjugate()]).real
>>> x = scipy.signal.lfilter([1.0], a, np.random.default_rng(0).normal(size=200_000))
>>> coeffs, sigma2 = ar_fit(x, 2)
>>> freq, damping = ar_resonances(coeffs, fs)
>>> round(float(freq[0])), round(float(damping[0]), 3)
(3000, 0.02)
"""

from __future__ import annotations

import math

import numpy as np

from .._validation import check_number

__all__ = ["autocorrelation", "levinson", "ar_fit", "ar_order", "ar_resonances",
           "MAX_ORDER_PER_HZ"]

#: order cap of :func:`ar_order` per Hz of sampling rate: one pole per kHz, i.e. one
#: resonance (a pole pair) per 2 kHz of sampling rate, per 1 kHz of the band 0-fs/2.
#: Akaike's criterion on a few seconds of a real recording keeps falling with the order
#: (it fits the spectrum's fine structure, shaft lines included); modes closer than
#: about 1 kHz are not told apart in the demodulation bands envelope analysis uses
#: (Randall & Antoni, MSSP 2011: bands of a few kHz around a resonance).
MAX_ORDER_PER_HZ = 1e-3


def autocorrelation(x: np.ndarray, max_lag: int) -> np.ndarray:
    """Biased autocorrelation ``r[k] = sum_n x[n] x[n+k] / N`` of a mean-removed signal.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        Signal, any unit u.
    max_lag : int
        Largest lag, samples (0 <= max_lag < n_samples).

    Returns
    -------
    ndarray, shape (max_lag + 1,)
        r[0..max_lag], u^2. The biased estimate keeps the Toeplitz matrix positive
        definite, so the fitted filter is stable (Makhoul 1975).
    """
    x = np.asarray(x, dtype=float)
    x = x - x.mean()
    n = x.size
    size = 1 << int(math.ceil(math.log2(2 * n)))   # zero-padded: a linear correlation
    spectrum = np.fft.rfft(x, size)
    return np.fft.irfft(spectrum.real**2 + spectrum.imag**2, size)[:max_lag + 1] / n


def levinson(r: np.ndarray, order: int) -> tuple[np.ndarray, np.ndarray]:
    """Levinson-Durbin recursion over the Yule-Walker equations.

    Parameters
    ----------
    r : ndarray, shape (>= order + 1,)
        Autocorrelation r[0..order], r[0] > 0.
    order : int
        Model order p >= 1.

    Returns
    -------
    a : ndarray, shape (order + 1,)
        ``A(z)`` coefficients, ``a[0] = 1``.
    errors : ndarray, shape (order + 1,)
        Prediction-error variance of every order 0..p (``errors[0] = r[0]``), u^2.
    """
    a = np.array([1.0])
    err = float(r[0])
    errors = [err]
    for p in range(1, order + 1):
        k = -(r[p] + a[1:] @ r[p - 1:0:-1]) / err
        a = np.concatenate([a, [0.0]])
        a = a + k * a[::-1]
        err *= 1.0 - k * k
        errors.append(err)
    return a, np.asarray(errors)


def _check_signal(x, name: str = "x") -> np.ndarray:
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or x.size < 16:
        raise ValueError(f"{name} must be one signal of at least 16 samples, got shape "
                         f"{x.shape}")
    if not np.isfinite(x).all():
        raise ValueError(f"{name} holds NaN or infinite samples")
    if not np.ptp(x) > 0:
        raise ValueError(f"{name} is constant: it has no spectrum to fit")
    return x


def ar_fit(x, order: int) -> tuple[np.ndarray, float]:
    """All-pole model of order ``order`` of a signal (autocorrelation method).

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        Signal, any unit u (its mean is removed).
    order : int
        Model order p, 1 <= p < n_samples / 2.

    Returns
    -------
    a : ndarray, shape (order + 1,)
        ``A(z) = a[0] + a[1] z^-1 + ...``, ``a[0] = 1``; ``scipy.signal.lfilter([1], a, e)``
        drives the model with ``e``.
    sigma2 : float
        Variance of the prediction error (the white excitation that reproduces the
        signal's power through ``1 / A(z)``), u^2.

    Raises
    ------
    ValueError
        ``order`` out of range, or ``x`` is not a finite, non-constant 1-D signal.
    """
    x = _check_signal(x)
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or not (
            1 <= order < x.size // 2):
        raise ValueError(f"order must be an int in [1, {x.size // 2 - 1}] (below half the "
                         f"{x.size} samples), got {order!r}")
    a, errors = levinson(autocorrelation(x, int(order)), int(order))
    return a, float(errors[-1])


def ar_order(x, fs: float, max_order: int | None = None) -> int:
    """Order of the all-pole model of ``x`` by Akaike's information criterion.

    ``AIC(p) = N ln sigma_p^2 + 2 p`` over ``p = 1 .. max_order`` (Akaike 1974), its
    minimum; the prediction errors of all orders come from one Levinson-Durbin pass.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        Signal.
    fs : float
        Sampling frequency, Hz.
    max_order : int, optional
        Largest order tried; default ``round(fs * MAX_ORDER_PER_HZ)`` (51 at 51.2 kHz,
        12 at 12 kHz), at least 2, and below half the samples.

    Returns
    -------
    int
        The order, in [1, max_order].
    """
    x = _check_signal(x)
    check_number("fs", fs, 0.0, lo_open=True, unit="Hz")
    cap = max(2, round(fs * MAX_ORDER_PER_HZ)) if max_order is None else max_order
    if isinstance(cap, bool) or not isinstance(cap, (int, np.integer)) or cap < 1:
        raise ValueError(f"max_order must be an int >= 1, got {max_order!r}")
    cap = min(int(cap), x.size // 2 - 1)
    _, errors = levinson(autocorrelation(x, cap), cap)
    p = np.arange(1, cap + 1)
    aic = x.size * np.log(errors[1:]) + 2 * p
    return int(p[np.argmin(aic)])


def ar_resonances(a, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """Natural frequencies and damping ratios of the poles of ``1 / A(z)``.

    A pole ``z = exp(s / fs)`` with ``s = -zeta w_n + j w_n sqrt(1 - zeta^2)`` is a mode
    of natural frequency ``w_n = |s|`` and damping ratio ``zeta = -Re(s) / |s|`` (the
    impulse-invariant map of a second-order system).

    Parameters
    ----------
    a : array_like, shape (p + 1,)
        ``A(z)`` coefficients, ``a[0] = 1``.
    fs : float
        Sampling frequency, Hz.

    Returns
    -------
    freq_hz : ndarray
        Natural frequency of each pole pair (and real pole), ascending, Hz.
    damping : ndarray
        Damping ratio of each, same order (1 for a real positive pole).
    """
    check_number("fs", fs, 0.0, lo_open=True, unit="Hz")
    roots = np.roots(np.asarray(a, dtype=float))
    roots = roots[roots.imag >= 0]
    s = np.log(roots.astype(complex)) * fs
    freq = np.abs(s) / (2 * np.pi)
    damping = -s.real / np.abs(s)
    order = np.argsort(freq)
    return freq[order], damping[order]
