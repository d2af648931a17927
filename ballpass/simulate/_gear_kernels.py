"""Numba kernels of the ``gearbox`` model: mesh stiffness, transmission error, the
coupled gear-bearing right-hand side and its fixed-step RK4 integrator.

The bearing part is the sr5 shaft-pedestal core, called through :mod:`._kernels`
(kinematics, contact loads, pedestal and housing forces); this module adds the gear
mesh. State layout (``N_STATE`` = 14)::

    y = [u_s, v_s, u_p, v_p, th_p, x_g, th_g, th_m,  (their rates in the same order)]

u_s, v_s: shaft (and pinion) centre; u_p, v_p: pedestal; th_p: pinion torsion relative
to its nominal angle (rad); x_g: gear centre along the line of action (m); th_g: gear
torsion relative to the load's nominal angle, positive in the gear's direction of
rotation (rad); th_m: the drive's (motor rotor's) torsion (rad). The line of action is
the bearing's load line u: the mesh force N pushes the pinion shaft along +u (into the
load zone, adding to the scene's radial load) and the gear along -u.

Gear parameters ``g`` (indices ``G_*``) and the static transmission error's harmonics
``te`` (rows: amplitude (m), phase (rad), one per mesh harmonic) are float64 arrays.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import _kernels as K

G_EPS_A, G_EPS_B, G_ZP, G_ZG = 0, 1, 2, 3
G_KM, G_CM, G_RBP, G_RBG, G_IP, G_IG = 4, 5, 6, 7, 8, 9
G_MG, G_KG, G_CG, G_KT, G_CT, G_TP = 10, 11, 12, 13, 14, 15
G_ECCP, G_ECCG = 16, 17
G_FGEAR, G_FTOOTH, G_FLOSS = 18, 19, 20
G_IM, G_KO, G_CO, G_D0 = 21, 22, 23, 24
N_GPARAMS = 25
#: fault-wheel codes in G_FGEAR
FAULT_NONE, FAULT_PINION, FAULT_GEAR = 0, 1, 2

N_STATE = 16
N_POS = 8


@njit(cache=True, error_model="numpy")
def _count_integral(x, eps_a):
    """Integral over [0, x] of the number of tooth pairs in contact of a spur slice at
    mesh phase v (teeth passed): floor(eps_a) + 1 while frac(v) < frac(eps_a), else
    floor(eps_a)."""
    whole = math.floor(eps_a)
    a = eps_a - whole
    fx = math.floor(x)
    return whole * x + fx * a + min(x - fx, a)


@njit(cache=True, error_model="numpy")
def _tooth_integral(x, z, eps_a):
    """Integral over [0, x] of the indicator that tooth 0 of a wheel of z teeth is in
    contact at mesh phase v: it meshes for v mod z in [0, eps_a)."""
    fz = math.floor(x / z)
    return fz * eps_a + min(x - fz * z, eps_a)


@njit(cache=True, error_model="numpy")
def mesh_stiffness(u, g):
    """Mesh stiffness at mesh phase u (teeth passed since t = 0), N/m.

    k = k_mean / eps_alpha * (n(u) - loss * m(u)): n is the number of tooth pairs in
    contact averaged over the face (spur slices staggered over eps_beta mesh periods),
    m the share of the faulty tooth in it.
    """
    eps_a = g[G_EPS_A]
    eps_b = g[G_EPS_B]
    if eps_b > 0.0:
        n = (_count_integral(u + eps_b, eps_a) - _count_integral(u, eps_a)) / eps_b
    else:
        whole = math.floor(eps_a)
        n = whole + (1.0 if u - math.floor(u) < eps_a - whole else 0.0)
    wheel = int(g[G_FGEAR])
    if wheel != FAULT_NONE:
        z = g[G_ZP] if wheel == FAULT_PINION else g[G_ZG]
        x = u - g[G_FTOOTH]
        if eps_b > 0.0:
            m = (_tooth_integral(x + eps_b, z, eps_a) - _tooth_integral(x, z, eps_a)) / eps_b
        else:
            m = 1.0 if x - z * math.floor(x / z) < eps_a else 0.0
        n -= g[G_FLOSS] * m
    return g[G_KM] / eps_a * n


@njit(cache=True, error_model="numpy")
def transmission_error(theta, w, g, te):
    """Static transmission error e (m) and its rate de/dt (m/s) at pinion angle
    ``theta`` (rad) turning at ``w`` (rad/s): mesh harmonics plus the once-per-turn
    runout of pinion and gear, e_p sin(theta) + e_g sin(theta z_p / z_g)."""
    zp = g[G_ZP]
    rg = zp / g[G_ZG]
    e = g[G_ECCP] * math.sin(theta) + g[G_ECCG] * math.sin(theta * rg)
    de = w * (g[G_ECCP] * math.cos(theta) + g[G_ECCG] * rg * math.cos(theta * rg))
    for h in range(te.shape[0]):
        arg = (h + 1) * zp * theta + te[h, 1]
        e += te[h, 0] * math.cos(arg)
        de -= te[h, 0] * (h + 1) * zp * w * math.sin(arg)
    return e, de


@njit(cache=True, error_model="numpy")
def mesh_force(t, y, p, g, te):
    """Mesh force N along the line of action (N, >= 0; exactly 0 when the teeth
    separate), the mesh stiffness (N/m) and the static transmission error (m) at (t, y).

    delta = r_bp th_p - r_bg th_g - (u_s - x_g) - e(t) + delta_0;
    N = k(t) delta + c_m d(delta)/dt; delta_0 (``g[G_D0]``) sets the angular references
    so that the static state has th_p = th_g = 0.
    """
    theta = K.shaft_angle(t, p)
    w = K.shaft_rate(t, p)
    k = mesh_stiffness(g[G_ZP] * theta / K.TWO_PI, g)
    e, de = transmission_error(theta, w, g, te)
    delta = g[G_RBP] * y[4] - g[G_RBG] * y[6] - (y[0] - y[5]) - e + g[G_D0]
    if delta <= 0.0:
        return 0.0, k, e
    ddelta = g[G_RBP] * y[N_POS + 4] - g[G_RBG] * y[N_POS + 6] - (y[N_POS] - y[N_POS + 5]) - de
    return max(k * delta + g[G_CM] * ddelta, 0.0), k, e


@njit(cache=True, error_model="numpy")
def rhs(t, y, dydt, p, walk, faults, g, te, kin, yc, dc):
    """dy/dt of the coupled gear-bearing model (layout above) into ``dydt``; returns
    the mesh force, N. ``yc``, ``dc`` are length-8 scratch for the bearing core.

    Bearing core: the sr5 equations (Sawalhi & Randall 2008; Tran, Furch & Cu eqs. 7-16 with
    the shaft damping, loads and sprung mass restored), plus N on the shaft along u.
    Angles are relative to the nominal motion (a speed ramp's angular acceleration
    alpha adds -alpha, -alpha z_p / z_g to each wheel's th'').
    Drive: I_m th_m'' = T_p - M_t, M_t = k_t (th_m - th_p) + c_t (th_m' - th_p') (shaft
    torque, pre-twisted by T_p / k_t).
    Pinion (Tran, Furch & Cu eq. 5): I_p th_p'' = M_t - r_bp N.
    Gear (eqs. 2, 6): I_g th_g'' = r_bg N - T_g - k_o th_g - c_o th_g',
    m_g x_g'' = -k_g x_g - c_g x_g' - N, with the load torque T_g = T_p r_bg / r_bp and
    the output shaft (k_o, c_o) to a load turning at the nominal speed.
    """
    for i in range(4):
        yc[i] = y[i]
        yc[4 + i] = y[N_POS + i]
    K.kinematics(t, p, walk, faults, kin)
    K.core_forces(yc, p, kin, dc)
    n, _k, _e = mesh_force(t, y, p, g, te)
    for i in range(4):
        dydt[i] = dc[i]
        dydt[N_POS + i] = dc[4 + i]
    dydt[N_POS] += n / p[K.P_MS]
    for i in range(4, N_POS):
        dydt[i] = y[N_POS + i]
    tp = g[G_TP]
    m_t = g[G_KT] * (y[7] - y[4]) + g[G_CT] * (y[N_POS + 7] - y[N_POS + 4])
    # the angles are relative to the nominal motion: its angular acceleration (a speed
    # ramp) enters as an inertial torque on each wheel
    alpha = (p[K.P_W1] - p[K.P_W0]) / p[K.P_T]
    alpha_g = alpha * g[G_ZP] / g[G_ZG]
    dydt[N_POS + 4] = (m_t - g[G_RBP] * n) / g[G_IP] - alpha
    dydt[N_POS + 5] = (-g[G_KG] * y[5] - g[G_CG] * y[N_POS + 5] - n) / g[G_MG]
    dydt[N_POS + 6] = (g[G_RBG] * n - tp * g[G_RBG] / g[G_RBP] - g[G_KO] * y[6]
                       - g[G_CO] * y[N_POS + 6]) / g[G_IG] - alpha_g
    dydt[N_POS + 7] = (tp - m_t) / g[G_IM] - alpha
    return n


@njit(cache=True, error_model="numpy")
def _next_jump(u0, u1, g):
    """Smallest mesh phase in (u0, u1] where the stiffness of a spur pair jumps (a tooth
    pair enters or leaves contact, or the faulty tooth does), or -1 if none: helical
    stiffness is continuous (its kinks need no split)."""
    if g[G_EPS_B] > 0.0:
        return -1.0
    eps_a = g[G_EPS_A]
    a = eps_a - math.floor(eps_a)
    best = -1.0
    # a pair enters at integer phases and one leaves at integer + frac(eps_a)
    for off in (0.0, a):
        v = math.floor(u0 - off) + 1.0 + off
        if v <= u1 and (best < 0.0 or v < best):
            best = v
    wheel = int(g[G_FGEAR])
    if wheel != FAULT_NONE:
        z = g[G_ZP] if wheel == FAULT_PINION else g[G_ZG]
        for off in (0.0, eps_a):
            base = g[G_FTOOTH] + off
            v = base + z * (math.floor((u0 - base) / z) + 1.0)
            if v <= u1 and (best < 0.0 or v < best):
                best = v
    return best


@njit(cache=True, error_model="numpy")
def _phase_time(v, p, zp, t_lo, t_hi):
    """Bracket (before, after) of the time in [t_lo, t_hi] at which the mesh phase
    z_p theta / (2 pi) reaches v: adjacent floating-point numbers with the phase below
    v at ``before`` and at or above it at ``after`` (bisection; the phase increases)."""
    for _ in range(200):
        mid = 0.5 * (t_lo + t_hi)
        if mid <= t_lo or mid >= t_hi:
            break
        if zp * K.shaft_angle(mid, p) / K.TWO_PI >= v:
            t_hi = mid
        else:
            t_lo = mid
    return t_lo, t_hi


@njit(cache=True, error_model="numpy")
def _stiffness_jump(before, after, p, g, zp):
    """The bracket of :func:`_phase_time` moved so that :func:`mesh_stiffness` gives
    the old tooth count at ``before`` and the new one at ``after``.

    The phase test of the bracket and the count of mesh_stiffness round differently:
    at the ``after`` of a pair leaving contact (phase k + frac(eps_alpha)) the count
    may still be the old one for an ulp or two of phase, and the step that starts
    there would take the old stiffness into its first stage, a first-order error (the
    15/29 spur pair's mesh force erred 2.8 % of its standard deviation against DOP853
    at the default step and 0.1 % at 0.5 us; 2.3e-3 and 2e-7 with the bracket moved,
    tests/test_gearbox.py). Each end moves by at most 64 ulps; a jump that does not
    change the stiffness leaves the bracket as it is."""
    k_old = mesh_stiffness(zp * K.shaft_angle(before, p) / K.TWO_PI, g)
    after = _other_stiffness(after, np.inf, k_old, p, g, zp)
    k_new = mesh_stiffness(zp * K.shaft_angle(after, p) / K.TWO_PI, g)
    return _other_stiffness(before, -np.inf, k_new, p, g, zp), after


@njit(cache=True, error_model="numpy")
def _other_stiffness(t, toward, k_ref, p, g, zp):
    """The first time from t towards ``toward`` (+-inf), within 64 ulps, at which
    :func:`mesh_stiffness` differs from ``k_ref``; t if there is none."""
    s = t
    for _ in range(64):
        if mesh_stiffness(zp * K.shaft_angle(s, p) / K.TWO_PI, g) != k_ref:
            return s
        s = np.nextafter(s, toward)
    return t


@njit(cache=True, error_model="numpy")
def _rk4_step(t, h, y, p, walk, faults, g, te, kin, yc, dc, k1, k2, k3, k4, tmp):
    """One classical RK4 step of length h from (t, y), in place."""
    n = y.shape[0]
    rhs(t, y, k1, p, walk, faults, g, te, kin, yc, dc)
    for i in range(n):
        tmp[i] = y[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, tmp, k2, p, walk, faults, g, te, kin, yc, dc)
    for i in range(n):
        tmp[i] = y[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, tmp, k3, p, walk, faults, g, te, kin, yc, dc)
    for i in range(n):
        tmp[i] = y[i] + h * k3[i]
    rhs(t + h, tmp, k4, p, walk, faults, g, te, kin, yc, dc)
    for i in range(n):
        y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@njit(cache=True, error_model="numpy")
def rk4(y0, p, walk, faults, sensors, g, te, h_out, n_sub, n_out, bound, out, forces, states):
    """Classical RK4 with ``n_sub`` steps per output interval ``h_out`` (s), split at
    the stiffness jumps of a spur mesh.

    Writes, at t = k h_out: the housing acceleration along each sensor (m/s^2) into
    ``out[k]``, the mesh force (N), stiffness (N/m) and static transmission error (m)
    into ``forces[k]`` and, if ``states`` has rows, the state into ``states[k]``.
    Returns (status, t_fail): status 0 = ok, 1 = the state left ``bound`` or became
    non-finite.
    """
    z = int(p[K.P_Z])
    kin = K.kinematics_scratch(z)
    yc = np.empty(8)
    dc = np.empty(8)
    acc = np.empty((1, sensors.shape[0]))
    n = y0.shape[0]
    y = y0.copy()
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    dt = h_out / n_sub
    zp = g[G_ZP]
    keep = states.shape[0] > 0
    for k in range(n_out):
        t = k * h_out
        f = rhs(t, y, k1, p, walk, faults, g, te, kin, yc, dc)
        K.housing_accel(yc, dc, p, sensors, kin, 0.0, acc, 0, False)
        out[k, :] = acc[0, :]
        _n, km, em = mesh_force(t, y, p, g, te)
        forces[k, 0] = f
        forces[k, 1] = km
        forces[k, 2] = em
        if keep:
            states[k, :] = y
        for i in range(n):
            if not (abs(y[i]) <= bound[i]):
                return 1, t
        if k == n_out - 1:
            break
        for s in range(n_sub):
            ts = t + s * dt
            te_ = ts + dt
            # split the step where a spur pair's stiffness jumps: RK4 across a jump
            # is only first-order accurate
            while True:
                u0 = zp * K.shaft_angle(ts, p) / K.TWO_PI
                u1 = zp * K.shaft_angle(te_, p) / K.TWO_PI
                v = _next_jump(u0, u1, g)
                if v < 0.0:
                    break
                before, after = _phase_time(v, p, zp, ts, te_)
                before, after = _stiffness_jump(before, after, p, g, zp)
                if before > ts:  # up to the last instant before the jump
                    _rk4_step(ts, before - ts, y, p, walk, faults, g, te, kin, yc, dc,
                              k1, k2, k3, k4, tmp)
                ts = after
                if ts >= te_:
                    break
            if te_ > ts:
                _rk4_step(ts, te_ - ts, y, p, walk, faults, g, te, kin, yc, dc,
                          k1, k2, k3, k4, tmp)
    return 0, n_out * h_out
