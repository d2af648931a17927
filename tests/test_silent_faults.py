"""Which outer-race faults loaded balls actually strike (GroundTruth.outer_fault_load_fraction),
against Stribeck's quasi-static load zone (Bearing.load_distribution)."""

import math

import pytest

import ballpass as bp

BEARING = bp.Bearing.catalog("6205")
LOAD_N = 500.0


def _fraction(angle_deg: float, clearance_um: float = 0.0, width_mm: float = 0.5) -> float:
    scene = bp.Scene(BEARING, rpm=1797, duration_s=0.2, fs=12_000, resonance_hz=3_000,
                     radial_load_n=LOAD_N, clearance_um=clearance_um,
                     fault=bp.Fault("outer", width_mm=width_mm, angle_deg=angle_deg))
    res = bp.simulate(scene, model="sr5", return_forces=True)
    return res.truth.outer_fault_load_fraction(scene.bearing)[0]


def test_a_fault_at_the_centre_of_the_load_zone_carries_the_largest_load():
    # every ball crossing 6 o'clock carries Q_max and strikes the exit edge harder still:
    # the clipped fraction is 1. An offset taken in degrees instead of radians finds no
    # ball over the fault (0).
    assert _fraction(0.0) == 1.0


@pytest.mark.parametrize("angle_deg", [30.0, 45.0, 60.0])
def test_a_narrow_fault_in_the_zone_carries_stribecks_load(angle_deg):
    # zero clearance: Stribeck's eps = 1/2 and Q(psi) / Q_max = cos(psi)^1.5 (Harris &
    # Kotzalas ch. 7). A 0.18 mm fault barely unloads the ball, so its exit impact adds
    # little; 0.05 covers that and the load ripple of the run (measured 0.01-0.02). An
    # angle taken in degrees where radians are due puts the fault elsewhere (0 at 30 and
    # 60 deg: 30 and 60 rad lie at 159 and 198 deg).
    stribeck = math.cos(math.radians(angle_deg)) ** 1.5
    assert _fraction(angle_deg, width_mm=0.18) == pytest.approx(stribeck, abs=0.05)


def test_a_fault_opposite_the_load_is_silent_at_zero_clearance():
    # zero clearance: the Stribeck zone spans +-90 deg; at 180 deg no ball is in contact,
    # and a separated contact carries exactly 0 N
    assert _fraction(180.0) == 0.0


def test_the_edge_of_the_zone_is_nearly_silent_and_preload_makes_the_opposite_side_strike():
    # Stribeck at zero clearance: the load falls to 0 at +-90 deg; only the run's
    # vibration loads a ball there, by a few newtons against Q_max ~ 240 N (< 5 %)
    assert _fraction(90.0) < 0.05
    # radial preload: Stribeck's zone becomes the full ring once the preload exceeds the
    # load's deflection (load_zone_half_angle 180 deg); the opposite fault is then struck,
    # harder the larger the preload. A clearance sign flipped in the kernel (preload read
    # as clearance) would leave it silent.
    for preload_um in (-6.0, -20.0):
        zone = BEARING.with_clearance(preload_um * 1e-3).load_distribution(LOAD_N)
        assert zone.load_zone_half_angle_deg == 180.0
    light, firm = _fraction(180.0, -6.0), _fraction(180.0, -20.0)
    assert 0.0 < light < firm <= 1.0


def test_only_outer_faults_have_a_fraction_and_forces_are_required():
    scene = bp.Scene(BEARING, rpm=1797, duration_s=0.1, fs=12_000, resonance_hz=3_000,
                     fault=bp.Fault("inner"))
    res = bp.simulate(scene, model="sr5", return_forces=True)
    assert math.isnan(res.truth.outer_fault_load_fraction(BEARING)[0])
    with pytest.raises(ValueError, match="return_forces=True"):
        bp.simulate(scene, model="sr5").truth.outer_fault_load_fraction(BEARING)
