"""Splits on drawn (continuous) axes leave out quantile bins, not each distinct value."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from ballpass.diagnose import split_indices
from ballpass.diagnose.benchmark import MAX_VALUE_FOLDS, QUANTILE_BINS, _split

SEGMENTS = 3  # rows (segments) per run: they must stay on one side of every fold


def _drawn_meta(n_runs: int = 40, seed: int = 3) -> pd.DataFrame:
    """Runs of a drawn-load grid: each run its own log-uniform load, cut in segments."""
    rng = np.random.default_rng(seed)
    load = np.exp(rng.uniform(np.log(100.0), np.log(2000.0), n_runs))
    labels = np.array(["healthy", "outer", "inner", "ball"])[np.arange(n_runs) % 4]
    return pd.DataFrame({
        "label": np.repeat(labels, SEGMENTS), "group": np.repeat(np.arange(n_runs), SEGMENTS),
        "rpm": 1797.0, "radial_load_n": np.repeat(load, SEGMENTS),
        "fault_width_mm": np.repeat(np.where(labels == "healthy", np.nan,
                                             rng.uniform(0.1, 0.6, n_runs)), SEGMENTS)})


def test_drawn_load_gets_quantile_bins_and_keeps_runs_together():
    meta = _drawn_meta()
    folds = split_indices(meta, "load", drawn={"radial_load_n"})
    # One fold per bin, not one per run's load (40 folds, the bug this catches).
    assert len(folds) == QUANTILE_BINS
    # Independent view of quantile bins: ranking the runs by load, each fold's test runs
    # are one contiguous block of the ranking, holding 40 / 4 = 10 runs.
    per_run = meta.groupby("group")["radial_load_n"].first()
    rank = per_run.rank(method="first").astype(int) - 1
    blocks = []
    groups = meta["group"].to_numpy()
    for train, test in folds:
        test_runs = np.unique(groups[test])
        assert not set(groups[train]) & set(test_runs)          # no run on both sides
        assert len(test) == SEGMENTS * len(test_runs)           # all of a run's segments
        r = np.sort(rank[test_runs].to_numpy())
        assert np.array_equal(r, np.arange(r[0], r[0] + len(r)))  # one bin
        assert len(r) == len(per_run) // QUANTILE_BINS
        blocks.append(r)
    # the bins cover every run once
    assert np.array_equal(np.sort(np.concatenate(blocks)), np.arange(len(per_run)))


def test_listed_axis_keeps_leave_one_value_out():
    meta = _drawn_meta()
    meta["radial_load_n"] = np.repeat([300.0, 1000.0, 2000.0] * 13 + [300.0], SEGMENTS)
    folds, rule = _split(meta, "load", 5, 0, drawn={"resonance_hz"})
    assert len(folds) == 3 and "leave one value" in rule
    for _train, test in folds:
        assert meta["radial_load_n"].iloc[test].nunique() == 1


def test_the_rule_is_stated_and_undeclared_many_values_are_binned():
    meta = _drawn_meta()
    folds, rule = _split(meta, "load", 5, 0, drawn={"radial_load_n"})
    assert f"{QUANTILE_BINS} quantile bins of `radial_load_n`" in rule and "drawn axis" in rule
    # without the list of drawn axes, 40 distinct loads (> MAX_VALUE_FOLDS) are binned too
    assert meta["radial_load_n"].nunique() > MAX_VALUE_FOLDS
    folds, rule = _split(meta, "load", 5, 0, drawn=None)
    assert len(folds) == QUANTILE_BINS and f"more than {MAX_VALUE_FOLDS} values" in rule


def test_drawn_fault_size_bins_faults_and_deals_healthy_runs():
    meta = _drawn_meta()
    folds = split_indices(meta, "fault_size", drawn={"fault_width_mm"})
    assert len(folds) == QUANTILE_BINS
    groups, healthy = meta["group"].to_numpy(), meta["label"].to_numpy() == "healthy"
    seen = []
    for train, test in folds:
        assert not set(groups[train]) & set(groups[test])
        seen += list(np.unique(groups[test]))
        width = meta["fault_width_mm"].to_numpy()[test[~healthy[test]]]
        others = meta["fault_width_mm"].to_numpy()[train[~healthy[train]]]
        # a bin: every held-out width lies on one side of every trained width's range
        lo, hi = width.min(), width.max()
        assert not np.any((others >= lo) & (others <= hi))
    assert sorted(seen) == list(range(meta["group"].nunique()))  # each run tested once


@pytest.mark.parametrize("split", ["speed", "load", "fault_size"])
def test_a_listed_single_value_still_forms_no_split(split):
    meta = _drawn_meta()
    meta["radial_load_n"] = 500.0
    meta["fault_width_mm"] = np.where(meta["label"] == "healthy", np.nan, 0.3)
    assert split_indices(meta, split, drawn={"radial_load_n", "fault_width_mm"}) == []


def test_cli_reads_the_drawn_axes_of_a_generated_dataset(tmp_path):
    """`ballpass benchmark` takes the drawn axes from the dataset's grid: a load drawn
    for each of 12 runs makes 4 bin folds, and the report says so."""
    from ballpass.cli import main
    from ballpass.datasets import generate

    grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "draws": 3, "seed": 1,
                        "model": "impulse"},
            "grid": {"bearing": "6205", "fault": ["healthy", "outer", "inner", "ball"],
                     "rpm": 1797, "resonance_hz": 3000,
                     "radial_load_n": {"log_uniform": [200, 2000]}}}
    generate(grid, tmp_path / "ds", progress=False)
    out = tmp_path / "report"
    assert main(["benchmark", str(tmp_path / "ds"), "--out", str(out), "--models",
                 "envelope", "--splits", "load", "-q"]) == 0
    text = (out / "results.md").read_text()
    assert "Folds: leave one of 4 quantile bins of `radial_load_n` out (drawn axis" in text
    assert pd.read_csv(out / "results.csv")["folds"].tolist() == [QUANTILE_BINS]
