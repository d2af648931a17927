"""Nakhaeinejad & Bryant (2011) sec. 5.2-5.3 with the multibody model: the impact
against the fault's size and the ball fault's signature, at the paper's set-up (ER-16K,
110 N, 35 Hz, the levels I-III of its Table 2). docs/seed000.md argues each finding;
these tests pin what it reports, so a change that breaks one fails here.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy import signal

import ballpass as bp

#: the paper's Table 1 bearing (groove radius 4.1 mm on both races, E = 210 GPa,
#: nu = 0.25) and operating point, as in benchmarks/seed000.py; 100 kHz to resolve the
#: 8-30 kHz band
ER16K = replace(bp.Bearing.catalog("ER-16K"), inner_conformity=4.1 / 7.94,
                outer_conformity=4.1 / 7.94, youngs_modulus_pa=2.1e11, poisson_ratio=0.25)
SCENE = dict(bearing=ER16K, rpm=2100.0, radial_load_n=110.0, fs=100_000.0,
             resonance_hz=15_000.0)
LEVELS = {"I": (1.0, 0.5), "II": (1.42, 0.71), "III": (2.82, 1.41)}


def _run(kind, level, duration_s):
    w, h = LEVELS[level]
    fault = bp.Fault(kind, width_mm=w, depth_mm=h, element=8 if kind == "ball" else 0,
                     angle_deg=330.0 if kind == "inner" else 0.0)
    scene = bp.Scene(**{**SCENE, "duration_s": duration_s, "fault": fault})
    return scene, bp.simulate(scene, model="multibody", return_forces=True)


def _load_zone_passages(scene, res, ball=None):
    """(contact, leading-to-trailing-edge time s, 8-30 kHz peak from 0.1 ms before the
    entry to 0.5 ms after the exit) for every passage with the ball within 60 deg of
    the load line at entry; ``ball``: the faulty ball of a ball fault."""
    sos = signal.butter(4, (8000.0, 30000.0), "bandpass", fs=scene.fs, output="sos")
    env = np.abs(signal.sosfiltfilt(sos, res.accel))
    c = res.truth.fault_crossings
    t_exit, e_exit = c.time_s[c.edge == "exit"], c.element[c.edge == "exit"]
    rows = []
    for t, e in zip(c.time_s[c.edge == "entry"], c.element[c.edge == "entry"], strict=True):
        later = t_exit[(t_exit > t) & (e_exit == e)]
        i = int(t * scene.fs)
        if t < 2e-3 or not later.size or int((later[0] + 5e-4) * scene.fs) > env.size:
            continue
        if math.cos(res.truth.element_angles[e if ball is None else ball, i]) < 0.5:
            continue
        rows.append((e, later[0] - t,
                     env[i - int(1e-4 * scene.fs):int((later[0] + 5e-4) * scene.fs)].max()))
    return np.array(rows)


def _median_peaks(kind, duration_s, contact=None):
    out = {}
    for level in LEVELS:
        scene, res = _run(kind, level, duration_s)
        rows = _load_zone_passages(scene, res, ball=8 if kind == "ball" else None)
        if contact is not None:
            rows = rows[rows[:, 0] == contact]
        assert len(rows) >= 3
        out[level] = float(np.median(rows[:, 2]))
    return out


@pytest.mark.parametrize(("kind", "duration_s", "contact"),
                         [("outer", 0.05, None), ("ball", 0.1, 0)])
def test_impact_rises_with_severity_where_the_ball_falls_into_the_notch(kind, duration_s,
                                                                       contact):
    # Paper sec. 5.3: "more severe faults ... generate impact with higher amplitudes".
    # At an outer-race notch (and a ball's own notch meeting the outer race, contact 0)
    # the centrifugal force pulls the ball into the notch, a t^2 / 2 deeper the longer
    # the notch: the trailing corner's closing speed rises 2.8x from level I to III in
    # closed form, and the reduced model of docs/seed000.md gives a peak 2.1x higher
    # (the multibody 2.1x outer, 2.6x ball). Median over the load-zone passages; III/I
    # must exceed 1.5, below the measured 2.1-2.6 by more than the 15 % a single
    # passage moves with the step. Catches a notch profile that saturates below the
    # ball's drop, the levels then alike (planted once as a 5 um cap: this test failed).
    peaks = _median_peaks(kind, duration_s, contact)
    assert peaks["I"] < peaks["II"] < peaks["III"]
    assert peaks["III"] > 1.5 * peaks["I"]


@pytest.mark.parametrize(("kind", "duration_s", "contact"),
                         [("inner", 0.06, None), ("ball", 0.1, 1)])
def test_inner_race_impact_does_not_rise_with_severity(kind, duration_s, contact):
    # The disagreement with the paper that docs/seed000.md proves: at an inner-race
    # notch (and a ball's notch meeting the inner race) the ball is held outwards by
    # its centrifugal force and weight and never falls in; the trailing corner meets
    # it at u sqrt(2 g / R) whatever the size (closed form), and the decaying swing of
    # the inner race makes a longer notch's impact weaker. Measured III/I: 0.64 (0.69
    # at half and a quarter of the step), 0.68 for the ball; the reduced model 0.57.
    # Bound 0.9: below the closed form's 1 by more than the step sensitivity. Catches a
    # ball that falls into a notch it should not see (the inner notch's drop leaking
    # into the ball's outer contact: planted once, this test failed).
    peaks = _median_peaks(kind, duration_s, contact)
    assert peaks["III"] < 0.9 * peaks["I"]


def test_ball_fault_edges_meet_a_race_at_the_rolling_speed_and_strikes_alternate_at_f_bf():
    # Paper sec. 5.3 / Fig. 14 read as docs/seed000.md argues: the defect's leading and
    # trailing edges cross a contact at the rolling speed u = (omega_i - Omega) R_i =
    # Omega R_o (rolling without slip), w / u apart like an inner-race notch's, while
    # successive strikes on the two races are half a ball turn apart, 1 / f_BF (eq.
    # 28), whatever the size. Tolerances: 1 % on w / u (a crossing is timed to the
    # step, 2.5 us of 480-1360 us) and 0.2 % on the mean 1 / f_BF over 0.1 s, 1.4 cage
    # turns (the cage slips 0.02 %; outside the load zone the ball skids between its
    # pocket contacts, single intervals +-1.7 %, and catches up). Catches a defect arc
    # measured on the wrong radius (planted once as 1.1 R: this test failed).
    ri, ro = ER16K.inner_race_radius_m, ER16K.outer_race_radius_m
    wi = 2100.0 * math.pi / 30.0
    u = (wi - wi * ri / (ri + ro)) * ri
    t_bf = 1.0 / ER16K.frequencies(35.0).ball_defect
    for level in ("I", "III"):
        scene, res = _run("ball", level, 0.1)
        rows = _load_zone_passages(scene, res, ball=8)
        assert set(rows[:, 0]) == {0.0, 1.0}
        np.testing.assert_allclose(rows[:, 1], LEVELS[level][0] * 1e-3 / u, rtol=0.01)
        entries = res.truth.fault_crossings.entries()
        np.testing.assert_allclose(np.mean(np.diff(entries)), t_bf, rtol=2e-3)
