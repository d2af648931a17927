"""benchmarks/diagnose_robustness.py: the perturbations are what the page says, and a
changed verdict is counted as the outcome it is."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from tests._bench import load_benchmark

bench = load_benchmark("diagnose_robustness")


def record(x, fs=12_000.0, rpm=1797.0, label="healthy"):
    return bench.Record("r", "DE", label, "6205", fs, rpm, np.asarray(x, dtype=float))


@pytest.mark.parametrize("truth, reference, new, expected", [
    ("h", "h", "h", "same"),
    ("h", "h", "o", "false alarm"),
    ("h", "o", "h", "better"),          # a false alarm cleared
    ("h", "o", "i", "fault renamed"),   # still a false alarm, another family
    ("o", "o", "h", "fault lost"),
    ("o", "o", "i", "fault renamed"),
    ("o", "i", "o", "better"),          # a wrong family put right
    ("o", "h", "o", "better"),          # a missed fault named
    ("o", "h", "i", "fault renamed"),   # a missed fault named wrong
    ("b", "o", "h", "fault lost"),      # lost, even where the verdict was wrong
])
def test_outcome(truth, reference, new, expected):
    assert bench.outcome(truth, reference, new) == expected


def test_count_tallies_records_and_segments():
    frame = pd.DataFrame({"truth": ["healthy", "outer"], "verdicts": ["o", "hh"],
                          "reference": ["h", "oo"], "segments": ["hoh", ""],
                          "segments_reference": ["hhh", ""]})
    whole = bench.count(frame, "verdicts", "reference")
    assert (whole["units"], whole["flips"], whole["false alarm"], whole["fault lost"]) \
        == (3, 3, 1, 2)
    seg = bench.count(frame, "segments", "segments_reference")
    assert (seg["units"], seg["flips"], seg["false alarm"]) == (3, 1, 1)


def test_int16_uses_a_tenth_of_the_range():
    x = np.sin(np.linspace(0, 20, 1000)) * 3.7
    q = bench._int16(record(x))
    assert q.dtype == np.int16
    # the peak maps to full scale / 10: 32767 / 10 counts, rounded
    assert np.max(np.abs(q)) == round(32767 / bench.FULL_SCALE_PEAKS)
    # the counts are the signal to within half a count (uniform rounding)
    lsb = bench.FULL_SCALE_PEAKS * np.max(np.abs(x)) / 32767
    assert np.max(np.abs(q * lsb - x)) <= 0.5 * lsb * (1 + 1e-9)


def test_offsets_and_rates():
    rng = np.random.default_rng(0)
    rec = record(rng.standard_normal(24_000))
    cases = {c.name: c for c in bench.perturbations()}
    (x, fs, rpm), = cases[f"DC offset ({bench.OFFSET_RMS:g} x RMS)"].apply(rec)
    assert np.mean(x) == pytest.approx(bench.OFFSET_RMS * np.std(rec.x), rel=0.01)
    settle = cases[f"settling ({bench.OFFSET_RMS:g} x RMS, tau {bench.SETTLE_S:g} s)"]
    (x, _, _), = settle.apply(rec)
    # the transient at t = tau is 1/e of its start
    k = round(bench.SETTLE_S * rec.fs)
    assert (x - rec.x)[k] / (x - rec.x)[0] == pytest.approx(np.exp(-1.0))
    (x, fs, rpm), = cases["resampled 12 -> 10 kHz"].apply(rec)
    assert (fs, x.size, rpm) == (10_000.0, 20_000, rec.rpm)
    assert cases["resampled 51.2 -> 20 kHz"].apply(rec) == []   # another rate's
    assert len(cases["2 s crops"].apply(rec)) == 1
    assert cases["10 s crops"].apply(rec) == []
    (_, _, rpm), = cases["stated speed -2 %"].apply(rec)
    assert rpm == pytest.approx(0.98 * rec.rpm)


def test_page_is_written_from_its_csvs():
    # docs/diagnosis_robustness.md is what the script writes from the committed CSVs
    # (its run time read back from the page): a hand edit of the page, or CSVs
    # regenerated without it, fail here
    paths = load_benchmark("_paths")
    page = (paths.DOCS / "diagnosis_robustness.md").read_text()
    seconds = float(page.split("diagnose_robustness.py` (")[1].split(" s)")[0])
    read = {"dtype": str, "keep_default_na": False}
    frame = pd.read_csv(paths.RESULTS_DIR / "diagnosis_robustness.csv", **read)
    before = pd.read_csv(paths.RESULTS_DIR / "diagnosis_robustness_before.csv", **read)
    lines = bench.page(bench.summary(frame), frame, seconds, before, bench.NOTES)
    assert "\n".join(lines).rstrip("\n") + "\n" == page
