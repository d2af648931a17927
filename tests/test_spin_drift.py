"""A ball defect whose spin axis wanders (``Fault(spin_drift_deg=...)``).

Per spin revolution the defect's latitude lambda off the rolling band is drawn with
sin(lambda) uniform on [-sin D, sin D]; the pit (radius r) then sits R sin(lambda) off
the centre line of the Hertz contact (semi-axis a across the track, R the ball radius)
and strikes with the share of the contact it covers, on min(1, (r + a) / (R sin D)) of
the revolutions. sr5 and the impulse model read the same draws.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy import integrate

import ballpass as bp
from ballpass.simulate import _kernels as K
from ballpass.simulate.impulse import _impacts
from ballpass.simulate.sr5 import _ellipse_half_width_m, _reference_load_n, build_model

#: a CWRU-like drive-end scene: 6205, 0.021 in (0.53 mm) ball defect, 1797 rpm, no slip
#: (the kinematics are then exactly periodic), a 12 kHz record ringing at 3.5 kHz
BASE = dict(bearing="6205", rpm=1797.0, fs=12_000.0, resonance_hz=3500.0, slip=0.0,
            radial_load_n=500.0, seed=7)


def ball(drift, width=0.53, **kw):
    return bp.Fault("ball", width_mm=width, depth_mm=0.28, spin_drift_deg=drift, **kw)


def hertz_strip(s, r):
    """Share of a Hertz contact's load on |x - s| < r (units of the semi-axis a), by
    quadrature of the load density 1 - x^2 across the track (Johnson 1985, sec. 4.2):
    an independent reference for the kernel's closed form."""
    lo, hi = max(s - r, -1.0), min(s + r, 1.0)
    if hi <= lo:
        return 0.0
    return integrate.quad(lambda x: 1.0 - x * x, lo, hi)[0] / (4.0 / 3.0)


def shares(scene, n_rev, face=0):
    """strike_share of the scene's ball defect on its first ``n_rev`` spin revolutions
    (the phase at each outer-race contact, 2 pi k), where it meets the outer race
    (``face`` 0) or the inner race (1), and its fault-table row."""
    faults = build_model(scene).faults
    return np.array([K.strike_share(faults, 0, 2.0 * math.pi * k, face)
                     for k in range(n_rev)]), faults[0]


@pytest.mark.parametrize("s, r", [(0.0, 0.3), (0.5, 0.3), (0.9, 0.3), (-1.2, 0.3),
                                  (1.31, 0.3), (0.2, 1.5), (0.0, 0.05)])
def test_strip_share_is_the_hertz_integral(s, r):
    # quad of a polynomial is exact to rounding: 1e-12
    assert K.strip_share(s, r) == pytest.approx(hertz_strip(s, r), abs=1e-12)


@pytest.mark.parametrize("drift, width, face", [(15.0, 0.53, 0), (40.0, 0.53, 0),
                                                (90.0, 0.53, 0), (90.0, 0.18, 0),
                                                (3.0, 0.18, 0), (40.0, 0.53, 1),
                                                (90.0, 0.18, 1)])
def test_share_of_struck_revolutions_is_the_closed_form(drift, width, face):
    n = 20_000
    got, row = shares(bp.Scene(**BASE, fault=ball(drift, width)), n, face)
    # r / a and R / a with the semi-axis a of the face's own contact ellipse: the table
    # holds them over the outer ellipse's a_o and a_o / a_i; Hertz's a grows as Q^(1/3)
    # on both races, so a_o / a_i is the same at any load (rounding: 1e-9)
    b = bp.Bearing.catalog("6205")
    q = _reference_load_n(b, 500.0)
    a_o, a_i = (_ellipse_half_width_m(b, race, q) for race in ("outer", "inner"))
    assert row[K.F_A_IN] == pytest.approx(a_o / a_i, rel=1e-9)
    scale = a_o / a_i if face else 1.0
    ratio_r, ratio_big_r = row[K.F_PIT_A] * scale, row[K.F_BALL_A] * scale
    assert ratio_r == pytest.approx(0.5 * width / (0.5 * 7.94) * ratio_big_r, rel=1e-3)
    p = min(1.0, (ratio_r + 1.0) / (ratio_big_r * math.sin(math.radians(drift))))
    # Binomial(20000, p): 5 standard errors, at most 0.018
    tol = 5.0 * math.sqrt(p * (1.0 - p) / n) + 1e-12
    assert abs(np.mean(got > 0) - p) <= tol, (np.mean(got > 0), p)
    # the mean depth factor: sin(lambda) uniform on [-sin D, sin D] through the strip
    # share, by quadrature; the factor lies in [0, 1] (sd <= 0.5): 5 standard errors
    sd = math.sin(math.radians(drift))
    mean = integrate.quad(lambda u: hertz_strip(u * ratio_big_r, ratio_r), -sd, sd,
                          points=[-(1 + ratio_r) / ratio_big_r, (1 + ratio_r) / ratio_big_r],
                          limit=200)[0] / (2 * sd) / hertz_strip(0.0, ratio_r)
    assert np.mean(got) == pytest.approx(mean, abs=5 * 0.5 / math.sqrt(n))
    assert got.min() >= 0.0 and got.max() <= 1.0


def test_a_fixed_axis_strikes_every_revolution_fully():
    got, row = shares(bp.Scene(**BASE, fault=ball(0.0)), 500)
    assert np.all(got == 1.0) and row[K.F_DRIFT] == 0.0


def struck_impacts(scene):
    """Impulse-model impacts of ``scene``: times (s), face (0 outer, 1 inner race) and
    whether each struck (a non-zero step)."""
    times, steps, (before, _fault, elem, _edges) = _impacts(scene)
    face = elem[np.searchsorted(before, times)]
    return times, face, np.abs(steps[0]) > 0


def test_strikes_hit_both_races_on_the_2xbsf_grid_and_as_often_as_the_geometry_says():
    sc = bp.Scene(**BASE, duration_s=20.0, needs=("envelope",), fault=ball(90.0))
    t, face, hit = struck_impacts(sc)
    t1, face1, hit1 = struck_impacts(sc.replace(fault=ball(0.0)))
    # same kinematics: the same exits, of which the fixed axis strikes every loaded one
    np.testing.assert_array_equal(t, t1)
    period = 1.0 / (2.0 * sc.frequencies.bsf)
    struck = t[hit]
    # the strikes that happen keep the 2xBSF spacing: every gap a whole number of
    # periods (constant speed, no slip: the spin phase is linear in time, to rounding)
    gaps = np.diff(struck) / period
    np.testing.assert_allclose(gaps, np.round(gaps), atol=1e-6)
    assert set(np.round(gaps).astype(int)) >= {1, 3}     # misses between strikes
    # both races: a revolution holds one outer contact and then one inner contact at
    # one latitude of the defect; the inner contact's ellipse is the wider on a 6205
    # (a_o / a_i < 1), so wherever the fixed axis strikes both (both in the load zone)
    # an outer strike comes with an inner one, and some inner strikes come alone
    assert not np.any(hit & ~hit1)
    row = build_model(sc).faults[0]
    assert row[K.F_A_IN] < 1.0
    pair = np.flatnonzero((face[:-1] == 0) & (face[1:] == 1))
    both = pair[hit1[pair] & hit1[pair + 1]]
    assert not np.any(hit[both] & ~hit[both + 1])
    assert np.any(~hit[both] & hit[both + 1])
    assert hit[both].sum() > 50 and (~hit[both + 1]).sum() > 50
    # share of the loaded exits that strike, per face: the closed form (r + a) / R at
    # D = 90 deg with the face's ellipse; ~700 loaded revolutions of 20 s, each one
    # Bernoulli draw per face: 5 standard errors
    for f, scale in ((0, 1.0), (1, row[K.F_A_IN])):
        p = (row[K.F_PIT_A] * scale + 1.0) / (row[K.F_BALL_A] * scale)
        n_rev = hit1[face == f].sum()
        got = hit[face == f].sum() / n_rev
        assert got == pytest.approx(p, abs=5 * math.sqrt(p * (1 - p) / n_rev)), f


def test_sr5_strikes_on_the_revolutions_the_impulse_model_strikes():
    sc = bp.Scene(**BASE, duration_s=1.0, fault=ball(90.0))
    # the same fault table (seeds, drift columns) for both models
    np.testing.assert_array_equal(build_model(sc).faults[0],
                                  build_model(sc, equilibrium=False).faults[0])
    t, _face, hit = struck_impacts(sc.replace(needs=("envelope",)))
    faulty = bp.simulate(sc, model="sr5").accel
    healthy = bp.simulate(sc.replace(fault=None), model="sr5").accel
    diff = (faulty - healthy) ** 2
    # energy of sr5's defect response in the 2 ms after each exit of the impulse model
    # (the ring at 3.5 kHz, 5 % damping, decays by e^-2.2 in that time)
    n = int(0.002 * sc.fs)
    energy = np.array([diff[int(x * sc.fs):int(x * sc.fs) + n].sum() for x in t])
    loud = energy > 0.05 * energy.max()
    # every exit the impulse model leaves silent is silent in sr5 too; most it strikes
    # are heard (a strike at the load zone's edge, with a small share, may stay quiet)
    assert not np.any(loud & ~hit)
    assert loud[hit].mean() > 0.5 and hit.sum() >= 10


def test_grid_axis_draws_the_drift_and_rows_regenerate_bit_for_bit(tmp_path):
    from ballpass.datasets import generate, load, regenerate

    grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "model": "impulse", "seed": 5,
                        "draws": 3},
            "grid": {"bearing": ["6205"], "fault": ["outer", "ball"],
                     "fault_spin_drift_deg": {"uniform": [0.0, 90.0]}, "rpm": [1797],
                     "resonance_hz": [3500]}}
    generate(grid, tmp_path / "d", progress=False)
    X, meta = load(tmp_path / "d")
    balls = meta[meta.label == "ball"]
    drifts = [json.loads(s)["fault"]["spin_drift_deg"] for s in balls.scene]
    assert len(set(drifts)) == 3 and all(0.0 <= d <= 90.0 for d in drifts)
    np.testing.assert_array_equal(balls.fault_spin_drift_deg, drifts)
    assert set(meta[meta.label == "outer"].fault_spin_drift_deg) == {0.0}
    for i, row in meta.iterrows():
        np.testing.assert_array_equal(regenerate(row), X[i])


def test_auto_runs_the_impulse_model_for_an_envelope_only_wandering_ball():
    sc = bp.Scene(**BASE, duration_s=0.5, needs=("envelope",), fault=ball(60.0))
    assert "intermittent_faults" in bp.simulate.scene_needs(sc)
    assert bp.simulate.resolve_model(sc) == "impulse"
    # and it honours the drift: fewer strikes than with a fixed axis
    assert struck_impacts(sc)[2].sum() < struck_impacts(sc.replace(fault=ball(0.0)))[2].sum()


@pytest.mark.parametrize("make, message", [
    (lambda: ball(90.5), r"spin_drift_deg.*90"),
    (lambda: ball(-1.0), r"spin_drift_deg"),
    (lambda: bp.Fault("outer", spin_drift_deg=10.0), "ball defects only"),
])
def test_bad_spin_drift_is_refused(make, message):
    with pytest.raises(ValueError, match=message):
        make()
