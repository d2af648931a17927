"""The depth a defect lets the mating surface drop (``Fault.effective_depth_mm``): the
approach of two circles bridging a notch in the rolling plane, and what the simulators
make of it (a ball defect strikes the inner race deeper than the outer: a line at BSF).

Planted once each, and seen to fail: the +- sign of the race's sagitta swapped (inner
0.75x, outer 1.17x the ball's own sagitta): the geometry, multibody, contact-force and
impulse-step tests fail; the outer depth used on both races (the symmetric ball of the
old model): the multibody, contact-force, impulse-step and BSF-line tests fail.
"""

from __future__ import annotations

import math
from unittest import mock

import numpy as np
import pytest
from scipy import optimize

import ballpass as bp
from ballpass.simulate import _kernels as K
from ballpass.simulate.impulse import _impacts, impact_amplitudes
from ballpass.simulate.sr5 import build_model

B6205 = bp.Bearing.catalog("6205")
_ORIGINAL = bp.Fault.effective_depth_mm


def _symmetric(self, bearing, race=None):
    """The old model's ball defect: the same depth on both races (its outer one)."""
    return _ORIGINAL(self, bearing, "outer" if self.kind == "ball" else race)


def bridged_approach_mm(r_defect, r_mate, a, mate):
    """Approach (mm) of a mating circle (radius ``r_mate``) onto a circle of radius
    ``r_defect`` cut by a notch whose corners lie on it at half chord ``a``, by root
    finding on the mate's centre (on the symmetry axis, the defective circle's centre
    at 0, the notch at its top): the mate rests on both corners, a distance ``r_mate``
    from its centre, instead of touching the intact circle. ``mate``: "outside" (two
    convex surfaces, tangent with the centres r_d + r_m apart), "inside" (a ball in a
    notched concave race, its centre at r_d - r_m, moving out) or "around" (a race
    enclosing a notched ball, its centre at r_d - r_m, moving down)."""
    corner = math.sqrt(r_defect**2 - a**2)
    tol = dict(xtol=1e-15, rtol=4 * np.finfo(float).eps)
    if mate == "outside":
        c = optimize.brentq(lambda c: math.hypot(a, c - corner) - r_mate, corner,
                            corner + r_mate, **tol)
        return (r_defect + r_mate) - c
    c = optimize.brentq(lambda c: math.hypot(a, corner - c) - r_mate, corner - r_mate,
                        corner, **tol)
    return c - (r_defect - r_mate) if mate == "inside" else (r_defect - r_mate) - c


@pytest.mark.parametrize("bearing", ["6205", "6004", "NJ305"])
@pytest.mark.parametrize("width_mm", [0.18, 0.36, 0.53, 2.0])
def test_the_drop_is_the_approach_of_two_circles_bridging_the_notch(bearing, width_mm):
    """Closed form s(R_b) +- s(R_race) against the circles' own geometry by root
    finding, for a notch in each race and a ball defect striking each race. The drops
    are 1e-3 to 1e-1 mm against centre distances of 10-30 mm: brentq's 1e-15 mm and
    the cancellation in c0 - c (a few 1e-15 mm) leave 1e-9 relative."""
    b = bp.Bearing.catalog(bearing)
    a = 0.5 * width_mm
    rb = 0.5 * b.element_diameter_mm
    ri, ro = b.inner_race_radius_m * 1e3, b.outer_race_radius_m * 1e3
    deep = 5.0   # deeper than any drop: the geometry decides
    cases = {
        ("inner", None): bridged_approach_mm(ri, rb, a, "outside"),
        ("outer", None): bridged_approach_mm(ro, rb, a, "inside"),
        ("ball", "inner"): bridged_approach_mm(rb, ri, a, "outside"),
        ("ball", "outer"): bridged_approach_mm(rb, ro, a, "around"),
    }
    for (kind, race), expected in cases.items():
        got = bp.Fault(kind, width_mm=width_mm, depth_mm=deep).effective_depth_mm(b, race)
        assert got == pytest.approx(expected, rel=1e-9), (kind, race)
    # the same notch: in the race or on the ball, struck against the same race
    assert cases["inner", None] == pytest.approx(cases["ball", "inner"], rel=1e-9)
    assert cases["ball", "inner"] > cases["ball", "outer"]


def test_6205_ratios_to_the_balls_own_sagitta():
    """On a 6205 (R_b 3.97, R_i 15.55, R_o 23.49 mm) the inner race takes
    1 + R_b/R_i = 1.255x the ball's own sagitta and the outer 1 - R_b/R_o = 0.831x (to
    first order in (w/d)^2: 1e-3 at w = 0.53 mm), so a ball defect strikes the inner
    race 1.51x deeper."""
    for w in (0.18, 0.36, 0.53):
        f = bp.Fault("ball", width_mm=w, depth_mm=1.0)
        own = 0.5 * 7.94 * (1.0 - math.sqrt(1.0 - (w / 7.94) ** 2))
        inner, outer = f.effective_depth_mm(B6205, "inner"), f.effective_depth_mm(B6205, "outer")
        assert inner / own == pytest.approx(1 + 3.97 / 15.55, rel=1e-3)
        assert outer / own == pytest.approx(1 - 3.97 / 23.49, rel=1e-3)
        assert inner / outer == pytest.approx(1.51, abs=0.005)


def test_the_depth_caps_the_drop_and_a_wide_defect_is_reached():
    shallow = bp.Fault("ball", width_mm=0.53, depth_mm=0.005)
    assert shallow.effective_depth_mm(B6205, "inner") == 0.005   # 11 um drop > 5 um
    assert shallow.effective_depth_mm(B6205, "outer") == 0.005   # 7.4 um drop > 5 um
    wide = bp.Fault("inner", width_mm=7.94, depth_mm=0.2)         # as wide as the ball
    assert wide.effective_depth_mm(B6205) == 0.2


def test_the_race_argument_is_checked():
    ball = bp.Fault("ball", width_mm=0.5)
    with pytest.raises(ValueError, match="race must be 'inner' or 'outer' for a ball fault"):
        ball.effective_depth_mm(B6205)
    with pytest.raises(ValueError, match="race must be None or 'inner'"):
        bp.Fault("inner").effective_depth_mm(B6205, "outer")
    assert bp.Fault("inner").effective_depth_mm(B6205, "inner") == \
        bp.Fault("inner").effective_depth_mm(B6205)


@pytest.mark.parametrize("width_mm", [0.18, 0.36, 0.53])
def test_sr5_drops_as_deep_as_the_multibody_model(width_mm):
    """sr5's fault table against the multibody model's own notch drop at the notch's
    centre, reff - sqrt(reff^2 - a^2) with its relative radius of the pair
    (Nakhaeinejad & Bryant (2011) geometry, an independent computation). The two forms
    agree to O((a/R)^2) of the drop: 9e-4 at 0.53 mm on a 6205 (zero clearance, so
    the multibody's radii are the bearing's); 2e-3 allowed."""
    from ballpass.simulate import multibody as mb
    from ballpass.simulate.multibody import _kernels as MK

    faults = [bp.Fault("outer", width_mm=width_mm, depth_mm=0.3),
              bp.Fault("inner", width_mm=width_mm, depth_mm=0.3),
              bp.Fault("ball", width_mm=width_mm, depth_mm=0.3, element=1)]
    scene = bp.Scene("6205", fault=faults, duration_s=0.01)
    assert B6205.radial_clearance_m == 0.0
    rb, ri, ro, _, _ = mb._geometry(scene, mb.MultibodyParameters())
    table = mb._fault_table(scene, rb, ri, ro, np.zeros(9), 0.0)
    sr5 = build_model(scene, equilibrium=False).faults

    def multibody_drop(i, which):   # which: 1 inner contact, 0 outer
        reff = table[i, MK.F_REFF_I] if which == 1 else table[i, MK.F_REFF_O]
        return MK.notch_drop(0.0, table[i, MK.F_HALF], table[i, MK.F_DEPTH], reff)

    np.testing.assert_allclose(sr5[0, K.F_DEPTH], multibody_drop(0, 0), rtol=2e-3)
    np.testing.assert_allclose(sr5[1, K.F_DEPTH], multibody_drop(1, 1), rtol=2e-3)
    np.testing.assert_allclose(sr5[2, K.F_DEPTH], multibody_drop(2, 0), rtol=2e-3)
    np.testing.assert_allclose(sr5[2, K.F_DEPTH_IN], multibody_drop(2, 1), rtol=2e-3)


#: a CWRU-like drive-end scene, no slip (exact kinematic lines), 500 N: the most loaded
#: ball's deflection is 8.8 um, above the 0.18 mm defect's drops (1.28 um against the
#: inner race, 0.85 um against the outer), so every strike unloads the ball partly and
#: the released load grows with the depth
BASE = dict(bearing="6205", rpm=1797.0, radial_load_n=500.0, fs=12_000.0,
            resonance_hz=3500.0, slip=0.0, seed=1)


def ball_scene(**kw):
    return bp.Scene(**{**BASE, **kw}, fault=bp.Fault("ball", width_mm=0.18, depth_mm=0.28))


def _unloading_by_race(res):
    """Median share of its load the defective ball loses while its defect faces each
    race (the contact force's minimum over the passage, over its value just before),
    over the passages within the load zone (the ball above half the largest load)."""
    cr = res.truth.fault_crossings
    edges = np.asarray(cr.edge)
    entries, faces = cr.time_s[edges == "entry"], cr.element[edges == "entry"]
    exits = cr.time_s[edges == "exit"]
    q, t = res.truth.contact_forces[0], res.t
    out = {0: [], 1: []}
    for t0, face in zip(entries, faces, strict=True):
        later = exits[exits > t0]
        before = np.searchsorted(t, t0) - 2
        inside = (t >= t0) & (t <= later[0]) if later.size else None
        if inside is None or not inside.any() or before < 0 or q[before] < 0.5 * q.max():
            continue
        out[int(face)].append(1.0 - q[inside].min() / q[before])
    return {face: float(np.median(v)) for face, v in out.items()}


def test_sr5s_ball_defect_unloads_the_ball_more_on_the_inner_race():
    """Quasi-static closed form at the load line, 1 - (1 - h/delta)^1.5 with the
    test's drops (h 1.281 and 0.848 um, delta 8.76 um): 0.211 inner, 0.142 outer, a
    ratio of 1.49. sr5's contact forces (48 kHz, 0.5 s, 9 loaded passages per face)
    give 1.42: the ramped edges and the ring of the contact differ between the faces by
    a few percent (the symmetric-depth ball gives 0.96, not 1) and the shaft's weight
    adds 1 % to the load; 15 % allowed. The old symmetric ball (0.96) and the swapped
    sign (0.6) fail."""
    res = bp.simulate(ball_scene(fs=48_000.0, duration_s=0.5), model="sr5",
                      return_forces=True)
    got = _unloading_by_race(res)
    delta = B6205.load_distribution(500.0).deflection_m * 1e6
    closed = [1.0 - (1.0 - h / delta) ** 1.5 for h in (0.8479, 1.2807)]
    assert got[1] / got[0] == pytest.approx(closed[1] / closed[0], rel=0.15)


def test_impulse_strikes_release_the_load_of_the_race_struck():
    """Each impact of the impulse model against a run with the same depth on both races
    (same kinematics, same impacts): an outer-race strike is unchanged, an inner-race
    strike grows by dQ(psi, h_i) / dQ(psi, h_o) (impact_amplitudes at the ball's angle,
    with the test's own closed-form drops): to rounding."""
    scene = ball_scene(duration_s=0.5, needs=("envelope",))
    times, steps, (before, _fault, elem, _edges) = _impacts(scene)
    with mock.patch.object(bp.Fault, "effective_depth_mm", _symmetric):
        times_sym, steps_sym, _ = _impacts(scene)
    np.testing.assert_array_equal(times, times_sym)
    face = elem[np.searchsorted(before, times)]
    loaded = np.abs(steps_sym[0]) > 1e-6 * np.abs(steps_sym[0]).max()
    assert (loaded & (face == 0)).sum() > 5 and (loaded & (face == 1)).sum() > 5
    np.testing.assert_array_equal(steps[0, face == 0], steps_sym[0, face == 0])
    bm = build_model(scene, equilibrium=False)
    psi = np.array([K.cage_angle(t, bm.p, bm.walk)[0] for t in times])   # ball 0
    inner = loaded & (face == 1)
    # the sagittas s(R_b) + s(R_i), s(R_b) - s(R_o) over a = 0.09 mm, to 6 digits
    # (hence 1e-5 below; the release is smooth in h)
    h_in, h_out = 1.28073e-6, 0.847868e-6
    ratio = (impact_amplitudes(scene, psi[inner], np.full(inner.sum(), h_in))
             / impact_amplitudes(scene, psi[inner], np.full(inner.sum(), h_out)))
    np.testing.assert_allclose(steps[0, inner] / steps_sym[0, inner], ratio, rtol=1e-5)
    # the release is concave in h, so the ratio is at most h_i / h_o = 1.51 (near the
    # load line) and 1 where both drops exceed the deflection (the load zone's edge)
    assert ratio.max() > 1.45 and np.all((ratio >= 1.0) & (ratio <= h_in / h_out))


@pytest.mark.parametrize("model", ["impulse", "sr5"])
def test_a_ball_defects_signal_carries_a_line_at_bsf(model):
    """Strikes alternating between the two races with released loads A (inner) and B
    (outer) put a line at BSF in the squared envelope spectrum, of (A^2 - B^2) / (A^2 +
    B^2) the line at 2 BSF (the strike rate), times the squared ring's spectrum
    |2 sigma + i 2 pi 2BSF| / |2 sigma + i 2 pi BSF| (1.057 at 3.5 kHz, 5 % damping).
    With A / B = 1.51 (drops far below the deflection: dQ ~ h, 2 % off at the load line)
    that is 0.412; measured 0.427 (impulse), 0.425 (sr5) on 2 s without slip. 15 %
    allowed: the ball moves 30 deg round the load zone between strikes and the
    nonlinear release weighs the faces a little differently there. A ball with the same
    depth on both races has none of it (0.011): below 0.05."""
    scene = ball_scene(duration_s=2.0)
    fb = scene.frequencies.bsf

    def ratio(res):
        f, a = bp.features.envelope_spectrum(np.asarray(res.accel).ravel(), scene.fs,
                                             band=(2500.0, 4500.0))
        line = [a[np.abs(f - h * fb) <= f[1]].max() for h in (1, 2)]
        return line[0] / line[1]

    sigma = scene.resonance_damping * 2 * math.pi * scene.resonance_hz
    ring = abs(complex(2 * sigma, 4 * math.pi * fb)) / abs(complex(2 * sigma, 2 * math.pi * fb))
    r = 1.28073 / 0.847868
    expected = (r**2 - 1) / (r**2 + 1) * ring
    assert ratio(bp.simulate(scene, model=model)) == pytest.approx(expected, rel=0.15)
    with mock.patch.object(bp.Fault, "effective_depth_mm", _symmetric):
        assert ratio(bp.simulate(scene, model=model)) < 0.05
