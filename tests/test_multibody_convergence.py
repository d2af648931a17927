"""Order of the multibody integrator: RK4 against scipy's DOP853 at tight tolerance."""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.integrate import solve_ivp

import ballpass as bp
from ballpass.simulate.multibody import build, integrate


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
    scene = bp.Scene(bearing="ER-16K", rpm=2100.0, radial_load_n=110.0, fs=48_000.0,
                     duration_s=0.01)
    system = build(scene)
    h, n = 4e-6, 50
    settled = dataclasses.replace(system, y0=integrate(system, h_out=h, n_out=0,
                                                        stride=1)["y_end"], t0=0.0)
    nd = settled.n_state - 2 * scene.bearing.n_elements
    atol = np.concatenate([np.full(nd // 2, 1e-15), np.full(nd // 2 + 18, 1e-10)])
    ref = solve_ivp(settled.rhs, (0.0, n * h), settled.y0, method="DOP853", rtol=1e-12,
                    atol=atol)
    assert ref.status == 0
    loads_ref = np.concatenate(settled.contact_loads(n * h, ref.y[:, -1]))
    dts, errors = [], []
    for n_sub in (2, 4, 8, 16):
        y = integrate(settled, h_out=h, n_out=n, stride=n, dt=h / n_sub)["y_end"]
        loads = np.concatenate(settled.contact_loads(n * h, y))
        dts.append(h / n_sub)
        errors.append(np.max(np.abs(loads - loads_ref)) / np.max(loads_ref))
    order = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert abs(order - 4.0) < 0.35, (order, errors)
    assert np.all(np.array(errors[:-1]) / np.array(errors[1:]) > 2.0**3.6), errors
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
