"""Numba kernels of the lumped-parameter bearing models: kinematics, fault profiles,
contact law, right-hand side and sensor output. Kernels only: plain floats, ints and
float64/int64 arrays in, no Python objects; validation happens in the callers.

State layout (``n_res`` sensor resonators; ``n_res = 0`` for ``sr4``)::

    y = [u_s, v_s, u_p, v_p, z_1 .. z_nres,  du_s, dv_s, du_p, dv_p, dz_1 .. dz_nres]

u is along the load line (towards the centre of the load zone, angle 0), v is
perpendicular to it in the direction of shaft rotation (angle +90 deg). s = shaft and
inner ring, p = pedestal and outer ring, z_i = deflection of sensor i's resonator
relative to the housing.

Parameter vector ``p`` (indices below, SI units) is built by :mod:`.sr5`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# indices into the parameter vector p
P_MS, P_MP, P_KS, P_CS, P_KP, P_CP = 0, 1, 2, 3, 4, 5
P_KH, P_NH, P_CLEAR, P_FR, P_G = 6, 7, 8, 9, 10
P_W0, P_W1, P_T = 11, 12, 13
P_CAGE, P_SPIN, P_Z = 14, 15, 16
P_WR, P_ZETA = 17, 18
P_US0, P_VS0 = 19, 20
N_PARAMS = 21

# fault kinds (integer codes used in the kernels)
KIND_OUTER, KIND_INNER, KIND_BALL = 0, 1, 2

TWO_PI = 2.0 * math.pi


@njit(cache=True)
def wrap_pi(a):
    """Wrap an angle (rad) to [-pi, pi)."""
    return a - TWO_PI * math.floor((a + math.pi) / TWO_PI)


@njit(cache=True)
def shaft_angle(t, p):
    """Shaft angle turned since t = 0 for a linear speed ramp, rad."""
    return p[P_W0] * t + 0.5 * (p[P_W1] - p[P_W0]) * t * t / p[P_T]


@njit(cache=True)
def element_angles(t, p, walk, psi, cpsi, spsi):
    """Angular positions of the rolling elements at time t, rad, written into ``psi``.

    The cage turns at its kinematic rate plus a random walk ``walk`` (rad), sampled at
    every element spacing of nominal cage angle and interpolated linearly between:
    each interval between consecutive ball passes is stretched by an independent
    random fraction, so inter-impact periods vary with standard deviation ``slip`` of
    the nominal period and the cage keeps its mean speed (the random-slip model of
    Randall & Antoni 2011). Elements keep their nominal spacing 2 pi / Z.
    Also writes cos(psi) and sin(psi) into ``cpsi``, ``spsi``, advancing from element to
    element by a rotation (four trigonometric calls in all, whatever Z).
    """
    z = psi.shape[0]
    step = TWO_PI / z
    cage = p[P_CAGE] * shaft_angle(t, p)
    x = cage / step
    k = math.floor(x)
    f = x - k
    kk = int(k)
    n_knots = walk.shape[0]
    if kk < 0:
        kk = 0
    if kk > n_knots - 2:
        kk = n_knots - 2
    cage += walk[kk] * (1.0 - f) + walk[kk + 1] * f
    c = math.cos(cage)
    sn = math.sin(cage)
    cs = math.cos(step)
    ss = math.sin(step)
    for j in range(z):
        psi[j] = cage + step * j
        cpsi[j] = c
        spsi[j] = sn
        c, sn = c * cs - sn * ss, sn * cs + c * ss


@njit(cache=True)
def profile(offset, half, depth, ramp):
    """Depth of a defect at angular offset ``offset`` from its centre, m.

    ``half`` is the half extent (rad), ``ramp`` the fraction of the extent taken by each
    half-cosine ramp (0 = sharp rectangular notch).
    """
    a = abs(offset)
    if a >= half:
        return 0.0
    if ramp <= 0.0:
        return depth
    x = (half - a) / (2.0 * half)  # 0 at the edge, 0.5 at the centre
    if x >= ramp:
        return depth
    return depth * 0.5 * (1.0 - math.cos(math.pi * x / ramp))


@njit(cache=True)
def fault_depths(t, m, psi, depth):
    """Extra clearance opened by the defects for each element at time t, m.

    Outer race: fixed centre. Inner race: centre turns with the shaft. Ball defect on
    element e: its spin phase advances at the ball spin rate relative to the cage
    (rolling without slip on the element's own path), facing the outer race at phase 0
    and the inner race at phase pi.
    """
    p, psi0 = m[0], m[2]
    f_kind, f_center, f_half, f_depth, f_ramp, f_elem = m[3], m[4], m[5], m[6], m[7], m[8]
    z = psi.shape[0]
    for j in range(z):
        depth[j] = 0.0
    th = shaft_angle(t, p)
    for i in range(f_kind.shape[0]):
        kind = f_kind[i]
        if kind == KIND_BALL:
            e = f_elem[i]
            spin = f_center[i] + p[P_SPIN] * (psi[e] - psi0[e])
            d_out = profile(wrap_pi(spin), f_half[i], f_depth[i], f_ramp[i])
            d_in = profile(wrap_pi(spin - math.pi), f_half[i], f_depth[i], f_ramp[i])
            depth[e] += d_out + d_in
        else:
            centre = f_center[i]
            if kind == KIND_INNER:
                centre += th
            for j in range(z):
                depth[j] += profile(wrap_pi(psi[j] - centre), f_half[i], f_depth[i], f_ramp[i])


@njit(cache=True)
def contact_loads(y, p, cpsi, spsi, depth, q):
    """Hertz contact loads Q_j = K max(delta_j, 0)^n, N, written into ``q``.

    delta_j = (u_s - u_p) cos psi_j + (v_s - v_p) sin psi_j - c - depth_j
    (Sawalhi & Randall 2008 eq. 12 as printed in seed 004). Separated elements carry
    exactly zero force.
    """
    du = y[0] - y[2]
    dv = y[1] - y[3]
    kh = p[P_KH]
    nh = p[P_NH]
    c = p[P_CLEAR]
    ball = nh == 1.5
    for j in range(cpsi.shape[0]):
        d = du * cpsi[j] + dv * spsi[j] - c - depth[j]
        if d > 0.0:
            q[j] = kh * d * math.sqrt(d) if ball else kh * d**nh
        else:
            q[j] = 0.0


@njit(cache=True)
def housing_accel(p, cpsi, spsi, q, s_ang, s_att, fu, fv, out):
    """Local housing acceleration along each sensor's direction, m/s^2.

    The pedestal's rigid-body acceleration with each contact force weighted by its
    transmission factor exp(-kappa (1 - cos(psi_j - theta_i))) to sensor i: 1 at the
    sensor, exp(-2 kappa) opposite it (after McFadden & Smith 1984). With kappa = 0 this
    is exactly the pedestal acceleration projected on the sensor axis. ``fu, fv`` are
    the spring, damping and gravity forces on the pedestal (N).
    """
    mp = p[P_MP]
    for i in range(s_ang.shape[0]):
        ci = math.cos(s_ang[i])
        si = math.sin(s_ang[i])
        kappa = s_att[i]
        acc = (fu * ci + fv * si) / mp
        for j in range(cpsi.shape[0]):
            if q[j] != 0.0:
                cos_rel = cpsi[j] * ci + spsi[j] * si
                w = math.exp(-kappa * (1.0 - cos_rel)) if kappa != 0.0 else 1.0
                acc += w * q[j] * cos_rel / mp
        out[i] = acc


@njit(cache=True)
def rhs(t, y, dydt, m, n_res, work):
    """Right-hand side of the sr4/sr5 equations of motion; writes dy/dt into ``dydt``.

    Shaft:      m_s a_s = -k_s (x_s - x_s0) - c_s v_s - sum_j Q_j n_j + F_r e_u + m_s g e_u
    Pedestal:   m_p a_p = -k_p x_p - c_p v_p + sum_j Q_j n_j + m_p g e_u
    Resonator i (sr5): z_i'' + 2 zeta w z_i' + w^2 z_i = -s_i'' (base excitation by the
    local housing acceleration s_i'' of :func:`housing_accel`).

    ``m`` is the model tuple built by :func:`ballpass.simulate.sr5.build_model`; ``work``
    holds scratch arrays ``(psi, depth, q, sacc, cpsi, spsi)`` (lengths Z, Z, Z,
    n_sensors, Z, Z).
    """
    p, s_ang, s_att = m[0], m[9], m[10]
    psi, depth, q, sacc, cpsi, spsi = work
    element_angles(t, p, m[1], psi, cpsi, spsi)
    fault_depths(t, m, psi, depth)
    contact_loads(y, p, cpsi, spsi, depth, q)
    fu = 0.0
    fv = 0.0
    for j in range(psi.shape[0]):
        if q[j] != 0.0:
            fu += q[j] * cpsi[j]
            fv += q[j] * spsi[j]
    nd = 4 + n_res
    g = p[P_G]
    # shaft
    dydt[0] = y[nd + 0]
    dydt[1] = y[nd + 1]
    dydt[nd + 0] = (-p[P_KS] * (y[0] - p[P_US0]) - p[P_CS] * y[nd + 0] - fu + p[P_FR]) / p[P_MS] + g
    dydt[nd + 1] = (-p[P_KS] * (y[1] - p[P_VS0]) - p[P_CS] * y[nd + 1] - fv) / p[P_MS]
    # pedestal
    pu = -p[P_KP] * y[2] - p[P_CP] * y[nd + 2] + p[P_MP] * g
    pv = -p[P_KP] * y[3] - p[P_CP] * y[nd + 3]
    dydt[2] = y[nd + 2]
    dydt[3] = y[nd + 3]
    dydt[nd + 2] = (pu + fu) / p[P_MP]
    dydt[nd + 3] = (pv + fv) / p[P_MP]
    if n_res > 0:
        housing_accel(p, cpsi, spsi, q, s_ang, s_att, pu, pv, sacc)
        w = p[P_WR]
        zeta = p[P_ZETA]
        for i in range(n_res):
            dydt[4 + i] = y[nd + 4 + i]
            dydt[nd + 4 + i] = -2.0 * zeta * w * y[nd + 4 + i] - w * w * y[4 + i] - sacc[i]


@njit(cache=True)
def sensor_output(t, y, m, n_res, work, out):
    """Acceleration measured by each sensor at state y, m/s^2, into ``out``.

    sr5 (``n_res > 0``): absolute acceleration of the sensor's resonator mass,
    -(2 zeta w z_i' + w^2 z_i) (as Sawalhi & Randall measure y_b). sr4: the local
    housing acceleration itself.
    """
    p = m[0]
    if n_res > 0:
        nd = 4 + n_res
        w = p[P_WR]
        zeta = p[P_ZETA]
        for i in range(n_res):
            out[i] = -(2.0 * zeta * w * y[nd + 4 + i] + w * w * y[4 + i])
        return
    psi, depth, q, cpsi, spsi = work[0], work[1], work[2], work[4], work[5]
    element_angles(t, p, m[1], psi, cpsi, spsi)
    fault_depths(t, m, psi, depth)
    contact_loads(y, p, cpsi, spsi, depth, q)
    pu = -p[P_KP] * y[2] - p[P_CP] * y[6] + p[P_MP] * p[P_G]
    pv = -p[P_KP] * y[3] - p[P_CP] * y[7]
    housing_accel(p, cpsi, spsi, q, m[9], m[10], pu, pv, out)


@njit(cache=True)
def element_angles_many(t, p, walk, z):
    """Element angles at many times: (len(t), Z) array, rad (for kinematics in Python)."""
    out = np.empty((t.shape[0], z))
    psi = np.empty(z)
    cpsi = np.empty(z)
    spsi = np.empty(z)
    for k in range(t.shape[0]):
        element_angles(t[k], p, walk, psi, cpsi, spsi)
        out[k, :] = psi
    return out


@njit(cache=True)
def fault_offset(t, m, i, j, psi, cpsi, spsi):
    """Signed angular offset (rad, in [-pi, pi)) of element j from the centre of fault i.

    For a ball defect ``j`` selects the face: 0 = facing the outer race (phase 0),
    1 = facing the inner race (phase pi). Same arithmetic as :func:`fault_depths`, so
    crossing times found with it are exactly where the kernels switch.
    """
    p = m[0]
    element_angles(t, p, m[1], psi, cpsi, spsi)
    kind = m[3][i]
    if kind == KIND_BALL:
        e = m[8][i]
        spin = m[4][i] + p[P_SPIN] * (psi[e] - m[2][e])
        return wrap_pi(spin - math.pi * j)
    centre = m[4][i]
    if kind == KIND_INNER:
        centre += shaft_angle(t, p)
    return wrap_pi(psi[j] - centre)


@njit(cache=True)
def find_crossings(m, t_grid, levels_per_fault):
    """Times at which an element crosses a fault edge (or a ramp end), by bisection.

    Parameters
    ----------
    m : tuple
        Model tuple.
    t_grid : ndarray, shape (n,)
        Increasing scan times, s; one grid interval must not contain a wrap of the
        offset (guaranteed when the offset moves < pi per interval).
    levels_per_fault : ndarray, shape (n_faults, 4)
        Offsets (rad) that mark an event for each fault: -half, -half_ramp, +half_ramp,
        +half (duplicates allowed for sharp edges; NaN to skip).

    Returns
    -------
    before, after : ndarray
        Bracketing times (s) with ``before < crossing <= after`` and ``after - before``
        at floating-point resolution.
    fault, element, level : ndarray of int64
        Which fault, which element (face for a ball defect) and which level.
    """
    z = m[2].shape[0]
    psi = np.empty(z)
    cpsi = np.empty(z)
    spsi = np.empty(z)
    n_f = m[3].shape[0]
    cap = 1024
    before = np.empty(cap)
    after = np.empty(cap)
    f_out = np.empty(cap, dtype=np.int64)
    e_out = np.empty(cap, dtype=np.int64)
    l_out = np.empty(cap, dtype=np.int64)
    n = 0
    for i in range(n_f):
        n_paths = 2 if m[3][i] == KIND_BALL else z
        for j in range(n_paths):
            o_prev = fault_offset(t_grid[0], m, i, j, psi, cpsi, spsi)
            for k in range(1, t_grid.shape[0]):
                o_next = fault_offset(t_grid[k], m, i, j, psi, cpsi, spsi)
                if abs(o_next - o_prev) < math.pi:
                    for lv in range(4):
                        level = levels_per_fault[i, lv]
                        if level != level:
                            continue
                        if lv > 0 and level == levels_per_fault[i, lv - 1]:
                            continue
                        a_side = o_prev >= level
                        b_side = o_next >= level
                        if a_side == b_side:
                            continue
                        lo = t_grid[k - 1]
                        hi = t_grid[k]
                        for _ in range(200):
                            mid = 0.5 * (lo + hi)
                            if mid <= lo or mid >= hi:
                                break
                            if (fault_offset(mid, m, i, j, psi, cpsi, spsi) >= level) == a_side:
                                lo = mid
                            else:
                                hi = mid
                        if n == before.shape[0]:
                            before = np.concatenate((before, np.empty(n)))
                            after = np.concatenate((after, np.empty(n)))
                            f_out = np.concatenate((f_out, np.empty(n, dtype=np.int64)))
                            e_out = np.concatenate((e_out, np.empty(n, dtype=np.int64)))
                            l_out = np.concatenate((l_out, np.empty(n, dtype=np.int64)))
                        before[n] = lo
                        after[n] = hi
                        f_out[n] = i
                        e_out[n] = j
                        l_out[n] = lv
                        n += 1
                o_prev = o_next
    order = np.argsort(before[:n])
    return before[:n][order], after[:n][order], f_out[:n][order], e_out[:n][order], l_out[:n][order]


@njit(cache=True)
def contact_loads_many(t, states, m):
    """Contact loads of every element at many (time, state) pairs: (len(t), Z), N."""
    p = m[0]
    z = m[2].shape[0]
    psi = np.empty(z)
    cpsi = np.empty(z)
    spsi = np.empty(z)
    depth = np.empty(z)
    q = np.empty(z)
    out = np.empty((t.shape[0], z))
    for k in range(t.shape[0]):
        element_angles(t[k], p, m[1], psi, cpsi, spsi)
        fault_depths(t[k], m, psi, depth)
        contact_loads(states[k], p, cpsi, spsi, depth, q)
        out[k, :] = q
    return out
