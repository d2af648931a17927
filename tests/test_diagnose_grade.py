"""The grade of a diagnosis (Smith & Randall's Y/P/N) pinned on marginal cases.

"Y" needs the named family to clear its threshold *and* every other family by the
grade margin; "N" when a second family clears its threshold within that margin (the
families collide); "P" otherwise. Each case is built from the evidence the
diagnoser itself reports for one signal (so it holds whatever the evidence engine
computes): the thresholds are placed around that evidence, through the public
``threshold_db`` and ``explain()``. The margins used (1 dB against 10 dB) sit on either
side of any sensible grade margin (3 dB now).
"""

import numpy as np
import pytest

import ballpass as bp

FS, RPM = 12_000.0, 1797.0


@pytest.fixture(scope="module")
def outer_signal():
    """Impacts at BPFO ringing a 3 kHz resonance, in white noise, 2 s: the outer family
    reads far above the others."""
    bpfo = bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfo
    t = np.arange(int(2 * FS)) / FS
    phase = (t * bpfo) % 1.0 / bpfo  # time since the last impact, s
    x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    x = x + 0.3 * np.random.default_rng(0).standard_normal(t.size)
    evidence = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(x[None])[0].evidence_db
    assert evidence["outer"] > 12.0 and all(np.isfinite(v) for v in evidence.values())
    return x, evidence


def _explain(x, evidence, offsets):
    """Explanation with each family's threshold at its own evidence minus ``offsets``
    (dB): the family's margin over its threshold becomes exactly that offset."""
    thresholds = {f: evidence[f] - offsets[f] for f in offsets}
    # false_alarm=None: the thresholds are these, not raised to the noise floor
    why = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM, threshold_db=thresholds,
                                        false_alarm=None).explain(x[None])[0]
    # the case is what the explanation itself reports: each family's margin is its
    # offset (a family the diagnoser did not judge, -inf, is below any threshold)
    for f, offset in offsets.items():
        margin = why.evidence_db[f] - why.threshold_db[f]
        assert margin == pytest.approx(offset, abs=1e-9) or (margin == -np.inf and offset < 0)
    return why


@pytest.mark.parametrize(("offsets", "label", "grade"), [
    # barely clears its threshold, the next family 11 dB below it: partly diagnosed
    ({"outer": 1.0, "inner": -10.0, "ball": -10.0}, "outer", "P"),
    # clears its threshold and the others by 10 dB: clearly diagnosed
    ({"outer": 10.0, "inner": -10.0, "ball": -10.0}, "outer", "Y"),
    # every family 10 dB below its threshold: clearly healthy
    ({"outer": -10.0, "inner": -10.0, "ball": -10.0}, "healthy", "Y"),
    # healthy, but the outer family only 1 dB below its threshold: partly
    ({"outer": -1.0, "inner": -10.0, "ball": -10.0}, "healthy", "P"),
])
def test_grade_of_marginal_and_clear_cases(outer_signal, offsets, label, grade):
    x, evidence = outer_signal
    offsets = {f: min(o, evidence[f]) for f, o in offsets.items()}  # thresholds >= 0
    why = _explain(x, evidence, offsets)
    assert (why.label, why.grade) == (label, grade), why
    assert f"{label} (grade {grade})" in str(why)


def test_two_families_clearing_their_thresholds_together_are_not_diagnosable(outer_signal):
    """Outer clears its threshold by 1 dB more than the inner family clears its own
    (its threshold set to 0): the two families collide, the record is named by the
    stronger (``predict`` keeps its four labels) but graded "N", with a note naming the
    rival. Smith & Randall's grades decide it: the one shared record where two families
    clear within the margin (CWRU 118, ball 0.007 in, read outer 12.1 dB and inner
    9.2 dB) is graded N1 there. Planted: the former "P" for this case fails it."""
    x, evidence = outer_signal
    assert evidence["inner"] >= 2.0  # the competitor's margin at threshold 0
    why = _explain(x, evidence, {"outer": evidence["inner"] + 1.0, "inner": evidence["inner"]})
    assert (why.label, why.grade) == ("outer", "N"), why
    assert any(n.startswith("outer and inner both clear") for n in why.notes), why.notes


def test_a_competitor_close_below_its_threshold_leaves_a_partial_diagnosis(outer_signal):
    """Outer clears its threshold by 2 dB, inner stays 0.5 dB below its own: the
    margin between them is under 3 dB but only one family clears, so the grade is "P"
    (partly), not "N". Planted: grading every close competitor "N" fails it."""
    x, evidence = outer_signal
    why = _explain(x, evidence, {"outer": 2.0, "inner": -0.5, "ball": -10.0})
    assert (why.label, why.grade) == ("outer", "P"), why
    assert not any("both clear" in n for n in why.notes)


def test_healthy_is_only_partly_diagnosed_when_a_family_could_not_be_judged(outer_signal):
    """0.3 s is 3.6 cage periods, fewer than the ball family needs to resolve its +-FTF
    sidebands (4): with every judged family far below a 40 dB threshold the record is
    healthy, but grade "P", not "Y", and the note says why."""
    x, _ = outer_signal
    why = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM, threshold_db=40.0).explain(
        x[None, :int(0.3 * FS)])[0]
    assert why.evidence_db["ball"] == -np.inf and why.evidence_db["outer"] < 37.0
    assert (why.label, why.grade) == ("healthy", "P"), why
    assert any(note.startswith("ball not judged") for note in why.notes)
