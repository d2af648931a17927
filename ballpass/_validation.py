"""Scalar argument checks shared by the whole package.

Every public entry point validates its arguments here before any work, raising
``TypeError`` for a value of the wrong type and ``ValueError`` naming the argument, the
allowed range (with its unit) and the value it got.
"""

from __future__ import annotations

import math
import numbers


def check_number(name: str, value, lo: float = -math.inf, hi: float = math.inf, *,
                 lo_open: bool = False, hi_open: bool = False, unit: str = "") -> float:
    """Return ``value`` as a float after checking it is a finite real in the range.

    Parameters
    ----------
    name : str
        Argument name used in the error message.
    value : real
        The value (Python or NumPy real; ``bool`` is refused).
    lo, hi : float, optional
        Bounds of the allowed range (default: unbounded).
    lo_open, hi_open : bool, optional
        Exclude the bound itself.
    unit : str, optional
        Unit named in the message.

    Returns
    -------
    float

    Examples
    --------
    >>> check_number("rpm", 1797, 0.0, 1e5, lo_open=True)
    1797.0
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a number, got {type(value).__name__} ({value!r})")
    value = float(value)
    lo_ok = value > lo if lo_open else value >= lo
    hi_ok = value < hi if hi_open else value <= hi
    if math.isfinite(value) and lo_ok and hi_ok:
        return value
    where = f" {unit}" if unit else ""
    if math.isinf(hi) and math.isinf(lo):
        allowed = "a finite number"
    elif math.isinf(hi):
        allowed = f"a finite number {'>' if lo_open else '>='} {lo:g}"
    else:
        allowed = (f"a finite number in {'(' if lo_open else '['}{lo:g}, {hi:g}"
                   f"{')' if hi_open else ']'}")
    raise ValueError(f"{name} must be {allowed}{where}, got {value!r}")


#: Fewest samples a segment (a dataset row, a ``--segment`` piece) may hold: below this a
#: spectrum, an envelope or a kurtosis estimate has nothing to work on.
MIN_SEGMENT_SAMPLES = 64


def check_segment(segment_s, fs: float, name: str = "segment_s") -> int:
    """Samples per segment of ``segment_s`` seconds at ``fs`` Hz, at least 64.

    Examples
    --------
    >>> check_segment(0.5, 12_000.0)
    6000
    """
    if isinstance(segment_s, bool) or not isinstance(segment_s, numbers.Real) or not (
            math.isfinite(segment_s) and segment_s > 0):
        raise ValueError(f"{name} must be a finite number > 0 s, got {segment_s!r}")
    length = round(segment_s * fs)
    if length < MIN_SEGMENT_SAMPLES:
        raise ValueError(f"{name} must give at least {MIN_SEGMENT_SAMPLES} samples per "
                         f"segment (a spectrum needs them), got {segment_s!r} s x {fs:g} Hz "
                         f"= {segment_s * fs:g}")
    return length
