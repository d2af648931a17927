"""``rotor2``: the rigid rotor on a cylindrical roller bearing of the NJ 305 paper.

A rigid rotor of mass m (2 DOF: x along the load line, y perpendicular, in the
bearing plane) runs on the Z rollers of a cylindrical roller bearing whose outer ring
is fixed to a rigid housing. The NJ 305 paper ("Dynamic behaviour of rotor roller bearing
system with bearing defects"; authors and year not printed), section 3.5:

    m x'' + c x' + sum_j Q_j cos(phi_j) = F_r + m g + m_u e (w^2 cos(theta) + w' sin(theta))
    m y'' + c y' + sum_j Q_j sin(phi_j) =             m_u e (w^2 sin(theta) - w' cos(theta))

with c = 200 N s/m the bearing damping of the paper's section 3.6 (the lumped viscous
damping of Harsha's 2-DOF rotor models, which the paper follows), theta the shaft angle,
w = theta' and the unbalance term m_u e w^2 the paper's equation needs (it prints m w^2,
without the unbalance mass and eccentricity).
Roller j sits at phi_j = phi_0 + 2 pi j / Z + (1 - r) theta / 2 (rigid cage at the fundamental train
frequency, r = d cos(alpha) / d_p) and is compressed by

    delta_j = x cos(phi_j) + y sin(phi_j) - c_r - h_j(t)

with c_r the radial clearance (negative: preload) and h_j the depth of any localized
defect under the roller. Its load is the Palmgren line contact (the paper's eqs. 1-2,
6), optionally with the constant contact damping c_d of the paper's section 2.3
(``Rotor2Parameters.contact_damping_ns_m``, default 0 so that the paper's damping is
not counted twice):

    Q_j = max(0, K delta_j^(10/9) + c_d (x' cos(phi_j) + y' sin(phi_j)))  for delta_j > 0,
    Q_j = 0                                                                otherwise,

K the load-deflection constant of one roller between both races
(:meth:`ballpass.Bearing.hertz_stiffness`: Palmgren delta = 3.84e-5 Q^0.9 / l^0.8 per
contact, inner and outer in series). With a misalignment gamma the roller is sliced
into k laminae of width w = l / k (the paper's section 3.4.2, eq. 6): lamina lambda at
axial position s_lambda from the roller centre is compressed by
delta_j + s_lambda gamma cos(phi_j) and carries (K / k) delta^(10/9), which sums to
Palmgren's law when gamma = 0 (the laminae then collapse to one exact term).

Ball bearings run the same equations with Hertz point contacts, Q = K delta^(3/2) and
K from :meth:`ballpass.Bearing.hertz_stiffness` (the 2-DOF rotor of Harsha's papers);
laminae need rollers, so a misalignment is refused there.

Assumptions (where the paper is silent or garbled):

* Rigid housing and outer ring; the sensor signal ``res.accel`` is the rotor's
  (journal's) acceleration projected on each sensor's radial direction,
  a_x cos(theta_s) + a_y sin(theta_s), AC-coupled: there is no structural resonance,
  so rotor2 does not represent ``envelope`` and ignores ``Scene.resonance_hz`` and the
  sensors' ``attenuation``.
* Rigid cage, no slip (``Scene.slip`` is ignored): the model is deterministic, as the
  paper's, so that Poincare sections show the dynamics, not the slip.
* Damping: the paper's rotor equation has one viscous term c Y2' with c = 200 N s/m;
  it acts on the rotor in both directions whether rollers touch or not. Per-contact
  damping (section 2.3) acts only along loaded rollers: alone it leaves the rotor's
  sideways rolling over a roller almost undamped (its lines of action are nearly
  radial), so it is an option, not the default. Rollers have no mass of their own
  (no centrifugal load, the paper's eq. 10 is dropped) and the roller-race contacts are
  lumped into one series contact.
* Defects are the :class:`~ballpass.Fault` depth profiles shared with ``sr5``: a
  notch of effective depth min(h, drop), the drop of the mating surfaces over the
  notch's width in the rolling plane (:meth:`ballpass.Fault.effective_depth_mm`: a
  cylinder of diameter d drops as a ball does), sharp or with half-cosine ramps;
  inner-race defects turn with the shaft, roller defects spin at the roller spin
  frequency and meet both races, the inner one deeper. The paper's sinusoidal roller
  profile (eqs. 4-5) is not used: its constants A_1, R_r/D_L are undefined there.
* Roller tilt: only a prescribed misalignment gamma (``Rotor2Parameters``); the paper's
  thrust-driven tilt needs an axial load the Scene does not have.
* The run starts at the quasi-static equilibrium of the healthy bearing under
  F_r + m g (:meth:`ballpass.Bearing.load_distribution`), at rest.
* Ground truth: the fault-edge crossings (``res.truth.fault_crossings``) follow from
  the kinematics in closed form (rollers keep the kinematic cage speed, no slip); they
  equal sr5's at ``slip=0`` (tests/test_rotor2.py).

Solvers: ``rk4`` (default; classical Runge-Kutta 4 at dt = ``DT_RK4_OMEGA`` /
omega_c, omega_c the linearised contact frequency, steps independent of the output
grid, restarted at the fault edges and ramp ends, which follow from the kinematics in
closed form, with ``RK4_RAMP_STEPS`` steps across each ramp, and where a roller's
contact closes or opens: a step over which a roller's compression (:func:`rotor2_gaps`)
changes sign is retaken up to its root on the step's quintic Hermite interpolant, and
the step on the loaded side of the kink graded towards it, since K delta^n has no
derivatives of order above n there; :func:`._second_order.rk4_for`), ``newmark`` (the
paper's method: average acceleration with Newton iterations on the contact forces,
:func:`._second_order.newmark_for`) and ``dopri5`` (adaptive Dormand-Prince on the same
equations), so each checks the others (tests/test_rotor2.py). Newmark's
average-acceleration scheme is unconditionally stable, but second order: the contact
mode rings for ~15 periods after every roller pass and impact and its phase error,
(omega dt)^2 / 12 per radian, accumulates, so the output acceleration is within 1e-2 of
dopri5 only for omega_c dt <~ 0.05 (about one step per 5 us output sample at 48 kHz).
RK4 at the default 0.3 errs 2.8e-3 to 3.9e-3 on the 6205 reference scene with and
without a defect and 3.9e-3 to 9.9e-3 on the NJ 305 paper's scene, where its rollers
leave and re-enter the load zone every pass and, with its defect, the rotor bounces off
its rollers (about 4 400 restarts per second there; 16 on the 6205 scene, whose Hertz
contacts' stiffness grows from zero: :data:`GAP_STIFFNESS`), the error falling 12-15x
per halved step there (fourth order: 16x; docs/rotor2_step.md).

Cost: every RK4 step evaluates the force twice at its midpoint and twice at its end;
the kinematics of those times (roller angles, the defect depth under each roller, the
unbalance angle) are computed once per time and cached in ``p``
(:func:`_kinematics`), their sines and cosines by a small rotation from the previous
time, and the explicit integrators skip the force's tangents, which only Newmark's
Newton iterations read. The steps are most of a call; the outputs at the internal grid
and the anti-alias decimation about a fifth at 48 kHz (docs/rotor2_step.md).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numba import njit

from .._validation import check_number
from ..scene import STANDARD_GRAVITY, Scene
from . import _kernels as _K
from . import _second_order as _I
from ._registry import Model
from ._shared import (
    OVERSAMPLE,
    SimulationUnstableError,
    add_noise,
    check_finite,
    check_solver_args,
    divisor_step,
    stiffness_and_load_zone,
    to_output_rate,
)
from .result import FaultCrossings, GroundTruth, SimulationResult
from .sr5 import MAX_DEFLECTION_RATIO, _fault_table

__all__ = ["Rotor2Parameters", "ROTOR2", "SOLVERS", "DT_RK4_OMEGA", "RK4_RAMP_STEPS",
           "DT_NEWMARK_OMEGA", "RAMP_STEPS",
           "elastic_limit_m",
           "contact_omega"]

#: solver name -> description
SOLVERS = {
    "rk4": "classical Runge-Kutta 4, fixed step DT_RK4_OMEGA / omega_c, restarted at the "
           "fault edges and ramp ends (known in closed form) and where a roller's contact "
           "closes or opens (located in the step); output by quintic Hermite "
           "interpolation",
    "newmark": "Newmark-beta, average acceleration (gamma 1/2, beta 1/4), Newton "
               "iterations on the contact forces with their tangent stiffness; fixed step",
    "dopri5": "Dormand-Prince 5(4) on the same equations, adaptive step with error control",
}

#: default rk4 step = DT_RK4_OMEGA / omega_c (see :func:`_rk4_breaks` for the steps on
#: defect ramps)
DT_RK4_OMEGA = 0.3
#: default Newmark step = DT_NEWMARK_OMEGA / omega_c, omega_c the linearised contact
#: natural frequency (rad/s) at the static equilibrium (about 1.2 us for the NJ 305 at
#: 500 N); the average-acceleration scheme's relative period error is
#: (omega dt)^2 / 12 = 5e-5 at 0.025
DT_NEWMARK_OMEGA = 0.025
#: ... and at most 1/RAMP_STEPS of the time a roller takes to cross the ramp of a
#: defect deep enough to unload it (depth beyond the static contact deflection; a sharp
#: edge counts the whole notch): its impacts are stiffer than the static contact. With
#: both limits the dynamic part of the displacement stays within a relative L2 error of
#: 1e-2 of dopri5 at rtol 1e-10 on the NJ 305 paper's scenes for as long as the motion is not
#: chaotic (benchmarks/seed003.py, docs/seed003.md; where it is, no two solvers agree
#: for long)
RAMP_STEPS = 128
#: rk4 steps across each defect ramp (a half-cosine in time)
RK4_RAMP_STEPS = 8
#: rk4 restarts where a roller's contact closes or opens (:func:`rotor2_gaps`) if within
#: the step its stiffness n K delta^(n - 1) reaches GAP_STIFFNESS times the most loaded
#: roller's static one, i.e. delta >= GAP_STIFFNESS^(1 / (n - 1)) delta_static
#: (:func:`_gap_tol`): 2.6e-4 delta_static for Palmgren's rollers (n = 10/9: the
#: stiffness switches on almost whole, and on the NJ 305 scene a restart missed at
#: 1e-2 delta_static costs 4x the error), 0.16 delta_static for Hertz's balls (n = 3/2:
#: it grows from zero; on the 6205 reference scene restarting at every closure changes
#: the error by 10 % for 1.4x the steps). Any value in 0.3-0.55 gives both scenes their
#: best error (docs/rotor2_step.md)
GAP_STIFFNESS = 0.4

# parameter vector: the sr5 kernel's speed/cage/contact slots (so _kernels'
# shaft_angle, shaft_rate and profile apply) and rotor2's own slots after them
P_MUE = _K.N_PARAMS          # unbalance m_u e, kg m
P_UPH = _K.N_PARAMS + 1      # unbalance phase at t = 0, rad
P_CD = _K.N_PARAMS + 2       # contact damping, N s/m
P_PHI0 = _K.N_PARAMS + 3     # angle of roller 0 at t = 0, rad
P_TILT = _K.N_PARAMS + 4     # misalignment gamma, rad
P_NLAM = _K.N_PARAMS + 5     # number of laminae k
P_LEN = _K.N_PARAMS + 6      # roller length l, m
P_NF = _K.N_PARAMS + 7       # number of faults
P_CR = _K.N_PARAMS + 8       # rotor (bearing) damping, N s/m
P_FAULTS = _K.N_PARAMS + 9   # fault table (sr5 layout), row after row


@dataclass(frozen=True)
class Rotor2Parameters:
    """Structural parameters of the ``rotor2`` model (defaults: the paper, section 3.6).

    Parameters
    ----------
    rotor_mass_kg : float, optional
        Mass m of the rigid rotor with the inner ring, kg, in (0, 1e4]. Default 1.0
        ("the mass of the rotor roller bearing system is 1 kg", the paper's section 3.6).
    bearing_damping_ns_m : float, optional
        Viscous damping c of the rotor in the bearing, N s/m, in [0, 1e6], the c Y2'
        of the paper's rotor equation (section 3.5). Default 200 ("damping factor of the
        bearing is 200 N.s/m", the paper's section 3.6).
    contact_damping_ns_m : float, optional
        Viscous damping c_d of each loaded roller contact along its line of action,
        N s/m, in [0, 1e6] (the constant lubricant damping of the paper's section 2.3).
        Default 0: the paper's 200 N s/m is the bearing damping above.
    unbalance_mass_kg : float, optional
        Unbalance mass m_u, kg, in [0, rotor_mass_kg]. Default 0.05 (the paper's section
        3.6: 50 g).
    unbalance_eccentricity_m : float, optional
        Its eccentricity e, m, in [0, 0.1]. Default 20e-6 (the paper's section 3.6). The
        unbalance force is m_u e w^2 (the paper's eq. prints m w^2).
    unbalance_phase_deg : float, optional
        Angle of the unbalance at t = 0, degrees from the load line. Default 0.
    misalignment_rad : float, optional
        Tilt gamma of the inner ring relative to the outer about the axis perpendicular
        to the load line, rad, with abs(gamma) <= 0.01. Default 0 (aligned; the laminae
        collapse to Palmgren's law exactly).
    n_laminae : int, optional
        Laminae k per roller when ``misalignment_rad`` is not 0 (the paper's eq. 6), in
        [1, 100]. Default 10.
    cage_angle_deg : float, optional
        Angle of roller 0 at t = 0, degrees from the load line. Default 0 (a roller on
        the load line).

    Examples
    --------
    >>> from ballpass.simulate.rotor2 import Rotor2Parameters
    >>> p = Rotor2Parameters()
    >>> round(p.unbalance_mass_kg * p.unbalance_eccentricity_m * (2000 * 3.14159 / 30) ** 2, 3)
    0.044
    """

    rotor_mass_kg: float = 1.0
    bearing_damping_ns_m: float = 200.0
    contact_damping_ns_m: float = 0.0
    unbalance_mass_kg: float = 0.05
    unbalance_eccentricity_m: float = 20e-6
    unbalance_phase_deg: float = 0.0
    misalignment_rad: float = 0.0
    n_laminae: int = 10
    cage_angle_deg: float = 0.0

    def __post_init__(self) -> None:
        m = check_number("rotor_mass_kg", self.rotor_mass_kg, 0.0, 1e4, lo_open=True,
                         unit="kg")
        for name in ("bearing_damping_ns_m", "contact_damping_ns_m"):
            check_number(name, getattr(self, name), 0.0, 1e6, unit="N s/m")
        check_number("unbalance_mass_kg", self.unbalance_mass_kg, 0.0, m, unit="kg")
        check_number("unbalance_eccentricity_m", self.unbalance_eccentricity_m, 0.0, 0.1,
                     unit="m")
        check_number("unbalance_phase_deg", self.unbalance_phase_deg, -1e6, 1e6, unit="deg")
        check_number("misalignment_rad", self.misalignment_rad, -0.01, 0.01, unit="rad")
        check_number("cage_angle_deg", self.cage_angle_deg, -1e6, 1e6, unit="deg")
        if isinstance(self.n_laminae, bool) or not isinstance(self.n_laminae, int):
            raise TypeError(f"n_laminae must be an int, got {self.n_laminae!r}")
        if not 1 <= self.n_laminae <= 100:
            raise ValueError(f"n_laminae must be in [1, 100], got {self.n_laminae}")


# ---------------------------------------------------------------------- kernels
@njit(cache=True, error_model="numpy", inline="always")
def _defect_depth(j, phi, theta, n_faults, p):
    """Depth of the defects under roller j at roller angle phi, shaft angle theta, m."""
    depth = 0.0
    for i in range(n_faults):
        r = P_FAULTS + i * _K.N_FCOLS
        kind = int(p[r + _K.F_KIND])
        half, d, ramp = p[r + _K.F_HALF], p[r + _K.F_DEPTH], p[r + _K.F_RAMP]
        if kind == _K.KIND_BALL:
            if int(p[r + _K.F_ELEM]) == j:
                spin = p[r + _K.F_CENTRE] + p[_K.P_SPIN] * (phi - p[r + _K.F_PSI0])
                # facing the outer race at spin phase 0, the inner (deeper) at pi
                depth += _K.profile(_K.wrap_pi(spin), half, d, ramp)
                depth += _K.profile(_K.wrap_pi(spin - math.pi), half,
                                    p[r + _K.F_DEPTH_IN], ramp)
        else:
            centre = p[r + _K.F_CENTRE]
            if kind == _K.KIND_INNER:
                centre += theta
            depth += _K.profile(_K.wrap_pi(phi - centre), half, d, ramp)
    return depth


@njit(cache=True, error_model="numpy", inline="always")
def _contact(delta, vn, tilt, n_lam, p):
    """One roller's load Q (N), dQ/d(delta) (N/m) and contact damping (N s/m), given its
    compression delta = x cos(phi) + y sin(phi) - c_r - h (m, the defect depth h under
    it already taken off), the rotor's velocity along it vn (m/s) and the tilt across
    its length l gamma cos(phi) (m). Exactly 0 load when separated. ``n_lam`` is
    ``p[P_NLAM]`` as an int."""
    n = p[_K.P_NH]
    if n_lam == 1:  # aligned: one Palmgren (or Hertz) term
        if delta <= 0.0:
            return 0.0, 0.0, 0.0
        # Hertz's 3/2 as delta sqrt(delta): a pow costs several times a square root
        q = p[_K.P_KH] * (delta * math.sqrt(delta) if n == 1.5 else delta ** n)
        dq = n * q / delta
    else:
        k_lam = p[_K.P_KH] / n_lam
        q = 0.0
        dq = 0.0
        for lam in range(n_lam):
            d = delta + ((lam + 0.5) / n_lam - 0.5) * tilt
            if d > 0.0:
                q_lam = k_lam * d ** n
                q += q_lam
                dq += n * q_lam / d
        if q == 0.0:
            return 0.0, 0.0, 0.0
    damping = p[P_CD]
    q += damping * vn
    if q <= 0.0:  # the damping would pull: the contact lets go
        return 0.0, 0.0, 0.0
    return q, dq, damping


@njit(cache=True, error_model="numpy", inline="always")
def _kinematics(t, p):
    """Offset k0 in ``p`` of the kinematics at time t, recomputed unless they are the
    last call's: p[k0] = t, p[k0 + 1], p[k0 + 2] the cos and sin of the unbalance
    angle, then per roller j the cos and sin of phi_j and the defect depth under it (m)
    at p[k0 + 3 + 3 j ...], then the rotation caches of phi_0 and of the unbalance
    angle (:func:`._kernels.cached_cos_sin`, 4 slots each). A Runge-Kutta step
    evaluates the force twice at each of two times (its midpoint, its end), with the
    same kinematics. The roller angles phi_j = phi_0 + 2 pi j / Z + c theta are stepped
    by a rotation of 2 pi / Z, and phi_0 and the unbalance angle by a rotation from the
    previous time: no sine or cosine at most times (they cost a quarter of a step
    otherwise)."""
    n_faults = int(p[P_NF])
    k0 = P_FAULTS + n_faults * _K.N_FCOLS
    if p[k0] == t:
        return k0
    z = int(p[_K.P_Z])
    theta = _K.shaft_angle(t, p)
    phi = p[P_PHI0] + p[_K.P_CAGE] * theta
    kc = k0 + 3 + 3 * z  # the rotation caches
    cs, sn = _K.cached_cos_sin(phi, p[kc:kc + 4])
    pitch = _K.TWO_PI / z
    cz, sz = p[_K.P_COS_STEP], p[_K.P_SIN_STEP]
    for j in range(z):
        r = k0 + 3 + 3 * j
        p[r] = cs
        p[r + 1] = sn
        p[r + 2] = _defect_depth(j, phi, theta, n_faults, p) if n_faults > 0 else 0.0
        cs, sn = cs * cz - sn * sz, sn * cz + cs * sz
        phi += pitch
    p[k0 + 1], p[k0 + 2] = _K.cached_cos_sin(theta + p[P_UPH], p[kc + 4:kc + 8])
    p[k0] = t
    return k0


@njit(cache=True, error_model="numpy", inline="always")
def _force(t, x, v, p, f, kx, kv, tangents):
    """Generalised force of M a + f = 0 (contacts minus loads) into f and, with
    ``tangents`` (a constant at each caller), its tangents into kx and kv."""
    k0 = _kinematics(t, p)
    z = int(p[_K.P_Z])
    clear = p[_K.P_CLEAR]
    length_tilt = p[P_LEN] * p[P_TILT]
    reach = 0.5 * abs(length_tilt)  # the most a tilt brings a lamina closer, m
    n_lam = int(p[P_NLAM])
    x0, x1, v0, v1 = x[0], x[1], v[0], v[1]
    # sums in scalars (stores into f, kx, kv may alias x and v for the compiler)
    f0 = f1 = kxx = kxy = kyy = cxx = cxy = cyy = 0.0
    for j in range(z):
        r = k0 + 3 + 3 * j
        cs, sn = p[r], p[r + 1]
        delta = x0 * cs + x1 * sn - clear
        if delta + reach <= 0.0:  # separated, whatever the defect and the tilt
            continue
        q, dq, c = _contact(delta - p[r + 2], v0 * cs + v1 * sn, length_tilt * cs, n_lam, p)
        if q > 0.0:
            f0 += q * cs
            f1 += q * sn
            if tangents:
                kxx += dq * cs * cs
                kxy += dq * cs * sn
                kyy += dq * sn * sn
                cxx += c * cs * cs
                cxy += c * cs * sn
                cyy += c * sn * sn
    c_r = p[P_CR]
    w = _K.shaft_rate(t, p)
    dw = (p[_K.P_W1] - p[_K.P_W0]) / p[_K.P_T]
    mue = p[P_MUE]
    cu, su = p[k0 + 1], p[k0 + 2]
    f[0] = f0 + c_r * v0 - p[_K.P_FR] - p[_K.P_MS] * p[_K.P_G] - mue * (w * w * cu + dw * su)
    f[1] = f1 + c_r * v1 - mue * (w * w * su - dw * cu)
    if tangents:
        kx[0, 0] = kxx
        kx[0, 1] = kx[1, 0] = kxy
        kx[1, 1] = kyy
        kv[0, 0] = cxx + c_r
        kv[0, 1] = kv[1, 0] = cxy
        kv[1, 1] = cyy + c_r


@njit(cache=True, error_model="numpy", inline="always")
def rotor2_force(t, x, v, p, f, kx, kv):
    """Generalised force of M a + f = 0 and its tangents (:func:`_force`), for the
    Newmark integrator of :mod:`._second_order`, whose Newton iterations use them."""
    _force(t, x, v, p, f, kx, kv, True)


@njit(cache=True, error_model="numpy", inline="always")
def rotor2_force_only(t, x, v, p, f, kx, kv):
    """The generalised force alone (kx, kv untouched), for the explicit integrators
    (RK4, DOPRI5), which never read the tangents."""
    _force(t, x, v, p, f, kx, kv, False)


@njit(cache=True, error_model="numpy", inline="always")
def rotor2_gaps(t, x, p, g):
    """The compressions at which the contact law has its kinks, m, into g (Z k,): roller
    j's lamina lambda at g[j k + lambda] (k = ``p[P_NLAM]`` laminae, one when aligned),
    delta_j + s_lambda gamma l cos(phi_j) of :func:`_contact` with the defect depth
    under the roller taken off; Q = K delta^n starts (its derivatives of order above n
    do not exist) where one changes sign."""
    k0 = _kinematics(t, p)
    z = int(p[_K.P_Z])
    n_lam = int(p[P_NLAM])
    length_tilt = p[P_LEN] * p[P_TILT]
    clear = p[_K.P_CLEAR]
    for j in range(z):
        r = k0 + 3 + 3 * j
        cs, sn = p[r], p[r + 1]
        delta = x[0] * cs + x[1] * sn - clear - p[r + 2]
        if n_lam == 1:
            g[j] = delta
        else:
            for lam in range(n_lam):
                g[j * n_lam + lam] = delta + ((lam + 0.5) / n_lam - 0.5) * length_tilt * cs


@njit(cache=True, error_model="numpy")
def _roller(j, t, x, v, p):
    """Roller j at time t for rotor state (x, v): load Q (N), dQ/d(delta) (N/m), contact
    damping (N s/m) and the cos and sin of its angle (the force's own arithmetic, one
    roller at a time)."""
    k0 = _kinematics(t, p)
    r = k0 + 3 + 3 * j
    cs, sn = p[r], p[r + 1]
    q, dq, c = _contact(x[0] * cs + x[1] * sn - p[_K.P_CLEAR] - p[r + 2],
                        v[0] * cs + v[1] * sn, p[P_LEN] * p[P_TILT] * cs, int(p[P_NLAM]), p)
    return q, dq, c, cs, sn


@njit(cache=True, error_model="numpy")
def _loads_many(t, x, v, p, out):
    """Roller loads (N) at times t (n,) for states x, v (n, 2) into out (n, Z)."""
    for i in range(t.shape[0]):
        for j in range(out.shape[1]):
            out[i, j] = _roller(j, t[i], x[i], v[i], p)[0]


#: the integrators compiled for rotor2's force
_newmark = _I.newmark_for(rotor2_force)
_dopri5 = _I.dopri5_for(rotor2_force_only)
_rk4 = _I.rk4_for(rotor2_force_only, rotor2_gaps)


# ---------------------------------------------------------------------- binding
def elastic_limit_m(bearing) -> float:
    """Largest contact deflection rotor2 accepts, m: ``MAX_DEFLECTION_RATIO`` (1 %) of the
    roller diameter, the elastic limit sr5 uses (ISO 76 static rating, 4 GPa)."""
    return MAX_DEFLECTION_RATIO * bearing.element_diameter_m


@dataclass(frozen=True)
class _Bound:
    """A scene bound to the kernel: parameters, initial state and scales."""

    p: np.ndarray
    x0: np.ndarray
    x_scale: np.ndarray
    omega: float
    mass: float
    t_impact: float
    t_ramp: np.ndarray
    levels: np.ndarray
    static_deflection: float


def _static_load(scene: Scene, params: Rotor2Parameters) -> float:
    """Static load on the bearing along the load line: F_r + m g, N."""
    g = STANDARD_GRAVITY if scene.gravity else 0.0
    return scene.radial_load_n + params.rotor_mass_kg * g


def contact_omega(scene: Scene, params: Rotor2Parameters | None = None) -> float:
    """Linearised natural frequency of the rotor on its loaded rollers at the static
    equilibrium, rad/s: sqrt(sum_j dQ_j/d(delta) cos^2(phi_j) / m).

    Without a static load (no contact) the stiffness at 1 N of load is used.

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate.rotor2 import contact_omega
    >>> round(contact_omega(bp.Scene(bearing="NJ305", radial_load_n=0.0)) / (2 * 3.14159))
    1771
    """
    params = params or Rotor2Parameters()
    b = scene.bearing
    ld = b.load_distribution(max(_static_load(scene, params), 1.0),
                             cage_angle_deg=params.cage_angle_deg)
    return _omega_of(ld, params.rotor_mass_kg)


def _omega_of(ld, mass: float) -> float:
    """:func:`contact_omega` of the static equilibrium ``ld``
    (:meth:`ballpass.Bearing.load_distribution`) of a rotor of ``mass`` kg, rad/s."""
    psi = np.radians(ld.element_angles_deg)
    radial = ld.deflection_m * np.cos(psi) + ld.lateral_deflection_m * np.sin(psi)
    delta = np.maximum(radial - ld.clearance_m, 0.0)
    n = ld.load_exponent
    dq = np.where(delta > 0.0, n * ld.stiffness * delta ** (n - 1.0), 0.0)
    return float(math.sqrt(np.sum(dq * np.cos(psi) ** 2) / mass))


def _bind(scene: Scene, params: Rotor2Parameters) -> _Bound:
    """Check the scene against the model's limits and build the kernel parameters."""
    refusal = _accepts(scene)
    if refusal:
        raise ValueError(f"model 'rotor2' cannot take this scene: {refusal}")
    b = scene.bearing
    if b.element != "roller" and params.misalignment_rad != 0.0:
        raise ValueError(f"misalignment_rad={params.misalignment_rad:g} needs the laminae of "
                         f"a roller; bearing {b.name!r} has balls (use misalignment_rad=0)")
    load = _static_load(scene, params)
    kh, ld = stiffness_and_load_zone(b, load, None, params.cage_angle_deg)
    deflection = ld.deflection_m - b.radial_clearance_m
    limit = elastic_limit_m(b)
    if ld.q_max_n > 0 and (ld.q_max_n / kh) ** (1.0 / b.load_exponent) > limit:
        raise ValueError(
            f"radial_load_n={scene.radial_load_n:g} N (plus the rotor's weight) deflects the "
            f"most loaded roller beyond the elastic limit {limit * 1e6:.0f} um "
            f"({MAX_DEFLECTION_RATIO:.0%} of the roller diameter)")
    speed = scene.speed
    orders = b.frequencies(1.0)  # the kinematic frequencies per unit shaft speed
    cage_ratio = orders.ftf
    z = b.n_elements
    psi0 = math.radians(params.cage_angle_deg) + 2.0 * math.pi * np.arange(z) / z
    faults, levels = _fault_table(scene, psi0, kh)
    # parameters, the fault table, then the kinematics cache of _kinematics (its time
    # NaN: none cached yet) and its two rotation caches (zero: empty)
    p = np.zeros(P_FAULTS + faults.size + 3 + 3 * b.n_elements + 8)
    p[_K.P_MS] = params.rotor_mass_kg
    p[_K.P_KH] = kh
    p[_K.P_NH] = b.load_exponent
    p[_K.P_CLEAR] = b.radial_clearance_m
    p[_K.P_FR] = scene.radial_load_n
    p[_K.P_G] = STANDARD_GRAVITY if scene.gravity else 0.0
    p[_K.P_W0] = speed.rpm_start * math.pi / 30.0
    p[_K.P_W1] = speed.rpm_end * math.pi / 30.0
    p[_K.P_T] = scene.duration_s
    p[_K.P_CAGE] = cage_ratio
    p[_K.P_SPIN] = orders.bsf / orders.ftf
    p[_K.P_Z] = z
    p[_K.P_COS_STEP] = math.cos(2.0 * math.pi / z)
    p[_K.P_SIN_STEP] = math.sin(2.0 * math.pi / z)
    p[P_MUE] = params.unbalance_mass_kg * params.unbalance_eccentricity_m
    p[P_UPH] = math.radians(params.unbalance_phase_deg)
    p[P_CD] = params.contact_damping_ns_m
    p[P_CR] = params.bearing_damping_ns_m
    p[P_PHI0] = math.radians(params.cage_angle_deg)
    p[P_TILT] = params.misalignment_rad
    p[P_NLAM] = params.n_laminae if params.misalignment_rad != 0.0 else 1
    p[P_LEN] = (b.roller_length_mm or 0.0) * 1e-3
    p[P_NF] = faults.shape[0]
    p[P_FAULTS:P_FAULTS + faults.size] = faults.ravel()
    p[P_FAULTS + faults.size] = math.nan
    x0 = np.array([ld.deflection_m, ld.lateral_deflection_m])
    scale = abs(b.radial_clearance_m) + max(deflection, 1e-7)
    # time to cross the ramps of the defects deep enough to unload a roller
    w_max = max(p[_K.P_W0], p[_K.P_W1])
    rate = {_K.KIND_OUTER: cage_ratio * w_max, _K.KIND_INNER: (1.0 - cage_ratio) * w_max,
            _K.KIND_BALL: p[_K.P_SPIN] * cage_ratio * w_max}
    static = (ld.q_max_n / kh) ** (1.0 / b.load_exponent)
    t_impact = min((2.0 * row[_K.F_HALF] * (row[_K.F_RAMP] or 1.0) / rate[int(row[_K.F_KIND])]
                    for row in faults if max(row[_K.F_DEPTH], row[_K.F_DEPTH_IN]) > static),
                   default=math.inf)
    # duration of each fault's ramps (0: sharp edges)
    t_ramp = np.array([2.0 * row[_K.F_HALF] * row[_K.F_RAMP] / rate[int(row[_K.F_KIND])]
                       for row in faults])
    # the linearised contact frequency from the same equilibrium (contact_omega takes at
    # least 1 N, so that an unloaded rotor still has a stiffness)
    omega = _omega_of(ld if load >= 1.0 else stiffness_and_load_zone(
        b, 1.0, kh, params.cage_angle_deg)[1], params.rotor_mass_kg)
    return _Bound(p=p, x0=x0, x_scale=np.full(2, scale), omega=omega,
                  mass=params.rotor_mass_kg, t_impact=t_impact, t_ramp=t_ramp, levels=levels,
                  static_deflection=static)


def _crossings(scene: Scene, p: np.ndarray, levels: np.ndarray, t_end: float) -> FaultCrossings:
    """Times in [0, t_end] at which rollers cross the fault edges and ramp ends, s.

    rotor2's rollers keep the kinematic cage speed (no slip), so every path's offset
    from a fault centre is linear in the shaft angle theta, as :func:`_defect_depth`
    computes it: ``phi_j - centre`` for the outer race (roller angle ``phi_j = phi_0 +
    2 pi j / Z + c theta``), ``phi_j - centre - theta`` for the inner race, ``centre +
    s c theta - k pi`` for face ``k`` of a ball defect (``s`` the spin ratio). Each
    level is crossed at ``theta = (level - offset_0 + 2 pi m) / rate`` for whole ``m``,
    and the time follows from inverting the shaft angle of the speed profile (exact;
    the solvers need no events, so these are ground truth only).
    """
    z = int(p[_K.P_Z])
    cage, spin = p[_K.P_CAGE], p[_K.P_SPIN]
    w0, w1 = p[_K.P_W0], p[_K.P_W1]
    accel = 0.5 * (w1 - w0) / p[_K.P_T]  # theta = w0 t + accel t^2
    theta_end = w0 * t_end + accel * t_end * t_end
    names = np.array(["entry", "ramp_end", "ramp_start", "exit"])
    times, faults, paths, edges = [np.empty(0)], [np.empty(0, int)], [np.empty(0, int)], [names[:0]]
    for i, (fault, lv) in enumerate(zip(scene.faults, levels, strict=True)):
        r = P_FAULTS + i * _K.N_FCOLS
        centre = p[r + _K.F_CENTRE]
        if fault.kind == "ball":
            offset0 = centre - np.pi * np.arange(2)  # face 0 meets the outer race
            rate = spin * cage
        else:
            offset0 = p[P_PHI0] + 2.0 * np.pi * np.arange(z) / z - centre
            rate = cage - 1.0 if fault.kind == "inner" else cage
        for k in range(4):
            if not np.isfinite(lv[k]):
                continue  # no ramp: no ramp ends
            # turns m with theta in [0, theta_end] on every path, one spare at each end
            first = (offset0 - lv[k]) / (2.0 * np.pi)
            last = first + rate * theta_end / (2.0 * np.pi)
            m = np.arange(np.floor(min(first.min(), last.min())) - 1,
                          np.ceil(max(first.max(), last.max())) + 2)
            theta = (lv[k] - offset0[:, None] + 2.0 * np.pi * m) / rate  # (path, turn)
            path, turn = np.nonzero((theta >= 0.0) & (theta <= theta_end))
            theta = theta[path, turn]
            t = (theta / w0 if accel == 0.0
                 else 2.0 * theta / (w0 + np.sqrt(w0 * w0 + 4.0 * accel * theta)))
            times.append(t)
            faults.append(np.full(t.size, i))
            paths.append(path)
            # an inner-race offset falls: it meets its levels from the top down
            edges.append(np.full(t.size, names[k] if rate > 0 else names[3 - k]))
    t = np.concatenate(times)
    order = np.argsort(t, kind="stable")
    return FaultCrossings(time_s=t[order], fault=np.concatenate(faults)[order],
                          element=np.concatenate(paths)[order],
                          edge=np.concatenate(edges)[order])


def _gap_tol(bound: _Bound) -> float:
    """Compression (m) a closing or opening contact must reach within an rk4 step for
    the step to restart on it (:data:`GAP_STIFFNESS`)."""
    n = bound.p[_K.P_NH]
    return bound.static_deflection * GAP_STIFFNESS ** (1.0 / (n - 1.0))


def _rk4_breaks(cr: FaultCrossings, bound: _Bound, t_end: float, dt_max: float):
    """Breaks of the rk4 solver and the largest step between them.

    The breaks are the fault-edge and ramp-end crossings ``cr`` of :func:`_crossings`
    (where the defect depth under a roller is not smooth in time); a segment that lies on a
    ramp (from an ``entry`` or ``ramp_start`` crossing to the ramp's end) takes steps
    of at most 1 / :data:`RK4_RAMP_STEPS` of the ramp's duration, the others
    ``dt_max``.
    """
    keep = (cr.time_s > 0.0) & (cr.time_s < t_end)
    breaks = np.unique(cr.time_s[keep])
    seg_dt = np.full(breaks.size + 1, dt_max)
    if breaks.size:
        starts = np.concatenate(([0.0], breaks))
        ends = np.concatenate((breaks, [t_end]))
        mid = 0.5 * (starts + ends)
        ramp_in = np.isin(cr.edge, ("entry", "ramp_start"))
        for i in np.unique(cr.fault):
            sel = ramp_in & (cr.fault == i)
            t_ramp = bound.t_ramp[i]
            if not sel.any() or not t_ramp > 0.0:
                continue
            t0 = np.sort(cr.time_s[sel])
            j = np.searchsorted(t0, mid, side="right") - 1
            on = (j >= 0) & (mid < t0[np.maximum(j, 0)] + t_ramp)
            seg_dt[on] = np.minimum(seg_dt[on], t_ramp / RK4_RAMP_STEPS)
    return breaks, seg_dt


def _accepts(scene: Scene) -> str | None:
    """rotor2 takes roller (line contact) and ball (point contact) bearings whose
    clearance stays elastic."""
    b = scene.bearing
    limit = elastic_limit_m(b)
    if b.radial_clearance_m < -limit:
        return (f"radial_clearance_mm={b.radial_clearance_mm:g} is a preload beyond the "
                f"elastic limit: it must be >= {-limit * 1e3:.4g} mm ({MAX_DEFLECTION_RATIO:.0%}"
                " of the roller diameter)")
    return None


def _run(scene: Scene, solver: str, *, dt=None, rtol=None, atol=None, params=None,
         return_forces: bool = False, oversample: int = OVERSAMPLE) -> SimulationResult:
    """Simulate ``scene`` with rotor2 (arguments validated by :func:`simulate`)."""
    # again with the resolved solver: simulate() checks "auto" before resolving it, so
    # rtol with the default newmark would pass silently
    check_solver_args("rotor2", solver, tuple(SOLVERS), ("rk4", "newmark"), dt, rtol, atol,
                      oversample)
    if params is None:
        params = Rotor2Parameters()
    elif not isinstance(params, Rotor2Parameters):
        raise TypeError(f"params must be Rotor2Parameters for the rotor2 model, got "
                        f"{type(params).__name__}")
    t_wall = time.perf_counter()
    bound = _bind(scene, params)
    n_samples = scene.n_samples
    h_out = 1.0 / (scene.fs * oversample)
    n_out = n_samples * oversample
    mass = np.eye(2) * bound.mass
    info = {"solver": solver, "internal_fs": 1.0 / h_out,
            "contact_hz": bound.omega / (2.0 * math.pi)}
    # the crossings up to the end of the internal grid: the rk4 breaks, and the ground
    # truth up to the last output sample (each crossing is a closed form of its own)
    t_end = (n_out - 1) * h_out
    crossings = _crossings(scene, bound.p, bound.levels, t_end)
    if solver == "rk4":
        dt_max = dt if dt is not None else DT_RK4_OMEGA / bound.omega
        breaks, seg_dt = _rk4_breaks(crossings, bound, t_end, dt_max)
        xs = np.empty((n_out, 2))
        vs = np.empty((n_out, 2))
        acc = np.empty((n_out, 2))
        # x and v are only read for the contact forces, at the output samples: without
        # them only row 0 is written (the untouched rows cost no memory traffic)
        n_gaps = scene.bearing.n_elements * int(bound.p[P_NLAM])
        status, n_steps, n_restarts, t_fail = _rk4(
            bound.p, np.linalg.inv(mass), bound.x0, np.zeros(2), h_out, n_out, breaks,
            seg_dt, n_gaps, _gap_tol(bound), 1e4, bound.x_scale,
            oversample if return_forces else n_out, xs, vs, acc)
        info.update(n_steps=int(n_steps), n_rejected=0, dt_s=dt_max, n_events=breaks.size,
                    n_contact_restarts=int(n_restarts))
        step_text = f"dt = {dt_max:.3g} s"
    elif solver == "newmark":
        dt_req = dt if dt is not None else min(DT_NEWMARK_OMEGA / bound.omega,
                                               bound.t_impact / RAMP_STEPS)
        n_sub, step = divisor_step(h_out, dt_req, dt)
        xs = np.empty((n_out, 2))
        vs = np.empty((n_out, 2))
        acc = np.empty((n_out, 2))
        status, n_steps, max_iter, t_fail = _newmark(
            bound.p, mass, bound.x0, np.zeros(2), h_out, n_sub, n_out,
            bound.x_scale, 1e-10, 1e4, xs, vs, acc)
        info.update(n_steps=int(n_steps), n_rejected=0, dt_s=step,
                    newton_max_iter=int(max_iter))
        step_text = f"dt = {step:.3g} s"
    else:
        rtol_v = 1e-6 if rtol is None else float(rtol)
        factor = 1.0 if atol is None else float(atol)
        atol_v = rtol_v * factor * np.concatenate((bound.x_scale, bound.x_scale * bound.omega))
        ys = np.empty((n_out, 4))
        dys = np.empty((n_out, 4))
        y0 = np.concatenate((bound.x0, np.zeros(2)))
        status, n_acc, n_rej, h_min, t_fail = _dopri5(
            bound.p, np.linalg.inv(mass), y0, h_out, n_out, rtol_v, atol_v,
            0.5 * math.pi / bound.omega, int(200 * n_out + 10_000), ys, dys)
        xs, vs, acc = ys[:, :2], ys[:, 2:], dys[:, 2:]
        info.update(n_steps=int(n_acc), n_rejected=int(n_rej), dt_min_s=float(h_min),
                    rtol=rtol_v)
        step_text = f"rtol = {rtol_v:g}"
    if status != _I.STATUS_OK:
        raise SimulationUnstableError(
            f"rotor2 with solver {solver!r} ({step_text}) failed at t = {t_fail:.6g} s: "
            f"{_I.STATUS_REASONS[status]}. Try a smaller dt / rtol. Scene: {scene!r}")
    info["integration_time_s"] = time.perf_counter() - t_wall

    angles = np.radians([s.angle_deg for s in scene.sensors])
    out = acc @ np.vstack((np.cos(angles), np.sin(angles)))  # (n_out, n_sensors)
    accel = add_noise(scene, to_output_rate(out, n_samples, oversample))
    check_finite(scene, accel, "rotor2")

    t = np.arange(n_samples) / scene.fs
    idx = np.arange(n_samples) * oversample
    shaft_angle = scene.speed.shaft_angle(t, scene.duration_s)
    forces = element_angles = displacement = None
    if return_forces:
        z = scene.bearing.n_elements
        forces = np.empty((n_samples, z))
        _loads_many(idx * h_out, np.ascontiguousarray(xs[idx]), np.ascontiguousarray(vs[idx]),
                    bound.p, forces)
        forces = forces.T.copy()
        element_angles = (bound.p[P_PHI0] + 2.0 * math.pi * np.arange(z)[:, None] / z
                          + bound.p[_K.P_CAGE] * shaft_angle[None, :])
        displacement = xs[idx].T.copy()
    truth = GroundTruth.of_scene(
        scene, t,
        FaultCrossings(*(getattr(crossings, k)[crossings.time_s <= t[-1]]
                         for k in ("time_s", "fault", "element", "edge"))),
        contact_forces=forces,
        element_angles=element_angles,
        displacement=displacement,
    )
    info["wall_time_s"] = time.perf_counter() - t_wall
    return SimulationResult.of_scene(scene, accel, t, truth, info)


#: the registry entry
ROTOR2 = Model(
    name="rotor2",
    description="the NJ 305 paper's rigid rotor (2 DOF) on a roller (Palmgren line "
                "contacts) or ball (Hertz) bearing: clearance, unbalance, gravity, "
                "localized defects; RK4 (Newmark-beta as in the paper on request)",
    represents=frozenset({"rotor_dynamics", "contact_dynamics", "contact_forces",
                          "varying_speed"}),
    # wall time per simulated second against sr5, side by side, on the 6205 reference
    # scene at 48 kHz with the rk4 default: 0.85 (IQR 0.83-0.86, CPU time 0.85; 15
    # interleaved rounds on a quiet machine, benchmarks/models_cost.py,
    # docs/models_cost.md; 0.99 on a loaded one; 1.17 before the cached rotations, the
    # per-step output coefficients and the binding computed once); 0.60 at 12 kHz; 25x
    # with the old Newmark step. 1.0, not below: on a tie the registry keeps sr5 first
    relative_cost=1.0,
    solvers=tuple(SOLVERS),
    fixed_step_solvers=("rk4", "newmark"),
    reference="Dynamic behaviour of rotor roller bearing system with bearing defects "
              "(NJ 305; authors and year not printed); Palmgren (1959) line "
              "contact; Newmark (1959)",
    accepts=_accepts,
    run=_run,
)
