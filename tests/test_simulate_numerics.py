"""Integrators against an independent reference, convergence order, determinism,
and failure modes."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import ballpass as bp
from ballpass.simulate import SimulationUnstableError, build, integrate

FS = 12_000.0
H_OUT = 1.0 / (4 * FS)  # the internal grid simulate() uses at 12 kHz


def short_scene(kind="outer", **kw):
    base = dict(bearing="6205", rpm=1797.0, duration_s=0.02, fs=FS, resonance_hz=3000.0,
                resonance_damping=0.02, fault=bp.Fault(kind, width_mm=0.5, depth_mm=0.1))
    base.update(kw)
    return bp.Scene(**base)


def reference_output(bm, n_out, crossings):
    """scipy DOP853 at rtol 1e-10 on the same right-hand side, restarted at every fault
    edge (the ramped profile has a jump in its second derivative there)."""
    t_grid = np.arange(n_out) * H_OUT
    breaks = np.concatenate(([0.0], crossings, [t_grid[-1]]))
    y = bm.y0.copy()
    out = np.empty((n_out, len(bm.scene.sensors)))
    for a, b in zip(breaks[:-1], breaks[1:], strict=True):
        if b <= a:
            continue
        sel = (t_grid >= a) & (t_grid <= b)
        sol = solve_ivp(bm.rhs, (a, b), y, method="DOP853", rtol=1e-10,
                        atol=1e-10 * bm.scale, t_eval=t_grid[sel], dense_output=False)
        assert sol.success
        for k, t in zip(np.flatnonzero(sel), sol.t, strict=True):
            out[k] = bm.sensor_output(t, sol.y[:, list(sol.t).index(t)])
        y = solve_ivp(bm.rhs, (a, b), y, method="DOP853", rtol=1e-10,
                      atol=1e-10 * bm.scale).y[:, -1]
    return out


@pytest.fixture(scope="module")
def outer_reference():
    bm = build(short_scene())
    n_out = int(round(bm.scene.duration_s / H_OUT)) + 1
    raw = integrate(bm, "rk4", h_out=H_OUT, n_out=n_out)
    ref = reference_output(bm, n_out, raw.crossings.time_s)
    return bm, n_out, ref


def rel_l2(a, b):
    return np.linalg.norm(a - b) / np.linalg.norm(b)


def test_rk4_and_dopri5_agree_with_scipy_dop853(outer_reference):
    bm, n_out, ref = outer_reference
    rk4 = integrate(bm, "rk4", h_out=H_OUT, n_out=n_out).output
    dp = integrate(bm, "dopri5", h_out=H_OUT, n_out=n_out, rtol=1e-9).output
    # The reference is good to ~1e-9. RK4 at the default step (omega_max dt = 0.25)
    # has a local error ~ (omega dt)^5 / 120 ~ 1e-5 per step, accumulating over the
    # ~60 resonator periods of the run to ~1e-3 of the output: assert 5e-3.
    assert rel_l2(rk4, ref) < 5e-3
    # Dormand-Prince at rtol 1e-9 controls the local error to 1e-9 of the scales; the
    # global output error stays below 1e-6 here (measured ~1e-8).
    assert rel_l2(dp, ref) < 1e-6


def test_rk4_converges_at_fourth_order(outer_reference):
    bm, n_out, ref = outer_reference
    errors = []
    # steps of h_out, h_out/2, h_out/4: with the Ruan et al. masses (m_s 3.26 kg) the
    # contact mode is slower than with the former 1 kg, and h_out/8 reaches a floor
    # (~4e-8) of the resonator-input interpolation and the reference
    for n_sub in (1, 2, 4):
        out = integrate(bm, "rk4", h_out=H_OUT, n_out=n_out, dt=H_OUT / n_sub).output
        errors.append(rel_l2(out, ref))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    # halving the step divides a 4th-order method's error by 16; the steps are split at
    # the fault edges so the non-smooth profile does not spoil the order. Allow 10-24
    # (round-off and the reference's own 1e-9 floor stay far below these errors).
    assert np.all((ratios > 10.0) & (ratios < 24.0)), (errors, ratios)


def test_dopri5_error_shrinks_with_tolerance(outer_reference):
    bm, n_out, ref = outer_reference
    errs = [rel_l2(integrate(bm, "dopri5", h_out=H_OUT, n_out=n_out, rtol=r).output, ref)
            for r in (1e-4, 1e-6, 1e-8)]
    # tolerance proportionality: 100x tighter rtol gives at least 10x smaller error
    assert errs[1] < errs[0] / 10 and errs[2] < errs[1] / 10, errs


def test_same_seed_is_bit_identical_and_another_seed_slips_differently():
    sc = short_scene(duration_s=0.2, fs=FS)
    a, b = bp.simulate(sc), bp.simulate(sc)
    np.testing.assert_array_equal(a.accel, b.accel)
    c = bp.simulate(sc.replace(seed=1))
    ta, tc = a.truth.fault_crossings.entries(), c.truth.fault_crossings.entries()
    n = min(len(ta), len(tc))
    assert not np.allclose(ta[:n], tc[:n])
    assert not np.array_equal(a.accel, c.accel)


def test_noise_is_seeded_and_at_the_requested_snr():
    sc = short_scene(duration_s=0.5, snr_db=0.0)
    clean = bp.simulate(sc.replace(snr_db=None)).accel
    noisy = bp.simulate(sc).accel
    np.testing.assert_array_equal(noisy, bp.simulate(sc).accel)
    noise = noisy - clean
    # 0 dB: noise RMS equals signal RMS; 6000 samples estimate an RMS to ~1 %
    assert np.std(noise) == pytest.approx(np.std(clean), rel=0.03)
    absolute = bp.simulate(sc.replace(snr_db=None, noise_rms=2.0)).accel - clean
    assert np.std(absolute) == pytest.approx(2.0, rel=0.03)


def test_instability_raises_with_scene_and_step_instead_of_nan():
    sc = short_scene(duration_s=0.05)
    # a 0.1 g shaft on its 7.42e7 N/m support: omega = 8.6e5 rad/s; with a 1 ms step
    # omega dt = 860, far beyond RK4's stability interval (2.8): it diverges
    light = bp.simulate.SR5Parameters(shaft_mass=1e-4)
    with pytest.raises(SimulationUnstableError, match=r"dt = 0\.001 s.*Scene\(") as err:
        bp.simulate(sc, solver="rk4", dt=1e-3, oversample=1, params=light)
    assert "rk4" in str(err.value)


def test_output_shape_units_and_info():
    sc = short_scene(duration_s=0.1, sensors=("loaded", "unloaded"))
    res = bp.simulate(sc)
    assert res.accel.shape == (2, 1200)
    assert res.t[1] == pytest.approx(1 / FS)
    assert res.info["model"] == "sr5" and res.info["solver"] == "rk4"
    assert res.info["n_steps"] > 0 and res.info["wall_time_s"] > 0
    assert np.all(np.isfinite(res.accel))
    # tachometer channel: the shaft turns rpm/60 revolutions per second
    assert res.truth.shaft_angle[-1] == pytest.approx(2 * np.pi * 1797 / 60 * res.t[-1])
    # AC-coupled sensors
    np.testing.assert_allclose(res.accel.mean(axis=1), 0.0, atol=1e-9)


def test_sr4_has_no_resonator_and_reads_the_housing():
    sc = short_scene(duration_s=0.1)
    sr4 = bp.simulate(sc, model="sr4")
    sr5 = bp.simulate(sc, model="sr5")
    assert sr4.info["model"] == "sr4"
    assert bp.simulate.resolve_model(sc) == "sr5"
    # the 3 kHz resonator amplifies the impacts' content near 3 kHz: sr5 carries more
    # energy in 2-4 kHz than the bare housing (Q = 1/(2 zeta) = 25 at resonance)
    from ballpass.features import bandpass
    e4 = np.std(bandpass(sr4.accel, FS, (2000.0, 4000.0)))
    e5 = np.std(bandpass(sr5.accel, FS, (2000.0, 4000.0)))
    assert e5 > 3 * e4


@pytest.mark.parametrize("slope_db_oct", [0.0, -3.0])
def test_snr_is_relative_to_the_rms_of_a_signal_with_a_mean(slope_db_oct):
    """snr_db is relative to the RMS of the noise-free signal (Scene docs), DC included.
    For 1 + sin the RMS is sqrt(1.5) and the std sqrt(0.5): a noise level scaled by the
    std would come out 42 % low. 100 000 samples estimate an RMS to 1/sqrt(2 n) = 0.2 %
    (white; the -3 dB/oct noise is normalised to unit RMS exactly): rel 2 %."""
    from ballpass.simulate._shared import add_noise

    n = 100_000
    clean = 1.0 + np.sin(2 * np.pi * 50 * np.arange(n) / FS)[None]  # 50 Hz: whole cycles
    scene = bp.Scene("6205", rpm=1797.0, duration_s=n / FS, fs=FS, resonance_hz=3000.0,
                     snr_db=6.0, noise_slope_db_oct=slope_db_oct)
    noise = add_noise(scene, clean) - clean
    assert np.sqrt(np.mean(noise**2)) == pytest.approx(np.sqrt(1.5) * 10 ** (-6 / 20), rel=0.02)


@pytest.mark.parametrize("changes", [
    {"fault": bp.Fault("outer", width_mm=1.0)},
    {"fault": bp.Fault("inner", width_mm=1.0, edge="blunt")},
    {"fault": bp.Fault("ball", width_mm=1.0)},
    {"waviness": bp.Waviness("outer", (3, 10), (0.5, 0.2))},
    {"waviness": bp.Waviness("inner", (3, 10), (0.5, 0.2))},
    {"waviness": bp.Waviness("ball", (3, 10), (0.5, 0.2))},
], ids=["outer", "inner-blunt", "ball", "wavy-outer", "wavy-inner", "wavy-ball"])
def test_kinematic_rates_are_the_derivatives_of_the_angles_and_depths(changes):
    """The contact damping is fed the rate of each element's defect depth, and the
    cage speed drives the ball-spin and housing terms: each must be the time derivative
    of the depth and angle the kernel computes (central difference, h = 10 ns), during
    a speed ramp with 2 % slip, at 20 instants where some depth is changing (on a ramp
    or a wavy race). The fastest change, a 0.2 mm ramp crossed in ~50 us, leaves
    (pi h / 50 us)^2 = 4e-7 of truncation (measured <= 2e-8): rtol 1e-6. A rate of the
    wrong sign (inner race: cage minus shaft speed) or missing a factor is off by O(1)."""
    from ballpass.simulate import _kernels as K
    from ballpass.simulate.sr5 import build_model

    sc = bp.Scene("6205", rpm=(1700.0, 1900.0), duration_s=0.2, fs=FS, resonance_hz=3000.0,
                  slip=0.02, **changes)
    bm = build_model(sc)
    z = sc.bearing.n_elements
    kin = K.kinematics_scratch(z)

    def at(t):
        cage_rate = K.element_angles(t, bm.p, bm.walk, kin)
        K.fault_depths(t, bm.p, bm.faults, kin, cage_rate, True)
        return (cage_rate, kin[K.K_PSI, 0], kin[K.K_DEPTH, :z].copy(),
                kin[K.K_DDEPTH, :z].copy())

    changing = [t for t in np.linspace(0.001, 0.199, 4000) if np.any(at(t)[3] != 0.0)]
    assert len(changing) > 40
    h = 1e-8
    for t in np.random.default_rng(0).choice(changing, 20, replace=False):
        cage_rate, _, _, depth_rate = at(t)
        (_, psi_lo, depth_lo, _), (_, psi_hi, depth_hi, _) = at(t - h), at(t + h)
        assert cage_rate == pytest.approx((psi_hi - psi_lo) / (2 * h), rel=1e-6)
        np.testing.assert_allclose(depth_rate, (depth_hi - depth_lo) / (2 * h), rtol=0,
                                   atol=1e-6 * np.max(np.abs(depth_rate)))


@pytest.mark.parametrize("kind", ["outer", "inner", "ball"])
def test_contact_damping_sees_the_rate_of_the_deflection_the_hertz_law_sees(kind):
    """Hunt-Crossley contacts carry Q = K delta^n (1 + alpha d(delta)/dt): the rate must
    be the time derivative of the deflection the Hertz law is fed (ring velocities, the
    cage carrying the element round, the depth of a defect ramp). Both are read from
    the kernel's own loads: with alpha = 0, delta = (Q / K)^(1/n); with alpha, the rate
    is (Q_alpha / Q - 1) / alpha. Along rings moving at constant velocity during a speed
    ramp with slip, at 10 instants where a loaded element is on a defect ramp and 10
    anywhere, it must equal a central difference of delta (h = 10 ns; truncation as in
    the kinematic rates above, measured <= 2e-8 of the largest rate): rtol 1e-6."""
    from ballpass.simulate import _kernels as K
    from ballpass.simulate.sr5 import SR5Parameters, build_model

    sc = bp.Scene("6205", rpm=(1700.0, 1900.0), duration_s=0.2, fs=FS, resonance_hz=3000.0,
                  slip=0.02, fault=bp.Fault(kind, width_mm=1.0))
    bm = build_model(sc, SR5Parameters(contact_damping=1e-4))
    elastic = bm.p.copy()
    elastic[K.P_CD] = 0.0
    z = sc.bearing.n_elements
    kin = K.kinematics_scratch(z)
    rng = np.random.default_rng(0)
    velocity = rng.normal(size=4) * 1e-3  # u_s, v_s, u_p, v_p rates, m/s

    def loads(t, t_c, p):
        """Contact loads at t of rings at the static state at t_c, moving at velocity."""
        K.fault_depths(t, bm.p, bm.faults, kin, K.element_angles(t, bm.p, bm.walk, kin), True)
        u_s, v_s, u_p, v_p = bm.y0[:4] + (t - t_c) * velocity
        return np.array([K.contact_load(j, u_s - u_p, v_s - v_p, velocity[0] - velocity[2],
                                        velocity[1] - velocity[3], p, kin) for j in range(z)])

    def on_ramp(t):
        loaded = loads(t, t, elastic) > 0.0
        return np.any(loaded & (kin[K.K_DDEPTH, :z] != 0.0))

    ramps = [t for t in np.linspace(0.001, 0.199, 4000) if on_ramp(t)]
    assert len(ramps) >= 10
    h = 1e-8
    for t_c in np.concatenate((rng.choice(ramps, 10, replace=False), rng.uniform(0.01, 0.19, 10))):
        hertz = loads(t_c, t_c, elastic)
        on = hertz > 0.0
        rate = (loads(t_c, t_c, bm.p)[on] / hertz[on] - 1.0) / bm.p[K.P_CD]
        delta = [(loads(t, t_c, elastic) / bm.p[K.P_KH]) ** (1 / bm.p[K.P_NH])
                 for t in (t_c - h, t_c + h)]
        expected = ((delta[1] - delta[0]) / (2 * h))[on]
        np.testing.assert_allclose(rate, expected, rtol=0, atol=1e-6 * np.max(np.abs(expected)))
