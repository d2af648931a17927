"""Order tracking: resample signals from uniform time to uniform shaft angle.

Fault frequencies are fixed multiples (orders) of the shaft speed. During a run-up
they sweep in Hz, and a spectrum in Hz smears each line over the speed range.
Resampled at uniform shaft angle ("computed order tracking"), the same signal shows
sharp lines at constant orders. For envelope analysis the structural resonance stays
fixed in Hz, so the envelope is formed in the time domain first and only the envelope
is resampled (Borghesani et al. 2013, section 2; Randall & Antoni 2011, section 5).

References
----------
.. [1] K. R. Fyfe, E. D. S. Munck, "Analysis of computed order tracking", MSSP 11
   (1997) 187-205 (angle from tachometer pulses, interpolation, resampling).
.. [2] P. Borghesani et al., MSSP 36 (2013) 370-384.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.integrate
import scipy.interpolate

from .._resources import available_memory, human_bytes
from ._validation import check_fs, check_positive_int, check_signal
from .envelope import _amplitude_spectrum, _checked_envelope

__all__ = ["shaft_revolutions", "order_track", "order_envelope_spectrum"]


def _pulse_times(tacho: np.ndarray, fs: float) -> np.ndarray:
    """Rising crossings of the mid level of a pulse train, s (linear sub-sample)."""
    level = 0.5 * (tacho.max() + tacho.min())
    i = np.flatnonzero((tacho[:-1] < level) & (tacho[1:] >= level))
    frac = (level - tacho[i]) / (tacho[i + 1] - tacho[i])
    return (i + frac) / fs


def shaft_revolutions(n_samples: int, fs: float, *, rpm=None, tacho=None, pulses_per_rev=1):
    """Shaft angle against time, in revolutions, from an rpm profile or a tachometer.

    Parameters
    ----------
    n_samples : int
        Number of samples of the signal the angle belongs to.
    fs : float
        Sampling frequency, Hz.
    rpm : float or array_like of shape (n_samples,), optional
        Shaft speed, rev/min, > 0: a constant or a profile sampled with the signal.
        The angle is its time integral (trapezoidal rule), starting at 0.
    tacho : array_like of shape (n_samples,), optional
        Tachometer (once-per-revolution or ``pulses_per_rev`` per revolution) signal,
        any unit. The rising crossings of its mid level mark the pulses; pulse ``k``
        is at ``k / pulses_per_rev`` revolutions. Give ``rpm`` or ``tacho``.
    pulses_per_rev : int, optional
        Tachometer pulses per shaft revolution (default 1).

    Returns
    -------
    t : ndarray, shape (n_points,)
        Times at which the angle is known, s: every sample for ``rpm``, the pulses for
        ``tacho``.
    revs : ndarray, shape (n_points,)
        Shaft angle at ``t``, revolutions, increasing.

    Examples
    --------
    >>> from ballpass.features import shaft_revolutions
    >>> t, revs = shaft_revolutions(1001, 1000.0, rpm=600.0)     # 10 rev/s for 1 s
    >>> round(float(revs[-1]), 9)
    10.0
    """
    fs = check_fs(fs)
    n_samples = check_positive_int("n_samples", n_samples, 2)
    pulses_per_rev = check_positive_int("pulses_per_rev", pulses_per_rev, 1)
    if (rpm is None) == (tacho is None):
        raise ValueError("give exactly one of rpm (rev/min) and tacho (pulse signal)")
    if rpm is not None:
        try:
            speed = np.asarray(rpm, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"rpm must be a number or an array of numbers, got {rpm!r}") \
                from None
        if speed.ndim == 0:
            speed = np.full(n_samples, float(speed))
        if speed.shape != (n_samples,):
            raise ValueError(
                f"rpm must be a number or an array of n_samples = {n_samples} values, "
                f"got shape {speed.shape}"
            )
        if not (np.isfinite(speed).all() and (speed > 0).all()):
            raise ValueError("rpm must be finite and > 0 (rev/min) throughout")
        revs = scipy.integrate.cumulative_trapezoid(speed / 60.0, dx=1.0 / fs, initial=0.0)
        return np.arange(n_samples) / fs, revs
    tacho = check_signal(tacho, name="tacho")
    if tacho.shape != (n_samples,):
        raise ValueError(f"tacho must have shape (n_samples,) = ({n_samples},), got {tacho.shape}")
    t = _pulse_times(tacho, fs)
    if t.size < 3:
        raise ValueError(f"tacho must contain at least 3 pulses, found {t.size}")
    return t, np.arange(t.size) / pulses_per_rev


def order_track(
    x,
    fs: float,
    *,
    rpm=None,
    tacho=None,
    pulses_per_rev: int = 1,
    samples_per_rev: int | None = None,
    axis: int = -1,
) -> tuple[np.ndarray, np.ndarray]:
    """Resample signals at uniform shaft angle (computed order tracking).

    The time of each uniform angle step is interpolated from the shaft angle
    (linearly for an rpm profile, monotone cubic (PCHIP) between tachometer pulses);
    the signal is then evaluated there by cubic-spline interpolation. With a
    tachometer only the span between the first and last pulse is returned.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s) sharing one shaft, any unit.
    fs : float
        Sampling frequency, Hz.
    rpm, tacho, pulses_per_rev
        Shaft speed; see :func:`shaft_revolutions`.
    samples_per_rev : int, optional
        Angular sampling rate, samples per revolution. Default
        ``ceil(fs / lowest shaft speed in Hz)``, so that no part of the record is
        sampled more coarsely than in time (no aliasing).
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    revs : ndarray, shape (n_angles,)
        Shaft angle of each output sample, revolutions (uniform).
    x_angle : ndarray, shape (..., n_angles)
        Signal(s) at those angles.

    Examples
    --------
    A tone at order 3 during a run-up from 10 to 20 rev/s becomes a sampled cosine
    with exactly 3 cycles per revolution:

    >>> import numpy as np
    >>> from ballpass.features import order_track, shaft_revolutions
    >>> fs = 5000.0
    >>> rpm = np.linspace(600, 1200, 10_000)
    >>> t, revs = shaft_revolutions(rpm.size, fs, rpm=rpm)
    >>> x = np.cos(2 * np.pi * 3 * revs)
    >>> r, xa = order_track(x, fs, rpm=rpm, samples_per_rev=64)
    >>> bool(np.allclose(xa, np.cos(2 * np.pi * 3 * r), atol=1e-4))
    True
    """
    fs = check_fs(fs)
    xv = check_signal(x, axis)
    grid, x_angle, _ = _order_track(xv, fs, rpm, tacho, pulses_per_rev, samples_per_rev)
    return grid, np.moveaxis(x_angle, -1, axis)


def _order_track(xv, fs, rpm, tacho, pulses_per_rev, samples_per_rev):
    """:func:`order_track` on validated ``xv`` (samples last); also returns the rate."""
    n = xv.shape[-1]
    t, revs = shaft_revolutions(n, fs, rpm=rpm, tacho=tacho, pulses_per_rev=pulses_per_rev)
    max_rev_time = np.max(np.diff(t) / np.diff(revs))  # s per revolution, slowest
    default = math.ceil(fs * max_rev_time)
    samples_per_rev = check_positive_int(
        "samples_per_rev", default if samples_per_rev is None else samples_per_rev, 2)
    n_out = math.floor((revs[-1] - revs[0]) * samples_per_rev) + 1
    # the angle grid, its times and each output row with the spline's temporaries
    needed = 8 * n_out * (2 + 4 * math.prod(xv.shape[:-1]))
    if needed > available_memory():   # before anything that size is built
        raise ValueError(
            f"samples_per_rev={samples_per_rev} gives {n_out:,} samples per signal "
            f"({human_bytes(needed)} to compute), more than the "
            f"{human_bytes(available_memory())} of memory available; the default, "
            f"{default}, samples the slowest revolution as finely as the signal does")
    grid = revs[0] + np.arange(n_out) / samples_per_rev
    if tacho is None:
        t_grid = np.interp(grid, revs, t)
    else:
        t_grid = scipy.interpolate.PchipInterpolator(revs, t)(grid)
    spline = scipy.interpolate.CubicSpline(np.arange(n) / fs, xv, axis=-1)
    return grid, spline(t_grid), samples_per_rev


def order_envelope_spectrum(
    x,
    fs: float,
    *,
    rpm=None,
    tacho=None,
    pulses_per_rev: int = 1,
    samples_per_rev: int | None = None,
    band=None,
    squared: bool = True,
    prewhiten: bool = False,
    window="hann",
    order: int = 4,
    axis: int = -1,
) -> tuple[np.ndarray, np.ndarray]:
    """(Squared) envelope spectrum in shaft orders, for variable speed.

    The envelope is formed in time (band-pass around the resonance, which is fixed in
    Hz, then Hilbert), resampled at uniform shaft angle with :func:`order_track`, and
    its amplitude spectrum taken as in :func:`ballpass.features.envelope_spectrum`.
    A fault line sits at its order (e.g. BPFO / shaft speed = 3.5848 for a 6205)
    whatever the speed profile.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s), e.g. acceleration in m/s^2.
    fs : float
        Sampling frequency, Hz.
    rpm, tacho, pulses_per_rev, samples_per_rev
        Shaft speed and angular sampling; see :func:`order_track`.
    band, squared, prewhiten, window, order
        As in :func:`ballpass.features.envelope_spectrum` (band in Hz).
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    orders : ndarray, shape (n_angles // 2 + 1,)
        Orders (cycles per shaft revolution); resolution ``1 / revolutions``.
    amplitude : ndarray, shape (..., n_angles // 2 + 1)
        One-sided amplitude, unit^2 (squared) or unit.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import order_envelope_spectrum, shaft_revolutions
    >>> fs = 12_000.0
    >>> rpm = np.linspace(900, 1800, 24_000)                  # run-up over 2 s
    >>> t, revs = shaft_revolutions(rpm.size, fs, rpm=rpm)
    >>> am = 1 + 0.5 * np.cos(2 * np.pi * 3.5 * revs)          # modulation at order 3.5
    >>> x = am * np.sin(2 * np.pi * 3000 * t)
    >>> o, amp = order_envelope_spectrum(x, fs, rpm=rpm, band=(2000, 4000))
    >>> round(float(o[np.argmax(amp)]), 1)
    3.5
    """
    fs, e, restore = _checked_envelope(x, fs, band, squared, prewhiten, order, None, axis)
    _, e_angle, spr = _order_track(e, fs, rpm, tacho, pulses_per_rev, samples_per_rev)
    orders, amp = _amplitude_spectrum(e_angle, window, float(spr))
    return orders, restore(amp)
