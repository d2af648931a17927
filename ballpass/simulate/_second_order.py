"""Generic second-order integrators for the models written as M a + f(t, x, v) = 0
(rotor2 and later ones): Newmark-beta with Newton iterations, adaptive Dormand-Prince
5(4) and fixed-step RK4 restarted at known breaks and where a contact closes or opens.

A model supplies its equations of motion as one numba function
``force(t, x, v, p, f, kx, kv)`` that fills the generalised force f (n,), everything
except the inertia (contacts, damping, minus the external loads), and its tangent
matrices kx = df/dx and kv = df/dv (n, n); ``p`` is the model's float64 parameter
array. :func:`newmark_for`, :func:`dopri5_for` and :func:`rk4_for` compile the
integrators for one force function. (The force is bound as a global of a copy of the
integrator, not passed as an argument: numba cannot cache a function that receives
another as a value, whose type holds an address that changes from process to process.)

The Dormand-Prince tableau, the error norm and the step-size controller are those of
the sr5 integrators (:mod:`._integrators`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._integrators import (
    A21,
    A31,
    A32,
    A41,
    A42,
    A43,
    A51,
    A52,
    A53,
    A54,
    A61,
    A62,
    A63,
    A64,
    A65,
    B1,
    B3,
    B4,
    B5,
    B6,
    C2,
    C3,
    C4,
    C5,
    GRID_TOL,
    PI_ALPHA,
    STATUS_MAX_STEPS,
    STATUS_NONFINITE,
    STATUS_OK,
    STATUS_UNDERFLOW,
    _dopri_error,
    _pi_factor,
)

#: status code of :func:`newmark`: the Newton iterations did not converge
STATUS_NEWTON = 4
#: Newton iterations per Newmark step before :func:`newmark` gives up
NEWTON_MAX_ITER = 60
#: full Newton steps before the iteration is relaxed (halved increments), which
#: settles it onto a kink of the force (a contact closing with a damping jump)
NEWTON_FULL_ITER = 12


#: what each status code of the integrators means, for the models' error messages
STATUS_REASONS = {
    STATUS_NONFINITE: "the state became non-finite or unbounded",
    STATUS_UNDERFLOW: "the step size underflowed",
    STATUS_MAX_STEPS: "the step budget was exhausted",
    STATUS_NEWTON: "the Newton iterations did not converge",
}


@njit(cache=True, error_model="numpy")
def _solve_small(a, b, x):
    """Solve a x = b for a small dense system by Gaussian elimination with partial
    pivoting; ``a`` and ``b`` are overwritten. Returns False if a is singular."""
    n = b.shape[0]
    for col in range(n):
        piv = col
        for r in range(col + 1, n):
            if abs(a[r, col]) > abs(a[piv, col]):
                piv = r
        if a[piv, col] == 0.0:
            return False
        if piv != col:
            for c in range(n):
                a[col, c], a[piv, c] = a[piv, c], a[col, c]
            b[col], b[piv] = b[piv], b[col]
        for r in range(col + 1, n):
            m = a[r, col] / a[col, col]
            if m != 0.0:
                for c in range(col, n):
                    a[r, c] -= m * a[col, c]
                b[r] -= m * b[col]
    for r in range(n - 1, -1, -1):
        s = b[r]
        for c in range(r + 1, n):
            s -= a[r, c] * x[c]
        x[r] = s / a[r, r]
    return True


def _newmark(p, mass, x0, v0, h_out, n_sub, n_out, x_scale, newton_tol, bound,
            out_x, out_v, out_a):
    """Newmark-beta, average acceleration (gamma = 1/2, beta = 1/4), with Newton
    iterations on the non-linear force (the bound ``force``, see :func:`newmark_for`)
    and its tangent matrices.

    Integrates M a + f(t, x, v) = 0 from t = 0 with ``n_sub`` equal steps
    dt = h_out / n_sub per output interval and records x, v, a at t = k h_out,
    k = 0 .. n_out - 1. Each step solves for x_{n+1} with
    a_{n+1} = 4 (x_{n+1} - x_n - dt v_n) / dt^2 - a_n and
    v_{n+1} = 2 (x_{n+1} - x_n) / dt - v_n (Newmark 1959; Hughes, *The Finite Element
    Method*, ch. 9): residual R = M a_{n+1} + f(t_{n+1}, x_{n+1}, v_{n+1}), Jacobian
    4 M / dt^2 + kx + 2 kv / dt. The scheme is implicit, unconditionally stable for
    linear systems, second-order accurate and free of numerical damping. Newton stops
    when every increment is below ``newton_tol * x_scale``; after
    :data:`NEWTON_FULL_ITER` iterations the increments are halved (so the iteration
    settles on a kink of f instead of cycling across it).

    Parameters
    ----------
    p : ndarray
        Parameters passed to ``force``.
    mass : ndarray (n, n)
        Mass matrix M, kg.
    x0, v0 : ndarray (n,)
        Initial displacement (m) and velocity (m/s).
    h_out : float
        Output spacing, s.
    n_sub : int
        Steps per output interval (>= 1).
    n_out : int
        Number of output points.
    x_scale : ndarray (n,)
        Characteristic displacement of each coordinate, m (> 0).
    newton_tol : float
        Relative Newton tolerance on the increments.
    bound : float
        The state is declared unbounded when |x_i| > bound * x_scale_i.
    out_x, out_v, out_a : ndarray (n_out, n)
        Filled with the displacement, velocity and acceleration at the output times.

    Returns
    -------
    status : int
        0 ok, 1 non-finite or unbounded state, 4 Newton failed to converge.
    n_steps : int
        Steps taken.
    max_iter : int
        Largest number of Newton iterations any step needed.
    t_fail : float
        Time reached, s.
    """
    n = x0.shape[0]
    dt = h_out / n_sub
    f = np.zeros(n)
    kx = np.zeros((n, n))
    kv = np.zeros((n, n))
    jac = np.zeros((n, n))
    rhs = np.zeros(n)
    dx = np.zeros(n)
    x = x0.copy()
    v = v0.copy()
    a = np.zeros(n)
    # initial acceleration from the equations of motion: M a0 = -f(0, x0, v0)
    force(0.0, x, v, p, f, kx, kv)  # noqa: F821 (bound by _bind)
    for i in range(n):
        rhs[i] = -f[i]
        for j in range(n):
            jac[i, j] = mass[i, j]
    if not _solve_small(jac, rhs, a):
        return STATUS_NONFINITE, 0, 0, 0.0
    for i in range(n):
        out_x[0, i] = x[i]
        out_v[0, i] = v[i]
        out_a[0, i] = a[i]
    xn = np.zeros(n)
    vn = np.zeros(n)
    an = np.zeros(n)
    c_a = 4.0 / (dt * dt)
    c_v = 2.0 / dt
    n_steps = 0
    max_iter = 0
    for k in range(1, n_out):
        for s in range(n_sub):
            t1 = ((k - 1) * n_sub + s + 1) * dt
            for i in range(n):
                xn[i] = x[i]
                vn[i] = v[i]
                an[i] = a[i]
            # predictor: constant acceleration over the step
            for i in range(n):
                x[i] = xn[i] + dt * vn[i] + 0.5 * dt * dt * an[i]
            converged = False
            it = 0
            while it < NEWTON_MAX_ITER:
                it += 1
                for i in range(n):
                    a[i] = c_a * (x[i] - xn[i] - dt * vn[i]) - an[i]
                    v[i] = c_v * (x[i] - xn[i]) - vn[i]
                force(t1, x, v, p, f, kx, kv)  # noqa: F821 (bound by _bind)
                for i in range(n):
                    r = f[i]
                    for j in range(n):
                        r += mass[i, j] * a[j]
                        jac[i, j] = c_a * mass[i, j] + kx[i, j] + c_v * kv[i, j]
                    rhs[i] = -r
                if not _solve_small(jac, rhs, dx):
                    return STATUS_NONFINITE, n_steps, max_iter, t1
                relax = 1.0 if it <= NEWTON_FULL_ITER else 0.5
                small = True
                for i in range(n):
                    x[i] += relax * dx[i]
                    if not abs(dx[i]) <= newton_tol * x_scale[i]:
                        small = False
                if small:
                    converged = True
                    break
            for i in range(n):
                a[i] = c_a * (x[i] - xn[i] - dt * vn[i]) - an[i]
                v[i] = c_v * (x[i] - xn[i]) - vn[i]
                if not (abs(x[i]) <= bound * x_scale[i] and math.isfinite(v[i])
                        and math.isfinite(a[i])):
                    return STATUS_NONFINITE, n_steps, max_iter, t1
            n_steps += 1
            if it > max_iter:
                max_iter = it
            if not converged:
                return STATUS_NEWTON, n_steps, max_iter, t1
        for i in range(n):
            out_x[k, i] = x[i]
            out_v[k, i] = v[i]
            out_a[k, i] = a[i]
    return STATUS_OK, n_steps, max_iter, (n_out - 1) * h_out


def _second_order_rhs(t, y, p, minv, f, kx, kv, dy):
    """dy/dt of the first-order form y = (x, v) of M a + f(t, x, v) = 0."""
    n = f.shape[0]
    force(t, y[:n], y[n:], p, f, kx, kv)  # noqa: F821 (bound by _bind)
    for i in range(n):
        dy[i] = y[n + i]
        s = 0.0
        for j in range(n):
            s -= minv[i, j] * f[j]
        dy[n + i] = s


def _dopri5_second_order(p, minv, y0, h_out, n_out, rtol, atol, h_max, max_steps,
                        out_y, out_dy):
    """Dormand-Prince 5(4) with error control on M a + f(t, x, v) = 0 (the bound
    ``force``, see :func:`dopri5_for`), written as y' = (v, -M^-1 f) with y = (x, v).

    Steps never cross an output time t = k h_out: a step that would is shortened to
    end on it, so the outputs are the method's own step ends (no interpolation).
    Error norm: RMS over components of err_i / (atol_i + rtol |y_i|), with Hairer's
    PI step control (as :func:`dopri5`).

    Parameters
    ----------
    p : ndarray
        Parameters passed to ``force``.
    minv : ndarray (n, n)
        Inverse mass matrix, 1/kg.
    y0 : ndarray (2 n,)
        Initial (x, v).
    h_out : float
        Output spacing, s.
    n_out : int
        Number of output points.
    rtol : float
    atol : ndarray (2 n,)
        Absolute tolerance per component (m, m/s).
    h_max : float
        Largest step, s.
    max_steps : int
        Budget of accepted plus rejected steps.
    out_y, out_dy : ndarray (n_out, 2 n)
        Filled with y and y' at the output times.

    Returns
    -------
    status : int
        0 ok, 1 non-finite state, 2 step underflow, 3 step budget exhausted.
    n_acc, n_rej : int
        Accepted and rejected steps.
    h_min : float
        Smallest accepted step, s.
    t_fail : float
        Time reached, s.
    """
    m = y0.shape[0]
    n = m // 2
    f = np.zeros(n)
    kx = np.zeros((n, n))
    kv = np.zeros((n, n))
    y = y0.copy()
    k1 = np.zeros(m)
    k2 = np.zeros(m)
    k3 = np.zeros(m)
    k4 = np.zeros(m)
    k5 = np.zeros(m)
    k6 = np.zeros(m)
    k7 = np.zeros(m)
    ys = np.zeros(m)
    y5 = np.zeros(m)
    _second_order_rhs(0.0, y, p, minv, f, kx, kv, k1)
    for i in range(m):
        out_y[0, i] = y[i]
        out_dy[0, i] = k1[i]
    t = 0.0
    h = min(h_max, h_out)
    h_min = math.inf
    n_acc = 0
    n_rej = 0
    err_prev = 1e-4
    rejected = False
    k = 1
    while k < n_out:
        if n_acc + n_rej >= max_steps:
            return STATUS_MAX_STEPS, n_acc, n_rej, h_min, t
        t_next = k * h_out
        h_try = min(h, h_max)
        lands = t + h_try >= t_next - GRID_TOL * h_out
        if lands:
            h_try = t_next - t
        if h_try <= 1e-14 * max(t_next, h_out):
            return STATUS_UNDERFLOW, n_acc, n_rej, h_min, t
        for i in range(m):
            ys[i] = y[i] + h_try * A21 * k1[i]
        _second_order_rhs(t + C2 * h_try, ys, p, minv, f, kx, kv, k2)
        for i in range(m):
            ys[i] = y[i] + h_try * (A31 * k1[i] + A32 * k2[i])
        _second_order_rhs(t + C3 * h_try, ys, p, minv, f, kx, kv, k3)
        for i in range(m):
            ys[i] = y[i] + h_try * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i])
        _second_order_rhs(t + C4 * h_try, ys, p, minv, f, kx, kv, k4)
        for i in range(m):
            ys[i] = y[i] + h_try * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i])
        _second_order_rhs(t + C5 * h_try, ys, p, minv, f, kx, kv, k5)
        for i in range(m):
            ys[i] = y[i] + h_try * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i]
                                    + A65 * k5[i])
        _second_order_rhs(t + h_try, ys, p, minv, f, kx, kv, k6)
        for i in range(m):
            y5[i] = y[i] + h_try * (B1 * k1[i] + B3 * k3[i] + B4 * k4[i] + B5 * k5[i]
                                    + B6 * k6[i])
        t_new = t_next if lands else t + h_try
        _second_order_rhs(t_new, y5, p, minv, f, kx, kv, k7)
        err = _dopri_error(h_try, k1, k3, k4, k5, k6, k7, y, y5, atol, rtol, m)
        if not math.isfinite(err):
            err = 1e10
        if err <= 1.0:
            for i in range(m):
                y[i] = y5[i]
                k1[i] = k7[i]
                if not math.isfinite(y[i]):
                    return STATUS_NONFINITE, n_acc, n_rej, h_min, t_new
            t = t_new
            n_acc += 1
            if h_try < h_min:
                h_min = h_try
            fac = _pi_factor(err, err_prev, rejected)
            rejected = False
            err_prev = max(err, 1e-4)
            # a step cut short by the grid keeps the step size the error allows
            h = max(h, h_try) * fac if lands else h_try * fac
            if lands:
                for i in range(m):
                    out_y[k, i] = y[i]
                    out_dy[k, i] = k1[i]
                k += 1
        else:
            n_rej += 1
            rejected = True
            h = h_try * max(0.2, 0.9 * err ** -PI_ALPHA)
    return STATUS_OK, n_acc, n_rej, h_min, t


#: gap left on each side of a break by :func:`rk4_for`'s integrator, s: the last step
#: before a break ends this far ahead of it and the next starts as far after it, so no
#: stage evaluates f on the far side of a jump (the state is carried over unchanged)
EVENT_GAP = 1e-11
#: a gap's root is located to this fraction of the step (:func:`_gap_root`): a kink
#: left this far inside a step costs an error of order (ROOT_TOL h)^(n + 1) for a
#: contact law delta^n, far below the step's own
ROOT_TOL = 1e-9
#: steps the step next to a contact's kink is split into, ending at fractions
#: (k / GRADE_STEPS) ** GRADE_POWER of it from the kink: a step starting on a load
#: K tau^n (n = 10/9) errs by Simpson's rule on it, 1.6e-3 K h^(n + 1); 4 steps at
#: (k / 4)^2 err 1.5e-5 (110x less, for 3 more steps per closure and opening)
GRADE_STEPS = 4
GRADE_POWER = 2


@njit(cache=True, error_model="numpy", inline="always")
def _minv_times(minv, f, out):
    """out = -M^-1 f: the acceleration of M a + f = 0."""
    n = f.shape[0]
    for i in range(n):
        s = 0.0
        for j in range(n):
            s -= minv[i, j] * f[j]
        out[i] = s


@njit(cache=True, error_model="numpy", inline="always")
def _quintic_acc(h, x0, v0, a0, x1, v1, a1, c):
    """Coefficients of the second derivative of a step's quintic Hermite interpolant:
    a(s) = c[0] + c[1] s + c[2] s^2 + c[3] s^3 at s = (t - t0) / h, written into c
    (4, n), from the step's end states (x, v, a) and its length h. Once per step, so
    that each output time in it costs three multiply-adds per component."""
    for i in range(x0.shape[0]):
        dp = (x0[i] - x1[i]) / (h * h)
        m0, m1 = v0[i] / h, v1[i] / h
        c[0, i] = a0[i]
        c[1, i] = -60.0 * dp - 36.0 * m0 - 24.0 * m1 - 9.0 * a0[i] + 3.0 * a1[i]
        c[2, i] = 180.0 * dp + 96.0 * m0 + 84.0 * m1 + 18.0 * a0[i] - 12.0 * a1[i]
        c[3, i] = -120.0 * dp - 60.0 * (m0 + m1) - 10.0 * (a0[i] - a1[i])


@njit(cache=True, error_model="numpy", inline="always")
def _quintic_out(t0, h, x0, v0, a0, x1, v1, a1, c, tk, k, with_xv, out_x, out_v, out_a):
    """Record at tk in [t0, t0 + h] the quintic Hermite interpolant of a step's end
    states (x, v, a): its second derivative (the acceleration, accurate to O(h^4), the
    order of the method) from the coefficients ``c`` of :func:`_quintic_acc` and, if
    ``with_xv``, its value and first derivative."""
    s = (tk - t0) / h
    for i in range(x0.shape[0]):
        out_a[k, i] = c[0, i] + s * (c[1, i] + s * (c[2, i] + s * c[3, i]))
    if not with_xv:
        return
    s2 = s * s
    s3 = s2 * s
    s4 = s3 * s
    s5 = s4 * s
    h2 = h * h
    # weights of x0 - x1 (plus x1), h v0, h v1, h^2 a0, h^2 a1 in x and in h v
    x_0, x_1 = 1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5, s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5
    x_2, x_3 = -4.0 * s3 + 7.0 * s4 - 3.0 * s5, 0.5 * (s2 - 3.0 * s3 + 3.0 * s4 - s5)
    x_4 = 0.5 * (s3 - 2.0 * s4 + s5)
    v_0, v_1 = -30.0 * s2 + 60.0 * s3 - 30.0 * s4, 1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4
    v_2 = -12.0 * s2 + 28.0 * s3 - 15.0 * s4
    v_3 = 0.5 * (2.0 * s - 9.0 * s2 + 12.0 * s3 - 5.0 * s4)
    v_4 = 0.5 * (3.0 * s2 - 8.0 * s3 + 5.0 * s4)
    for i in range(x0.shape[0]):
        dp, m0, m1, c0, c1 = x0[i] - x1[i], h * v0[i], h * v1[i], h2 * a0[i], h2 * a1[i]
        out_x[k, i] = x1[i] + x_0 * dp + x_1 * m0 + x_2 * m1 + x_3 * c0 + x_4 * c1
        out_v[k, i] = (v_0 * dp + v_1 * m0 + v_2 * m1 + v_3 * c0 + v_4 * c1) / h


@njit(cache=True, error_model="numpy")
def _no_gaps(t, x, p, g):
    """The gap function of a force with no kinks in x (``n_gaps`` 0): nothing to fill."""


def _gap_root(t0, h, x, v, a, x1, v1, a1, coef, j, p, g, sx, sv, sa):
    """Where gap j of ``gaps`` changes sign in the step [t0, t0 + h], s: the root of the
    gap along the quintic Hermite interpolant of the step's end states (x, v, a), by
    Illinois regula falsi until the bracket is :data:`ROOT_TOL` of the step, its end on
    the gap's new side. t0 if the interpolant keeps one sign over the step (a gap a
    restart left a rounding's width on the far side of its zero). ``g`` is scratch
    (n_gaps,), ``sx``, ``sv``, ``sa`` (1, n)."""
    gaps(t0, x, p, g)  # noqa: F821 (bound by _bind)
    ga = g[j]
    gaps(t0 + h, x1, p, g)  # noqa: F821
    gb = g[j]
    if (ga > 0.0) == (gb > 0.0):
        return t0
    lo, hi = 0.0, 1.0
    last = 0  # side the previous iterate replaced: Illinois halves the other end's value
    while hi - lo > ROOT_TOL:
        s = (lo * gb - hi * ga) / (gb - ga)
        s = min(max(s, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
        _quintic_out(t0, h, x, v, a, x1, v1, a1, coef, t0 + s * h, 0, True, sx, sv, sa)
        gaps(t0 + s * h, sx[0], p, g)  # noqa: F821
        if (g[j] > 0.0) == (ga > 0.0):
            lo, ga = s, g[j]
            if last == -1:
                gb *= 0.5
            last = -1
        else:
            hi, gb = s, g[j]
            if last == 1:
                ga *= 0.5
            last = 1
    return t0 + hi * h


def _rk4_second_order(p, minv, x0, v0, h_out, n_out, breaks, seg_dt, n_gaps, gap_tol,
                      bound, x_scale, xv_every, out_x, out_v, out_a):
    """Classical fixed-step Runge-Kutta 4 on M a + f(t, x, v) = 0 (the bound ``force``,
    see :func:`rk4_for`), restarted at the known non-smooth points of f in t and where a
    gap of f's kinks in x changes sign.

    The time axis [0, (n_out - 1) h_out] is cut at ``breaks`` (sorted times where f
    is not smooth in t: fault edges and ramp ends); segment i (between break i - 1 and
    break i) is covered in equal steps no longer than ``seg_dt[i]``, its last step ending
    :data:`EVENT_GAP` before the break and the next segment starting as far after it,
    with f re-evaluated there (so the method keeps its fourth order across a sharp
    edge). Within a segment, f may have kinks in x where one of the ``n_gaps`` gaps
    g(t, x) of the bound ``gaps`` (a contact's deflection) changes sign: when a step
    ends with a gap's sign changed, it is dropped and retaken up to the gap's root
    (:func:`_gap_root`), so that no step integrates across a kink, and the step on the
    kink's loaded side (before an opening, after a closure) is split into
    :data:`GRADE_STEPS` steps graded towards the kink; the rest of the segment is
    re-divided from there. Steps are independent of the output grid: the outputs
    at t = k h_out are the quintic Hermite interpolant of the step ends (x, v and the
    acceleration a = -M^-1 f, which is the next step's first stage: four evaluations of f
    per step).

    Parameters
    ----------
    p : ndarray
        Parameters passed to ``force`` and ``gaps``.
    minv : ndarray (n, n)
        Inverse mass matrix, 1/kg.
    x0, v0 : ndarray (n,)
        Initial displacement (m) and velocity (m/s).
    h_out : float
        Output spacing, s.
    n_out : int
        Number of output points.
    breaks : ndarray (n_breaks,)
        Sorted break times in (0, (n_out - 1) h_out), s.
    seg_dt : ndarray (n_breaks + 1,)
        Largest step of each segment, s (> 0).
    n_gaps : int
        Number of gaps ``gaps`` fills (0: no restarts on gaps).
    gap_tol : float
        A sign change restarts only if the gap reaches gap_tol on its positive side at
        one of the step's ends (a contact's compression, m: the kink's load over the
        step); 0 restarts at every one.
    bound : float
        The state is declared unbounded when |x_i| > bound * x_scale_i.
    x_scale : ndarray (n,)
        Characteristic displacement of each coordinate, m (> 0).
    xv_every : int
        Record x and v only at every ``xv_every``-th output time (k a multiple of it;
        the other rows are left as they are); a at every one.
    out_x, out_v, out_a : ndarray (n_out, n)
        Filled with the displacement, velocity and acceleration at the output times.

    Returns
    -------
    status : int
        0 ok, 1 non-finite or unbounded state.
    n_steps : int
        Steps taken (the dropped ones included).
    n_restarts : int
        Restarts at gap sign changes.
    t_fail : float
        Time reached, s.
    """
    n = x0.shape[0]
    f = np.zeros(n)
    kx = np.zeros((n, n))
    kv = np.zeros((n, n))
    x = x0.copy()
    v = v0.copy()
    a = np.zeros(n)
    xs = np.zeros(n)
    vs = np.zeros(n)
    x1 = np.zeros(n)
    v1 = np.zeros(n)
    a1 = np.zeros(n)
    a2 = np.zeros(n)
    a3 = np.zeros(n)
    a4 = np.zeros(n)
    coef = np.zeros((4, n))
    g = np.zeros(n_gaps)
    g_root = np.zeros(n_gaps)  # the root finder's
    g_start = np.zeros(n_gaps)  # the gaps at the step's start
    side = np.zeros(n_gaps, dtype=np.bool_)  # each gap > 0 at the step's start
    sx = np.zeros((1, n))
    sv = np.zeros((1, n))
    sa = np.zeros((1, n))
    plan = np.zeros(2 * GRADE_STEPS)  # step ends planned around a crossing, s
    cross_t, cross_j, cross_side = -1.0, -1, False  # the planned crossing
    xv_left = xv_every  # outputs to the next with x and v (k = 0 is written first)
    t_end = (n_out - 1) * h_out
    n_steps = 0
    n_restarts = 0
    k = 0  # next output index
    t = 0.0
    for seg in range(breaks.shape[0] + 1):
        t_stop = breaks[seg] - EVENT_GAP if seg < breaks.shape[0] else t_end
        if seg > 0:
            t = breaks[seg - 1] + EVENT_GAP
        # f changes at a break: the first stage is evaluated afresh after it
        force(t, x, v, p, f, kx, kv)  # noqa: F821 (bound by _bind)
        _minv_times(minv, f, a)
        if n_gaps > 0:
            gaps(t, x, p, g)  # noqa: F821
        for j in range(n_gaps):
            side[j] = g[j] > 0.0
            g_start[j] = g[j]
        if k == 0:
            for i in range(n):
                out_x[0, i] = x[i]
                out_v[0, i] = v[i]
                out_a[0, i] = a[i]
            k = 1
        n_plan = i_plan = 0  # no planned steps: equal steps to the segment's end
        cross_j = -1
        while t < t_stop:
            t0 = t
            if i_plan < n_plan:
                t1 = plan[i_plan]
            else:
                n_left = max(1, int(math.ceil((t_stop - t0) / seg_dt[seg] - 1e-9)))
                t1 = t_stop if n_left == 1 else t0 + (t_stop - t0) / n_left
            h = t1 - t0
            # stages 2 and 3 at the midpoint, 4 at the end (y' = (v, a))
            for i in range(n):
                xs[i] = x[i] + 0.5 * h * v[i]
                vs[i] = v[i] + 0.5 * h * a[i]
            force(t0 + 0.5 * h, xs, vs, p, f, kx, kv)  # noqa: F821
            _minv_times(minv, f, a2)
            for i in range(n):
                xs[i] = x[i] + 0.5 * h * vs[i]
                vs[i] = v[i] + 0.5 * h * a2[i]
            force(t0 + 0.5 * h, xs, vs, p, f, kx, kv)  # noqa: F821
            _minv_times(minv, f, a3)
            for i in range(n):
                x1[i] = x[i] + h * vs[i]
                v1[i] = v[i] + h * a3[i]
            force(t1, x1, v1, p, f, kx, kv)  # noqa: F821
            _minv_times(minv, f, a4)
            for i in range(n):
                x1[i] = x[i] + h / 6.0 * (v[i] + 2.0 * (v[i] + 0.5 * h * a[i])
                                          + 2.0 * vs[i] + v1[i])
                v1[i] = v[i] + h / 6.0 * (a[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i])
            force(t1, x1, v1, p, f, kx, kv)  # noqa: F821
            _minv_times(minv, f, a1)
            n_steps += 1
            if n_gaps > 0:
                gaps(t1, x1, p, g)  # noqa: F821
                t_cross = t1
                crossed = -1
                for j in range(n_gaps):
                    if j == cross_j and t1 == cross_t:
                        continue  # the planned crossing reached
                    # a sign change over the step whose loaded side reaches gap_tol
                    if (g[j] > 0.0) == side[j] or max(g[j], g_start[j]) < gap_tol:
                        continue
                    if crossed == -1:
                        _quintic_acc(h, x, v, a, x1, v1, a1, coef)
                    tj = _gap_root(t0, h, x, v, a, x1, v1, a1, coef, j, p, g_root,
                                   sx, sv, sa)
                    if t0 < tj < t_cross:
                        t_cross = tj
                        crossed = j
                if crossed >= 0:
                    # the step is dropped; the next ones end on the crossing, graded
                    # towards it if the contact opens there (its load's kink ends them),
                    # and, if it closes, start from it graded
                    n_restarts += 1
                    n_plan = i_plan = 0
                    opens = side[crossed]
                    for s in range(1, GRADE_STEPS if opens else 1):
                        plan[n_plan] = t0 + (t_cross - t0) * (
                            1.0 - ((GRADE_STEPS - s) / GRADE_STEPS) ** GRADE_POWER)
                        n_plan += 1
                    plan[n_plan] = t_cross
                    n_plan += 1
                    if not opens:
                        end = min(t_cross + seg_dt[seg], t_stop)
                        for s in range(1, GRADE_STEPS):
                            plan[n_plan] = t_cross + (end - t_cross) * (
                                s / GRADE_STEPS) ** GRADE_POWER
                            n_plan += 1
                        plan[n_plan] = end
                        n_plan += 1
                    cross_t, cross_j, cross_side = t_cross, crossed, not opens
                    continue
                for j in range(n_gaps):
                    side[j] = g[j] > 0.0
                    g_start[j] = g[j]
                if t1 == cross_t:  # it crossed over, whatever side rounding left it on
                    side[cross_j] = cross_side
                    cross_j = -1
            i_plan += 1
            for i in range(n):
                if not (abs(x1[i]) <= bound * x_scale[i] and math.isfinite(v1[i])
                        and math.isfinite(a1[i])):
                    return STATUS_NONFINITE, n_steps, n_restarts, t1
            if k < n_out and k * h_out <= t1 + GRID_TOL * h_out:
                _quintic_acc(t1 - t0, x, v, a, x1, v1, a1, coef)
            while k < n_out and k * h_out <= t1 + GRID_TOL * h_out:
                # x and v at every xv_every-th output (counted down: an integer division
                # per output costs as much as the interpolation)
                xv_left -= 1
                _quintic_out(t0, t1 - t0, x, v, a, x1, v1, a1, coef, min(k * h_out, t1), k,
                             xv_left == 0, out_x, out_v, out_a)
                if xv_left == 0:
                    xv_left = xv_every
                k += 1
            for i in range(n):
                x[i] = x1[i]
                v[i] = v1[i]
                a[i] = a1[i]
            t = t1
    return STATUS_OK, n_steps, n_restarts, t_end


_BOUND: dict = {}


def _bind(template, force, name: str, cache: bool, **extra):
    """A numba-compiled copy of ``template`` whose global ``force`` is ``force`` (and
    whose other globals named in ``extra`` are those)."""
    import types

    key = (template.__name__, force, cache, *extra.values())
    if key not in _BOUND:
        glb = dict(template.__globals__, force=force, **extra)
        fn = types.FunctionType(template.__code__, glb, name, template.__defaults__)
        fn.__qualname__ = name
        fn.__doc__ = template.__doc__
        _BOUND[key] = njit(cache=cache, error_model="numpy")(fn)
    return _BOUND[key]


def newmark_for(force, *, cache: bool = True):
    """The Newmark-beta integrator compiled for one model's force function.

    Parameters
    ----------
    force : numba function
        ``force(t, x, v, p, f, kx, kv)``: fills the generalised force f (n,) of
        M a + f(t, x, v) = 0 and its tangents kx = df/dx, kv = df/dv (n, n).
    cache : bool, optional
        Cache the machine code on disk (default True; numba keys it on this module's
        source, so use it only for forces defined in ``ballpass.simulate``, whose
        sources the package's cache stamp covers).

    Returns
    -------
    callable
        ``newmark(p, mass, x0, v0, h_out, n_sub, n_out, x_scale, newton_tol, bound,
        out_x, out_v, out_a) -> (status, n_steps, max_iter, t_fail)``; see
        :func:`_newmark`.
    """
    return _bind(_newmark, force, f"newmark_{force.__name__}", cache)


def dopri5_for(force, *, cache: bool = True):
    """Adaptive Dormand-Prince 5(4) compiled for one model's force function.

    Parameters
    ----------
    force : numba function
        As for :func:`newmark_for`.
    cache : bool, optional
        As for :func:`newmark_for`.

    Returns
    -------
    callable
        ``dopri5(p, minv, y0, h_out, n_out, rtol, atol, h_max, max_steps, out_y,
        out_dy) -> (status, n_acc, n_rej, h_min, t_fail)``; see
        :func:`_dopri5_second_order`.
    """
    rhs = _bind(_second_order_rhs, force, f"rhs_{force.__name__}", cache)
    return _bind(_dopri5_second_order, force, f"dopri5_{force.__name__}", cache,
                 _second_order_rhs=rhs)


def rk4_for(force, gaps=None, *, cache: bool = True):
    """Fixed-step Runge-Kutta 4, restarted at known breaks and where a gap of the
    force's kinks changes sign, compiled for one model's force function.

    Parameters
    ----------
    force : numba function
        As for :func:`newmark_for`.
    gaps : numba function, optional
        ``gaps(t, x, p, g)``: fills g (n_gaps,) with functions of t and x, smooth
        within a segment, whose sign changes are the kinks of ``force`` in x (contact
        deflections: f is smooth while no gap changes sign). Default: none.
    cache : bool, optional
        As for :func:`newmark_for`.

    Returns
    -------
    callable
        ``rk4(p, minv, x0, v0, h_out, n_out, breaks, seg_dt, n_gaps, gap_tol, bound,
        x_scale, xv_every, out_x, out_v, out_a) -> (status, n_steps, n_restarts,
        t_fail)``; see
        :func:`_rk4_second_order`.
    """
    gaps = _no_gaps if gaps is None else gaps
    name = f"{force.__name__}_{gaps.__name__}"
    root = _bind(_gap_root, force, f"gap_root_{name}", cache, gaps=gaps)
    return _bind(_rk4_second_order, force, f"rk4_{name}", cache, gaps=gaps, _gap_root=root)
