"""The HIT-SM twin study's tables (benchmarks/twin_hit.py): how runs over twin seeds are
summarized, and the grid lines that make each variant of the twin."""

import re

import pandas as pd
import pytest
from _bench import load_benchmark

bench = load_benchmark("twin_hit", "twin_hit_bench")


def _runs():
    rows = []
    for seed, (bal, h) in enumerate([(0.8, 1.0), (0.9, 0.7), (1.0, 1.0)]):
        rows.append({"twin": "spread impacts", "input": "Normal_600", "model": "recommended",
                     "twin_seed": seed, "n_test": 100, "recall_healthy": h,
                     "recall_outer": 0.9, "recall_inner": 0.9,
                     "balanced_accuracy_3class": bal, "balanced_3class_seed_min": bal - seed / 100,
                     "balanced_3class_seed_max": bal, "generate_s": 10.0 + seed,
                     "benchmark_s": 90.0 - seed})
    return pd.DataFrame(rows)


def test_summary_averages_over_twin_seeds():
    """Three twin seeds of one input and model: mean recall and balanced accuracy, the
    balanced accuracy's range over the seeds, the largest training-seed range (0.02 at
    seed 2), the longest wall times. Exact arithmetic on a hand-made table (float
    rounding only). Planted: a median instead of the mean (healthy 1.0, not 0.9) fails."""
    out = bench.summary(_runs())
    assert len(out) == 1
    row = out.iloc[0]
    assert row["recall_healthy"] == pytest.approx(0.9)
    assert row["balanced_accuracy_3class"] == pytest.approx(0.9)
    assert (row["balanced_twin_seed_min"], row["balanced_twin_seed_max"]) == (0.8, 1.0)
    assert row["training_seed_spread_max"] == pytest.approx(0.02)
    assert (row["generate_s_max"], row["benchmark_s_max"]) == (12.0, 90.0)


def test_each_twin_changes_its_lines_of_the_written_grid():
    """Every variant's axes have one line each in the grid the twin writes, and
    variant() sets exactly those: the default twin is the grid as written (both passage
    shapes drawn per row), the others fix one. An axis the grid lacks is an error, not a silent
    no-op (planted: a misspelt axis)."""
    from ballpass.datasets.twin import _GRID_TEMPLATE, TWIN_DEFAULTS

    text = _GRID_TEMPLATE.format(
        names="a", bearing="6205", fs=51_200.0, manifest='"m.csv"', duration_s=1.0,
        draws=2, seed=0, rpm="900", d=TWIN_DEFAULTS, resonance_hz=12_800.0, n_runs=8)
    assert bench.TWINS[bench.DEFAULT_TWIN] == {}
    assert re.search(r"^impact_edges = \{ choice = \[0, 1\] \}$", text, flags=re.M)
    for lines in bench.TWINS.values():
        changed = bench.variant(text, lines)
        diff = set(changed.splitlines()) ^ set(text.splitlines())
        assert len(diff) == 2 * sum(v != re.search(rf"^{k} = (.*)$", text, re.M)[1]
                                    for k, v in lines.items())
    assert "impact_edges = [0]" in bench.variant(text, bench.TWINS["point impacts"])
    assert "impact_edges = [1]" in bench.variant(text, bench.TWINS["Hertzian edges"])
    with pytest.raises(ValueError, match="0 lines of impact_edge,"):
        bench.variant(text, {"impact_edge": "[0]"})


def test_pipeline_choice_and_leave_one_input_out():
    """benchmarks/twin_pipelines.py: the pipeline with the highest mean over inputs (and
    twins) is chosen; leaving an input out, the choice is made on the other inputs only.
    Hand-made scores: A leads on the mean (0.85) on the strength of input 1 alone, B leads
    on inputs 2 and 3, so with input 1 left out B is chosen and scored there (0.6).
    Planted: the choice made on all inputs picks A for every left-out input; fails."""
    pipelines = load_benchmark("twin_pipelines", "twin_pipelines_bench")
    scores = {("dimensionless", "A"): (1.0, 0.8, 0.75), ("combined", "B"): (0.6, 0.82, 0.8)}
    runs = pd.DataFrame([{"features": f, "model": m, "input": i + 1, "twin_seed": s,
                          "balanced_accuracy_3class": v + (s - 0.5) / 100}
                         for (f, m), vals in scores.items() for i, v in enumerate(vals)
                         for s in (0, 1)])
    per_input, held = pipelines.summary(runs)
    assert per_input.index[0] == ("dimensionless", "A")
    assert per_input.loc[("dimensionless", "A"), "mean"] == pytest.approx(0.85)
    first = held.set_index("left_out").loc[1]
    assert (first["features"], first["model"]) == ("combined", "B")
    assert first["balanced_accuracy_3class"] == pytest.approx(0.6)
    assert list(held.set_index("left_out").loc[[2, 3], "model"]) == ["A", "A"]
