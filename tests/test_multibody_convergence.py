"""Order of the multibody integrators: RK4 and the Rosenbrock-W solver against scipy's DOP853
at tight tolerance."""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.integrate import solve_ivp

import ballpass as bp
from ballpass.simulate.multibody import build, integrate


def _settled_reference(scene, h, n):
    """The scene settled to t = 0 and DOP853's loads at n h (rtol 1e-12; atol 1e-15 m,
    1e-10 m/s and N: ~1e-11 of the loads)."""
    system = build(scene)
    settled = dataclasses.replace(system, y0=integrate(system, h_out=h, n_out=0,
                                                        stride=1)["y_end"], t0=0.0)
    nd = settled.n_state - 2 * scene.bearing.n_elements
    atol = np.concatenate([np.full(nd // 2, 1e-15), np.full(nd // 2 + 18, 1e-10)])
    ref = solve_ivp(settled.rhs, (0.0, n * h), settled.y0, method="DOP853", rtol=1e-12,
                    atol=atol)
    assert ref.status == 0
    return settled, np.concatenate(settled.contact_loads(n * h, ref.y[:, -1]))


def _load_error(settled, h, n, n_sub, solver, loads_ref):
    y = integrate(settled, h_out=h, n_out=n, stride=n, dt=h / n_sub, solver=solver)["y_end"]
    loads = np.concatenate(settled.contact_loads(n * h, y))
    return float(np.max(np.abs(loads - loads_ref)) / np.max(loads_ref))


def _smooth_order(solver):
    """Fitted order and load errors of ``solver`` at 2 to 0.25 us on the healthy ER-16K
    (110 N, 35 Hz) settled to t = 0, over 50 grid intervals of 4 us."""
    scene = bp.Scene(bearing="ER-16K", rpm=2100.0, radial_load_n=110.0, fs=48_000.0,
                     duration_s=0.01)
    h, n = 4e-6, 50
    settled, loads_ref = _settled_reference(scene, h, n)
    n_subs = np.array([2, 4, 8, 16])
    errors = np.array([_load_error(settled, h, n, k, solver, loads_ref) for k in n_subs])
    return np.polyfit(np.log(h / n_subs), np.log(errors), 1)[0], errors


def test_rk4_converges_at_fourth_order_on_a_smooth_scene():
    # Seed 000's healthy ER-16K (110 N, 35 Hz, traction on), settled to t = 0, then 200 us
    # (50 grid intervals of 4 us): no contact separates, no ball meets its pocket, so the
    # right-hand side is smooth along the path and classical RK4 must show its order,
    # error ~ dt^4, halving the step dividing the error by 16. The reference is DOP853 on
    # the same right-hand side (rtol 1e-12; atol 1e-15 m, 1e-10 m/s and N): its error,
    # ~1e-11 of the loads, is 100 times below the finest RK4 error checked (1e-9).
    # The checked steps run from lambda_max dt = 1 (2 us, where the dt^5 term still adds
    # ~20 %: measured ratio 19) down to 0.25 us (ratio 16.7), so the fitted order over
    # the four steps must be 4 within 0.35 and every halving must gain at least 2^3.6.
    # Catches a wrong RK4 weight or stage (order 1-3), the stages evaluated at the wrong
    # time (the drive angle is time-dependent), a traction state left out of the update.
    order, errors = _smooth_order("rk4")
    assert abs(order - 4.0) < 0.35, (order, errors)
    assert np.all(errors[:-1] / errors[1:] > 2.0**3.6), errors
    assert errors[-1] > 100 * 1e-11


def test_recording_leaves_the_trajectory_unchanged():
    # The kernel reuses the right-hand side evaluated to record the loads at a grid
    # point as the next step's first stage. Recording at every grid point (stride 1)
    # or at none after the first (stride larger than the run) must give the same final
    # state bit for bit: the same arithmetic in the same order, so no tolerance.
    # Catches a first stage reused after the state moved on (a stale k1: planted, the
    # states differ from the second step on) or a recording call that writes the state.
    scene = bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fs=48_000.0,
                     duration_s=0.01, fault=bp.Fault("inner", width_mm=0.5, depth_mm=0.1))
    system = build(scene)
    h, n = 1.0 / 192_000, 200
    every = integrate(system, h_out=h, n_out=n, stride=1)
    once = integrate(system, h_out=h, n_out=n, stride=n + 1)
    assert np.array_equal(every["y_end"], once["y_end"])
    assert np.array_equal(every["exc"], once["exc"])
    assert np.array_equal(every["q_inner"][0], once["q_inner"][0])


def test_rosenbrock_w_converges_at_third_order_on_a_smooth_scene():
    # The same smooth 200 us as the RK4 test above (healthy ER-16K settled to t = 0, no
    # contact separating): ROS34PW2 is of order 3 for any matrix W, so halving the step
    # must divide the error by 8. Measured from dt = 2 us to 0.25 us: 4.2e-6, 5.8e-7,
    # 7.7e-8, 1.0e-8 (ratios 7.2-7.8, the dt^4 term still visible at the largest step),
    # all 1000 times above DOP853's own error. Fitted order 3 within 0.3; every halving
    # at least 2^2.6. Catches a wrong coefficient (order 1-2: a planted sign error in the
    # h J sum g_ij k_j coupling of _w_solve gives order 1.9), a stage at the wrong time, a
    # block solved with the wrong matrix.
    order, errors = _smooth_order("rosw")
    assert abs(order - 3.0) < 0.3, (order, errors)
    assert np.all(errors[:-1] / errors[1:] > 2.0**2.6), errors
    assert errors[-1] > 100 * 1e-11


def test_rosenbrock_w_stays_accurate_past_the_rk4_limit_of_the_contact_root():
    # The 6205 at 500 N settled, 40 grid intervals of 5.2 us taken in one step each:
    # lambda_max dt = 4.2, past RK4's real-axis limit of 2.79 on the overdamped contact
    # root. RK4 there is a different motion (measured load error 0.46 against DOP853);
    # ROS34PW2 treats each ball's contact stiffness and damping implicitly, so the same
    # step stays within 2.2e-5 of the loads. Bounds: 1e-4 (5x the measured error) and
    # 0.1 for RK4. Catches contact blocks left out of W (then the step is explicit and
    # fails like RK4: planted, the state diverges within 31 us; the sign error of the
    # test above: 2.7e-4) or a block with the wrong mass or damping time.
    scene = bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fs=48_000.0,
                     duration_s=0.01)
    h, n = 1.0 / 192_000, 40
    settled, loads_ref = _settled_reference(scene, h, n)
    assert settled.lambda_max * h > 2.79
    assert _load_error(settled, h, n, 1, "rosw", loads_ref) < 1e-4
    assert _load_error(settled, h, n, 1, "rk4", loads_ref) > 0.1
