"""Running the Sawalhi-Randall models ``sr5`` and ``sr4``: the fault-edge event scan,
step splitting, the integrator calls and the assembly of the result.

The models themselves (parameters, kernel binding, static equilibrium) are in
:mod:`.sr5`; the compiled right-hand side in :mod:`._kernels`; the integrators in
:mod:`._integrators`.

Integration: the nonlinear shaft-pedestal core (4 DOF, Hertz contacts) is stepped by
the chosen Runge-Kutta method, split at every fault edge and slip-walk knot; the sensor
resonators, linear and one-way coupled, are advanced exactly for the cubic Hermite
interpolant of their excitation (an exponential integrator, see
:mod:`._integrators`), so the 15 kHz resonance does not limit the step. Which solver
for which purpose: docs/solvers.md; speed against error: :func:`work_precision`.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass

import numpy as np
from numba import njit

from .._warnings import warn_user
from ..phenomena import DEFAULT_NEEDS
from ..scene import Scene
from . import _integrators as _I
from . import _kernels as _K
from ._registry import Model
from ._shared import (
    OVERSAMPLE,
    SimulationUnstableError,
    add_noise,
    check_finite,
    check_solver_args,
    to_output_rate,
)
from .result import FaultCrossings, GroundTruth, SimulationResult
from .sr5 import BearingModel, SR5Parameters, build_model

__all__ = ["SR5", "SR4", "SOLVERS", "DT_DEFAULT_OMEGA", "DT_SR5_OMEGA", "RawIntegration",
           "integrate", "build"]

#: solver name -> description
SOLVERS = {
    "rk4": "classical Runge-Kutta on the shaft-pedestal core, fixed step, split at fault "
           "edges; sensor resonators integrated exactly",
    "dopri5": "Dormand-Prince 5(4) on the core, adaptive step with error control, split at "
              "fault edges; sensor resonators integrated exactly",
}

#: default RK4 step of the gearbox model = DT_DEFAULT_OMEGA / its fastest linearised mode,
#: rounded down to the internal output grid. Checked by work-precision like sr5's
#: (benchmarks/gearbox_step.py, docs/results/gearbox_step.md): at the rule's worst
#: case (one step per grid interval, omega dt = 0.35 exactly) the output's relative L2
#: error against 1/32 of the step is 3.5e-6 to 9.6e-5 on Tran, Furch & Cu's helical and spur
#: pairs, healthy, with a tooth fault, a bearing fault or both (goal 1e-3, met up to
#: omega dt = 1.0: 5.2e-4); kept at 0.35 for the margin (a stiffer pair or sharper
#: edges than these scenes)
DT_DEFAULT_OMEGA = 0.35
#: default sr4/sr5 RK4 step = DT_SR5_OMEGA / omega_contact (see :func:`simulate`),
#: rounded down to the internal output grid: the largest grid multiple at which RK4
#: keeps the output's relative L2 error below 1e-3 on the work-precision scenes and
#: the 1797 rpm speed scenes (6205 at 500 N: omega dt = 0.26, six grid intervals at
#: 48 kHz; errors 6e-4 to 7e-4, against 2e-3 to 3e-3 at the former 0.35, which the
#: heavier 3.26 kg shaft had stretched to eight intervals; benchmarks/sr5_speed.py)
DT_SR5_OMEGA = 0.3


def build(scene: Scene, model: str = "sr5", params: SR5Parameters | None = None
          ) -> BearingModel:
    """Bind ``scene`` to the sr5 (or ``model="sr4"``) kernels without integrating
    (e.g. to call ``.rhs`` from scipy).

    Parameters
    ----------
    scene : Scene
    model : {"sr5", "sr4", "auto"}, optional
        ``"auto"`` is ``"sr5"`` here.
    params : SR5Parameters, optional

    Returns
    -------
    BearingModel

    Examples
    --------
    The bound model starts at the static equilibrium, where the right-hand side vanishes:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.simulate import build
    >>> bm = build(bp.Scene("6205", rpm=1797, duration_s=0.01))
    >>> bm.n_state, bm.n_res                # shaft, pedestal, resonator: positions, velocities
    (10, 1)
    >>> bool(np.abs(bm.rhs(0.0, bm.y0)).max() < 1e-9)          # m/s^2 against g = 9.81
    True
    """
    if model not in ("auto", "sr5", "sr4"):
        raise ValueError(f"build binds the sr5/sr4 kernels: model must be 'sr5' or 'sr4', "
                         f"got {model!r}")
    return build_model(scene, params, resonator=(model != "sr4"))


def _core_omega(bm: BearingModel) -> float:
    """Linearised contact natural frequency of the core (shaft on its contacts), rad/s:
    the fastest mode the Runge-Kutta step must resolve (the resonators are integrated
    exactly and do not constrain it)."""
    nd = 4 + bm.n_res
    return float(bm.scale[nd] / bm.scale[0])


def _events(bm: BearingModel, t_end: float, exact: bool = True):
    """Fault-edge crossings in [0, t_end], by time: brackets (s), fault, element and
    level indices. ``exact=False`` gives each crossing's time to 1e-13 s in both
    brackets instead of adjacent floating-point numbers around it
    (:func:`._kernels.find_crossings`). One compiled call (:func:`_events_kernel`)."""
    before, after, index, n = _events_kernel(bm.p, bm.walk, bm.faults, bm.levels,
                                             float(t_end), exact)
    if n < 0:
        raise RuntimeError(f"more fault crossings than the kinematic bound {-n - 1}")
    return before, after, index[:, 0], index[:, 1], index[:, 2]


@njit(cache=True, error_model="numpy")
def _events_kernel(p, walk, faults, levels, t_end, exact):
    """:func:`_events`: the sorted crossings, their (fault, element, level) rows and
    their count, or -1 - the capacity when they exceed it.

    Scan so that every offset moves by at most 0.5 rad per interval: each offset is
    monotone in time and the levels lie within 1 rad of the fault centre (a race fault
    is narrower than the element spacing, a ball fault than the ball), so a sign change
    against a level is never missed and a wrap at +-pi never mistaken for one. Offset
    speeds: the cage (with its steepest slip increment), the inner race relative to it
    (< shaft speed) or the ball spin. The scan times are numpy's
    ``linspace(0, t_end, n_scan)``, value for value.
    """
    n_faults = levels.shape[0]
    z = int(p[_K.P_Z])
    w_max = max(p[_K.P_W0], p[_K.P_W1])
    steepest = 0.0
    for k in range(1, walk.shape[0]):
        steepest = max(steepest, abs(walk[k] - walk[k - 1]))
    slope = steepest * z / (2.0 * math.pi)
    cage = p[_K.P_CAGE] * w_max * (1.0 + slope)
    rate = 0.0
    capacity = 0  # at most one crossing of each level per turn of the offset, every path
    for i in range(n_faults):  # the localized faults; waviness rows follow them
        kind = int(faults[i, _K.F_KIND])
        if kind == _K.KIND_OUTER:
            r = cage
        elif kind == _K.KIND_INNER:
            r = w_max
        else:
            r = p[_K.P_SPIN] * cage
        rate = max(rate, r)
        capacity += 4 * (2 if kind == _K.KIND_BALL else z) * (
            math.ceil(r * t_end / (2.0 * math.pi)) + 2)
    n_scan = max(2, math.ceil(t_end * rate / 0.5) + 1)
    t_scan = np.empty(n_scan)
    step = t_end / (n_scan - 1)
    for k in range(n_scan - 1):
        t_scan[k] = k * step + 0.0
    t_scan[n_scan - 1] = t_end
    before, after = np.empty(capacity), np.empty(capacity)
    index = np.empty((capacity, 3), dtype=np.int64)
    n = _K.find_crossings(p, walk, faults[:n_faults], t_scan, levels, before, after, index,
                          exact) if n_faults else 0
    if n < 0:
        return before[:0], after[:0], index[:0], -1 - capacity
    order = np.argsort(before[:n], kind="mergesort")  # stable
    return before[:n][order], after[:n][order], index[:n][order], n


def _ramp_times(bm: BearingModel) -> tuple[float, float]:
    """Shortest time an element takes to cross a defect ramp, s (inf without ramps), at
    the top speed: ramp fraction times the defect's angular extent over the speed of
    its paths (cage; inner race relative to the cage; ball spin). First over all
    defects, then over those deep enough to unload an element completely (depth beyond
    the static contact deflection), whose ramps end in impacts."""
    p = bm.p
    w_max = max(p[_K.P_W0], p[_K.P_W1])
    cage = p[_K.P_CAGE] * w_max
    rate = {_K.KIND_OUTER: cage, _K.KIND_INNER: w_max - cage, _K.KIND_BALL: p[_K.P_SPIN] * cage}
    every, deep = math.inf, math.inf
    for row in bm.faults[:bm.levels.shape[0]]:
        if row[_K.F_RAMP] > 0.0:
            t = row[_K.F_RAMP] * 2.0 * row[_K.F_HALF] / rate[int(row[_K.F_KIND])]
            every = min(every, t)
            if max(row[_K.F_DEPTH], row[_K.F_DEPTH_IN]) > bm.static_deflection:
                deep = min(deep, t)
    return every, deep


def _split_times(bm: BearingModel, t_end: float, ev_before: np.ndarray | None = None,
                 ev_after: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Brackets (s) of every time where the right-hand side is not smooth and the
    integrators split their steps: the fault-edge crossings and the knots of the slip
    walk, where the cage speed jumps. Sorted."""
    if ev_before is None:
        ev_before, ev_after = _events(bm, t_end)[:2]
    knot_before, knot_after = _K.find_knots(bm.p, t_end)
    before = np.concatenate((ev_before, knot_before))
    order = np.argsort(before, kind="stable")
    return before[order], np.concatenate((ev_after, knot_after))[order]


def _edge_names(bm: BearingModel, fault: np.ndarray, level: np.ndarray) -> np.ndarray:
    forward = np.array(["entry", "ramp_end", "ramp_start", "exit"])
    backward = forward[::-1]
    inner = np.array([f.kind == "inner" for f in bm.scene.faults], dtype=bool)
    names = np.where(inner[fault], backward[level], forward[level]) if fault.size else \
        np.empty(0, dtype=forward.dtype)
    return names


@dataclass(frozen=True)
class RawIntegration:
    """Output of :func:`integrate` on the internal grid, before decimation.

    Attributes
    ----------
    output : ndarray (n_out, n_sensors)
        Sensor output at t = k h_out, m/s^2 (not AC-coupled).
    states : ndarray (n_out, n_state) or (0, n_state)
        States at the grid times when requested.
    h_out : float
        Grid spacing, s.
    crossings : FaultCrossings
    info : dict
        Solver statistics.
    """

    output: np.ndarray
    states: np.ndarray
    h_out: float
    crossings: FaultCrossings
    info: dict


def _rk4_grid(dt: float, h_out: float) -> tuple[int, int]:
    """``(mult, n_sub)`` of the RK4 step :func:`integrate` makes of ``dt`` (s): the step
    ``h_out * mult / n_sub`` ends on the output grid of spacing ``h_out`` (s), a
    multiple of it (``n_sub = 1``) or a divisor (``mult = 1``); the 1e-9 keeps a ``dt``
    meant as an exact multiple or divisor from rounding the other way."""
    if dt >= h_out:
        return math.floor(dt / h_out + 1e-9), 1
    return 1, math.ceil(h_out / dt - 1e-9)

def integrate(bm: BearingModel, solver: str, *, h_out: float, n_out: int,
              dt: float | None = None, rtol: float | None = None, atol: float | None = None,
              keep_states: bool = False) -> RawIntegration:
    """Integrate a bound model and return the sensor output on a uniform grid.

    This is the integration step of :func:`simulate` without decimation, AC coupling
    or noise; useful to compare solvers with each other and with scipy.

    Parameters
    ----------
    bm : BearingModel
        From :func:`build`.
    solver : {"rk4", "dopri5"}
    h_out : float
        Grid spacing of the output, s.
    n_out : int
        Number of grid points (t = 0 .. (n_out - 1) h_out).
    dt, rtol, atol
        As in :func:`simulate`.
    keep_states : bool
        Also return the state at every grid point.

    Returns
    -------
    RawIntegration

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate import build, integrate
    >>> bm = build(bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.01))
    >>> raw = integrate(bm, "rk4", h_out=1 / 48_000, n_out=480)
    >>> raw.output.shape, raw.info["solver"]
    ((480, 1), 'rk4')
    >>> raw.crossings.edge[:2].tolist()            # the first ball reaching the fault
    ['ramp_start', 'exit']
    """
    scene = bm.scene
    check_solver_args("sr5", solver, SOLVERS, ("rk4",), dt, rtol, atol, OVERSAMPLE)
    if solver == "auto":
        solver = "rk4"
    t_wall = time.perf_counter()
    t_end = (n_out - 1) * h_out
    ev_before, ev_after, ev_fault, ev_elem, ev_level = _events(bm, t_end)
    split_before, split_after = _split_times(bm, t_end, ev_before, ev_after)
    out = np.empty((n_out, len(scene.sensors)))
    states = np.empty((n_out if keep_states else 0, bm.n_state))
    nd = 4 + bm.n_res
    bound = np.empty(bm.n_state)
    bound[:nd] = 1e4 * np.maximum(bm.scale[:nd], 1e-6)
    bound[nd:] = 1e4 * bm.scale[nd:] + 1e3
    omega = _core_omega(bm)
    t_ramp, t_impact = _ramp_times(bm)
    info = {"solver": solver, "internal_fs": 1.0 / h_out, "n_events": int(ev_before.shape[0])}
    if solver == "rk4":
        dt_req = dt if dt is not None else DT_SR5_OMEGA / omega
        mult, n_sub = _rk4_grid(dt_req, h_out)
        work = _I.rk4_start(bm.y0, *bm.model, bm.n_res, h_out, mult, n_sub, n_out,
                            split_before, out, states)
        status, n_steps, t_fail = _I.run_chunked(
            _I.rk4, *bm.model, bm.n_res, h_out, mult, n_sub, n_out, split_before,
            split_after, t_ramp, t_impact, bound, out, states, *work)
        step = h_out * mult / n_sub
        if dt is not None and abs(step - dt) > 1e-6 * dt:
            warn_user(f"dt={dt:g} s rounded to {step:.6g} s so that the steps end on the "
                      f"internal output grid (spacing {h_out:.6g} s); res.info['dt_s'] "
                      "holds the step used")
        info.update(n_steps=int(n_steps), n_rejected=0, dt_s=step)
        step_text = f"dt = {step:.3g} s"
    else:
        rtol_v = 1e-6 if rtol is None else float(rtol)
        core_scale = np.concatenate((bm.scale[:4], bm.scale[nd:nd + 4]))
        atol_v = rtol_v * (1.0 if atol is None else float(atol)) * core_scale
        # the resonator excitation's scale: the resonator deflection scale times w_r^2
        w_r = bm.p[_K.P_WR]
        atol_in = rtol_v * (1.0 if atol is None else float(atol)) * (
            bm.scale[4] * w_r**2 if bm.n_res else 1.0)
        h_max = 0.5 * math.pi / omega  # at least 4 steps per period of the contact mode
        max_steps = int(50 * n_out + 100 * split_before.shape[0] + 10_000)
        work = _I.dopri5_start(bm.y0, *bm.model, bm.n_res, h_out, h_max, out, states)
        status, n_acc, n_rej, h_min, t_fail = _I.run_chunked(
            _I.dopri5, *bm.model, bm.n_res, h_out, n_out, split_before, split_after, t_ramp,
            bound, rtol_v, atol_v, atol_in, h_max, max_steps, out, states, *work)
        info.update(n_steps=int(n_acc), n_rejected=int(n_rej), dt_min_s=float(h_min),
                    rtol=rtol_v)
        step_text = f"rtol = {rtol_v:g}, smallest step {h_min:.3g} s"
    if status != _I.STATUS_OK:
        reason = {
            _I.STATUS_NONFINITE: "the state became non-finite or unbounded",
            _I.STATUS_UNDERFLOW: "the step size underflowed",
            _I.STATUS_MAX_STEPS: "the step budget was exhausted",
        }[status]
        raise SimulationUnstableError(
            f"simulation with solver {solver!r} ({step_text}) failed at t = {t_fail:.6g} s: "
            f"{reason}. Try a smaller dt / rtol or solver='dopri5'. Scene: {scene!r}"
        )
    info["integration_time_s"] = time.perf_counter() - t_wall
    crossings = FaultCrossings(
        time_s=ev_before.copy(), fault=ev_fault, element=ev_elem,
        edge=_edge_names(bm, ev_fault, ev_level),
    )
    return RawIntegration(output=out, states=states, h_out=h_out, crossings=crossings,
                          info=info)


def _mode_filter(hz: float, zeta: float, hz1: float, zeta1: float, fs: float):
    """Digital filter (b, a) of T_k(s) / T_1(s) at sampling rate fs: a further
    structural mode k seen through the output of the main resonator 1, with
    T(s) = (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2) the transmissibility of a
    base-excited resonator (its absolute acceleration over the base's). Bilinear
    transform with every natural frequency pre-warped (w -> 2 fs tan(w / 2 fs)), so
    both resonances sit exactly where they should."""
    from scipy import signal

    def warp(f):
        return 2.0 * fs * math.tan(math.pi * f / fs)

    w, w1 = warp(hz), warp(hz1)
    num = np.polymul([2 * zeta * w, w * w], [1.0, 2 * zeta1 * w1, w1 * w1])
    den = np.polymul([1.0, 2 * zeta * w, w * w], [2 * zeta1 * w1, w1 * w1])
    return signal.bilinear(num, den, fs=fs)


def add_modes(scene: Scene, out: np.ndarray, fs: float) -> np.ndarray:
    """The sensor output with the scene's further structural modes
    (``Scene.resonances``): y + sum_k g_k (T_k / T_1) y, where y (n, n_sensors) is the
    main resonator's output at rate fs, so that the result is sum over all modes of
    g_k T_k applied to the housing excitation (parallel modes of the transfer path;
    the resonators are linear and one-way coupled, so this equals integrating them
    all). The filters start in the steady state of the first sample."""
    if not scene.resonances:
        return out
    from scipy import signal

    total = out.copy()
    for hz, zeta, gain in scene.resonances:
        b, a = _mode_filter(hz, zeta, scene.resonance_hz, scene.resonance_damping, fs)
        zi = signal.lfilter_zi(b, a)[:, None] * out[0][None, :]
        total += gain * signal.lfilter(b, a, out, axis=0, zi=zi)[0]
    return total


#: (solver, resonator) pairs already run in this process (kernels compiled or loaded)
_WARM: set = set()


def _run(scene: Scene, solver: str, *, resonator: bool, dt=None, rtol=None, atol=None,
         params: SR5Parameters | None = None, return_forces: bool = False,
         oversample: int = OVERSAMPLE) -> SimulationResult:
    """Simulate ``scene`` with sr5 (``resonator=True``) or sr4 (arguments validated)."""
    if params is not None and not isinstance(params, SR5Parameters):
        raise TypeError(f"params must be SR5Parameters for the sr4/sr5 models, got "
                        f"{type(params).__name__}")
    if scene.resonances and not resonator:
        raise ValueError(f"Scene.resonances={scene.resonances!r} adds modes beside the main "
                         "resonator, which sr4 does not have: use model='sr5'")
    compile_s = 0.0
    if (solver, resonator) not in _WARM:
        # the first run of a process compiles the kernels (or loads them from numba's
        # cache): time that once on a few samples, so it is not reported as the run
        _WARM.add((solver, resonator))
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the real run below warns, once
            _run(scene.replace(duration_s=8.0 / scene.fs), solver, resonator=resonator,
                 dt=dt, rtol=rtol, atol=atol, params=params, oversample=oversample)
        compile_s = time.perf_counter() - t0
    t_wall = time.perf_counter()
    bm = build_model(scene, params, resonator=resonator)
    n_samples = scene.n_samples
    raw = integrate(bm, solver, h_out=1.0 / (scene.fs * oversample),
                    n_out=n_samples * oversample, dt=dt, rtol=rtol, atol=atol,
                    keep_states=return_forces)
    out, states, info = raw.output, raw.states, raw.info
    out = add_modes(scene, out, 1.0 / raw.h_out)
    h_out = raw.h_out

    accel = add_noise(scene, to_output_rate(out, n_samples, oversample))
    check_finite(scene, accel, "sr5" if resonator else "sr4")

    t = np.arange(n_samples) / scene.fs
    forces = angles = displacement = None
    if return_forces:
        idx = np.arange(n_samples) * oversample
        forces = _K.contact_loads_many(idx * h_out, states[idx], *bm.model[:3]).T.copy()
        angles = _K.element_angles_many(idx * h_out, bm.p, bm.walk,
                                        scene.bearing.n_elements).T.copy()
        displacement = states[idx][:, :4].T.copy()
    truth = GroundTruth.of_scene(
        scene, t, raw.crossings,
        contact_forces=forces,
        element_angles=angles,
        displacement=displacement,
    )
    info["wall_time_s"] = time.perf_counter() - t_wall
    info["compile_time_s"] = compile_s
    if bm.film_m:
        info["ehl_film_m"] = bm.film_m
    return SimulationResult.of_scene(scene, accel, t, truth, info)


def _run_sr5(scene: Scene, solver: str, **kwargs) -> SimulationResult:
    return _run(scene, solver, resonator=True, **kwargs)


def _run_sr4(scene: Scene, solver: str, **kwargs) -> SimulationResult:
    return _run(scene, solver, resonator=False, **kwargs)


def _accepts(scene: Scene) -> str | None:
    """sr4/sr5 take every scene (balls or rollers, any sensors, constant or ramped
    speed) but an EHL film on rollers: the film formula is for point contacts."""
    if "ehl_film" in scene.needs and scene.bearing.element != "ball":
        return ("the EHL film (needs 'ehl_film') is modelled for point contacts only; "
                f"bearing {scene.bearing.name!r} has rollers")
    clearance = (scene.bearing.radial_clearance_mm if scene.clearance_um is None
                 else scene.clearance_um * 1e-3)
    if scene.axial_load_n > 0 and clearance < 0:
        return ("an axial load on a preloaded bearing (clearance < 0) is not modelled: "
                "give clearance_um >= 0 or axial_load_n=0")
    return None


_REFERENCE = ("N. Sawalhi, R. B. Randall, 'Simulating gear and bearing interactions in the "
              "presence of faults: Part I', MSSP 22 (2008) 1924-1951 (equations as printed in "
              "Tran, Furch & Cu, with the sprung mass restored; see ballpass.simulate.sr5)")

#: the scene options the sr5 kernels and driver honour (``Scene.clearance_um`` and
#: ``resonances``, pit faults, intermittent ball defects, the EHL film); sr4 has no
#: resonator to add modes to
SR5_SCENE_OPTIONS = frozenset({"mounted_clearance", "structural_modes", "pit_faults",
                               "intermittent_faults", "ehl_film"})

#: the 5-DOF model with the high-frequency resonator per sensor
SR5 = Model(
    name="sr5",
    description="Sawalhi-Randall 5-DOF: shaft, pedestal and a high-frequency resonator per "
                "sensor; Hertz contacts, clearance, slip, localized faults",
    represents=DEFAULT_NEEDS | {"contact_forces", "varying_speed", "waviness", "axial_load",
                                *SR5_SCENE_OPTIONS},
    relative_cost=1.0,
    solvers=tuple(SOLVERS),
    fixed_step_solvers=("rk4",),
    reference=_REFERENCE,
    accepts=_accepts,
    run=_run_sr5,
)

#: the same without the resonator: the sensors read the housing acceleration, so the
#: envelope signature lacks its resonance carrier
SR4 = Model(
    name="sr4",
    description="Sawalhi-Randall 4-DOF: shaft and pedestal, sensors read the housing "
                "acceleration (no resonator)",
    represents=frozenset({"contact_dynamics", "contact_forces", "varying_speed", "waviness",
                          "axial_load", *(SR5_SCENE_OPTIONS - {"structural_modes"})}),
    # measured by benchmarks/models_cost.py (docs/models_cost.md: 3.1 at 48 kHz, 1.3 at
    # 12 kHz, median of interleaved rounds): the same steps as sr5, but its output, the
    # housing acceleration, is evaluated from the contact forces at every internal
    # sample, while sr5's resonators are advanced exactly
    relative_cost=3.1,
    solvers=tuple(SOLVERS),
    fixed_step_solvers=("rk4",),
    reference=_REFERENCE,
    accepts=_accepts,
    run=_run_sr4,
)
