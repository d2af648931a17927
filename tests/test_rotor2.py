"""rotor2 (seed 003 rotor on a cylindrical roller bearing) and the generic RK4,
Newmark-beta and second-order Dormand-Prince integrators it runs on."""

import math
import time

import numpy as np
import pytest
import scipy.linalg
from numba import njit

import ballpass as bp
from ballpass.simulate import MODELS, Rotor2Parameters
from ballpass.simulate import _second_order as I

# -- a linear 2-DOF system M a + C v + K x = F cos(W t) e, exact by matrix exponential --
M = np.diag([2.0, 1.0])
K = np.array([[3.0e4, -1.0e4], [-1.0e4, 2.0e4]])  # coupled: modes 14 and 27 Hz
C = 2e-4 * K + 0.5 * M  # Rayleigh damping, a few percent
F_AMP, W_F = np.array([30.0, 0.0]), 60.0  # harmonic force on DOF 0, rad/s


@njit
def _linear_force(t, x, v, p, f, kx, kv):
    # p packs K (4), C (4), F (2), W: f = C v + K x - F cos(W t)
    for i in range(2):
        f[i] = -p[8 + i] * math.cos(p[10] * t)
        for j in range(2):
            kx[i, j] = p[2 * i + j]
            kv[i, j] = p[4 + 2 * i + j]
            f[i] += kx[i, j] * x[j] + kv[i, j] * v[j]


def _linear_exact(t, x0, v0):
    """Closed form: the steady harmonic response plus the free response, propagated
    exactly by the matrix exponential of the first-order system."""
    a = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    b = np.concatenate((np.zeros(2), np.linalg.solve(M, F_AMP)))
    y_amp = np.linalg.solve(1j * W_F * np.eye(4) - a, b)  # y_p = Re(Y exp(i W t))
    y0 = np.concatenate((x0, v0)) - y_amp.real
    free = np.array([scipy.linalg.expm(a * ti) @ y0 for ti in t])
    steady = np.real(np.outer(np.exp(1j * W_F * t), y_amp))
    return (free + steady)[:, :2]


def test_newmark_linear_2dof_closed_form_second_order():
    p = np.concatenate((K.ravel(), C.ravel(), F_AMP, [W_F]))
    x0, v0 = np.array([1e-3, -2e-3]), np.array([0.05, 0.0])
    h_out, n_out = 2e-3, 251  # 0.5 s: ~7 and ~13 periods of the two modes
    exact = _linear_exact(np.arange(n_out) * h_out, x0, v0)
    newmark = I.newmark_for(_linear_force, cache=False)  # a test's force: not cached
    errors = []
    for n_sub in (2, 4, 8):
        out = [np.empty((n_out, 2)) for _ in range(3)]
        status, n_steps, _, _ = newmark(p, M, x0, v0, h_out, n_sub, n_out, np.full(2, 1e-3),
                                        1e-12, 1e6, *out)
        assert status == I.STATUS_OK and n_steps == (n_out - 1) * n_sub
        errors.append(np.max(np.abs(out[0] - exact)) / np.max(np.abs(exact)))
    # second order: halving the step divides the error by 4 (period error (w dt)^2/12);
    # the band allows the next-order term at w dt up to 0.17
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 3.6) & (ratios < 4.4)), (errors, ratios)
    # and the error is the scheme's, not a wrong equation: (w dt)^2/12 scaled by the
    # phase accumulated over the record (27 Hz mode, 0.5 s, dt 0.25 ms) is ~1e-3
    assert errors[-1] < 3e-3


def _scene(clearance_mm=0.005, load=500.0, fault=True, rpm=1500.0, duration=0.06, fs=20_000.0):
    b = bp.Bearing.catalog("NJ305").with_clearance(clearance_mm)
    f = bp.Fault("inner", width_mm=0.5, depth_mm=0.5) if fault else None  # seed 003 s. 3.6
    return bp.Scene(bearing=b, rpm=rpm, radial_load_n=load, fault=f, duration_s=duration,
                    fs=fs, resonance_hz=0.4 * fs)


def test_rk4_linear_2dof_closed_form_fourth_order_between_steps():
    # steps longer than the output spacing, a break mid-record: the interpolated
    # outputs (x, v and a = -M^-1 f) keep the method's fourth order
    p = np.concatenate((K.ravel(), C.ravel(), F_AMP, [W_F]))
    x0, v0 = np.array([1e-3, -2e-3]), np.array([0.05, 0.0])
    h_out, n_out = 2.5e-4, 2001  # 0.5 s, output 4-16 times per step
    t = np.arange(n_out) * h_out
    exact = _linear_exact(t, x0, v0)
    acc_exact = -np.linalg.solve(M, (K @ exact.T + C @ np.gradient(exact, h_out, axis=0).T
                                     - np.outer(F_AMP, np.cos(W_F * t)))).T
    rk4 = I.rk4_for(_linear_force, cache=False)  # a test's force: not cached
    breaks = np.array([0.2371])
    errors, acc_errors = [], []
    for dt in (4e-3, 2e-3, 1e-3):  # w dt 0.68, 0.34, 0.17 for the 27 Hz mode
        out = [np.empty((n_out, 2)) for _ in range(3)]
        status, n_steps, _, _ = rk4(p, np.linalg.inv(M), x0, v0, h_out, n_out, breaks,
                                    np.full(2, dt), 0, 0.0, 1e6, np.full(2, 1e-3), 1, *out)
        assert status == I.STATUS_OK and n_steps == pytest.approx(0.5 / dt, abs=2)
        errors.append(np.max(np.abs(out[0] - exact)) / np.max(np.abs(exact)))
        # the exact acceleration's np.gradient velocity is O(h_out^2) off: compare
        # against the equation of motion at the interpolated state instead
        acc_model = -np.linalg.solve(M, (K @ out[0].T + C @ out[1].T
                                         - np.outer(F_AMP, np.cos(W_F * t)))).T
        acc_errors.append(np.max(np.abs(out[2] - acc_model)) / np.max(np.abs(acc_exact)))
    # fourth order: halving the step divides the error by 16 (the band allows the
    # next-order term at w dt up to 0.7)
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 13) & (ratios < 19)), (errors, ratios)
    assert errors[-1] < 1e-4
    # the interpolated acceleration is the equation of motion's at the interpolated
    # state to the same order (a wrong Hermite weight leaves an O(1) error here)
    assert acc_errors[-1] < 1e-3 and acc_errors[0] / acc_errors[-1] > 8, acc_errors


def _accel_error(res, ref):
    """Relative L2 error of the output acceleration (work-precision ``error_l2``)."""
    return float(np.linalg.norm(res.accel - ref.accel) / np.linalg.norm(ref.accel))


@pytest.mark.parametrize("solver", ["rk4", "newmark"])
def test_default_steps_match_dopri5_on_rotor2(solver):
    # a regular (non-chaotic) seed-003 scene: small clearance, 500 N, the seed's 0.5 mm
    # inner-race defect, whose impacts are the hard part
    scene = _scene()
    res = bp.simulate(scene, model="rotor2", solver=solver, return_forces=True)
    ref = bp.simulate(scene, model="rotor2", solver="dopri5", rtol=1e-10, return_forces=True)
    assert res.info["solver"] == solver and res.info["dt_s"] > 0
    x, x_ref = res.truth.displacement, ref.truth.displacement
    assert x.shape == (2, scene.n_samples)
    dynamic = x_ref - x_ref.mean(axis=1, keepdims=True)
    # the bound, on the dynamic part of the displacement (the static offset
    # c + delta would make any error look small) and on the output acceleration
    assert np.linalg.norm(x - x_ref) / np.linalg.norm(dynamic) < 1e-2
    assert _accel_error(res, ref) < 1e-2
    # the defect moves the rotor by micrometres (seed 003: 0.7-4 um), so this is a test
    assert np.ptp(x_ref[0]) > 1e-6
    # the sensor signal is the rotor acceleration on the sensor direction (load line)
    acc = np.gradient(np.gradient(x_ref[0], scene.fs), scene.fs)
    acc -= acc.mean()
    corr = np.corrcoef(acc[50:-50], res.accel[50:-50])[0, 1]
    assert corr > 0.9


@pytest.mark.parametrize("fault", [False, True])
def test_rk4_fourth_order_across_contact_closures_on_the_nj305_scene(fault):
    # The NJ 305 scene (5 um clearance): rollers leave and re-enter the load zone every
    # pass and, with the 0.5 mm defect, the rotor bounces off its rollers (~260 contact
    # closures and openings in 60 ms); Palmgren's load K delta^(10/9) has a kink of its
    # derivatives at each. Halving the step must divide the error against dopri5
    # (rtol 1e-10, whose own error is below 1e-8 of these) by 16, fourth order:
    # measured 15.2 healthy and 12.2-12.5 with the defect (at 0.3 / omega_c the
    # defect's ramps take their own steps of 1/8 of the ramp, 7.7 us, about half the
    # 15 us step, so the ramps' share of the error does not fall with it). The band
    # [11, 22] excludes third order (8). Planted: closures only (openings stepped
    # over) gives 1.0 with the defect, restarts at the crossing step's midpoint 22.5
    # (and both fail the default step's 1e-2 bound in the test above).
    scene = _scene(fault=fault)
    from ballpass.simulate.rotor2 import contact_omega

    omega = contact_omega(scene)
    ref = bp.simulate(scene, model="rotor2", solver="dopri5", rtol=1e-10, return_forces=True)
    dynamic = ref.truth.displacement - ref.truth.displacement.mean(axis=1, keepdims=True)
    err_a, err_x = [], []
    for c in (0.15, 0.3):
        res = bp.simulate(scene, model="rotor2", dt=c / omega, return_forces=True)
        err_a.append(_accel_error(res, ref))
        err_x.append(float(np.linalg.norm(res.truth.displacement - ref.truth.displacement)
                           / np.linalg.norm(dynamic)))
        if fault:  # the bounces are there to be restarted on
            assert res.info["n_contact_restarts"] > 100
    for err in (err_a, err_x):
        assert 11 < err[1] / err[0] < 22, (err_a, err_x)


def test_default_rk4_step_within_1e2_on_the_cost_scene():
    # issue scene of the cost table (6205, 1797 rpm, 500 N, inner 0.5 x 0.1 mm, 48 kHz),
    # 50 ms: the default rk4 step (0.3 / omega_c, ~32 us, longer than the 5.2 us
    # output spacing) against dopri5 at rtol 1e-10; measured 3.9e-3 (benchmarks/rotor2_step.py)
    scene = bp.Scene(bearing="6205", rpm=1797, radial_load_n=500, duration_s=0.05,
                     fault=bp.Fault("inner", width_mm=0.5, depth_mm=0.1), fs=48_000.0)
    res = bp.simulate(scene, model="rotor2")
    ref = bp.simulate(scene, model="rotor2", solver="dopri5", rtol=1e-10)
    assert res.info["dt_s"] > 4 / (scene.fs * 4)  # steps span several output points
    assert _accel_error(res, ref) < 1e-2


@pytest.mark.parametrize("tangents", [True, False])
def test_force_is_the_contact_law_at_times_visited_out_of_order(tangents):
    """The force against an independent evaluation (each roller's angle from its own
    sines and cosines, a sharp outer-race notch's depth by hand, Hertz's law) at times
    visited out of order and repeated, as the integrators do: catches kinematics
    cached per time but not refreshed (planted: never recomputed after the first call
    fails by the load zone's motion), and the force without tangents differing from
    the one with them. Tolerance 1e-9 of the largest force: the two differ only by the
    rounding of the roller angles (a rotation per roller against direct sines)."""
    from ballpass.simulate import _kernels as K
    from ballpass.simulate import rotor2 as R

    fault = bp.Fault("outer", width_mm=3.0, depth_mm=0.1, edge="sharp", angle_deg=20.0)
    scene = bp.Scene(bearing="6205", rpm=1797, radial_load_n=500, duration_s=0.1,
                     fault=fault, fs=48_000.0)
    bound = R._bind(scene, Rotor2Parameters())
    p = bound.p
    force = R.rotor2_force if tangents else R.rotor2_force_only
    rng = np.random.default_rng(0)
    z = int(p[K.P_Z])
    row = R.P_FAULTS  # the notch's row of the fault table
    # at 14 ms and 51.2 ms a loaded roller sits in the notch
    for t in (0.0, 0.014, 0.0, 0.0371, 0.014, 0.0371, 0.0512):
        x = bound.x0 * (1.0 + 0.3 * rng.standard_normal(2))
        v = 0.01 * rng.standard_normal(2)
        f, kx, kv = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2))
        force(t, x, v, p, f, kx, kv)
        theta = p[K.P_W0] * t
        phi = p[R.P_PHI0] + 2 * np.pi * np.arange(z) / z + p[K.P_CAGE] * theta
        off = (phi - p[row + K.F_CENTRE] + np.pi) % (2 * np.pi) - np.pi
        depth = np.where(np.abs(off) < p[row + K.F_HALF], p[row + K.F_DEPTH], 0.0)
        delta = x[0] * np.cos(phi) + x[1] * np.sin(phi) - p[K.P_CLEAR] - depth
        q = p[K.P_KH] * np.maximum(delta, 0.0) ** 1.5
        ref = np.array([q @ np.cos(phi), q @ np.sin(phi)])
        ref += p[R.P_CR] * v - np.array([p[K.P_FR] + p[K.P_MS] * p[K.P_G], 0.0])
        u = theta + p[R.P_UPH]  # the unbalance m_u e w^2 at constant speed
        ref -= p[R.P_MUE] * p[K.P_W0] ** 2 * np.array([np.cos(u), np.sin(u)])
        np.testing.assert_allclose(f, ref, rtol=0, atol=1e-9 * np.abs(q).max())
        if tangents:  # dQ/d(delta) = 1.5 Q / delta projected on the rollers
            dq = np.where(delta > 0, 1.5 * q / np.where(delta > 0, delta, 1.0), 0.0)
            np.testing.assert_allclose(kx[0, 0], dq @ np.cos(phi) ** 2, rtol=1e-9)


def _line(x, fs, f):
    """Amplitude of x (Hann window) at exactly the frequency f, same unit as x."""
    t = np.arange(x.size) / fs
    win = np.hanning(x.size)
    return 2 * abs(np.sum(win * (x - x.mean()) * np.exp(-2j * np.pi * f * t))) / win.sum()


def test_seed003_defect_lines():
    # seed 003 section 5: inner-race lines at f_i = Z/2 f_r (1 + d/D_m) for the NJ 305
    expected = {1500: 166.73, 900: 100.04, 600: 66.69, 500: 55.55}
    for rpm, f_seed in expected.items():
        # the same samples and steps per revolution at every speed; the regular regime
        # (small clearance, 500 N), where the healthy rotor has no line at BPFI
        scene = _scene(clearance_mm=0.005, load=500.0, rpm=rpm, duration=8 * 60 / rpm,
                       fs=3000.0 * rpm / 1500)
        bpfi = scene.frequencies.bpfi
        assert bpfi == pytest.approx(f_seed, abs=0.05)  # the seed rounds (55.55 vs 55.58)
        amp = {}
        for s in (scene, scene.replace(fault=None)):
            res = bp.simulate(s, model="rotor2", return_forces=True)
            x = res.truth.displacement[0, scene.n_samples // 8:]  # one revolution of start
            # at BPFI and half a shaft order either side (between its sidebands)
            amp[s.label] = [_line(x, s.fs, bpfi + d * scene.shaft_hz) for d in (0, -.5, .5)]
        faulty, healthy = amp["inner"], amp["healthy"]
        # the defect makes the content at BPFI: 0.014-0.08 um against < 1e-4 um healthy
        # (leakage of the varying-compliance line at BPFO), 100x leaves room for both ...
        assert faulty[0] > 100 * healthy[0]
        # ... and a line that stands above the defect's broadband response (each impact
        # rings the lightly damped rotor modes; measured 1.7-12x over 7 revolutions).
        # Not at 1500 rpm: there the impacts make the trajectory sensitive (rk4 at the
        # default step, at 1/8 of it and Newmark at 1.3 us give 45 / 68 / 79 nm at BPFI
        # and 49 / 41 / 22 nm half an order above), so the ratio is the trajectory's
        if rpm != 1500:
            assert faulty[0] > max(faulty[1:])
        # ... and below the kinematic ceiling of a rotor on its rollers: the roller drops
        # at most h into the notch, which is under a roller Z w / (2 pi r_i) of the time,
        # and a non-negative pulse train's line is at most twice its mean
        # (docs/seed003.md): 0.88 um. A defect acting deeper than a roller can reach (the
        # paper's 0.5 mm profile height) breaks it
        b = scene.bearing
        fault = scene.faults[0]
        r_i = 0.5 * (b.pitch_diameter_mm - b.element_diameter_mm)
        duty = b.n_elements * fault.width_mm / (2 * math.pi * r_i)
        assert faulty[0] < 2 * fault.effective_depth_mm(b) * 1e-3 * duty


@pytest.mark.parametrize("name", ["NJ305", "6205"])
def test_static_equilibrium_matches_load_distribution(name):
    # a quasi-static rotor (0.01 rpm), no unbalance, rollers not symmetric about the
    # load line (cage at 10 deg: the rotor also shifts sideways): after the start the
    # rotor must stay at the equilibrium of Bearing.load_distribution (Stribeck, solved
    # by brentq on the same Palmgren law; Hertz for the balls of the 6205) and carry
    # its element loads
    b = bp.Bearing.catalog(name).with_clearance(0.02)
    scene = bp.Scene(bearing=b, rpm=0.01, radial_load_n=800.0, duration_s=0.05, fs=4000.0,
                     resonance_hz=1000.0)
    params = Rotor2Parameters(unbalance_mass_kg=0.0, cage_angle_deg=10.0,
                              rotor_mass_kg=2.0)
    res = bp.simulate(scene, model="rotor2", params=params, return_forces=True)
    # at the cage angle reached at the end (the cage turns 1e-3 deg in 0.05 s)
    cage_deg = math.degrees(res.truth.element_angles[0, -1])
    assert cage_deg == pytest.approx(10.0, abs=2e-3)
    ld = b.load_distribution(800.0 + 2.0 * 9.80665, cage_angle_deg=cage_deg)
    x, y = res.truth.displacement[:, -1]
    assert ld.lateral_deflection_m != 0.0
    # 1e-6: what remains of the start transient (5 decay times) and the quasi-static lag
    assert x == pytest.approx(ld.deflection_m, rel=1e-6)
    assert y == pytest.approx(ld.lateral_deflection_m, rel=1e-4, abs=1e-12)
    np.testing.assert_allclose(res.truth.contact_forces[:, -1], ld.element_loads_n,
                               rtol=1e-4, atol=1e-6 * ld.q_max_n)
    # separated rollers carry exactly nothing
    assert np.all(res.truth.contact_forces[ld.element_loads_n == 0.0] == 0.0)


def test_rotor2_in_registry_and_auto():
    m = MODELS["rotor2"]
    assert {"rotor_dynamics", "contact_dynamics", "contact_forces"} <= m.represents
    assert m.default_solver == "rk4" and m.fixed_step_solvers == ("rk4", "newmark")
    scene = _scene(fault=False).replace(needs=("rotor_dynamics",))
    assert bp.simulate.resolve_model(scene) == "rotor2"


def test_bad_input_refused_before_work():
    with pytest.raises(ValueError, match="n_elements"):  # zero rollers
        bp.Bearing(name="zero", n_elements=0, element_diameter_mm=9.25, pitch_diameter_mm=43.5,
                   element="roller", roller_length_mm=11.0)
    # a preload beyond the elastic limit (1 % of the roller diameter = 92.5 um)
    tight = _scene(clearance_mm=-0.2)
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=r"radial_clearance_mm=-0\.2.*elastic limit"):
        bp.simulate(tight, model="rotor2")
    assert time.perf_counter() - t0 < 1.0  # refused before integrating
    with pytest.raises(ValueError, match="misalignment_rad=0.001 needs the laminae"):
        bp.simulate(bp.Scene(bearing="6205"), model="rotor2",
                    params=Rotor2Parameters(misalignment_rad=1e-3))
    with pytest.raises(ValueError, match="n_laminae"):
        Rotor2Parameters(n_laminae=0)
    with pytest.raises(ValueError, match="rotor_mass_kg"):
        Rotor2Parameters(rotor_mass_kg=-1.0)
    with pytest.raises(ValueError, match="rtol"):
        bp.simulate(_scene(), model="rotor2", rtol=1e-6)  # rk4 takes dt
    with pytest.raises(TypeError, match="Rotor2Parameters"):
        bp.simulate(_scene(), model="rotor2", params=bp.simulate.SR5Parameters())


def test_laminae_collapse_to_palmgren_when_aligned():
    # seed 003 eq. 6: k laminae of width l/k carrying q = delta^1.11 / (1.24e-5 l^0.11)
    # each sum to Palmgren's law; a tilt loads one end of the roller harder
    scene = _scene(fault=False, duration=0.03, fs=4000.0)
    base = bp.simulate(scene, model="rotor2", return_forces=True)
    one = bp.simulate(scene, model="rotor2", return_forces=True,
                      params=Rotor2Parameters(misalignment_rad=1e-3, n_laminae=1))
    np.testing.assert_array_equal(one.truth.displacement, base.truth.displacement)
    tilted = bp.simulate(scene, model="rotor2", return_forces=True,
                         params=Rotor2Parameters(misalignment_rad=1e-3, n_laminae=20))
    # a 1 mrad tilt over 11 mm varies the approach by +-5.5 um along the roller; with
    # the convex law (exponent 10/9 > 1) a varying approach carries more than a uniform
    # one of the same mean (Jensen), so the tilted bearing is stiffer: the rotor settles
    # higher (the mean of the last 10 ms; the transient decays in ~5 ms)
    last = slice(-40, None)
    lift = (base.truth.displacement[0, last].mean()
            - tilted.truth.displacement[0, last].mean())
    assert lift > 1e-8


@pytest.mark.parametrize("n_laminae", [10, 7])
def test_a_tilt_and_its_opposite_move_the_rotor_alike(n_laminae):
    """A roller is symmetric about its centre: tilted by +1 mrad or -1 mrad, its
    laminae (centred at s = (lambda + 1/2) w - l/2) carry the same set of approaches,
    so the rotor moves the same, to the rounding of the summation order (measured 6e-12
    of the largest displacement, 3e-11 of the largest acceleration): 1e-9. Laminae
    shifted by half a width lose the symmetry: 2e-2. The tilt itself moves the rotor by
    70 % of its largest displacement, so the comparison is not between two aligned
    runs."""
    scene = _scene(duration=0.03, fs=20_000.0)
    runs = [bp.simulate(scene, model="rotor2", return_forces=True,
                        params=Rotor2Parameters(misalignment_rad=gamma, n_laminae=n_laminae))
            for gamma in (1e-3, -1e-3, 0.0)]
    plus, minus, aligned = (r.truth.displacement for r in runs)
    scale = np.max(np.abs(plus))
    assert np.max(np.abs(plus - minus)) < 1e-9 * scale
    assert np.max(np.abs(runs[0].accel - runs[1].accel)) < 1e-9 * np.max(np.abs(runs[0].accel))
    assert np.max(np.abs(plus - aligned)) > 0.5 * scale


def test_laminae_approach_the_line_contact_integral_at_second_order():
    """k laminae at the centres of k equal slices are the midpoint rule for the tilted
    line contact K integral over s/l in [-1/2, 1/2] of (delta + s gamma cos phi)^n,
    whose closed form is K ((delta + a/2)^(n+1) - (delta - a/2)^(n+1)) / ((n+1) a),
    a = l gamma cos phi. With every lamina in contact (delta = 8 um > a/2 = 5.5 um) the
    error is -(n (n-1) / 24) (a/delta)^2 / k^2 to leading order: 1.1e-4 at k = 10
    (measured), falling 4x per doubling. Laminae shifted by half a slice are the
    left-point rule: a first-order error n a / (2 k delta) = 8 %."""
    from ballpass.simulate import _kernels as K
    from ballpass.simulate import rotor2 as R

    scene, gamma, delta = _scene(fault=False), 1e-3, 8e-6
    errors = []
    for n_laminae in (10, 20):
        p = R._bind(scene, Rotor2Parameters(misalignment_rad=gamma, n_laminae=n_laminae)).p
        phi = p[R.P_PHI0]  # roller 0 at t = 0, pressed by delta along its own line
        x = (delta + p[K.P_CLEAR]) * np.array([math.cos(phi), math.sin(phi)])
        load = R._roller(0, 0.0, x, np.zeros(2), p)[0]
        a, n = p[R.P_LEN] * gamma * math.cos(phi), p[K.P_NH]
        exact = p[K.P_KH] * ((delta + a / 2) ** (n + 1) - (delta - a / 2) ** (n + 1)) / (
            (n + 1) * a)
        errors.append(load / exact - 1.0)
    assert abs(errors[0]) < 5e-4
    assert 3.5 < errors[0] / errors[1] < 4.5


@pytest.mark.parametrize("kind, angle_deg", [("outer", 30.0), ("inner", 0.0), ("ball", 40.0)])
def test_fault_crossings_match_sr5_kinematics(kind, angle_deg):
    """rotor2's ground-truth crossings (a closed form in the shaft angle) equal sr5's
    (found numerically by bracketing in the kernel) when sr5's cage does not slip, on a
    speed ramp, edge for edge: catches an inner race whose entries and exits are
    swapped (its offset falls), a ball face mislabelled, or a ramp inverted as if the
    speed were constant. Tolerance 1e-12 s: both are exact up to the bracketing's
    floating-point width (~1e-16 s here)."""
    scene = bp.Scene(bearing="NJ305", rpm=(1500.0, 1800.0), radial_load_n=500.0,
                     duration_s=0.05, fs=48_000.0, slip=0.0,
                     fault=bp.Fault(kind, width_mm=1.0, depth_mm=0.1, angle_deg=angle_deg))
    mine = bp.simulate(scene, model="rotor2").truth.fault_crossings
    ref = bp.simulate(scene, model="sr5").truth.fault_crossings
    assert len(mine) == len(ref) > 8
    np.testing.assert_allclose(mine.time_s, ref.time_s, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(mine.edge, ref.edge)
    np.testing.assert_array_equal(mine.element, ref.element)


def test_rotor2_equations_match_an_independent_writing(monkeypatch):
    # docs/seed003.md section 5 argues about rotor2's chaos with the rotor's equations
    # written again in NumPy (benchmarks/seed003_chaos.py, rotor_rhs) and integrated by
    # SciPy: the two must be the same equations. From the same state, rotor2's dopri5 at
    # rtol 1e-10 and solve_ivp's DOP853 at rtol 1e-10 agree to ~1e-15 m over 5 ms
    # (measured 6e-16 m at 900 rpm; the Lyapunov exponent, ~150 1/s, amplifies a
    # difference only 2x in 5 ms), so 1e-12 m (1e-8 of the clearance) fails any change
    # of the physics: the paper's unbalance of 0.009 N alone moves the rotor ~1e-7 m in
    # 5 ms. Planted: the unbalance's sign flipped in rotor_rhs, failed.
    import importlib.util
    from pathlib import Path

    from scipy.integrate import solve_ivp

    bench = Path(__file__).resolve().parents[1] / "benchmarks"
    monkeypatch.syspath_prepend(str(bench))
    spec = importlib.util.spec_from_file_location("seed003_chaos", bench / "seed003_chaos.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    s = mod.scene(0.125, 900.0, 0.005)
    params = Rotor2Parameters()
    res = bp.simulate(s, model="rotor2", solver="dopri5", rtol=1e-10, return_forces=True,
                      params=params)
    ours = res.truth.displacement
    y0 = np.concatenate((ours[:, 0], [0.0, 0.0]))
    ref = solve_ivp(mod.rotor_rhs(s, params), (0.0, res.t[-1]), y0, method="DOP853",
                    rtol=1e-10, atol=1e-16, t_eval=res.t).y[:2]
    assert np.abs(ours - ref).max() < 1e-12
    assert np.ptp(ref[0]) > 1e-8  # the rotor moved: the comparison is not of two rests
