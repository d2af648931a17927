"""``multibody``: the planar multibody bearing of Nakhaeinejad & Bryant (2011).

Every ball is a body: the cage speed, the slip of each ball, the load sharing, the
centrifugal load and the two impacts of a ball crossing a notch come out of the
equations of motion instead of being prescribed. The high-fidelity end of the model
hierarchy, and the reference the cheaper models are judged against.

Model
-----
Bodies (planar, global frame, x along the load line towards the load zone, y at
+90 deg in the direction of rotation; Newton-Euler, Nakhaeinejad & Bryant eqs. 19-25):

* **inner race** with its share of the shaft: x, y, rotation. It carries the radial
  load F_r and its weight along the load line, and is driven through a torsional
  coupling (stiffness k_d, damping c_d) by a motor that follows the scene's speed
  profile exactly, against the load and seal friction torques of eqs. 15-17;
* **outer race** in a housing with stiffness and damping (Nakhaeinejad & Bryant Table 1:
  4e7 N/mm); its rotation is locked by the housing fit (the paper's outer-race
  rotation DOF carries no load in a fixed housing);
* **Z balls**: x, y and spin each;
* **a cage** (rotation about the housing centre) whose pockets hold the balls apart
  with a tangential spring-damper beyond the pocket clearance. The paper neglects the
  cage; without one, balls that leave the load zone lose traction and drift, and
  nothing would stop two of them passing through each other. The cage also carries the
  lubricant drag of the rolling set (eq. 18), which is what makes the balls slip when
  traction is short.

That is 3 (Z + 2) degrees of freedom, 33 for nine balls, as in the paper (with the
cage's rotation in place of the locked outer-race rotation).

Contacts (each ball with each race; Nakhaeinejad & Bryant eqs. 5-14):

* normal force ``Q = K delta^1.5 + tau (1.5 K delta^0.5) d(delta)/dt``, clipped at 0:
  Hertz (K of each race from :meth:`ballpass.Bearing.contact_stiffnesses`, the exact
  elliptic-integral form of eqs. 6-8) with Kramer's damping (eq. 9: b = tau k, tau =
  1e-5 s; the print's 1e-2 is read as Kramer's 1e-5, his range being (0.25-2.5) 1e-5 k)
  applied with the contact's own linearised stiffness k = dQ/d(delta), so the damping vanishes with
  the contact and the force is exactly 0 while separated;
* traction ``F_t = mu(s) Q`` against the sliding velocity, with the slide-roll law of
  eq. 13 applied odd-symmetrically (mu(-s) = -mu(s); mu(0) = 0, so it is continuous),
  s = |sliding speed| / rolling speed (mean surface speed relative to the contact); the
  film parameter Lambda blends it with the hydrodynamic law by eq. 12 with the
  breakpoint 1.5 in the denominator (the print's 1.6 breaks continuity at Lambda = 1.5).
  No value of mu_hd is given; mu_hd(s) = hydrodynamic_ratio * mu_bd(s) (assumption);
* the notch of a fault (``Fault``: kind, width, depth, location; several at once) is a
  change of the surface profile: the mating surface sinks into the notch until it meets
  the nearer corner, ``reff - sqrt(reff^2 - a^2)`` with a the distance to that corner
  and reff the relative radius of the pair in the rolling plane, at most the depth.
  Entry unloads the ball gradually; the trailing corner stops it abruptly: two events
  per passage, their spacing set by the width. ``Fault.edge`` and ``ramp_fraction``
  (sr5's depth profiles) do not apply: the profile is the geometry.

Centrifugal and gyroscopic terms: the equations are written in the inertial frame, so
the centrifugal load of an orbiting ball (m Omega^2 r) is the part of the outer-race
force that bends its path, not an added force; it appears in ``outer_contact_forces``.
The gyroscopic moment omega x J omega of eq. 20 is identically zero for planar motion
(every angular velocity along z) and is therefore absent.

Friction torques: T_load (eq. 16, with F_s = F_r of eq. 17 and the static load rating
of ISO 76) plus a constant seal torque resist the inner race's rotation; T_lub (eq. 18)
resists the cage's, smoothed as tanh(omega / 1 rad/s) around zero speed.

Integration: classical RK4 with a fixed step (:data:`SOLVERS`), justified by the
eigenvalues of the linearised system (benchmarks/multibody_speed.py computes them from
the Jacobian and measures the work-precision). With Kramer's damping a ball between its
two contacts is overdamped (zeta = tau omega / 2 ~ 1.4 for the 6205 at 500 N): its fast
root, at most tau omega^2 ~ 7e5 1/s, is the stiffest real eigenvalue (lambda_max). The
fastest oscillation (omega_max, ~60 kHz) is the slip of a loaded ball against the lag of
its traction, sqrt(d(mu Q)/d(v_s) / m_red * u_r / L), lightly damped by u_r / (2 L).
The default step keeps lambda_max dt <= 1.8 (RK4 is stable to 2.79 on the real axis;
the margin covers the stiffening of a contact at twice its static load, k ~ Q^(1/3),
+26 %, and the accuracy of the overdamped root) and omega_max dt <= 1.0 (stable to
2.83; at 1.0 RK4 damps that 60 kHz mode by 0.6 % per step, above the output band,
while modes below the 24 kHz Nyquist frequency of a 48 kHz output, omega dt <= 0.3,
lose less than 1e-5 per step), rounded down to a divisor of the internal grid
interval: three steps of 1.74 us per 192 kHz interval on the 6205 reference scene.
Larger steps (two per interval, lambda_max dt = 2.1) stay stable but bias the mean
contact forces (the centrifugal load of a 35 Hz ER-16K by 2 % at 4.2 us, 0.5 % at
1.8 us); benchmarks/multibody_speed.py shows the work-precision, and that the
overdamped root is what costs the third step: with Kramer's time halved (that root
halved, the oscillation unchanged) two steps per interval are as accurate as three.
``solver="rosw"`` takes the Rosenbrock-W method ROS34PW2 (Rang & Angermann 2005; order
3 for any approximate Jacobian, L-stable) with W = I - gamma h J, J holding only the
2 x 2 stiffness and damping blocks of each ball's centre against its races and of the
outer race against its housing (Kramer's damping is tau times the stiffness, so each
block is one 2 x 2 solve per stage); everything else is stepped explicitly. It stays
accurate past RK4's limit on the overdamped root (one step per 5.2 us interval,
lambda_max dt = 4.2, keeps the loads within 2e-5 of DOP853 over 200 us where RK4 is
off by 0.46), and gets the centrifugal balance right at a third of RK4's evaluations,
but at equal cost its short-horizon loads and sensor signal are less accurate than
RK4's (order 3 against 4, and the explicit traction-slip oscillation): RK4 stays the
default (benchmarks/multibody_speed.py, work-precision).
Quasi-static balls (``MultibodyParameters(balls="quasistatic")``, :func:`._kernels.rhs_qs`):
the massless limit of each ball's radial motion. A loaded ball's radial natural
frequency (~100 kHz) lies far above the output band, so its radius follows the rings:
with m_b r'' dropped, the radial balance of its two contacts (each Hertz with Kramer's
damping, so affine in the ball's radial speed r'), its centrifugal load m_b u^2 / r
(u its speed across the radius), its weight and the radial parts of its tractions is
solved for r' over the contacts that press; the ball relaxes onto its elastic balance
with Kramer's time tau (the dynamic ball's slow root, 1.17 / tau on the 6205, becomes
1 / tau; its fast root, ~7e5 1/s, is gone). Clearance, separation (a contact carries
exactly 0) and the notch profiles are as for dynamic balls; the orbit (traction, pocket,
weight) and the spin stay dynamic, and so do the cage and the slip: the traction-slip
oscillation (~3.4e5 rad/s) then sets the step with the housing's mode, at omega_max dt
<= :data:`QS_OMEGA_DT` (two steps per 5.2 us interval on the 6205). Where it applies:
scenes whose signal does not hinge on a ball's inertia. On the healthy 6205 it is the
dynamic model (contact loads within 2e-6 over 2 ms, the centrifugal balance exact,
the cage within 1e-6) at 0.85x its cost; with a race notch the ball no longer strikes
the trailing corner with its mass, and the envelope's fault lines come out about 0.7 of
the dynamic balls' (RMS and cage speed agree); ball faults are refused
(benchmarks/multibody_speed.py). The default stays "dynamic".
The run starts from the quasi-static equilibrium with the centrifugal load and rolling
kinematics and settles for ``settle_s`` before t = 0, so the cage finds its pockets and
its slip before the record begins.

Outputs: each sensor reads the housing acceleration (housing spring and damper plus
every outer contact force weighted by its transmission factor, as in sr5) through the
scene's structural resonance (one-way coupled, solved exactly for the interval means
of its excitation), anti-alias decimated and AC coupled, like sr5.

Assumptions (defaults in :class:`MultibodyParameters`, each with its source): planar
motion (no axial load, no ball precession: the paper's 3-D randomness of ball faults is
absent), rigid bodies apart from the contacts, the cage centred on the housing, the
normal force along the line of centres (the tilt of the force on a notch corner is
neglected, as in the paper's profile model), no EHL film stiffness. Radial loads up to
the one at which the most loaded contact reaches ISO 76's 4200 MPa
(:data:`CONTACT_PRESSURE_LIMIT_PA`; 10.6 kN for a 6205): beyond it the contacts are not
elastic and the model refuses the scene (see :func:`static_equilibrium`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, fields

import numpy as np
from scipy import optimize
from scipy import signal as _signal

from ..._validation import check_number
from ...scene import STANDARD_GRAVITY, Scene
from .._registry import Model
from .._shared import SimulationUnstableError, add_noise, check_finite, to_output_rate
from ..result import FaultCrossings, GroundTruth, SimulationResult
from . import _kernels as K

__all__ = ["BALLS", "MULTIBODY", "MultibodyParameters", "MultibodySystem", "build",
           "integrate", "SOLVERS", "mu_traction", "static_equilibrium"]

SOLVERS = {
    "rk4": "classical Runge-Kutta, fixed step (default: omega_max dt = 1.0 and "
           "lambda_max dt = 1.8 from the linearised contact and traction dynamics)",
    "rosw": "Rosenbrock-W ROS34PW2 (Rang & Angermann 2005), fixed step, each ball's "
            "contact stiffness and damping implicit (omega_max dt = 1.5)",
}

#: default step limits: omega_max dt (the traction-slip oscillation, RK4 stable to 2.83)
#: and lambda_max dt (the overdamped contact's fast root, RK4 stable to 2.79); see the
#: module docstring and benchmarks/multibody_speed.py
OMEGA_DT, LAMBDA_DT = 1.0, 1.8
#: how the balls move (``MultibodyParameters(balls=...)``)
BALLS = {
    "dynamic": "every ball a rigid body: centre (x, y) and spin with their inertia",
    "quasistatic": "massless-limit balls: each ball's radial position follows the rings "
                   "through its contacts' force balance (centrifugal load kept); its "
                   "orbit and spin stay dynamic",
}
#: default step limit with quasi-static balls: omega_max dt (the traction-slip
#: oscillation, then the fastest mode; RK4 is stable to 2.83 but at omega_max dt ~ 2.3,
#: one step per 5.2 us interval on the 6205, it damps that mode by a quarter per step
#: and the sensor signal of a healthy 6205 moves by 1e-2; at 1.15, two steps, it is as
#: accurate as the dynamic balls' default: benchmarks/multibody_speed.py)
QS_OMEGA_DT = 1.2

#: default step limit of the Rosenbrock-W solver: omega_max dt (its explicit part,
#: everything but the balls' contact blocks, is stable to 1.5 on the imaginary axis)
ROSW_OMEGA_DT = 1.5

#: Hertz pressure at the centre of the most loaded contact up to which the model takes
#: a scene, Pa: ISO 76's basic static load rating of radial ball bearings (4200 MPa,
#: a permanent deformation of ball and race of 1e-4 of the ball diameter; Harris &
#: Kotzalas ch. 8). Beyond it the contacts dent plastically and the elastic Hertz law
#: of the model no longer holds.
CONTACT_PRESSURE_LIMIT_PA = 4.2e9


@dataclass(frozen=True)
class MultibodyParameters:
    """Structural and tribological parameters of the multibody model (SI units).

    Parameters
    ----------
    shaft_mass : float
        Inner race with its share of the shaft, kg. Default 1.0 (sr5's m_s, so the two
        models compare on the same scene).
    shaft_inertia : float or None
        Polar moment of the inner race and shaft, kg m^2; None: a solid shaft of the
        inner-raceway radius, m R_i^2 / 2.
    housing_mass : float
        Outer race and the part of the housing that moves with it, kg. Default 1.0
        (not given by Nakhaeinejad & Bryant; the order of a pillow block for a 1-inch shaft).
    housing_stiffness : float
        Housing stiffness, vertical and horizontal, N/m. Default 4e10 (the paper's
        Table 1: 4e7 N/mm).
    damping_time : float
        tau of Kramer's damping b = tau k (Nakhaeinejad & Bryant eq. 9, 1e-5 s with the paper's
        factor 1.0 and Kramer's exponent), s. Applied to every contact with its
        linearised stiffness and to the housing. Default 1e-5.
    density : float
        Ball density, kg/m^3. Default 7750 (Nakhaeinejad & Bryant Table 1).
    cage_mass : float
        Cage mass, kg (inertia m r_p^2 at the pitch radius). Default 0.01 (a pressed
        steel cage of this size; Nakhaeinejad & Bryant have none).
    pocket_clearance : float
        Tangential play of a ball in its pocket, m. Default 1e-4 (typical 0.1 mm).
    pocket_stiffness, pocket_damping : float
        Pocket contact, N/m and N s/m. Defaults 1e7 and 30 (damping ratio ~0.1 with a
        2 g ball).
    drive_stiffness, drive_damping : float
        Torsional coupling of the motor to the inner race, N m/rad and N m s/rad.
        Defaults 1000 and 0.4 (a beam coupling, Nakhaeinejad & Bryant sec. 4; ~560 Hz, damping
        ratio ~0.7 with a 1 kg shaft). 0 and 0 leave the inner race spinning freely.
    film_parameter : float
        Lambda of Nakhaeinejad & Bryant eq. 12, >= 0. Default 0: boundary lubrication, mu = mu_bd as
        in eq. 14.
    hydrodynamic_ratio : float
        mu_hd / mu_bd at equal slide-roll ratio, in [0, 1]. Default 0.5 (EHD traction
        coefficients are about half the boundary ones; the paper gives no value).
    traction : bool
        Tangential contact forces on (default). False makes every contact frictionless.
    viscosity_cst : float
        Kinematic viscosity nu_o of the lubricant in eq. 18, cSt. Default 20 (a light
        spindle oil; the paper gives none).
    lubrication_factor : float
        f_o of eq. 18. Default 1 (deep-groove ball bearing, oil mist; Nakhaeinejad & Bryant).
    friction_torques : bool
        Apply the torques of eqs. 15-18 (default True).
    seal_torque : float
        T_seal, N m, constant (eq. 15). Default 0 (open bearing).
    static_load_rating : float or None
        C_s of eq. 16, N; None: ISO 76, C_0 = f_0 Z D^2 with f_0 = 12.3.
    contact_stiffness : tuple of float or None
        (K_inner, K_outer), N/m^1.5; None: :meth:`ballpass.Bearing.contact_stiffnesses`.
    relaxation_length : float or None
        Rolling distance over which a contact's traction relaxes to mu(s) Q, m; None:
        the Hertz contact length 2 b of the most loaded inner contact at the start
        (Johnson, Contact Mechanics, sec. 8.2: transient creep settles within about one
        contact length). Without it the traction's real eigenvalue (~4e6 1/s for the
        ER-16K at 110 N) would set an explicit step of 0.35 us.
    settle_s : float
        Time simulated before t = 0 from the quasi-static start, s. Default 0.005.
    balls : {"dynamic", "quasistatic"}
        How the balls move (:data:`BALLS`). "dynamic" (default): every ball a rigid
        body. "quasistatic": the massless limit of each ball's radial motion (its
        radial natural frequency, ~100 kHz, lies far above the output band): the
        ball's radius follows the rings through the balance of its two damped Hertz
        contacts, its centrifugal load and weight, relaxing onto it with Kramer's time;
        its orbit (against traction and pocket) and spin stay dynamic. It removes the
        stiff radial contact modes from the step. Not for ball faults (refused).

    Examples
    --------
    Frictionless contacts in a full film, passed to ``simulate(..., params=...)``:

    >>> from ballpass.simulate import MultibodyParameters
    >>> p = MultibodyParameters(traction=False, film_parameter=2.0)
    >>> p.traction, p.film_parameter, p.housing_stiffness      # -, -, N/m
    (False, 2.0, 40000000000.0)
    >>> MultibodyParameters(shaft_mass=-1)
    Traceback (most recent call last):
        ...
    ValueError: shaft_mass must be a finite number > 0, got -1.0
    """

    shaft_mass: float = 1.0
    shaft_inertia: float | None = None
    housing_mass: float = 1.0
    housing_stiffness: float = 4e10
    damping_time: float = 1e-5
    density: float = 7750.0
    cage_mass: float = 0.01
    pocket_clearance: float = 1e-4
    pocket_stiffness: float = 1e7
    pocket_damping: float = 30.0
    drive_stiffness: float = 1000.0
    drive_damping: float = 0.4
    film_parameter: float = 0.0
    hydrodynamic_ratio: float = 0.5
    traction: bool = True
    viscosity_cst: float = 20.0
    lubrication_factor: float = 1.0
    friction_torques: bool = True
    seal_torque: float = 0.0
    static_load_rating: float | None = None
    contact_stiffness: tuple | None = None
    relaxation_length: float | None = None
    settle_s: float = 0.005
    balls: str = "dynamic"

    def __post_init__(self) -> None:
        positive = ("shaft_mass", "housing_mass", "housing_stiffness", "density",
                    "cage_mass", "pocket_stiffness")
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name == "balls":
                if value not in BALLS:
                    raise ValueError(f"balls must be one of {sorted(BALLS)}, got {value!r}")
            elif f.name in ("traction", "friction_torques"):
                if not isinstance(value, bool):
                    raise TypeError(f"{f.name} must be a bool, got {value!r}")
            elif f.name == "contact_stiffness":
                if value is not None:
                    if not (isinstance(value, tuple) and len(value) == 2):
                        raise ValueError("contact_stiffness must be (K_inner, K_outer) in "
                                         f"N/m^1.5 or None, got {value!r}")
                    for v in value:
                        check_number("contact_stiffness", v, 0.0, lo_open=True, unit="N/m^1.5")
            elif value is None and f.name in ("shaft_inertia", "static_load_rating",
                                              "relaxation_length"):
                continue
            elif f.name == "hydrodynamic_ratio":
                check_number(f.name, value, 0.0, 1.0)
            elif f.name == "settle_s":
                check_number(f.name, value, 0.0, 1.0, unit="s")
            else:
                check_number(f.name, value, 0.0, lo_open=f.name in positive or f.name in (
                    "shaft_inertia", "static_load_rating", "relaxation_length"))


def mu_traction(s, film_parameter: float = 0.0, hydrodynamic_ratio: float = 0.5):
    """Traction coefficient against the slide-roll ratio (Nakhaeinejad & Bryant eqs. 12-13).

    mu_bd(s) = (-0.1 + 22.28 |s|) exp(-181.46 |s|) + 0.1, applied odd-symmetrically;
    for 0.01 <= Lambda < 1.5, mu = (mu_bd - mu_hd) ((Lambda - 1.5)/(0.01 - 1.5))^6 + mu_hd
    (eq. 12 with the breakpoint 1.5 in its denominator: continuous at both ends), mu_bd
    below 0.01 and mu_hd from 1.5 on, with mu_hd = hydrodynamic_ratio * mu_bd.

    Parameters
    ----------
    s : float or array_like
        Slide-roll ratio (signed).
    film_parameter : float, optional
        Lambda, >= 0. Default 0.
    hydrodynamic_ratio : float, optional
        mu_hd / mu_bd. Default 0.5.

    Returns
    -------
    float or ndarray
        mu, with the sign of s.

    Examples
    --------
    >>> from ballpass.simulate.multibody import mu_traction
    >>> round(float(mu_traction(0.01)), 4), round(float(mu_traction(-0.01)), 4)
    (0.12, -0.12)
    """
    lam = check_number("film_parameter", film_parameter, 0.0)
    r = check_number("hydrodynamic_ratio", hydrodynamic_ratio, 0.0, 1.0)
    s = np.asarray(s, dtype=float)
    a = np.abs(s)
    mu_bd = (-0.1 + 22.28 * a) * np.exp(-181.46 * a) + 0.1
    out = np.sign(s) * mu_bd * (_blend_weight(lam) + (1.0 - _blend_weight(lam)) * r)
    return out if out.ndim else float(out)


def _blend_weight(lam: float) -> float:
    """Weight of mu_bd in eq. 12 (1 below Lambda = 0.01, 0 from 1.5)."""
    if lam < 0.01:
        return 1.0
    if lam >= 1.5:
        return 0.0
    return ((lam - 1.5) / (0.01 - 1.5)) ** 6


@dataclass
class MultibodySystem:
    """A scene bound to the multibody kernels.

    Attributes
    ----------
    scene : Scene
    params : MultibodyParameters
    p : ndarray (N_PARAMS,)
        Kernel parameters (indices ``P_*`` of :mod:`._kernels`).
    faults : ndarray (n_faults, N_FCOLS)
    sensors : ndarray (n_sensors, N_SCOLS)
    y0 : ndarray (2 (6 + 3 Z) + 2 Z,) or, with quasi-static balls, (12 + 7 Z,)
        Quasi-static start at t = -settle_s (layouts: :func:`._kernels.rhs` and
        :func:`._kernels.rhs_qs`).
    t0 : float
        Start time, s (= -settle_s).
    omega_max : float
        Fastest linearised oscillation, rad/s.
    lambda_max : float
        Stiffest linearised traction rate, 1/s.
    """

    scene: Scene
    params: MultibodyParameters
    p: np.ndarray
    faults: np.ndarray
    sensors: np.ndarray
    y0: np.ndarray
    t0: float
    omega_max: float
    lambda_max: float

    @property
    def n_state(self) -> int:
        """2 (6 + 3 Z) + 2 Z (coordinates, rates, traction forces); with quasi-static
        balls 12 + 7 Z (6 + 2 Z rates: no radial ball speeds)."""
        return self.y0.shape[0]

    @property
    def quasistatic(self) -> bool:
        """Whether the balls are quasi-static (``params.balls``)."""
        return self.params.balls == "quasistatic"

    def default_dt(self, solver: str = "rk4") -> float:
        """Default step of ``solver``, s: for RK4 omega_max dt = OMEGA_DT (QS_OMEGA_DT
        with quasi-static balls) and lambda_max dt = LAMBDA_DT; for ROS34PW2, whose
        contact blocks are implicit, omega_max dt = ROSW_OMEGA_DT only."""
        if solver == "rosw":
            return ROSW_OMEGA_DT / self.omega_max
        limit = QS_OMEGA_DT if self.quasistatic else OMEGA_DT
        return min(limit / self.omega_max, LAMBDA_DT / self.lambda_max)

    def _eval(self, t: float, y: np.ndarray):
        z = int(self.p[K.P_Z])
        out, qi, qo = np.empty(self.n_state), np.zeros(z), np.zeros(z)
        K._f(self.quasistatic, float(t), np.ascontiguousarray(y, dtype=np.float64), out,
             self.p, self.faults, self.sensors, qi, qo, np.zeros((z, 2), dtype=np.int64),
             np.zeros(len(self.scene.sensors)), False)
        return out, qi, qo

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt at (t, y), callable from Python (e.g. by scipy's ``solve_ivp``)."""
        return self._eval(t, y)[0]

    def contact_loads(self, t: float, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Inner and outer normal contact load of every ball at (t, y), N."""
        return self._eval(t, y)[1:]

    def energy(self, t: float, y: np.ndarray) -> float:
        """Mechanical energy of the conservative part (see :func:`._kernels.energy`), J;
        dynamic balls only."""
        if self.quasistatic:
            raise ValueError("energy needs balls='dynamic' (massless-limit balls carry no "
                             "radial kinetic energy)")
        return float(K.energy(float(t), np.ascontiguousarray(y, dtype=np.float64), self.p))


def _geometry(scene: Scene, prm: MultibodyParameters):
    b = scene.bearing
    rb = 0.5 * b.element_diameter_m
    c = b.radial_clearance_m
    # the clearance split between both races: a ball on the pitch circle has c/2 on
    # each side, so the inner ring's free radial travel is c (bearing.py's definition)
    ri = b.inner_race_radius_m - 0.5 * c
    ro = b.outer_race_radius_m + 0.5 * c
    ki, ko = prm.contact_stiffness or b.contact_stiffnesses()
    return rb, ri, ro, ki, ko


def _accepts(scene: Scene) -> str | None:
    """Ball bearings with zero contact angle (the model is planar)."""
    b = scene.bearing
    if b.element != "ball":
        return f"it models ball bearings (point contacts); {b.name!r} has rollers"
    if b.contact_angle_deg != 0.0:
        return (f"it is planar (radial contacts); {b.name!r} has a contact angle of "
                f"{b.contact_angle_deg:g} deg")
    return None


def static_equilibrium(scene: Scene, params: MultibodyParameters | None = None, *,
                       cage_angle: float = 0.0, orbit_rate: float | None = None):
    """Quasi-static equilibrium of the rolling bearing with the centrifugal load.

    Each ball j sits at angle cage_angle + 2 pi j / Z at the radius where its radial
    forces balance: inner load, outer load, centrifugal force m Omega^2 r and weight;
    the inner race (relative to the outer) where the ball loads balance F_r and its
    weight (Harris & Kotzalas, ch. 7 with the centrifugal term of Fig. 12's
    comparison).

    The model's range: radial loads up to the one at which the most loaded contact
    reaches the Hertz pressure of ISO 76's basic static load rating,
    :data:`CONTACT_PRESSURE_LIMIT_PA` (4200 MPa for radial ball bearings, where the
    permanent deformation of ball and race together reaches 1e-4 of the ball
    diameter): beyond it the contacts dent plastically (brinelling) and the elastic
    Hertz law the model rests on no longer holds. That is about 10.6 kN for a 6205 or
    an ER-16K, 6.5 kN for a 6203, 24 kN for a 6208 (zero clearance).

    Parameters
    ----------
    scene : Scene
    params : MultibodyParameters, optional
    cage_angle : float, optional
        Angle of ball 0, rad.
    orbit_rate : float, optional
        Orbital speed Omega of the balls, rad/s; default the kinematic cage speed at the
        start speed.

    Returns
    -------
    dict
        ``inner`` (x, y) displacement of the inner race relative to the outer, m;
        ``radius`` (Z,) ball centre radii, m; ``q_inner``, ``q_outer`` (Z,) loads, N;
        ``angles`` (Z,) rad.

    Raises
    ------
    ValueError
        If the radial load takes a contact beyond :data:`CONTACT_PRESSURE_LIMIT_PA`;
        the message gives the largest load the model takes for that bearing.

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate.multibody import static_equilibrium
    >>> eq = static_equilibrium(bp.Scene(bearing="ER-16K", rpm=2100, radial_load_n=110))
    >>> round(float(eq["inner"][0]) * 1e6, 2), round(float(eq["q_inner"][0]), 1)  # um, N
    (3.39, 58.4)
    >>> eq = static_equilibrium(bp.Scene(bearing="6205", rpm=1797, radial_load_n=5000))
    >>> round(float(eq["q_inner"][0]) * 9 / 5000, 2)      # Stribeck: Q_max Z / F_r ~ 4.4
    4.4
    """
    prm = params or MultibodyParameters()
    b = scene.bearing
    z = b.n_elements
    rb, ri, ro, ki, ko = _geometry(scene, prm)
    mb = prm.density * math.pi / 6.0 * b.element_diameter_m ** 3
    g = STANDARD_GRAVITY if scene.gravity else 0.0
    w0 = scene.speed.rpm_start * math.pi / 30.0
    om = w0 * ri / (ri + ro) if orbit_rate is None else orbit_rate
    psi = cage_angle + 2.0 * math.pi * np.arange(z) / z
    e = np.stack((np.cos(psi), np.sin(psi)), axis=1)
    load = scene.radial_load_n + prm.shaft_mass * g
    k_series = _series(ki, ko)
    centrifugal = mb * om * om * (ri + rb)
    # initial guess: Stribeck's distribution with the outer contacts' compression by the
    # centrifugal force as extra clearance (a ball flung outwards leaves that gap at the
    # inner race). Without it a fast, lightly loaded bearing starts where no ball
    # touches the inner race and the residual is flat.
    clearance = b.radial_clearance_m + (centrifugal / ko) ** (2.0 / 3.0)
    guess = _elastic_distribution(scene, load - scene.radial_load_n, centrifugal, clearance,
                                  k_series, cage_angle)

    def ball(j, d):
        def radial(r):
            c = r * e[j] - d
            dist = math.hypot(*c)
            di = rb + ri - dist
            do = r + rb - ro
            qi = ki * max(di, 0.0) ** 1.5
            qo = ko * max(do, 0.0) ** 1.5
            force = qi * float(c @ e[j]) / dist - qo + mb * om * om * r + mb * g * e[j, 0]
            return force, qi, c / dist
        # a bracket for any |d| < ri: at lo the ball is pressed into the inner race
        # only, at hi into the outer race by at least 0.02 D
        span = 0.02 * b.element_diameter_m + abs(d).sum()
        lo, hi = ri + rb - span, ro - rb + span
        r = optimize.brentq(lambda rr: radial(rr)[0], lo, hi, xtol=1e-16, rtol=1e-15)
        _, qi, n = radial(r)
        return r, qi, n

    def residual(d):
        f = np.array([load, 0.0])
        for j in range(z):
            _, qi, n = ball(j, d)
            f -= qi * n
        return f / max(load, 1.0)

    # deflection scale: the clearance plus the approach at which one ball would carry
    # the whole load (load_distribution's bracket). The force balance bounds the
    # solution by it: the ball nearest the load line (|psi| <= pi / Z) carries at most
    # F / cos(pi / Z), so |x| <= scale / cos(pi / Z)^(5/3) < 2 scale for Z >= 5. The
    # bounds only keep trial steps inside the bearing (where ``ball`` has a bracket);
    # the unknowns are scaled by it so that xtol is relative to the deflection.
    scale = abs(clearance) + (load / k_series) ** (2.0 / 3.0)
    limit = 4.0 * scale
    x0 = np.clip([guess.deflection_m, guess.lateral_deflection_m], -0.9 * limit, 0.9 * limit)
    sol = optimize.least_squares(residual, x0, bounds=(-limit, limit), x_scale=scale,
                                 xtol=1e-15, ftol=1e-15, gtol=1e-15)
    d = sol.x
    if np.max(np.abs(residual(d))) > 1e-7:
        raise RuntimeError(f"multibody static equilibrium did not converge for {scene!r}: "
                           f"{sol.message}")
    radius, q_in, q_out = np.empty(z), np.empty(z), np.empty(z)
    for j in range(z):
        radius[j], q_in[j], _ = ball(j, d)
        q_out[j] = ko * max(radius[j] + rb - ro, 0.0) ** 1.5
    return {"inner": d, "radius": radius, "q_inner": q_in, "q_outer": q_out, "angles": psi,
            "orbit_rate": om}


def _contact_length(b, q: float) -> float:
    """Hertz contact length 2 b (rolling direction) of the inner contact at load q, m."""
    return 2.0 * b.contact_ellipse("inner", q)[1]


def _peak_pressure(b, q: float, race: str) -> float:
    """Hertz pressure at the centre of the contact ellipse, 3 Q / (2 pi a b), Pa."""
    if q <= 0.0:
        return 0.0
    a, bb = b.contact_ellipse(race, q)
    return 1.5 * q / (math.pi * a * bb)


def _elastic_distribution(scene: Scene, weight: float, centrifugal: float,
                          clearance: float, k_series: float, cage_angle: float):
    """Stribeck's load distribution of the scene's radial load plus ``weight`` (N) with
    ``clearance`` (m) and ball 0 at ``cage_angle`` (rad), refused with a ValueError if
    the most loaded contact exceeds :data:`CONTACT_PRESSURE_LIMIT_PA` as the balls pass
    the load line (cage angle 0): at the inner race, or at the outer with the
    ``centrifugal`` force (N) added. The message gives the largest radial load the
    model takes for the bearing."""
    b = scene.bearing

    def distribution(f_r, angle):
        return b.load_distribution(f_r + weight, clearance_m=clearance,
                                   cage_angle_deg=math.degrees(angle), stiffness=k_series)

    def excess(f_r):
        q = distribution(f_r, 0.0).q_max_n
        return max(_peak_pressure(b, q, "inner"), _peak_pressure(b, q + centrifugal, "outer")) \
            - CONTACT_PRESSURE_LIMIT_PA

    if excess(scene.radial_load_n) <= 0.0:
        return distribution(scene.radial_load_n, cage_angle)
    largest = (optimize.brentq(excess, 0.0, scene.radial_load_n, rtol=1e-6)
               if excess(0.0) < 0.0 else 0.0)
    raise ValueError(
        f"radial_load_n={scene.radial_load_n:g} N loads the most loaded ball of the "
        f"{b.name} with {distribution(scene.radial_load_n, 0.0).q_max_n:.0f} N, a Hertz "
        f"contact pressure above the {CONTACT_PRESSURE_LIMIT_PA / 1e6:.0f} MPa of ISO 76's "
        "static load rating (permanent deformation 1e-4 of the ball diameter), where the "
        "elastic contacts of the multibody model no longer hold; it takes radial loads up "
        f"to {math.floor(largest):.0f} N for this bearing")


def _series(ki: float, ko: float) -> float:
    from ...bearing import series_stiffness
    return series_stiffness(ki, ko, 1.5)


def _fault_table(scene: Scene, rb: float, ri: float, ro: float, psi0: np.ndarray,
                 thb0: float) -> np.ndarray:
    """Kernel fault table: body-frame centre (rad), half width and depth (m), the
    relative radius of the mating pair at the inner and the outer contact (m)."""
    rows = []
    r_in = 1.0 / (1.0 / rb + 1.0 / ri)   # two convex surfaces
    r_out = 1.0 / (1.0 / rb - 1.0 / ro)  # ball in the concave outer race
    for f in scene.faults:
        row = np.zeros(K.N_FCOLS)
        if f.kind == "outer":
            kind, centre = K.KIND_OUTER, math.radians(f.angle_deg)
        elif f.kind == "inner":
            kind, centre = K.KIND_INNER, math.radians(f.angle_deg)
        else:
            # spin phase at t = 0, 0 = facing the outer race (Fault.angle_deg)
            kind = K.KIND_BALL
            centre = psi0[f.element] + math.radians(f.angle_deg) - thb0
        half = 0.5 * f.width_mm * 1e-3
        surface = {K.KIND_OUTER: ro, K.KIND_INNER: ri, K.KIND_BALL: rb}[kind]
        row[[K.F_KIND, K.F_CENTRE, K.F_HALF, K.F_DEPTH, K.F_ELEM, K.F_REFF_I, K.F_REFF_O,
             K.F_COS, K.F_SIN, K.F_COSHALF]] = (
            kind, centre, half, f.depth_mm * 1e-3, f.element, r_in, r_out, math.cos(centre),
            math.sin(centre), math.cos(min(half / surface + 1e-9, math.pi)))
        rows.append(row)
    return np.array(rows, dtype=np.float64).reshape(-1, K.N_FCOLS)


def build(scene: Scene, params: MultibodyParameters | None = None) -> MultibodySystem:
    """Bind a scene to the multibody kernels: parameters, faults, sensors and the
    quasi-static start (without integrating).

    Parameters
    ----------
    scene : Scene
    params : MultibodyParameters, optional

    Returns
    -------
    MultibodySystem

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate.multibody import build
    >>> system = build(bp.Scene(bearing="ER-16K", rpm=2100, radial_load_n=110))
    >>> system.n_state            # 33 coordinates, 33 rates, 18 traction forces
    84
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a ballpass.Scene, got {type(scene).__name__}")
    prm = params or MultibodyParameters()
    if not isinstance(prm, MultibodyParameters):
        raise TypeError(f"params must be MultibodyParameters for the multibody model, got "
                        f"{type(prm).__name__}")
    refusal = _accepts(scene)
    if refusal:
        raise ValueError(f"model 'multibody' cannot take this scene: {refusal}")
    b = scene.bearing
    z = b.n_elements
    rb, ri, ro, ki, ko = _geometry(scene, prm)
    mb = prm.density * math.pi / 6.0 * b.element_diameter_m ** 3
    jb = 0.4 * mb * rb * rb
    rp = 0.5 * b.pitch_diameter_m
    g = STANDARD_GRAVITY if scene.gravity else 0.0
    w0 = scene.speed.rpm_start * math.pi / 30.0
    om = w0 * ri / (ri + ro)
    c_s = prm.static_load_rating or 12.3 * z * (b.element_diameter_mm ** 2)
    f_s = scene.radial_load_n
    t_load = 0.0003 * (f_s / c_s) ** 0.55 * f_s * b.pitch_diameter_mm * 1e-3  # N m (eq. 16)

    p = np.zeros(K.N_PARAMS)
    p[K.P_Z] = z
    p[[K.P_RB, K.P_RI, K.P_RO, K.P_KI, K.P_KO]] = rb, ri, ro, ki, ko
    p[K.P_TAU] = prm.damping_time
    p[K.P_MI] = prm.shaft_mass
    p[K.P_JI] = prm.shaft_inertia or 0.5 * prm.shaft_mass * ri * ri
    p[K.P_MO] = prm.housing_mass
    p[K.P_MB] = mb
    p[K.P_JB] = jb
    p[K.P_JC] = prm.cage_mass * rp * rp
    p[K.P_RP] = rp
    p[K.P_KPOCK] = prm.pocket_stiffness
    p[K.P_CPOCK] = prm.pocket_damping
    p[K.P_EPOCK] = prm.pocket_clearance
    play = prm.pocket_clearance / rp
    p[K.P_PITCH_COS], p[K.P_PITCH_SIN] = math.cos(2.0 * math.pi / z), math.sin(2.0 * math.pi / z)
    p[K.P_POCK_SIN2] = math.sin(play) ** 2 * (1.0 - 1e-9) if play < 0.5 * math.pi else -1.0
    p[K.P_KH] = prm.housing_stiffness
    p[K.P_CH] = prm.damping_time * prm.housing_stiffness
    p[K.P_FR] = scene.radial_load_n
    p[K.P_G] = g
    p[K.P_W0] = w0
    p[K.P_W1] = scene.speed.rpm_end * math.pi / 30.0
    p[K.P_T] = scene.duration_s
    p[K.P_KD] = prm.drive_stiffness
    p[K.P_CD] = prm.drive_damping
    p[K.P_TLOAD] = (t_load + prm.seal_torque) if prm.friction_torques else 0.0
    p[K.P_NU] = prm.viscosity_cst
    p[K.P_F0] = prm.lubrication_factor
    p[K.P_DPMM] = b.pitch_diameter_mm
    p[K.P_LUB] = 1.0 if prm.friction_torques else 0.0
    p[K.P_WBD] = _blend_weight(prm.film_parameter)
    p[K.P_HD] = prm.hydrodynamic_ratio
    p[K.P_TRACTION] = 1.0 if prm.traction else 0.0
    # rolling-speed floor: 1e-3 of the start rolling speed keeps s finite at rest
    p[K.P_UFLOOR] = 1e-3 * max(w0 * ri, 1e-3)
    p[K.P_WEPS] = 1.0

    quasistatic = prm.balls == "quasistatic"
    if quasistatic and any(f.kind == "ball" for f in scene.faults):
        raise ValueError("balls='quasistatic' does not take ball faults (a ball notch's "
                         "impacts need the ball's inertia): use balls='dynamic'")
    t0 = -prm.settle_s
    start_angle = -om * prm.settle_s
    eq = static_equilibrium(scene, prm, cage_angle=start_angle, orbit_rate=om)
    nd = 6 + 3 * z
    y0 = np.zeros(2 * nd + 2 * z - (z if quasistatic else 0))
    load_on_outer = np.zeros(2)
    e = np.stack((np.cos(eq["angles"]), np.sin(eq["angles"])), axis=1)
    for j in range(z):
        load_on_outer += eq["q_outer"][j] * e[j]
    xo = (load_on_outer + np.array([prm.housing_mass * g, 0.0])) / prm.housing_stiffness
    y0[0:2] = xo + eq["inner"]
    y0[2] = w0 * t0
    y0[3:5] = xo
    y0[5] = start_angle - prm.pocket_clearance / rp  # pockets trail: the balls push
    y0[nd + 2] = w0
    y0[nd + 5] = om
    for j in range(z):
        bj = 6 + 3 * j
        r = eq["radius"][j]
        y0[bj:bj + 2] = xo + r * e[j]
        if quasistatic:  # speed across the radius, spin
            vj = nd + 6 + 2 * j
            y0[vj] = om * math.hypot(*y0[bj:bj + 2])
            y0[vj + 1] = -om * r / rb
            continue
        y0[nd + bj:nd + bj + 2] = om * r * np.array([-e[j, 1], e[j, 0]])
        y0[nd + bj + 2] = -om * r / rb
    # ball faults are located at t = 0 (spin phase): the spin turned -om r/rb * settle
    psi_t0 = eq["angles"] + om * prm.settle_s
    faults = _fault_table(scene, rb, ri, ro, psi_t0, -om * rp / rb * prm.settle_s)
    sensors = np.array([[math.cos(math.radians(s.angle_deg)), math.sin(math.radians(s.angle_deg)),
                         s.attenuation] for s in scene.sensors], dtype=np.float64)

    # linearised time scales: a ball between its contacts, the housing, the inner race;
    # the traction of the most loaded ball
    qmax = max(float(eq["q_inner"].max()), 1e-3)
    relax = prm.relaxation_length or _contact_length(b, qmax)
    p[K.P_RELAX] = relax
    kl_i = 1.5 * ki ** (2.0 / 3.0) * qmax ** (1.0 / 3.0)
    qmo = float(eq["q_outer"].max())
    kl_o = 1.5 * ko ** (2.0 / 3.0) * max(qmo, 1e-3) ** (1.0 / 3.0)
    # a quasi-static ball has no radial mode: it relaxes onto its balance at 1 / tau
    omega = max(0.0 if quasistatic else math.sqrt((kl_i + kl_o) / mb),
                math.sqrt((prm.housing_stiffness + z * kl_o) / prm.housing_mass),
                math.sqrt(z * kl_i / prm.shaft_mass),
                math.sqrt(prm.pocket_stiffness / mb),
                math.sqrt(prm.pocket_stiffness * rp * rp / max(p[K.P_JC], 1e-30) * z))
    damp = 1.0 / max(prm.damping_time, 1e-30) if quasistatic else \
        prm.damping_time * (kl_i + kl_o) / mb
    u_roll = max(0.5 * (w0 - om) * ri + 0.5 * om * rp, p[K.P_UFLOOR])
    slope = 22.28 + 0.1 * 181.46  # d mu_bd / ds at s = 0 (eq. 13)
    reduced = mb / 3.5            # 1/m + rb^2/J_b = 3.5/m for a solid sphere
    # the traction lag turns the slip mode into an oscillation at sqrt(lambda_t u_r / L)
    lam_t = slope * (qmax + qmo) / u_roll / reduced if prm.traction else 0.0
    omega = max(omega, math.sqrt(lam_t * u_roll / relax))
    lam = max(damp, u_roll / relax, 1.0)
    return MultibodySystem(scene=scene, params=prm, p=p, faults=faults, sensors=sensors,
                           y0=y0, t0=t0, omega_max=omega, lambda_max=lam)


def _resonator(exc: np.ndarray, h: float, f_hz: float, zeta: float) -> np.ndarray:
    """Absolute acceleration of the sensor resonator (natural frequency f_hz, damping
    zeta) base-excited by the housing acceleration ``exc`` (n, n_sensors), whose
    interval means are held over each grid interval of ``h`` s: the exact (zero-order
    hold) discretisation of H(s) = (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2), started
    at rest under the first value."""
    w = 2.0 * math.pi * f_hz
    num, den = [2.0 * zeta * w, w * w], [1.0, 2.0 * zeta * w, w * w]
    bz, az, _ = _signal.cont2discrete((num, den), h, method="zoh")
    bz = np.ravel(bz)
    zi = _signal.lfilter_zi(bz, az)
    out = np.empty_like(exc)
    for s in range(exc.shape[1]):
        out[:, s], _ = _signal.lfilter(bz, az, exc[:, s], zi=zi * exc[0, s])
    return out


def integrate(system: MultibodySystem, *, h_out: float, n_out: int, stride: int,
              dt: float | None = None, solver: str = "rk4"):
    """Integrate a bound system over [t0, n_out h_out] with a fixed step (no
    decimation, AC coupling or noise: the integration step of the multibody model's
    ``simulate``).

    Parameters
    ----------
    system : MultibodySystem
        From :func:`build`.
    h_out : float
        Internal grid spacing, s.
    n_out : int
        Grid intervals recorded from t = 0.
    stride : int
        Record forces and angles at every ``stride``-th grid point.
    dt : float, optional
        Step, s, rounded down to a divisor of ``h_out``; default
        :meth:`MultibodySystem.default_dt` of the solver.
    solver : str, optional
        One of :data:`SOLVERS`: ``"rk4"`` (default) or ``"rosw"``.

    Returns
    -------
    dict
        ``exc`` (n_out, n_sensors) mean housing acceleration per grid interval, m/s^2;
        ``q_inner``, ``q_outer``, ``angles`` (n_rec, Z) at every ``stride``-th grid
        point; ``disp`` (n_rec, 4) inner x, y and outer x, y, m; ``cage`` (n_rec,) cage
        angle, rad; ``crossings``: FaultCrossings; ``info``; ``y_end``.

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate.multibody import build, integrate
    >>> system = build(bp.Scene(bearing="ER-16K", rpm=2100, radial_load_n=110,
    ...                         duration_s=0.005, fs=20_000, resonance_hz=5000))
    >>> raw = integrate(system, h_out=1 / 80_000, n_out=400, stride=4)
    >>> raw["q_inner"].shape, raw["exc"].shape
    ((100, 9), (400, 1))
    """
    if solver not in SOLVERS:
        raise ValueError(f"solver must be one of {sorted(SOLVERS)}, got {solver!r}")
    qs = system.quasistatic
    if qs and solver != "rk4":
        raise ValueError(f"solver must be 'rk4' with balls='quasistatic', got {solver!r}")
    z = int(system.p[K.P_Z])
    dt_req = system.default_dt(solver) if dt is None else float(dt)
    n_sub = max(1, math.ceil(h_out / dt_req - 1e-9))
    step = h_out / n_sub
    # the settling steps end exactly at t = 0 whatever the step, so that runs at
    # different steps start from the same state
    n_pre = math.ceil(-system.t0 / step - 1e-9)
    t0 = system.t0
    step_pre = -t0 / n_pre if n_pre else step
    n_rec = (n_out + stride - 1) // stride
    ns = system.sensors.shape[0]
    exc = np.zeros((n_out, ns))
    rec_qi, rec_qo = np.zeros((n_rec, z)), np.zeros((n_rec, z))
    rec_ang, rec_disp, rec_cage = np.zeros((n_rec, z)), np.zeros((n_rec, 4)), np.zeros(n_rec)
    t_end = n_out * h_out
    n_faults = system.faults.shape[0]
    # a contact meets a fault at most once per turn of the slowest path it lies on:
    # the cage (outer), the inner race relative to the cage, the ball spin (twice)
    w_max = max(system.p[K.P_W0], system.p[K.P_W1])
    turns = w_max * (t_end - t0) / (2.0 * math.pi) * (1.0 + system.p[K.P_RP] / system.p[K.P_RB])
    cap = int(n_faults * 2 * (2 * z) * (turns + 2)) + 16
    cross_t = np.zeros(cap)
    cross_f = np.zeros(cap, dtype=np.int64)
    cross_e = np.zeros(cap, dtype=np.int64)
    cross_edge = np.zeros(cap, dtype=np.int64)
    y = system.y0.copy()
    nd = 6 + 3 * z
    scale = np.concatenate((np.full(nd, 1.0), np.full(nd - (z if qs else 0), 1e3 * (1.0 + w_max)),
                            np.full(2 * z, 1e3 * (1.0 + scene_load(system)))))
    bound = 1e6 * scale
    t_wall = time.perf_counter()
    method = K.METHOD_RK4 if solver == "rk4" else K.METHOD_ROSW
    status, n_steps, t_fail, n_cross = K.integrate_fixed(
        method, qs, y, system.p, system.faults, system.sensors, t0, step_pre, step, n_pre, n_sub,
        n_out + 1, stride, exc, rec_qi, rec_qo, rec_ang, rec_disp, rec_cage, cross_t, cross_f,
        cross_e, cross_edge, bound)
    wall = time.perf_counter() - t_wall
    if status != K.STATUS_OK or not np.all(np.isfinite(y)):
        raise SimulationUnstableError(
            f"multibody simulation with {solver} (dt = {step:.3g} s) failed at t = {t_fail:.6g} s: "
            f"the state became non-finite or unbounded. Try a smaller dt. Scene: "
            f"{system.scene!r}")
    t_x = cross_t[:n_cross]
    order = np.argsort(t_x, kind="stable")
    keep = t_x[order] >= 0.0
    edges = np.array(["entry", "exit"])
    crossings = FaultCrossings(time_s=t_x[order][keep], fault=cross_f[:n_cross][order][keep],
                               element=cross_e[:n_cross][order][keep],
                               edge=edges[cross_edge[:n_cross][order][keep]])
    info = {"solver": solver, "dt_s": step, "n_steps": int(n_steps), "n_rejected": 0,
            "internal_fs": 1.0 / h_out, "settle_s": -t0, "integration_time_s": wall,
            "n_events": int(len(crossings)),
            "omega_dt": step * system.omega_max, "lambda_dt": step * system.lambda_max}
    return {"exc": exc, "q_inner": rec_qi, "q_outer": rec_qo, "angles": rec_ang,
            "disp": rec_disp, "cage": rec_cage, "crossings": crossings, "info": info,
            "y_end": y}


def scene_load(system: MultibodySystem) -> float:
    """Radial load plus weights, N (a force scale for the divergence bound)."""
    return float(system.p[K.P_FR] + 10.0 * system.p[K.P_G] * system.p[K.P_MI])


def _run(scene: Scene, solver: str, *, dt=None, rtol=None, atol=None, params=None,
         return_forces: bool = False, oversample: int = 4) -> SimulationResult:
    """Simulate ``scene`` with the multibody model (arguments validated by simulate)."""
    t_wall = time.perf_counter()
    system = build(scene, params)
    n_samples = scene.n_samples
    h_out = 1.0 / (scene.fs * oversample)
    raw = integrate(system, h_out=h_out, n_out=n_samples * oversample, stride=oversample,
                    dt=dt, solver=solver)
    info = raw["info"]
    housing = _resonator(raw["exc"], h_out, scene.resonance_hz, scene.resonance_damping)
    accel = add_noise(scene, to_output_rate(housing, n_samples, oversample))
    check_finite(scene, accel, "multibody")
    t = np.arange(n_samples) / scene.fs
    cage = raw["cage"][:n_samples]
    # measured from the simulated motion: the cage's and balls' mean orbital speed
    info["cage_hz"] = float((cage[-1] - cage[0]) / (2.0 * math.pi * max(t[-1], 1e-12))) \
        if n_samples > 1 else float("nan")
    ang = np.unwrap(raw["angles"][:n_samples], axis=0)
    info["ball_orbit_hz"] = float(np.mean(ang[-1] - ang[0]) / (2.0 * math.pi * max(t[-1], 1e-12))) \
        if n_samples > 1 else float("nan")
    info["slip_note"] = "scene.slip is not used: ball slip comes from the traction physics"
    forces = angles = outer = displacement = None
    if return_forces:
        forces = raw["q_inner"][:n_samples].T.copy()
        outer = raw["q_outer"][:n_samples].T.copy()
        angles = ang.T.copy()
        displacement = raw["disp"][:n_samples].T.copy()
    truth = GroundTruth.of_scene(
        scene, t, raw["crossings"],
        contact_forces=forces,
        element_angles=angles,
        displacement=displacement,
        outer_contact_forces=outer,
    )
    info["wall_time_s"] = time.perf_counter() - t_wall
    n_sensors = len(scene.sensors)
    return SimulationResult(accel=accel[0] if n_sensors == 1 else accel, fs=scene.fs, t=t,
                            scene=scene, sensor_names=tuple(s.name for s in scene.sensors),
                            truth=truth, info=info)


#: the planar multibody bearing of Nakhaeinejad & Bryant (2011)
MULTIBODY = Model(
    name="multibody",
    description="planar multibody bearing (Nakhaeinejad & Bryant 2011): inner race, Z "
                "balls, cage and outer race in a housing as bodies; Hertz contacts with "
                "damping, slide-roll traction, centrifugal load, friction torques, notch "
                "profiles",
    represents=frozenset({"ball_dynamics", "contact_dynamics", "contact_forces", "envelope",
                          "varying_speed"}),
    # benchmarks/models_cost.py (docs/models_cost.md): 76x sr5 per simulated second
    # (median of 15 interleaved rounds, IQR 75-77x; CPU time 74x) on the 6205 reference
    # scene at 48 kHz, 53x at 12 kHz, on the loaded shared machine (84x and 61x before
    # the kernels ran without numba's reference counting; 57-93x in earlier runs; 225x
    # before the trig-free contact tests and the step from the linearised spectrum).
    # The Rosenbrock-W solver is not the default: 63x against RK4's 72x side by side
    # (docs/results/multibody_speed.md), less accurate on faulted scenes. Nor are
    # quasi-static balls (MultibodyParameters(balls="quasistatic"), about 0.85x the
    # dynamic balls' cost at their default step): their fault lines are weaker. What
    # each route to 50x can give: docs/results/multibody_speed.md, "routes to 50x sr5"
    # (a cheaper evaluation 55x at most; two RK4 steps per interval 53x, less accurate
    # in the short-horizon loads; two exponential RK4 steps, the overdamped radial mode
    # integrated exactly, 69x: the balance mended, the faulted scene's short-horizon
    # loads not)
    relative_cost=76.0,
    solvers=tuple(SOLVERS),
    fixed_step_solvers=tuple(SOLVERS),
    reference="M. Nakhaeinejad, M. D. Bryant, 'Dynamic modeling of rolling element bearings "
              "with surface contact defects using bond graphs', J. Tribology 133 (2011) "
              "011102, read with E = 210 GPa, K in N/mm^1.5, eq. 12's breakpoint 1.5 and "
              "Kramer's 1e-5 s in eq. 9",
    accepts=_accepts,
    run=_run,
)
