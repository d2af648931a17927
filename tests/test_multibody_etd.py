"""The exponential RK4 step of benchmarks/_multibody_routes.py (ETDRK4, Cox & Matthews
2002, on the fast root of every overdamped contact block, in a copy of the kernels): its
phi functions and weights against their closed forms, its propagator against the
eigen-decomposition of the contact block, and its order against scipy's DOP853."""

from __future__ import annotations

import math

import numpy as np
import pytest
from _bench import load_benchmark
from test_multibody_convergence import _load_error, _settled_reference

import ballpass as bp
from ballpass.simulate.multibody import build, integrate

routes = load_benchmark("_multibody_routes")


@pytest.fixture(scope="module")
def etd():
    return routes.variant_kernels(routes.ETD)


def test_phi_functions_and_weights_match_their_closed_forms(etd):
    # phi_1..3 by their Taylor series (|z| <= 0.5) and by the recursion beyond, against
    # the closed forms (e^z - 1) / z, (e^z - 1 - z) / z^2, (e^z - 1 - z - z^2 / 2) / z^3
    # written with expm1: at |z| >= 0.3 the closed form of phi_3 loses eps / |z|^3 <
    # 1e-14 to cancellation, so 1e-12 relative bounds rounding only (a wrong series
    # coefficient or recursion constant is off by 1e-3 or more).
    for z in (-0.3, -0.5, -0.5000001, -0.9, -2.1, -4.2, -30.0):
        em = math.expm1(z)
        want = (em / z, (em - z) / z**2, (em - z - 0.5 * z * z) / z**3)
        got = etd._phi123(z, em)
        np.testing.assert_allclose(got, want, rtol=1e-12, err_msg=str(z))
    # at z = 0 the step is classical RK4: exp 1, h/2, weights h/6, h/3 (on N_a + N_b), h/6
    h = 2.6e-6
    out = np.zeros(5)
    etd._root_coefs(0.0, h, out, 0)
    np.testing.assert_allclose(out, [1.0, h / 2, h / 6, h / 3, h / 6], rtol=1e-15)


def _block_system():
    """A real system's parameters and one ball with a stiff contact along (0.6, 0.8)
    (k = 2e8 N/m, a loaded 6205 contact block: lambda dt = 2 at 2.6 us) and none across it."""
    system = build(bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fs=48_000.0,
                            duration_s=0.01))
    z = system.scene.bearing.n_elements
    kb = np.zeros((z + 1, 3))
    n = np.array([0.6, 0.8])
    kb[0] = 2e8 * np.array([n[0] * n[0], n[0] * n[1], n[1] * n[1]])
    return system, kb, n


def test_propagator_is_the_exponential_of_the_fast_mode(etd):
    # The linear part L of a ball with one loaded direction n is the fast root s1 of
    # its block [[0, 1], [-k/m, -tau k/m]] on the fast eigenvector; the propagator
    # exp(h L / 2) must scale that mode of (x, v) along n by exp(s1 h / 2) and leave the
    # slow mode, the direction across n and every other state as they are. Reference:
    # numpy's eigen-decomposition of the 2 x 2 block. 1e-12 of the result's largest
    # entry (a speed s1 x ~ 1e5 times a position): rounding through the modal
    # transform's condition number (below 3). Catches a wrong sign of the
    # exponent (exp(+s1 h / 2) = 10 times the mode), the slow root in place of the fast
    # one, the direction across n (a rotation's sign).
    system, kb, n = _block_system()
    p = system.p
    h = 2.6e-6
    z = kb.shape[0] - 1
    prop = np.zeros((z + 1, etd.ETD_COLS))
    etd.etd_blocks(kb, p, h, prop)
    m, tau = p[etd.P_MB], p[etd.P_TAU]
    w0 = 2e8 / m
    lam, vec = np.linalg.eig(np.array([[0.0, 1.0], [-w0, -tau * w0]]))
    assert np.all(np.isreal(lam)) and lam.min() * h < -1.5  # overdamped and stiff
    rng = np.random.default_rng(3)
    v = rng.normal(size=system.n_state)
    nd = system.n_state // 2 - z
    b = 6
    got = v.copy()
    etd._etd_apply(got, prop, p, 0, 1.0)
    # modal coordinates of (x, v) along n
    xv = np.array([n @ v[b:b + 2], n @ v[nd + b:nd + b + 2]])
    c = np.linalg.solve(vec, xv)
    fast = int(np.argmin(lam.real))
    c[fast] *= math.exp(lam[fast].real * h / 2)
    new = (vec @ c).real
    want = v.copy()
    want[b:b + 2] += n * (new[0] - xv[0])
    want[nd + b:nd + b + 2] += n * (new[1] - xv[1])
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.max(np.abs(want)))
    # h/2 phi_1(z/2) on the same mode, the scalar h/2 elsewhere
    got = v.copy()
    etd._etd_apply(got, prop, p, 1, 0.5 * h)
    zf = lam[fast].real * h / 2
    c = np.linalg.solve(vec, xv)
    c[fast] *= 0.5 * h * math.expm1(zf) / zf
    c[1 - fast] *= 0.5 * h
    new = (vec @ c).real
    want = 0.5 * h * v
    want[b:b + 2] += n * (new[0] - 0.5 * h * xv[0])
    want[nd + b:nd + b + 2] += n * (new[1] - 0.5 * h * xv[1])
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.max(np.abs(want)))


def test_etd_converges_at_fourth_order_on_a_smooth_scene(etd):
    # The healthy ER-16K of test_multibody_convergence (settled, 200 us, no contact
    # separating: a smooth path) against DOP853 at rtol 1e-12 (~1e-11 of the loads).
    # With L frozen per step and its remainder f - L w smooth, ETDRK4 has classical
    # order 4 (Cox & Matthews 2002; Hochbruck & Ostermann 2010's stiff order conditions
    # only weaken it for unbounded L, here lambda_max dt <= 1): the fitted order over
    # 2 to 0.25 us must be 4 within 0.5 (RK4 on the same scene: within 0.35; the
    # exponential weights add their own h^5 terms at the coarse end). The scene's
    # overdamped blocks must be in L (else this is RK4's test again). Catches a wrong
    # sign of the exponent (diverges), L subtracted at one stage but not propagated
    # (the block not frozen consistently: order 1 or no convergence), a wrong weight.
    scene = bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fs=48_000.0,
                     duration_s=0.01)
    h, n = 4e-6, 50
    settled, loads_ref = _settled_reference(scene, h, n)
    z = scene.bearing.n_elements
    kb = np.zeros((z + 1, 3))
    prop = np.zeros((z + 1, etd.ETD_COLS))
    _f, qi, qo = settled._eval(0.0, settled.y0)
    etd.ball_stiffness(settled.y0, settled.p, qi, qo, kb)
    etd.etd_blocks(kb, settled.p, h / 2, prop)
    assert np.count_nonzero(prop[:z, 2]) >= 3  # loaded balls' fast roots in L
    n_subs = np.array([2, 4, 8, 16])
    with routes.kernels(etd):
        errors = np.array([_load_error(settled, h, n, k, "rk4", loads_ref) for k in n_subs])
    order = np.polyfit(np.log(h / n_subs), np.log(errors), 1)[0]
    assert abs(order - 4.0) < 0.5, (order, errors)
    assert errors[-1] < 1e-8, errors


def test_etd_copy_is_not_the_model_and_gives_it_back(etd):
    # The work-precision rows etd run the copy: it must change the trajectory (a copy
    # whose branch never runs would time and score RK4) and leave the model's kernels
    # in place afterwards.
    system = build(bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fs=48_000.0,
                            duration_s=0.01))
    h = 1.0 / 192_000
    plain = integrate(system, h_out=h, n_out=40, stride=4, dt=h / 2)
    with routes.kernels(etd):
        other = integrate(system, h_out=h, n_out=40, stride=4, dt=h / 2)
    again = integrate(system, h_out=h, n_out=40, stride=4, dt=h / 2)
    assert not np.array_equal(plain["y_end"], other["y_end"])
    assert np.array_equal(plain["y_end"], again["y_end"])
