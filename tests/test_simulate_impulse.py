"""The impulse model (issue 10 item 4): what its *signal* shows against the kinematics,
the Stribeck load zone and sr5; and the options it refuses before any work."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ballpass as bp
from ballpass.bearing import stribeck_qmax
from ballpass.features import envelope_spectrum
from ballpass.simulate import impulse as imp

FS = 24_000.0
RES_HZ = 6_000.0  # inside the 24 kHz output band; cheap to analyse


def _ses(res, channel=0):
    x = np.atleast_2d(res.accel)[channel]
    return envelope_spectrum(x, res.fs, band=res.scene.demodulation_band)


def _line(f, a, freq, half_width):
    """Largest SES amplitude within +-half_width Hz of freq."""
    sel = np.abs(f - freq) <= half_width
    return float(a[sel].max())


def _background(f, a, hi):
    sel = (f > 2.0) & (f < hi)
    return float(np.median(a[sel]))


def _scene(kind, rpm, **kw):
    kw.setdefault("duration_s", 2.0)
    return bp.Scene(bearing="6205", rpm=rpm, fault=bp.Fault(kind, **kw.pop("fault_kw", {})),
                    fs=FS, resonance_hz=RES_HZ, needs=("envelope",), **kw)


# The line width: slip of 1 % of the period (Scene default) smears the k-th harmonic
# of f_d over about k * 1 % * f_d; the 2 s records resolve 0.5 Hz. Lines are searched
# within max(1.5 Hz, 1.5 % of the frequency). "Standing out" means 5x the median SES
# (14 dB): a noise-free impulse train's lines stand 20-50x above it (measured), while
# a missing modulation leaves the sideband bins at the level of the leakage skirt.
def _tol(freq):
    return max(1.5, 0.015 * freq)


@pytest.mark.parametrize("rpm", [600.0, 1797.0, 3600.0])
def test_outer_race_ses_line_at_bpfo(rpm):
    res = bp.simulate(_scene("outer", rpm))
    assert res.info["model"] == "impulse"
    f, a = _ses(res)
    fr = res.scene.frequencies
    bg = _background(f, a, 5 * fr.bpfi)
    bpfo = _line(f, a, fr.bpfo, _tol(fr.bpfo))
    assert bpfo > 5 * bg
    # the strongest line below 1.5 x BPFO is BPFO itself (not the shaft, not BPFI)
    sel = (f > 2.0) & (f < 1.5 * fr.bpfo)
    assert abs(f[sel][np.argmax(a[sel])] - fr.bpfo) <= _tol(fr.bpfo)


@pytest.mark.parametrize("rpm", [600.0, 1797.0, 3600.0])
def test_inner_race_bpfi_with_shaft_sidebands(rpm):
    # the defect turns with the shaft through the load zone: its impacts are modulated
    # at the shaft rate, so BPFI carries sidebands at +-f_shaft (McFadden & Smith 1984)
    res = bp.simulate(_scene("inner", rpm))
    f, a = _ses(res)
    fr = res.scene.frequencies
    bg = _background(f, a, 5 * fr.bpfi)
    assert _line(f, a, fr.bpfi, _tol(fr.bpfi)) > 5 * bg
    for side in (fr.bpfi - fr.shaft, fr.bpfi + fr.shaft):
        assert _line(f, a, side, _tol(side)) > 5 * bg, f"sideband {side:.1f} Hz missing"


@pytest.mark.parametrize("rpm", [900.0, 1797.0])
def test_ball_fault_at_twice_bsf_with_cage_sidebands(rpm):
    # a ball defect strikes the outer and the inner race once each per spin turn: its
    # impacts repeat at 2 x BSF; the ball rides with the cage through the load zone, so
    # the train is modulated at the FTF (sidebands at +-FTF). A defect striking one race
    # only would put the line at BSF instead.
    res = bp.simulate(_scene("ball", rpm))
    f, a = _ses(res)
    fr = res.scene.frequencies
    bg = _background(f, a, 5 * fr.bpfi)
    line = _line(f, a, fr.ball_defect, _tol(fr.ball_defect))
    assert line > 5 * bg
    assert line > 3 * _line(f, a, fr.bsf, _tol(fr.bsf))
    for side in (fr.ball_defect - fr.ftf, fr.ball_defect + fr.ftf):
        assert _line(f, a, side, 0.5 * fr.ftf) > 5 * bg, f"sideband {side:.1f} Hz missing"


def test_run_up_keeps_the_impacts_at_the_bpfo_order():
    # generated in the angle domain: over a 900 -> 1800 rpm run-up the envelope,
    # resampled on the tachometer's shaft angle, shows the BPFO *order* (BPFO / f_shaft,
    # 3.585 for the 6205), whatever the speed. A train laid out in time at the mean
    # speed would smear it over +-33 %.
    scene = bp.Scene(bearing="6205", rpm=(900.0, 1800.0), fault=bp.Fault("outer"), fs=FS,
                     resonance_hz=RES_HZ, duration_s=3.0, needs=("envelope",))
    res = bp.simulate(scene)
    assert res.info["model"] == "impulse"
    env = bp.features.envelope(res.accel, res.fs, band=scene.demodulation_band)
    turns = res.truth.shaft_angle / (2 * math.pi)
    grid = np.arange(0.0, turns[-1], 1.0 / 64.0)  # 64 samples per shaft turn
    env_angle = np.interp(grid, turns, env)
    spec = np.abs(np.fft.rfft((env_angle - env_angle.mean()) * np.hanning(grid.size)))
    orders = np.fft.rfftfreq(grid.size, d=1.0 / 64.0)
    sel = (orders > 1.0) & (orders < 6.0)
    order_bpfo = scene.bearing.frequencies(1.0).bpfo
    # resolution: 1 / (number of turns) ~ 0.015 orders; slip smears 1 % of the order
    assert abs(orders[sel][np.argmax(spec[sel])] - order_bpfo) < 0.05


@pytest.mark.parametrize("zeta, times, n", [
    # two rings overlapping, two of them starting on the same sample (ceil(91.34) = 92)
    (0.04, [0.00123, 0.004567, 0.0046], 400),
    # lightly damped, with stretches without a new ring longer than the kernel's table
    # of powers (_SPAN samples): the amplitude is carried block by block (planted: not
    # advancing it between blocks fails by the ring's full size)
    (0.001, [0.00123, 0.3, 0.30002], 3 * imp._SPAN),
])
def test_ring_is_the_exact_resonator_response(zeta, times, n):
    # independent reference: the base-acceleration step response of a resonator,
    # absolute acceleration a [1 - e^{-s tau} (cos w_d tau - s/w_d sin w_d tau)], minus
    # the step itself, summed directly at every sample
    fs, f_n = 20_000.0, 3_000.0
    times = np.array(times)
    steps = np.array([[2.0, -1.0, 0.5], [0.3, 0.7, -0.2]])
    out, mean = imp._ring(times, steps, n, fs, f_n, zeta)
    w_n = 2 * math.pi * f_n
    s, w_d = zeta * w_n, w_n * math.sqrt(1 - zeta**2)
    t = np.arange(n) / fs
    ref = np.zeros((2, n))
    for k, tk in enumerate(times):
        tau = t - tk
        on = tau >= 0
        ring = -np.exp(-s * tau[on]) * (np.cos(w_d * tau[on]) - s / w_d * np.sin(w_d * tau[on]))
        ref[:, on] += steps[:, k:k + 1] * ring
    # each sample is the carried amplitude times a tabulated power of z: rounding only,
    # a few ulps per carry, far below 1e-12 of the largest step; the mean, summed in
    # closed form, against numpy's mean of the reference (planted: the closed-form sum
    # divided by n + 1 samples fails by 4e-6, 2e-6 of the largest step)
    tol = 1e-12 * np.abs(steps).max()
    np.testing.assert_allclose(mean, ref.mean(axis=1, keepdims=True), rtol=0, atol=tol)
    np.testing.assert_allclose(out, ref - ref.mean(axis=1, keepdims=True), rtol=0, atol=tol)


def _zero_clearance_scene(angle_deg, **fault_kw):
    b = bp.Bearing.catalog("6205").with_clearance(0.0)
    fault_kw.setdefault("width_mm", 3.0)
    fault_kw.setdefault("depth_mm", 0.5)
    return bp.Scene(bearing=b, rpm=1797.0, radial_load_n=500.0, gravity=False, fs=FS,
                    resonance_hz=RES_HZ, duration_s=1.0, needs=("envelope",),
                    fault=bp.Fault("outer", angle_deg=angle_deg, **fault_kw),
                    # the sensor sits at the fault, without attenuation: what differs
                    # between the runs is the load the element releases
                    sensors=(bp.Sensor(angle_deg=angle_deg, name="s", attenuation=0.0),))


def _rms(scene):
    return float(np.sqrt(np.mean(bp.simulate(scene).accel ** 2)))


def test_load_zone_modulation_follows_stribeck():
    # zero clearance: the load zone spans +-90 deg with Q(psi) = Q_max cos(psi)^1.5
    # (Stribeck, eps = 0.5; Harris & Kotzalas ch. 7). A defect deeper than the contact
    # deflection releases the whole load where the element strikes its trailing edge,
    # psi = centre + h (h = half width / outer-race radius), so the rings of a defect at
    # 60 deg are (cos(60 deg + h) / cos(h))^1.5 of those at 0 deg (0.30; 0.354 at the
    # centres); out of the zone (120, 180 deg) nothing strikes. Tolerance 3 %: the two
    # runs differ in their impact counts by at most one of ~107 (0.9 %).
    s0, s60 = _zero_clearance_scene(0.0), _zero_clearance_scene(60.0)
    h = 0.5 * s0.fault.width_mm * 1e-3 / s0.bearing.outer_race_radius_m
    expected = (math.cos(math.radians(60.0) + h) / math.cos(h)) ** 1.5
    assert _rms(s60) / _rms(s0) == pytest.approx(expected, rel=0.03)
    assert _rms(_zero_clearance_scene(120.0)) == 0.0
    assert _rms(_zero_clearance_scene(180.0)) == 0.0


def test_fault_size_shallow_defect_releases_part_of_the_load():
    # a defect shallower than the contact deflection delta_0 lets the element keep
    # K (delta_0 - h)^1.5: it releases 1 - (1 - h / delta_0)^1.5 of its load. delta_0 from
    # Stribeck's closed form Q_max = F_r / (Z J_r) (zero clearance), independent of the
    # model's discrete equilibrium (0.4 % apart for 9 balls: 0.3 % in delta_0 and
    # < 1 % in the ratio), plus the impact-count spread of the test above: 3 %.
    b = bp.Bearing.catalog("6205").with_clearance(0.0)
    q_max = stribeck_qmax(500.0, b.n_elements)
    delta0 = (q_max / b.hertz_stiffness()) ** (1 / 1.5)
    h = 0.4 * delta0
    shallow = _zero_clearance_scene(0.0, depth_mm=h * 1e3)
    # the element strikes at the trailing edge, where its deflection is delta_0 cos(edge)
    edge = 0.5 * shallow.fault.width_mm * 1e-3 / shallow.bearing.outer_race_radius_m
    delta = delta0 * math.cos(edge)
    expected = 1.0 - (1.0 - h / delta) ** 1.5
    assert _rms(shallow) / _rms(_zero_clearance_scene(0.0)) == pytest.approx(expected, rel=0.03)


def test_round_pit_strikes_with_sr5s_shallower_depth():
    # A round pit removes only a strip of the contact ellipse, so sr5 takes a shallower
    # equivalent depth for it than the notch drop (sr5._pit_depth_m); the impulse model
    # reads sr5's fault table, so its pit impacts shrink by the same factor. Measured RMS
    # ratio pit / groove: impulse 0.826, sr5 0.823 (0.3 mm, 6205, 500 N); 3 % leaves room
    # for sr5's contact dynamics and ringing. An impulse model that used the notch drop
    # for a pit reads 1.0 and fails.
    ratios = {}
    for model in ("impulse", "sr5"):
        rms = []
        for geometry in ("groove", "pit"):
            scene = bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0,
                             fault=bp.Fault("outer", width_mm=0.3, depth_mm=0.1,
                                            geometry=geometry),
                             duration_s=0.5, fs=48_000.0)
            x = bp.simulate(scene, model=model, allow_unrepresented=True).accel
            rms.append(float(np.sqrt(np.mean(x**2))))
        ratios[model] = rms[1] / rms[0]
    assert ratios["impulse"] < 0.95
    assert ratios["impulse"] == pytest.approx(ratios["sr5"], rel=0.03)


def test_sensor_transmission_as_sr5():
    # two sensors, loaded zone and opposite, kappa = 0.8. The element strikes the
    # trailing edge of the defect (centred at 0 deg) at psi = h, h = half width /
    # outer-race radius; the force along the contact normal reaches a sensor at theta
    # with the factor exp(-kappa (1 - cos(psi - theta))) cos(psi - theta): the opposite
    # sensor reads exactly -exp(-2 kappa cos h) times the loaded one, sample by sample
    scene = _zero_clearance_scene(0.0).replace(
        sensors=(bp.Sensor(0.0, attenuation=0.8), bp.Sensor(180.0, attenuation=0.8)))
    x = bp.simulate(scene).accel
    h = 0.5 * scene.fault.width_mm * 1e-3 / scene.bearing.outer_race_radius_m
    np.testing.assert_allclose(x[1], -math.exp(-1.6 * math.cos(h)) * x[0], rtol=0,
                               atol=1e-12 * abs(x).max())


def test_impulse_and_sr5_agree():
    # The same scene through both models: the same defect entries and exits (same
    # kinematics, same slip from the same seed; the impulse model finds their times to
    # 1e-13 s, sr5 brackets them to adjacent floating-point numbers), SES lines at the
    # same frequencies and correlated
    # envelope spectra. Measured correlation over 1-500 Hz: 0.989-0.995 for outer, inner
    # and ball faults at 1797 rpm (docs/models.md, benchmarks/models_agreement.py); the
    # threshold 0.9 leaves room for sr5's physics options; a ball defect striking one
    # race only (half the impact rate) fails this test.
    for kind, name in (("outer", "bpfo"), ("inner", "bpfi"), ("ball", "ball_defect")):
        scene = bp.Scene(bearing="6205", rpm=1797.0, fault=bp.Fault(kind), duration_s=0.5,
                         fs=48_000.0)
        r5 = bp.simulate(scene, model="sr5")
        ri = bp.simulate(scene, model="impulse")
        c5, ci = r5.truth.fault_crossings, ri.truth.fault_crossings
        edges = np.isin(c5.edge, ("entry", "exit"))  # impulse has no edge ramps
        np.testing.assert_allclose(c5.time_s[edges], ci.time_s, rtol=0,
                                   atol=imp.K.SECANT_TOL_S + 1e-16)
        np.testing.assert_array_equal(c5.edge[edges], ci.edge)
        np.testing.assert_array_equal(c5.element[edges], ci.element)
        f, a5 = _ses(r5)
        _, ai = _ses(ri)
        freq = getattr(scene.frequencies, name)
        sel = (f > 0.5 * freq) & (f < 1.5 * freq)
        peak5, peaki = f[sel][np.argmax(a5[sel])], f[sel][np.argmax(ai[sel])]
        # both at the defect frequency and within one bin (2 Hz) of each other: slip
        # smears a line over ~1 % of its frequency, across the bins next to it
        assert abs(peak5 - peaki) <= f[1] + 1e-9, kind
        assert abs(peaki - freq) <= _tol(freq), kind
        band = (f > 1.0) & (f < 500.0)
        assert np.corrcoef(a5[band], ai[band])[0, 1] > 0.9, kind


@pytest.mark.parametrize("scene", [
    bp.Scene("6205", rpm=1797.0, fault=bp.Fault("inner"), duration_s=0.5, fs=48_000.0),
    bp.Scene("6205", rpm=(600.0, 1800.0), fault=bp.Fault("ball"), duration_s=0.5,
             fs=48_000.0, seed=3, sensors=("loaded", "unloaded")),
])
def test_impacts_from_approximate_crossings_as_from_exact_ones(monkeypatch, scene):
    # the impulse model takes its impact times to 1e-13 s (SECANT_TOL_S) instead of sr5's
    # brackets to adjacent floating-point numbers: a ring starting dt late differs from the
    # exact one by at most its phase shift 2 pi f_n dt = 9.4e-9 rad at 15 kHz (plus the
    # element angle's change, 1e-11 rad), and the 5 %-damped rings barely overlap
    # (impacts 2-10 ms apart, rings decaying e-fold in 0.2 ms): samples within 1e-7 of
    # the largest. Measured: 1e-11 (inner, constant speed) and 3e-9 (ball, run-up).
    # Planted: a secant tolerance of 1e-9 s fails on both scenes.
    fast = bp.simulate(scene, model="impulse")
    exact_events = imp._events
    monkeypatch.setattr(imp, "_events", lambda bm, t_end, exact=True: exact_events(bm, t_end))
    ref = bp.simulate(scene, model="impulse")
    np.testing.assert_allclose(fast.accel, ref.accel, rtol=0, atol=1e-7 * abs(ref.accel).max())


def test_envelope_need_resolves_to_impulse_and_contact_dynamics_to_sr5():
    scene = bp.Scene(bearing="6205", needs=("envelope",))
    assert bp.simulate.resolve_model(scene) == "impulse"
    assert bp.simulate.resolve_model(scene.replace(rpm=(600.0, 1800.0))) == "impulse"
    assert bp.simulate.resolve_model(scene.replace(needs=("envelope", "contact_dynamics"))) \
        == "sr5"
    # forces are not represented: auto goes to sr5 and says why
    assert bp.simulate.resolve_model(scene, return_forces=True) == "sr5"
    # a healthy impulse bearing is silent: snr_db has no reference, auto falls back to sr5
    healthy = bp.Scene(bearing="6205", needs=("envelope",), snr_db=10.0)
    res = bp.simulate(healthy.replace(duration_s=0.01))
    assert res.info["model"] == "sr5"
    assert "impulse has no signal for a healthy bearing" in res.info["model_reason"]
    quiet = bp.simulate(healthy.replace(snr_db=None, duration_s=0.01))
    assert quiet.info["model"] == "impulse" and not np.any(quiet.accel)


@pytest.mark.parametrize(("kwargs", "error", "match"), [
    # refused by the shared solver check (the analytic "solver" takes no step)
    ({"dt": 1e-5}, ValueError, "dt=1e-05"),
    ({"rtol": 1e-6}, ValueError, "rtol=1e-06: the impulse model"),
    ({"oversample": 8}, ValueError, "oversample=8: the impulse model"),
    ({"return_forces": True}, ValueError, "does not represent contact_forces"),
    ({"params": bp.simulate.SR5Parameters()}, TypeError, "params must be ImpulseParameters"),
    ({"solver": "rk4"}, ValueError, r"solver must be 'auto' or one of \['analytic'\]"),
])
def test_bad_options_refused_before_any_work(monkeypatch, kwargs, error, match):
    def no_work(*args, **kw):
        raise AssertionError("the model started work before refusing its options")

    monkeypatch.setattr(imp, "build_model", no_work)
    scene = bp.Scene(bearing="6205", fault=bp.Fault("outer"), duration_s=0.01)
    with pytest.raises(error, match=match):
        bp.simulate(scene, model="impulse", **kwargs)


def test_bad_parameters_and_needs_refused():
    with pytest.raises(ValueError, match="housing_mass"):
        imp.ImpulseParameters(housing_mass=0.0)
    with pytest.raises(ValueError, match=r"unknown phenomenon 'impulses'"):
        bp.Scene(bearing="6205", needs=("impulses",))
