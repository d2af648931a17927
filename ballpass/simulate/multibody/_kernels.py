"""Numba kernels of the planar multibody bearing (Nakhaeinejad & Bryant 2011): the
right-hand side, the fixed-step RK4 loop with its recorders, and the mechanical energy.

State (``nd = 6 + 3 Z`` coordinates, then their rates; SI units, global frame, x along
the load line towards the centre of the load zone, y at +90 deg in the direction of
rotation, angles counter-clockwise from x)::

    q = [x_i, y_i, th_i,  x_o, y_o,  th_c,  x_0, y_0, th_0,  x_1, y_1, th_1, ...]
    y = [q, dq/dt, F_inner_0 .. F_inner_Z-1, F_outer_0 .. F_outer_Z-1]

The last 2 Z states are the traction forces of the contacts (N, on the ball along the
contact tangent z x n), which relax towards mu(s) Q over the relaxation length.

i = inner race (with the shaft share), o = outer race (in its housing; its rotation is
locked by the housing fit), c = cage (rotation about the housing centre), 0..Z-1 the
balls (centre and spin angle). Kernels take plain arrays; validation and the physics
documentation live in :mod:`ballpass.simulate.multibody`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# parameter vector p
(P_Z, P_RB, P_RI, P_RO, P_KI, P_KO, P_TAU, P_MI, P_JI, P_MO, P_MB, P_JB, P_JC, P_RP,
 P_KPOCK, P_CPOCK, P_EPOCK, P_KH, P_CH, P_FR, P_G, P_W0, P_W1, P_T, P_KD, P_CD, P_TLOAD,
 P_NU, P_F0, P_DPMM, P_WBD, P_HD, P_TRACTION, P_UFLOOR, P_WEPS, P_LUB, P_RELAX,
 P_POCK_SIN2, P_PITCH_COS, P_PITCH_SIN) = range(40)
N_PARAMS = 40
# P_POCK_SIN2: sin^2 of the pocket play's half angle (pocket_clearance / r_p), shrunk by
# 1e-9 against rounding (-1 when the play exceeds 90 deg): below it a ball cannot touch
# its pocket, which spares the angle of every free ball; P_PITCH_COS, P_PITCH_SIN: cos and
# sin of the pocket pitch 2 pi / Z

# fault table columns: kind, centre in the body frame (rad), half width (m), depth (m),
# ball index (ball faults), effective radius of the pair at the inner and the outer
# contact (m; the notch profile follows the mating surface's relative curvature), the
# centre's direction in the body frame (cos, sin) and the cosine of the notch's half
# angle on its surface widened by 1e-9 rad (a contact point whose direction has a
# smaller cosine cannot be on the notch)
(F_KIND, F_CENTRE, F_HALF, F_DEPTH, F_ELEM, F_REFF_I, F_REFF_O, F_COS, F_SIN,
 F_COSHALF) = range(10)
N_FCOLS = 10
KIND_OUTER, KIND_INNER, KIND_BALL = 0, 1, 2

# sensor table columns: cos and sin of the sensor angle, transmission attenuation kappa
S_COS, S_SIN, S_ATT = 0, 1, 2
N_SCOLS = 3

STATUS_OK, STATUS_NONFINITE = 0, 1

# Every kernel below but integrate_fixed allocates nothing and is compiled without numba's
# runtime (**_NO_RUNTIME): numba then emits no reference counting of the array arguments
# (an atomic increment and decrement per array per call, a quarter of an RK4 step's time
# outside the right-hand side itself); the arithmetic is unchanged. The switch is
# private to numba: where a numba lacks it, the kernels compile as usual.
try:
    from numba.core.cpu import CPUTargetOptions
    _NO_RUNTIME = {"_nrt": False} if hasattr(CPUTargetOptions, "_nrt") else {}
except ImportError:  # pragma: no cover - numba moved its options
    _NO_RUNTIME = {}
TWO_PI = 2.0 * math.pi


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def wrap_pi(a):
    """Wrap an angle (rad) to [-pi, pi)."""
    return a - TWO_PI * math.floor((a + math.pi) / TWO_PI)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def mu_slide_roll(s, w_bd, hd_ratio):
    """Traction coefficient at slide-roll ratio s >= 0: Nakhaeinejad & Bryant eq. 13
    mu_bd = (-0.1 + 22.28 s) exp(-181.46 s) + 0.1, blended by eq. 12 with weight w_bd
    with the hydrodynamic law mu_hd = hd_ratio * mu_bd."""
    mu_bd = (-0.1 + 22.28 * s) * math.exp(-181.46 * s) + 0.1
    return mu_bd * (w_bd + (1.0 - w_bd) * hd_ratio)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def notch_drop(x, half, depth, reff):
    """Extra clearance (m) opened by a rectangular notch of half width ``half`` and
    depth ``depth`` at arc offset ``x`` of the contact from its centre: the mating
    surface (relative radius ``reff``) sinks until it meets the nearer corner,
    reff - sqrt(reff^2 - a^2) with a = half - |x|, at most the depth."""
    a = half - abs(x)
    if a <= 0.0:
        return 0.0
    if a >= reff:
        return depth
    drop = reff - math.sqrt(reff * reff - a * a)
    return drop if drop < depth else depth


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def theta_ref(t, p):
    """Drive (motor) angle and speed at t: the scene's speed profile for t >= 0 and its
    start speed during the settling time before 0."""
    if t <= 0.0:
        return p[P_W0] * t, p[P_W0]
    a = (p[P_W1] - p[P_W0]) / p[P_T]
    return p[P_W0] * t + 0.5 * a * t * t, p[P_W0] + a * t


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _race_drop(faults, kind, bx, by, radius, j, which):
    """Largest notch drop at a contact whose point sits in direction (bx, by) (unit
    vector, body frame) on a race of ``kind`` (radius m), or on ball j's surface (kind
    ball, ``which`` 0 = outer contact, 1 = inner); also flags (bit per fault) which
    faults hold the contact. A point whose direction is further from a notch's centre
    than its half angle is skipped before the arc offset (an atan2) is computed."""
    drop = 0.0
    flags = 0
    for f in range(faults.shape[0]):
        k = int(faults[f, F_KIND])
        if k != kind or (k == KIND_BALL and int(faults[f, F_ELEM]) != j):
            continue
        c, s = faults[f, F_COS], faults[f, F_SIN]
        dot = bx * c + by * s
        if dot <= faults[f, F_COSHALF]:
            continue
        x = radius * math.atan2(by * c - bx * s, dot)
        half = faults[f, F_HALF]
        if abs(x) < half:
            flags |= 1 << f
            reff = faults[f, F_REFF_I] if which == 1 else faults[f, F_REFF_O]
            d = notch_drop(x, half, faults[f, F_DEPTH], reff)
            if d > drop:
                drop = d
    return drop, flags


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _has_ball_faults(faults):
    """Whether any ball carries a fault (else no ball looks its own faults up)."""
    for f in range(faults.shape[0]):
        if int(faults[f, F_KIND]) == KIND_BALL:
            return True
    return False


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _has_ball_fault(faults, j):
    """Whether ball j carries a fault."""
    for f in range(faults.shape[0]):
        if int(faults[f, F_KIND]) == KIND_BALL and int(faults[f, F_ELEM]) == j:
            return True
    return False


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _contact_force(k, tau, delta, ddelta):
    """Normal force of a Hertz contact with Kramer damping that vanishes with the
    contact: K delta^1.5 + tau (1.5 K delta^0.5) d(delta)/dt, never pulling; exactly 0
    when separated."""
    if delta <= 0.0:
        return 0.0
    root = math.sqrt(delta)
    q = k * delta * root + tau * 1.5 * k * root * ddelta
    return q if q > 0.0 else 0.0


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _ring_loads(t, y, nd, p, sensors, exc, want_exc):
    """Forces (N) and torques (N m) on the rings and the cage other than the balls':
    the radial load, weights, drive coupling and friction torques (eqs. 15-18) and the
    housing; with ``want_exc`` writes the housing's share of each sensor's acceleration
    into ``exc``. ``nd``: index of the first rate in y. Returns (fxi, fyi, ti, fxo,
    fyo, tc)."""
    g = p[P_G]
    weps = p[P_WEPS]
    thi = y[2]
    xo, yo = y[3], y[4]
    wi = y[nd + 2]
    vxo, vyo, wc = y[nd + 3], y[nd + 4], y[nd + 5]
    # inner race: radial load, weight, drive coupling, load and seal friction (eqs. 16-17)
    th_r, w_r = theta_ref(t, p)
    fxi = p[P_FR] + p[P_MI] * g
    fyi = 0.0
    ti = p[P_KD] * (th_r - thi) + p[P_CD] * (w_r - wi) - p[P_TLOAD] * math.tanh(wi / weps)
    # outer race in the housing
    fxo_h = -p[P_KH] * xo - p[P_CH] * vxo
    fyo_h = -p[P_KH] * yo - p[P_CH] * vyo
    fxo = fxo_h + p[P_MO] * g
    fyo = fyo_h
    # cage: lubricant drag of the rolling set (eq. 18), opposing its rotation
    tc = 0.0
    if p[P_LUB] != 0.0:
        vn = p[P_NU] * abs(wi) * 30.0 / math.pi
        if vn >= 2000.0:
            t_lub = 1e-7 * p[P_F0] * vn ** (2.0 / 3.0) * p[P_DPMM] ** 3 * 1e-3
        else:
            t_lub = 160e-7 * p[P_F0] * p[P_DPMM] ** 3 * 1e-3
        tc -= t_lub * math.tanh(wc / weps)
    if want_exc:
        for s in range(sensors.shape[0]):
            exc[s] = (fxo_h * sensors[s, S_COS] + fyo_h * sensors[s, S_SIN]) / p[P_MO]
    return fxi, fyi, ti, fxo, fyo, tc


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _traction_rate(vs, ur, q, f, w_bd, hd, inv_relax):
    """dF/dt of a loaded contact's traction F (N): the lag towards mu(s) Q against the
    sliding speed ``vs`` at rolling speed ``ur`` (m/s)."""
    target = mu_slide_roll(abs(vs) / ur, w_bd, hd) * q
    if vs > 0.0:
        target = -target
    return (target - f) * ur * inv_relax


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _sensor_share(exc, sensors, nx, ny, q, mo):
    """Add an outer contact's load ``q`` (N, along (nx, ny)) to each sensor's housing
    acceleration, weighted by its transmission factor."""
    for s in range(sensors.shape[0]):
        cos_rel = nx * sensors[s, S_COS] + ny * sensors[s, S_SIN]
        kappa = sensors[s, S_ATT]
        w = math.exp(-kappa * (1.0 - cos_rel)) if kappa != 0.0 else 1.0
        exc[s] += w * q * cos_rel / mo


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _ring_rates(dydt, y, nd, p, fxi, fyi, ti, fxo, fyo, tc):
    """Rates of the rings' and the cage's coordinates and velocities."""
    for k in range(6):
        dydt[k] = y[nd + k]
    dydt[nd] = fxi / p[P_MI]
    dydt[nd + 1] = fyi / p[P_MI]
    dydt[nd + 2] = ti / p[P_JI]
    dydt[nd + 3] = fxo / p[P_MO]
    dydt[nd + 4] = fyo / p[P_MO]
    dydt[nd + 5] = tc / p[P_JC]


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _pocket(xb, yb, vxb, vyb, uc, us, wc, p):
    """Signed tangential force (N, positive ahead of the pocket centre) of the cage
    pocket on a ball at (xb, yb) moving at (vxb, vyb), its pocket centre in direction
    (uc, us), the cage turning at wc: a linear spring-damper beyond the pocket
    clearance; 0 when not touching. The ball's angle from its pocket centre is an
    atan2 only when the sine test cannot rule out a touch."""
    r2 = xb * xb + yb * yb
    dot = xb * uc + yb * us
    cr = yb * uc - xb * us
    if dot <= 0.0 or cr * cr >= p[P_POCK_SIN2] * r2:
        off = p[P_RP] * math.atan2(cr, dot)
        if abs(off) > p[P_EPOCK]:
            sgn = 1.0 if off > 0.0 else -1.0
            doff = p[P_RP] * ((xb * vyb - yb * vxb) / r2 - wc)
            fp = p[P_KPOCK] * (abs(off) - p[P_EPOCK]) + p[P_CPOCK] * doff * sgn
            if fp > 0.0:
                return sgn * fp
    return 0.0


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def rhs(t, y, dydt, p, faults, sensors, qi, qo, flags, exc, want_exc):
    """dy/dt at (t, y). The traction forces are first-order lags of the paper's
    steady law (eq. 11-13): dF/dt = (mu(s) Q - F) u_r / L, L the relaxation length
    (creep builds up over about a contact length of rolling, Johnson, Contact
    Mechanics, sec. 8.2); a separated contact applies none and its traction decays.
    Also writes the inner and outer normal contact loads of every ball (N) into
    ``qi``/``qo``, the fault flags of every contact into ``flags`` (bit f set: fault f
    holds the contact; column 0 outer, 1 inner) and, with ``want_exc``, the housing
    acceleration seen by each sensor (m/s^2) into ``exc``."""
    z = int(p[P_Z])
    nd = 6 + 3 * z
    rb, ri, ro = p[P_RB], p[P_RI], p[P_RO]
    ki, ko, tau = p[P_KI], p[P_KO], p[P_TAU]
    mb, jb = p[P_MB], p[P_JB]
    g = p[P_G]
    traction = p[P_TRACTION] != 0.0
    w_bd, hd, ufloor = p[P_WBD], p[P_HD], p[P_UFLOOR]
    has_faults = faults.shape[0] > 0
    has_ball = _has_ball_faults(faults)
    inv_relax = 1.0 / p[P_RELAX]
    inv_mb = 1.0 / mb

    xi, yi, thi = y[0], y[1], y[2]
    xo, yo, thc = y[3], y[4], y[5]
    vxi, vyi, wi = y[nd], y[nd + 1], y[nd + 2]
    vxo, vyo, wc = y[nd + 3], y[nd + 4], y[nd + 5]
    fxi, fyi, ti, fxo, fyo, tc = _ring_loads(t, y, nd, p, sensors, exc, want_exc)

    # inner race rotation (for its notches), the pocket of ball 0 and the pitch step
    ci = math.cos(thi) if has_faults else 1.0
    si = math.sin(thi) if has_faults else 0.0
    uc, us = math.cos(thc), math.sin(thc)
    pc, ps = p[P_PITCH_COS], p[P_PITCH_SIN]
    for j in range(z):
        b = 6 + 3 * j
        xb, yb, thb = y[b], y[b + 1], y[b + 2]
        vxb, vyb, wb = y[nd + b], y[nd + b + 1], y[nd + b + 2]
        fxb = mb * g
        fyb = 0.0
        tb = 0.0
        cb, sb = 1.0, 0.0
        ball_fault = has_ball and _has_ball_fault(faults, j)
        if ball_fault:
            cb, sb = math.cos(thb), math.sin(thb)
        # ---- inner contact
        dx = xb - xi
        dy = yb - yi
        dist = math.sqrt(dx * dx + dy * dy)
        inv_dist = 1.0 / dist
        nx = dx * inv_dist
        ny = dy * inv_dist
        drop = 0.0
        fl_i = 0
        if has_faults:
            # the contact point: direction n in the inner race, -n on the ball
            drop, fl_i = _race_drop(faults, KIND_INNER, nx * ci + ny * si, ny * ci - nx * si,
                                    ri, j, 1)
            if ball_fault:
                d2, f2 = _race_drop(faults, KIND_BALL, -(nx * cb + ny * sb),
                                    -(ny * cb - nx * sb), rb, j, 1)
                drop = drop if drop > d2 else d2
                fl_i |= f2
        delta = rb + ri - dist - drop
        rvx = vxb - vxi
        rvy = vyb - vyi
        q = _contact_force(ki, tau, delta, -(nx * rvx + ny * rvy))
        qi[j] = q
        if traction and q == 0.0:
            dydt[2 * nd + j] = -y[2 * nd + j] * 1e3 * ufloor * inv_relax
        if q > 0.0:
            fxb += q * nx
            fyb += q * ny
            fxi -= q * nx
            fyi -= q * ny
            if traction:
                vt = -rvx * ny + rvy * nx
                vs = vt - wb * rb - wi * ri
                om = vt * inv_dist
                ur = 0.5 * (abs((wi - om) * ri) + abs((wb - om) * rb)) + ufloor
                f = y[2 * nd + j]
                dydt[2 * nd + j] = _traction_rate(vs, ur, q, f, w_bd, hd, inv_relax)
                fxb -= f * ny
                fyb += f * nx
                fxi += f * ny
                fyi -= f * nx
                tb -= rb * f
                ti -= ri * f
        # ---- outer contact
        dx = xb - xo
        dy = yb - yo
        dist = math.sqrt(dx * dx + dy * dy)
        inv_dist = 1.0 / dist
        nx = dx * inv_dist
        ny = dy * inv_dist
        drop = 0.0
        fl_o = 0
        if has_faults:
            # the contact point: direction n in the (non-rotating) outer race and on the ball
            drop, fl_o = _race_drop(faults, KIND_OUTER, nx, ny, ro, j, 0)
            if ball_fault:
                d2, f2 = _race_drop(faults, KIND_BALL, nx * cb + ny * sb, ny * cb - nx * sb,
                                    rb, j, 0)
                drop = drop if drop > d2 else d2
                fl_o |= f2
        delta = dist + rb - ro - drop
        rvx = vxb - vxo
        rvy = vyb - vyo
        q = _contact_force(ko, tau, delta, nx * rvx + ny * rvy)
        qo[j] = q
        if traction and q == 0.0:
            dydt[2 * nd + z + j] = -y[2 * nd + z + j] * 1e3 * ufloor * inv_relax
        if q > 0.0:
            fxb -= q * nx
            fyb -= q * ny
            fxo += q * nx
            fyo += q * ny
            if want_exc:
                _sensor_share(exc, sensors, nx, ny, q, p[P_MO])
            if traction:
                vt = -rvx * ny + rvy * nx
                vs = vt + wb * rb
                om = vt * inv_dist
                ur = 0.5 * (abs(om * ro) + abs((wb - om) * rb)) + ufloor
                f = y[2 * nd + z + j]
                dydt[2 * nd + z + j] = _traction_rate(vs, ur, q, f, w_bd, hd, inv_relax)
                fxb -= f * ny
                fyb += f * nx
                fxo += f * ny
                fyo -= f * nx
                tb += rb * f
        flags[j, 0] = fl_o
        flags[j, 1] = fl_i
        # ---- cage pocket (tangential, linear spring-damper beyond the pocket clearance)
        fp = _pocket(xb, yb, vxb, vyb, uc, us, wc, p)
        if fp != 0.0:
            r = math.sqrt(xb * xb + yb * yb)
            fs = fp * p[P_RP] / r
            fxb += fs * yb / r
            fyb -= fs * xb / r
            tc += fp * p[P_RP]
        uc, us = uc * pc - us * ps, uc * ps + us * pc
        dydt[b] = vxb
        dydt[b + 1] = vyb
        dydt[b + 2] = wb
        dydt[nd + b] = fxb * inv_mb
        dydt[nd + b + 1] = fyb * inv_mb
        dydt[nd + b + 2] = tb / jb
    if not traction:
        for k in range(2 * nd, dydt.shape[0]):
            dydt[k] = 0.0
    _ring_rates(dydt, y, nd, p, fxi, fyi, ti, fxo, fyo, tc)


#: radial drag floor of a quasi-static ball, in units of m_b / tau (N s/m): it bounds
#: the radial speed of a ball touching neither race (F tau / (0.01 m_b)) and changes
#: the relaxation rate of a loaded ball (tau (k_i + k_o) ~ 100 m_b / tau on the 6205)
#: by about 1e-4
QS_DRAG_FLOOR = 1e-2


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def rhs_qs(t, y, dydt, p, faults, sensors, qi, qo, flags, exc, want_exc):
    """dy/dt at (t, y) with massless-limit (quasi-static) balls: as :func:`rhs`, but
    each ball's radial motion carries no inertia. State (``nq = 6 + 3 Z`` coordinates
    as in :func:`rhs`, then ``6 + 2 Z`` rates)::

        y = [x_i, y_i, th_i, x_o, y_o, th_c, x_0, y_0, th_0, ...,
             (rates of the first six), u_0, w_0, u_1, w_1, ...,
             F_inner_0 .. F_inner_Z-1, F_outer_0 .. F_outer_Z-1]

    u_j is ball j's speed across its radius e = (x, y) / r (about the housing centre),
    w_j its spin. Both contacts are Hertz springs with Kramer's damping, Q = K
    delta^1.5 + tau k d(delta)/dt with k = 1.5 K delta^0.5; with m_b r'' dropped,
    the radial balance Q_i (n_i.e) - Q_o (n_o.e) + m_b u^2 / r + m_b g e_x +
    (traction along e) = 0 is linear in r' (each Q is affine in it): r' solves it over
    the contacts that press (a contact whose Q would pull is left out and the balance
    solved again), and the ball relaxes onto its elastic balance with the time tau.
    The tangential motion (m_b (u' + r' u / r) = the tangential force) and the spin
    stay dynamic. Ball faults are not modelled (refused by ``build``)."""
    z = int(p[P_Z])
    nq = 6 + 3 * z
    i_f = nq + 6 + 2 * z
    rb, ri, ro = p[P_RB], p[P_RI], p[P_RO]
    ki, ko, tau = p[P_KI], p[P_KO], p[P_TAU]
    mb, jb = p[P_MB], p[P_JB]
    g = p[P_G]
    traction = p[P_TRACTION] != 0.0
    w_bd, hd, ufloor = p[P_WBD], p[P_HD], p[P_UFLOOR]
    has_faults = faults.shape[0] > 0
    inv_relax = 1.0 / p[P_RELAX]
    floor = QS_DRAG_FLOOR * mb / tau if tau > 0.0 else QS_DRAG_FLOOR * mb * 1e5
    inv_mb, inv_jb = 1.0 / mb, 1.0 / jb

    xi, yi, thi = y[0], y[1], y[2]
    xo, yo, thc = y[3], y[4], y[5]
    vxi, vyi, wi = y[nq], y[nq + 1], y[nq + 2]
    vxo, vyo, wc = y[nq + 3], y[nq + 4], y[nq + 5]
    fxi, fyi, ti, fxo, fyo, tc = _ring_loads(t, y, nq, p, sensors, exc, want_exc)
    ci = math.cos(thi) if has_faults else 1.0
    si = math.sin(thi) if has_faults else 0.0
    uc, us = math.cos(thc), math.sin(thc)
    pc, ps = p[P_PITCH_COS], p[P_PITCH_SIN]
    for j in range(z):
        b = 6 + 3 * j
        v = nq + 6 + 2 * j
        xb, yb = y[b], y[b + 1]
        u, wb = y[v], y[v + 1]
        r = math.sqrt(xb * xb + yb * yb)
        inv_r = 1.0 / r
        ex, ey = xb * inv_r, yb * inv_r
        vtx, vty = -u * ey, u * ex   # the ball's velocity but r' e
        # ---- geometry of both contacts (normals from the race centres to the ball)
        dx, dy = xb - xi, yb - yi
        dist_i = math.sqrt(dx * dx + dy * dy)
        inv_i = 1.0 / dist_i
        nix, niy = dx * inv_i, dy * inv_i
        dx, dy = xb - xo, yb - yo
        dist_o = math.sqrt(dx * dx + dy * dy)
        inv_o = 1.0 / dist_o
        nox, noy = dx * inv_o, dy * inv_o
        drop_i, drop_o, fl_i, fl_o = 0.0, 0.0, 0, 0
        if has_faults:
            drop_i, fl_i = _race_drop(faults, KIND_INNER, nix * ci + niy * si,
                                      niy * ci - nix * si, ri, j, 1)
            drop_o, fl_o = _race_drop(faults, KIND_OUTER, nox, noy, ro, j, 0)
        flags[j, 0] = fl_o
        flags[j, 1] = fl_i
        d_i = rb + ri - dist_i - drop_i
        d_o = dist_o + rb - ro - drop_o
        pi_, k_i, po_, k_o = 0.0, 0.0, 0.0, 0.0
        if d_i > 0.0:
            root = math.sqrt(d_i)
            pi_, k_i = ki * d_i * root, 1.5 * ki * root
        if d_o > 0.0:
            root = math.sqrt(d_o)
            po_, k_o = ko * d_o * root, 1.5 * ko * root
        c_i = nix * ex + niy * ey
        c_o = nox * ex + noy * ey
        # approach rates: d(delta_i)/dt = a_i - c_i r', d(delta_o)/dt = c_o r' - a_o
        a_i = nix * (vxi - vtx) + niy * (vyi - vty)
        a_o = nox * (vxo - vtx) + noy * (vyo - vty)
        f_i, f_o = y[i_f + j], y[i_f + z + j]
        tr_i = f_i * (nix * ey - niy * ex) if traction else 0.0
        tr_o = f_o * (nox * ey - noy * ex) if traction else 0.0
        load = mb * (u * u * inv_r + g * ex)
        on_i, on_o = d_i > 0.0, d_o > 0.0
        rdot, q_i, q_o = 0.0, 0.0, 0.0
        for _ in range(3):
            num, den = load, floor
            if on_i:
                num += c_i * (pi_ + tau * k_i * a_i) + tr_i
                den += tau * k_i * c_i * c_i
            if on_o:
                num += tr_o - c_o * (po_ - tau * k_o * a_o)
                den += tau * k_o * c_o * c_o
            rdot = num / den
            q_i = pi_ + tau * k_i * (a_i - c_i * rdot) if on_i else 0.0
            q_o = po_ + tau * k_o * (c_o * rdot - a_o) if on_o else 0.0
            if on_i and q_i <= 0.0:
                on_i = False
            elif on_o and q_o <= 0.0:
                on_o = False
            else:
                break
        q_i = q_i if q_i > 0.0 else 0.0
        q_o = q_o if q_o > 0.0 else 0.0
        qi[j] = q_i
        qo[j] = q_o
        vbx, vby = vtx + rdot * ex, vty + rdot * ey
        fxb, fyb, tb = mb * g, 0.0, 0.0
        if q_i > 0.0:
            fxb += q_i * nix
            fyb += q_i * niy
            fxi -= q_i * nix
            fyi -= q_i * niy
            if traction:
                rvx, rvy = vbx - vxi, vby - vyi
                vt = -rvx * niy + rvy * nix
                om = vt * inv_i
                ur = 0.5 * (abs((wi - om) * ri) + abs((wb - om) * rb)) + ufloor
                dydt[i_f + j] = _traction_rate(vt - wb * rb - wi * ri, ur, q_i, f_i, w_bd,
                                               hd, inv_relax)
                fxb -= f_i * niy
                fyb += f_i * nix
                fxi += f_i * niy
                fyi -= f_i * nix
                tb -= rb * f_i
                ti -= ri * f_i
        elif traction:
            dydt[i_f + j] = -f_i * 1e3 * ufloor * inv_relax
        if q_o > 0.0:
            fxb -= q_o * nox
            fyb -= q_o * noy
            fxo += q_o * nox
            fyo += q_o * noy
            if want_exc:
                _sensor_share(exc, sensors, nox, noy, q_o, p[P_MO])
            if traction:
                rvx, rvy = vbx - vxo, vby - vyo
                vt = -rvx * noy + rvy * nox
                om = vt * inv_o
                ur = 0.5 * (abs(om * ro) + abs((wb - om) * rb)) + ufloor
                dydt[i_f + z + j] = _traction_rate(vt + wb * rb, ur, q_o, f_o, w_bd, hd,
                                                   inv_relax)
                fxb -= f_o * noy
                fyb += f_o * nox
                fxo += f_o * noy
                fyo -= f_o * nox
                tb += rb * f_o
        elif traction:
            dydt[i_f + z + j] = -f_o * 1e3 * ufloor * inv_relax
        ft = fyb * ex - fxb * ey
        fp = _pocket(xb, yb, vtx, vty, uc, us, wc, p)
        if fp != 0.0:
            ft -= fp * p[P_RP] * inv_r
            tc += fp * p[P_RP]
        uc, us = uc * pc - us * ps, uc * ps + us * pc
        dydt[b] = vbx
        dydt[b + 1] = vby
        dydt[b + 2] = wb
        dydt[v] = ft * inv_mb - rdot * u * inv_r
        dydt[v + 1] = tb * inv_jb
    if not traction:
        for k in range(i_f, dydt.shape[0]):
            dydt[k] = 0.0
    _ring_rates(dydt, y, nq, p, fxi, fyi, ti, fxo, fyo, tc)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _f(qs, t, y, dydt, p, faults, sensors, qi, qo, flags, exc, want_exc):
    """The right-hand side of the ball model: :func:`rhs_qs` if ``qs``, else :func:`rhs`."""
    if qs:
        rhs_qs(t, y, dydt, p, faults, sensors, qi, qo, flags, exc, want_exc)
    else:
        rhs(t, y, dydt, p, faults, sensors, qi, qo, flags, exc, want_exc)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def energy(t, y, p):
    """Mechanical energy (J) of the conservative part: kinetic energy of every body,
    Hertz potentials 0.4 K delta^2.5 (healthy races), housing and pocket springs,
    drive coupling, and the potentials of gravity and the radial load."""
    z = int(p[P_Z])
    nd = 6 + 3 * z
    e = 0.5 * p[P_MI] * (y[nd] ** 2 + y[nd + 1] ** 2) + 0.5 * p[P_JI] * y[nd + 2] ** 2
    e += 0.5 * p[P_MO] * (y[nd + 3] ** 2 + y[nd + 4] ** 2) + 0.5 * p[P_JC] * y[nd + 5] ** 2
    e += 0.5 * p[P_KH] * (y[3] ** 2 + y[4] ** 2)
    e -= (p[P_FR] + p[P_MI] * p[P_G]) * y[0] + p[P_MO] * p[P_G] * y[3]
    th_r, _w = theta_ref(t, p)
    e += 0.5 * p[P_KD] * (th_r - y[2]) ** 2
    pitch = TWO_PI / z
    for j in range(z):
        b = 6 + 3 * j
        xb, yb = y[b], y[b + 1]
        e += 0.5 * p[P_MB] * (y[nd + b] ** 2 + y[nd + b + 1] ** 2)
        e += 0.5 * p[P_JB] * y[nd + b + 2] ** 2 - p[P_MB] * p[P_G] * xb
        d = p[P_RB] + p[P_RI] - math.sqrt((xb - y[0]) ** 2 + (yb - y[1]) ** 2)
        if d > 0.0:
            e += 0.4 * p[P_KI] * d ** 2.5
        d = math.sqrt((xb - y[3]) ** 2 + (yb - y[4]) ** 2) + p[P_RB] - p[P_RO]
        if d > 0.0:
            e += 0.4 * p[P_KO] * d ** 2.5
        off = p[P_RP] * wrap_pi(math.atan2(yb, xb) - y[5] - pitch * j)
        if abs(off) > p[P_EPOCK]:
            e += 0.5 * p[P_KPOCK] * (abs(off) - p[P_EPOCK]) ** 2
    return e


#: fixed-step methods of :func:`integrate_fixed`
METHOD_RK4, METHOD_ROSW = 0, 1

# ROS34PW2 (Rang & Angermann 2005, BIT 45: 761): a four-stage Rosenbrock-W method of
# order 3 for any approximation W of the Jacobian, L-stable, stiffly accurate
# (Hairer-Wanner form: W k_i = h f(y + sum a_ij k_j) + h J sum g_ij k_j, W = I - gamma h J)
RW_GAMMA = 0.435866521508459
RW_A = np.array([[0.0, 0.0, 0.0],
                 [0.87173304301691801, 0.0, 0.0],
                 [0.84457060015369423, -0.11299064236397981, 0.0],
                 [0.0, 0.0, 1.0]])
RW_G = np.array([[0.0, 0.0, 0.0],
                 [-0.87173304301691801, 0.0, 0.0],
                 [-0.90338057013044082, 0.054180672388095326, 0.0],
                 [0.24212380706095346, -1.2232505839045147, 0.54526025533510214]])
RW_B = np.array([0.24212380706095346, -1.2232505839045147, 1.5452602553351023,
                 0.435866521508459])
RW_C = RW_A.sum(axis=1)  # stage times


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def ball_stiffness(y, p, qi, qo, kb):
    """Linearised stiffness of every ball against its races and of the outer race
    against its housing and the balls, N/m, each as the symmetric 2 x 2 matrix
    sum_c k_c n_c n_c^T (``kb[j] = (kxx, kxy, kyy)``, row Z the outer race), with
    k_c = dQ/d(delta) = 1.5 K^(2/3) Q^(1/3) of each contact at the loads ``qi``, ``qo``
    (N; the damping share of Q is kept, which a W-method allows: any matrix is a
    consistent approximation of the Jacobian). Kramer's damping of the same contacts
    and of the housing is tau times it."""
    z = int(p[P_Z])
    c_i = 1.5 * p[P_KI] ** (2.0 / 3.0)
    c_o = 1.5 * p[P_KO] ** (2.0 / 3.0)
    kb[z, 0] = p[P_KH]
    kb[z, 1] = 0.0
    kb[z, 2] = p[P_KH]
    for j in range(z):
        b = 6 + 3 * j
        kxx = 0.0
        kxy = 0.0
        kyy = 0.0
        for race in range(2):
            q = qi[j] if race == 0 else qo[j]
            if q <= 0.0:
                continue
            dx = y[b] - y[3 * race]
            dy = y[b + 1] - y[3 * race + 1]
            k = (c_i if race == 0 else c_o) * q ** (1.0 / 3.0) / (dx * dx + dy * dy)
            kxx += k * dx * dx
            kxy += k * dx * dy
            kyy += k * dy * dy
            if race == 1:
                kb[z, 0] += k * dx * dx
                kb[z, 1] += k * dx * dy
                kb[z, 2] += k * dy * dy
        kb[j, 0] = kxx
        kb[j, 1] = kxy
        kb[j, 2] = kyy


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _w_solve(k, r, g, kb, p, h):
    """k = W^-1 (r + h J g) for a ROS34PW2 stage, J the contact blocks
    d(dx/dt, dv/dt)/d(x, v) = [[0, I], [-K/m, -tau K/m]] of every ball's centre and of
    the outer race (K from :func:`ball_stiffness`; zero elsewhere: the other states,
    and the couplings between the bodies, are stepped explicitly). Each body is a
    2 x 2 solve: with W = I - gamma h J, k_v solves
    (I + (gamma h tau + gamma^2 h^2) K/m) k_v = r_v - gamma h K/m r_x and
    k_x = r_x + gamma h k_v."""
    n = k.shape[0]
    z = int(p[P_Z])
    nd = 6 + 3 * z
    for i in range(n):
        k[i] = r[i]
    tau = p[P_TAU]
    gh = RW_GAMMA * h
    a = gh * tau + gh * gh
    for j in range(z + 1):
        b = 6 + 3 * j if j < z else 3
        inv_m = 1.0 / (p[P_MB] if j < z else p[P_MO])
        kxx, kxy, kyy = kb[j, 0] * inv_m, kb[j, 1] * inv_m, kb[j, 2] * inv_m
        # r + h J g on the body's centre
        gvx, gvy = g[nd + b], g[nd + b + 1]
        rx = r[b] + h * gvx
        ry = r[b + 1] + h * gvy
        ux = g[b] + tau * gvx
        uy = g[b + 1] + tau * gvy
        sx = r[nd + b] - h * (kxx * ux + kxy * uy) - gh * (kxx * rx + kxy * ry)
        sy = r[nd + b + 1] - h * (kxy * ux + kyy * uy) - gh * (kxy * rx + kyy * ry)
        m11 = 1.0 + a * kxx
        m12 = a * kxy
        m22 = 1.0 + a * kyy
        det = m11 * m22 - m12 * m12
        kvx = (m22 * sx - m12 * sy) / det
        kvy = (m11 * sy - m12 * sx) / det
        k[nd + b] = kvx
        k[nd + b + 1] = kvy
        k[b] = rx + gh * kvx
        k[b + 1] = ry + gh * kvy


@njit(cache=True, error_model="numpy")
def integrate_fixed(method, qs, y, p, faults, sensors, t0, dt_pre, dt, n_pre, n_sub, n_grid,
                    stride, exc_out, rec_qi, rec_qo, rec_ang, rec_disp, rec_cage,
                    cross_t, cross_f, cross_e, cross_edge, bound):
    """Fixed-step integration from t0 (< 0: ``n_pre`` settling steps of ``dt_pre`` to
    t = 0), then ``n_sub`` steps per internal grid interval for ``n_grid - 1``
    intervals, by classical RK4 (``method`` METHOD_RK4) or by the Rosenbrock-W method
    ROS34PW2 with each ball's contact block implicit (METHOD_ROSW, :func:`_w_solve`;
    dynamic balls only). ``qs``: the balls are quasi-static (:func:`rhs_qs` and its
    state layout) instead of dynamic (:func:`rhs`).

    Records per grid interval the mean housing acceleration at each sensor
    (``exc_out``: the method's own quadrature of its stages, Simpson's rule for RK4,
    the weights b_i for ROS34PW2), at every ``stride``-th grid point the contact loads,
    ball orbit angles about the housing centre, ring displacements and the cage angle,
    and every change of a contact's fault flags (time, fault, element, edge 0 = entry /
    1 = exit). Returns (status, n_steps, t_fail, n_crossings); ``y`` holds the final
    state."""
    n = y.shape[0]
    z = int(p[P_Z])
    ns = sensors.shape[0]
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    gsum = np.empty(n)
    kb = np.zeros((z + 1, 3))
    qi = np.zeros(z)
    qo = np.zeros(z)
    flags = np.zeros((z, 2), dtype=np.int64)
    prev = np.zeros((z, 2), dtype=np.int64)
    e1 = np.zeros(ns)
    e2 = np.zeros(ns)
    e3 = np.zeros(ns)
    e4 = np.zeros(ns)
    acc = np.zeros(ns)
    n_faults = faults.shape[0]
    cap = cross_t.shape[0]
    n_cross = 0
    t = t0
    n_steps = 0
    total = n_pre + (n_grid - 1) * n_sub
    # initial flags
    _f(qs, t, y, k1, p, faults, sensors, qi, qo, prev, e1, False)
    rec_i = 0
    have_k1 = False
    for step in range(total + 1):
        grid = step >= n_pre and (step - n_pre) % n_sub == 0
        if grid:
            g_i = (step - n_pre) // n_sub
            if g_i > 0:
                for s in range(ns):
                    exc_out[g_i - 1, s] = acc[s] / (n_sub * dt)
                    acc[s] = 0.0
            for k in range(n):
                if not (abs(y[k]) <= bound[k]):
                    return STATUS_NONFINITE, n_steps, t, n_cross
            if g_i % stride == 0 and rec_i < rec_qi.shape[0]:
                # the step's first stage, whose loads are the ones recorded
                if not have_k1:
                    _f(qs, t, y, k1, p, faults, sensors, qi, qo, flags, e1, True)
                have_k1 = True
                for j in range(z):
                    rec_qi[rec_i, j] = qi[j]
                    rec_qo[rec_i, j] = qo[j]
                    b = 6 + 3 * j
                    rec_ang[rec_i, j] = math.atan2(y[b + 1] - y[4], y[b] - y[3])
                rec_disp[rec_i, 0] = y[0]
                rec_disp[rec_i, 1] = y[1]
                rec_disp[rec_i, 2] = y[3]
                rec_disp[rec_i, 3] = y[4]
                rec_cage[rec_i] = y[5]
                rec_i += 1
        if step == total:
            break
        h = dt if step >= n_pre else dt_pre
        if not have_k1:
            _f(qs, t, y, k1, p, faults, sensors, qi, qo, flags, e1, True)
        have_k1 = False
        if n_faults > 0:
            n_cross = _log_crossings(faults, flags, prev, t, cross_t, cross_f, cross_e,
                                     cross_edge, n_cross, cap)
        if method == METHOD_RK4:
            if qs:
                _rk4_stages_qs(t, y, h, k1, k2, k3, k4, tmp, p, faults, sensors, qi, qo,
                               flags, e1, e2, e3, e4)
            else:
                _rk4_stages(t, y, h, k1, k2, k3, k4, tmp, p, faults, sensors, qi, qo, flags,
                            e1, e2, e3, e4)
            if step >= n_pre:
                for s in range(ns):
                    acc[s] += dt / 6.0 * (e1[s] + 2.0 * e2[s] + 2.0 * e3[s] + e4[s])
        else:
            ball_stiffness(y, p, qi, qo, kb)
            _rosw_stages(t, y, h, k1, k2, k3, k4, tmp, gsum, kb, p, faults, sensors, qi, qo,
                         flags, e2, e3, e4)
            if step >= n_pre:
                for s in range(ns):
                    acc[s] += dt * (RW_B[0] * e1[s] + RW_B[1] * e2[s] + RW_B[2] * e3[s]
                                    + RW_B[3] * e4[s])
        n_steps += 1
        if step + 1 == n_pre:
            t = 0.0
        elif step + 1 > n_pre:
            t = (step + 1 - n_pre) // n_sub * (n_sub * dt) + ((step + 1 - n_pre) % n_sub) * dt
        else:
            t = t0 + (step + 1) * dt_pre
    return STATUS_OK, n_steps, t, n_cross


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _log_crossings(faults, flags, prev, t, cross_t, cross_f, cross_e, cross_edge, n_cross,
                   cap):
    """Append every change of a contact's fault flags since ``prev`` (then updated);
    returns the new count."""
    z = flags.shape[0]
    for j in range(z):
        for c in range(2):
            if flags[j, c] != prev[j, c]:
                for f in range(faults.shape[0]):
                    bit = 1 << f
                    now = flags[j, c] & bit
                    if now != (prev[j, c] & bit) and n_cross < cap:
                        cross_t[n_cross] = t
                        cross_f[n_cross] = f
                        if int(faults[f, F_KIND]) == KIND_BALL:
                            cross_e[n_cross] = c
                        else:
                            cross_e[n_cross] = j
                        cross_edge[n_cross] = 0 if now else 1
                        n_cross += 1
                prev[j, c] = flags[j, c]
    return n_cross


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _rk4_stages(t, y, h, k1, k2, k3, k4, tmp, p, faults, sensors, qi, qo, flags, e1, e2,
                e3, e4):
    """One classical RK4 step of y (in place), k1 = f(t, y) given."""
    n = y.shape[0]
    for k in range(n):
        tmp[k] = y[k] + 0.5 * h * k1[k]
    rhs(t + 0.5 * h, tmp, k2, p, faults, sensors, qi, qo, flags, e2, True)
    for k in range(n):
        tmp[k] = y[k] + 0.5 * h * k2[k]
    rhs(t + 0.5 * h, tmp, k3, p, faults, sensors, qi, qo, flags, e3, True)
    for k in range(n):
        tmp[k] = y[k] + h * k3[k]
    rhs(t + h, tmp, k4, p, faults, sensors, qi, qo, flags, e4, True)
    for k in range(n):
        y[k] += h / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k])


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _rk4_update(y, h, k1, k2, k3, k4):
    """y += h (k1 + 2 k2 + 2 k3 + k4) / 6."""
    for k in range(y.shape[0]):
        y[k] += h / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k])


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _shifted(tmp, y, c, k1):
    """tmp = y + c k1."""
    for k in range(y.shape[0]):
        tmp[k] = y[k] + c * k1[k]


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _rk4_stages_qs(t, y, h, k1, k2, k3, k4, tmp, p, faults, sensors, qi, qo, flags, e1,
                   e2, e3, e4):
    """:func:`_rk4_stages` with quasi-static balls (:func:`rhs_qs`). A separate kernel:
    a branch between the two right-hand sides at every stage slows the dynamic balls'
    step by 3-4 %."""
    _shifted(tmp, y, 0.5 * h, k1)
    rhs_qs(t + 0.5 * h, tmp, k2, p, faults, sensors, qi, qo, flags, e2, True)
    _shifted(tmp, y, 0.5 * h, k2)
    rhs_qs(t + 0.5 * h, tmp, k3, p, faults, sensors, qi, qo, flags, e3, True)
    _shifted(tmp, y, h, k3)
    rhs_qs(t + h, tmp, k4, p, faults, sensors, qi, qo, flags, e4, True)
    _rk4_update(y, h, k1, k2, k3, k4)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _rosw_stages(t, y, h, f1, k2, k3, k4, tmp, gsum, kb, p, faults, sensors, qi, qo, flags,
                 e2, e3, e4):
    """One ROS34PW2 step of y (in place) with the per-ball contact blocks ``kb``
    (:func:`ball_stiffness`), f1 = f(t, y) given (overwritten by the first stage
    k_1; k2..k4 hold the later stages' increments)."""
    n = y.shape[0]
    a = RW_A
    g = RW_G
    for k in range(n):
        tmp[k] = h * f1[k]
        gsum[k] = 0.0
    _w_solve(f1, tmp, gsum, kb, p, h)  # k_1 (no earlier stage: g = 0)
    for k in range(n):
        tmp[k] = y[k] + a[1, 0] * f1[k]
        gsum[k] = g[1, 0] * f1[k]
    rhs(t + RW_C[1] * h, tmp, k2, p, faults, sensors, qi, qo, flags, e2, True)
    for k in range(n):
        tmp[k] = h * k2[k]
    _w_solve(k2, tmp, gsum, kb, p, h)
    for k in range(n):
        tmp[k] = y[k] + a[2, 0] * f1[k] + a[2, 1] * k2[k]
        gsum[k] = g[2, 0] * f1[k] + g[2, 1] * k2[k]
    rhs(t + RW_C[2] * h, tmp, k3, p, faults, sensors, qi, qo, flags, e3, True)
    for k in range(n):
        tmp[k] = h * k3[k]
    _w_solve(k3, tmp, gsum, kb, p, h)
    for k in range(n):
        tmp[k] = y[k] + k3[k]  # a[3] = (0, 0, 1)
        gsum[k] = g[3, 0] * f1[k] + g[3, 1] * k2[k] + g[3, 2] * k3[k]
    rhs(t + h, tmp, k4, p, faults, sensors, qi, qo, flags, e4, True)
    for k in range(n):
        tmp[k] = h * k4[k]
    _w_solve(k4, tmp, gsum, kb, p, h)
    for k in range(n):
        y[k] += RW_B[0] * f1[k] + RW_B[1] * k2[k] + RW_B[2] * k3[k] + RW_B[3] * k4[k]
