"""Numba integrators for the bearing models: fixed-step RK4 and adaptive
Dormand-Prince 5(4) on the nonlinear core, exact propagation of the sensor resonators.

Splitting. The sr5 resonators are linear, time-invariant and one-way coupled: the
housing excites them, they do not act back. Only the 4-DOF core (shaft and pedestal
with Hertz contacts, state layout ``yc`` of :mod:`._kernels`) goes through the
Runge-Kutta method, at the step its own dynamics (contact modes of a few kHz) and the
fault events need; the 15 kHz resonators no longer bound the step. Over each core step
[t0, t1] the excitation s''(t) of every resonator is the cubic Hermite interpolant of
its values and exact time derivatives at t0 and t1 (4th order, like the core method),
and the resonator z'' + 2 zeta w z' + w^2 z = -s''(t) is advanced exactly for that
cubic input: x(t + tau) = Phi(tau) x(t) + sum_m c_m g_m(tau), with Phi the matrix
exponential and g_m the exact integrals against s^m (:func:`lti_propagator`).
This is an exponential integrator of the whole sr5 system: the full-state equations of
``BearingModel.rhs`` and the integrated ones are the same; only their discretisation
differs.

Both integrators

* never step across an event: a step that would cross one is shortened to end just
  before it (``ev_before``), and integration resumes just after it (``ev_after``),
  with the right-hand side re-evaluated there. Events are the fault edges and ramp
  ends and the knots of the slip random walk (where the cage speed jumps), all known
  functions of time (rigid kinematics), so every such non-smooth point of the
  right-hand side falls on a step boundary and the methods keep their order through
  them. The one that depends on the state, a contact opening or closing (the Hertz
  law's kink at zero deflection), is caught by rk4 from the loaded contacts at its
  stages: such a step is redone from grid point to grid point (dopri5's error control
  shrinks its steps there);
* on the ramps of a defect, where the excitation follows the depth profile rather
  than the core, sample the resonator input up to ``REFINE_PIECES`` times per step
  (rk4 also limits its step to h_out on short ramps that end in impacts; dopri5
  controls the input error), see :data:`RAMP_PIECES`;
* record the sensor output on a uniform internal grid ``k * h_out``, independent of the
  step: the resonators are propagated exactly from grid point to grid point; the core
  state between steps is the cubic Hermite interpolant of the step's end states and
  derivatives (for sr4 output and for ``states``);
* stop with a status code as soon as the state is not finite or leaves a bound,
  so the caller can raise a clear error (no NaN ever leaves the simulator).

Speed notes (rk4, the default). Between events no element is inside a localized
defect most of the time: the fault depths are then exactly zero and are not
recomputed (:func:`_depths_needed`). The resonators of a step of n whole grid
intervals are advanced with a table of the propagators of 1 .. n intervals
(:func:`_emit_grid`). numba reference-counts the array arguments of a function unless
its refcount-pruning pass can prove the counts balanced, which fails as soon as the
function calls another looping kernel or may raise (hence ``error_model="numpy"``:
no division-by-zero branches). The per-stage kernels are therefore leaves (they call
only loop-free helpers) and the output routines take few arrays: the segment's
vectors are rows of one workspace ``seg`` (rows ``R_*``), the resonator states and
input coefficients one array ``res`` (columns ``X_Z, X_DZ, X_C``), the propagators one
array ``prop``; the common rk4 segment, grid point to grid point, has its own lean
routine (:func:`_emit_grid`).

Status codes: 0 ok, 1 non-finite or unbounded state, 2 step size underflow
(adaptive), 3 too many steps (adaptive), 4 paused after the call's step budget
(resumable: the drivers call again in chunks, so Ctrl-C is not held up by a long run).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._kernels import (
    K_CACHE,
    KC_INSIDE,
    KC_RAMP,
    N_CORE,
    P_WR,
    P_Z,
    P_ZETA,
    contact_loads,
    core_forces,
    element_angles,
    fault_depths,
    housing_accel,
    kinematics_scratch,
)

STATUS_OK, STATUS_NONFINITE, STATUS_UNDERFLOW, STATUS_MAX_STEPS = 0, 1, 2, 3
#: a call that used its step budget and can be resumed (see :func:`rk4`)
STATUS_PAUSED = 4
# integer loop state of rk4 carried between calls (the floats: t, refine_end)
RK4_EV, RK4_N_STEPS, RK4_K_NEXT, RK4_N, RK4_MASK, RK4_DEPTHS, RK4_RAMP = range(7)
N_RK4_IST = 7
# integer loop state of dopri5 (the floats: t, h, h_min_used, err_prev)
DP_K_NEXT, DP_EV, DP_N_ACC, DP_N_REJ, DP_REJECTED = range(5)
N_DP_IST = 5

# Dormand & Prince (1980) RK5(4)7M tableau
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = (
    71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40,
)

# rows of the segment workspace: core state and derivative at both ends and
# interpolated; resonator excitation and rate at both ends, at the current and the
# next refinement point (each excitation row is followed by its rate row, as
# housing_accel writes them)
R_Y0, R_F0, R_Y1, R_F1, R_YI, R_FI = 0, 1, 2, 3, 4, 5
R_A0, R_DA0, R_A1, R_DA1, R_AC, R_DAC, R_AK, R_DAK = 6, 7, 8, 9, 10, 11, 12, 13
N_SEG = 14
# columns of the resonator array: z, z' and the input cubic's coefficients c0..c3
X_Z, X_DZ, X_C = 0, 1, 2
# propagator slots in prop (2, 6, 2): rows 0-1 Phi, rows 2-5 g_0..g_3
PROP_H, PROP_TMP = 0, 1

# step-size controller of dopri5: error exponents (PI control, beta = 0.04)
PI_BETA = 0.04
PI_ALPHA = 0.2 - 0.75 * PI_BETA

#: Defect ramps are resolved more finely than the core needs: the resonator input of a
#: segment on a ramp is interpolated in up to REFINE_PIECES pieces, at least
#: RAMP_PIECES per ramp duration (a cubic Hermite interpolant over a quarter of a
#: segment errs 4^4 = 256 times less); and rk4 steps from grid point to grid point on
#: a ramp it would cross in fewer than RAMP_STEPS steps that ends in an impact (the
#: defect unloads the element completely and it strikes the far edge, stiffening its
#: contact). Measured at 48 kHz: the 0.5 mm outer-race fault at 1797 rpm (57 us ramps,
#: 21 us steps) 1.4e-3 -> 5e-4; a 0.1 mm one at 6000 rpm (3.4 us ramps in single
#: segments) 1e-3 -> 1.5e-4; a 2 mm inner-race fault at 6000 rpm (68 us ramps)
#: 5.6e-3 -> 5e-4 for 20 % more steps; slow ramps (1.4 ms at 300 rpm) are left alone.
REFINE_PIECES = 4
RAMP_PIECES = 16
RAMP_STEPS = 8


@njit(cache=True, error_model="numpy")
def _ramp_pieces(tau, t_ramp):
    """Pieces in which the resonator input of a segment of length tau (s) on a ramp is
    interpolated, given the shortest ramp duration t_ramp (s; inf without ramps)."""
    return min(REFINE_PIECES, max(1, math.ceil(RAMP_PIECES * tau / t_ramp)))


#: a grid point within this fraction of h_out of a segment end belongs to that segment
#: (step ends are computed in floating point; 1e-9 h_out is far below any step)
GRID_TOL = 1e-9


#: below this w tau the propagator comes from its Taylor series (see lti_propagator)
LTI_SERIES_BELOW = 0.1


@njit(cache=True, error_model="numpy")
def lti_propagator(tau, w, zeta, prop, slot):
    """Exact propagator of the resonator x = (z, z') over tau with polynomial input,
    into ``prop[slot]`` (rows 0-1: Phi, rows 2-5: g_0..g_3).

    For z'' + 2 zeta w z' + w^2 z = -u(s), i.e. x' = A x + B u with
    A = [[0, 1], [-w^2, -2 zeta w]], B = (0, -1), and u(s) = sum_m c_m s^m (m <= 3):
    x(tau) = Phi x(0) + sum_m c_m g_m, Phi = exp(A tau) and
    g_m = int_0^tau exp(A (tau - s)) B s^m ds.

    Closed form for the underdamped oscillator (0 < zeta < 1, damped frequency
    w_d = w sqrt(1 - zeta^2)): Phi = e^(-zeta w tau) [[c + zeta w s / w_d, s / w_d],
    [-w^2 s / w_d, c - zeta w s / w_d]] with c, s = cos, sin(w_d tau), and by parts
    g_0 = A^-1 (Phi - I) B, g_m = A^-1 (m g_(m-1) - tau^m B). That recursion loses
    about a factor w tau per level to cancellation (1e-12 of g_3 at w tau = 0.1), so
    below ``LTI_SERIES_BELOW`` the Taylor series
    g_m = m! tau^(m+1) sum_k (A tau)^k B k!/(k+m+1)! is summed instead (< 15 terms).

    Parameters
    ----------
    tau : float
        Interval, s.
    w, zeta : float
        Natural angular frequency (rad/s) and damping ratio in (0, 1).
    prop : ndarray (2, 6, 2)
        Written at ``prop[slot]``.
    slot : int
    """
    if w * tau < LTI_SERIES_BELOW:
        _lti_series(tau, w, zeta, prop, slot)
        return
    wd = w * math.sqrt(1.0 - zeta * zeta)
    e = math.exp(-zeta * w * tau)
    c = math.cos(wd * tau)
    sn = math.sin(wd * tau)
    prop[slot, 0, 0] = e * (c + zeta * w * sn / wd)
    prop[slot, 0, 1] = e * sn / wd
    prop[slot, 1, 0] = -e * w * w * sn / wd
    prop[slot, 1, 1] = e * (c - zeta * w * sn / wd)
    # A^-1 = [[-2 zeta / w, -1 / w^2], [1, 0]]; B = (0, -1)
    b0 = -prop[slot, 0, 1]  # (Phi - I) B
    b1 = 1.0 - prop[slot, 1, 1]
    g0 = -2.0 * zeta / w * b0 - b1 / (w * w)
    g1 = b0
    prop[slot, 2, 0] = g0
    prop[slot, 2, 1] = g1
    tp = 1.0
    for mm in range(1, 4):
        tp *= tau
        b0 = mm * g0  # m g_(m-1) - tau^m B
        b1 = mm * g1 + tp
        g0 = -2.0 * zeta / w * b0 - b1 / (w * w)
        g1 = b0
        prop[slot, 2 + mm, 0] = g0
        prop[slot, 2 + mm, 1] = g1


@njit(cache=True, error_model="numpy")
def _lti_series(tau, w, zeta, prop, slot):
    """:func:`lti_propagator` from the Taylor series of exp(A tau), summed until the
    terms fall below 1e-17 of the leading ones (w tau < 0.1: < 15 terms)."""
    a10 = -w * w * tau
    a11 = -2.0 * zeta * w * tau
    # column 0: u = (A tau)^k e0 / k!; column 1: v = (A tau)^k e1 / k!
    u0, u1 = 1.0, 0.0
    v0, v1 = 0.0, 1.0
    for r in range(6):
        prop[slot, r, 0] = 0.0
        prop[slot, r, 1] = 0.0
    for k in range(200):
        prop[slot, 0, 0] += u0
        prop[slot, 1, 0] += u1
        prop[slot, 0, 1] += v0
        prop[slot, 1, 1] += v1
        # g_m = -tau^(m+1) sum_k v_k m! / ((k+1)...(k+m+1))
        c = 1.0 / (k + 1)
        for mm in range(4):
            prop[slot, 2 + mm, 0] -= c * v0
            prop[slot, 2 + mm, 1] -= c * v1
            c *= (mm + 1.0) / (k + mm + 2.0)
        if k > 2 and abs(u0) + abs(u1) / w + abs(v0) * w + abs(v1) < 1e-17:
            break
        u0, u1 = u1 * tau / (k + 1), (a10 * u0 + a11 * u1) / (k + 1)
        v0, v1 = v1 * tau / (k + 1), (a10 * v0 + a11 * v1) / (k + 1)
    tp = tau
    for mm in range(4):
        prop[slot, 2 + mm, 0] *= tp
        prop[slot, 2 + mm, 1] *= tp
        tp *= tau


@njit(cache=True, error_model="numpy", inline="always")
def _hermite_input(t0, t1, seg, r_a0, r_da0, r_a1, r_da1, res):
    """Cubic u(s) = sum_m res[i, X_C + m] s^m, s = t - t0, through the excitation and
    its rate in rows (r_a0, r_da0) of ``seg`` at t0 and (r_a1, r_da1) at t1."""
    tau = t1 - t0
    for i in range(res.shape[0]):
        a0 = seg[r_a0, i]
        da0 = seg[r_da0, i]
        da1 = seg[r_da1, i]
        slope = (seg[r_a1, i] - a0) / tau
        res[i, X_C] = a0
        res[i, X_C + 1] = da0
        res[i, X_C + 2] = (3.0 * slope - 2.0 * da0 - da1) / tau
        res[i, X_C + 3] = (-2.0 * slope + da0 + da1) / (tau * tau)


@njit(cache=True, error_model="numpy", inline="always")
def _propagate(res, s0, prop, slot):
    """Advance each resonator (z, z') in ``res`` over one piece starting at s = s0 of
    its input cubic (re-expanded about s0), with the propagator ``prop[slot]``."""
    for i in range(res.shape[0]):
        b0 = res[i, X_C]
        b1 = res[i, X_C + 1]
        b2 = res[i, X_C + 2]
        c3 = res[i, X_C + 3]
        c2 = b2 + 3.0 * c3 * s0
        c1 = b1 + s0 * (2.0 * b2 + 3.0 * c3 * s0)
        c0 = b0 + s0 * (b1 + s0 * (b2 + s0 * c3))
        z = res[i, X_Z]
        dz = res[i, X_DZ]
        for r in range(2):
            res[i, r] = (prop[slot, r, 0] * z + prop[slot, r, 1] * dz
                         + c0 * prop[slot, 2, r] + c1 * prop[slot, 3, r]
                         + c2 * prop[slot, 4, r] + c3 * prop[slot, 5, r])


@njit(cache=True, error_model="numpy", inline="always")
def _resonator_output(res, w, zeta, out, k):
    """Absolute acceleration of each resonator mass, -(2 zeta w z' + w^2 z), m/s^2, into
    ``out[k]``."""
    for i in range(res.shape[0]):
        out[k, i] = -(2.0 * zeta * w * res[i, X_DZ] + w * w * res[i, X_Z])


@njit(cache=True, error_model="numpy")
def _store_state(states, k, seg, r_y, res):
    """Row k of ``states`` in the full layout of :mod:`._kernels`: the core state in
    row ``r_y`` of ``seg`` and the resonator states."""
    n_res = res.shape[0]
    nd = 4 + n_res
    for i in range(4):
        states[k, i] = seg[r_y, i]
        states[k, nd + i] = seg[r_y, 4 + i]
    for i in range(n_res):
        states[k, 4 + i] = res[i, X_Z]
        states[k, nd + 4 + i] = res[i, X_DZ]


@njit(cache=True, error_model="numpy")
def _ok(seg, r_y, res, bound):
    """True when the core state in row ``r_y`` of ``seg`` and the resonator states are
    finite and within ``bound`` (full layout)."""
    n_res = res.shape[0]
    nd = 4 + n_res
    for i in range(4):
        if not (abs(seg[r_y, i]) <= bound[i] and abs(seg[r_y, 4 + i]) <= bound[nd + i]):
            return False
    for i in range(n_res):
        if not (abs(res[i, X_Z]) <= bound[4 + i] and abs(res[i, X_DZ]) <= bound[nd + 4 + i]):
            return False
    return True


@njit(cache=True, error_model="numpy")
def _on_ramp(kin):
    """True when some element is on the ramp of a defect at the kinematics in ``kin``
    (the flag :func:`._kernels.fault_depths` sets; waviness, smooth, does not count).
    Segments are split at every fault edge and ramp end, so one interior time decides
    for the whole segment."""
    return kin[K_CACHE, KC_RAMP] != 0.0


@njit(cache=True, error_model="numpy")
def _depths_needed(t0, t1, p, walk, faults, kin):
    """Whether the fault depths can be non-zero between consecutive split times t0 and
    t1 (s): the flag :func:`._kernels.fault_depths` sets (a path inside a localized
    defect, or waviness), read at the middle of (t0, t1). Paths enter and leave the
    defects only at the fault-edge crossings the steps are split at, so it holds for
    the whole interval; at the crossings themselves (the interval's ends) a path may
    sit on an edge. Overwrites the kinematics in ``kin``."""
    tm = 0.5 * (t0 + t1)
    rate = element_angles(tm, p, walk, kin)
    fault_depths(tm, p, faults, kin, rate, False)
    return kin[K_CACHE, KC_INSIDE] != 0.0


@njit(cache=True, error_model="numpy")
def _next_split(t, ev, ev_before, t_end):
    """The first split time after t (s), searching the sorted ``ev_before`` from index
    ev; t_end without one."""
    while ev < ev_before.shape[0]:
        if ev_before[ev] > t:
            return min(ev_before[ev], t_end)
        ev += 1
    return t_end


@njit(cache=True, error_model="numpy")
def _excitation(t, seg, r_y, r_f, r_a, p, walk, faults, sensors, kin):
    """Core derivative (row ``r_f``) at time t and core state row ``r_y`` of ``seg``,
    and the housing excitation of every sensor and its rate (rows ``r_a``,
    ``r_a + 1``). Returns the loaded contacts (see :func:`._kernels.core_forces`)."""
    y = seg[r_y]
    f = seg[r_f]
    rate = element_angles(t, p, walk, kin)
    fault_depths(t, p, faults, kin, rate, True)
    mask = core_forces(y, p, kin, f)
    housing_accel(y, f, p, sensors, kin, rate, seg, r_a, True)
    return mask


@njit(cache=True, error_model="numpy")
def _interpolate_core(t0, t1, tk, seg):
    """Cubic Hermite interpolant of the core state at tk in [t0, t1] from rows R_Y0,
    R_F0, R_Y1, R_F1 of ``seg``, into row R_YI."""
    tau = t1 - t0
    s = min(max((tk - t0) / tau, 0.0), 1.0)
    h00 = (1.0 + 2.0 * s) * (1.0 - s) ** 2
    h10 = s * (1.0 - s) ** 2 * tau
    h01 = s * s * (3.0 - 2.0 * s)
    h11 = s * s * (s - 1.0) * tau
    for i in range(N_CORE):
        seg[R_YI, i] = (h00 * seg[R_Y0, i] + h10 * seg[R_F0, i] + h01 * seg[R_Y1, i]
                        + h11 * seg[R_F1, i])


@njit(cache=True, error_model="numpy")
def _input_error(t, h, n_pieces, seg, rtol, atol_in, p, walk, faults, sensors, kin):
    """Error of the resonator state caused by the cubic Hermite input over [t, t + h]
    on a defect's ramp, in the units of the error norm (1 = at tolerance).

    :func:`_emit` interpolates the excitation there over pieces of length
    L = h / n_pieces. On a piece the input error e(s) = u''''/24 s^2 (L - s)^2
    integrates to 16/30 L e(L/2) of resonator velocity, over the step to
    16/30 h e(L/2); against the velocity scale u_scale / w_r this is
    (16/30) w_r h |e(L/2)| / (atol_in + rtol |u|): the control the resonators would get
    in the Runge-Kutta error norm of the full state. e(L/2) compares the Hermite
    interpolant of the first piece [t, t + L] at its middle with the excitation u of
    the interpolated core state (``atol_in`` in m/s^2; RMS over the sensors). Needs
    rows R_Y0, R_F0, R_A0, R_DA0 (start) and R_Y1, R_F1 (end) of ``seg``; overwrites
    R_YI, R_FI, R_AC, R_DAC, R_AK, R_DAK."""
    length = h / n_pieces
    n_s = sensors.shape[0]
    _interpolate_core(t, t + h, t + length, seg)
    _excitation(t + length, seg, R_YI, R_FI, R_AK, p, walk, faults, sensors, kin)
    _interpolate_core(t, t + h, t + 0.5 * length, seg)
    _excitation(t + 0.5 * length, seg, R_YI, R_FI, R_AC, p, walk, faults, sensors, kin)
    err = 0.0
    for i in range(n_s):
        # the cubic Hermite interpolant at mid-piece
        mid = (0.5 * (seg[R_A0, i] + seg[R_AK, i])
               + 0.125 * length * (seg[R_DA0, i] - seg[R_DAK, i]))
        exact = seg[R_AC, i]
        err += ((mid - exact) / (atol_in + rtol * abs(exact))) ** 2
    return (16.0 / 30.0) * p[P_WR] * h * math.sqrt(err / n_s)


@njit(cache=True, error_model="numpy")
def _emit(t0, t1, n_pieces, k_next, h_out, seg, res, prop, p, walk, faults, sensors, kin,
          out, states):
    """Output of one core segment [t0, t1] on the grid points t_k = k h_out in (t0, t1].

    Advances the resonators in ``res`` exactly from grid point to grid point and on
    to t1 (``prop[PROP_H]``: the propagator of a full h_out piece), writes their output
    (sr5) or the housing acceleration of the interpolated core state (sr4), and the
    full state when ``states`` has rows. Returns the index of the next grid point.

    The core state between t0 and t1 is the cubic Hermite interpolant of its values
    and derivatives at both ends (rows R_Y0, R_F0, R_Y1, R_F1 of ``seg``). The
    resonator input is the cubic Hermite interpolant of the excitation and its rate at
    both ends (R_A0, R_DA0, R_A1, R_DA1), unless ``n_pieces`` > 1 (the segment lies on
    a ramp of a defect, where the excitation follows the depth profile, which can
    change faster than the core): the segment is then cut into ``n_pieces`` pieces
    whose ends get the excitation of the interpolated core state, and the input is
    interpolated piece by piece.
    """
    w = p[P_WR]
    zeta = p[P_ZETA]
    n_res = res.shape[0]
    n_out = out.shape[0]
    keep = states.shape[0] > 0
    if n_res == 0:
        n_pieces = 1
    if n_res > 0:
        for i in range(n_res):  # the excitation at the start of the current piece
            seg[R_AC, i] = seg[R_A0, i]
            seg[R_DAC, i] = seg[R_DA0, i]
    b0 = t0
    for piece in range(1, n_pieces + 1):
        b1 = t1 if piece == n_pieces else t0 + piece * (t1 - t0) / n_pieces
        if n_res > 0:
            if piece == n_pieces:
                for i in range(n_res):
                    seg[R_AK, i] = seg[R_A1, i]
                    seg[R_DAK, i] = seg[R_DA1, i]
            else:
                _interpolate_core(t0, t1, b1, seg)
                _excitation(b1, seg, R_YI, R_FI, R_AK, p, walk, faults, sensors, kin)
            _hermite_input(b0, b1, seg, R_AC, R_DAC, R_AK, R_DAK, res)
        tc = b0
        while k_next < n_out:
            tk = k_next * h_out
            if tk > b1 + GRID_TOL * h_out:
                break
            if n_res > 0:
                if tk > tc:
                    slot = PROP_H
                    if abs(tk - tc - h_out) > GRID_TOL * h_out:
                        slot = PROP_TMP
                        lti_propagator(tk - tc, w, zeta, prop, slot)
                    _propagate(res, tc - b0, prop, slot)
                    tc = tk
                _resonator_output(res, w, zeta, out, k_next)
            if n_res == 0 or keep:
                _interpolate_core(t0, t1, tk, seg)
            if n_res == 0:
                yi = seg[R_YI]
                rate = element_angles(tk, p, walk, kin)
                fault_depths(tk, p, faults, kin, rate, False)
                contact_loads(yi, p, kin, 4)
                housing_accel(yi, yi, p, sensors, kin, 0.0, out, k_next, False)
            if keep:
                _store_state(states, k_next, seg, R_YI, res)
            k_next += 1
        if n_res > 0:
            if b1 > tc:
                lti_propagator(b1 - tc, w, zeta, prop, PROP_TMP)
                _propagate(res, tc - b0, prop, PROP_TMP)
            for i in range(n_res):
                seg[R_AC, i] = seg[R_AK, i]
                seg[R_DAC, i] = seg[R_DAK, i]
        b0 = b1
    return k_next


@njit(cache=True, error_model="numpy")
def _emit_grid(t0, t1, n, k_next, seg, res, tab, w, zeta, out):
    """:func:`_emit` for the common case of an sr5 segment of ``n`` whole grid intervals
    from grid point to grid point without states to keep. ``tab[j]`` holds the
    propagator of j h_out (j = 1 .. n, :func:`lti_propagator`), so each grid point's
    resonator state comes straight from the segment start and the input cubic about
    it: x_j = Phi(j h_out) x_0 + sum_m c_m g_m(j h_out), the same exact solution as
    propagating from grid point to grid point, without re-expanding the cubic or a
    chain of dependent updates. Its helpers are inlined and it takes few arrays, so
    numba can drop the reference counting of its arguments."""
    _hermite_input(t0, t1, seg, R_A0, R_DA0, R_A1, R_DA1, res)
    for i in range(res.shape[0]):
        z = res[i, X_Z]
        dz = res[i, X_DZ]
        c0 = res[i, X_C]
        c1 = res[i, X_C + 1]
        c2 = res[i, X_C + 2]
        c3 = res[i, X_C + 3]
        zj = z
        dzj = dz
        for j in range(1, n + 1):
            zj = (tab[j, 0, 0] * z + tab[j, 0, 1] * dz + c0 * tab[j, 2, 0]
                  + c1 * tab[j, 3, 0] + c2 * tab[j, 4, 0] + c3 * tab[j, 5, 0])
            dzj = (tab[j, 1, 0] * z + tab[j, 1, 1] * dz + c0 * tab[j, 2, 1]
                   + c1 * tab[j, 3, 1] + c2 * tab[j, 4, 1] + c3 * tab[j, 5, 1])
            out[k_next + j - 1, i] = -(2.0 * zeta * w * dzj + w * w * zj)
        res[i, X_Z] = zj
        res[i, X_DZ] = dzj
    return k_next + n


@njit(cache=True, error_model="numpy")
def _start(y0, p, walk, faults, sensors, n_res, h_out, out, states):
    """Workspaces for a run, the initial state split into core (row R_Y0 of ``seg``)
    and resonators, evaluated at t = 0; output row 0 written.

    Returns (seg, res, prop, kin).
    """
    nd = 4 + n_res
    n_s = sensors.shape[0]
    seg = np.zeros((N_SEG, max(N_CORE, n_s)))
    res = np.zeros((n_res, 6))
    prop = np.zeros((2, 6, 2))
    kin = kinematics_scratch(int(p[P_Z]))
    for i in range(4):
        seg[R_Y0, i] = y0[i]
        seg[R_Y0, 4 + i] = y0[nd + i]
    for i in range(n_res):
        res[i, X_Z] = y0[4 + i]
        res[i, X_DZ] = y0[nd + 4 + i]
    _excitation(0.0, seg, R_Y0, R_F0, R_A0, p, walk, faults, sensors, kin)
    if n_res > 0:
        lti_propagator(h_out, p[P_WR], p[P_ZETA], prop, PROP_H)
        _resonator_output(res, p[P_WR], p[P_ZETA], out, 0)
    else:
        for i in range(n_s):
            out[0, i] = seg[R_A0, i]
    if states.shape[0] > 0:
        _store_state(states, 0, seg, R_Y0, res)
    return seg, res, prop, kin


@njit(cache=True, error_model="numpy")
def _advance(seg, res):
    """The segment's end becomes the next one's start: rows Y1, F1, A1, DA1 to Y0, F0,
    A0, DA0."""
    for i in range(N_CORE):
        seg[R_Y0, i] = seg[R_Y1, i]
        seg[R_F0, i] = seg[R_F1, i]
    for i in range(res.shape[0]):
        seg[R_A0, i] = seg[R_A1, i]
        seg[R_DA0, i] = seg[R_DA1, i]


#: passes of an integrator's main loop per call (steps to a grid step end for rk4,
#: attempted steps for dopri5): :func:`run_chunked` calls the kernel again until it is
#: done, so Python raises a KeyboardInterrupt (Ctrl-C) between calls, a few hundredths
#: of a second apart, instead of after the whole run; the calls' overhead is well below
#: 1 % of their work (benchmarks/sr5_chunking.py)
CHUNK_PASSES = 1 << 14


def run_chunked(kernel, *args, passes: int | None = None):
    """Call a resumable integrator (:func:`rk4`, :func:`dopri5`) with ``args`` (its
    arguments but the last, workspace included) and ``passes`` (default
    :data:`CHUNK_PASSES`) until it returns a status other than ``STATUS_PAUSED``;
    returns that call's result. The workspace carries every loop variable, so the
    result does not depend on ``passes``, bit for bit."""
    passes = CHUNK_PASSES if passes is None else passes
    while True:
        result = kernel(*args, passes)
        if result[0] != STATUS_PAUSED:
            return result


@njit(cache=True, error_model="numpy")
def rk4_start(y0, p, walk, faults, sensors, n_res, h_out, mult, n_sub, n_out, ev_before,
              out, states):
    """Workspace of an :func:`rk4` run, evaluated at t = 0 (output row 0 written).

    Parameters as in :func:`rk4`.

    Returns
    -------
    work : tuple
        ``(seg, res, prop, kin, tab, ist, fst)``: the segment rows, resonator states,
        propagators, kinematics, the propagator table of the fast output, and the
        scalar loop state (integers ``ist``, indices ``RK4_*``; floats ``fst``: time
        and the end of a refinement), all carried from one :func:`rk4` call to the next.
    """
    seg, res, prop, kin = _start(y0, p, walk, faults, sensors, n_res, h_out, out, states)
    # steps from grid point to grid point of sr5 without states take the fast output,
    # with the resonator propagators of 1 .. mult grid intervals
    fast = n_sub == 1 and n_res > 0 and states.shape[0] == 0
    tab = np.zeros((mult + 1 if fast else 0, 6, 2))
    for j in range(1, tab.shape[0]):
        lti_propagator(j * h_out, p[P_WR], p[P_ZETA], tab, j)
    ist = np.zeros(N_RK4_IST, dtype=np.int64)
    fst = np.zeros(2)
    ist[RK4_RAMP] = _on_ramp(kin)  # on a defect's ramp; changes only at events
    # f0 again (kin holds t = 0): the loaded contacts
    ist[RK4_MASK] = core_forces(seg[R_Y0], p, kin, seg[R_F0])
    ist[RK4_K_NEXT] = 1
    fst[1] = -1.0
    # outside every localized defect (and without waviness) the fault depths are
    # exactly zero and stay so until the next event: they are not recomputed (kin's
    # depth rows stay the zeros the check left)
    t_end = (n_out - 1) * h_out
    ist[RK4_DEPTHS] = _depths_needed(0.0, _next_split(0.0, 0, ev_before, t_end), p, walk,
                                     faults, kin)
    return seg, res, prop, kin, tab, ist, fst


@njit(cache=True, error_model="numpy")
def rk4(p, walk, faults, sensors, n_res, h_out, mult, n_sub, n_out, ev_before, ev_after,
        t_ramp, t_impact, bound, out, states, seg, res, prop, kin, tab, ist, fst, max_passes):
    """Classical RK4 on the core with a fixed step of ``mult * h_out / n_sub``, split at
    events, and no longer than h_out on short ramps ending in impacts.

    A call returns after at most ``max_passes`` steps to the next step end on the
    grid (status ``STATUS_PAUSED``), its loop state saved in the workspace; the next
    call with the same workspace goes on exactly where it stopped, so a run in many
    calls is bit-identical to one in a single call (and Python can raise a
    KeyboardInterrupt in between).

    Parameters
    ----------
    p, walk, faults, sensors : ndarray
        The model (see :mod:`._kernels`).
    n_res : int
        Number of resonators (sensors for sr5, 0 for sr4).
    h_out : float
        Internal output spacing, s.
    mult, n_sub : int
        Step = ``mult * h_out / n_sub``, one of them 1: a step spans ``mult`` output
        intervals or an output interval holds ``n_sub`` steps, so step ends fall on
        the grid.
    n_out : int
        Number of internal output samples (t = 0 .. (n_out - 1) h_out).
    ev_before, ev_after : ndarray
        Sorted event brackets, s.
    t_ramp, t_impact : float
        Shortest duration of a defect ramp, and of one ending in an impact, s (inf
        without; see :data:`RAMP_STEPS`).
    bound : ndarray (n_state,)
        Magnitude above which a full-state component counts as diverged.
    out : ndarray (n_out, n_sensors)
        Written with the sensor output at the grid times.
    states : ndarray (n_out, n_state) or (0, n_state)
        Written with the full state at the grid times when it has rows.
    seg, res, prop, kin, tab, ist, fst : ndarray
        The workspace from :func:`rk4_start`, updated.
    max_passes : int
        Steps to a grid step end in this call (>= 1).

    Returns
    -------
    status, n_steps, t
        Status code, steps taken so far and the time reached (of the failure, if any).
    """
    y = seg[R_Y0]
    f0 = seg[R_F0]
    y1 = seg[R_Y1]
    f1 = seg[R_F1]
    k2 = np.empty(N_CORE)
    k3 = np.empty(N_CORE)
    k4 = np.empty(N_CORE)
    tmp = np.empty(N_CORE)
    t_end = (n_out - 1) * h_out
    n_ev = ev_before.shape[0]
    ev = ist[RK4_EV]
    n_steps = ist[RK4_N_STEPS]
    k_next = ist[RK4_K_NEXT]
    n = ist[RK4_N]
    mask0 = ist[RK4_MASK]
    depths = ist[RK4_DEPTHS] != 0
    ramp = ist[RK4_RAMP] != 0
    t = fst[0]
    refine_end = fst[1]
    fast = tab.shape[0] > 0
    h_step = h_out * mult / n_sub
    sub_ramp = mult > 1 and t_impact < RAMP_STEPS * h_step
    # a contact that opens or closes inside a step puts a kink of the Hertz law
    # (Q ~ delta^n, no longer smooth at delta = 0) in it, which costs RK4 its order:
    # such a step is redone from grid point to grid point
    passes = 0
    while t < t_end:
        if passes == max_passes:
            ist[RK4_EV] = ev
            ist[RK4_N_STEPS] = n_steps
            ist[RK4_K_NEXT] = k_next
            ist[RK4_N] = n
            ist[RK4_MASK] = mask0
            ist[RK4_DEPTHS] = 1 if depths else 0
            ist[RK4_RAMP] = 1 if ramp else 0
            fst[0] = t
            fst[1] = refine_end
            return STATUS_PAUSED, n_steps, t
        passes += 1
        n += 1
        q, r = divmod(n, n_sub)
        t_next = min(q * mult, n_out - 1) * h_out
        if r > 0:
            t_next += r * h_out / n_sub
        while t < t_next:
            while ev < n_ev and ev_after[ev] <= t:
                ev += 1
            te = t_next
            if (ramp and sub_ramp) or t < refine_end:
                # on a defect's ramp the depth profile, not the core, sets the pace
                # (an impact can stiffen the contacts many times): step from grid point
                # to grid point; so across a contact opening or closing
                te = min(te, k_next * h_out)
            hit = ev < n_ev and ev_before[ev] < te
            if hit:
                te = ev_before[ev]
            if te > t:
                h = te - t
                for i in range(N_CORE):
                    tmp[i] = y[i] + 0.5 * h * f0[i]
                rate = element_angles(t + 0.5 * h, p, walk, kin)
                if depths:
                    fault_depths(t + 0.5 * h, p, faults, kin, rate, True)
                n_pieces = _ramp_pieces(h, t_ramp) if _on_ramp(kin) else 1
                changed = core_forces(tmp, p, kin, k2) != mask0
                for i in range(N_CORE):
                    tmp[i] = y[i] + 0.5 * h * k2[i]
                changed = core_forces(tmp, p, kin, k3) != mask0 or changed
                for i in range(N_CORE):
                    tmp[i] = y[i] + h * k3[i]
                rate = element_angles(te, p, walk, kin)
                if depths:
                    fault_depths(te, p, faults, kin, rate, n_res > 0)
                changed = core_forces(tmp, p, kin, k4) != mask0 or changed
                for i in range(N_CORE):
                    y1[i] = y[i] + h / 6.0 * (f0[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
                mask1 = core_forces(y1, p, kin, f1)
                if (changed or mask1 != mask0) and h > (1.0 + GRID_TOL) * h_out:
                    refine_end = te  # redo [t, te] in grid steps
                    continue
                mask0 = mask1
                if n_res > 0:
                    housing_accel(y1, f1, p, sensors, kin, rate, seg, R_A1, True)
                n_grid = int(round((te - t) / h_out))
                if (fast and not hit and n_pieces == 1 and t == (k_next - 1) * h_out
                        and 1 <= n_grid <= mult
                        and abs(te - t - n_grid * h_out) <= GRID_TOL * h_out):
                    k_next = _emit_grid(t, te, n_grid, k_next, seg, res, tab, p[P_WR],
                                        p[P_ZETA], out)
                else:
                    k_next = _emit(t, te, n_pieces, k_next, h_out, seg, res, prop, p, walk,
                                   faults, sensors, kin, out, states)
                n_steps += 1
                if not _ok(seg, R_Y1, res, bound):
                    return STATUS_NONFINITE, n_steps, te
                _advance(seg, res)
            if hit:
                t = ev_after[ev]
                ev += 1
                if t < t_end:
                    depths = _depths_needed(t, _next_split(t, ev, ev_before, t_end), p,
                                            walk, faults, kin)
                mask0 = _excitation(t, seg, R_Y0, R_F0, R_A0, p, walk, faults, sensors, kin)
                ramp = _on_ramp(kin)
            else:
                t = te
    return STATUS_OK, n_steps, t


@njit(cache=True, error_model="numpy")
def dopri5_start(y0, p, walk, faults, sensors, n_res, h_out, h_max, out, states):
    """Workspace of a :func:`dopri5` run, evaluated at t = 0 (output row 0 written).

    Parameters as in :func:`dopri5`.

    Returns
    -------
    work : tuple
        ``(seg, res, prop, kin, h_regime, ist, fst)``: as :func:`rk4_start`'s, with the
        step size remembered for each regime; the scalar loop state in ``ist``
        (indices ``DP_*``) and ``fst`` (time, step, smallest step, previous error).
    """
    seg, res, prop, kin = _start(y0, p, walk, faults, sensors, n_res, h_out, out, states)
    h = min(h_max, h_out)
    # step-size memory for each regime: on a defect's ramp the depth profile sets the
    # pace, elsewhere the core does; an event switching regimes restarts from the step
    # last used in the new one instead of paying rejections to get there
    h_regime = np.array([h, h])
    ist = np.zeros(N_DP_IST, dtype=np.int64)
    ist[DP_K_NEXT] = 1
    fst = np.array([0.0, h, h, 1e-4])
    return seg, res, prop, kin, h_regime, ist, fst


@njit(cache=True, error_model="numpy")
def dopri5(p, walk, faults, sensors, n_res, h_out, n_out, ev_before, ev_after, t_ramp,
           bound, rtol, atol, atol_in, h_max, max_steps, out, states, seg, res, prop, kin,
           h_regime, ist, fst, max_passes):
    """Adaptive Dormand-Prince 5(4) on the core with error control, output on a grid.

    The local error estimate of the embedded 4th-order solution is kept below 1 in the
    RMS norm ``err_i / (atol_i + rtol * max(|y_i|, |y_new_i|))`` over the 8 core states
    (``atol`` has length 8); the step never exceeds ``h_max`` nor crosses an event.
    Resonators and output as in :func:`rk4`, from the accepted steps.

    On the ramps of a defect the resonator excitation follows the depth profile, which
    the core error estimate does not see: it is refined as in :func:`rk4` and the step
    is also controlled by the error of that input (:func:`_input_error`; ``atol_in`` in
    m/s^2). A call returns after ``max_passes`` attempted steps (status
    ``STATUS_PAUSED``) with its loop state in the workspace from
    :func:`dopri5_start` (``seg, res, prop, kin, h_regime, ist, fst``); the next call
    goes on exactly where it stopped, as :func:`rk4`'s do. Other parameters as in
    :func:`rk4`.

    Returns
    -------
    status, n_accepted, n_rejected, h_min_used, t_fail
    """
    y = seg[R_Y0]
    k1 = seg[R_F0]
    y_new = seg[R_Y1]
    k7 = seg[R_F1]
    n = N_CORE
    t_end = (n_out - 1) * h_out
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    k5 = np.empty(n)
    k6 = np.empty(n)
    tmp = np.empty(n)
    n_ev = ev_before.shape[0]
    k_next = ist[DP_K_NEXT]
    ev = ist[DP_EV]
    n_acc = ist[DP_N_ACC]
    n_rej = ist[DP_N_REJ]
    rejected = ist[DP_REJECTED] != 0
    t = fst[0]
    h = fst[1]
    h_min_used = fst[2]
    err_prev = fst[3]
    passes = 0
    while t < t_end:
        if passes == max_passes:
            ist[DP_K_NEXT] = k_next
            ist[DP_EV] = ev
            ist[DP_N_ACC] = n_acc
            ist[DP_N_REJ] = n_rej
            ist[DP_REJECTED] = 1 if rejected else 0
            fst[0] = t
            fst[1] = h
            fst[2] = h_min_used
            fst[3] = err_prev
            return STATUS_PAUSED, n_acc, n_rej, h_min_used, t
        passes += 1
        if n_acc + n_rej >= max_steps:
            return STATUS_MAX_STEPS, n_acc, n_rej, h_min_used, t
        while ev < n_ev and ev_after[ev] <= t:
            ev += 1
        h = min(h, h_max, t_end - t)
        h_wanted = h
        hits_event = False
        if ev < n_ev and t + h > ev_before[ev]:
            h = ev_before[ev] - t
            hits_event = True
        if h <= 1e-15 * max(1.0, t):
            if hits_event:
                # already at the event (several fall at one time): jump over it and
                # keep the step size wanted before it
                t = ev_after[ev]
                ev += 1
                _excitation(t, seg, R_Y0, R_F0, R_A0, p, walk, faults, sensors, kin)
                h = h_wanted
                continue
            return STATUS_UNDERFLOW, n_acc, n_rej, h, t
        for i in range(n):
            tmp[i] = y[i] + h * A21 * k1[i]
        rate = element_angles(t + C2 * h, p, walk, kin)
        fault_depths(t + C2 * h, p, faults, kin, rate, False)
        core_forces(tmp, p, kin, k2)
        for i in range(n):
            tmp[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i])
        rate = element_angles(t + C3 * h, p, walk, kin)
        fault_depths(t + C3 * h, p, faults, kin, rate, True)
        regime = 1 if _on_ramp(kin) else 0
        core_forces(tmp, p, kin, k3)
        for i in range(n):
            tmp[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i])
        rate = element_angles(t + C4 * h, p, walk, kin)
        fault_depths(t + C4 * h, p, faults, kin, rate, False)
        core_forces(tmp, p, kin, k4)
        for i in range(n):
            tmp[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i])
        rate = element_angles(t + C5 * h, p, walk, kin)
        fault_depths(t + C5 * h, p, faults, kin, rate, False)
        core_forces(tmp, p, kin, k5)
        for i in range(n):
            tmp[i] = y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i]
                                 + A65 * k5[i])
        rate = element_angles(t + h, p, walk, kin)
        fault_depths(t + h, p, faults, kin, rate, n_res > 0)
        core_forces(tmp, p, kin, k6)
        for i in range(n):
            y_new[i] = y[i] + h * (B1 * k1[i] + B3 * k3[i] + B4 * k4[i] + B5 * k5[i]
                                   + B6 * k6[i])
        core_forces(y_new, p, kin, k7)
        err = _dopri_error(h, k1, k3, k4, k5, k6, k7, y, y_new, atol, rtol, n)
        if n_res > 0:
            housing_accel(y_new, k7, p, sensors, kin, rate, seg, R_A1, True)
        if regime == 1 and n_res > 0:
            err = max(err, _input_error(t, h, _ramp_pieces(h, t_ramp), seg, rtol, atol_in, p,
                                        walk, faults, sensors, kin))
        if not (err == err):  # NaN: treat as a failed step with a much smaller h
            err = 1e10
        if err <= 1.0:
            if hits_event:
                t_new = ev_before[ev]
            elif h == t_end - t:
                t_new = t_end
            else:
                t_new = t + h
            n_pieces = _ramp_pieces(h, t_ramp) if regime == 1 else 1
            k_next = _emit(t, t_new, n_pieces, k_next, h_out, seg, res, prop, p, walk,
                           faults, sensors, kin, out, states)
            if not _ok(seg, R_Y1, res, bound):
                return STATUS_NONFINITE, n_acc, n_rej, h_min_used, t_new
            _advance(seg, res)
            n_acc += 1
            if h < h_min_used:
                h_min_used = h
            # PI step control of Hairer's DOPRI5 (Hairer, Norsett & Wanner 1993, II.4):
            # exponents 0.2 - 0.75 beta and beta = 0.04 on the previous error, safety
            # 0.9, growth within [0.2, 5] and none right after a rejection
            fac = 5.0 if err == 0.0 else min(5.0, max(
                0.2, 0.9 * err ** -PI_ALPHA * err_prev ** PI_BETA))
            if rejected:
                fac = min(fac, 1.0)
            rejected = False
            err_prev = max(err, 1e-4)
            h = h * fac
            if hits_event:
                h = max(h, h_wanted)  # the event, not the error, limited this step
                h_regime[regime] = h
                t = ev_after[ev]
                ev += 1
                _excitation(t, seg, R_Y0, R_F0, R_A0, p, walk, faults, sensors, kin)
                h = h_regime[1 if _on_ramp(kin) else 0]
            else:
                h_regime[regime] = h
                t = t_new
        else:
            n_rej += 1
            rejected = True
            h = h * max(0.2, 0.9 * err ** -PI_ALPHA)
    return STATUS_OK, n_acc, n_rej, h_min_used, t



@njit(cache=True, error_model="numpy", inline="always")
def _dopri_error(h, k1, k3, k4, k5, k6, k7, y, y_new, atol, rtol, n):
    """Hairer's RMS error norm of a DOPRI5 step of size ``h`` over the first ``n``
    components: the embedded 4th-order difference sum_j E_j k_j, each component scaled
    by atol_i + rtol max(|y_i|, |y_new_i|)."""
    err = 0.0
    for i in range(n):
        e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i]
                 + E7 * k7[i])
        sc = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
        err += (e / sc) ** 2
    return math.sqrt(err / n)


@njit(cache=True, error_model="numpy")
def _pi_factor(err, err_prev, rejected):
    """Step-size factor of Hairer's DOPRI5 PI control (as in :func:`dopri5`): exponents
    0.2 - 0.75 beta and beta on the previous error, safety 0.9, within [0.2, 5], no
    growth right after a rejection."""
    fac = 5.0 if err == 0.0 else min(5.0, max(
        0.2, 0.9 * err ** -PI_ALPHA * err_prev ** PI_BETA))
    return min(fac, 1.0) if rejected else fac
