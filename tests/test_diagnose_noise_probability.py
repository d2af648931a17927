"""The false-alarm probability stated with each explanation: a Gumbel law of the
strongest evidence of noise records."""

import math

import numpy as np
import pytest

import ballpass as bp
from ballpass.diagnose.rules import NOISE_EVIDENCE_GUMBEL, noise_probability

FS, RPM = 12_000.0, 1797.0


def test_gumbel_closed_form():
    loc, scale = NOISE_EVIDENCE_GUMBEL
    # P(X >= loc) = 1 - exp(-1) for a Gumbel law; one scale above, 1 - exp(-e^-1).
    assert noise_probability(loc) == pytest.approx(1 - math.exp(-1), rel=1e-12)
    assert noise_probability(loc + scale) == pytest.approx(1 - math.exp(-math.exp(-1)),
                                                           rel=1e-12)
    assert noise_probability(float("-inf")) == 1.0
    assert noise_probability(float("inf")) == 0.0


def test_law_does_not_understate_fresh_noise():
    # 24 one-second white-noise records not used in the fit (other seeds). The law is
    # fitted over rates, lengths, speeds and bearings whose mean strongest evidence
    # spreads 3.4-3.9 dB (docs/diagnosis_noise.md), so one configuration's mean may sit
    # below the law's mean (loc + 0.5772 scale), but not above it by more than 4
    # standard errors (sd pi scale / sqrt 6 over sqrt 24): a stated false-alarm
    # probability must not be too low. And not more than 1 dB below it: a law fitted on
    # threshold-level evidence (location 5 dB) would state nothing. Measured: 3.20 dB
    # against the law's 3.63 dB.
    loc, scale = NOISE_EVIDENCE_GUMBEL
    rng = np.random.default_rng(2024)
    x = rng.standard_normal((24, int(FS)))
    ev = bp.diagnose.envelope_evidence(x, FS, "6205", RPM)
    strongest = np.max(np.stack(list(ev.evidence_db.values())), axis=0)
    mean = loc + 0.5772 * scale
    se = math.pi * scale / math.sqrt(6) / math.sqrt(len(x))
    assert mean - 1.0 < strongest.mean() < mean + 4 * se


def test_explanation_states_it():
    bpfo = bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfo
    t = np.arange(int(FS)) / FS
    phase = (t * bpfo) % 1.0 / bpfo
    fault = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    noise = 0.3 * np.random.default_rng(5).standard_normal(t.size)
    why = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(np.stack([fault + noise,
                                                                            noise]))
    assert why[0].label == "outer" and why[0].noise_probability < 1e-6
    assert why[1].label == "healthy" and why[1].noise_probability > 1e-3
    assert "noise alone reads the strongest evidence with probability" in str(why[0])


def test_false_alarm_probability_per_record_holds_on_200_noise_records():
    # The per-record false-alarm probability explain() states, checked on 200 fresh
    # one-second white-noise records (12 kHz, 6205 at 1797 rpm): the fraction called
    # faulty must not exceed the upper end of the 99.9 % binomial interval of the
    # stated probability (a stated number too low would be a false promise). Three
    # thresholds: the default (stated 7e-5, target at most 1 %), and thresholds where
    # the law states 20 % and 50 % per record, which 200 records can check. Measured
    # here: 0, 4.5 % and 17.5 %: the law, fitted over rates, lengths, speeds and
    # bearings, overstates this configuration (its strongest evidence averages 3.3 dB
    # against the law's 3.6 dB), so the statement is an upper bound here, not an
    # estimate. Catches a law that understates the search (planted: location 3.0 dB
    # instead of 3.51, as a law of one reading rather than of a record's strongest
    # would: the 50 % threshold calls most records faulty).
    import scipy.stats

    loc, scale = NOISE_EVIDENCE_GUMBEL
    x = np.random.default_rng(77).standard_normal((200, int(FS)))
    for stated in (None, 0.2, 0.5):
        threshold = (6.0 if stated is None
                     else loc - scale * math.log(-math.log(1.0 - stated)))
        diag = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM, threshold_db=threshold)
        why = diag.explain(x)
        p = why[0].false_alarm_probability
        assert p == pytest.approx(noise_probability(threshold), rel=1e-12)
        if stated is None:
            assert p <= 0.01
        else:
            assert p == pytest.approx(stated, rel=1e-9)
        faulty = sum(w.label != "healthy" for w in why)
        assert faulty <= scipy.stats.binom.ppf(0.999, len(x), p), (stated, faulty)
    assert "false-alarm probability per record" in str(why[0])
