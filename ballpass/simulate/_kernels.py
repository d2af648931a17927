"""Numba kernels of the lumped-parameter bearing models: kinematics, fault profiles,
contact law, right-hand sides and sensor excitation. Kernels only: plain floats, ints
and float64 arrays in, no Python objects; validation happens in the callers.

Two state layouts. The *full* state (what ``BearingModel.rhs`` integrates, e.g. with
scipy; ``n_res`` sensor resonators, ``n_res = 0`` for ``sr4``)::

    y = [u_s, v_s, u_p, v_p, z_1 .. z_nres,  du_s, dv_s, du_p, dv_p, dz_1 .. dz_nres]

and the *core* state of the nonlinear 4-DOF part alone (what the ballpass integrators
step; the resonators are linear and one-way coupled, so they are integrated exactly,
see :mod:`._integrators`)::

    yc = [u_s, v_s, u_p, v_p, du_s, dv_s, du_p, dv_p]

u is along the load line (towards the centre of the load zone, angle 0), v is
perpendicular to it in the direction of shaft rotation (angle +90 deg). s = shaft and
inner ring, p = pedestal and outer ring, z_i = deflection of sensor i's resonator
relative to the housing.

The model is four arrays, built by :mod:`.sr5`: the parameter vector ``p`` (indices
``P_*``), the cage's slip random walk ``walk`` (rad), one row per fault in ``faults``
(columns ``F_*``) and one row per sensor in ``sensors`` (columns ``S_*``). Kernels take
arrays one by one, never tuples of arrays: numba reference-counts every member of a
tuple argument on each call, which cost more than the physics. Scratch: ``kin``
(``N_KIN`` x Z) holds the element angles, their cos/sin, the fault depths and their
rates and the contact loads (rows ``K_*``).
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
P_COS_STEP, P_SIN_STEP = 21, 22
P_CD = 23  # Hunt-Crossley contact damping factor alpha, s/m (0 = no contact damping)
# axial load (0 = none): A sin(alpha_0) + delta_a, the groove centres' axial offset held at
# its quasi-static value, m; and A = (f_i + f_o - 1) d, their distance when unloaded, m
P_AX, P_A = 24, 25
N_PARAMS = 26

# columns of the fault table: kind code, centre (rad), half extent (rad), depth (m),
# ramp fraction, element (ball defects), initial angle of that element (rad), ramp
# shape (RAMP_COSINE or RAMP_LINEAR), engagement probability per spin revolution (ball
# defects) and the seed of those draws; for a ball defect whose spin axis drifts
# (:func:`strike_share`): sin of the drift range (0 = no drift), the ball radius and the
# pit radius, both over the outer-race contact ellipse's semi-axis across the track, and
# F_A_IN, that semi-axis over the inner-race contact's (the inner face's ellipse is
# another width: on a 6205 at 500 N 0.92 mm against 0.73 mm). F_DEPTH is a
# race defect's depth; a ball defect's F_DEPTH is its depth where it strikes the outer
# race and F_DEPTH_IN where it strikes the inner race (the mating surfaces' curvature
# sets each, :meth:`ballpass.Fault.effective_depth_mm`; F_DEPTH_IN is 0 on other rows).
# Waviness rows (kinds KIND_WAVY_*) reuse the columns: F_CENTRE the phase (rad), F_HALF
# the order, F_DEPTH the amplitude (m), F_ELEM the ball (KIND_WAVY_BALL).
F_KIND, F_CENTRE, F_HALF, F_DEPTH, F_RAMP, F_ELEM, F_PSI0 = 0, 1, 2, 3, 4, 5, 6
F_SHAPE, F_ENGAGE, F_SEED = 7, 8, 9
F_DRIFT, F_BALL_A, F_PIT_A, F_DEPTH_IN, F_A_IN = 10, 11, 12, 13, 14
N_FCOLS = 15
RAMP_COSINE, RAMP_LINEAR = 0, 1
# columns of the sensor table: angle (rad), attenuation kappa, cos and sin of the angle
S_ANG, S_ATT, S_COS, S_SIN = 0, 1, 2, 3
N_SCOLS = 4
# rows of the kinematics scratch; row K_CACHE holds the last cage angle, its cos and
# sin, the number of rotations since they were last computed exactly, the cage speed
# (rad/s, column KC_RATE), whether an element is on a defect ramp (KC_RAMP) and whether
# the depths can be non-zero: a path inside a localized defect, waviness or a film (KC_INSIDE)
K_PSI, K_COS, K_SIN, K_DEPTH, K_DDEPTH, K_Q, K_CACHE = 0, 1, 2, 3, 4, 5, 6
N_KIN = 7
KC_RATE, KC_RAMP, KC_INSIDE = 4, 5, 6
#: cos/sin of the cage angle are recomputed exactly after this many small rotations
#: (each rotation may add a rounding; 64 bound the drift to ~1e-14)
CACHE_REFRESH = 64

# fault kinds (codes in the F_KIND column): localized defects, then waviness rows, then
# the EHL film row (F_DEPTH the film h_i + h_o in m at the shaft speed F_CENTRE in
# rad/s, F_HALF its speed exponent)
KIND_OUTER, KIND_INNER, KIND_BALL = 0, 1, 2
KIND_WAVY_OUTER, KIND_WAVY_INNER, KIND_WAVY_BALL = 3, 4, 5
KIND_FILM = 6

N_CORE = 8
TWO_PI = 2.0 * math.pi


@njit(cache=True, error_model="numpy")
def wrap_pi(a):
    """Wrap an angle (rad) to [-pi, pi)."""
    return a - TWO_PI * math.floor((a + math.pi) / TWO_PI)


@njit(cache=True, error_model="numpy")
def shaft_angle(t, p):
    """Shaft angle turned since t = 0 for a linear speed ramp, rad."""
    return p[P_W0] * t + 0.5 * (p[P_W1] - p[P_W0]) * t * t / p[P_T]


@njit(cache=True, error_model="numpy")
def shaft_rate(t, p):
    """Shaft angular speed at t, rad/s."""
    return p[P_W0] + (p[P_W1] - p[P_W0]) * t / p[P_T]


@njit(cache=True, error_model="numpy")
def knot_position(t, p):
    """Nominal cage angle at t in units of the element spacing: the slip walk has a
    knot at every integer, where the cage speed jumps (see :func:`cage_angle`)."""
    return p[P_CAGE] * shaft_angle(t, p) / (TWO_PI / p[P_Z])


@njit(cache=True, error_model="numpy")
def cage_angle(t, p, walk):
    """Angle of element 0 (rad) and the cage's angular speed (rad/s) at time t.

    The cage turns at its kinematic rate plus a random walk ``walk`` (rad), sampled at
    every element spacing of nominal cage angle and interpolated linearly between:
    each interval between consecutive ball passes is stretched by an independent
    random fraction, so inter-impact periods vary with standard deviation ``slip`` of
    the nominal period and the cage keeps its mean speed (the random-slip model of
    Randall & Antoni 2011).
    """
    step = TWO_PI / p[P_Z]
    nominal = p[P_CAGE] * shaft_angle(t, p)
    x = knot_position(t, p)
    k = math.floor(x)
    f = x - k
    kk = int(k)
    n_knots = walk.shape[0]
    if kk < 0:
        kk = 0
    if kk > n_knots - 2:
        kk = n_knots - 2
    angle = nominal + walk[kk] * (1.0 - f) + walk[kk + 1] * f
    rate = p[P_CAGE] * shaft_rate(t, p) * (1.0 + (walk[kk + 1] - walk[kk]) / step)
    return angle, rate


@njit(cache=True, error_model="numpy")
def kinematics_scratch(z):
    """Fresh ``kin`` scratch for Z elements (zeroed: no cached cage angle yet)."""
    return np.zeros((N_KIN, max(z, KC_INSIDE + 1)))


@njit(cache=True, error_model="numpy", inline="always")
def cached_cos_sin(angle, cache):
    """cos and sin of ``angle`` (rad), from those of the previous call.

    ``cache`` holds that call's angle, cosine and sine and the number of calls left
    before an exact refresh (0: nothing cached yet); they are rotated through the small
    angle between the calls (Taylor series to 8th order: exact to 1e-21 below 0.01 rad),
    with trigonometric calls only for a larger jump or every ``CACHE_REFRESH`` calls.
    ``cache`` is updated.
    """
    d = angle - cache[0]
    if cache[3] > 0.0 and abs(d) < 0.01:
        d2 = d * d
        cd = 1.0 - d2 * (0.5 - d2 * (1.0 / 24.0 - d2 / 720.0))
        sd = d * (1.0 - d2 * (1.0 / 6.0 - d2 * (1.0 / 120.0 - d2 / 5040.0)))
        c = cache[1] * cd - cache[2] * sd
        sn = cache[2] * cd + cache[1] * sd
        cache[3] -= 1.0
    else:
        c = math.cos(angle)
        sn = math.sin(angle)
        cache[3] = CACHE_REFRESH
    cache[0] = angle
    cache[1] = c
    cache[2] = sn
    return c, sn


@njit(cache=True, error_model="numpy")
def element_angles(t, p, walk, kin):
    """Angular positions of the rolling elements at time t (rad) into ``kin[K_PSI]``.

    Elements keep their nominal spacing 2 pi / Z behind the cage angle of
    :func:`cage_angle`. Also writes cos(psi) and sin(psi) into ``kin[K_COS]``,
    ``kin[K_SIN]``, advancing from element to element by a rotation, and from the cage
    angle of the previous call (cached in ``kin[K_CACHE]``) by a rotation through the
    small angle between them (Taylor series to 8th order: exact to 1e-21 below
    0.01 rad); trigonometric calls only for a larger jump or every
    ``CACHE_REFRESH`` calls. Returns the cage's angular speed, rad/s.
    """
    step = TWO_PI / p[P_Z]
    cage, rate = cage_angle(t, p, walk)
    c, sn = cached_cos_sin(cage, kin[K_CACHE])
    kin[K_CACHE, KC_RATE] = rate
    cs = p[P_COS_STEP]
    ss = p[P_SIN_STEP]
    for j in range(int(p[P_Z])):
        kin[K_PSI, j] = cage + step * j
        kin[K_COS, j] = c
        kin[K_SIN, j] = sn
        c, sn = c * cs - sn * ss, sn * cs + c * ss
    return rate


@njit(cache=True, error_model="numpy")
def profile(offset, half, depth, ramp, shape=RAMP_COSINE):
    """Depth of a defect at angular offset ``offset`` from its centre, m.

    ``half`` is the half extent (rad), ``ramp`` the fraction of the extent taken by each
    ramp (0 = sharp rectangular notch), ``shape`` the ramp's form: RAMP_COSINE, a
    half-cosine (smooth at both ends), or RAMP_LINEAR, a blunted edge (Liu & Shao 2014,
    Wrzochal & Adamczak's review section 4.2: the ball rolls on the flat cut of the edge, so its
    centre
    drops linearly from the edge to the ramp end).
    """
    a = abs(offset)
    if a >= half:
        return 0.0
    if ramp <= 0.0:
        return depth
    x = (half - a) / (2.0 * half)  # 0 at the edge, 0.5 at the centre
    if x >= ramp:
        return depth
    if shape == RAMP_LINEAR:
        return depth * x / ramp
    return depth * 0.5 * (1.0 - math.cos(math.pi * x / ramp))


@njit(cache=True, error_model="numpy")
def profile_slope(offset, half, depth, ramp, shape=RAMP_COSINE):
    """d(profile)/d(offset), m/rad: zero outside the ramps (a sharp notch's jumps are
    events, handled by the integrators, not slopes)."""
    a = abs(offset)
    if a >= half or ramp <= 0.0:
        return 0.0
    x = (half - a) / (2.0 * half)
    if x >= ramp:
        return 0.0
    dx = -0.5 / half if offset > 0.0 else 0.5 / half
    if shape == RAMP_LINEAR:
        return depth / ramp * dx
    return depth * 0.5 * math.sin(math.pi * x / ramp) * (math.pi / ramp) * dx


@njit(cache=True, error_model="numpy")
def race_reference(faults, i, theta):
    """Angle of the centre of race fault i (rad): fixed on the outer race, turning
    with the shaft (``theta``, rad) on the inner race."""
    centre = faults[i, F_CENTRE]
    if int(faults[i, F_KIND]) == KIND_INNER:
        centre += theta
    return centre


@njit(cache=True, error_model="numpy")
def path_offset(faults, i, p, psi_j, theta, face):
    """Signed angular offset (rad, in [-pi, pi)) of a path from the centre of fault i.

    ``psi_j`` is the angle of the element on the path (for a ball defect: of the
    defective element), ``theta`` the shaft angle, ``face`` 0 or 1 for a ball defect
    facing the outer (spin phase 0) or the inner race (phase pi). Race offsets are
    wrap_pi(psi_j - race_reference), the arithmetic :func:`fault_depths` uses, so
    event times found with this function are exactly where the kernels switch.
    """
    if int(faults[i, F_KIND]) == KIND_BALL:
        spin = faults[i, F_CENTRE] + p[P_SPIN] * (psi_j - faults[i, F_PSI0])
        return wrap_pi(spin - math.pi * face)
    return wrap_pi(psi_j - race_reference(faults, i, theta))


@njit(cache=True, error_model="numpy")
def path_rate(faults, i, p, cage_rate, shaft_w):
    """d(offset)/dt of the paths of fault i, rad/s."""
    kind = int(faults[i, F_KIND])
    if kind == KIND_BALL:
        return p[P_SPIN] * cage_rate
    if kind == KIND_INNER:
        return cage_rate - shaft_w
    return cage_rate


@njit(cache=True, error_model="numpy")
def engaged(faults, i, spin):
    """Whether ball defect i lies on the rolling band during the spin revolution that
    holds spin phase ``spin`` (rad): a pseudo-random draw per revolution with
    probability ``faults[i, F_ENGAGE]`` (1 = always, Sawalhi & Randall).

    Revolution k runs from spin phase 2 pi k - pi/2 to 2 pi k + 3 pi/2, so it holds the
    outer-race contact (phase 2 pi k) and the inner-race one (2 pi k + pi) and switches
    where neither face can be inside a defect (narrower than the ball): no new events.
    The draw is a hash of (k, seed), fixed for a scene.
    """
    prob = faults[i, F_ENGAGE]
    if prob >= 1.0:
        return True
    k = math.floor((spin + 0.5 * math.pi) / TWO_PI)
    x = math.sin(k * 12.9898 + faults[i, F_SEED] * 78.233) * 43758.5453
    return x - math.floor(x) < prob


@njit(cache=True, error_model="numpy")
def _unit_draw(k, seed):
    """A uniform draw in [0, 1) for revolution ``k`` (int) and a fault's ``seed``
    (float, an integer value): the splitmix64 finaliser of both, fixed for a scene."""
    z = np.uint64(k + 2**40) * np.uint64(0x9E3779B97F4A7C15) + np.uint64(seed)
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    z = z ^ (z >> np.uint64(31))
    return float(z >> np.uint64(11)) * 2.0 ** -53


@njit(cache=True, error_model="numpy")
def strip_share(s, r):
    """Share of a Hertz contact's load on the strip |x - s| < r across the track, in
    units of the ellipse's semi-axis a: the load density across the track goes as
    1 - x^2 (Johnson, Contact Mechanics, 1985, sec. 4.2), whose integral over [-1, 1]
    is 4/3; 0 when the strip misses the ellipse."""
    lo = max(s - r, -1.0)
    hi = min(s + r, 1.0)
    if hi <= lo:
        return 0.0
    return 0.75 * ((hi - hi ** 3 / 3.0) - (lo - lo ** 3 / 3.0))


@njit(cache=True, error_model="numpy")
def strike_share(faults, i, spin, face):
    """Depth factor, in [0, 1], of ball defect i during the spin revolution holding
    spin phase ``spin`` (rad), where it meets the outer race (``face`` 0) or the inner
    race (1): 0 when the defect misses the rolling band, 1 when it strikes as a defect
    on the band does.

    The engagement draw of :func:`engaged` first; then, with a spin-axis drift
    (``faults[i, F_DRIFT]`` = sin D > 0), the defect's latitude lambda from the
    rolling band's centre line is drawn per revolution with sin(lambda) uniform on
    [-sin D, sin D]: the spin axis uniform over the directions within D of square
    to the defect's radius (Archimedes: a uniform direction on a zone of the sphere
    has a uniform sine of latitude; D = 90 deg, a ball turning every way). The pit,
    of radius r, then lies s = R sin(lambda) off the centre line of the contact
    ellipse (semi-axis a across the track, that of the race the face meets: one
    latitude per revolution, two ellipses); it removes the strip |x - s| < r of the
    contact (:func:`strip_share`), and the depth is scaled by that share over the
    share of a pit on the centre line. It strikes a face on a share
    min(1, (r + a) / (R sin D)) of the revolutions.
    """
    if not engaged(faults, i, spin):
        return 0.0
    sin_d = faults[i, F_DRIFT]
    if sin_d <= 0.0:
        return 1.0
    k = math.floor((spin + 0.5 * math.pi) / TWO_PI)
    u = (2.0 * _unit_draw(k, faults[i, F_SEED]) - 1.0) * sin_d
    scale = faults[i, F_A_IN] if face == 1 else 1.0   # a_outer / a_face
    r = faults[i, F_PIT_A] * scale
    return strip_share(u * faults[i, F_BALL_A] * scale, r) / strip_share(0.0, r)


@njit(cache=True, error_model="numpy")
def waviness(faults, i, p, kin, th, w, cage_rate, rates):
    """Add the waviness row i of the fault table to the contact geometry in ``kin``.

    A race (or ball) surface raised by r(phi) = A cos(q phi + phase) (order q, amplitude
    A, m) closes the gap of the contact at that point: the deflection of element j
    gains r, i.e. ``kin[K_DEPTH, j]`` (the extra clearance) loses it (Wrzochal & Adamczak's review
    section
    4.4, Liu & Shao 2015 eq. 19: delta_j = ... + Pi_j). phi is the contact's angle on
    the wavy body: psi_j on the outer race, psi_j - theta on the inner race; on ball e
    its spin phase s at the outer-race contact and s + pi at the inner-race one.
    """
    kind = int(faults[i, F_KIND])
    q = faults[i, F_HALF]
    amp = faults[i, F_DEPTH]
    phase = faults[i, F_CENTRE]
    if kind == KIND_WAVY_BALL:
        e = int(faults[i, F_ELEM])
        spin = p[P_SPIN] * (kin[K_PSI, e] - faults[i, F_PSI0]) + phase
        for face in range(2):
            arg = q * (spin + math.pi * face)
            kin[K_DEPTH, e] -= amp * math.cos(arg)
            if rates:
                kin[K_DDEPTH, e] += amp * q * math.sin(arg) * p[P_SPIN] * cage_rate
        return
    rel = th if kind == KIND_WAVY_INNER else 0.0
    rate = cage_rate - w if kind == KIND_WAVY_INNER else cage_rate
    for j in range(int(p[P_Z])):
        arg = q * (kin[K_PSI, j] - rel) + phase
        kin[K_DEPTH, j] -= amp * math.cos(arg)
        if rates:
            kin[K_DDEPTH, j] += amp * q * math.sin(arg) * rate


@njit(cache=True, error_model="numpy")
def film(faults, i, p, kin, w, rates):
    """EHL film row i at shaft speed w (rad/s): every element's approach gains the film
    h = h_ref (w / w_ref)^e (Liu & Shao 2015 eq. 19, as Wrzochal & Adamczak report it;
    Hamrock & Dowson's film grows as the entrainment speed to the power e), so its extra
    clearance ``kin[K_DEPTH, j]`` loses it; with ``rates`` also dh/dt = e h w' / w."""
    expo = faults[i, F_HALF]
    h = faults[i, F_DEPTH] * (w / faults[i, F_CENTRE]) ** expo
    dh = expo * h * (p[P_W1] - p[P_W0]) / (p[P_T] * w) if rates else 0.0
    for j in range(int(p[P_Z])):
        kin[K_DEPTH, j] -= h
        kin[K_DDEPTH, j] -= dh


@njit(cache=True, error_model="numpy")
def fault_depths(t, p, faults, kin, cage_rate, rates):
    """Extra clearance opened by the defects for each element at time t (m) into
    ``kin[K_DEPTH]``; with ``rates`` (always with contact damping, which needs them)
    also its time derivative (m/s) into ``kin[K_DDEPTH]`` (``cage_rate`` in rad/s).
    Needs the element angles in ``kin``. Sets ``kin[K_CACHE, KC_RAMP]`` to 1 when an
    element is on a defect ramp, and ``kin[K_CACHE, KC_INSIDE]`` to 1 when some path
    lies inside a localized defect (|offset| < half extent) or the table has waviness
    or film rows: otherwise every depth and rate written is exactly zero. Both flags change
    only at fault-edge crossings, which the integrators step to: read between two
    crossings, they hold from one to the next.

    Outer race: fixed centre. Inner race: centre turns with the shaft. Ball defect on
    element e: its spin phase advances at the ball spin rate relative to the cage
    (rolling without slip on the element's own path), facing the outer race at phase 0
    and the inner race at phase pi; it meets the races only on the spin revolutions
    drawn by :func:`engaged`, as deep as :func:`strike_share` gives, of its depth
    against that race (F_DEPTH facing the outer race, F_DEPTH_IN the inner). Waviness
    rows: :func:`waviness`; the film row: :func:`film`.
    """
    z = int(p[P_Z])
    rates = rates or p[P_CD] != 0.0
    for j in range(z):
        kin[K_DEPTH, j] = 0.0
        kin[K_DDEPTH, j] = 0.0
    on_ramp = 0.0
    inside = 0.0
    th = shaft_angle(t, p)
    w = shaft_rate(t, p)
    for i in range(faults.shape[0]):
        kind = int(faults[i, F_KIND])
        if kind == KIND_FILM:
            film(faults, i, p, kin, w, rates)
            inside = 1.0
            continue
        if kind >= KIND_WAVY_OUTER:
            waviness(faults, i, p, kin, th, w, cage_rate, rates)
            inside = 1.0
            continue
        half = faults[i, F_HALF]
        ramp = faults[i, F_RAMP]
        shape = faults[i, F_SHAPE]
        dr = path_rate(faults, i, p, cage_rate, w)
        if kind == KIND_BALL:
            e = int(faults[i, F_ELEM])
            spin = faults[i, F_CENTRE] + p[P_SPIN] * (kin[K_PSI, e] - faults[i, F_PSI0])
            for face in range(2):
                off = path_offset(faults, i, p, kin[K_PSI, e], th, face)
                if abs(off) >= half:
                    continue
                inside = 1.0
                share = strike_share(faults, i, spin, face)
                if share == 0.0:
                    continue
                depth = share * faults[i, F_DEPTH_IN if face == 1 else F_DEPTH]
                kin[K_DEPTH, e] += profile(off, half, depth, ramp, shape)
                slope = profile_slope(off, half, depth, ramp, shape)
                if slope != 0.0:
                    on_ramp = 1.0
                if rates:
                    kin[K_DDEPTH, e] += dr * slope
        else:
            depth = faults[i, F_DEPTH]
            ref = race_reference(faults, i, th)
            # Only the element nearest the centre (at most half a spacing away) and
            # those within `side` spacings of it can be inside: the k-th neighbour is
            # at least (k - 1/2) spacings away, beyond the half extent for k > side,
            # and keeps exactly the zero depth the profile would give it. A defect
            # narrower than the spacing (every outer-race one) leaves the nearest
            # element alone: one instead of Z.
            spacing = TWO_PI / p[P_Z]
            side = int(half / spacing + 0.5)
            n_cand = 2 * side + 1
            near = int(round(-wrap_pi(kin[K_PSI, 0] - ref) / spacing)) - side
            if n_cand >= z:
                n_cand = z
                near = 0
            for c in range(n_cand):
                j = (near + c) % z
                off = wrap_pi(kin[K_PSI, j] - ref)  # = path_offset, hoisted
                if abs(off) < half:
                    inside = 1.0
                kin[K_DEPTH, j] += profile(off, half, depth, ramp, shape)
                slope = profile_slope(off, half, depth, ramp, shape)
                if slope != 0.0:
                    on_ramp = 1.0
                if rates:
                    kin[K_DDEPTH, j] += dr * slope
    kin[K_CACHE, KC_RAMP] = on_ramp
    kin[K_CACHE, KC_INSIDE] = inside


@njit(cache=True, error_model="numpy")
def kinematics(t, p, walk, faults, kin):
    """Element angles (with cos/sin) and fault depths at time t into ``kin``; returns
    the cage speed, rad/s. Depends on t only, so stages at one time share it."""
    rate = element_angles(t, p, walk, kin)
    fault_depths(t, p, faults, kin, rate, False)
    return rate


@njit(cache=True, error_model="numpy")
def hertz(d, kh, nh):
    """Hertz load K d^n of a contact compressed by d >= 0 (m), N (exactly 0 at d = 0);
    d^1.5 as d sqrt(d)."""
    return kh * d * math.sqrt(d) if nh == 1.5 else kh * d**nh


@njit(cache=True, error_model="numpy")
def axial_approach(d, p):
    """Normal approach (m) and cos(alpha) of a ball whose radial approach is ``d`` (m,
    clearance and defects included) under an axial load: the groove centres are
    hypot(P_AX, A + d) apart, A when unloaded (Harris & Kotzalas ch. 7; A + d is
    A cos(alpha_0) plus the radial displacement along the ball)."""
    rad = p[P_A] + d
    s = math.hypot(p[P_AX], rad)
    return s - p[P_A], rad / s


@njit(cache=True, error_model="numpy")
def contact_load(j, du, dv, ddu, ddv, p, kin):
    """Load of contact j, N, from the ring offset (du, dv) and its rate (ddu, ddv):
    Hertz Q = K max(delta, 0)^n, times the Hunt-Crossley factor 1 + alpha d(delta)/dt
    with contact damping (``p[P_CD] = alpha > 0``), never negative.

    delta = du cos psi + dv sin psi - c - depth (Sawalhi & Randall 2008 eq. 12 as
    printed in Tran, Furch & Cu); d(delta)/dt = ddu cos psi + ddv sin psi + (dv cos psi -
    du sin psi) psi' - d(depth)/dt. The damping force alpha Q_hertz d(delta)/dt grows
    with the load and vanishes on separation with it (Hunt & Crossley 1975): no jump
    at contact, and a receding contact never pulls. Separated contacts carry exactly
    zero force.
    """
    cj = kin[K_COS, j]
    sj = kin[K_SIN, j]
    d = du * cj + dv * sj - p[P_CLEAR] - kin[K_DEPTH, j]
    cos_a = 1.0
    if p[P_AX] != 0.0:
        # axial load: the normal approach, and only the radial share Q cos(alpha) acts
        # on the shaft and pedestal
        d, cos_a = axial_approach(d, p)
    if d <= 0.0:
        return 0.0
    q = hertz(d, p[P_KH], p[P_NH]) * cos_a
    alpha = p[P_CD]
    if alpha == 0.0:
        return q
    vel = (ddu * cj + ddv * sj + (dv * cj - du * sj) * kin[K_CACHE, KC_RATE]
           - kin[K_DDEPTH, j]) * cos_a
    f = 1.0 + alpha * vel
    return q * f if f > 0.0 else 0.0


@njit(cache=True, error_model="numpy")
def contact_loads(y, p, kin, iv):
    """Contact loads of :func:`contact_load`, N, into ``kin[K_Q]``. ``y`` starts with
    u_s, v_s, u_p, v_p; their rates are at ``y[iv:iv + 4]`` (4 for the core layout,
    4 + n_res for the full one)."""
    du = y[0] - y[2]
    dv = y[1] - y[3]
    ddu = y[iv] - y[iv + 2]
    ddv = y[iv + 1] - y[iv + 3]
    for j in range(int(p[P_Z])):
        kin[K_Q, j] = contact_load(j, du, dv, ddu, ddv, p, kin)


@njit(cache=True, error_model="numpy")
def pedestal_forces(p, up, vp, dup, dvp):
    """Spring, damping and gravity forces on the pedestal along u and v, N."""
    fu = -p[P_KP] * up - p[P_CP] * dup + p[P_MP] * p[P_G]
    fv = -p[P_KP] * vp - p[P_CP] * dvp
    return fu, fv


@njit(cache=True, error_model="numpy")
def core_forces(y, p, kin, dydt):
    """Core right-hand side (layout ``yc``) at state ``y`` with the kinematics already in
    ``kin`` (see :func:`kinematics`); the contact loads are left in ``kin[K_Q]``.
    Returns which contacts carry load, as the bits of an integer (element j on bit
    j mod 62), for the integrators' contact-state checks.

    Shaft:      m_s a_s = -k_s (x_s - x_s0) - c_s v_s - sum_j Q_j n_j + F_r e_u + m_s g e_u
    Pedestal:   m_p a_p = -k_p x_p - c_p v_p + sum_j Q_j n_j + m_p g e_u
    """
    # the loads of :func:`contact_loads`, summed in the same loop (a kernel that calls
    # another looping kernel keeps numba's reference counting of its array arguments)
    du = y[0] - y[2]
    dv = y[1] - y[3]
    ddu = y[4] - y[6]
    ddv = y[5] - y[7]
    fu = 0.0
    fv = 0.0
    z = int(p[P_Z])
    if p[P_CD] == 0.0 and p[P_AX] == 0.0:
        # without contact damping and axial load the loads are K max(delta, 0)^n,
        # branch-free so the loop vectorises (K 0 sqrt(0) = 0: separated contacts carry
        # exactly zero); the same values as :func:`contact_load`, summed in the same order
        kh = p[P_KH]
        nh = p[P_NH]
        c = p[P_CLEAR]
        for j in range(z):
            d = du * kin[K_COS, j] + dv * kin[K_SIN, j] - c - kin[K_DEPTH, j]
            kin[K_Q, j] = hertz(d if d > 0.0 else 0.0, kh, nh)
    else:
        for j in range(z):
            kin[K_Q, j] = contact_load(j, du, dv, ddu, ddv, p, kin)
    mask = 0
    bit = 1
    for j in range(z):
        q = kin[K_Q, j]
        fu += q * kin[K_COS, j]
        fv += q * kin[K_SIN, j]
        if q != 0.0:
            mask |= bit
        bit = bit << 1 if j % 62 != 61 else 1
    ms = p[P_MS]
    mp = p[P_MP]
    dydt[0] = y[4]
    dydt[1] = y[5]
    dydt[2] = y[6]
    dydt[3] = y[7]
    dydt[4] = (-p[P_KS] * (y[0] - p[P_US0]) - p[P_CS] * y[4] - fu + p[P_FR]) / ms + p[P_G]
    dydt[5] = (-p[P_KS] * (y[1] - p[P_VS0]) - p[P_CS] * y[5] - fv) / ms
    pu, pv = pedestal_forces(p, y[2], y[3], y[6], y[7])
    dydt[6] = (pu + fu) / mp
    dydt[7] = (pv + fv) / mp
    return mask


@njit(cache=True, error_model="numpy")
def housing_accel(y, dydt, p, sensors, kin, cage_rate, out, row, rates):
    """Local housing acceleration along each sensor's direction (m/s^2) into
    ``out[row]`` and, with ``rates``, its time derivative (m/s^3) into ``out[row + 1]``.

    The pedestal's rigid-body acceleration with each contact force weighted by its
    transmission factor exp(-kappa (1 - cos(psi_j - theta_i))) to sensor i: 1 at the
    sensor, exp(-2 kappa) opposite it (after McFadden & Smith 1984). With kappa = 0 this
    is exactly the pedestal acceleration projected on the sensor axis.

    ``y`` is a core state (layout ``yc``) with the kinematics and the contact loads of
    that state already in ``kin`` (see :func:`core_forces`). For the derivative,
    ``dydt`` is the core derivative at (t, y), ``cage_rate`` the cage speed (rad/s)
    and ``kin`` must hold the fault-depth rates (:func:`fault_depths` with
    ``rates``). Each term is differentiated
    exactly: dQ_j/dt = n K delta_j^(n-1) d(delta_j)/dt, and the transmission-weighted
    projection w c turns with the element at the cage speed.
    """
    mp = p[P_MP]
    fu, fv = pedestal_forces(p, y[2], y[3], y[6], y[7])
    dfu = dfv = 0.0
    du = y[0] - y[2]
    dv = y[1] - y[3]
    ddu = ddv = 0.0
    if rates:
        dfu = -p[P_KP] * y[6] - p[P_CP] * dydt[6]
        dfv = -p[P_KP] * y[7] - p[P_CP] * dydt[7]
        ddu = y[4] - y[6]
        ddv = y[5] - y[7]
    nh = p[P_NH]
    c = p[P_CLEAR]
    alpha = p[P_CD]
    for i in range(sensors.shape[0]):
        ci = sensors[i, S_COS]
        si = sensors[i, S_SIN]
        kappa = sensors[i, S_ATT]
        acc = (fu * ci + fv * si) / mp
        dacc = (dfu * ci + dfv * si) / mp
        for j in range(int(p[P_Z])):
            q = kin[K_Q, j]
            if q != 0.0:
                cj = kin[K_COS, j]
                sj = kin[K_SIN, j]
                cos_rel = cj * ci + sj * si
                w = math.exp(-kappa * (1.0 - cos_rel)) if kappa != 0.0 else 1.0
                acc += w * q * cos_rel / mp
                if rates:
                    d = du * cj + dv * sj - c - kin[K_DEPTH, j]
                    dd = ddu * cj + ddv * sj + (dv * cj - du * sj) * cage_rate - kin[K_DDEPTH, j]
                    if p[P_AX] == 0.0:
                        dq = nh * q / d * dd
                    else:
                        # q = H cos(alpha), H = K delta^n: dq/dd = n H cos^2(alpha) /
                        # delta + H sin^2(alpha) / s (s the groove centres' distance)
                        delta, cos_a = axial_approach(d, p)
                        h = q / cos_a
                        dq = (nh * h * cos_a * cos_a / delta
                              + h * (1.0 - cos_a * cos_a) / (p[P_A] + delta)) * dd
                    if alpha != 0.0:
                        # Hunt-Crossley: Q = H (1 + alpha dd); d/dt adds H alpha dd',
                        # dd' from the relative acceleration (the second derivatives
                        # of the depth and of the projection are left out: this rate
                        # only shapes the resonator input between steps)
                        dd2 = (dydt[4] - dydt[6]) * cj + (dydt[5] - dydt[7]) * sj
                        dq += q / (1.0 + alpha * dd) * alpha * dd2
                    dcos = -(sj * ci - cj * si) * cage_rate
                    dacc += w * (dq * cos_rel + q * (1.0 + kappa * cos_rel) * dcos) / mp
        out[row, i] = acc
        if rates:
            out[row + 1, i] = dacc


@njit(cache=True, error_model="numpy")
def rhs(t, y, dydt, p, walk, faults, sensors, n_res, kin, buf, acc):
    """Right-hand side of the full sr4/sr5 equations of motion (layout ``y``); writes
    dy/dt into ``dydt``.

    The core equations of :func:`core_forces` plus, for sr5, the resonator of each
    sensor i: z_i'' + 2 zeta w z_i' + w^2 z_i = -s_i'' (base excitation by the local
    housing acceleration s_i'' of :func:`housing_accel`). Scratch: ``buf`` of length 16,
    ``acc`` of shape (1, n_sensors).
    """
    nd = 4 + n_res
    yc = buf[:N_CORE]
    dc = buf[N_CORE:]
    for i in range(4):
        yc[i] = y[i]
        yc[4 + i] = y[nd + i]
    kinematics(t, p, walk, faults, kin)
    core_forces(yc, p, kin, dc)
    for i in range(4):
        dydt[i] = dc[i]
        dydt[nd + i] = dc[4 + i]
    if n_res > 0:
        housing_accel(yc, dc, p, sensors, kin, 0.0, acc, 0, False)
        w = p[P_WR]
        zeta = p[P_ZETA]
        for i in range(n_res):
            dydt[4 + i] = y[nd + 4 + i]
            dydt[nd + 4 + i] = -2.0 * zeta * w * y[nd + 4 + i] - w * w * y[4 + i] - acc[0, i]


@njit(cache=True, error_model="numpy")
def sensor_output(t, y, p, walk, faults, sensors, n_res, kin, out):
    """Acceleration measured by each sensor at full state y, m/s^2, into ``out[0]``.

    sr5 (``n_res > 0``): absolute acceleration of the sensor's resonator mass,
    -(2 zeta w z_i' + w^2 z_i) (as Sawalhi & Randall measure y_b). sr4: the local
    housing acceleration itself.
    """
    if n_res > 0:
        nd = 4 + n_res
        w = p[P_WR]
        zeta = p[P_ZETA]
        for i in range(n_res):
            out[0, i] = -(2.0 * zeta * w * y[nd + 4 + i] + w * w * y[4 + i])
        return
    kinematics(t, p, walk, faults, kin)
    contact_loads(y, p, kin, 4)
    housing_accel(y, y, p, sensors, kin, 0.0, out, 0, False)


@njit(cache=True, error_model="numpy")
def sensor_output_many(t, states, p, walk, faults, sensors, n_res):
    """:func:`sensor_output` at many (time, full state) pairs: (len(t), n_sensors),
    m/s^2."""
    kin = kinematics_scratch(int(p[P_Z]))
    out = np.empty((t.shape[0], sensors.shape[0]))
    for k in range(t.shape[0]):
        sensor_output(t[k], states[k], p, walk, faults, sensors, n_res, kin, out[k:k + 1])
    return out


@njit(cache=True, error_model="numpy")
def element_angles_many(t, p, walk, z):
    """Element angles at many times: (len(t), Z) array, rad (for kinematics in Python)."""
    out = np.empty((t.shape[0], z))
    kin = kinematics_scratch(z)
    for k in range(t.shape[0]):
        element_angles(t[k], p, walk, kin)
        out[k, :] = kin[K_PSI, :z]
    return out


@njit(cache=True, error_model="numpy")
def fault_offset(t, p, walk, faults, i, j):
    """Signed angular offset (rad, in [-pi, pi)) of path j from the centre of fault i.

    Races: ``j`` is the element. Ball defect: ``j`` selects the face, 0 = facing the
    outer race (phase 0), 1 = the inner race (phase pi). Same arithmetic as
    :func:`fault_depths` (both go through :func:`path_offset`).
    """
    return _offset_at(cage_angle(t, p, walk)[0], shaft_angle(t, p), p, faults, i, j)


@njit(cache=True, error_model="numpy")
def _offset_at(cage, theta, p, faults, i, j):
    """:func:`fault_offset` from the cage angle ``cage`` and shaft angle ``theta`` (rad)
    at its time, which every path at that time shares."""
    step = TWO_PI / p[P_Z]
    if int(faults[i, F_KIND]) == KIND_BALL:
        return path_offset(faults, i, p, cage + step * int(faults[i, F_ELEM]), 0.0, j)
    return path_offset(faults, i, p, cage + step * j, theta, 0)


@njit(cache=True, error_model="numpy")
def _bracket(p, walk, faults, i, j, level, a_side, lo, hi, f_lo, f_hi):
    """Shrink [lo, hi] around the time path j of fault i crosses ``level`` to adjacent
    floating-point numbers: secant steps (the offset is nearly linear in time), each
    followed by a probe on the far side of its estimate, at twice the distance the
    secant slope puts the crossing from it (plus two units in the last place), which
    closes the bracket from both sides; then bisection. The side test is
    ``offset >= level``, as in the kernels, and every update keeps it straddled, so the
    result is the adjacent pair the side test switches between."""
    for _ in range(100):
        if hi - lo <= 1e-12 * (hi - lo + abs(hi)):
            break
        m = hi - f_hi * (hi - lo) / (f_hi - f_lo)
        if not (lo < m < hi):
            m = 0.5 * (lo + hi)
        slope = (f_hi - f_lo) / (hi - lo)
        o_m = fault_offset(m, p, walk, faults, i, j)
        f_m = o_m - level
        reach = 2.0 * abs(f_m / slope) + 4e-16 * abs(m)
        if (o_m >= level) == a_side:
            lo, f_lo = m, f_m
            q = m + reach
            if q < hi:
                o_q = fault_offset(q, p, walk, faults, i, j)
                if (o_q >= level) == a_side:
                    lo, f_lo = q, o_q - level
                else:
                    hi, f_hi = q, o_q - level
        else:
            hi, f_hi = m, f_m
            q = m - reach
            if q > lo:
                o_q = fault_offset(q, p, walk, faults, i, j)
                if (o_q >= level) == a_side:
                    lo, f_lo = q, o_q - level
                else:
                    hi, f_hi = q, o_q - level
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if (fault_offset(mid, p, walk, faults, i, j) >= level) == a_side:
            lo = mid
        else:
            hi = mid
    return lo, hi


@njit(cache=True, error_model="numpy")
def _secant(p, walk, faults, i, j, level, lo, hi, f_lo, f_hi):
    """The time (s) path j of fault i crosses ``level`` in [lo, hi], to 1e-13 s:
    false-position steps with the Illinois halving (Dahlquist & Bjorck). Between slip
    knots at constant speed the offset is linear in time, and one step lands on the
    crossing to rounding; a knot or a speed ramp inside [lo, hi] takes a few more."""
    m = lo
    side = 0  # which end the last step replaced: -1 lo, +1 hi
    for _ in range(60):
        m = hi - f_hi * (hi - lo) / (f_hi - f_lo)
        if not (lo <= m <= hi):
            m = 0.5 * (lo + hi)
        f_m = fault_offset(m, p, walk, faults, i, j) - level
        slope = (f_hi - f_lo) / (hi - lo)
        if abs(f_m) <= SECANT_TOL_S * abs(slope) or hi - lo <= SECANT_TOL_S:
            break
        if (f_m >= 0.0) == (f_lo >= 0.0):
            lo, f_lo = m, f_m
            if side == -1:  # the same end twice: halve the other's weight
                f_hi *= 0.5
            side = -1
        else:
            hi, f_hi = m, f_m
            if side == 1:
                f_lo *= 0.5
            side = 1
    return m


#: time accuracy of :func:`_secant`, s
SECANT_TOL_S = 1e-13


@njit(cache=True, error_model="numpy")
def find_crossings(p, walk, faults, t_scan, levels_per_fault, before, after, index,
                   exact=True):
    """Times at which an element crosses a fault edge (or a ramp end), unsorted.

    Parameters
    ----------
    p, walk, faults : ndarray
        The model (see the module docstring).
    t_scan : ndarray, shape (n,)
        Increasing scan times, s. Each offset is monotone in time; within one scan
        interval it must move by less than pi (so a wrap is recognised) and the
        fault's levels lie within +-1 rad of its centre (see the caller).
    levels_per_fault : ndarray, shape (n_faults, 4)
        Offsets (rad) that mark an event for each fault: -half, -half_ramp, +half_ramp,
        +half (duplicates allowed for sharp edges; NaN to skip).
    before, after : ndarray (capacity,)
        Written with bracketing times (s): ``before < crossing <= after``, adjacent
        floating-point numbers (see :func:`_bracket`); with ``exact=False`` both hold
        the crossing to :data:`SECANT_TOL_S` (:func:`_secant`, a few offsets per
        crossing instead of the twenty or so of the bracket to adjacent numbers).
    index : ndarray of int64 (capacity, 3)
        Written with the fault, the element (the face for a ball defect) and the
        level of each crossing.
    exact : bool, optional
        True (default): brackets to adjacent floating-point numbers, where the
        integrators split their steps; False: the crossing times to 1e-13 s, enough to
        place an impact (the impulse model).

    Returns
    -------
    int
        Number of crossings written, or -1 when they exceed the capacity.
    """
    z = int(p[P_Z])
    n = 0
    # the cage and shaft angles at the scan times, shared by every path and fault
    cage = np.empty(t_scan.shape[0])
    theta = np.empty(t_scan.shape[0])
    for k in range(t_scan.shape[0]):
        cage[k] = cage_angle(t_scan[k], p, walk)[0]
        theta[k] = shaft_angle(t_scan[k], p)
    for i in range(faults.shape[0]):
        n_paths = 2 if int(faults[i, F_KIND]) == KIND_BALL else z
        for j in range(n_paths):
            o_prev = _offset_at(cage[0], theta[0], p, faults, i, j)
            for k in range(1, t_scan.shape[0]):
                o_next = _offset_at(cage[k], theta[k], p, faults, i, j)
                if abs(o_next - o_prev) < math.pi:
                    for lv in range(4):
                        level = levels_per_fault[i, lv]
                        if level != level:
                            continue
                        if lv > 0 and level == levels_per_fault[i, lv - 1]:
                            continue
                        a_side = o_prev >= level
                        if a_side == (o_next >= level):
                            continue
                        if n == before.shape[0]:
                            return -1
                        if exact:
                            before[n], after[n] = _bracket(
                                p, walk, faults, i, j, level, a_side, t_scan[k - 1],
                                t_scan[k], o_prev - level, o_next - level)
                        else:
                            before[n] = after[n] = _secant(
                                p, walk, faults, i, j, level, t_scan[k - 1], t_scan[k],
                                o_prev - level, o_next - level)
                        index[n, 0] = i
                        index[n, 1] = j
                        index[n, 2] = lv
                        n += 1
                o_prev = o_next
    return n


@njit(cache=True, error_model="numpy")
def find_knots(p, t_end):
    """Brackets ``(before, after)`` (s) of the slip-walk knots in (0, t_end], where the
    cage speed jumps, by bisection on :func:`knot_position` (the same arithmetic as the
    kernels, so each bracket straddles the kernels' switch)."""
    n = int(math.floor(knot_position(t_end, p)))
    before = np.empty(max(n, 0))
    after = np.empty(max(n, 0))
    lo = 0.0
    for k in range(1, n + 1):
        hi = t_end
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if math.floor(knot_position(mid, p)) >= k:
                hi = mid
            else:
                lo = mid
        before[k - 1] = lo
        after[k - 1] = hi
        lo = hi
    return before, after


@njit(cache=True, error_model="numpy")
def contact_loads_many(t, states, p, walk, faults):
    """Contact loads of every element at many (time, state) pairs: (len(t), Z), N.

    ``states`` rows start with u_s, v_s, u_p, v_p (either layout)."""
    z = int(p[P_Z])
    kin = kinematics_scratch(z)
    out = np.empty((t.shape[0], z))
    for k in range(t.shape[0]):
        kinematics(t[k], p, walk, faults, kin)
        contact_loads(states[k], p, kin, states.shape[1] // 2)
        out[k, :] = kin[K_Q, :z]
    return out
