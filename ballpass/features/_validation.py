"""Argument checks shared by the feature functions.

Every public function validates here, before any numerical work, and raises
``ValueError``/``TypeError`` naming the argument, its value and the allowed range.
"""

from __future__ import annotations

import math
import numbers

import numpy as np


def check_fs(fs) -> float:
    """Return ``fs`` as a float after checking it is a finite number > 0 (Hz)."""
    if isinstance(fs, bool) or not isinstance(fs, numbers.Real):
        raise TypeError(f"fs must be a number (Hz), got {type(fs).__name__} ({fs!r})")
    fs = float(fs)
    if not (math.isfinite(fs) and fs > 0):
        raise ValueError(f"fs must be a finite number > 0 Hz, got {fs!r}")
    return fs


def check_signal(x, axis: int = -1, *, name: str = "x", min_samples: int = 2,
                 nonempty: bool = False) -> np.ndarray:
    """Return ``x`` as a float64 array with the sample axis moved last.

    Raises ``TypeError`` for non-real input and ``ValueError`` for signals shorter
    than ``min_samples``, containing NaN/inf, or (``nonempty``) a batch of no signals.
    """
    arr = np.asarray(x)
    if arr.dtype == object or not (
        np.issubdtype(arr.dtype, np.floating) or np.issubdtype(arr.dtype, np.integer)
    ):
        raise TypeError(f"{name} must be a real numeric array, got dtype {arr.dtype}")
    if arr.ndim == 0:
        raise ValueError(f"{name} must have at least one dimension (the samples), got a scalar")
    if not isinstance(axis, numbers.Integral) or not -arr.ndim <= axis < arr.ndim:
        raise ValueError(f"axis must be an int in [{-arr.ndim}, {arr.ndim}), got {axis!r}")
    arr = np.moveaxis(arr.astype(np.float64, copy=False), axis, -1)
    if arr.shape[-1] < min_samples:
        raise ValueError(
            f"{name} must have at least {min_samples} samples along axis {axis}, "
            f"got {arr.shape[-1]}"
        )
    if nonempty and arr.size == 0:
        raise ValueError(f"{name} holds no signals (shape {np.shape(x)}): pass at least one")
    if arr.size and not np.isfinite(arr).all():
        raise ValueError(f"{name} contains NaN or inf; clean or interpolate the signal first")
    return arr



def check_signals(x) -> np.ndarray:
    """Return ``x`` of shape (n_samples,) or (n_signals, n_samples) as a float64 array
    of shape (n_signals, n_samples), checked as by :func:`check_signal`; a ValueError
    naming both shapes for more dimensions."""
    xv = np.atleast_2d(check_signal(x))
    if xv.ndim != 2:
        raise ValueError(f"x must be (n_signals, n_samples) or (n_samples,), got {xv.shape}")
    return xv

def to_unit_scale(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``x`` (samples last) scaled so that each signal's largest magnitude lies in
    [0.25, 1), and the exponent ``k`` (int, shape (..., 1)) with ``x = scaled * 2**k``.

    The factor is an even power of two, so the scaling (and a square root of it) is
    exact: results that do not depend on scale come out bit for bit the same at any
    scale, and a result in unit^p is ``np.ldexp(r, p * k)``, without the overflow or
    underflow of squaring a signal of 1e200 or 1e-300 on the way. An all-zero signal
    gets ``k = 0``.
    """
    peak = np.max(np.abs(x), axis=-1, keepdims=True) if x.size else np.zeros(x.shape[:-1] + (1,))
    _, k = np.frexp(peak)           # peak = m 2**k, m in [0.5, 1)
    k = np.where(peak > 0, k + k % 2, 0)
    return np.ldexp(x, -k), k


def from_unit_scale(r: np.ndarray, k: np.ndarray, power: int) -> np.ndarray:
    """A result ``r`` in unit^``power`` of signals scaled by :func:`to_unit_scale`, in
    the signals' own unit: exact, and inf only where the float range ends."""
    with np.errstate(over="ignore"):
        return np.ldexp(r, power * k)


#: Narrowest band accepted, as a fraction of fs. A 4th-order Butterworth band-pass
#: narrower than fs/1000 rings for thousands of samples and its second-order sections
#: lose precision; envelope analysis needs a band several times wider than the fault
#: frequencies it demodulates anyway (Randall & Antoni, MSSP 25 (2011) 485-520, sec. 3.2).
MIN_BAND_FRACTION = 1e-3


def check_band(band, fs: float) -> tuple[float, float]:
    """Return ``band`` as ``(lo, hi)`` floats with ``0 <= lo < hi <= fs/2`` (Hz) and
    ``hi - lo >= fs / 1000``."""
    try:
        lo, hi = (float(v) for v in band)
    except (TypeError, ValueError):
        raise TypeError(f"band must be a pair (lo, hi) in Hz or None, got {band!r}") from None
    nyquist = 0.5 * fs
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 <= lo < hi <= nyquist):
        raise ValueError(
            f"band must satisfy 0 <= lo < hi <= fs/2 = {nyquist:g} Hz, got ({lo:g}, {hi:g})"
        )
    if hi - lo < MIN_BAND_FRACTION * fs:
        raise ValueError(
            f"band must be at least fs/1000 = {MIN_BAND_FRACTION * fs:g} Hz wide (a narrower "
            f"band-pass is ill-conditioned and demodulates nothing), got ({lo:g}, {hi:g}): "
            f"{hi - lo:g} Hz"
        )
    return lo, hi


def check_positive_int(name: str, value, minimum: int, maximum: int | None = None) -> int:
    """Return ``value`` as an int after checking ``minimum <= value`` (``<= maximum``)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an int, got {type(value).__name__} ({value!r})")
    if value < minimum or (maximum is not None and value > maximum):
        span = f">= {minimum}" if maximum is None else f"in [{minimum}, {maximum}]"
        raise ValueError(f"{name} must be an int {span}, got {value!r}")
    return int(value)


#: Highest Butterworth order per band edge accepted: its second-order sections lose
#: their accuracy near 100 on narrow bands (the Parseval check of ``_sos`` refuses
#: them); checked first so that an order of 10**9 designs no filter (it exhausted memory)
MAX_FILTER_ORDER = 200


def check_flag(name: str, value) -> bool:
    """Return ``value`` after checking it is True or False (NumPy's too): "no" or 2 is
    a mistake, not a truthy value."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def check_nonnegative(name: str, value) -> float:
    """Return ``value`` as a float after checking it is finite and >= 0."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a number, got {type(value).__name__} ({value!r})")
    value = float(value)
    if not (math.isfinite(value) and value >= 0):
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return value


def check_rpm(rpm, shape: tuple[int, ...]) -> np.ndarray:
    """Return ``rpm`` (rev/min, > 0) broadcast to ``shape``, one speed per signal."""
    try:
        arr = np.asarray(rpm, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"rpm must be a number or an array of numbers, got {rpm!r}") from None
    if not (np.isfinite(arr).all() and (arr > 0).all()):
        raise ValueError(f"rpm must be finite and > 0 (rev/min), got {rpm!r}")
    try:
        return np.broadcast_to(arr, shape)
    except ValueError:
        raise ValueError(
            f"rpm must be a scalar or broadcast to the signals' leading shape {shape}, "
            f"got shape {arr.shape}"
        ) from None
