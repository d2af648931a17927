"""Thresholds from a healthy baseline (``ballpass.diagnose.baseline``)."""

import numpy as np
import pytest

import ballpass as bp
from ballpass.diagnose import EnvelopeDiagnoser, baseline_thresholds
from ballpass.diagnose.baseline import sliding_windows

FS, RPM = 12_000.0, 1797.0


def ringing(rate, n, amplitude, seed):
    """Impacts at ``rate`` Hz of ``amplitude`` ringing 3 kHz in unit white noise."""
    t = np.arange(n) / FS
    phase = (t * rate) % 1.0 / rate
    x = amplitude * np.exp(-600 * phase) * np.sin(2 * np.pi * 3_000 * phase)
    return x + np.random.default_rng(seed).standard_normal(n)


def test_sliding_windows_start_every_step_and_copy_the_samples():
    x = np.arange(100.0)
    w = sliding_windows(x, 40, step=0.25)
    # starts 0, 10, ..., 60: the last window ends at sample 99, within one hop of the end
    assert w.shape == (7, 40)
    np.testing.assert_array_equal(w[:, 0], np.arange(0, 61, 10))
    np.testing.assert_array_equal(w[3], x[30:70])
    assert len(sliding_windows(x, 100)) == 1  # as long as x: x itself


@pytest.mark.parametrize("n, step, match", [
    (0, 0.5, "n must be in"), (101, 0.5, "n must be in"),
    (10, 0.0, "step must be in"), (10, 1.5, "step must be in"),
])
def test_sliding_windows_bad_arguments_are_named(n, step, match):
    with pytest.raises(ValueError, match=match):
        sliding_windows(np.zeros(100), n, step)


def test_a_baseline_line_sets_its_family_threshold_above_what_it_reads():
    """A healthy machine with its own line at BPFO (9-11 dB of outer-race evidence on
    1 s, above the 6 dB default): the outer-race threshold rises above what any second
    of it reads (so a new record of it is healthy), the other families keep 6 dB (catches
    the thresholds taken from the wrong family or not raised), and a second record
    without the line does not lower it (the largest over the records)."""
    bpfo = bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfo
    with_line = ringing(bpfo, 60_000, 1.5, seed=1)
    clean = np.random.default_rng(2).standard_normal(60_000)
    thresholds = baseline_thresholds([(clean, FS, RPM), (with_line, FS, RPM)], "6205", 1.0)
    assert thresholds["inner"] == thresholds["ball"] == 6.0
    plain = EnvelopeDiagnoser("6205", fs=FS, rpm=RPM)
    seconds = ringing(bpfo, 60_000, 1.5, seed=3).reshape(5, -1)  # a new record of it
    assert (plain.predict(seconds) == "outer").all()
    read = plain.explain(sliding_windows(with_line, 12_000))
    assert thresholds["outer"] > max(why.evidence_db["outer"] for why in read)
    calibrated = EnvelopeDiagnoser("6205", fs=FS, rpm=RPM, threshold_db=thresholds)
    assert (calibrated.predict(seconds) == "healthy").all()
    alone = baseline_thresholds([(with_line, FS, RPM)], "6205", 1.0)
    assert alone == thresholds


@pytest.mark.parametrize("records, seconds, match", [
    ([], 1.0, "at least one healthy"),
    ([(np.zeros(12_000), FS, RPM)], 0.0, "seconds must be finite and > 0"),
    ([(np.zeros((2, 12_000)), FS, RPM)], 1.0, r"records\[0\] signal must be 1-D"),
    ([(np.zeros(12_000), -1.0, RPM)], 1.0, "fs must be"),
])
def test_baseline_bad_arguments_are_named(records, seconds, match):
    with pytest.raises(ValueError, match=match):
        baseline_thresholds(records, "6205", seconds)
