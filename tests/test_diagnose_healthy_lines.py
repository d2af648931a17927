"""A healthy bearing's own line at BPFO against a localized fault's, and the ball
fault's cage-rate modulation, on closed-form signals and on the sr5 simulator.

A loaded healthy bearing vibrates at BPFO: the stiffness of the ball set varies as the
balls pass the load line (varying compliance, Sawalhi & Randall 2008). That vibration
is a *direct* line at BPFO and its first harmonics, low in the spectrum, with no
high-frequency carrier. A localized fault's impacts ring the structure's resonances:
its lines appear in the squared envelope of a *high* band. The diagnoser demodulates
only bands that start above the highest fault line it reads, so a low-frequency line
cannot enter its evidence however strong it is.

A ball defect strikes both races once per ball spin (2 x BSF) and is carried through
the load zone at the cage speed: its squared envelope spectrum holds 2 x BSF with
sidebands at +-FTF.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.fft

import ballpass as bp
from ballpass.diagnose import EnvelopeDiagnoser

BEARING = bp.Bearing.catalog("6205")


def line_db(x, fs, freq_hz, *, half_width_hz=10.0):
    """Level of the strongest Hann-windowed bin within +-2 bins of ``freq_hz`` above the
    median of the bins within +-``half_width_hz``, dB."""
    power = np.abs(scipy.fft.rfft((x - x.mean()) * np.hanning(x.size))) ** 2
    f = scipy.fft.rfftfreq(x.size, 1.0 / fs)
    i = int(np.argmin(np.abs(f - freq_hz)))
    near = np.abs(f - freq_hz) <= half_width_hz
    return 10 * np.log10(power[i - 2 : i + 3].max() / np.median(power[near]))


@pytest.mark.parametrize(("fs", "rpm", "seconds"), [
    (12_000.0, 1797.0, 1.0), (12_000.0, 1797.0, 10.0), (48_000.0, 900.0, 2.0),
    (51_200.0, 1200.0, 5.0),
])
def test_a_strong_low_frequency_bpfo_line_in_noise_is_healthy(fs, rpm, seconds):
    """A pure line at BPFO and a weaker one at 2 x BPFO (a healthy loaded bearing's
    varying compliance, here 20 and 10 times the noise's standard deviation: 30-60 dB
    above the noise floor in the raw spectrum) in white noise: every family stays
    below its threshold, so the noise statistics (false-alarm probability about 7e-5
    per record at 6 dB, ``noise_probability``) hold.

    Planted: demodulation bands allowed to start below the highest fault line
    (``lo < lowest_hz`` dropped from ``candidate_bands``): the line's square writes
    2 x BPFO into the squared envelope and the record is called outer; the test fails.
    """
    bpfo = BEARING.frequencies(rpm / 60).bpfo
    t = np.arange(round(seconds * fs)) / fs
    rng = np.random.default_rng(int(fs + rpm + seconds))
    x = (20 * np.sin(2 * np.pi * bpfo * t + 0.3) + 10 * np.sin(4 * np.pi * bpfo * t)
         + rng.standard_normal(t.size))
    assert line_db(x, fs, bpfo) > 30.0  # the line is there, far above the noise
    (why,) = EnvelopeDiagnoser(fs=fs, rpm=rpm).explain(x[None])
    assert why.label == "healthy", why
    # 6 dB threshold, 3 dB grade margin: no family comes within reach of a verdict
    assert max(why.evidence_db.values()) < why.threshold_db["outer"], why


@pytest.mark.parametrize(("fs", "rpm", "seconds", "snr_db"), [
    (12_000.0, 1797.0, 2.0, 20.0), (48_000.0, 900.0, 1.0, 20.0), (51_200.0, 1200.0, 2.0, 10.0),
])
def test_a_simulated_healthy_bearing_under_load_carries_bpfo_and_is_healthy(
        fs, rpm, seconds, snr_db):
    """sr5, healthy 6205 under 500 N with measurement noise: the varying-compliance line
    at BPFO stands out of the raw spectrum (about 35 dB measured; 20 dB asserted, far
    above the 5 dB a noise bin reaches with probability e^-(10^0.5) = 4 %), and the
    diagnoser calls the bearing healthy (the line has no high-frequency carrier).

    Planted: bands starting at 0 Hz (as above): every one of these records is called
    faulty.
    """
    scene = bp.Scene(bearing="6205", rpm=rpm, radial_load_n=500.0, duration_s=seconds,
                     fs=fs, snr_db=snr_db, seed=1, resonance_hz=3000.0)
    x = np.atleast_2d(bp.simulate(scene).accel)[0]
    assert line_db(x, fs, BEARING.frequencies(rpm / 60).bpfo) > 20.0
    (why,) = EnvelopeDiagnoser(fs=fs, rpm=rpm).explain(x[None])
    assert why.label == "healthy", why


@pytest.mark.parametrize(("rpm", "seed"), [(1797.0, 0), (1200.0, 1)])
def test_a_simulated_ball_fault_is_modulated_at_the_cage_speed(rpm, seed):
    """sr5, 6205 with a 0.53 mm ball defect, 12 kHz, 2 s, SNR 10 dB: the squared
    envelope spectrum carries 2 x BSF with +-FTF sidebands (the defect passes through the
    load zone once per cage revolution), and the diagnoser names the ball.

    The sidebands are read where they are told from the shaft harmonics: 1 x 2 x BSF
    +- FTF (4.315 and 5.112 orders), more than 3 SES bins (1.5 Hz at 2 s) from any
    shaft harmonic at both speeds. Threshold 6 dB: the SES background's local median
    is exceeded by 6 dB with probability e^-4 = 2 % per bin for noise alone.

    Planted: the ball family's +-FTF sidebands counted against it, as the outer race's
    are (``FAULT_FAMILIES["ball"]`` with sign -1): the ball is no longer named.
    """
    scene = bp.Scene(bearing="6205", rpm=rpm, radial_load_n=500.0,
                     fault=bp.Fault("ball", width_mm=0.53, depth_mm=0.28),
                     duration_s=2.0, fs=12_000.0, snr_db=10.0, seed=seed,
                     resonance_hz=3000.0)
    x = np.atleast_2d(bp.simulate(scene).accel)[0]
    (why,) = EnvelopeDiagnoser(fs=12_000.0, rpm=rpm).explain(x[None])
    # Named, and told from the races by at least 3 dB (the grade's margin); the grade
    # itself is "P" at 1797 rpm: 2x2xBSF+FTF sits on 2xBPFI-fr and is left out, and the
    # ball clears its threshold by 2.9 dB.
    assert why.label == "ball" and why.grade in ("Y", "P"), why
    ev = why.evidence_db
    assert ev["ball"] > max(ev["outer"], ev["inner"]) + 3.0, ev
    ball = why.lines[why.lines.fault == "ball"].set_index("line")
    for line in ("1x2xBSF", "1x2xBSF-FTF", "1x2xBSF+FTF"):
        assert ball.loc[line, "level_db"] > 6.0, ball
