"""The ``impulse`` model: fault impacts ringing the structure, without contact dynamics.

The phenomenological bearing-fault model of McFadden & Smith (1984) and Ho & Randall
(2000), in the form of the simulators of D'Elia, Cocconcelli et al. and Buzzoni et al.:
every time a rolling element meets a defect, the housing receives a force impulse that
rings the structural resonance; the train of impulses follows the kinematics with
random slip and is amplitude-modulated by the load zone and the transmission path.
It represents the envelope-level signature (``envelope``, ``varying_speed``) at a
fraction of sr5's cost; it has no contact dynamics (no varying compliance, no shaft
response, no contact forces as output).

The impulse model
-----------------
*Impact times.* The same kinematics and the same slip process as sr5, drawn from the
same seed: the cage angle with its random walk (:func:`.sr5._slip_walk`,
:func:`._kernels.cage_angle`) and the fault-edge crossings of every element path
(:func:`._sr5_driver._events`), so the defect entries and exits in
``res.truth.fault_crossings`` of an impulse run are those of an sr5 run of the same
scene (sr5 also lists the ends of its edge ramps), their times within 1e-13 s: sr5
brackets each to adjacent floating-point numbers to split its steps there, an impact
only needs its time; the impacts are the ``exit`` crossings. Impacts are placed in
the angle domain (cage and shaft angles) and mapped to time through the speed profile,
so a run-up keeps them at their kinematic orders; the resonance rings in time, at a fixed frequency.

*Force released by an element crossing a defect.* An element at angle psi carries the
quasi-static Stribeck load of :meth:`ballpass.Bearing.load_distribution` (shaft
displacement x, y under F_r plus the shaft weight), with contact deflection
delta(psi) = (x cos psi + y sin psi - c) cos(alpha) and load Q = K delta^n. Entering a
defect of effective depth h (the drop of the mating surfaces over its width,
:meth:`ballpass.Fault.effective_depth_mm`; a ball defect's against the race it strikes,
deeper on the inner race than on the outer) its deflection falls to delta - h, so the
force released is

    dQ(psi) = K max(delta, 0)^n - K max(delta - h, 0)^n,

all of Q for a defect deeper than the deflection, and nothing outside the load zone.
Outer-race faults sit at a fixed psi; inner-race and ball faults meet the races at the
angle of the element they strike, so they rotate through the load zone (the
modulation at the shaft rate and the cage rate of McFadden & Smith 1984).

*Path to each sensor.* As in sr5 (:func:`._kernels.housing_accel`): the released
force acts on the housing mass m_h along the contact normal and reaches sensor i with
the transmission factor w = exp(-kappa (1 - cos(psi - theta_i))) (after McFadden &
Smith 1984) and the projection cos(psi - theta_i) on the sensor axis, a step of
housing acceleration a = w cos(psi - theta_i) dQ / m_h (m/s^2).

*Resonance.* The sensor's resonator (``Scene.resonance_hz``, ``resonance_damping``,
sr5's "sprung mass") turns each step of base acceleration into a ring; its absolute
acceleration rings as -a e^(-sigma tau) (cos w_d tau - sigma / w_d sin w_d tau), the
part of the exact step response above the base motion, with sigma = zeta w_n and
w_d = w_n sqrt(1 - zeta^2). One impact per passage, as in McFadden & Smith's and Ho &
Randall's trains: where the element leaves the defect and strikes its trailing edge,
taking its load back (the ``exit`` crossing of the ground truth). The gradual
unloading at the entry, and with it the interference of entry and exit, belongs to
``contact_dynamics`` (sr5): an entry ring of the opposite sign cancels the exit ring
whenever the passage lasts a whole number of resonance periods, which sr5 does not
show (benchmarks/models_agreement.py). The rings are summed exactly at the output
samples, each starting at its own sub-sample time, by one second-order recursion per
sensor: no oversampling, no decimation.

What it does not represent, stated: the quasi-static housing motion itself (the
element-pass rate of varying compliance, the force steps below the resonance), the
entry into the defect and the edge profile (ramped, sharp) beyond the exit time, the
dynamic overshoot and speed dependence of the impact (its rings are 0.2-0.4 of sr5's
RMS on the agreement scenes), and everything else of ``contact_dynamics``. A healthy
bearing is silent.

References: P. D. McFadden, J. D. Smith, "Model for the vibration produced by a single
point defect in a rolling element bearing", J. Sound Vib. 96 (1984) 69-82; D. Ho,
R. B. Randall, "Optimisation of bearing diagnostic techniques using simulated and
actual bearing fault signals", MSSP 14 (2000) 763-788; the phenomenological
bearing-signal simulators of D'Elia, Cocconcelli, Buzzoni et al. (as cited in the
literature; none of their papers was at hand to check details against).
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np
from numba import njit

from .._validation import check_number
from ..bearing import LoadDistribution
from ..scene import STANDARD_GRAVITY, Scene
from . import _kernels as K
from ._registry import Model
from ._shared import OVERSAMPLE, add_noise, check_finite, stiffness_and_load_zone
from ._sr5_driver import _edge_names, _events
from .result import Deferred, FaultCrossings, GroundTruth, SimulationResult, sample_times
from .sr5 import SR5Parameters, _check_elastic, build_model

__all__ = ["ImpulseParameters", "IMPULSE", "impact_amplitudes"]


@dataclass(frozen=True)
class ImpulseParameters:
    """Parameters of the impulse model (SI units), all overridable.

    Parameters
    ----------
    housing_mass : float
        m_h, the mass that turns a released contact force into housing acceleration,
        kg. Default: sr5's pedestal mass (:class:`SR5Parameters`), so the two models
        put the same acceleration step on the sensor for the same force.
    shaft_mass : float
        Shaft and inner ring, kg, whose weight the bearing carries with ``F_r`` when
        ``Scene.gravity``. Default: sr5's shaft mass.
    contact_stiffness : float or None
        Hertz load-deflection constant K of one element, N/m^n; None takes
        :meth:`ballpass.Bearing.hertz_stiffness`, as sr5 does.

    Examples
    --------
    >>> import ballpass as bp
    >>> scene = bp.Scene(bearing="6205", fault=bp.Fault("outer"), duration_s=0.05,
    ...                  needs=("envelope",))
    >>> light = bp.simulate(scene, params=bp.simulate.ImpulseParameters(housing_mass=3.0))
    >>> heavy = bp.simulate(scene)                       # sr5's 6.64 kg pedestal
    >>> round(float(abs(light.accel).max() / abs(heavy.accel).max()), 6)
    2.213333
    """

    housing_mass: float = SR5Parameters.pedestal_mass
    shaft_mass: float = SR5Parameters.shaft_mass
    contact_stiffness: float | None = None

    def __post_init__(self) -> None:
        check_number("housing_mass", self.housing_mass, 0.0, lo_open=True, unit="kg")
        check_number("shaft_mass", self.shaft_mass, 0.0, unit="kg")
        if self.contact_stiffness is not None:
            check_number("contact_stiffness", self.contact_stiffness, 0.0, lo_open=True)


#: the default parameters, validated once
_DEFAULTS = ImpulseParameters()


@functools.lru_cache(maxsize=64)
def _sr5_parameters(shaft_mass: float, stiffness: float) -> SR5Parameters:
    """sr5's parameters with this shaft mass and contact stiffness, validated once per
    process (frozen, so shared between runs)."""
    return SR5Parameters(shaft_mass=shaft_mass, contact_stiffness=stiffness)


def impact_amplitudes(scene: Scene, psi: np.ndarray, depth_m: np.ndarray,
                      params: ImpulseParameters | None = None) -> np.ndarray:
    """Force released by an element at angle ``psi`` dropping into a defect, N.

    dQ = K max(delta, 0)^n - K max(delta - h, 0)^n with the quasi-static Stribeck
    deflection delta(psi) of :meth:`ballpass.Bearing.load_distribution` under the
    scene's radial load (plus the shaft weight with ``gravity``) and h the effective
    defect depth (see the module docstring).

    Parameters
    ----------
    scene : Scene
    psi : ndarray
        Element angles from the load line, rad.
    depth_m : ndarray
        Effective defect depth for each angle (broadcast with ``psi``), m.
    params : ImpulseParameters, optional

    Returns
    -------
    ndarray
        dQ, N, >= 0; exactly 0 outside the load zone.

    Examples
    --------
    >>> import numpy as np, ballpass as bp
    >>> from ballpass.simulate.impulse import impact_amplitudes
    >>> scene = bp.Scene(bearing="6205", radial_load_n=500.0, gravity=False)
    >>> dq = impact_amplitudes(scene, np.radians([0.0, 60.0, 180.0]), np.full(3, 1e-3))
    >>> bool(dq[0] > dq[1] > 0.0), float(dq[2])   # deep defect: the whole load, 0 opposite
    (True, 0.0)
    """
    kh, load_zone = _load_zone(scene, params or _DEFAULTS)
    psi, depth_m = np.broadcast_arrays(np.asarray(psi, dtype=np.float64),
                                       np.asarray(depth_m, dtype=np.float64))
    out = np.empty(psi.shape)
    _released_many(psi.ravel(), depth_m.ravel(), _zone(scene, load_zone, kh), out.reshape(-1))
    return out


def _load_zone(scene: Scene, params: ImpulseParameters) -> tuple[float, LoadDistribution]:
    """K and the Stribeck equilibrium under the scene's radial load (plus the shaft
    weight with ``gravity``), refused beyond the elastic limit sr5 refuses (its largest
    contact deflection above 1 % of the element diameter)."""
    load = scene.radial_load_n + (params.shaft_mass * STANDARD_GRAVITY if scene.gravity else 0.0)
    b = scene.bearing
    kh, ld = stiffness_and_load_zone(b, load, params.contact_stiffness)
    _check_elastic(scene, (ld.deflection_m - b.radial_clearance_m) * math.cos(b.contact_angle_rad),
                   load)
    return kh, ld


def _zone(scene: Scene, ld: LoadDistribution, kh: float) -> np.ndarray:
    """The load zone as :func:`_released` reads it: shaft displacement x, y (m), radial
    clearance (m), cos(contact angle), K (N/m^n) and n."""
    b = scene.bearing
    return np.array([ld.deflection_m, ld.lateral_deflection_m, b.radial_clearance_m,
                     math.cos(b.contact_angle_rad), kh, b.load_exponent])


@njit(cache=True, error_model="numpy")
def _released(psi, depth, zone):
    """dQ of :func:`impact_amplitudes` at element angle ``psi`` (rad) for a defect of
    depth ``depth`` (m) on the load zone ``zone`` (:func:`_zone`), N."""
    delta = (zone[0] * math.cos(psi) + zone[1] * math.sin(psi) - zone[2]) * zone[3]
    return zone[4] * (max(delta, 0.0) ** zone[5] - max(delta - depth, 0.0) ** zone[5])


@njit(cache=True, error_model="numpy")
def _released_many(psi, depth, zone, out):
    """:func:`_released` at every angle of ``psi`` (1-D), into ``out``."""
    for k in range(psi.shape[0]):
        out[k] = _released(psi[k], depth[k], zone)


@njit(cache=True, error_model="numpy")
def _impact_steps(before, fault, elem, level, exit_level, faults, p, walk, depth, zone,
                  sensors, housing_mass):
    """Impact times and housing acceleration steps from the crossings (see
    :func:`_impacts`): the crossings whose level is their fault's ``exit_level``, the
    angle of the element that meets the defect there (for a ball defect its carrier,
    column F_ELEM; for a race defect the element of the path), the force it releases
    (:func:`_released`, defect depth ``depth[fault, face]``: a ball defect's face 0
    strikes the outer race, face 1 the inner; a race defect's column 0) and its step at
    each sensor, w cos(psi - theta) dQ / m_h with w = exp(-kappa (1 - cos(psi - theta)))."""
    n = 0
    for c in range(before.shape[0]):
        if level[c] == exit_level[fault[c]]:
            n += 1
    times = np.empty(n)
    steps = np.empty((sensors.shape[0], n))
    step = K.TWO_PI / p[K.P_Z]
    k = 0
    for c in range(before.shape[0]):
        i = fault[c]
        if level[c] != exit_level[i]:
            continue
        ball = int(faults[i, K.F_KIND]) == K.KIND_BALL
        j = int(faults[i, K.F_ELEM]) if ball else elem[c]
        # element j's angle as K.element_angles puts it, without the other elements
        psi = K.cage_angle(before[c], p, walk)[0] + step * j
        share = 1.0
        h = depth[i, 0]
        if ball:
            # the revolution's strike, as sr5's fault depths take it, on the race the
            # path's face meets
            share = K.strike_share(faults, i, faults[i, K.F_CENTRE]
                                   + p[K.P_SPIN] * (psi - faults[i, K.F_PSI0]), elem[c])
            h = depth[i, elem[c]]
        dq = _released(psi, share * h, zone) / housing_mass
        for s in range(sensors.shape[0]):
            cos_rel = math.cos(psi - sensors[s, K.S_ANG])
            steps[s, k] = math.exp(-sensors[s, K.S_ATT] * (1.0 - cos_rel)) * cos_rel * dq
        times[k] = before[c]
        k += 1
    return times, steps


def _ring(times: np.ndarray, steps: np.ndarray, n_samples: int, fs: float, f_n: float,
          zeta: float) -> tuple[np.ndarray, np.ndarray]:
    """Sum of resonator rings at the output samples, AC-coupled, (n_sensors, n_samples),
    m/s^2, and the mean taken off each sensor (n_sensors, 1), m/s^2.

    Step k of base acceleration ``steps[:, k]`` (m/s^2) at ``times[k]`` (s, ascending)
    adds -a e^(-sigma tau) (cos w_d tau - sigma/w_d sin w_d tau), tau = t - t_k >= 0.
    With n0 = ceil(t_k fs) and the sub-sample lag f = n0 - t_k fs, the ring at n0 + m
    is D [alpha C_m + beta S_m] with C_m = r^m cos(theta m), S_m = r^m sin(theta m),
    r = e^(-sigma/fs), theta = w_d / fs: the real and imaginary parts of z^m with
    z = r e^(i theta), which :func:`_ring_kernel` sums over the rings exactly (no
    truncation, no resampling). The mean over the record (taken off, as the
    AC-coupled accelerometers of sr5 do) is summed in closed form, a geometric series
    per stretch between starts.
    """
    out = np.empty((steps.shape[0], n_samples))
    mean = np.empty((steps.shape[0], 1))
    _ring_kernel(np.ascontiguousarray(times, dtype=np.float64),
                 np.ascontiguousarray(steps, dtype=np.float64), fs, 2.0 * math.pi * f_n,
                 zeta, out, mean)
    return out, mean


@njit(cache=True, error_model="numpy")
def _ring_weights(times, steps, fs, w_n, zeta, n_out):
    """First sample n0 of each ring that starts before ``n_out`` and its weights alpha,
    beta (n_sensors, n_rings) on C_m and S_m (see :func:`_ring`)."""
    sigma = zeta * w_n
    w_d = w_n * math.sqrt(1.0 - zeta * zeta)
    ratio = sigma / w_d
    m = 0
    while m < times.shape[0] and math.ceil(times[m] * fs) < n_out:
        m += 1
    n0 = np.empty(m, dtype=np.int64)
    alpha = np.empty((steps.shape[0], m))
    beta = np.empty((steps.shape[0], m))
    for k in range(m):
        n0[k] = int(math.ceil(times[k] * fs))
        lag = (n0[k] - times[k] * fs) / fs  # tau at the first sample, s
        decay = math.exp(-sigma * lag)
        cphi, sphi = math.cos(w_d * lag), math.sin(w_d * lag)
        # e^(-s tau)(cos w_d tau - ratio sin w_d tau) at tau = lag + m/fs, on C_m, S_m
        for i in range(steps.shape[0]):
            alpha[i, k] = -steps[i, k] * decay * (cphi - ratio * sphi)
            beta[i, k] = steps[i, k] * decay * (sphi + ratio * cphi)
    return n0, alpha, beta, math.exp(-sigma / fs), w_d / fs


@njit(cache=True, error_model="numpy")
def _powers(r, theta, span):
    """Real and imaginary parts of z^0 .. z^span, z = r e^(i theta): z^j directly for
    j below :data:`_BLOCK`, beyond it z^(q + b) = z^q z^b with z^q, q a multiple of
    _BLOCK, directly (one rounded product: within two units in the last place of the
    direct value, at a 1/_BLOCK of its cost in pow, cos and sin)."""
    pr = np.empty(span + 1)
    pi = np.empty(span + 1)
    for j in range(min(span + 1, _BLOCK)):
        mag = r ** j
        pr[j] = mag * math.cos(theta * j)
        pi[j] = mag * math.sin(theta * j)
    for q in range(_BLOCK, span + 1, _BLOCK):
        mag = r ** q
        qr, qi = mag * math.cos(theta * q), mag * math.sin(theta * q)
        for b in range(min(_BLOCK, span + 1 - q)):
            pr[q + b] = qr * pr[b] - qi * pi[b]
            pi[q + b] = qr * pi[b] + qi * pr[b]
    return pr, pi


@njit(cache=True, error_model="numpy")
def _sweep(n0, alpha, beta, pr, pi, row, shift, write):
    """One sensor's rings (weights ``alpha``, ``beta`` of :func:`_ring_weights`) over
    the record: with ``write``, ``row[n]`` = their sum at sample n minus ``shift``.
    Returns the sum over every sample of the record (before the shift).

    Each stretch of ``gap`` samples from amplitude A sums to
    Re(A (1 - z^gap) / (1 - z)); the stretches' A (1 - z^gap) are summed and divided once.
    """
    n_out = row.shape[0]
    m = n0.shape[0]
    span = pr.shape[0] - 1
    if write:
        row[:n_out if m == 0 else n0[0]] = -shift
    ar = ai = cr = ci = 0.0
    k = 0
    while k < m:
        s = n0[k]
        while k < m and n0[k] == s:  # rings starting on the same sample
            ar += alpha[k]
            ai -= beta[k]
            k += 1
        end = n0[k] if k < m else n_out
        while s < end:  # Re(A z^j) up to the next start, A carried by z^gap
            gap = min(end - s, span)
            if write:
                for j in range(gap):
                    row[s + j] = ar * pr[j] - ai * pi[j] - shift
            nr, ni = ar * pr[gap] - ai * pi[gap], ar * pi[gap] + ai * pr[gap]
            cr += ar - nr
            ci += ai - ni
            ar, ai = nr, ni
            s += gap
    dr, di = 1.0 - pr[1], -pi[1]  # 1 - z; Re(C / d) = Re(C conj(d)) / |d|^2
    return (cr * dr + ci * di) / (dr * dr + di * di)


@njit(cache=True, error_model="numpy")
def _ring_kernel(times, steps, fs, w_n, zeta, out, mean):
    """Evaluate the rings of :func:`_ring` at the output samples into ``out``
    (n_sensors, n_samples), less their mean over the record, written into ``mean``
    (n_sensors, 1).

    With z = r e^(i theta) and the weights of :func:`_ring_weights`, the rings started
    at or before sample n sum to Re(A z^(n - s)), where s is the latest start and the
    complex amplitude A = sum_k (alpha_k - i beta_k) z^(s - n0_k) is carried from start
    to start; between starts every sample is one product with a tabulated power z^m,
    independent of its neighbours (no recursion through the samples, so the loop
    vectorises). A first sweep without writing sums the record (:func:`_sweep`), the
    second writes it with the mean taken off.
    """
    n_out = out.shape[1]
    n0, alpha, beta, r, theta = _ring_weights(times, steps, fs, w_n, zeta, n_out)
    m = n0.shape[0]
    # powers z^0 .. z^span, span the longest stretch without a new ring (capped: longer
    # stretches advance by z^span per block; at least 1, for 1 - z)
    span = n_out if m == 0 else max(n0[0], n_out - n0[m - 1])
    for k in range(1, m):
        span = max(span, n0[k] - n0[k - 1])
    pr, pi = _powers(r, theta, max(1, min(span, _SPAN)))
    for i in range(out.shape[0]):
        mean[i, 0] = _sweep(n0, alpha[i], beta[i], pr, pi, out[i], 0.0, False) / n_out
        _sweep(n0, alpha[i], beta[i], pr, pi, out[i], mean[i, 0], True)


#: most powers of z :func:`_ring_kernel` tabulates (a longer stretch without a new ring
#: advances block by block)
_SPAN = 4096
#: powers of z :func:`_powers` computes directly before it multiplies blocks
_BLOCK = 32


def _run(scene: Scene, solver: str, *, dt=None, rtol=None, atol=None, params=None,
         return_forces: bool = False, oversample: int = OVERSAMPLE) -> SimulationResult:
    """Simulate ``scene`` with the impulse model (see the module docstring)."""
    # refuse, before any work, what this model would otherwise silently ignore
    if params is not None and not isinstance(params, ImpulseParameters):
        raise TypeError(f"params must be ImpulseParameters for the impulse model, got "
                        f"{type(params).__name__}")
    for name, value in (("dt", dt), ("rtol", rtol), ("atol", atol)):
        if value is not None:
            raise ValueError(f"{name}={value!r}: the impulse model has no integrator (its "
                             "rings are summed exactly at the output samples); leave it unset")
    if oversample != OVERSAMPLE:
        raise ValueError(f"oversample={oversample!r}: the impulse model computes the output "
                         "samples exactly, without an internal grid; leave it at its default")
    if return_forces:
        raise ValueError("return_forces=True: the impulse model does not represent "
                         "contact_forces; use model='sr5' (or model='auto')")
    t_wall = time.perf_counter()
    t_hit, steps, (before, fault, elem, edges) = _impacts(scene, params)
    n_samples = scene.n_samples
    # AC-coupled accelerometers, as sr5: the mean over the record taken off
    accel, mean = _ring(t_hit, steps, n_samples, scene.fs, scene.resonance_hz,
                        scene.resonance_damping)
    # the mean is finite only if every ring's amplitude is, and so every sample: it
    # checks the signal without another pass over it
    check_finite(scene, mean, "impulse")
    accel = add_noise(scene, accel)

    # the sample times (and from them the tachometer and the speed) on first read
    t = Deferred(sample_times, n_samples, scene.fs)
    truth = GroundTruth.of_scene(
        scene, t, FaultCrossings(time_s=before, fault=fault, element=elem, edge=edges))
    info = {"solver": solver, "n_impacts": int(t_hit.size), "n_events": int(before.size),
            "wall_time_s": time.perf_counter() - t_wall}
    return SimulationResult.of_scene(scene, accel, t, truth, info)


def _impacts(scene: Scene, params: ImpulseParameters | None = None):
    """The impacts of ``scene``: when, and the housing acceleration step each gives each
    sensor, before any resonator (see the module docstring).

    Returns
    -------
    times : ndarray, shape (n_impacts,)
        Impact times (the ``exit`` crossings), s, ascending.
    steps : ndarray, shape (n_sensors, n_impacts)
        Step of housing acceleration at each sensor, m/s^2.
    crossings : tuple of ndarray
        Time, fault, element and edge name (a :class:`.result.Deferred`) of every defect
        crossing (the ground truth's ``fault_crossings``).
    """
    params = params or _DEFAULTS
    # K, for the kinematics and the loads; refuses a load beyond the elastic limit
    kh, load_zone = _load_zone(scene, params)
    # the sr5 kinematics of this scene: parameter vector, slip walk and fault table from
    # the scene's own seed (the sr4 binding without its static equilibrium: no state is
    # integrated)
    bm = build_model(scene, _sr5_parameters(params.shaft_mass, kh), resonator=False,
                     equilibrium=False)
    n_samples = scene.n_samples
    # sr5's event horizon (the end of its internal grid), so both list the same entries
    # and exits; the ends of the edge ramps (columns 1, 2 of the levels) are sr5's
    # business, not this model's: NaN levels are skipped by the crossing search. An
    # impact needs its time, not sr5's bracket to adjacent floating-point numbers:
    # found to 1e-13 s (the ring's phase at 15 kHz moves by 1e-8 rad in that time)
    t_end = (n_samples * OVERSAMPLE - 1) / (scene.fs * OVERSAMPLE)
    bm.levels[:, 1:3] = np.nan
    before, _after, fault, elem, level = _events(bm, t_end, exact=False)
    # one impact per passage, where the element strikes the defect's trailing edge and
    # takes its load again (the entry, a gradual unloading, belongs to contact_dynamics):
    # the last level a path crosses, the first for an inner-race defect (its paths run
    # backwards through it, see _edge_names)
    inner = np.array([f.kind == "inner" for f in scene.faults], dtype=bool)
    # the depth of each fault's strikes, sr5's (its fault table, localized faults first):
    # a race fault's against its race, a ball defect's against the outer race (face 0)
    # and the inner race (face 1); a round pit's the shallower depth that unloads a
    # contact as the pit does (sr5._pit_depth_m)
    depth = np.ascontiguousarray(bm.faults[:len(scene.faults)][:, [K.F_DEPTH, K.F_DEPTH_IN]])
    t_hit, steps = _impact_steps(before, fault, elem, level, np.where(inner, 0, 3),
                                 bm.faults, bm.p, bm.walk, depth, _zone(scene, load_zone, kh),
                                 bm.sensors, params.housing_mass)
    return t_hit, steps, (before, fault, elem, Deferred(_edge_names, bm, fault, level))


def _accepts(scene: Scene) -> str | None:
    """The impulse model takes every scene but a healthy one with ``snr_db``: its healthy
    bearing is silent, and noise relative to a silent signal is undefined."""
    if not scene.faults and scene.snr_db is not None:
        return ("has no signal for a healthy bearing (no varying compliance), so snr_db "
                "has no reference: give noise_rms instead")
    return None


#: McFadden-Smith / Ho-Randall impulse trains, registered in ballpass.simulate.MODELS
IMPULSE = Model(
    name="impulse",
    description="phenomenological impulse train: impacts at the kinematic rates with sr5's "
                "slip, Stribeck load-zone and transmission modulation, ringing the "
                "scene's resonance; no contact dynamics",
    represents=frozenset({"envelope", "varying_speed", "intermittent_faults"}),
    # measured by benchmarks/models_cost.py (docs/models_cost.md), 15 interleaved rounds
    # of 3 back-to-back calls: 0.0196 of sr5's time at 48 kHz (IQR 0.018-0.021, CPU time
    # alike; 0.37 ms per call) and 0.017 at 12 kHz, after its fixed cost was cut (binding
    # only the kinematics, the crossings in one compiled call, the mean taken off in
    # closed form, the sample times, tachometer and speed computed on first read):
    # 0.044 and 0.024 before
    relative_cost=0.02,
    solvers=("analytic",),
    fixed_step_solvers=(),
    reference="P. D. McFadden, J. D. Smith, J. Sound Vib. 96 (1984) 69-82; D. Ho, R. B. "
              "Randall, MSSP 14 (2000) 763-788; the phenomenological simulators of "
              "D'Elia, Cocconcelli, Buzzoni et al. (see ballpass.simulate.impulse)",
    accepts=_accepts,
    run=_run,
)
