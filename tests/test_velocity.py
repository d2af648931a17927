"""res.velocity: the sensors' velocity, the antiderivative of the acceleration."""

import dataclasses

import numpy as np
import pytest

import ballpass as bp


@pytest.fixture(scope="module")
def impulse_result():
    scene = bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.1,
                     sensors=("loaded", "unloaded"))
    return bp.simulate(scene, model="impulse")


def test_velocity_of_a_tone(impulse_result):
    """a = A sin(2 pi f t) with whole cycles in the record -> v = -A cos(2 pi f t) /
    (2 pi f), exactly (to round-off), also at 15 kHz of a 48 kHz record where a
    trapezoidal sum is a third low; both channels independently."""
    t = impulse_result.t
    for f in (30.0, 1000.0, 15_000.0):
        tone = np.vstack([3.0 * np.sin(2 * np.pi * f * t), -np.sin(2 * np.pi * f * t)])
        v = dataclasses.replace(impulse_result, accel=tone).velocity
        expected = -np.cos(2 * np.pi * f * t) / (2 * np.pi * f) * np.array([[3.0], [-1.0]])
        # round-off of two FFTs of 4800 points: ~1e-11 of the amplitude
        np.testing.assert_allclose(v, expected, rtol=0, atol=1e-9 * 3 / (2 * np.pi * f))


def test_velocity_derivative_is_the_acceleration():
    """sr5 at 400 kHz (the 15 kHz resonance 27 samples a period): the centred
    difference of the velocity equals the acceleration to the difference's own
    error, 1 - sin(w h)/(w h) = 0.9 % at 15 kHz; 2 % of the RMS. A sign or 2 pi slip
    in the integral fails by 100 % or more."""
    scene = bp.Scene("6205", rpm=1797, fault=bp.Fault("inner"), duration_s=0.02,
                     fs=400_000.0)
    res = bp.simulate(scene, model="sr5")
    v, a = res.velocity, res.accel
    derivative = (v[2:] - v[:-2]) * res.fs / 2.0
    error = derivative - a[1:-1]
    assert np.sqrt(np.mean(error**2)) < 0.02 * np.sqrt(np.mean(a**2))
    assert abs(v.mean()) < 1e-12 * np.abs(v).max()   # AC-coupled: no DC, no drift
