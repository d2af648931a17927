"""The instruments of benchmarks/_multibody_routes.py (the routes to a cheaper multibody
model): a recompiled copy of the kernels is the model until a change is made in it, and
the Python RK4 that records every stage's loads follows the kernel's trajectory."""

from __future__ import annotations

import dataclasses

import numpy as np
from _bench import load_benchmark

import ballpass as bp
from ballpass.simulate.multibody import _kernels as K
from ballpass.simulate.multibody import build, integrate

routes = load_benchmark("_multibody_routes")

H = 1.0 / 192_000


def _scene():
    return bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fs=48_000.0,
                    duration_s=0.01, fault=bp.Fault("inner", width_mm=0.5, depth_mm=0.1))


def test_unchanged_copy_of_the_kernels_is_the_model_and_a_change_shows():
    # The cost ceilings time copies of the kernels compiled from their source with one
    # change each, against the unchanged kernels: the copy without a change must give
    # the model's output bit for bit (same source, same compiler: same arithmetic), so
    # that a timing difference is the change's. And a change must reach the kernels
    # integrate runs (the traction law's exponential replaced by a division moves the
    # state), else every ratio would be 1 whatever was changed (planted: a copy that
    # drops its replacements fails here).
    system = build(_scene())
    n = 100
    plain = integrate(system, h_out=H, n_out=n, stride=4)
    with routes.kernels(routes.variant_kernels([])):
        copy = integrate(system, h_out=H, n_out=n, stride=4)
    assert np.array_equal(plain["y_end"], copy["y_end"])
    assert np.array_equal(plain["exc"], copy["exc"])
    name = "traction law: its exponential replaced by a division"
    with routes.kernels(routes.variant_kernels(routes.VARIANTS[name])):
        changed = integrate(system, h_out=H, n_out=n, stride=4)
    assert not np.array_equal(plain["y_end"], changed["y_end"])
    assert routes.mb.K is K  # the kernels are given back


def test_python_rk4_follows_the_kernel():
    # The study of two steps per interval reads every stage's loads from a Python RK4
    # on the model's right-hand side; it must be the kernel's RK4. Its arithmetic is
    # the kernel's (stage states y + (c h) k, update y + h/6 (k1 + 2 k2 + 2 k3 + k4),
    # in that order): measured, the loads it records at the grid points equal the
    # kernel's bit for bit over these 64 intervals. The bound, 1e-11 of the largest
    # load, leaves room only for a last-place rounding of a stage time (the kernel
    # rebuilds t from the grid index) grown over 0.3 ms. Catches a wrong stage weight
    # or stage state (planted: 3 k3 for 2 k3 in the update is off by 0.14).
    system = build(_scene())
    p0 = system.p.copy()
    p0[K.P_TAU] = 0.0
    elastic = dataclasses.replace(system, p=p0)
    n_grid, n_sub = 64, 2
    rec = routes._rk4_loads(system, elastic, H, n_sub, n_grid, 8)
    kern = integrate(system, h_out=H, n_out=n_grid, stride=4, dt=H / n_sub)
    z = system.scene.bearing.n_elements
    want = kern["q_inner"]
    got = rec["start"][::4 * n_sub, :z][:want.shape[0]]
    assert got.shape == want.shape == (n_grid // 4, z)
    assert np.max(np.abs(got - want)) < 1e-11 * np.max(want)
    # the elastic share at the first grid point: the settled state's loads without
    # Kramer's damping (exact: the same evaluation)
    assert rec["el_start"].shape[1] == z
    y = integrate(system, h_out=H, n_out=0, stride=1, dt=H / n_sub)["y_end"]
    np.testing.assert_array_equal(rec["el_start"][0], elastic.contact_loads(0.0, y)[0])
