"""The false-alarm probability stated with each explanation: a Gumbel law of a noise
record's strongest evidence whose location grows with the log of the search size."""

import math

import numpy as np
import pytest
import scipy.stats

import ballpass as bp
from ballpass.diagnose.noise_law import (
    NOISE_EVIDENCE_LAW,
    noise_evidence_law,
    noise_probability,
    noise_threshold,
)

FS, RPM = 12_000.0, 1797.0


def test_gumbel_closed_form():
    loc, scale = noise_evidence_law(1000, 2.0)
    # P(X >= loc) = 1 - exp(-1) for a Gumbel law; one scale above, 1 - exp(-e^-1).
    assert noise_probability(loc, 1000, 2.0) == pytest.approx(1 - math.exp(-1), rel=1e-12)
    assert noise_probability(loc + scale, 1000, 2.0) == pytest.approx(
        1 - math.exp(-math.exp(-1)), rel=1e-12)
    assert noise_probability(-math.inf, 1000, 2.0) == 1.0
    assert noise_probability(math.inf, 1000, 2.0) == 0.0
    # The maximum of N iid readings with an exponential tail: multiplying the search by
    # e moves the location by b, not the scale.
    a, b = NOISE_EVIDENCE_LAW[:2]
    assert noise_evidence_law(math.e * 1000, 2.0)[0] - loc == pytest.approx(b, rel=1e-12)
    assert noise_threshold(0.01, 1000, 2.0) == pytest.approx(
        loc - scale * math.log(-math.log(0.99)), rel=1e-12)
    with pytest.raises(ValueError, match="probability must be in"):
        noise_threshold(1.0, 1000, 2.0)


def _strongest(x, fs, rpm, bearing="6205"):
    ev = bp.diagnose.envelope_evidence(x, fs, bearing, rpm)
    return np.max(np.stack(list(ev.evidence_db.values())), axis=0), ev


@pytest.mark.parametrize("fs, seconds, rpm, resolved", [
    (12_000.0, 1.0, 600.0, False),     # 4 cage periods short: outer judged on carriers
    (12_000.0, 5.0, 1797.0, True),     # a long record: the largest search here
    (48_000.0, 1.0, 1200.0, True),     # a fast rate: many bands
])
def test_law_holds_across_rate_length_speed(fs, seconds, rpm, resolved):
    # Fresh noise (seeds not in the fit), 40 records per configuration: the fraction
    # above the law's 50 % and 20 % quantiles of each record's own search must lie in
    # the 99.9 % binomial interval of 40 draws (a stated probability neither too low
    # nor too high, whatever the rate, length and speed). Measured: 27 / 8, 26 / 12,
    # 25 / 13 of 40 (the law's location sits about 0.1 dB low on these, within the
    # interval; docs/diagnosis_noise.md). Planted: the unresolved offset dropped (c = 0)
    # puts 38 of the 40 one-second records at 600 rpm above the median and 22 above
    # the 20 % quantile; fails. (The search-size term alone, b = 0 at the location of
    # a 4000-reading search, is not caught here, the searches of these three regimes
    # being alike: the 200-record test below catches it.)
    rng = np.random.default_rng(round(fs + seconds * 10 + rpm))
    x = rng.standard_normal((40, int(fs * seconds)))
    top, ev = _strongest(x, fs, rpm)
    for q in (0.5, 0.2):
        thr = noise_threshold(q, ev.n_readings, seconds, resolved)
        above = int(np.sum(top >= thr))
        lo, hi = scipy.stats.binom.interval(0.999, len(top), q)
        assert lo <= above <= hi, (q, above, lo, hi)


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
    assert why[1].n_readings > 100
    assert "noise alone reads the strongest evidence with probability" in str(why[0])
    assert "readings searched" in str(why[0])


def test_threshold_follows_the_search():
    # The default false-alarm probability raises the 6 dB floor where noise alone
    # reaches it more often than that: a one-second record at 600 rpm (sidebands not
    # resolved, the widest law) gets a threshold above 6 dB with the stated probability
    # exactly 1e-3; a long record keeps the floor, its probability below 1e-3.
    x = np.random.default_rng(3).standard_normal((1, 12_000))
    short = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=600.0).explain(x)[0]
    assert short.threshold_db["outer"] > 6.0
    assert short.false_alarm_probability == pytest.approx(1e-3, rel=1e-9)
    long = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(
        np.random.default_rng(4).standard_normal((1, 60_000)))[0]
    assert long.threshold_db["outer"] == 6.0 and long.false_alarm_probability < 1e-3
    with pytest.raises(ValueError, match="false_alarm must be"):
        bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM, false_alarm=2.0).predict(x)


def test_false_alarm_probability_per_record_holds_on_noise_records():
    # The stated per-record probability checked on 200 fresh one-second white-noise
    # records (12 kHz, 6205 at 1797 rpm) at a false_alarm where the diagnoser's own
    # thresholds follow the law (threshold_db 0: no floor). The fraction called faulty
    # must lie in the 99.9 % binomial interval of the stated probability, 8-35
    # (measured: 15). Planted: the search-size term dropped (b = 0: the law of one
    # reading rather than of the search's maximum) calls 190 of them faulty.
    x = np.random.default_rng(77).standard_normal((200, int(FS)))
    diag = bp.diagnose.EnvelopeDiagnoser(fs=FS, rpm=RPM, threshold_db=0.0, false_alarm=0.1)
    why = diag.explain(x)
    assert all(w.false_alarm_probability == pytest.approx(0.1, rel=1e-9) for w in why)
    faulty = sum(w.label != "healthy" for w in why)
    lo, hi = scipy.stats.binom.interval(0.999, len(x), 0.1)
    assert lo <= faulty <= hi, faulty
    assert "false-alarm probability per record" in str(why[0])
