"""The multibody model's quasi-static start from light to heavy loads.

``static_equilibrium`` (the start of every multibody run) once bounded the inner race's
deflection by the clearance plus 0.5 % of the ball diameter, 40 um for a 6205: a 6205
at 5 kN deflects 41 um, so the least-squares solution stopped on the bound and every
heavy-load multibody scene failed. These tests cover every catalogue bearing the model
takes, from 10 N to the load at which the most loaded contact reaches ISO 76's
4200 MPa, against Stribeck's distribution of ``bearing.py`` (an independent solver: a
linearised approach per ball and nested brentq, no ball bodies).
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import ballpass as bp
from ballpass.bearing import series_stiffness
from ballpass.simulate.multibody import static_equilibrium

G = 9.80665
BALL_BEARINGS = [n for n in bp.Bearing.catalog_names()
                 if bp.Bearing.catalog(n).element == "ball"
                 and bp.Bearing.catalog(n).contact_angle_deg == 0.0]


def _largest_load(bearing, **scene) -> float:
    """The largest radial load the model takes, N, as its refusal of 1 MN states it."""
    with pytest.raises(ValueError, match="radial_load_n") as err:
        static_equilibrium(bp.Scene(bearing=bearing, radial_load_n=1e6, **scene))
    return float(re.search(r"up to (\d+) N", str(err.value)).group(1))


@pytest.mark.parametrize("name, clearance_mm", [(n, None) for n in BALL_BEARINGS]
                         + [("6205", 0.02), ("6205", -0.01)])
def test_equilibrium_matches_stribeck_from_light_to_heavy_loads(name, clearance_mm):
    # Slow (60 rpm: centrifugal force < 2e-3 N) and weightless, so that only the
    # geometry differs from Stribeck's: the multibody balls sit at their exact
    # distance from the displaced ring, Stribeck's approach is x cos(psi) - c. The
    # difference is (x sin(psi))^2 / (2 r) against the approach, below 3e-3 of Q_max at
    # the heaviest load (measured 2.6e-3 at most over the catalogue): 0.5 %. The cage
    # at 7 deg makes the distribution asymmetric (a lateral deflection too). Catches the
    # bound that stopped the solver at 41 um (a RuntimeError from 4 kN on for a 6205),
    # a stiffness or clearance error of the start, a sign error of the lateral balance.
    b = bp.Bearing.catalog(name)
    if clearance_mm is not None:
        b = b.with_clearance(clearance_mm)
    scene = dict(rpm=60.0, gravity=False)
    largest = _largest_load(b, **scene)
    k = series_stiffness(*b.contact_stiffnesses(), 1.5)
    for load in (10.0, 100.0, 1000.0, 5000.0, 0.999 * largest):
        if load > largest:
            continue
        eq = static_equilibrium(bp.Scene(bearing=b, radial_load_n=load, **scene),
                                cage_angle=math.radians(7.0))
        ref = b.load_distribution(load, cage_angle_deg=7.0, stiffness=k)
        assert np.max(np.abs(eq["q_inner"] - ref.element_loads_n)) < 5e-3 * ref.q_max_n, load
        assert abs(eq["inner"][0] - ref.deflection_m) < 5e-3 * ref.deflection_m, load


@pytest.mark.parametrize("name, load", [("6205", 5000.0), ("6208", 20_000.0),
                                        ("6203", 10.0), ("6307", 10.0)])
def test_contact_forces_balance_the_load_and_the_shaft_weight(name, load):
    # The inner contact forces, recomputed here from the returned geometry with Hertz's
    # law, must balance the radial load plus the shaft's weight (1 kg, gravity on) along
    # the load line and nothing across it, to the solver's 1e-7. At 10000 rpm the
    # centrifugal force of a light 6307's balls (46 N each) exceeds the load: the
    # start guess must leave room for it (a Stribeck guess without it starts where no
    # ball touches the inner race, and the solver stalled on the flat residual).
    # Catches a solution stopped on a bound, a wrong sign of a contact normal, loads
    # that do not follow the returned radii.
    b = bp.Bearing.catalog(name)
    scene = bp.Scene(bearing=b, rpm=10_000.0 if load < 100 else 1797.0, radial_load_n=load)
    eq = static_equilibrium(scene, cage_angle=0.1)
    k_inner, _ = b.contact_stiffnesses()
    rb, c = 0.5 * b.element_diameter_m, b.radial_clearance_m
    ri = b.inner_race_radius_m - 0.5 * c
    centre = eq["radius"][:, None] * np.stack((np.cos(eq["angles"]), np.sin(eq["angles"])), 1)
    to_ball = centre - eq["inner"]
    dist = np.hypot(*to_ball.T)
    q = k_inner * np.maximum(rb + ri - dist, 0.0) ** 1.5
    np.testing.assert_allclose(q, eq["q_inner"], rtol=1e-9, atol=1e-9 * load)
    total = (q[:, None] * to_ball / dist[:, None]).sum(axis=0)
    np.testing.assert_allclose(total, [load + 1.0 * G, 0.0], rtol=0, atol=1e-7 * load)


def test_heavy_load_scene_simulates_with_stribeck_loads():
    # The failing case of the issue: a 6205 at 1797 rpm and 5 kN. The dynamic run must
    # start and keep the loads of Stribeck's distribution: ball weights (0.02 N), cage
    # drag and centrifugal force (0.2 N) are < 1e-4 of them and the exact geometry
    # differs by ~0.2 % (above); measured 0.4 %, so 1 %.
    scene = bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=5000.0, duration_s=0.01,
                     fs=20_000.0, resonance_hz=3000.0)
    res = bp.simulate(scene, model="multibody", return_forces=True)
    q = res.truth.contact_forces[:, -1]
    angles = res.truth.element_angles[:, -1]
    ref = scene.bearing.load_distribution(5000.0 + 1.0 * G,
                                          cage_angle_deg=math.degrees(angles[0]))
    loaded = ref.element_loads_n > 0.05 * ref.q_max_n
    assert np.all(np.abs(q[loaded] / ref.element_loads_n[loaded] - 1.0) < 0.01)
    assert np.all(np.abs(q - ref.element_loads_n) < 0.01 * ref.q_max_n)


def test_loads_beyond_the_elastic_contacts_are_refused_with_the_limit():
    # ISO 76's 4200 MPa on the inner contact of a 6205 (conformity 0.515): Q_max = 5.2
    # kN, F_r = Q_max Z / 4.4 = 10.6 kN at zero clearance. The stated limit must be
    # taken and 1 % more refused, through simulate too, before any kernel runs. The
    # limit lies between ISO 76's C_0 = 12.3 Z D^2 = 6.98 kN (which assumes the more
    # peaked Q_max = 5 F_r / Z of a bearing with clearance and looser conformities) and
    # twice it. Catches a pressure in wrong units or with a wrong power of the load, a
    # limit that the refusal misstates.
    largest = _largest_load("6205", rpm=1797.0)
    assert 6979.0 < largest < 2 * 6979.0
    static_equilibrium(bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=largest))
    heavier = bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=1.01 * largest)
    with pytest.raises(ValueError, match=r"radial_load_n=10\d+(\.\d+)? N .*4200 MPa"):
        static_equilibrium(heavier)
    with pytest.raises(ValueError, match=f"up to {largest:.0f} N"):
        bp.simulate(heavier, model="multibody")
