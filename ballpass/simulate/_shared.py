"""Pieces every simulation model shares: solver-argument checks, the sensor's
anti-alias decimation and AC coupling, measurement noise, the ground-truth time base."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit
from scipy import signal as _signal

from .._warnings import warn_user
from ..scene import Scene

__all__ = [
    "SimulationUnstableError",
    "OVERSAMPLE",
    "check_solver_args",
    "to_output_rate",
    "add_noise",
    "check_finite",
    "divisor_step",
]

#: internal output rate = OVERSAMPLE * fs before the anti-alias decimation
OVERSAMPLE = 4


class SimulationUnstableError(RuntimeError):
    """The integration diverged (non-finite or unbounded state) or could not proceed.

    Examples
    --------
    Raised instead of returning non-finite samples; catch it to skip a scene of a sweep:

    >>> from ballpass.simulate import SimulationUnstableError
    >>> issubclass(SimulationUnstableError, RuntimeError)
    True
    """


def check_solver_args(model: str, solver: str, solvers: tuple[str, ...], fixed_step: tuple,
                      dt, rtol, atol, oversample) -> None:
    """Refuse solver options before any work: unknown solvers, out-of-range values and
    options the chosen solver would silently ignore.

    Parameters
    ----------
    model : str
        Model name, for the messages.
    solver : str
        Requested solver (``"auto"`` or a name).
    solvers : tuple of str
        Solvers the model supports.
    fixed_step : tuple of str
        Those of ``solvers`` that take ``dt``; the others are adaptive and take
        ``rtol``/``atol``.
    dt, rtol, atol, oversample
        As in :func:`ballpass.simulate.simulate`.
    """
    if not isinstance(solver, str) or solver not in ("auto", *solvers):
        raise ValueError(f"solver must be 'auto' or one of {list(solvers)} for model "
                         f"{model!r}, got {solver!r}")
    if dt is not None and not (isinstance(dt, (int, float)) and not isinstance(dt, bool)
                               and 1e-10 <= dt <= 1e-3):
        raise ValueError(f"dt must be a step size in [1e-10, 1e-3] s, got {dt!r}")
    if rtol is not None and not (isinstance(rtol, (int, float)) and 1e-13 <= rtol <= 1e-1):
        raise ValueError(f"rtol must be in [1e-13, 0.1], got {rtol!r}")
    if atol is not None and not (isinstance(atol, (int, float)) and atol > 0):
        raise ValueError(f"atol must be a positive number (scale factor), got {atol!r}")
    if not (isinstance(oversample, int) and 1 <= oversample <= 64):
        raise ValueError(f"oversample must be an int in [1, 64], got {oversample!r}")
    if solver == "auto":
        solver = solvers[0]  # the model's default: an option it would ignore is refused too
    adaptive = solver not in fixed_step
    if adaptive and dt is not None:
        raise ValueError(f"dt={dt!r} applies to the fixed-step solvers {list(fixed_step)}; "
                         f"solver {solver!r} chooses its own steps: give rtol/atol instead")
    if not adaptive and (rtol is not None or atol is not None):
        raise ValueError(f"rtol/atol apply to adaptive solvers; solver {solver!r} takes a "
                         "fixed step: give dt instead (or solver='dopri5')")


@lru_cache(maxsize=256)
def stiffness_and_load_zone(bearing, load_n: float, stiffness: float | None = None,
                            cage_angle_deg: float = 0.0):
    """K (``stiffness``, or the bearing's two Hertz contacts in series, N/m^n) and the
    Stribeck equilibrium under ``load_n`` (N) with an element at ``cage_angle_deg``
    (:meth:`ballpass.Bearing.load_distribution`): computed once per bearing, load,
    stiffness and cage angle in a process, as a dataset holds a few of each and many runs
    (read-only results)."""
    kh = stiffness or bearing.hertz_stiffness()
    return kh, bearing.load_distribution(load_n, stiffness=kh, cage_angle_deg=cage_angle_deg)


@lru_cache(maxsize=8)
def _antialias_taps(down: int) -> np.ndarray:
    """The low-pass FIR of ``scipy.signal.resample_poly(x, 1, down)``: 20 down + 1 taps,
    cut-off at the output Nyquist frequency, Kaiser window (beta 5)."""
    return _signal.firwin(20 * down + 1, 1.0 / down, window=("kaiser", 5.0))


@njit(cache=True, error_model="numpy")
def _decimate_line(x, h, down, y):
    """y[m] = sum_j h[j] x[down m + half - j] (half = (len(h) - 1) / 2) with x extended
    beyond its ends by the straight line through its first and last samples: what
    ``resample_poly(x, 1, down, padtype="line")`` computes, summed tap by tap over
    contiguous polyphase copies of x so that the loop over the outputs vectorises.
    ``y`` (ceil(len(x) / down),) is overwritten."""
    n = x.shape[0]
    n_h = h.shape[0]
    half = (n_h - 1) // 2
    slope = (x[n - 1] - x[0]) / (n - 1) if n > 1 else 0.0
    n_y = y.shape[0]
    n_ph = n_y + (2 * half) // down + 1
    # phases[r, i] = x_ext[down i + r], with x_ext[k + half] = x[k]
    phases = np.empty((down, n_ph))
    for r in range(down):
        for i in range(n_ph):
            k = down * i + r - half
            if k < 0:
                phases[r, i] = x[0] + k * slope
            elif k >= n:
                phases[r, i] = x[n - 1] + (k - n + 1) * slope
            else:
                phases[r, i] = x[k]
    for m in range(n_y):
        y[m] = 0.0
    for j in range(n_h):
        q, r = divmod(2 * half - j, down)
        hj = h[j]
        row = phases[r, q:q + n_y]
        for m in range(n_y):
            y[m] += hj * row[m]


def decimate(out: np.ndarray, oversample: int) -> np.ndarray:
    """Anti-alias decimation of internal-grid output (n_out, n_sensors) by
    ``oversample``: (n_sensors, ceil(n_out / oversample)).

    The result of ``scipy.signal.resample_poly(out, 1, oversample, axis=0,
    padtype="line")`` (the same filter and end extension; summed in another order, so
    equal to rounding, tests/test_sr5_fast_paths.py), in a third of its time.
    padtype="line" extends the record by its end trend instead of zeros, otherwise the
    sensor's DC level (a static load seen through the transfer path) rings the
    anti-alias filter into a spike on the first and last samples.
    """
    n_out, n_sensors = out.shape
    h = _antialias_taps(oversample)
    accel = np.empty((n_sensors, -(-n_out // oversample)))
    for i in range(n_sensors):
        _decimate_line(np.ascontiguousarray(out[:, i]), h, oversample, accel[i])
    return accel


def divisor_step(h_out: float, dt_req: float, dt) -> tuple[int, float]:
    """The fixed step of a solver that ends every step on the output grid.

    Parameters
    ----------
    h_out : float
        Spacing of the internal output grid, s.
    dt_req : float
        Step wanted, s: ``dt`` when given, else the model's default.
    dt : float or None
        The step the caller gave, s; a ``UserWarning`` (pointing at the caller of
        :func:`ballpass.simulate`) says so when it had to be rounded by more than 1e-6
        of itself.

    Returns
    -------
    n_sub : int
        Steps per output interval, ``ceil(h_out / dt_req)`` (1e-9 below it: a ``dt``
        meant as an exact divisor does not round up), at least 1.
    step : float
        ``h_out / n_sub``, s: the largest divisor of ``h_out`` not above ``dt_req``.
    """
    n_sub = max(1, math.ceil(h_out / dt_req - 1e-9))
    step = h_out / n_sub
    if dt is not None and abs(step - dt) > 1e-6 * dt:
        warn_user(f"dt={dt:g} s rounded to {step:.6g} s, a divisor of the internal output "
                  f"spacing {h_out:.6g} s; res.info['dt_s'] holds the step used")
    return n_sub, step

def to_output_rate(out: np.ndarray, n_samples: int, oversample: int) -> np.ndarray:
    """Internal-grid output (n_out, n_sensors) to what a sensor delivers: anti-alias
    decimation by ``oversample`` (:func:`decimate`) and AC coupling;
    (n_sensors, n_samples), m/s^2."""
    accel = decimate(out, oversample)[:, :n_samples] if oversample > 1 else out[:n_samples].T
    accel = accel.copy()
    accel -= accel.mean(axis=1, keepdims=True)  # AC-coupled accelerometers
    return accel


def add_noise(scene: Scene, accel: np.ndarray) -> np.ndarray:
    """Gaussian measurement noise from the scene's own noise stream (white, or coloured
    by ``noise_slope_db_oct``) and the shaft-rate lines of ``shaft_harmonics`` (see
    :mod:`.background`).

    Parameters
    ----------
    scene : Scene
        Gives ``snr_db`` or ``noise_rms`` and the seed (the second child of
        ``SeedSequence(scene.seed)``; the first drives the slip).
    accel : ndarray (n_sensors, n_samples)
        Noise-free signals, m/s^2.

    Returns
    -------
    ndarray (n_sensors, n_samples)
    """
    from .background import coloured_noise, shaft_lines

    accel = accel + shaft_lines(scene, accel.shape[-1]) if scene.shaft_harmonics else accel
    if scene.snr_db is None and scene.noise_rms is None:
        return accel
    _slip_seed, noise_seed = np.random.SeedSequence(scene.seed).spawn(2)
    rng = np.random.default_rng(noise_seed)
    if scene.noise_rms is not None:
        sigma = np.full((accel.shape[0], 1), scene.noise_rms)
    else:
        rms = np.sqrt(np.mean(accel**2, axis=1, keepdims=True))
        sigma = rms * 10.0 ** (-scene.snr_db / 20.0)
    return accel + sigma * coloured_noise(rng, accel.shape, scene.fs, scene.noise_slope_db_oct)


def check_finite(scene: Scene, accel: np.ndarray, model: str) -> None:
    """Raise :class:`SimulationUnstableError` if any output sample is not finite."""
    if not np.all(np.isfinite(accel)):
        raise SimulationUnstableError(f"model {model!r} produced non-finite output for "
                                      f"scene {scene!r}")
