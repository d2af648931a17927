"""``nabhan2020``: the lumped bearing model of Nabhan & Rashed (2020), with its table.

Nabhan & Rashed (2020), "Detection of localized fault in inner race of deep groove ball
bearing based on MSC-ADAMS" (EGTRIB J. 17(2)), model an SKF 6004 with an inner-race
notch as inner race, ball, outer race and a sprung mass (its Fig. 3, eqs. 16-21) and
give every mass, stiffness and damping in its parameter table ("Table 1, Parameters of
the ball bearing model"). This preset runs those degrees of freedom with that table.

Degrees of freedom (u along the load line, positive into the load zone at 0 deg, and
v at +90 deg; 7 coordinates, 14 states):

* inner race u_i, v_i: mass M_i, held to the frame by K_i, C_i (eqs. 18-19);
* ball coordinate u_b, v_b: the ball set between the races, mass Z M_b;
* outer race u_o, v_o: mass M_o, held by K_o, C_o (eqs. 16-17);
* sprung mass u_s along the load line only: mass M_sm on K_sm, C_sm from the outer race
  (eq. 21), the paper's "system" mode at sqrt(K_sm / M_sm) / 2 pi = 2123 Hz.

Equations (the paper's signs corrected so that springs restore and dampers dissipate,
eq. 19's k_i x_i read k_i y_i, eq. 21 in the relative form the paper's eq. 17 implies):

    M_i u_i'' = F_r + M_i g - sum_j Qi_j cos psi_j - C_i u_i' - K_i u_i
    M_i v_i'' =             - sum_j Qi_j sin psi_j - C_i v_i' - K_i v_i
    m_b u_b'' = m_b g + sum_j (Qi_j - Qo_j) cos psi_j,  m_b = Z M_b
    m_b v_b'' =         sum_j (Qi_j - Qo_j) sin psi_j
    M_o u_o'' = M_o g + sum_j Qo_j cos psi_j - C_o u_o' - K_o u_o
                - C_sm (u_o' - u_s') - K_sm (u_o - u_s)
    M_o v_o'' =         sum_j Qo_j sin psi_j - C_o v_o' - K_o v_o
    M_sm u_s'' = M_sm g - C_sm (u_s' - u_o') - K_sm (u_s - u_o)

with ball j at psi_j = 2 pi j / Z + w_c t (eq. 6; cage speed eq. 7, no slip) and its
inner and outer contacts compressed by (eqs. 11, 24 with sin for the second term)

    di_j = (u_i - u_b) cos psi_j + (v_i - v_b) sin psi_j - c/2 - h_j(t)
    do_j = (u_b - u_o) cos psi_j + (v_b - v_o) sin psi_j - c/2

(c the bearing's radial clearance, shared equally by the two contacts; h_j the notch
depth under ball j, eq. 25). Each contact carries Q = max(0, P(d) + C_b d') for d > 0,
where P is the Hertz contact (eq. 1, K_in or K_out of eq. 3, Harris) in series with
half the ball's own body, a linear spring 2 K_b: (P / K)^(2/3) + P / (2 K_b) = d.

Assumptions and every choice the paper leaves open:

* **The ball coordinate.** Eq. 20 as printed (M_b x_b'' = -C_b x_b' - k_b x_b with
  x_b = x_o - x_i) is a free oscillator no force reaches. It is read as the ball set
  between the races: one planar body of mass Z M_b (all balls translate together),
  K_b the compressive stiffness of a ball (1.62e10 N/m, in series with the Hertz
  contacts: at 200 N it changes the contact compliance by 0.3 %), C_b the damping of
  each loaded ball-race contact.
* **Supports.** Eqs. 16-19 hold the inner race by K_i, C_i and the outer race by K_o,
  C_o to the frame; the radial load F_r acts on the inner race, so K_i carries part of
  it in parallel with the bearing (about half at 500 N for a 6004). Gravity acts along
  the load line on every mass when ``Scene.gravity`` (the paper's M g terms).
* **Notch.** Sharp edges: the ball drops by h = min(depth, d_b/2 (1 - sqrt(1 -
  (w/d_b)^2))) (eq. 26 with d_b, :func:`notch_depth_mm`: the ball's own sagitta, as the
  paper specifies; the other models take the inner race's curvature too,
  :meth:`ballpass.Fault.effective_depth_mm`, 1.26x deeper on a 6205) while its
  angle is within w / r_i of the notch's leading edge, r_i the inner raceway radius;
  the notch turns with the shaft (eq. 23). ``Fault.edge`` and ``ramp_fraction`` are not
  used: the paper's notch is rectangular.
* **No noise, no slip.** The model adds no noise (a scene's ``noise_rms``/``snr_db`` is
  added as in every model) and its cage turns at the kinematic rate (``Scene.slip`` is
  not used: the paper has none).
* **Sensors.** A sensor at angle theta reads u_s'' cos theta + v_o'' sin theta (the
  sprung mass along the load line, the outer race across it), AC-coupled. There is no
  per-contact transmission path: a sensor at 180 deg reads minus the one at 0 deg, so
  the lumped model cannot tell the loaded from the unloaded zone. ``resonance_hz``
  and the sensors' ``attenuation`` are not used: the sprung mass is the resonance.
* **Integration.** Fixed-step RK4 at ``dt`` (default 1 us, half the stability limit of
  the contact damping on the ball set, rounded down to divide the output spacing; a
  sharp notch edge falls inside a step, which costs first order there: 0.4 % relative
  L2 against a 0.2 us run, see :data:`DEFAULT_DT`).

Represents ``contact_dynamics`` and ``ball_race_sprung_mass`` (this preset's own
phenomenon), not ``envelope`` (no slip, no transmission path): ``model="auto"``
never picks it unless a scene asks for ``ball_race_sprung_mass``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, fields

import numba
import numpy as np

from ..bearing import Bearing
from ..scene import Fault, Scene
from ._registry import Model
from ._shared import OVERSAMPLE, add_noise, check_finite, to_output_rate
from .result import FaultCrossings, GroundTruth, SimulationResult

__all__ = ["Nabhan2020Parameters", "NABHAN2020", "static_equilibrium", "DOF_NAMES",
           "notch_depth_mm"]

#: the 7 coordinates of the state (positions, then the same velocities)
DOF_NAMES = ("u_i", "v_i", "u_b", "v_b", "u_o", "v_o", "u_s")
_G = 9.81
#: default RK4 step, s (rounded down to divide the internal output spacing). The contact
#: damping of ~5 loaded balls (2 contacts x 1350 N s/m) on the 9.45 g ball set decays at
#: ~1.4e6 1/s, RK4's real-axis limit 2.79 / 1.4e6 = 2 us. Against 0.2 us, a 6004 with a
#: 0.5 mm sharp notch at 1500 rpm, 48 kHz: relative L2 difference 0.4 % at 0.87 us (the
#: notch edges, inside a step, cost first order), 0.5 % at 1.7 us, 1.2 % at 2.6 us.
DEFAULT_DT = 1e-6


@dataclass(frozen=True)
class Nabhan2020Parameters:
    """Masses (kg), stiffnesses (N/m) and dampings (N s/m) of Nabhan & Rashed (2020),
    "Table 1, Parameters of the ball bearing model" (the sprung-mass rows are printed
    "... of outer race"). All values SI.

    Examples
    --------
    >>> from ballpass.simulate.nabhan2020 import Nabhan2020Parameters
    >>> p = Nabhan2020Parameters()
    >>> round((p.sprung_stiffness / p.sprung_mass) ** 0.5 / (2 * 3.141592653589793))
    2123
    """

    ball_mass: float = 1.05e-3
    ball_stiffness: float = 1.62e10
    ball_damping: float = 1350.0
    inner_mass: float = 20.27e-3
    inner_stiffness: float = 15.1e6
    inner_damping: float = 2000.0
    outer_mass: float = 29.36e-3
    outer_stiffness: float = 15.0e6
    outer_damping: float = 2000.0
    sprung_mass: float = 0.5
    sprung_stiffness: float = 8.9e7
    sprung_damping: float = 1250.0

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
                raise ValueError(f"{f.name} must be a finite number > 0, got {value!r}")


@numba.njit(cache=True)
def _series_load(d, k_hertz, k_body):  # pragma: no cover - numba
    """Load P (N) of a Hertz contact (P = k_hertz a^1.5) in series with a linear spring
    k_body at total approach d > 0 (m), by the fixed point P = k_hertz (d - P/k_body)^1.5
    from P = k_hertz d^1.5. Each pass multiplies the relative error by
    1.5 P / (k_body (d - P/k_body)), below 1e-2 up to the elastic limit of a ball
    contact (P / (k_body d) < 4e-3 for the table's 2 K_b = 3.2e10 N/m and a 6004 at
    2 kN per ball), so three passes leave < 1e-6 of P."""
    p = k_hertz * d**1.5
    for _ in range(3):
        a = d - p / k_body
        p = k_hertz * a * math.sqrt(a) if a > 0.0 else 0.0
    return p


@numba.njit(cache=True)
def _accelerations(t, y, p, out, loads):  # pragma: no cover - numba
    """y'' of the 7 coordinates (into ``out[7:]``, velocities into ``out[:7]``) and the
    inner/outer contact loads of every ball (``loads`` (2, Z)).

    p = [F_r, g, M_i, K_i, C_i, m_b, M_o, K_o, C_o, M_s, K_s, C_s, K_in, K_out, 2 K_b,
    C_b, c/2, w_c, w_s, Z, n_faults, then (phi0, span, depth) per notch].
    """
    f_r, g = p[0], p[1]
    m_i, k_i, c_i, m_b = p[2], p[3], p[4], p[5]
    m_o, k_o, c_o, m_s, k_s, c_s = p[6], p[7], p[8], p[9], p[10], p[11]
    k_in, k_out, k_body, c_b, half_c = p[12], p[13], p[14], p[15], p[16]
    w_c, w_s = p[17], p[18]
    z = int(p[19])
    n_f = int(p[20])
    ui, vi, ub, vb, uo, vo, us = y[0], y[1], y[2], y[3], y[4], y[5], y[6]
    dui, dvi, dub, dvb, duo, dvo, dus = y[7], y[8], y[9], y[10], y[11], y[12], y[13]
    fiu = 0.0
    fiv = 0.0
    fou = 0.0
    fov = 0.0
    two_pi = 2.0 * math.pi
    for j in range(z):
        psi = two_pi * j / z + w_c * t
        cs = math.cos(psi)
        sn = math.sin(psi)
        drop = 0.0
        for k in range(n_f):
            rel = (psi - (p[21 + 3 * k] + w_s * t)) % two_pi
            if rel < p[22 + 3 * k]:
                drop += p[23 + 3 * k]
        di = (ui - ub) * cs + (vi - vb) * sn - half_c - drop
        qi = 0.0
        if di > 0.0:
            qi = max(_series_load(di, k_in, k_body)
                     + c_b * ((dui - dub) * cs + (dvi - dvb) * sn), 0.0)
        do = (ub - uo) * cs + (vb - vo) * sn - half_c
        qo = 0.0
        if do > 0.0:
            qo = max(_series_load(do, k_out, k_body)
                     + c_b * ((dub - duo) * cs + (dvb - dvo) * sn), 0.0)
        loads[0, j] = qi
        loads[1, j] = qo
        fiu += qi * cs
        fiv += qi * sn
        fou += qo * cs
        fov += qo * sn
    for m in range(7):
        out[m] = y[7 + m]
    out[7] = (f_r + m_i * g - fiu - c_i * dui - k_i * ui) / m_i
    out[8] = (-fiv - c_i * dvi - k_i * vi) / m_i
    out[9] = g + (fiu - fou) / m_b
    out[10] = (fiv - fov) / m_b
    out[11] = (m_o * g + fou - c_o * duo - k_o * uo - c_s * (duo - dus) - k_s * (uo - us)) / m_o
    out[12] = (fov - c_o * dvo - k_o * vo) / m_o
    out[13] = g - (c_s * (dus - duo) + k_s * (us - uo)) / m_s


@numba.njit(cache=True)
def _integrate(y0, p, t0, dt, n_sub, n_out, cos_s, sin_s):  # pragma: no cover - numba
    """RK4 with ``n_sub`` steps of ``dt`` between outputs; returns the sensor signals
    (n_out, n_sensors), m/s^2, and the final state."""
    z = int(p[19])
    loads = np.zeros((2, z))
    y = y0.copy()
    k1 = np.empty(14)
    k2 = np.empty(14)
    k3 = np.empty(14)
    k4 = np.empty(14)
    tmp = np.empty(14)
    out = np.empty((n_out, cos_s.size))
    t = t0
    for n in range(n_out):
        _accelerations(t, y, p, k1, loads)
        for s in range(cos_s.size):
            out[n, s] = k1[13] * cos_s[s] + k1[12] * sin_s[s]
        if not np.isfinite(k1[13]):
            out[n:, :] = np.nan
            return out, y
        for _ in range(n_sub):
            _accelerations(t, y, p, k1, loads)
            for m in range(14):
                tmp[m] = y[m] + 0.5 * dt * k1[m]
            _accelerations(t + 0.5 * dt, tmp, p, k2, loads)
            for m in range(14):
                tmp[m] = y[m] + 0.5 * dt * k2[m]
            _accelerations(t + 0.5 * dt, tmp, p, k3, loads)
            for m in range(14):
                tmp[m] = y[m] + dt * k3[m]
            _accelerations(t + dt, tmp, p, k4, loads)
            for m in range(14):
                y[m] += dt / 6.0 * (k1[m] + 2.0 * k2[m] + 2.0 * k3[m] + k4[m])
            t += dt
    return out, y


def notch_depth_mm(fault: Fault, bearing: Bearing) -> float:
    """Depth the ball drops into ``fault``, mm, as Nabhan & Rashed (2020) eq. 26
    specifies it (with the ball diameter d_b in place of the printed pitch diameter):
    min(h, d_b/2 (1 - sqrt(1 - (w/d_b)^2))) for w < d_b, else h. The ball's own
    sagitta over the width w, without the race's curvature
    (:meth:`ballpass.Fault.effective_depth_mm` adds it).

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate.nabhan2020 import notch_depth_mm
    >>> b = bp.Bearing.catalog("6205")                       # ball diameter 7.94 mm
    >>> round(notch_depth_mm(bp.Fault("inner", width_mm=0.5, depth_mm=0.2), b), 4)
    0.0079
    """
    d, w = bearing.element_diameter_mm, fault.width_mm
    if w >= d:
        return fault.depth_mm
    return min(fault.depth_mm, 0.5 * d * (1.0 - math.sqrt(1.0 - (w / d) ** 2)))


def parameter_vector(scene: Scene, params: Nabhan2020Parameters) -> np.ndarray:
    """The kernel's parameter vector for ``scene`` (see :func:`_accelerations`)."""
    b = scene.bearing
    k_in, k_out = b.contact_stiffnesses()
    w_s = 2.0 * math.pi * scene.speed.rpm_start / 60.0
    w_c = 0.5 * w_s * (1.0 - b.diameter_ratio)   # eq. 7
    notches = []
    for f in scene.faults:
        span = f.width_mm * 1e-3 / b.inner_race_radius_m
        notches += [math.radians(f.angle_deg), span, notch_depth_mm(f, b) * 1e-3]
    g = _G if scene.gravity else 0.0
    head = [scene.radial_load_n, g, params.inner_mass, params.inner_stiffness,
            params.inner_damping, b.n_elements * params.ball_mass, params.outer_mass,
            params.outer_stiffness, params.outer_damping, params.sprung_mass,
            params.sprung_stiffness, params.sprung_damping, k_in, k_out,
            2.0 * params.ball_stiffness, params.ball_damping, 0.5 * b.radial_clearance_m,
            w_c, w_s, float(b.n_elements), float(len(scene.faults))]
    return np.array(head + notches, dtype=np.float64)


def static_equilibrium(scene: Scene, params: Nabhan2020Parameters | None = None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The model at rest under its loads, at t = 0 with the cage where the scene starts.

    Solved with :func:`scipy.optimize.root` (hybrid Powell) on the model's own forces,
    defects included, to a residual force below 1e-9 of the load.

    Parameters
    ----------
    scene : Scene
    params : Nabhan2020Parameters, optional

    Returns
    -------
    state : ndarray (14,)
        Positions of :data:`DOF_NAMES` (m) and zero velocities.
    loads : ndarray (2, Z)
        Inner and outer contact load of every ball, N.

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate.nabhan2020 import static_equilibrium
    >>> y, q = static_equilibrium(bp.Scene(bearing="6004", radial_load_n=500.0))
    >>> q.shape
    (2, 9)
    """
    from scipy.optimize import root

    p = parameter_vector(scene, params or Nabhan2020Parameters())
    masses = np.array([p[2], p[2], p[5], p[5], p[6], p[6], p[9]])
    scale = max(scene.radial_load_n, 1.0)
    out = np.empty(14)
    loads = np.zeros((2, int(p[19])))

    def residual(x_um):
        _accelerations(0.0, np.concatenate([x_um * 1e-6, np.zeros(7)]), p, out, loads)
        return out[7:] * masses / scale

    # start from the supports alone (every mass on its springs) with the contacts a few
    # um into compression: at zero approach a Hertz contact has no stiffness to follow
    guess = np.full(7, scene.radial_load_n / (p[3] + p[7]) * 1e6)
    guess[[1, 3, 5]] = 0.0
    guess[0] += 4.0
    guess[2] += 2.0
    sol = root(residual, guess, method="hybr", options={"xtol": 1e-13})
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-9:
        raise RuntimeError(f"nabhan2020: no static equilibrium found for {scene!r}: "
                           f"{sol.message}")
    state = np.concatenate([sol.x * 1e-6, np.zeros(7)])
    _accelerations(0.0, state, p, out, loads)
    return state, loads.copy()


def _crossings(scene: Scene, p: np.ndarray) -> FaultCrossings:
    """Entry and exit times of every ball at every notch edge, from the kinematics."""
    z, w_c, w_s = int(p[19]), p[17], p[18]
    rows = []
    for k in range(len(scene.faults)):
        phi0, span = p[21 + 3 * k], p[22 + 3 * k]
        period = 2.0 * math.pi / (w_s - w_c)  # the notch laps the cage
        for j in range(z):
            # rel = psi_j - phi_notch decreases at (w_s - w_c): entry when rel falls
            # through span, exit when it falls through 0
            rel0 = (2.0 * math.pi * j / z - phi0) % (2.0 * math.pi)
            for edge, level in (("entry", span), ("exit", 0.0)):
                first = ((rel0 - level) % (2.0 * math.pi)) / (w_s - w_c)
                times = np.arange(first, scene.duration_s, period)
                rows += [(t, k, j, edge) for t in times]
    rows.sort()
    return FaultCrossings(time_s=np.array([r[0] for r in rows], dtype=float),
                          fault=np.array([r[1] for r in rows], dtype=np.int64),
                          element=np.array([r[2] for r in rows], dtype=np.int64),
                          edge=np.array([r[3] for r in rows], dtype=object))


def _run(scene: Scene, solver: str, *, dt=None, rtol=None, atol=None, params=None,
         return_forces: bool = False, oversample: int = OVERSAMPLE) -> SimulationResult:
    """Simulate ``scene`` with the Nabhan & Rashed (2020) model (module docstring)."""
    if params is not None and not isinstance(params, Nabhan2020Parameters):
        raise TypeError(f"params must be Nabhan2020Parameters for the nabhan2020 model, got "
                        f"{type(params).__name__}")
    if return_forces:
        raise ValueError("return_forces=True: the nabhan2020 model does not return contact "
                         "forces; use model='sr5' or 'multibody'")
    params = params or Nabhan2020Parameters()
    t_wall = time.perf_counter()
    p = parameter_vector(scene, params)
    grid = 1.0 / (scene.fs * oversample)
    step = DEFAULT_DT if dt is None else dt
    n_sub = max(1, math.ceil(grid / step - 1e-9))
    # at rest under the loads of the healthy bearing; a notch's own transient belongs
    # to the run (the notch is a discontinuity a root finder cannot settle on)
    y0, _ = static_equilibrium(scene.replace(fault=None), params)
    theta = np.radians([s.angle_deg for s in scene.sensors])
    n_out = scene.n_samples * oversample
    out, _ = _integrate(y0, p, 0.0, grid / n_sub, n_sub, n_out, np.cos(theta), np.sin(theta))
    accel = to_output_rate(out, scene.n_samples, oversample)
    check_finite(scene, accel, "nabhan2020")
    accel = add_noise(scene, accel)
    t = np.arange(scene.n_samples) / scene.fs
    truth = GroundTruth.of_scene(scene, t, _crossings(scene, p),
                                 tuple(notch_depth_mm(f, scene.bearing) for f in scene.faults))
    info = {"solver": solver, "dt": grid / n_sub, "steps": n_out * n_sub,
            "wall_time_s": time.perf_counter() - t_wall}
    return SimulationResult.of_scene(scene, accel, t, truth, info)


def _accepts(scene: Scene) -> str | None:
    """Ball bearings at a constant speed with inner-race notches, as in the paper."""
    if scene.bearing.element != "ball":
        return "it models a ball bearing (Nabhan & Rashed 2020): the bearing has rollers"
    if not scene.speed.is_constant:
        return "it runs at a constant speed only"
    if scene.speed.rpm_start <= 0:
        return "it needs a turning shaft (rpm > 0)"
    for f in scene.faults:
        if f.kind != "inner" or f.geometry != "groove":
            return (f"it models inner-race notches only (the paper's fault), got a "
                    f"{f.kind} {f.geometry}")
    return None


#: Nabhan & Rashed (2020)'s lumped model, registered in ballpass.simulate.MODELS
NABHAN2020 = Model(
    name="nabhan2020",
    description="Nabhan & Rashed (2020) preset: inner race, ball set, outer race and a "
                "2.1 kHz sprung mass with the paper's table; sharp notch, no slip",
    represents=frozenset({"contact_dynamics", "ball_race_sprung_mass"}),
    # measured side by side with sr5, 4 interleaved rounds of CPU time (time.process_time)
    # on a 6004 with an inner notch at 1500 rpm, 48 kHz, 0.25 s: 0.80-0.93 s against
    # 0.006-0.009 s, median ratio 113 (the 1 us RK4 step against the 31 ms per simulated
    # second of sr5 in docs/models_cost.md)
    relative_cost=115.0,
    solvers=("rk4",),
    fixed_step_solvers=("rk4",),
    reference="Nabhan & Rashed (2020), EGTRIB J. 17(2), eqs. 1-26 and Table 1 "
              "(see ballpass.simulate.nabhan2020)",
    accepts=_accepts,
    run=_run,
)
