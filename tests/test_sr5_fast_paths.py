"""The fast paths of sr5's default RK4 against the reference paths they replace
(issue 14, P1): the vectorised contact loads against the contact law element by
element, the skipped fault depths against computing them, the propagator-table output
against grid-to-grid propagation, the polyphase decimation against scipy's
resample_poly, and the default step with its contact-state refinement against dopri5
at rtol 1e-10."""

import numpy as np
import pytest
from scipy import signal

import ballpass as bp
from ballpass.simulate import _kernels as K
from ballpass.simulate import build, integrate
from ballpass.simulate._shared import decimate
from ballpass.simulate._sr5_driver import _split_times


def scene(kind="outer", **kw):
    base = dict(bearing="6205", rpm=1797.0, duration_s=0.05, fs=48_000.0,
                fault=None if kind is None else bp.Fault(kind))
    base.update(kw)
    return bp.Scene(**base)


def rel_l2(a, b):
    return np.linalg.norm(a - b) / np.linalg.norm(b)


def test_vectorised_contact_loads_are_the_contact_law_bit_for_bit():
    # core_forces computes the loads branch-free without contact damping; they must be
    # the loads of contact_load (the reference law) exactly, and exactly zero for every
    # separated contact, on states that load some contacts and separate others
    bm = build(scene())
    rng = np.random.default_rng(1)
    kin = K.kinematics_scratch(bm.scene.bearing.n_elements)
    dydt = np.empty(8)
    z = bm.scene.bearing.n_elements
    n_loaded = n_free = 0
    for t in rng.uniform(0.0, 0.05, 200):
        y = np.concatenate((bm.y0[:4], bm.y0[5:9]))
        y[:4] += rng.normal(0.0, 2e-6, 4)  # a few microns around the static state
        y[4:] += rng.normal(0.0, 1e-3, 4)
        K.kinematics(t, bm.p, bm.walk, bm.faults, kin)
        K.core_forces(y, bm.p, kin, dydt)
        loads = kin[K.K_Q, :z].copy()
        law = [K.contact_load(j, y[0] - y[2], y[1] - y[3], y[4] - y[6], y[5] - y[7],
                              bm.p, kin) for j in range(z)]
        np.testing.assert_array_equal(loads, law)
        d = ((y[0] - y[2]) * kin[K.K_COS, :z] + (y[1] - y[3]) * kin[K.K_SIN, :z]
             - bm.p[K.P_CLEAR] - kin[K.K_DEPTH, :z])
        assert np.all(loads[d <= 0.0] == 0.0) and np.all(loads[d > 0.0] > 0.0)
        n_loaded += int(np.sum(d > 0.0))
        n_free += int(np.sum(d <= 0.0))
    assert n_loaded > 100 and n_free > 100  # both branches exercised


@pytest.mark.parametrize("kind,width", [("outer", 0.5), ("inner", 2.0), ("ball", 0.5)])
def test_depth_flag_is_exact_and_constant_between_events(kind, width):
    # rk4 skips the fault depths between two split times when the flag, read at their
    # middle, says no path is inside a defect: exact only if (a) every depth and rate
    # is then exactly zero and (b) the flag cannot change strictly between the split
    # brackets (at the brackets themselves a path may sit exactly on an edge)
    sc = scene(kind, duration_s=0.1, fault=bp.Fault(kind, width_mm=width, depth_mm=0.1))
    bm = build(sc)
    before, after = _split_times(bm, 0.1)
    kin = K.kinematics_scratch(sc.bearing.n_elements)
    z = sc.bearing.n_elements
    rng = np.random.default_rng(2)
    starts = np.concatenate(([0.0], after))
    ends = np.concatenate((before, [0.1]))
    n_inside = n_outside = 0
    for a, b in zip(starts, ends, strict=True):
        if b <= a:
            continue
        flags = []
        for t in np.concatenate(([0.5 * (a + b)], a + (b - a) * rng.uniform(1e-6, 1.0, 6))):
            rate = K.element_angles(t, bm.p, bm.walk, kin)
            K.fault_depths(t, bm.p, bm.faults, kin, rate, True)
            flag = kin[K.K_CACHE, K.KC_INSIDE]
            flags.append(flag)
            if flag == 0.0:
                assert np.all(kin[K.K_DEPTH, :z] == 0.0)
                assert np.all(kin[K.K_DDEPTH, :z] == 0.0)
        assert len(set(flags)) == 1, (a, b, flags)
        n_inside += flags[0] == 1.0
        n_outside += flags[0] == 0.0
    assert n_inside >= 4 and n_outside >= 4  # the run passes the defect repeatedly


def test_propagator_table_output_equals_grid_to_grid_propagation():
    # Keeping the states sends every step through the general output routine, which
    # propagates the resonator from grid point to grid point; the default run uses the
    # table of 1..n-interval propagators. Same core steps, same exact solution of the
    # same input cubic: they differ by rounding only (a few ulps per grid point on a
    # damped resonator), so 1e-10 is generous; a wrong table row errs by O(1).
    bm = build(scene("outer", duration_s=0.05))
    n_out = bm.scene.n_samples * 4
    fast = integrate(bm, "rk4", h_out=1 / 192_000, n_out=n_out)
    ref = integrate(bm, "rk4", h_out=1 / 192_000, n_out=n_out, keep_states=True)
    assert fast.info["n_steps"] == ref.info["n_steps"]
    assert rel_l2(fast.output, ref.output) < 1e-10


@pytest.mark.parametrize("kind,rpm,width,duration,dt", [
    # the speed benchmark's scene (benchmarks/sr5_speed.py), default step
    ("inner", 1797.0, 0.5, 0.1, None),
    # slow, wide and deep: contacts open and close slowly inside steps of six grid
    # intervals (the default step of the 6205 at 500 N and 48 kHz)
    ("outer", 300.0, 2.0, 0.25, 6 / 192_000),
])
def test_rk4_within_1e3_of_dopri5(kind, rpm, width, duration, dt):
    # The default step (omega dt = 0.3, rounded down to the grid) is chosen for a
    # relative L2 error below 1e-3 against dopri5 at rtol 1e-10 (error ~1e-9): measured
    # 6.4e-4 on the first scene, 6.0e-4 on the second (benchmarks/sr5_speed.py,
    # docs/work_precision.md). The second needs the contact-state refinement: without
    # it, 1.4e-3.
    sc = scene(kind, rpm=rpm, duration_s=duration,
               fault=bp.Fault(kind, width_mm=width, depth_mm=0.1))
    res = bp.simulate(sc, dt=dt)
    ref = bp.simulate(sc, solver="dopri5", rtol=1e-10)
    assert rel_l2(res.accel, ref.accel) < 1e-3


@pytest.mark.parametrize("n,n_sensors", [(19_200, 1), (1003, 2), (5, 1)])
def test_decimation_is_resample_poly_with_line_padding(n, n_sensors):
    # The same 81-tap filter and straight-line end extension as scipy, summed tap by
    # tap: equal up to rounding of 81-term sums (|h| <= 0.25, so ~1e-14 of the largest
    # sample; 1e-12 is safe). A signal with a large offset and a trend, where the end
    # extension decides the first and last outputs (zero or constant padding errs by
    # O(1) there); lengths a multiple of 4 and not, and shorter than the filter.
    rng = np.random.default_rng(3)
    t = np.arange(n)[:, None]
    x = 5.0 + 0.01 * t + rng.standard_normal((n, n_sensors)).cumsum(axis=0)
    ref = signal.resample_poly(x, 1, 4, axis=0, padtype="line").T
    got = decimate(x, 4)
    assert got.shape == ref.shape
    assert np.max(np.abs(got - ref)) < 1e-12 * np.max(np.abs(x))
