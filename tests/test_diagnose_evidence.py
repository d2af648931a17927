"""Family evidence traps (shared harmonics, shaft harmonics, ball comb, slip, speed) and
the diagnoser's refusals of bad input.

The signals are synthetic impact trains with a known answer: impacts at a defect rate,
each ringing a 3 kHz resonance (the CWRU drive-end rig rings at 2.5-4 kHz), optionally
amplitude-modulated (load zone), in white noise.
"""

from __future__ import annotations

import numpy as np
import pytest

import ballpass as bp
from ballpass.diagnose import EnvelopeDiagnoser, envelope_evidence

FS = 12_000.0
RPM = 1797.0
#: Fault orders of the 6205 computed here from its geometry (9 balls, d = 7.94 mm,
#: D = 39.04 mm, contact angle 0), independently of the package: BPFO = Z/2 (1 - d/D)...
_R = 7.94 / 39.04
ORDERS_6205 = {"bpfo": 4.5 * (1 - _R), "bpfi": 4.5 * (1 + _R), "ftf": 0.5 * (1 - _R),
               "ball_defect": 39.04 / 7.94 * (1 - _R**2)}


def impacts(rate_hz, seconds, *, modulation=None, noise=0.2, seed=0, ring_hz=3000.0):
    """Impacts at ``rate_hz`` ringing ``ring_hz`` (decay 800 1/s), times ``modulation(t)``."""
    t = np.arange(round(seconds * FS)) / FS
    since = (t * rate_hz) % 1.0 / rate_hz  # time since the last impact, s
    x = np.exp(-800 * since) * np.sin(2 * np.pi * ring_hz * since)
    if modulation is not None:
        x = x * modulation(t)
    return x + noise * np.random.default_rng(seed).standard_normal(t.size)


def test_orders_used_by_the_test_match_the_data_readme():
    # The CWRU README gives BPFI 5.4152, BPFO 3.5848, FTF 0.39828, 2xBSF 4.7135.
    assert ORDERS_6205["bpfi"] == pytest.approx(5.4152, abs=2e-4)
    assert ORDERS_6205["bpfo"] == pytest.approx(3.5848, abs=2e-4)
    # (the README works from the inch dimensions, the catalogue from rounded mm)
    assert ORDERS_6205["ftf"] == pytest.approx(0.39828, abs=5e-5)
    assert ORDERS_6205["ball_defect"] == pytest.approx(4.7135, abs=2e-4)


def test_slip_is_searched_below_the_kinematic_frequency():
    # Slip slows the cage: the outer-race lines sit 1.5 % below BPFO. A search that
    # only looks upwards misses them (the line window is +-1 bin = 0.1 % of 3xBPFO).
    fr = RPM / 60
    x = impacts(0.985 * ORDERS_6205["bpfo"] * fr, 2.0)
    ev = envelope_evidence(x, FS, "6205", RPM)
    assert ev.scale["outer"][0] == pytest.approx(0.985, abs=0.002)
    assert ev.evidence_db["outer"][0] > 10.0
    assert EnvelopeDiagnoser(fs=FS, rpm=RPM).predict(x[None])[0] == "outer"


def test_ball_comb_is_not_an_outer_race_fault():
    # A ball fault, carried through the load zone at the cage speed, fills the FTF comb:
    # its BPFO = 9 x FTF line stands no higher than its +-FTF neighbours. Counting
    # those neighbours *for* the outer race would make this an outer-race fault.
    fr = RPM / 60
    ftf = ORDERS_6205["ftf"] * fr
    zone = lambda t: (1 + np.cos(2 * np.pi * ftf * t)) ** 2  # noqa: E731
    x = impacts(ORDERS_6205["ball_defect"] * fr, 2.0, modulation=zone, noise=0.05)
    (exp,) = EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(x[None])
    assert exp.label == "ball"
    assert exp.evidence_db["outer"] < exp.threshold_db["outer"]


def test_outer_race_sidebands_do_not_refute_it():
    # Real outer-race records carry +-FTF sidebands 12-16 dB above the background
    # (Smith & Randall 2015); a 30 % modulation at FTF gives such sidebands.
    fr = RPM / 60
    ftf = ORDERS_6205["ftf"] * fr
    x = impacts(ORDERS_6205["bpfo"] * fr, 2.0,
                modulation=lambda t: 1 + 0.3 * np.cos(2 * np.pi * ftf * t), noise=0.1)
    (exp,) = EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(x[None])
    sidebands = exp.lines[(exp.lines.fault == "outer") & (exp.lines.role != "carrier")]
    assert sidebands["level_db"].max() > 12.0
    assert exp.label == "outer" and exp.grade == "Y"


def test_harmonics_two_families_share_are_left_out():
    # 2xBPFI = 10.830 and 3xBPFO = 10.754 orders: 0.7 % apart, inside the slip search.
    ev = envelope_evidence(np.random.default_rng(0).standard_normal(12_000), FS, "6205", RPM)
    # carriers are every third line (carrier, lower, upper sideband per harmonic)
    shared = {f: [n for n, s in zip(ev.line_names[f][::3], ev.shared[f][::3], strict=True) if s]
              for f in ev.line_names}
    assert "3xBPFO" in shared["outer"] and "2xBPFI" in shared["inner"]
    assert np.isnan(ev.levels_db["inner"][0, ev.line_names["inner"].index("2xBPFI")])
    # An outer-race fault whose 3xBPFO is its only strong line gives the inner race
    # nothing: its 2xBPFI is not counted.
    fr = RPM / 60
    x = impacts(ORDERS_6205["bpfo"] * fr, 2.0)
    ev = envelope_evidence(x, FS, "6205", RPM)
    assert ev.evidence_db["inner"][0] < 6.0 < ev.evidence_db["outer"][0]


def test_shaft_harmonics_of_a_healthy_6203_are_not_faults():
    # The 6203's 2xBSF (3.988 orders) lies 0.3 % from 4x shaft, BPFO (3.053) 1.8 % from
    # 3x and BPFI (4.947) 1.1 % from 5x; a healthy fan-end channel carries a 4x line
    # 25-29 times above background. Here: resonance noise modulated at 3x, 4x, 5x.
    fr = RPM / 60
    rng = np.random.default_rng(3)
    for seconds in (1.0, 10.0):
        t = np.arange(round(seconds * FS)) / FS
        carrier = bp.features.bandpass(rng.standard_normal(t.size), FS, (2500, 3500))
        mod = 1 + sum(0.5 * np.cos(2 * np.pi * k * fr * t) for k in (3, 4, 5))
        x = carrier * mod + 0.05 * rng.standard_normal(t.size)
        (exp,) = EnvelopeDiagnoser(bearing="6203", fs=FS, rpm=RPM).explain(x[None])
        assert exp.label == "healthy", (seconds, exp.evidence_db)


def test_lines_on_shaft_harmonics_say_how_long_a_record_tells_them_apart():
    # The 6203's 2xBSF, computed here from its geometry (d = 6.746 mm, D = 28.5 mm,
    # contact angle 0): D/d (1 - (d/D)^2) = 3.988 orders; its third harmonic 11.964 is
    # 1.08 Hz below 12x at 1797 rpm (the first, 3.988, collides with 1xBPFI-fr = 3.947
    # and is left out). A healthy channel with a 12x line: on one-second records (1 Hz
    # bins; an 8x line too, so that the second carrier cannot win the scale fit) the
    # ball's third carrier reads as that shaft line, and explain() says a
    # record of 3 bins / 1.08 Hz = 2.8 s tells them apart; on ten-second records it does.
    fr = RPM / 60
    ball = 28.5 / 6.746 * (1 - (6.746 / 28.5) ** 2) * fr
    need = 3.0 / abs(3 * ball - 12 * fr)  # the shaft guard is 3 SES bins of 1/T Hz
    rng = np.random.default_rng(5)
    for seconds in (1.0, 10.0):
        t = np.arange(round(seconds * FS)) / FS
        carrier = bp.features.bandpass(rng.standard_normal(t.size), FS, (2500, 3500))
        x = carrier * (1 + 0.5 * np.cos(2 * np.pi * 8 * fr * t)
                     + 0.5 * np.cos(2 * np.pi * 12 * fr * t))
        (exp,) = EnvelopeDiagnoser(bearing="6203", fs=FS, rpm=RPM).explain(x[None])
        lines = exp.lines.set_index(["fault", "line"])
        note = [n for n in exp.notes if n.startswith("ball:")]
        if seconds == 1.0:
            assert lines.loc[("ball", "3x2xBSF"), "on_shaft"]
            assert note and f"at least {need:.1f} s" in note[0], exp.notes
        else:
            assert not lines.loc[("ball", "3x2xBSF"), "on_shaft"]
            assert not note, exp.notes
        assert exp.label == "healthy"


def test_wrong_stated_speed_is_corrected_and_said():
    # 12k_FE_OR014@3_0 states 1774 rpm; a 1.3 % error moves 3xBPFO by 4 Hz, outside
    # the slip search above the kinematic lines. The signal's shaft comb (harmonics
    # 1-10 of 29.95 Hz) tells the speed.
    fr = RPM / 60
    t = np.arange(round(4.0 * FS)) / FS
    shaft = sum(0.3 / k * np.cos(2 * np.pi * k * fr * t + k) for k in range(1, 11))
    x = impacts(ORDERS_6205["bpfo"] * fr, 4.0, noise=0.3) + shaft
    diag = EnvelopeDiagnoser(fs=FS, rpm=1774.0)
    (exp,) = diag.explain(x[None])
    assert exp.rpm == pytest.approx(RPM, rel=0.002)
    assert exp.rpm_stated == 1774.0
    assert any("speed corrected from 1774" in note for note in exp.notes)
    assert exp.label == "outer"
    # Trusting the stated speed misses the fault.
    assert diag.set_params(speed_tolerance=0.0).predict(x[None])[0] != "outer"


def test_a_fault_comb_does_not_overrule_a_right_stated_speed():
    # A 6203's BPFO is 3.053 x fr: its raw-spectrum harmonics sit on the 3rd, 6th, 9th
    # harmonics of BPFO / 3 = 1.018 x fr, and on a 2 s record (0.5 Hz bins) the 1st and
    # 2nd of that false speed read the true shaft lines' main lobes: the comb search
    # prefers ~1817 rpm (two-second segments of the CWRU fan-end outer-race records were
    # "corrected" to 1829 rpm that way, losing an 18 dB outer-race fault). A correction
    # that loses 3 dB of fault evidence is not used; here the stated speed stays.
    bpfo = 0.995 * 3.053 * RPM / 60
    t = np.arange(round(2.0 * FS)) / FS
    low = sum(0.3 * np.cos(2 * np.pi * h * bpfo * t + h) for h in range(1, 7))
    shaft = sum(0.3 * np.cos(2 * np.pi * k * RPM / 60 * t + 2 * k) for k in (1, 2, 3))
    x = impacts(bpfo, 2.0, noise=0.3) + low + shaft
    found, _, _ = bp.diagnose.speed.estimate_shaft_speed(x[None], FS, np.array([RPM]))
    assert found[0] > 1.005 * RPM  # the trap is armed: the comb alone points elsewhere
    (exp,) = EnvelopeDiagnoser(bearing="6203", fs=FS, rpm=RPM).explain(x[None])
    assert exp.rpm == RPM
    assert exp.label == "outer"
    # The disagreement is said, not hidden.
    assert len(exp.notes) == 1
    assert exp.notes[0].startswith(f"the shaft-harmonic comb points to {found[0]:.0f} rpm; "
                                   "the stated 1797 rpm was kept")


def test_healthy_record_takes_the_comb_speed():
    # No fault to lose: the comb's speed is used whichever speed reads the (noise)
    # evidence a little higher.
    t = np.arange(round(4.0 * FS)) / FS
    x = sum(0.3 / k * np.cos(2 * np.pi * k * RPM / 60 * t + k) for k in range(1, 11))
    for seed in range(3):
        noisy = x + 0.3 * np.random.default_rng(seed).standard_normal(t.size)
        (exp,) = EnvelopeDiagnoser(fs=FS, rpm=1774.0).explain(noisy[None])
        assert exp.label == "healthy"
        assert exp.rpm == pytest.approx(RPM, rel=0.002)
        assert exp.notes[0].startswith("speed corrected from 1774")


@pytest.mark.parametrize("prewhiten", [False, True])
def test_noise_free_healthy_simulation_is_healthy(prewhiten):
    # The quick dataset's healthy rows (sr5, no noise, 0.25 s): the varying-compliance
    # line at BPFO has no high-frequency carrier, so no demodulation band holds it.
    # With pre-whitening the bands are still judged on the raw signal: a whitened
    # spectrum is flat, and judged on it every band would seem to hold signal.
    scene = bp.Scene(bearing="6205", rpm=RPM, duration_s=0.25, fs=FS, seed=0,
                     resonance_hz=3000.0)
    x = bp.simulate(scene).accel
    (exp,) = EnvelopeDiagnoser(fs=FS, rpm=RPM, prewhiten=prewhiten).explain(x[None])
    assert exp.label == "healthy"
    assert any(note.startswith("no band above the fault lines") for note in exp.notes)
    # 0.25 s is three cage periods: too short to resolve a ball fault's +-FTF sidebands.
    assert any(note.startswith("ball not judged") for note in exp.notes)
    assert exp.evidence_db["ball"] == -np.inf


# ---------------------------------------------------------------------- bad input
def test_fs_and_rpm_are_required():
    x = np.zeros((1, 12_000))
    with pytest.raises(ValueError, match="fs must be given"):
        EnvelopeDiagnoser(rpm=RPM).predict(x)
    with pytest.raises(ValueError, match="rpm must be given"):
        EnvelopeDiagnoser(fs=FS).predict(x)


def test_one_signal_must_be_a_row():
    # sklearn's own message for a 1-D X prints the whole array; ours names the shape.
    diag = EnvelopeDiagnoser(fs=FS, rpm=RPM)
    with pytest.raises(ValueError, match=r"got shape \(12000,\): pass x\[None\]") as err:
        diag.explain(np.zeros(12_000))
    assert "0. 0." not in str(err.value)
    with pytest.raises(ValueError, match=r"got shape \(1, 2, 12000\)"):
        diag.predict(np.zeros((1, 2, 12_000)))


def test_short_records_are_refused():
    # Two cage periods of a 6205 at 1797 rpm: 2 / (0.39828 x 29.95 Hz) = 0.168 s.
    with pytest.raises(ValueError, match=r"at least 2 cage periods \(0\.168 s"):
        EnvelopeDiagnoser(fs=FS, rpm=RPM).predict(np.ones((1, 2)))
    assert EnvelopeDiagnoser(fs=FS, rpm=RPM).predict(np.ones((1, 2040))).shape == (1,)


def test_fault_lines_above_nyquist_are_refused():
    # 3 x BPFI + fr at 6000 rpm = 3 x 541.5 + 100 = 1725 Hz > fs/2 = 1000 Hz.
    with pytest.raises(ValueError, match="above the Nyquist frequency fs/2 = 1000 Hz"):
        EnvelopeDiagnoser(fs=2000.0, rpm=6000.0).predict(np.ones((1, 2000)))


def test_fit_refuses_unknown_labels():
    x = np.random.default_rng(0).standard_normal((2, 12_000))
    with pytest.raises(ValueError, match=r"unknown labels \['cage'\]"):
        EnvelopeDiagnoser(fs=FS, rpm=RPM).fit(x, ["healthy", "cage"])


def test_a_sideband_on_another_familys_line_feeds_neither():
    # 2x2xBSF+FTF = 2 x 4.7135 + 0.3983 = 9.825 orders and 2xBPFI-fr = 2 x 5.4152 - 1 =
    # 9.830 orders (computed here from the geometry) lie 0.05 % apart, inside half the
    # 2 % slip search: a line there is left out of the ball and of the inner race.
    # Catches a collision rule that compares carriers only (planted: the ball kept
    # 2x2xBSF+FTF and read the inner race's line at 0 dB as its own).
    o = ORDERS_6205
    ball_side = 2 * o["ball_defect"] + o["ftf"]
    inner_side = 2 * o["bpfi"] - 1.0
    assert abs(ball_side - inner_side) < 0.5 * 0.02 * inner_side
    fr = RPM / 60
    t = np.arange(24_000) / FS
    # An envelope line exactly at 2xBPFI-fr on a 3 kHz carrier, in weak noise.
    x = (1 + np.cos(2 * np.pi * inner_side * fr * t)) * np.sin(2 * np.pi * 3000 * t)
    x = x + 0.1 * np.random.default_rng(3).standard_normal(t.size)
    ev = envelope_evidence(x, FS, "6205", RPM)
    for fault, line in (("ball", "2x2xBSF+FTF"), ("inner", "2xBPFI-fr")):
        k = ev.line_names[fault].index(line)
        assert ev.shared[fault][k] and np.isnan(ev.levels_db[fault][0, k])
    # Nothing else of the two families is left out on the 6205 at 2 s: no other line
    # lies within half the slip search (or 2 bins, 0.5 Hz) of another family's.
    # (2xBPFI-fr is also in the 2xBPFI trio, left out for 3xBPFO).
    assert ev.shared["ball"].sum() == 1 and ev.shared["inner"].sum() == 3


def test_collisions_widen_with_the_resolution():
    # The 6203's 1x2xBSF = 3.988 and 1xBPFI-fr = 3.947 orders (geometry: d = 6.746 mm,
    # D = 28.5 mm, 8 balls): 0.041 orders apart, just beyond half the 2 % slip search
    # (0.040) but within 2 bins of a 1 s record at 30 Hz (2 / 30 = 0.067 orders): on 1 s
    # they collide, on 10 s (0.0067) they do not. Catches the resolution ignored
    # (planted: resolution 0, the 1 s case fails) or always added to the slip window
    # (planted: the 10 s case fails).
    from ballpass.diagnose.evidence import family_lines, shared_lines

    r = 6.746 / 28.5
    ball, bpfi = 1 / r * (1 - r**2), 4 * (1 + r)
    assert 0.040 < ball - (bpfi - 1) < 0.042
    orders = bp.Bearing.catalog("6203").frequencies(1.0).as_dict()
    k = [n for n, _, _ in family_lines("ball", 3)].index("1x2xBSF")
    assert shared_lines(orders, 3, 0.02, 2 / 30)["ball"][k]
    assert not shared_lines(orders, 3, 0.02, 2 / 300)["ball"][k]


def test_a_ball_not_judged_takes_no_race_line():
    # A quarter second at 1500 rpm: 2 bins are 8 Hz = 0.33 orders, and the ball's
    # 1x2xBSF+FTF (5.112 orders) would take 1xBPFI (5.415) with it; but 0.25 s holds
    # 2.5 cage periods, too few to resolve the +-FTF sidebands, the ball is not judged,
    # and only carriers are compared: 1xBPFI stays. Catches line-by-line collisions with
    # an unjudged ball (planted: the inner race was left with one carrier and not
    # judged, and the envelope model's accuracy on 0.25 s rows fell to 0.57).
    rpm = 1500.0
    x = impacts(ORDERS_6205["bpfi"] * rpm / 60, 0.25,
                modulation=lambda t: 1 + np.cos(2 * np.pi * rpm / 60 * t))
    ev = envelope_evidence(x, FS, "6205", rpm)
    assert not ev.shared["inner"][ev.line_names["inner"].index("1xBPFI")]
    assert np.isinf(ev.evidence_db["ball"][0]) and ev.evidence_db["inner"][0] > 6.0
