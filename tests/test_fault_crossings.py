"""Fault-edge crossings (``_sr5_driver._events``): every crossing found, each bracketed by
adjacent floating-point times the kernels' side test switches between.

sr5 splits its steps there and the impulse model places its impacts there, so a missed
crossing drops an impact and a loose bracket shifts one; both are checked against a
brute-force dense scan of the same offsets, independent of the search.
"""

from __future__ import annotations

import numpy as np
import pytest

import ballpass as bp
from ballpass.simulate import _kernels as K
from ballpass.simulate._sr5_driver import _events
from ballpass.simulate.sr5 import build_model

SCENES = {
    "inner": bp.Scene("6205", rpm=1797.0, fault=bp.Fault("inner"), duration_s=0.2, fs=48_000,
                      resonance_hz=15_000),
    "outer": bp.Scene("6205", rpm=1797.0, fault=bp.Fault("outer"), duration_s=0.2, fs=48_000,
                      resonance_hz=15_000, seed=4),
    "ball run-up": bp.Scene("6205", rpm=(600.0, 1800.0), fault=bp.Fault("ball"),
                            duration_s=0.3, fs=48_000, resonance_hz=15_000, seed=7),
}


def _offset(bm, t, fault, path):
    return K.fault_offset(t, bm.p, bm.walk, bm.faults, fault, path)


@pytest.mark.parametrize("name", list(SCENES))
def test_every_crossing_found_and_bracketed_to_adjacent_floats(name):
    scene = SCENES[name]
    bm = build_model(scene, resonator=False, equilibrium=False)
    before, after, fault, path, level = _events(bm, scene.duration_s)
    assert before.size > 10
    # adjacent floating-point numbers: nothing lies between the two sides
    np.testing.assert_array_equal(after, np.nextafter(before, np.inf))
    for t0, t1, i, j, lv in zip(before, after, fault, path, level, strict=True):
        edge = bm.levels[i, lv]
        assert (_offset(bm, t0, i, j) >= edge) != (_offset(bm, t1, i, j) >= edge)
    # the count of every (fault, path, level) against a dense scan of the offsets: a
    # step of 15 us moves an offset by < 0.003 rad (188 rad/s at most), far below the
    # defect's angular half-width (> 0.01 rad), so the scan sees every crossing once
    # (wraps of +-pi are jumps of ~2 pi, told apart)
    t = np.linspace(0.0, scene.duration_s, 20_001)
    n_paths = 2 if scene.faults[0].kind == "ball" else scene.bearing.n_elements
    for j in range(n_paths):
        o = np.array([_offset(bm, tk, 0, j) for tk in t])
        smooth = np.abs(np.diff(o)) < np.pi
        for lv in np.unique(bm.levels[0][~np.isnan(bm.levels[0])], return_index=True)[1]:
            side = o >= bm.levels[0, lv]
            expected = int(np.sum((side[1:] != side[:-1]) & smooth))
            assert np.sum((path == j) & (level == lv)) == expected, (j, lv)


@pytest.mark.parametrize("name", list(SCENES))
def test_approximate_crossings_within_the_secant_tolerance(name):
    # exact=False (the impulse model) finds the same crossings by false position: every
    # time within SECANT_TOL_S (1e-13 s) of the exact bracket, plus the bracket's own
    # width (one unit in the last place, 2e-17 s at 0.2 s). Planted: stopping after
    # one false-position step leaves crossings 3e-6 to 6e-5 s off on all three scenes (a
    # slip knot inside the scan interval kinks the offset, a speed ramp bends it).
    scene = SCENES[name]
    bm = build_model(scene, resonator=False, equilibrium=False)
    exact = _events(bm, scene.duration_s)
    approx = _events(bm, scene.duration_s, exact=False)
    for a, b in zip(exact[2:], approx[2:], strict=True):
        np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(approx[0], approx[1])
    np.testing.assert_allclose(approx[0], exact[0], rtol=0, atol=K.SECANT_TOL_S + 1e-16)
