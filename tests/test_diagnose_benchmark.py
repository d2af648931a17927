"""Benchmark splits (groups never straddle), pipelines, cross-validation, report and CLI."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pytest
import sklearn
from sklearn.model_selection import GroupKFold, cross_validate
from sklearn.utils.estimator_checks import parametrize_with_checks

from ballpass.cli import main
from ballpass.datasets import generate, load
from ballpass.diagnose import (
    CLASSIFIERS,
    LABELS,
    SPLITS,
    make_pipeline,
    run_benchmark,
    split_indices,
    write_report,
)

HONEST = [s for s in SPLITS if s not in ("random", "sim2real")]


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    """A small generated dataset: 2 sizes x 2 speeds x 2 loads x 2 sensors, 0.25 s rows."""
    grid = {
        "dataset": {"duration_s": 0.5, "fs": 12_000, "repeats": 2, "seed": 7,
                    "segment_s": 0.25},
        "grid": {"bearing": ["6205"], "fault": list(LABELS), "fault_width_mm": [0.3, 0.53],
                 "fault_depth_mm": [0.28], "rpm": [1500, 1797], "radial_load_n": [300, 1000],
                 "resonance_hz": [3000], "snr_db": [10], "sensor": ["loaded", "unloaded"]},
    }
    out = tmp_path_factory.mktemp("bench") / "ds"
    generate(grid, out, n_jobs=1, progress=False)
    X, meta = load(out)
    return out, X, meta


def _synthetic_meta() -> pd.DataFrame:
    """Rows of runs with 3 segments and 2 sensors over speeds, loads and sizes."""
    rows, run = [], 0
    for label, rpm, radial_load, width, _ in itertools.product(
            LABELS, (1730.0, 1797.0), (200.0, 1000.0), (0.18, 0.53), range(3)):
        if label == "healthy" and width != 0.18:
            continue
        for sensor, segment in itertools.product(("loaded", "unloaded"), range(3)):
            rows.append({"label": label, "rpm": rpm, "radial_load_n": radial_load,
                         "fault_width_mm": np.nan if label == "healthy" else width,
                         "sensor": sensor, "segment": segment, "group": run})
        run += 1
    return pd.DataFrame(rows)


@pytest.mark.parametrize("split", HONEST)
def test_honest_splits_keep_groups_disjoint(split):
    meta = _synthetic_meta()
    folds = split_indices(meta, split, n_splits=4, random_state=0)
    assert len(folds) >= 2
    groups = meta["group"].to_numpy()
    tested = np.concatenate([test for _, test in folds])
    for train, test in folds:
        assert len(train) and len(test)
        assert not set(groups[train]) & set(groups[test])
    # every row is tested at most once; all of them except in the sensor shift
    assert len(tested) == len(set(tested))
    if split != "sensor":
        assert sorted(tested) == list(range(len(meta)))


def test_splits_hold_out_what_they_name():
    meta = _synthetic_meta()
    for train, test in split_indices(meta, "speed"):
        assert meta.rpm[test].nunique() == 1 and meta.rpm[test].iloc[0] not in set(meta.rpm[train])
    for train, test in split_indices(meta, "load"):
        assert not set(meta.radial_load_n[test]) & set(meta.radial_load_n[train])
    for train, test in split_indices(meta, "fault_size"):
        sizes = meta.fault_width_mm[test].dropna().unique()
        assert len(sizes) == 1 and sizes[0] not in set(meta.fault_width_mm[train])
        assert (meta.label[test] == "healthy").any() and (meta.label[train] == "healthy").any()
    for train, test in split_indices(meta, "sensor"):
        assert set(meta.sensor[train]) == {"loaded"} and set(meta.sensor[test]) == {"unloaded"}
    for _, test in split_indices(meta, "run"):
        assert set(meta.label[test]) == set(LABELS)  # stratified


def test_random_split_is_the_leaky_one():
    meta = _synthetic_meta()
    groups = meta["group"].to_numpy()
    folds = split_indices(meta, "random", n_splits=4)
    assert any(set(groups[tr]) & set(groups[te]) for tr, te in folds)


def test_a_single_value_forms_no_split():
    meta = _synthetic_meta()
    meta = meta[(meta.rpm == 1797.0) & (meta.sensor == "loaded")].reset_index(drop=True)
    assert split_indices(meta, "speed") == []
    assert split_indices(meta, "sensor") == []
    with pytest.raises(ValueError, match="split must be one of"):
        split_indices(meta, "sim2real")


def test_generated_dataset_splits_are_disjoint(dataset):
    _, _, meta = dataset
    groups = meta["group"].to_numpy()
    for split in HONEST:
        folds = split_indices(meta, split)
        assert folds, split
        for train, test in folds:
            assert not set(groups[train]) & set(groups[test]), split


def test_pipeline_cross_validates_on_a_generated_dataset(dataset):
    _, X, meta = dataset
    y, rpm = meta["label"].to_numpy(), meta["rpm"].to_numpy()
    pipe = make_pipeline("logistic", fs=12_000, bearing="6205")
    with sklearn.config_context(enable_metadata_routing=True):
        cv = cross_validate(pipe, X, y, cv=GroupKFold(n_splits=3),
                            params={"rpm": rpm, "groups": meta["group"]})
    # chance is 0.25; 0.25 s rows of 3 fault kinds at two sizes are easy to tell apart,
    # the unloaded-zone small faults aside
    assert cv["test_score"].mean() > 0.6


def test_benchmark_and_report(dataset, tmp_path):
    _, X, meta = dataset
    result = run_benchmark(X, meta, models=["envelope", "logistic"], n_splits=3)
    table = result.table
    assert set(table["split"]) == set(SPLITS) - {"sim2real"}
    assert table.loc[table.split == "random", "optimistic"].all()
    assert not table.loc[table.split != "random", "optimistic"].any()
    assert table[["accuracy", "macro_f1"]].stack().between(0, 1).all()
    run_env = table[(table.split == "run") & (table.model == "envelope")].iloc[0]
    assert run_env["n_test"] == len(X) and run_env["accuracy"] > 0.6
    assert result.confusion["run", "envelope"].sum() == len(X)
    paths = write_report(result, tmp_path)
    text = paths["markdown"].read_text()
    assert "OPTIMISTIC" in text and "confusion_run.png" in text
    # the rule that made each split's folds: two listed loads, each left out
    assert "Folds: leave one value of `radial_load_n` out (2 values)." in text
    assert all(p.exists() for p in paths.values())
    assert pd.read_csv(paths["csv"]).shape[0] == len(table)


def test_sim2real_trains_on_simulation_and_tests_on_real(dataset):
    _, X, meta = dataset
    rng = np.random.default_rng(0)
    X_real = rng.standard_normal((4, 6000))
    meta_real = pd.DataFrame({"label": "healthy", "group": ["a", "a", "b", "b"],
                              "rpm": 1797.0, "bearing": "6205", "fs": 12_000.0})
    result = run_benchmark(X, meta, real=(X_real, meta_real), splits=["sim2real"],
                           models=["envelope", "knn"])
    pred = result.predictions
    assert set(pred["row"]) == {0, 1, 2, 3} and set(pred["group"]) == {"a", "b"}
    assert result.table.set_index("model").loc["envelope", "recall_healthy"] == 1.0
    meta_real["fs"] = 48_000.0
    with pytest.raises(ValueError, match="fs"):
        run_benchmark(X, meta, real=(X_real, meta_real), splits=["sim2real"])


def test_knn_on_a_training_set_smaller_than_its_neighbourhood(dataset):
    # The quick example grid trains some folds on four rows: kNN (k = 5) then uses all
    # of them rather than failing, and still predicts a label for every test row.
    _, X, meta = dataset
    few = meta.index[meta.label.isin(["healthy", "outer"])][:4].to_numpy()
    X_real = X[few]
    meta_real = meta.iloc[few].reset_index(drop=True)
    result = run_benchmark(X[few], meta.iloc[few].reset_index(drop=True),
                           real=(X_real, meta_real), splits=["sim2real"], models=["knn"])
    assert len(result.predictions) == 4
    assert set(result.predictions.y_pred) <= {"healthy", "outer"}


def test_cli(dataset, tmp_path, capsys):
    path, _, _ = dataset
    out = tmp_path / "report"
    code = main(["benchmark", str(path), "--out", str(out), "--models", "envelope,knn",
                 "--splits", "run,random", "--folds", "2"])
    assert code == 0
    assert (out / "results.md").exists() and (out / "confusion_random.png").exists()
    assert "report:" in capsys.readouterr().out
    assert main(["benchmark", str(path), "--out", str(out), "--models", "nope"]) == 2


# ---------------------------------------------------------------- estimator checks
def _small(pipe):
    """Fewer trees / iterations: the checks fit dozens of times."""
    name = type(pipe[-1]).__name__
    if name == "RandomForestClassifier":
        pipe.set_params(classifier__n_estimators=10)
    elif name == "HistGradientBoostingClassifier":
        pipe.set_params(classifier__max_iter=10)
    return pipe


def _expected_failures(pipe):
    failures = {
        # every scikit-learn Pipeline fits its steps in place, which these two checks
        # read as a mutated parameter (sklearn's own make_pipeline fails them too)
        "check_estimators_overwrite_params": "Pipeline fits its steps in place",
        "check_dont_overwrite_parameters": "Pipeline fits its steps in place",
    }
    if type(pipe[-1]).__name__ != "RandomForestClassifier":
        # the check's toy data are rows of 2-10 'samples': no envelope, no spectrum;
        # their signal features separate the blobs only for the forest
        failures["check_classifiers_train"] = "toy rows of a few samples are not signals"
    return failures


@parametrize_with_checks([_small(make_pipeline(c)) for c in CLASSIFIERS],
                         expected_failed_checks=_expected_failures)
def test_pipelines_pass_sklearn_checks(estimator, check):
    check(estimator)


def test_fold_spread_and_few_groups_are_reported(dataset, tmp_path):
    """Each score carries its spread over the folds, and a class with fewer than five
    groups is warned about (the report says so too)."""
    _, X, meta = dataset
    healthy = meta.loc[meta.label == "healthy", "group"].unique()
    keep = ~meta.group.isin(healthy[3:]).to_numpy()          # 3 healthy runs left
    X, meta = X[keep], meta[keep].reset_index(drop=True)
    with pytest.warns(UserWarning, match="fewer than 5 groups") as caught:
        result = run_benchmark(X, meta, splits=["run"], models=["envelope"], n_splits=3)
    few = result.info["few_groups"]
    assert few == {"healthy": 3}
    assert not run_benchmark(X[meta.label != "healthy"], meta[meta.label != "healthy"],
                             splits=["run"], models=["envelope"], n_splits=3).info["few_groups"]
    assert any(str(few) in str(w.message) for w in caught)
    row = result.table.iloc[0]
    pred = result.predictions
    per_fold = (pred.y_true == pred.y_pred).groupby(pred.fold).mean()
    # the pooled accuracy lies within the spread of the per-fold accuracies
    assert row.accuracy_fold_min == per_fold.min() <= row.accuracy <= per_fold.max()
    assert row.accuracy_fold_max == per_fold.max()
    text = write_report(result, tmp_path)["markdown"].read_text()
    assert "**Warning:** classes with fewer than 5 groups" in text and "accuracy_fold_min" in text
