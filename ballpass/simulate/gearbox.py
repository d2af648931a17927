"""The ``gearbox`` model: a gear pair coupled to the sr5 bearing-pedestal model
(Tran, Furch & Cu; Sawalhi & Randall 2008).

The gearbox model
-----------------
The scene's bearing carries the input shaft, and the pinion of ``scene.gears`` (a
:class:`~ballpass.GearPair`) sits on that shaft; the gear turns on a second, elastically
supported shaft. Degrees of freedom (kernels in :mod:`._gear_kernels`):

* bearing: the sr5 shaft/inner ring u_s, v_s and pedestal/outer ring u_p, v_p with Hertz
  contacts, clearance, slip and localized faults (Tran, Furch & Cu eqs. 7-16 with the shaft
  damping, gravity, radial load and the sprung mass of eq. 11 restored; see
  :mod:`.sr5`). The pinion's lateral motion is the shaft's, and its mass is added to
  the shaft's;
* drive (motor rotor) torsion th_m: I_m th_m'' = T_p - M_t, driven by the input torque
  T_p and connected to the pinion by the input shaft, M_t = k_t (th_m - th_p) + c_t (..)';
* pinion torsion th_p (eq. 5): I_p th_p'' = M_t - r_bp N;
* gear torsion th_g and lateral x_g along the line of action (eqs. 4, 6):
  I_g th_g'' = r_bg N - T_g - k_o th_g - c_o th_g', m_g x_g'' = -k_g x_g - c_g x_g' - N,
  with the load torque T_g = T_p r_bg / r_bp and the output shaft (k_o) to a load turning
  at the nominal speed ``Scene.rpm * teeth[0] / teeth[1]``. Torque is an input: the
  mean mesh force is T_p / r_bp in steady state (the drive's and the pinion's torque
  balances); during a speed ramp the angles are relative to the nominal motion and its
  angular acceleration alpha takes (I_m + I_p) alpha of the input torque.
  c_t, c_o: 5 % of critical for each shaft on its wheel (assumed);
* mesh force along the line of action N = k(t) delta + c_m delta' for delta > 0, exactly
  0 when the teeth separate, with delta = r_bp th_p - r_bg th_g - (u_s - x_g) - e(t):
  the time-varying mesh stiffness k(t) from the transverse contact ratio and the
  helical overlap, a tooth fault as a local loss of it, and the static transmission
  error e(t) (mesh harmonics plus the runout of each wheel); see :mod:`ballpass.gears`.

The line of action is the bearing's load line: the mean mesh force adds to
``radial_load_n`` and the load zone stays centred at 0 deg. Each sensor reads the
housing through the sr5 transmission weighting and Sawalhi & Randall's resonator
(``resonance_hz``, ``resonance_damping``), applied as an exact (first-order-hold)
discretisation of its base-excitation transfer function to the housing acceleration on
the internal grid.

Assumptions and deviations from Tran, Furch & Cu, stated:

* the friction forces F_p, F_g and moments M_p, M_g of eqs. 1-6 are neglected, so the
  gear's motion across the line of action (y_g in eqs. 2, 4) is not excited and is not
  integrated; the helical mesh's axial force is ignored (planar model);
* the gear's own bearings are a linear support (k_g, c_g of :class:`GearPair`), not
  Hertz contacts; the sensors sit on the input bearing's housing, which the mesh
  reaches through that bearing;
* the solver is a fixed-step RK4, default step 0.35 / (fastest linearised mode; the
  mesh's torsional mode, ~10 kHz, sets ~5.6 us), split at the stiffness jumps of a spur
  mesh but not at bearing fault edges (the sr5 driver's event handling is not repeated
  here): keep the default ``"ramped"`` fault edges, or a small ``dt`` for sharp ones.
  Against scipy's DOP853 at rtol 1e-11 the mesh force's largest error is 3e-4 of its
  standard deviation for the helical Tran, Furch & Cu pair and 2.3e-3 for the 15/29 spur pair
  (whose jumps ring the mesh mode), 2e-7 at dt = 0.5 us (``tests/test_gearbox.py``);
  the output's relative L2 error at the default step is below 1e-4 on Tran, Furch & Cu's
  scenes (benchmarks/gearbox_step.py);
* the simulation starts from the static equilibrium under the mean mesh force; the
  torsional modes' start-up transient decays within a few ms (5-7 % damping).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np
from scipy import signal as _signal

from ..gears import GearPair
from ..scene import Scene
from . import _gear_kernels as G
from . import _kernels as K
from ._registry import Model
from ._shared import (
    OVERSAMPLE,
    SimulationUnstableError,
    add_noise,
    check_finite,
    divisor_step,
    to_output_rate,
)
from ._sr5_driver import DT_DEFAULT_OMEGA, SR5, _edge_names, _events, add_modes
from .result import FaultCrossings, GroundTruth, SimulationResult, effective_depths_mm
from .sr5 import BearingModel, SR5Parameters, build_model

__all__ = ["GEARBOX", "GearTruth", "GearboxModel", "build_gearbox"]

#: damping ratio of the drive's torsional mode (input shaft and coupling), assumed
DRIVE_DAMPING_RATIO = 0.05


@dataclass(frozen=True)
class GearTruth:
    """What the gear pair did (``res.truth.gear``).

    Attributes
    ----------
    pair : GearPair
    label : str
        ``"healthy"`` or the tooth fault's kind (``"crack"``, ``"spall"``).
    mesh_frequency_hz, pinion_hz, gear_hz : float
        Mean mesh and shaft frequencies, Hz.
    gear_shaft_angle : ndarray (n_samples,)
        Tachometer of the gear's shaft: angle turned since t = 0, rad.
    mesh_force : ndarray (n_samples,)
        Force along the line of action, N (0 when the teeth separate).
    mesh_stiffness : ndarray (n_samples,)
        Time-varying mesh stiffness, N/m.
    transmission_error : ndarray (n_samples,)
        Static transmission error imposed on the mesh, m.
    fault_entries_s : ndarray
        Times at which the faulty tooth begins to mesh, s (empty when healthy).
    """

    pair: GearPair
    label: str
    mesh_frequency_hz: float
    pinion_hz: float
    gear_hz: float
    gear_shaft_angle: np.ndarray
    mesh_force: np.ndarray
    mesh_stiffness: np.ndarray
    transmission_error: np.ndarray
    fault_entries_s: np.ndarray


@dataclass
class GearboxModel:
    """A scene bound to the gearbox kernels.

    Attributes
    ----------
    bearing : BearingModel
        The sr4 binding of the input bearing (pinion mass on the shaft, static
        equilibrium under radial load plus mean mesh force).
    g : ndarray (N_GPARAMS,)
        Gear parameters (indices ``G_*`` of :mod:`._gear_kernels`).
    te : ndarray (n_harmonics, 2)
        Static transmission error: amplitude (m) and phase (rad) per mesh harmonic.
    y0 : ndarray (N_STATE,)
        Initial (static) state.
    omega_max : float
        Fastest linearised mode the RK4 step must resolve, rad/s.
    """

    bearing: BearingModel
    g: np.ndarray
    te: np.ndarray
    y0: np.ndarray
    omega_max: float

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """dy/dt at (t, y), callable from Python (e.g. ``scipy.integrate.solve_ivp``)."""
        bm = self.bearing
        dydt = np.empty(G.N_STATE)
        G.rhs(float(t), np.ascontiguousarray(y, dtype=np.float64), dydt, bm.p, bm.walk,
              bm.faults, self.g, self.te, K.kinematics_scratch(bm.scene.bearing.n_elements),
              np.empty(8), np.empty(8))
        return dydt


def build_gearbox(scene: Scene, params: SR5Parameters | None = None) -> GearboxModel:
    """Bind a scene with gears to the gearbox kernels (static initial state included).

    Parameters
    ----------
    scene : Scene
        Must have ``gears``.
    params : SR5Parameters, optional
        The bearing-pedestal parameters (the pinion's mass is added to the shaft's).

    Returns
    -------
    GearboxModel
    """
    pair = scene.gears
    if pair is None:
        raise ValueError("scene.gears is None: the gearbox model needs a GearPair")
    params = params or SR5Parameters()
    (m_p, m_g), (i_p, i_g) = pair.masses, pair.inertias
    rbp, rbg = pair.base_radius_m
    n0 = pair.mean_mesh_force
    # static equilibrium of the bearing under the radial load and the mean mesh force,
    # which act along the same line; the kernel then applies the mesh force itself
    loaded = scene.replace(radial_load_n=scene.radial_load_n + n0)
    bm = build_model(loaded, replace(params, shaft_mass=params.shaft_mass + m_p),
                     resonator=False)
    bm.p[K.P_FR] = scene.radial_load_n

    g = np.zeros(G.N_GPARAMS)
    g[G.G_EPS_A] = pair.contact_ratio
    g[G.G_EPS_B] = pair.overlap_ratio
    g[G.G_ZP], g[G.G_ZG] = pair.teeth
    g[G.G_KM] = pair.mesh_stiffness
    g[G.G_CM] = pair.mesh_damping
    g[G.G_RBP], g[G.G_RBG] = rbp, rbg
    g[G.G_IP], g[G.G_IG] = i_p, i_g
    g[G.G_MG] = m_g
    g[G.G_KG] = pair.support_stiffness_n_per_m
    g[G.G_CG] = pair.support_damping_ns_per_m
    k_t, k_o = pair.drive_stiffness_nm_per_rad, pair.output_stiffness_nm_per_rad
    g[G.G_KT] = k_t
    g[G.G_CT] = 2.0 * DRIVE_DAMPING_RATIO * math.sqrt(k_t * i_p)
    g[G.G_IM] = pair.drive_inertia_kgm2
    g[G.G_KO] = k_o
    g[G.G_CO] = 2.0 * DRIVE_DAMPING_RATIO * math.sqrt(k_o * i_g)
    g[G.G_TP] = pair.torque_nm
    g[G.G_ECCP], g[G.G_ECCG] = (1e-6 * e for e in pair.eccentricity_um)
    if pair.fault is not None:
        g[G.G_FGEAR] = G.FAULT_PINION if pair.fault.gear == "pinion" else G.FAULT_GEAR
        g[G.G_FTOOTH] = pair.fault.tooth
        g[G.G_FLOSS] = pair.fault.stiffness_loss
    te = np.zeros((max(len(pair.transmission_error_um), 0), 2))
    te[:, 0] = 1e-6 * np.asarray(pair.transmission_error_um, dtype=float)

    # static state: input shaft pre-twisted by T_p / k_t, gear shaft deflected by
    # -N0/k_g, mesh compressed so that k(0) delta + c_m delta' = N0 with the wheels at
    # rest at th_p = th_g = 0 (delta_0 sets the angular references)
    y0 = np.zeros(G.N_STATE)
    y0[:4] = bm.y0[:4]
    k0 = G.mesh_stiffness(0.0, g)
    e0, de0 = G.transmission_error(0.0, bm.p[K.P_W0], g, te)
    y0[5] = -n0 / g[G.G_KG]
    y0[7] = pair.torque_nm / k_t
    g[G.G_D0] = (n0 + g[G.G_CM] * de0) / k0 + (y0[0] - y0[5]) + e0

    k_max = pair.mesh_stiffness * (math.floor(pair.contact_ratio) + 1) / pair.contact_ratio
    w_c = float(bm.scale[4] / bm.scale[0])  # bearing contact mode (sr4 scales)
    m_s = bm.p[K.P_MS]
    omega = max(w_c, math.sqrt(k_max / pair.equivalent_mass),
                math.sqrt(w_c**2 + (k_max + params.shaft_stiffness) / m_s),
                math.sqrt((k_max + pair.support_stiffness_n_per_m) / m_g),
                math.sqrt(k_t / i_p), math.sqrt(k_o / i_g))
    return GearboxModel(bearing=bm, g=g, te=te, y0=y0, omega_max=omega)


def _resonator(housing: np.ndarray, h: float, w: float, zeta: float) -> np.ndarray:
    """Absolute acceleration of Sawalhi & Randall's sprung mass base-excited by the
    housing acceleration (n, n_sensors), m/s^2: H(s) = (2 zeta w s + w^2) /
    (s^2 + 2 zeta w s + w^2), discretised exactly for a piecewise-linear input
    (first-order hold), started at rest under the first sample."""
    num = [2.0 * zeta * w, w * w]
    den = [1.0, 2.0 * zeta * w, w * w]
    b, a, _ = _signal.cont2discrete((num, den), h, method="foh")
    b = np.atleast_1d(np.squeeze(b))
    zi = _signal.lfilter_zi(b, a)
    return np.stack([_signal.lfilter(b, a, housing[:, i], zi=zi * housing[0, i])[0]
                     for i in range(housing.shape[1])], axis=1)


def _fault_entries(pair: GearPair, mesh_phase: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Times (s) at which the faulty tooth's first face slice enters mesh: mesh phase
    u = tooth - eps_beta + k z (z: teeth of the faulty wheel)."""
    if pair.fault is None:
        return np.empty(0)
    z = pair.teeth[0] if pair.fault.gear == "pinion" else pair.teeth[1]
    first = pair.fault.tooth - pair.overlap_ratio
    ks = np.arange(math.ceil((mesh_phase[0] - first) / z),
                   math.floor((mesh_phase[-1] - first) / z) + 1)
    return np.interp(first + ks * z, mesh_phase, t)


def _run(scene: Scene, solver: str, *, dt=None, rtol=None, atol=None,
         params: SR5Parameters | None = None, return_forces: bool = False,
         oversample: int = OVERSAMPLE) -> SimulationResult:
    """Simulate a scene with gears (arguments validated by :func:`simulate`)."""
    if params is not None and not isinstance(params, SR5Parameters):
        raise TypeError(f"params must be SR5Parameters for the gearbox model, got "
                        f"{type(params).__name__}")
    t_wall = time.perf_counter()
    gm = build_gearbox(scene, params)
    bm = gm.bearing
    n_samples = scene.n_samples
    n_out = n_samples * oversample
    h_out = 1.0 / (scene.fs * oversample)
    dt_req = dt if dt is not None else DT_DEFAULT_OMEGA / gm.omega_max
    n_sub, step = divisor_step(h_out, dt_req, dt)
    bound = np.full(G.N_STATE, 1e4 * float(np.max(np.abs(gm.y0[:4]))) + 1e-3)
    bound[[4, 6, 7, 12, 14, 15]] = 1e6  # angles (rad) and angular rates (rad/s)
    bound[8:12] = 1e4 * float(bm.scale[4]) + 1.0
    bound[13] = bound[8]
    n_sensors = len(scene.sensors)
    out = np.empty((n_out, n_sensors))
    forces = np.empty((n_out, 3))
    states = np.empty((n_out if return_forces else 0, G.N_STATE))
    status, t_fail = G.rk4(gm.y0, bm.p, bm.walk, bm.faults, bm.sensors, gm.g, gm.te, h_out,
                           n_sub, n_out, bound, out, forces, states)
    if status != 0:
        raise SimulationUnstableError(
            f"gearbox simulation (rk4, dt = {step:.3g} s) diverged at t = {t_fail:.6g} s: the "
            f"state became non-finite or unbounded. Try a smaller dt. Scene: {scene!r}")
    sensor = _resonator(out, h_out, 2.0 * math.pi * scene.resonance_hz, scene.resonance_damping)
    sensor = add_modes(scene, sensor, 1.0 / h_out)
    accel = add_noise(scene, to_output_rate(sensor, n_samples, oversample))
    check_finite(scene, accel, "gearbox")

    t = np.arange(n_samples) / scene.fs
    idx = np.arange(n_samples) * oversample
    pair = scene.gears
    shaft_angle = scene.speed.shaft_angle(t, scene.duration_s)
    t_fine = np.arange(n_out) * h_out
    mesh_phase = pair.teeth[0] * scene.speed.shaft_angle(t_fine, scene.duration_s) / (2 * math.pi)
    gear_truth = GearTruth(
        pair=pair, label=pair.fault.kind if pair.fault else "healthy",
        mesh_frequency_hz=pair.mesh_frequency(scene.shaft_hz), pinion_hz=scene.shaft_hz,
        gear_hz=pair.gear_shaft_hz(scene.shaft_hz),
        gear_shaft_angle=shaft_angle * pair.teeth[0] / pair.teeth[1],
        mesh_force=forces[idx, 0].copy(), mesh_stiffness=forces[idx, 1].copy(),
        transmission_error=forces[idx, 2].copy(),
        fault_entries_s=_fault_entries(pair, mesh_phase, t_fine),
    )
    ev_before, _after, ev_fault, ev_elem, ev_level = _events(bm, (n_out - 1) * h_out)
    contact = angles = displacement = None
    if return_forces:
        contact = K.contact_loads_many(t, states[idx], bm.p, bm.walk, bm.faults).T.copy()
        angles = K.element_angles_many(t, bm.p, bm.walk, scene.bearing.n_elements).T.copy()
        displacement = states[idx][:, :4].T.copy()
    truth = GroundTruth(
        label=scene.label, faults=scene.faults, frequencies=scene.frequencies,
        shaft_angle=shaft_angle, rpm=scene.speed.rpm_at(t, scene.duration_s) * np.ones_like(t),
        fault_crossings=FaultCrossings(time_s=ev_before.copy(), fault=ev_fault,
                                       element=ev_elem,
                                       edge=_edge_names(bm, ev_fault, ev_level)),
        effective_depth_mm=effective_depths_mm(scene),
        contact_forces=contact, element_angles=angles, displacement=displacement,
        gear=gear_truth,
    )
    info = {"solver": solver, "dt_s": step, "n_steps": int((n_out - 1) * n_sub),
            "n_rejected": 0, "internal_fs": 1.0 / h_out,
            "wall_time_s": time.perf_counter() - t_wall}
    return SimulationResult.of_scene(scene, accel, t, truth, info)


def _accepts(scene: Scene) -> str | None:
    """The gearbox model needs a gear pair on the scene."""
    if scene.gears is None:
        return "the scene has no gear pair (Scene(gears=...))"
    return None


#: Tran, Furch & Cu's gear pair on the sr5 bearing-pedestal model
GEARBOX = Model(
    name="gearbox",
    description="gear pair (pinion on the bearing's shaft, gear on an elastic shaft; "
                "torsional and lateral DOF, time-varying mesh stiffness, transmission "
                "error, tooth faults) coupled to the sr5 bearing-pedestal model",
    # the bearing is sr5's (clearance, pits, intermittent defects through its fault
    # table) and the further structural modes follow its resonator as in sr5
    represents=SR5.represents | {"gear_mesh"},
    # side by side with sr5 on the same 6208 scene without gears (1 s at 48 kHz, inner
    # fault, Tran, Furch & Cu helical pair): 16x after sr5's mass change (10x before, and 3x with
    # the seed's spall: docs/seed004.md)
    relative_cost=16.0,
    solvers=("rk4",),
    fixed_step_solvers=("rk4",),
    reference="C. V. Tran, J. Furch, X. P. Cu, 'Simulation of vibration propagated by rolling "
              "element bearings in mechanical gearbox' (Tran, Furch & Cu), eqs. 1-16; N. Sawalhi, "
              "R. B. Randall, MSSP 22 (2008) 1924-1951",
    accepts=_accepts,
    run=_run,
)
