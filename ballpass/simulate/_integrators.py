"""Numba integrators for the bearing models: fixed-step RK4 and adaptive
Dormand-Prince 5(4), both aware of the fault-edge events.

Both integrators

* never step across an event: a step that would cross one is shortened to end just
  before it (``ev_before``), and integration resumes just after it (``ev_after``),
  with the right-hand side re-evaluated there. The fault profile is a known function
  of time (rigid kinematics), so the discontinuities of a sharp-edged defect always
  fall on step boundaries and the methods keep their order through them;
* record the sensor output on a uniform internal grid ``k * h_out``;
* stop with a status code as soon as the state is not finite or leaves a bound,
  so the caller can raise a clear error (no NaN ever leaves the simulator).

Status codes: 0 ok, 1 non-finite or unbounded state, 2 step size underflow
(adaptive), 3 too many steps (adaptive).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._kernels import rhs, sensor_output

STATUS_OK, STATUS_NONFINITE, STATUS_UNDERFLOW, STATUS_MAX_STEPS = 0, 1, 2, 3

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


@njit(cache=True)
def _finite_and_bounded(y, bound):
    for i in range(y.shape[0]):
        v = y[i]
        if not (abs(v) <= bound[i]):
            return False
    return True


@njit(cache=True)
def _rk4_step(t, y, h, m, n_res, work, k1, k2, k3, k4, tmp, y_out):
    n = y.shape[0]
    rhs(t, y, k1, m, n_res, work)
    for i in range(n):
        tmp[i] = y[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, tmp, k2, m, n_res, work)
    for i in range(n):
        tmp[i] = y[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, tmp, k3, m, n_res, work)
    for i in range(n):
        tmp[i] = y[i] + h * k3[i]
    rhs(t + h, tmp, k4, m, n_res, work)
    for i in range(n):
        y_out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@njit(cache=True)
def rk4(y0, m, n_res, work, h_out, n_sub, n_out, ev_before, ev_after, bound, out, states):
    """Classical fixed-step RK4 on the grid ``h_out / n_sub``, split at events.

    Parameters
    ----------
    y0 : ndarray (n_state,)
        Initial state.
    m, n_res, work
        Model tuple, number of resonators, scratch arrays (see :func:`.rhs`).
    h_out : float
        Internal output spacing, s.
    n_sub : int
        RK4 steps per output interval (step h = h_out / n_sub).
    n_out : int
        Number of internal output samples (t = 0 .. (n_out - 1) h_out).
    ev_before, ev_after : ndarray
        Sorted event brackets, s.
    bound : ndarray (n_state,)
        Magnitude above which a state component counts as diverged.
    out : ndarray (n_out, n_sensors)
        Written with the sensor output at the grid times.
    states : ndarray (n_out, n_state) or (0, n_state)
        Written with the state at the grid times when it has rows.

    Returns
    -------
    status, n_steps, t_fail
    """
    n = y0.shape[0]
    y = y0.copy()
    y_new = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    row = np.empty(out.shape[1])
    sensor_output(0.0, y, m, n_res, work, row)
    out[0, :] = row
    keep = states.shape[0] > 0
    if keep:
        states[0, :] = y
    h = h_out / n_sub
    n_ev = ev_before.shape[0]
    ev = 0
    n_steps = 0
    t = 0.0
    for k in range(1, n_out):
        t_start = (k - 1) * h_out
        for s in range(n_sub):
            t_next = t_start + (s + 1) * h if s < n_sub - 1 else k * h_out
            while ev < n_ev and ev_after[ev] <= t:
                ev += 1
            while ev < n_ev and ev_before[ev] < t_next:
                if ev_before[ev] > t:
                    _rk4_step(t, y, ev_before[ev] - t, m, n_res, work, k1, k2, k3, k4, tmp,
                              y_new)
                    y[:] = y_new
                    n_steps += 1
                t = max(t, ev_after[ev])
                ev += 1
            if t_next > t:
                _rk4_step(t, y, t_next - t, m, n_res, work, k1, k2, k3, k4, tmp, y_new)
                y[:] = y_new
                n_steps += 1
            t = t_next
        if not _finite_and_bounded(y, bound):
            return STATUS_NONFINITE, n_steps, t
        sensor_output(t, y, m, n_res, work, row)
        out[k, :] = row
        if keep:
            states[k, :] = y
    return STATUS_OK, n_steps, t


@njit(cache=True)
def dopri5(y0, m, n_res, work, h_out, n_out, ev_before, ev_after, bound, rtol, atol,
           h_max, max_steps, out, states):
    """Adaptive Dormand-Prince 5(4) with error control, output on a uniform grid.

    The local error estimate of the embedded 4th-order solution is kept below 1 in the
    RMS norm ``err_i / (atol_i + rtol * max(|y_i|, |y_new_i|))``; the step never exceeds
    ``h_max`` nor crosses an event. Output between steps uses cubic Hermite interpolation
    of the state (4th-order accurate), then the sensor output of the interpolated state.

    Returns
    -------
    status, n_accepted, n_rejected, h_min_used, t_fail
    """
    n = y0.shape[0]
    t_end = (n_out - 1) * h_out
    y = y0.copy()
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    k5 = np.empty(n)
    k6 = np.empty(n)
    k7 = np.empty(n)
    tmp = np.empty(n)
    y_new = np.empty(n)
    yi = np.empty(n)
    row = np.empty(out.shape[1])
    sensor_output(0.0, y, m, n_res, work, row)
    out[0, :] = row
    keep = states.shape[0] > 0
    if keep:
        states[0, :] = y
    k_out = 1
    n_ev = ev_before.shape[0]
    ev = 0
    t = 0.0
    rhs(t, y, k1, m, n_res, work)
    h = min(h_max, h_out)
    h_min_used = h
    n_acc = 0
    n_rej = 0
    while t < t_end:
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
                # already at the event: jump over the zero-width bracket
                t = ev_after[ev]
                ev += 1
                rhs(t, y, k1, m, n_res, work)
                continue
            return STATUS_UNDERFLOW, n_acc, n_rej, h, t
        for i in range(n):
            tmp[i] = y[i] + h * A21 * k1[i]
        rhs(t + C2 * h, tmp, k2, m, n_res, work)
        for i in range(n):
            tmp[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i])
        rhs(t + C3 * h, tmp, k3, m, n_res, work)
        for i in range(n):
            tmp[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i])
        rhs(t + C4 * h, tmp, k4, m, n_res, work)
        for i in range(n):
            tmp[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i])
        rhs(t + C5 * h, tmp, k5, m, n_res, work)
        for i in range(n):
            tmp[i] = y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i]
                                 + A65 * k5[i])
        rhs(t + h, tmp, k6, m, n_res, work)
        for i in range(n):
            y_new[i] = y[i] + h * (B1 * k1[i] + B3 * k3[i] + B4 * k4[i] + B5 * k5[i]
                                   + B6 * k6[i])
        rhs(t + h, y_new, k7, m, n_res, work)
        err = 0.0
        for i in range(n):
            e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i]
                     + E7 * k7[i])
            sc = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
            err += (e / sc) ** 2
        err = math.sqrt(err / n)
        if not (err == err):  # NaN: treat as a failed step with a much smaller h
            err = 1e10
        if err <= 1.0:
            t_new = t + h
            # output on the grid points in (t, t_new]
            while k_out < n_out and k_out * h_out <= t_new + 1e-12 * h_out:
                tg = k_out * h_out
                s = (tg - t) / h
                if s > 1.0:
                    s = 1.0
                h00 = (1.0 + 2.0 * s) * (1.0 - s) ** 2
                h10 = s * (1.0 - s) ** 2
                h01 = s * s * (3.0 - 2.0 * s)
                h11 = s * s * (s - 1.0)
                for i in range(n):
                    yi[i] = h00 * y[i] + h10 * h * k1[i] + h01 * y_new[i] + h11 * h * k7[i]
                sensor_output(tg, yi, m, n_res, work, row)
                out[k_out, :] = row
                if keep:
                    states[k_out, :] = yi
                k_out += 1
            y[:] = y_new
            if not _finite_and_bounded(y, bound):
                return STATUS_NONFINITE, n_acc, n_rej, h_min_used, t_new
            n_acc += 1
            if h < h_min_used:
                h_min_used = h
            fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
            if hits_event:
                t = ev_after[ev]
                ev += 1
                rhs(t, y, k1, m, n_res, work)
                h = max(h * fac, h_wanted)  # the event, not the error, limited this step
            else:
                t = t_new
                k1[:] = k7
                h = h * fac
        else:
            n_rej += 1
            h = h * max(0.1, 0.9 * err ** -0.25)
    while k_out < n_out:  # t reached t_end exactly: the last grid point
        sensor_output(k_out * h_out, y, m, n_res, work, row)
        out[k_out, :] = row
        if keep:
            states[k_out, :] = y
        k_out += 1
    return STATUS_OK, n_acc, n_rej, h_min_used, t
