"""Quasi-static balls of the multibody model (``MultibodyParameters(balls="quasistatic")``):
the massless limit of each ball's radial motion between its two damped Hertz contacts.

The force-balance tests evaluate the right-hand side at hand-made states of a 6205
with concentric rings at rest, where the balance has a closed form; the signal tests
run short scenes against the dynamic balls (Nakhaeinejad & Bryant 2011).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize

import ballpass as bp
from ballpass.features.envelope import envelope_spectrum
from ballpass.simulate.multibody import MultibodyParameters, build, integrate
from ballpass.simulate.multibody import _kernels as K

QS = MultibodyParameters(balls="quasistatic")
FS = 48_000.0


def _ring_state(system, omega, radius):
    """Rings concentric and at rest, no traction, every ball at ``radius`` (m) about
    the centre moving across it at omega * radius (m/s); returns (y, r_p index map)."""
    z = int(system.p[K.P_Z])
    nq = 6 + 3 * z
    y = np.zeros(system.n_state)
    for j in range(z):
        psi = 2.0 * math.pi * j / z
        y[6 + 3 * j:8 + 3 * j] = radius * math.cos(psi), radius * math.sin(psi)
        y[nq + 6 + 2 * j] = omega * radius
    y[5] = -1e-3  # the cage clear of every pocket's clearance edge
    return y, nq


def _closed_form_radius(p, omega):
    """Radius where K_o delta_o^1.5 - K_i delta_i^1.5 = m Omega^2 r (concentric rings,
    no gravity): the quasi-static ball's balance, solved independently."""
    rb, ri, ro, ki, ko, mb = (p[K.P_RB], p[K.P_RI], p[K.P_RO], p[K.P_KI], p[K.P_KO],
                              p[K.P_MB])

    def balance(r):
        d_i, d_o = max(rb + ri - r, 0.0), max(r + rb - ro, 0.0)
        return ko * d_o ** 1.5 - ki * d_i ** 1.5 - mb * omega ** 2 * r

    # a preload: the rings 20 um closer than the ball (both contacts pressed)
    return optimize.brentq(balance, ro - rb - 1e-5, ri + rb + 1e-5, xtol=1e-18, rtol=1e-15)


@pytest.fixture(scope="module")
def preloaded():
    """A 6205 whose races squeeze the balls by 20 um (negative clearance), no gravity."""
    bearing = bp.Bearing.catalog("6205").with_clearance(-0.02)
    scene = bp.Scene(bearing=bearing, rpm=1797.0, radial_load_n=500.0, gravity=False,
                     duration_s=0.01, fs=FS)
    return build(scene, QS)


def test_ball_rests_where_the_contact_loads_differ_by_the_centrifugal_load(preloaded):
    # Closed form: at the radius where Q_o - Q_i = m Omega^2 r the ball does not move
    # (r' = 0) and both loads are the Hertz loads there. A ball 1 nm further out
    # relaxes inwards with Kramer's time: r' = -1e-9 (k_i + k_o) / (tau (k_i + k_o) +
    # floor) (the linearised balance; the floor, 1e-2 m_b / tau, is 2e-4 of the
    # contacts' tau k). 1e-9 m on approaches of ~10 um: the loads to 1e-9, the rate to
    # 1e-3 (the curvature of delta^1.5 over 1 nm is 1e-4 of the slope).
    # Catches: the centrifugal load dropped or doubled (r' = -/+ m Omega^2 r / (tau k),
    # ~1e-4 m/s, not 0), a contact stiffness of the wrong race, a sign of the damping.
    system = preloaded
    p = system.p
    omega = 75.0  # rad/s, about the 6205's cage speed at 1797 rpm
    r_eq = _closed_form_radius(p, omega)
    y, nq = _ring_state(system, omega, r_eq)
    qi, qo = system.contact_loads(0.0, y)
    rdot = system.rhs(0.0, y)[6]  # x' of ball 0 (on the x axis: r')
    d_i = p[K.P_RB] + p[K.P_RI] - r_eq
    d_o = r_eq + p[K.P_RB] - p[K.P_RO]
    np.testing.assert_allclose(qi, p[K.P_KI] * d_i ** 1.5, rtol=1e-9)
    np.testing.assert_allclose(qo, p[K.P_KO] * d_o ** 1.5, rtol=1e-9)
    np.testing.assert_allclose(qo - qi, p[K.P_MB] * omega ** 2 * r_eq, rtol=1e-6)
    k = 1.5 * p[K.P_KI] * d_i ** 0.5 + 1.5 * p[K.P_KO] * d_o ** 0.5
    tau = p[K.P_TAU]
    floor = K.QS_DRAG_FLOOR * p[K.P_MB] / tau
    assert abs(rdot) < 1e-3 * 1e-9 * k / (tau * k + floor)
    y, _ = _ring_state(system, omega, r_eq + 1e-9)
    rdot = system.rhs(0.0, y)[6]
    np.testing.assert_allclose(rdot, -1e-9 * k / (tau * k + floor), rtol=1e-3)


def test_separated_contacts_carry_exactly_nothing(preloaded):
    # A ball 30 um outside the inner race's reach touches only the outer race: its inner
    # load is exactly 0.0 (not a tiny or negative number: damping must not pull); with
    # no orbit, no gravity and the ball in the middle of a gap (radius between both
    # reaches) nothing loads it and it stays put. Catches delta^1.5 of a negative
    # approach, an unclipped damping term, a floor that moves a free ball.
    system = preloaded
    p = system.p
    y, _ = _ring_state(system, 75.0, p[K.P_RI] + p[K.P_RB] + 3e-5)
    qi, qo = system.contact_loads(0.0, y)
    assert np.all(qi == 0.0) and np.all(qo > 0.0)
    wide = build(bp.Scene(bearing=bp.Bearing.catalog("6205").with_clearance(0.05),
                          rpm=1797.0, radial_load_n=500.0, gravity=False, duration_s=0.01,
                          fs=FS), QS)
    gap_mid = 0.5 * (wide.p[K.P_RI] + wide.p[K.P_RO])
    y, _ = _ring_state(wide, 0.0, gap_mid)
    qi, qo = wide.contact_loads(0.0, y)
    assert np.all(qi == 0.0) and np.all(qo == 0.0)
    assert wide.rhs(0.0, y)[6] == 0.0


def _scene(duration_s, **kw):
    return bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, duration_s=duration_s,
                    fs=FS, **kw)


def test_agrees_with_dynamic_balls_on_a_healthy_bearing():
    # Healthy 6205, 20 ms, both at 24 steps per 5.2 us interval (the models, not the
    # steps, compared). The massless limit moves the ball's slow radial root (1 / tau
    # against 1.17 / tau with the 2 g ball) and drops its fast one (6e5 1/s), both far
    # above what the rings excite: the inner loads differ by 2e-6 (L2, first 2 ms), the
    # housing signal's RMS by 5e-4, the cage speed by 4e-7 (benchmarks/multibody_speed.py,
    # 0.1 s). Bounds 10-20x above: 5e-5, 1e-2, 1e-5. Catches a centrifugal load of the
    # wrong size (the loads move by m Omega^2 r / Q ~ 1e-3), a contact force missing its
    # reaction on a ring, a wrong tangential equation (the cage speed moves).
    h = 1.0 / (4 * FS)
    n = int(round(0.02 / h))
    raws = {}
    for balls in ("dynamic", "quasistatic"):
        system = build(_scene(0.02), MultibodyParameters(balls=balls))
        raws[balls] = integrate(system, h_out=h, n_out=n, stride=4, dt=h / 24)
    a, b = raws["quasistatic"], raws["dynamic"]
    short = slice(0, int(round(0.002 / h)) // 4)
    err = np.linalg.norm(a["q_inner"][short] - b["q_inner"][short])
    assert err / np.linalg.norm(b["q_inner"][short]) < 5e-5
    keep = slice(n // 5, None)
    assert abs(np.std(a["exc"][keep]) / np.std(b["exc"][keep]) - 1.0) < 1e-2
    cage = [np.unwrap(r["cage"]) for r in (a, b)]
    assert abs((cage[0][-1] - cage[0][0]) / (cage[1][-1] - cage[1][0]) - 1.0) < 1e-5


def test_inner_race_defect_frequency_shows_in_the_signal():
    # 6205 inner-race notch against the healthy 6205, 0.25 s each at the default step:
    # the squared envelope spectrum (5-20 kHz, around the 15 kHz resonance) of the
    # faulted bearing peaks at BPFI or its second harmonic (162.2 Hz; bins of 4.4 Hz,
    # the peak within one), and its BPFI line stands far above the healthy bearing's
    # spectrum there (a factor 10; measured 270; noise-free signals). Catches a fault
    # that does not unload its ball, notch crossings lost by the quasi-static contact
    # geometry.
    lines = []
    for fault in (bp.Fault("inner", width_mm=0.5, depth_mm=0.1), None):
        scene = _scene(0.25, fault=fault) if fault else _scene(0.25)
        res = bp.simulate(scene, model="multibody", params=QS)
        f, a = envelope_spectrum(res.accel[scene.n_samples // 10:], FS, band=(5000.0, 20000.0))
        bpfi = scene.frequencies.bpfi
        df = f[1] - f[0]
        lines.append(a[np.abs(f - bpfi) <= df].max())
        if fault:
            search = (f > 50.0) & (f < 400.0)
            peak = f[search][np.argmax(a[search])]
            assert min(abs(peak - bpfi), abs(peak - 2.0 * bpfi)) <= df
    assert lines[0] > 10.0 * lines[1], lines[0] / lines[1]


def test_bad_options_are_refused():
    with pytest.raises(ValueError, match="balls must be one of"):
        MultibodyParameters(balls="massless")
    ball = _scene(0.01, fault=bp.Fault("ball", width_mm=0.5, depth_mm=0.1))
    with pytest.raises(ValueError, match="ball faults"):
        build(ball, QS)
    system = build(_scene(0.01), QS)
    with pytest.raises(ValueError, match="solver must be 'rk4'"):
        integrate(system, h_out=1.0 / (4 * FS), n_out=4, stride=4, solver="rosw")
