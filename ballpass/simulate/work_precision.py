"""Work against precision: wall time and error of every solver on one scene.

:func:`work_precision` integrates a scene with each ballpass solver over a sweep of
step sizes / tolerances and with scipy's ``solve_ivp`` methods on the same equations
(:meth:`BearingModel.rhs`, the full state with the resonators), and measures the error
of what users look at against a reference solution at tight tolerance:

* ``error_l2``: relative L2 error of the output acceleration (all sensors, after the
  anti-alias decimation and AC coupling of :func:`ballpass.simulate`, without noise);
* ``error_ses``: largest error of the squared-envelope-spectrum (SES) amplitudes at the
  scene's fault lines (harmonics 1-3 of BPFO, BPFI or the ball-defect frequency; all
  three for a healthy bearing), relative to the tallest of those lines;
* ``error_ses_db``: largest change of the fault-band levels of
  :func:`ballpass.features.fault_band_features` at those lines, dB.

Both use a fixed demodulation band around the structural resonance, so every method is
judged on the same filter. Every integration, scipy's included, is restarted at the
same non-smooth points (fault edges and slip-walk knots; ballpass splits its steps
there): scipy is given the event handling it lacks, not handicapped by it.

Timing: ballpass rows time :func:`ballpass.simulate.integrate` (event search included),
best of ``repeats``; scipy rows time the stepping and the dense output at the grid
points, once (they take seconds to minutes), and stop a method's sweep when one run
exceeds ``scipy_time_limit``.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

import numpy as np

from ..scene import Scene
from . import _kernels as _K
from ._shared import OVERSAMPLE
from ._shared import to_output_rate as _to_output_rate
from ._sr5_driver import _core_omega, _rk4_grid, _split_times, build, integrate

if TYPE_CHECKING:  # pandas is imported when a table is made, not with the simulator
    import pandas as pd

__all__ = ["work_precision", "speedup", "plot_work_precision", "SCIPY_METHODS"]

#: scipy.integrate.solve_ivp methods compared by default
SCIPY_METHODS = ("RK45", "DOP853", "LSODA", "Radau")
#: RK4 steps swept by default, as omega_contact * dt (rounded to the output grid)
RK4_OMEGA_DT = (0.05, 0.1, 0.15, 0.2, 0.25, 0.35, 0.5, 0.7)
#: dopri5 tolerances swept by default
DOPRI5_RTOL = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
#: scipy tolerances swept by default (atol = rtol times each state's scale)
SCIPY_RTOL = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
#: reference: ballpass dopri5 at this tolerance
REFERENCE_RTOL = 1e-10
#: relative half-width of the window in which an SES line is read (1 % slip)
LINE_TOLERANCE = 0.01
#: harmonics of each fault line that are compared
HARMONICS = 3

COLUMNS = ["method", "family", "setting", "dt_s", "rtol", "wall_s", "wall_per_sim_s",
           "n_steps", "n_rhs", "error_l2", "error_ses", "error_ses_db", "status"]


def _fault_lines(scene: Scene) -> list[str]:
    """Names of :class:`ballpass.bearing.BearingFrequencies` attributes to compare."""
    by_kind = {"outer": "bpfo", "inner": "bpfi", "ball": "ball_defect"}
    kinds = {f.kind for f in scene.faults} or set(by_kind)
    return [by_kind[k] for k in sorted(kinds)]


class _Judge:
    """Errors of an internal-grid output against the reference, as the module
    docstring defines them."""

    def __init__(self, scene: Scene, reference: np.ndarray, oversample: int):
        from ..features import envelope_spectrum, fault_band_features

        self._ses = envelope_spectrum
        self._bands = fault_band_features
        self.scene = scene
        self.oversample = oversample
        self.band = scene.demodulation_band
        freqs = scene.frequencies
        self.targets = [h * getattr(freqs, name) for name in _fault_lines(scene)
                        for h in range(1, HARMONICS + 1)]
        self.level_names = [f"{name}_{h}" for name in _fault_lines(scene)
                            for h in range(1, HARMONICS + 1)]
        self.ref = self.accel(reference)
        self.ref_lines = self.lines(self.ref)
        self.ref_levels = self.levels(self.ref)

    def accel(self, out: np.ndarray) -> np.ndarray:
        return _to_output_rate(out, self.scene.n_samples, self.oversample)

    def lines(self, accel: np.ndarray) -> np.ndarray:
        """SES amplitude at each target line (largest value in a +-1 % window)."""
        f, ses = self._ses(accel, self.scene.fs, band=self.band)
        df = f[1]
        amps = []
        for target in self.targets:
            lo = max(1, math.floor(target * (1 - LINE_TOLERANCE) / df))
            hi = max(lo, min(f.size - 1, math.ceil(target * (1 + LINE_TOLERANCE) / df)))
            amps.append(ses[..., lo:hi + 1].max(axis=-1) if lo < f.size else
                        np.zeros(ses.shape[:-1]))
        return np.stack(amps, axis=-1)

    def levels(self, accel: np.ndarray) -> np.ndarray:
        feats = self._bands(accel, self.scene.fs, self.scene.bearing,
                            self.scene.speed.mean_rpm, band=self.band, harmonics=HARMONICS,
                            tolerance=LINE_TOLERANCE)
        return np.stack([np.asarray(feats[name], dtype=float) for name in self.level_names],
                        axis=-1)

    def errors(self, out: np.ndarray) -> tuple[float, float, float]:
        accel = self.accel(out)
        e_l2 = float(np.linalg.norm(accel - self.ref) / np.linalg.norm(self.ref))
        lines = self.lines(accel)
        scale = np.max(self.ref_lines, axis=-1, keepdims=True)
        e_ses = float(np.max(np.abs(lines - self.ref_lines) / scale))
        e_db = float(np.nanmax(np.abs(self.levels(accel) - self.ref_levels)))
        return e_l2, e_ses, e_db


def _grid(scene: Scene, oversample: int) -> tuple[float, int]:
    """Internal output grid of :func:`ballpass.simulate`: spacing (s) and length."""
    return 1.0 / (scene.fs * oversample), scene.n_samples * oversample


def _ballpass_row(bm, solver, judge, h_out, n_out, repeats, *, dt=None, rtol=None) -> dict:
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        raw = integrate(bm, solver, h_out=h_out, n_out=n_out, dt=dt, rtol=rtol)
        best = min(best, time.perf_counter() - t0)
    e_l2, e_ses, e_db = judge.errors(raw.output)
    info = raw.info
    per_step = 4 if solver == "rk4" else 6
    n_rhs = per_step * (info["n_steps"] + info["n_rejected"])
    setting = f"dt={info['dt_s']:.3g} s" if solver == "rk4" else f"rtol={rtol:g}"
    return dict(method=f"ballpass {solver}", family="ballpass", setting=setting,
                dt_s=info.get("dt_s", math.nan), rtol=math.nan if rtol is None else rtol,
                wall_s=best, n_steps=info["n_steps"], n_rhs=n_rhs, error_l2=e_l2,
                error_ses=e_ses, error_ses_db=e_db, status="ok")


def _scipy_run(bm, method, rtol, h_out, n_out, time_limit):
    """Integrate the full state with a scipy solver, restarted at the split times, and
    return (grid output, wall time, steps, rhs evaluations, status)."""
    from scipy import integrate as si

    solver_cls = getattr(si, method)  # the OdeSolver classes solve_ivp runs
    t_end = (n_out - 1) * h_out
    before, after = _split_times(bm, t_end)
    breaks = np.concatenate(([0.0], before, [t_end]))
    resumes = np.concatenate(([0.0], after))
    t_grid = np.arange(n_out) * h_out
    states = np.empty((n_out, bm.n_state))
    atol = rtol * bm.scale
    y = bm.y0.copy()
    states[0] = y
    k_next = 1
    n_steps = n_rhs = 0
    t_start = time.perf_counter()
    for a, b in zip(resumes, breaks[1:], strict=True):
        if b <= a:
            continue
        solver = solver_cls(bm.rhs, a, y, b, rtol=rtol, atol=atol)
        while solver.status == "running":
            if solver.step() is not None or solver.status == "failed":
                return None, time.perf_counter() - t_start, n_steps, n_rhs, "failed"
            n_steps += 1
            k_stop = k_next
            while k_stop < n_out and t_grid[k_stop] <= solver.t:
                k_stop += 1
            if k_stop > k_next:
                dense = solver.dense_output()
                states[k_next:k_stop] = dense(t_grid[k_next:k_stop]).T
                k_next = k_stop
            if time.perf_counter() - t_start > time_limit:
                return None, time.perf_counter() - t_start, n_steps, n_rhs, "time limit"
        n_rhs += solver.nfev  # finite-difference Jacobian columns included
        y = solver.y
    wall = time.perf_counter() - t_start
    out = _K.sensor_output_many(t_grid, states, *bm.model, bm.n_res)
    return out, wall, n_steps, n_rhs, "ok"


def work_precision(scene: Scene, *, model: str = "auto", rk4_dt=None, dopri5_rtol=DOPRI5_RTOL,
                   scipy_methods=SCIPY_METHODS, scipy_rtol=SCIPY_RTOL,
                   reference_rtol: float = REFERENCE_RTOL, repeats: int = 3,
                   scipy_time_limit: float = 120.0, oversample: int = OVERSAMPLE,
                   progress: bool = False) -> pd.DataFrame:
    """Wall time against error of the ballpass solvers and scipy on one scene.

    Parameters
    ----------
    scene : Scene
        What to integrate (its duration, fs and resonance set the work). Noise
        settings are ignored: errors are measured on the noise-free output.
    model : str, optional
        ``"auto"`` (default), ``"sr5"`` or ``"sr4"``.
    rk4_dt : sequence of float, optional
        RK4 steps, s. Default: omega dt in :data:`RK4_OMEGA_DT` with omega the
        linearised contact frequency (rad/s); each is rounded to a multiple or divisor
        of the internal output spacing and duplicates are dropped.
    dopri5_rtol : sequence of float, optional
        dopri5 relative tolerances (default :data:`DOPRI5_RTOL`).
    scipy_methods : sequence of str, optional
        ``solve_ivp`` methods (default :data:`SCIPY_METHODS`); empty for none.
    scipy_rtol : sequence of float, optional
        Their relative tolerances, loosest first (default :data:`SCIPY_RTOL`); absolute
        tolerance ``rtol`` times each state component's characteristic scale.
    reference_rtol : float, optional
        Tolerance of the reference, ballpass dopri5 (default 1e-10).
    repeats : int, optional
        Timing repeats of each ballpass run, the best counts (default 3).
    scipy_time_limit : float, optional
        Wall-time budget of one scipy run, s (default 120): a run that exceeds it is
        recorded with status ``"time limit"`` and the method's tighter tolerances are
        skipped.
    oversample : int, optional
        Internal output rate as a multiple of fs (default as in
        :func:`ballpass.simulate`).
    progress : bool, optional
        Print each row as it is measured.

    Returns
    -------
    pandas.DataFrame
        One row per run, columns :data:`COLUMNS`: ``method`` (e.g. ``"ballpass rk4"``,
        ``"scipy DOP853"``), ``family``, ``setting``, ``dt_s`` (s), ``rtol``, ``wall_s``
        (s), ``wall_per_sim_s`` (s of wall time per simulated s), ``n_steps``,
        ``n_rhs`` (right-hand-side evaluations, Jacobian columns included),
        ``error_l2``, ``error_ses``, ``error_ses_db`` (see the module docstring) and
        ``status``. ``attrs`` records the scene, the reference and its cost.

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate import work_precision
    >>> scene = bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.05,
    ...                  fs=12_000, resonance_hz=3_000)
    >>> table = work_precision(scene, rk4_dt=[2e-5], dopri5_rtol=[1e-6],
    ...                        scipy_methods=["RK45"], scipy_rtol=[1e-6], repeats=1)
    >>> list(table["method"])
    ['ballpass rk4', 'ballpass dopri5', 'scipy RK45']
    >>> bool((table["error_l2"] < 1e-2).all())
    True
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a ballpass.Scene, got {type(scene).__name__}")
    if not (isinstance(repeats, int) and repeats >= 1):
        raise ValueError(f"repeats must be an int >= 1, got {repeats!r}")
    if not (isinstance(scipy_time_limit, (int, float)) and scipy_time_limit > 0):
        raise ValueError(f"scipy_time_limit must be > 0 s, got {scipy_time_limit!r}")
    unknown = [m for m in scipy_methods if m not in SCIPY_METHODS]
    if unknown:
        raise ValueError(f"scipy_methods must be among {SCIPY_METHODS}, got {unknown}")
    bm = build(scene, model)
    h_out, n_out = _grid(scene, oversample)

    for solver in ("rk4", "dopri5"):  # compile (or load) the kernels before timing
        integrate(bm, solver, h_out=h_out, n_out=2)
    t0 = time.perf_counter()
    reference = integrate(bm, "dopri5", h_out=h_out, n_out=n_out, rtol=reference_rtol)
    ref_wall = time.perf_counter() - t0
    judge = _Judge(scene, reference.output, oversample)

    rows = []

    def record(row):
        row["wall_per_sim_s"] = row["wall_s"] / scene.duration_s
        rows.append(row)
        if progress:
            print(f"{row['method']:>16} {row['setting']:>16}  {row['wall_s']:9.4f} s  "
                  f"error {row['error_l2']:.2e}  {row['status']}", flush=True)

    if rk4_dt is None:
        omega = _core_omega(bm)
        rk4_dt = [f / omega for f in RK4_OMEGA_DT]
    steps_done = set()
    for dt in rk4_dt:
        mult, n_sub = _rk4_grid(dt, h_out)
        if (mult, n_sub) in steps_done:
            continue
        steps_done.add((mult, n_sub))
        record(_ballpass_row(bm, "rk4", judge, h_out, n_out, repeats, dt=h_out * mult / n_sub))
    for rtol in dopri5_rtol:
        record(_ballpass_row(bm, "dopri5", judge, h_out, n_out, repeats, rtol=rtol))
    for method in scipy_methods:
        for rtol in scipy_rtol:
            out, wall, n_steps, n_rhs, status = _scipy_run(bm, method, rtol, h_out, n_out,
                                                           scipy_time_limit)
            errs = judge.errors(out) if out is not None else (math.nan,) * 3
            record(dict(method=f"scipy {method}", family="scipy", setting=f"rtol={rtol:g}",
                        dt_s=math.nan, rtol=rtol, wall_s=wall, n_steps=n_steps, n_rhs=n_rhs,
                        error_l2=errs[0], error_ses=errs[1], error_ses_db=errs[2],
                        status=status))
            if status != "ok":
                break
    import pandas as pd

    table = pd.DataFrame(rows, columns=COLUMNS)
    table.attrs.update(scene=repr(scene), model="sr4" if bm.n_res == 0 else "sr5",
                       reference=f"ballpass dopri5 rtol={reference_rtol:g}",
                       reference_wall_s=ref_wall, duration_s=scene.duration_s,
                       band_hz=judge.band, lines=judge.level_names)
    return table


def _front(group: pd.DataFrame, error: str) -> tuple[np.ndarray, np.ndarray]:
    """Pareto front (error increasing, time decreasing) of one method's runs."""
    g = group[np.isfinite(group[error]) & (group[error] > 0)].sort_values(error)
    err, wall = [], []
    for e, w in zip(g[error], g["wall_s"], strict=True):
        if not wall or w < wall[-1]:
            err.append(e)
            wall.append(w)
    return np.array(err), np.array(wall)


def _time_at(err: np.ndarray, wall: np.ndarray, target: float) -> float:
    """Wall time to reach error ``target`` on a front: log-log interpolation inside it;
    above its largest error, the time of its cheapest run (an error at least that
    small costs no less); NaN below its smallest error (never extrapolated)."""
    if err.size == 0 or target < err[0]:
        return math.nan
    if target >= err[-1]:
        return float(wall[-1])
    return float(np.exp(np.interp(np.log(target), np.log(err), np.log(wall))))


def speedup(table: pd.DataFrame, error: str = "error_l2", at=(1e-2, 1e-3, 1e-4)
            ) -> pd.DataFrame:
    """Speed of each ballpass solver relative to the fastest scipy method at equal error.

    Each method's runs are reduced to their Pareto front (no run both slower and less
    accurate than another); the wall time to reach a given error is interpolated
    log-linearly along it, or is the cheapest run's time when even that one is more
    accurate, and is never extrapolated to smaller errors.

    Parameters
    ----------
    table : DataFrame
        From :func:`work_precision`.
    error : str, optional
        Error column (default ``"error_l2"``).
    at : sequence of float, optional
        Error levels.

    Returns
    -------
    pandas.DataFrame
        Index: ballpass methods; columns: the error levels; values: best scipy wall
        time / ballpass wall time (NaN where a curve does not reach the level).

    Examples
    --------
    A hand-made table: ballpass reaches each error 100 times faster than scipy.

    >>> import pandas as pd
    >>> from ballpass.simulate import speedup
    >>> table = pd.DataFrame({"method": ["ballpass rk4"] * 2 + ["scipy RK45"] * 2,
    ...                       "wall_s": [0.02, 0.04, 2.0, 4.0],
    ...                       "error_l2": [1e-2, 1e-4, 1e-2, 1e-4]})
    >>> speedup(table, at=(1e-3,)).round(1)
                  0.001
    ballpass rk4  100.0
    """
    fronts = {m: _front(g, error) for m, g in table.groupby("method")}
    scipy = [m for m in fronts if m.startswith("scipy")]
    result = {}
    for method in (m for m in fronts if m.startswith("ballpass")):
        ratios = []
        for target in at:
            mine = _time_at(*fronts[method], target)
            theirs = min((_time_at(*fronts[m], target) for m in scipy), default=math.nan,
                         key=lambda v: math.inf if math.isnan(v) else v)
            ratios.append(theirs / mine)
        result[method] = ratios
    import pandas as pd

    return pd.DataFrame.from_dict(result, orient="index", columns=list(at))


def plot_work_precision(table: pd.DataFrame, error: str = "error_l2", ax=None, title=None):
    """Log-log plot of wall time per simulated second against error, one curve per
    method.

    Parameters
    ----------
    table : DataFrame
        From :func:`work_precision`.
    error : str, optional
        Error column for the x axis (default ``"error_l2"``).
    ax : matplotlib.axes.Axes, optional
        Where to draw; a new figure when None.
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import pandas as pd
    >>> from ballpass.simulate import plot_work_precision
    >>> table = pd.DataFrame({"method": ["ballpass rk4"] * 2 + ["scipy RK45"] * 2,
    ...                       "wall_per_sim_s": [0.02, 0.04, 2.0, 4.0],
    ...                       "error_l2": [1e-2, 1e-4, 1e-2, 1e-4]})
    >>> ax = plot_work_precision(table)
    >>> ax.get_xscale(), ax.get_yscale(), len(ax.lines)
    ('log', 'log', 2)
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.4))
    for method, group in table.groupby("method", sort=False):
        g = group[np.isfinite(group[error])].sort_values(error)
        style = "-o" if method.startswith("ballpass") else "--s"
        ax.loglog(g[error], g["wall_per_sim_s"], style, label=method, ms=4)
    labels = {"error_l2": "relative L2 error of the acceleration",
              "error_ses": "relative error of the SES fault lines",
              "error_ses_db": "error of the fault-band levels, dB"}
    ax.set_xlabel(labels.get(error, error))
    ax.set_ylabel("wall time per simulated second, s")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    if title:
        ax.set_title(title, fontsize="medium")
    return ax
