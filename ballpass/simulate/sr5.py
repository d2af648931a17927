"""The Sawalhi-Randall bearing-pedestal models ``sr5`` (with the high-frequency
resonator) and ``sr4`` (without it).

Model
-----
Shaft/inner ring (u_s, v_s) on a support spring k_s, c_s; pedestal/outer ring (u_p, v_p)
on k_p, c_p; between them Z rolling elements with Hertz contact
Q_j = K max(delta_j, 0)^n, n = 3/2 (balls) or 10/9 (rollers),
delta_j = (u_s - u_p) cos psi_j + (v_s - v_p) sin psi_j - c - d_j(t)
(Sawalhi & Randall 2008, eqs. 7-14 as printed in Tran, Furch & Cu, with the shaft damping,
gravity and radial load that the print omits, and eq. 11 — the sprung mass — restored).
The radial load F_r and gravity act along the load line u (angle 0 = centre of the load
zone). Element angles psi_j follow the cage kinematics with random slip (see
:func:`._kernels.element_angles`); d_j(t) is the extra clearance opened by the defects
(``ramped`` or ``sharp`` edges, depth limited by the drop of the mating surfaces over
the defect, :meth:`ballpass.Fault.effective_depth_mm`: a ball defect strikes the inner
race deeper than the outer).
The cage carries a random walk for slip (:func:`._kernels.element_angles`).

``sr5`` adds, for every sensor, Sawalhi & Randall's high-frequency resonator (the
"sprung mass" y_b, default 15 kHz, 5 % damping: m_r = 1 kg, k_r = 8.8826e9 N/m,
c_r = 9424.8 N s/m) base-excited by the housing at the sensor. Assumptions and
deviations from the paper, stated:

* the resonator is a measurement path and does not load the pedestal (one-way
  coupling; the paper couples its 1 kg back). Its output is the absolute acceleration
  of the resonator mass, as in the paper;
* each sensor's housing excitation weights every contact force by a transmission
  factor exp(-kappa (1 - cos(angle from contact to sensor))) (after McFadden & Smith
  1984), so loaded- and unloaded-zone sensors differ; with kappa = 0 it is the pedestal
  acceleration projected on the sensor axis;
* sensors are AC-coupled: the mean of each output channel is removed;
* the balls are massless (quasi-static), there is no centrifugal or gyroscopic load;
  contact damping is an option (``contact_damping``, Hunt & Crossley), off by default
  as in the paper; so is the EHL lubricant film of Liu & Shao 2015 (a scene that
  needs ``"ehl_film"``): Hamrock & Dowson's central film at the inner and outer
  contacts, h_i + h_o, added to every contact approach (a loss of clearance);
* the shaft support spring k_s rests at the loaded static position, so the bearing
  carries all of F_r and the shaft's weight (``shaft_support="loaded"``, default). In
  the paper the spring rests at the unloaded position and shares the static load;
  ``shaft_support="free"`` does that (see :class:`SR5Parameters` for what it changes).

Options from Wrzochal & Adamczak's review (docs/review.md): race and ball waviness
(``Scene(waviness=...)``, :func:`._kernels.waviness`), blunted defect edges
(``Fault(edge="blunt")``), contact damping (``SR5Parameters(contact_damping=...)``),
the EHL film (``Scene(needs=(..., "ehl_film"))``, lubricant in
``SR5Parameters(lubricant_viscosity_pa_s=..., pressure_viscosity_per_pa=...)``).
Realism options of the scene: mounted clearance or preload (``Scene(clearance_um=...)``),
round EDM pits that unload the contact only partly (``Fault(geometry="pit")``), ball
defects that meet the races intermittently (``Fault(engagement=...)``), several structural modes
(``Scene(resonances=...)``), coloured background and shaft lines.

Axial load (``Scene(axial_load_n=...)``, ball bearings with clearance >= 0): the rings'
axial offset is held at the quasi-static value of the rigid-ring equilibrium
(:meth:`ballpass.Bearing.combined_load_distribution`, Harris & Kotzalas ch. 7); each
ball is then compressed by hypot(A sin alpha_0 + delta_a, A + d_j) - A, d_j the radial
approach above, A = (f_i + f_o - 1) d, and only the radial share Q_j cos(alpha_j) acts
on the shaft and pedestal (:func:`._kernels.axial_approach`). There is no axial degree
of freedom: the rings are axially rigid about that offset, and the contact constant K
stays the nominal one (its change with the contact angle is left out).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
from scipy import optimize

from .._validation import check_number
from ..lubrication import (
    FILM_KINDS,
    PRESSURE_VISCOSITY_PER_PA,
    VISCOSITY_PA_S,
    film_thickness_m,
)
from ..scene import STANDARD_GRAVITY, Scene
from . import _kernels as K

__all__ = ["SR5Parameters", "BearingModel", "build_model"]


@dataclass(frozen=True)
class SR5Parameters:
    """Structural parameters of the sr4/sr5 models (SI units), all overridable.

    Parameters
    ----------
    shaft_mass : float
        m_s, shaft and inner ring, kg. Default 3.26, the value of Ruan et al.'s public
        Modelica implementation of the Sawalhi-Randall model (as quoted to
        us; the 1.0 kg used before had no source).
    pedestal_mass : float
        m_p, pedestal and outer ring, kg. Default 6.64 (Ruan et al., as above; was 6.0).
    shaft_stiffness, shaft_damping : float
        k_s (N/m) and c_s (N s/m) of the shaft support. Defaults 7.42e7, 1376.8
        (Sawalhi & Randall 2008, Table 1).
    pedestal_stiffness, pedestal_damping : float
        k_p (N/m) and c_p (N s/m) of the pedestal. Defaults 1.51e7, 2210.7
        (Sawalhi & Randall 2008, Table 1).
    contact_stiffness : float or None
        Hertz load-deflection constant K, N/m^n; None (default) takes
        :meth:`ballpass.Bearing.hertz_stiffness`, derived from the bearing geometry.
    contact_damping : float
        Hunt-Crossley factor alpha, s/m, >= 0: each contact carries
        Q = K delta^n (1 + alpha d(delta)/dt), never negative (Hunt & Crossley 1975).
        The damping force alpha K delta^n d(delta)/dt grows with the load, as the
        lubricated-contact damping of Kong et al. 2019 (as Wrzochal & Adamczak review it) does, and
        vanishes on separation with the contact itself (no jump at contact). The factor
        follows from the coefficient of restitution e at an impact speed v as
        alpha = 3 (1 - e) / (2 v) (Hunt & Crossley); Kong et al.'s dependence on speed
        and lubricant viscosity is not modelled (the review does not print their formula).
        Default 0 (no contact damping, as Sawalhi & Randall).
    shaft_support : {"loaded", "free"}
        Where the shaft support spring k_s rests. ``"loaded"`` (default): at the loaded
        static position, so the bearing carries all of F_r and the shaft's weight.
        ``"free"``: at the unloaded position, as in Sawalhi & Randall 2008, so k_s
        carries part of the static load (for a 6205 at 500 N about a third, see
        docs/sim2real.md) and the load zone shrinks.
    lubricant_viscosity_pa_s, pressure_viscosity_per_pa : float
        Lubricant dynamic viscosity (Pa s, > 0) and Barus pressure-viscosity
        coefficient (1/Pa, > 0) of the EHL film, used only when the scene needs
        ``"ehl_film"``. Defaults 0.060 and 2.2e-8: an ISO VG 68 mineral oil at 40 C
        (:mod:`ballpass.lubrication`).

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate import SR5Parameters
    >>> heavy = SR5Parameters(shaft_mass=6.0)
    >>> heavy.shaft_mass, SR5Parameters().pedestal_stiffness
    (6.0, 15100000.0)
    >>> scene = bp.Scene("6205", rpm=1797, fault=bp.Fault("inner"), duration_s=0.05)
    >>> bp.simulate(scene, params=heavy).accel.shape
    (2400,)
    """

    shaft_mass: float = 3.26
    pedestal_mass: float = 6.64
    shaft_stiffness: float = 7.42e7
    shaft_damping: float = 1376.8
    pedestal_stiffness: float = 1.51e7
    pedestal_damping: float = 2210.7
    contact_stiffness: float | None = None
    contact_damping: float = 0.0
    shaft_support: str = "loaded"
    lubricant_viscosity_pa_s: float = VISCOSITY_PA_S
    pressure_viscosity_per_pa: float = PRESSURE_VISCOSITY_PER_PA

    def __post_init__(self) -> None:
        if self.shaft_support not in ("loaded", "free"):
            raise ValueError(f"shaft_support must be 'loaded' or 'free', got "
                             f"{self.shaft_support!r}")
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name == "shaft_support" or (value is None and f.name == "contact_stiffness"):
                continue
            # damping may be zero (an undamped structure); masses and stiffnesses not
            check_number(f.name, value, 0.0, lo_open=not f.name.endswith("damping"))


@dataclass
class BearingModel:
    """A scene bound to the sr4/sr5 kernels: parameters, kinematics and initial state.

    Attributes
    ----------
    scene : Scene
    params : SR5Parameters
    n_res : int
        Resonators in the state (one per sensor for sr5, 0 for sr4).
    p : ndarray (N_PARAMS,)
        Kernel parameter vector (indices ``P_*`` of :mod:`._kernels`), SI units.
    walk : ndarray
        Random walk of the cage angle, one knot per element spacing of cage angle, rad.
    psi0 : ndarray (Z,)
        Element angles at t = 0, rad.
    faults : ndarray (n_faults, N_FCOLS)
        Fault table (columns ``F_*`` of :mod:`._kernels`).
    sensors : ndarray (n_sensors, N_SCOLS)
        Sensor table (columns ``S_*`` of :mod:`._kernels`).
    y0 : ndarray (n_state,) or None
        Static equilibrium at t = 0 (full layout); None when bound without it.
    scale : ndarray (n_state,) or None
        Characteristic magnitude of each state component (for tolerances).
    levels : ndarray (n_faults, 4)
        Angular offsets (rad) marking fault edges and ramp ends.
    static_deflection : float
        Largest contact deflection at the static equilibrium, m (NaN without it).
    film_m : float
        EHL film thickness h_i + h_o added to every contact approach (Liu & Shao
        2015) at the mean speed, m; 0 unless the scene needs ``"ehl_film"`` (then the
        last row of ``faults``, scaled with the speed of a ramp).

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate import build
    >>> bm = build(bp.Scene("6205", rpm=1797, duration_s=0.01), model="sr4")
    >>> bm.n_res, bm.n_state, bm.psi0.shape     # no resonator; 9 balls
    (0, 8, (9,))
    """

    scene: Scene
    params: SR5Parameters
    n_res: int
    p: np.ndarray
    walk: np.ndarray
    psi0: np.ndarray
    faults: np.ndarray
    sensors: np.ndarray
    y0: np.ndarray | None
    scale: np.ndarray | None
    levels: np.ndarray
    static_deflection: float
    film_m: float = 0.0

    @property
    def n_state(self) -> int:
        """Length of the state vector, 2 (4 + n_res)."""
        return 2 * (4 + self.n_res)

    @property
    def model(self) -> tuple:
        """``(p, walk, faults, sensors)``: the arrays every kernel takes."""
        return self.p, self.walk, self.faults, self.sensors

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt of the full state (all resonators included) at (t, y): the compiled
        right-hand side, callable from Python (e.g. by ``scipy.integrate.solve_ivp``).

        Examples
        --------
        Integrate the compiled model with scipy (slower, for cross-checks):

        >>> import ballpass as bp
        >>> from scipy.integrate import solve_ivp
        >>> from ballpass.simulate import build
        >>> bm = build(bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.002))
        >>> sol = solve_ivp(bm.rhs, (0.0, 0.002), bm.y0, rtol=1e-8, atol=1e-12 * bm.scale)
        >>> sol.status, sol.y.shape[0]
        (0, 10)
        """
        dydt = np.empty(self.n_state)
        K.rhs(float(t), np.ascontiguousarray(y, dtype=np.float64), dydt, *self.model,
              self.n_res, self._kin, self._buf, self._acc)
        return dydt

    def sensor_output(self, t: float, y: np.ndarray) -> np.ndarray:
        """Sensor accelerations (m/s^2) at full state y, before AC coupling.

        Examples
        --------
        >>> import ballpass as bp
        >>> from ballpass.simulate import build
        >>> bm = build(bp.Scene("6205", rpm=1797, duration_s=0.01, sensors=("loaded", "unloaded")))
        >>> bm.sensor_output(0.0, bm.y0).shape          # one value per sensor, m/s^2
        (2,)
        """
        K.sensor_output(float(t), np.ascontiguousarray(y, dtype=np.float64), *self.model,
                        self.n_res, self._kin, self._acc)
        return self._acc[0].copy()

    def __post_init__(self) -> None:
        self._kin = K.kinematics_scratch(self.scene.bearing.n_elements)
        self._buf = np.empty(2 * K.N_CORE)
        self._acc = np.empty((1, len(self.scene.sensors)))


def _ellipse_half_width_m(bearing, race: str, load_n: float) -> float:
    """Semi-axis a (m) of the Hertz contact ellipse across the track of one contact
    under ``load_n`` (:meth:`ballpass.Bearing.contact_ellipse`); for a roller, half its
    length (a line contact spans the roller)."""
    if bearing.element == "roller":
        return 0.5 * bearing.roller_length_mm * 1e-3
    return bearing.contact_ellipse(race, load_n)[0]


#: Stribeck's load of the most loaded element, Q_max = 4.37 F_r / Z (zero clearance,
#: Harris & Kotzalas ch. 7), the reference load of a pit's equivalent depth
STRIBECK_FACTOR = 4.37


def _reference_load_n(bearing, bearing_load: float) -> float:
    """Stribeck's Q_max (N) under the radial load ``bearing_load`` (N), at least 1 N."""
    return max(STRIBECK_FACTOR * bearing_load / bearing.n_elements, 1.0)


def _pit_depth_m(scene: Scene, fault, kh: float, bearing_load: float, race: str) -> float:
    """Extra clearance (m) equivalent to a round pit that unloads a contact on ``race``
    partly.

    The contact on the pit keeps the share 1 - f of its load (f from
    :meth:`ballpass.Fault.pit_unloading`, with the ellipse of the most loaded element's
    contact on that race, Stribeck's Q_max). At that element's deflection
    delta_ref = (Q_max / K)^(1/n) the same load follows from an extra clearance
    h = delta_ref (1 - (1 - f)^(1/n)); the depth used is min(h, the drop of the mating
    surfaces over the pit's width, :meth:`ballpass.Fault.effective_depth_mm` against
    ``race``), the bound for a pit that unloads the contact fully. An equivalent
    clearance, exact at the reference load only: a lighter contact is unloaded a little
    more, a heavier one a little less.
    """
    b = scene.bearing
    n = b.load_exponent
    q_ref = _reference_load_n(b, bearing_load)
    share = fault.pit_unloading(_ellipse_half_width_m(b, race, q_ref) * 1e3)
    drop = fault.effective_depth_mm(b, race) * 1e-3
    if share >= 1.0:
        return drop
    delta_ref = (q_ref / kh) ** (1.0 / n)
    return min(drop, delta_ref * (1.0 - (1.0 - share) ** (1.0 / n)))


def _depths_m(scene: Scene, fault, kh: float, bearing_load: float) -> tuple[float, float]:
    """Depths (m) of a fault's strikes: a race fault against its own race (twice); a
    ball fault against the outer race, then the inner (fault-table columns F_DEPTH and
    F_DEPTH_IN)."""
    races = ("outer", "inner") if fault.kind == "ball" else (fault.kind, fault.kind)
    if fault.geometry == "pit":
        return tuple(_pit_depth_m(scene, fault, kh, bearing_load, r) for r in races)
    return tuple(fault.effective_depth_mm(scene.bearing, r) * 1e-3 for r in races)


_WAVY_KINDS = {"outer": K.KIND_WAVY_OUTER, "inner": K.KIND_WAVY_INNER, "ball": K.KIND_WAVY_BALL}


def _waviness_rows(scene: Scene, rng: np.random.Generator) -> list:
    """Fault-table rows of the scene's waviness: one per order (per order and ball for
    ball waviness, each ball with a random extra phase: balls are made one by one)."""
    rows = []
    for wav in scene.waviness:
        for q, amp, phase in zip(wav.orders, wav.amplitudes_um, wav.phases_deg, strict=True):
            balls = range(scene.bearing.n_elements) if wav.race == "ball" else (0,)
            for e in balls:
                row = np.zeros(K.N_FCOLS)
                extra = rng.uniform(0.0, 2.0 * math.pi) if wav.race == "ball" else 0.0
                row[[K.F_KIND, K.F_CENTRE, K.F_HALF, K.F_DEPTH, K.F_ELEM, K.F_ENGAGE]] = (
                    _WAVY_KINDS[wav.race], math.radians(phase) + extra, q, amp * 1e-6, e, 1.0)
                rows.append(row)
    return rows


def _drift_columns(scene: Scene, fault,
                   bearing_load: float) -> tuple[float, float, float, float]:
    """Fault-table columns F_DRIFT, F_BALL_A, F_PIT_A, F_A_IN of a ball defect whose
    spin axis drifts (:func:`._kernels.strike_share`): sin of the drift range, the ball
    radius R and the pit radius w/2 over the semi-axis a_o of the outer-race contact
    ellipse across the track, and a_o over the inner-race contact's a_i (the contacts of
    the most loaded ball, Stribeck's Q_max, as for a pit)."""
    b = scene.bearing
    q_ref = _reference_load_n(b, bearing_load)
    a = _ellipse_half_width_m(b, "outer", q_ref)
    return (math.sin(math.radians(fault.spin_drift_deg)), 0.5 * b.element_diameter_m / a,
            0.5 * fault.width_mm * 1e-3 / a, a / _ellipse_half_width_m(b, "inner", q_ref))


def _fault_table(scene: Scene, psi0: np.ndarray, kh: float | None = None,
                 bearing_load: float | None = None, rng: np.random.Generator | None = None,
                 draws: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Kernel fault table (localized faults first, then waviness rows) and the event
    levels (rad) of each localized fault. ``kh`` (default: the bearing's Hertz
    constant) and ``bearing_load`` (default: the radial load) size round pits; ``rng``
    (default: seeded by the scene) draws the per-fault seeds and ball phases.
    ``draws=False`` draws no waviness rows, and the per-fault seeds (column F_SEED,
    which only the strikes of an intermittent ball defect read, :func:`._kernels.
    strike_share`) only when a fault is intermittent: the same seeds as with draws
    (they come first), so the impulse model strikes on sr5's revolutions; for callers
    that use only the localized faults' kinematics."""
    b = scene.bearing
    kh = kh or b.hertz_stiffness()
    bearing_load = scene.radial_load_n if bearing_load is None else bearing_load
    seeds = draws or any(f.engagement < 1.0 or f.spin_drift_deg > 0.0 for f in scene.faults)
    if seeds:
        rng = rng or np.random.default_rng(np.random.SeedSequence(scene.seed).spawn(4)[3])
    rows, levels = [], []
    for f in scene.faults:
        depth_m, depth_in = _depths_m(scene, f, kh, bearing_load)
        width_m = f.width_mm * 1e-3
        if f.kind == "ball":
            radius = 0.5 * b.element_diameter_m
            kind = K.KIND_BALL
        else:
            radius = b.outer_race_radius_m if f.kind == "outer" else b.inner_race_radius_m
            kind = K.KIND_OUTER if f.kind == "outer" else K.KIND_INNER
        half = 0.5 * width_m / radius
        ramp = f.ramp_fraction if f.edge in ("ramped", "blunt") else 0.0
        shape = K.RAMP_LINEAR if f.edge == "blunt" else K.RAMP_COSINE
        row = np.zeros(K.N_FCOLS)
        row[[K.F_KIND, K.F_CENTRE, K.F_HALF, K.F_DEPTH, K.F_RAMP, K.F_ELEM, K.F_PSI0,
             K.F_SHAPE, K.F_ENGAGE, K.F_SEED]] = (
            kind, math.radians(f.angle_deg), half, depth_m, ramp, f.element,
            psi0[f.element] if f.kind == "ball" else 0.0, shape, f.engagement,
            float(rng.integers(1, 2**20)) if seeds else 0.0)
        if f.kind == "ball":
            row[K.F_DEPTH_IN] = depth_in
        if f.spin_drift_deg > 0.0:
            row[[K.F_DRIFT, K.F_BALL_A, K.F_PIT_A, K.F_A_IN]] = _drift_columns(
                scene, f, bearing_load)
        rows.append(row)
        inner = half * (1.0 - 2.0 * ramp) if ramp > 0 else math.nan
        levels.append([-half, -inner, inner, half])
    if draws:
        rows += _waviness_rows(scene, rng)
    return (np.array(rows, dtype=np.float64).reshape(-1, K.N_FCOLS),
            np.array(levels, dtype=np.float64).reshape(-1, 4))


def _sensor_table(scene: Scene) -> np.ndarray:
    """Kernel sensor table: angle (rad), attenuation, cos and sin of the angle."""
    table = np.empty((len(scene.sensors), K.N_SCOLS))
    for i, s in enumerate(scene.sensors):
        a = math.radians(s.angle_deg)
        table[i, [K.S_ANG, K.S_ATT, K.S_COS, K.S_SIN]] = a, s.attenuation, math.cos(a), math.sin(a)
    return table


def _slip_walk(scene: Scene, cage_ratio: float, rng: np.random.Generator) -> np.ndarray:
    """Random walk of the cage angle (rad), one knot per element spacing of cage angle.

    Knot k holds (2 pi / Z) * sum_{i<=k} eps_i with eps_i ~ N(0, slip^2): the cage takes
    (1 + eps_i) times the nominal angle increment over the i-th ball-pass interval, so
    consecutive impact intervals differ by ``slip`` of the period (1 sigma).
    """
    z = scene.bearing.n_elements
    total_cage = cage_ratio * scene.speed.shaft_angle(scene.duration_s, scene.duration_s)
    n_knots = int(math.floor(total_cage * z / (2 * math.pi))) + 3
    # A pass at a fixed angle falls at a fraction u of a knot interval and mixes two
    # increments, (1-u) eps_k + u eps_k+1; E[(1-u)^2 + u^2] = 2/3 over u, hence the
    # sqrt(3/2): on average over fault positions the period std equals ``slip``.
    steps = -scene.slip * math.sqrt(1.5) * rng.standard_normal(n_knots)
    steps[0] = 0.0
    return (2.0 * math.pi / z) * np.cumsum(steps)


def build_model(scene: Scene, params: SR5Parameters | None = None, *,
                resonator: bool = True, equilibrium: bool = True) -> BearingModel:
    """Bind a scene to the sr5 (``resonator=True``) or sr4 kernels.

    Draws the slip table from the scene's seed, converts faults and sensors to kernel
    arrays and solves the static equilibrium at t = 0 so that the run starts without a
    start-up transient.

    Parameters
    ----------
    scene : Scene
    params : SR5Parameters, optional
    resonator : bool
        True for sr5, False for sr4.
    equilibrium : bool
        False skips the static equilibrium, for callers that use only the kinematics
        (``p``, ``walk``, ``faults``, ``levels``: the impulse model): ``y0`` and
        ``scale`` are then None, ``static_deflection`` NaN, and the elastic-limit check
        is the caller's. It also skips the draws only the contact kernels read (see
        :func:`_fault_table`): the localized faults' rows without their seeds, no
        waviness rows, no EHL film.

    Returns
    -------
    BearingModel
    """
    params = params or SR5Parameters()
    b = scene.bearing
    kh = params.contact_stiffness or b.hertz_stiffness()
    clearance = b.radial_clearance_m if scene.clearance_um is None else scene.clearance_um * 1e-6
    speed = scene.speed
    orders = b.frequencies(1.0)  # the kinematic frequencies per unit shaft speed
    cage_ratio = orders.ftf
    spin_ratio = orders.bsf / orders.ftf
    g = STANDARD_GRAVITY if scene.gravity else 0.0
    w_r = 2.0 * math.pi * scene.resonance_hz
    p = np.zeros(K.N_PARAMS)
    p[K.P_MS] = params.shaft_mass
    p[K.P_MP] = params.pedestal_mass
    p[K.P_KS] = params.shaft_stiffness
    p[K.P_CS] = params.shaft_damping
    p[K.P_KP] = params.pedestal_stiffness
    p[K.P_CP] = params.pedestal_damping
    p[K.P_KH] = kh
    p[K.P_NH] = b.load_exponent
    p[K.P_CLEAR] = clearance
    p[K.P_FR] = scene.radial_load_n
    p[K.P_G] = g
    p[K.P_W0] = speed.rpm_start * math.pi / 30.0
    p[K.P_W1] = speed.rpm_end * math.pi / 30.0
    p[K.P_T] = scene.duration_s
    p[K.P_CAGE] = cage_ratio
    p[K.P_SPIN] = spin_ratio
    p[K.P_Z] = b.n_elements
    p[K.P_WR] = w_r
    p[K.P_ZETA] = scene.resonance_damping
    p[K.P_COS_STEP] = math.cos(2.0 * math.pi / b.n_elements)
    p[K.P_SIN_STEP] = math.sin(2.0 * math.pi / b.n_elements)
    p[K.P_CD] = params.contact_damping
    if scene.axial_load_n > 0.0:
        p[K.P_AX], p[K.P_A] = _axial_offset(scene, params, clearance, g)

    # children of the scene seed: 0 slip, 1 noise, 2 shaft lines, 3 fault draws; the
    # two used here built directly (SeedSequence(seed, spawn_key=(i,)) is the i-th child
    # that SeedSequence(seed).spawn returns, in a third of spawn(4)'s time)
    slip_seed = np.random.SeedSequence(scene.seed, spawn_key=(0,))
    walk = _slip_walk(scene, cage_ratio, np.random.default_rng(slip_seed))
    psi0 = K.element_angles_many(np.zeros(1), p, walk, b.n_elements)[0]
    bearing_load = scene.radial_load_n + params.shaft_mass * g
    faults, levels = _fault_table(
        scene, psi0, kh, bearing_load,
        np.random.default_rng(np.random.SeedSequence(scene.seed, spawn_key=(3,)))
        if equilibrium else None, draws=equilibrium)
    film = 0.0
    if equilibrium and "ehl_film" in scene.needs:
        film = _film_m(scene, params, bearing_load)
        row = np.zeros((1, K.N_FCOLS))
        row[0, [K.F_KIND, K.F_CENTRE, K.F_HALF, K.F_DEPTH]] = (
            K.KIND_FILM, scene.speed.mean_rpm * math.pi / 30.0, FILM_KINDS["central"][1], film)
        faults = np.concatenate((faults, row))
    sensors = _sensor_table(scene)
    n_res = len(scene.sensors) if resonator else 0

    y0, scale, deflection = (_static_state(scene, params, (p, walk, faults, sensors), n_res,
                                           kh) if equilibrium else (None, None, math.nan))
    return BearingModel(scene=scene, params=params, n_res=n_res, p=p, walk=walk, psi0=psi0,
                        faults=faults, sensors=sensors, y0=y0, scale=scale, levels=levels,
                        static_deflection=deflection, film_m=film)


def _film_m(scene: Scene, params: SR5Parameters, bearing_load: float) -> float:
    """EHL film h_i + h_o (m) that Liu & Shao (2015, eq. 19 as Wrzochal & Adamczak
    report it) add to every contact approach: Hamrock & Dowson's central film
    (:func:`ballpass.lubrication.film_thickness_m`) at the inner and the outer contact.

    Evaluated at the mean shaft speed and at Stribeck's load of the most loaded
    element, Q_max = 4.37 F / Z (the film varies as Q^-0.067, so the lighter contacts'
    films are within a few per cent of it); the kernel scales it with the speed of a
    ramp as Hamrock & Dowson's u^0.67 (:func:`._kernels.film`). Its change with the
    curvature of a wavy surface, which Liu & Shao include, is not modelled.
    """
    b = scene.bearing
    q_ref = max(STRIBECK_FACTOR * bearing_load / b.n_elements, 1.0)
    return sum(film_thickness_m(b, race, q_ref, scene.speed.mean_rpm,
                                viscosity_pa_s=params.lubricant_viscosity_pa_s,
                                pressure_viscosity_per_pa=params.pressure_viscosity_per_pa)
               for race in ("inner", "outer"))


#: largest static contact deflection the model accepts, as a fraction of the element
#: diameter. Hertz's law is elastic; bearing steel yields from about the static load
#: rating (ISO 76, 4.2 GPa contact pressure), which a 6205 reaches at ~0.7 % of d.
MAX_DEFLECTION_RATIO = 0.01


def _check_elastic(scene: Scene, delta_max: float, bearing_load: float) -> None:
    """Refuse a load that deflects the contacts beyond the elastic Hertz regime."""
    limit = MAX_DEFLECTION_RATIO * scene.bearing.element_diameter_m
    if delta_max > limit:
        # deflection grows as load^(1/n) for zero clearance: the load that reaches it
        n = scene.bearing.load_exponent
        allowed = bearing_load * (limit / delta_max) ** n
        raise ValueError(
            f"radial_load_n={scene.radial_load_n:g} N deflects the most loaded contact by "
            f"{delta_max * 1e6:.0f} um, more than {MAX_DEFLECTION_RATIO:.0%} of the element "
            f"diameter ({limit * 1e6:.0f} um): the bearing would yield and the elastic Hertz "
            f"contact of the model no longer applies. Use radial_load_n below about "
            f"{allowed:.3g} N for this bearing.")


def _axial_offset(scene: Scene, params: SR5Parameters, clearance: float,
                  g: float) -> tuple[float, float]:
    """Axial offset of the groove centres, A sin(alpha_0) + delta_a (m), and their
    unloaded distance A = (f_i + f_o - 1) d (m) under the scene's axial load.

    delta_a is the quasi-static axial ring displacement of the rigid-ring equilibrium
    under the axial load and the bearing's radial load (radial load plus the shaft's
    weight), :meth:`ballpass.Bearing.combined_load_distribution`; sr5 holds it there
    (no axial degree of freedom: the rings are axially rigid about that position)."""
    b = scene.bearing.with_clearance(clearance * 1e3)
    big_a = (b.inner_conformity + b.outer_conformity - 1.0) * b.element_diameter_m
    alpha_0 = math.acos(1.0 - clearance / big_a)
    ld = b.combined_load_distribution(scene.radial_load_n + params.shaft_mass * g,
                                      scene.axial_load_n)
    return big_a * math.sin(alpha_0) + ld.axial_deflection_m, big_a


def _static_state(scene: Scene, params: SR5Parameters, model: tuple, n_res: int, kh: float):
    """Static equilibrium at t = 0, characteristic scales of the state and the largest
    static contact deflection (m).

    With ``shaft_support="loaded"`` the bearing carries the radial load and the shaft's
    weight: the shaft support spring k_s acts about the loaded static position (its
    rest position ``p[P_US0]`` is set here), so it shares the dynamic, not the static,
    load. Solves the 2-D contact balance sum_j Q_j n_j = (F_r + m_s g) e_u for the ring
    displacement. With ``"free"`` the spring rests at the origin (Sawalhi & Randall):
    shaft k_s x_s + F_c = (F_r + m_s g) e_u and pedestal k_p x_p = F_c + m_p g e_u, i.e.
    F_c (1 + k_s/k_p) + k_s (x_s - x_p) = (F_r + m_s g - k_s m_p g / k_p) e_u.
    """
    b = scene.bearing
    p, _walk, faults, sensors = model
    z = b.n_elements
    kin = K.kinematics_scratch(z)
    K.kinematics(0.0, *model[:3], kin)
    depth = kin[K.K_DEPTH, :z].copy()
    cos_psi, sin_psi = np.cos(kin[K.K_PSI, :z]), np.sin(kin[K.K_PSI, :z])
    n = b.load_exponent
    c = p[K.P_CLEAR]
    g = p[K.P_G]
    bearing_load = scene.radial_load_n + params.shaft_mass * g
    ks = params.shaft_stiffness if params.shaft_support == "free" else 0.0
    share = 1.0 + ks / params.pedestal_stiffness  # 1 for the loaded support
    target = bearing_load - ks * params.pedestal_mass * g / params.pedestal_stiffness

    def contact(d):
        delta = d[0] * cos_psi + d[1] * sin_psi - c - depth
        if p[K.P_AX] == 0.0:
            return kh * np.maximum(delta, 0.0) ** n, delta
        # axial load: normal approach and the radial share Q cos(alpha) (K.axial_approach)
        dist = np.hypot(p[K.P_AX], p[K.P_A] + delta)
        normal = dist - p[K.P_A]
        return kh * np.maximum(normal, 0.0) ** n * (p[K.P_A] + delta) / dist, normal

    def residual(d):
        q, _ = contact(d)
        return [(share * np.sum(q * cos_psi) + ks * d[0] - target) / kh,
                (share * np.sum(q * sin_psi) + ks * d[1]) / kh]

    def jacobian(d):
        _, delta = contact(d)
        dq = share * n * np.maximum(delta, 0.0) ** (n - 1.0)
        return [[np.sum(dq * cos_psi**2) + ks / kh, np.sum(dq * cos_psi * sin_psi)],
                [np.sum(dq * cos_psi * sin_psi), np.sum(dq * sin_psi**2) + ks / kh]]

    # Start past the first contact: the ring must close the clearance, and the depth of
    # a defect under an element, before any force (or Jacobian) appears; from inside
    # that dead zone the solver cannot move (NJ305, 0.125 mm clearance, with a fault).
    ahead = cos_psi > 0.5
    first_contact = float(np.min((max(c, 0.0) + depth[ahead]) / cos_psi[ahead]))
    guess = (max(bearing_load, 1e-3) / (kh * z / 4.0)) ** (1.0 / n) + first_contact
    if bearing_load <= 0.0 and c >= 0.0:
        du, dv = 0.0, 0.0  # unloaded ring with clearance: centred, no contact
    else:
        sol = optimize.root(residual, x0=[guess, 0.0],
                            jac=jacobian if p[K.P_AX] == 0.0 else None, method="hybr",
                            options={"xtol": 1e-13})
        # judge by the force residual, not by hybr's progress flag: 1e-9 of the load
        if max(abs(v) for v in residual(sol.x)) * kh > 1e-9 * max(bearing_load, 1.0):
            raise RuntimeError(
                f"static equilibrium did not converge for {scene!r}: {sol.message}")
        du, dv = sol.x
    q, delta = contact((du, dv))
    deflection = float(np.max(delta, initial=0.0))
    _check_elastic(scene, deflection, bearing_load)
    fu, fv = np.sum(q * cos_psi), np.sum(q * sin_psi)
    u_p = (fu + params.pedestal_mass * g) / params.pedestal_stiffness
    v_p = fv / params.pedestal_stiffness
    u_s, v_s = u_p + du, v_p + dv
    # support spring at rest in the static position ("loaded") or at the origin
    p[K.P_US0] = u_s if ks == 0.0 else 0.0
    p[K.P_VS0] = v_s if ks == 0.0 else 0.0
    nd = 4 + n_res
    y0 = np.zeros(2 * nd)
    y0[:4] = [u_s, v_s, u_p, v_p]
    if n_res:
        # resonators at rest under the static housing acceleration
        sacc = np.empty((1, len(scene.sensors)))
        yc = np.concatenate((y0[:4], y0[nd:nd + 4]))
        K.contact_loads(yc, p, kin, 4)
        K.housing_accel(yc, yc, p, sensors, kin, 0.0, sacc, 0, False)
        y0[4:nd] = -sacc[0] / p[K.P_WR] ** 2
    load = bearing_load + params.pedestal_mass * g

    # scales: contact deflection, its velocity at the contact frequency, resonator
    x_scale = max(abs(du), abs(c), float(np.max(faults[:, [K.F_DEPTH, K.F_DEPTH_IN]],
                                                  initial=0.0)), 1e-7)
    if p[K.P_AX] != 0.0:
        # an axial load compresses every contact by itself: its normal approach sets
        # the contact frequency (and so the default step)
        x_scale = max(x_scale, deflection)
    k_lin = n * kh * x_scale ** (n - 1.0) * z / 2.0
    w_c = math.sqrt(k_lin / params.shaft_mass)
    f_scale = max(kh * x_scale**n, load)
    scale = np.empty(2 * nd)
    scale[:4] = x_scale
    scale[nd:nd + 4] = x_scale * w_c
    if n_res:
        w_r = p[K.P_WR]
        z_scale = f_scale / params.pedestal_mass / w_r**2
        scale[4:nd] = z_scale
        scale[nd + 4:] = z_scale * w_r
    return y0, scale, deflection
