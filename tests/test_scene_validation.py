"""Bad input is refused before any work, with the argument and the allowed range named."""

import math

import pytest

import ballpass as bp


def make(**kw):
    base = dict(bearing="6205", rpm=1797.0, fs=48_000.0, duration_s=0.1)
    base.update(kw)
    return bp.Scene(**base)


@pytest.mark.parametrize("rpm", [-100.0, 0.0, math.nan, math.inf, 2e5])
def test_bad_rpm(rpm):
    with pytest.raises(ValueError, match=r"rpm must be a finite number in \(0, 100000\]"):
        make(rpm=rpm)


def test_rpm_of_wrong_type():
    with pytest.raises(TypeError, match="rpm must be a number"):
        make(rpm="fast")


def test_impossible_geometry():
    with pytest.raises(ValueError, match="element_diameter_mm must be < pitch_diameter_mm"):
        bp.Bearing("x", n_elements=9, element_diameter_mm=40.0, pitch_diameter_mm=39.0)
    with pytest.raises(ValueError, match="do not fit on a pitch circle"):
        bp.Bearing("x", n_elements=30, element_diameter_mm=7.94, pitch_diameter_mm=39.04)


def test_fault_wider_than_the_element_spacing():
    # 6205: pi * 39.04 / 9 = 13.63 mm between elements on the pitch circle
    with pytest.raises(ValueError, match=r"width_mm must be < the element spacing.*13\.628"):
        make(fault=bp.Fault("outer", width_mm=14.0))
    with pytest.raises(ValueError, match=r"ball fault width_mm must be < the element diameter"):
        make(fault=bp.Fault("ball", width_mm=8.0))


@pytest.mark.parametrize("depth", [0.0, -0.1, math.nan])
def test_depth_must_be_positive(depth):
    with pytest.raises(ValueError, match=r"depth_mm must be a finite number in \(0, 50\]"):
        bp.Fault("inner", depth_mm=depth)


def test_unknown_bearing_and_fault_kind():
    with pytest.raises(ValueError, match="unknown bearing 'X999'.*6205"):
        make(bearing="X999")
    with pytest.raises(ValueError, match="fault kind must be one of"):
        bp.Fault("cage")


def test_resonance_above_the_output_band_is_refused_with_a_fix():
    # the CWRU pitfall: the 15 kHz default resonance at a 12 kHz output rate
    with pytest.raises(ValueError, match=r"resonance_hz=15000 lies above 0\.45\*fs = 5400.*"
                                          r"Lower resonance_hz.*raise fs to at least 33333"):
        make(fs=12_000.0)
    make(fs=12_000.0, resonance_hz=3000.0)  # the fix works


@pytest.mark.parametrize(
    ("kw", "name"),
    [
        (dict(fs=500.0), "fs"),
        (dict(duration_s=0.0), "duration_s"),
        (dict(radial_load_n=-1.0), "radial_load_n"),
        (dict(slip=0.5), "slip"),
        (dict(resonance_damping=1.5), "resonance_damping"),
        (dict(seed=-1), "seed"),
        (dict(snr_db=10.0, noise_rms=1.0), "snr_db or noise_rms"),
        (dict(sensors=()), "sensors"),
    ],
)
def test_other_arguments_are_named(kw, name):
    with pytest.raises((ValueError, TypeError), match=name):
        make(**kw)


def test_simulate_arguments_are_checked_before_work():
    sc = make(fs=12_000.0, resonance_hz=3000.0)
    with pytest.raises(ValueError, match="model must be 'auto' or one of"):
        bp.simulate(sc, model="fem")
    with pytest.raises(ValueError, match="solver must be 'auto' or one of"):
        bp.simulate(sc, solver="euler")
    with pytest.raises(ValueError, match=r"dt must be a step size in \[1e-10, 1e-3\] s"):
        bp.simulate(sc, dt=-1.0)
    with pytest.raises(ValueError, match=r"rtol must be in"):
        bp.simulate(sc, solver="dopri5", rtol=2.0)


def test_scene_conventions():
    # angles wrap to [0, 360): 359.9 and -0.1 are the same defect position
    wrapped = bp.Fault("outer", angle_deg=-0.1).angle_deg
    assert wrapped == bp.Fault("outer", angle_deg=359.9).angle_deg
    assert bp.Sensor(angle_deg=-180.0).name == "unloaded"
    s = make(fault=[bp.Fault("outer"), bp.Fault("inner")])
    assert s.label == "outer+inner" and len(s.faults) == 2
    assert make().label == "healthy"
    ramp = make(rpm=(600.0, 1200.0))
    assert ramp.speed.rpm_at(0.05, ramp.duration_s) == pytest.approx(900.0)
    # the shaft angle is the integral of the speed: mean speed times duration
    assert ramp.speed.shaft_angle(0.1, 0.1) == pytest.approx(2 * math.pi * 900.0 / 60 * 0.1)
    # drop limit: a 0.5 mm notch 1 mm deep lets a 7.94 mm ball in the concave outer race
    # (radius (39.04 + 7.94) / 2 mm) drop only the difference of their sagittas, 6.5 um
    # (tests/test_effective_depth.py checks the geometry)
    f = bp.Fault("outer", width_mm=0.5, depth_mm=1.0)
    sagitta = lambda r: r - math.sqrt(r * r - 0.25**2)  # noqa: E731
    assert f.effective_depth_mm(bp.Bearing.catalog("6205")) == pytest.approx(
        sagitta(3.97) - sagitta(23.49))
    wide = bp.Fault("outer", width_mm=9.0, depth_mm=0.2)
    assert wide.effective_depth_mm(bp.Bearing.catalog("6205")) == 0.2


def test_demodulation_band_surrounds_the_resonance_inside_the_output_band():
    assert make(fs=12_000.0, resonance_hz=3000.0).demodulation_band == (2400.0, 3600.0)
    # 15 kHz at 48 kHz: +-3 kHz fits below 0.49 fs = 23.52 kHz
    assert make().demodulation_band == (12_000.0, 18_000.0)
    # close to Nyquist the upper edge is clipped to 0.49 fs
    assert make(fs=12_000.0, resonance_hz=5000.0).demodulation_band == (4000.0, 5880.0)


def test_a_fault_bomb_is_refused_before_any_work():
    """More than MAX_FAULTS localized faults are refused when the scene is built, naming
    the argument, the limit and the alternative (each fault costs the simulators a test
    per element and step: 10^5 of them ran for minutes); the limit itself is accepted."""
    from ballpass.scene import MAX_FAULTS

    one = bp.Fault("outer", width_mm=0.1)
    assert len(bp.Scene("6205", fault=(one,) * MAX_FAULTS).faults) == MAX_FAULTS
    with pytest.raises(ValueError, match=rf"fault holds {MAX_FAULTS + 1} faults; at most "
                                         rf"{MAX_FAULTS} .*waviness"):
        bp.Scene("6205", fault=(one,) * (MAX_FAULTS + 1))
