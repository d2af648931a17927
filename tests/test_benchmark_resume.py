"""``run_benchmark`` computes each row's work once, keeps what it finished on Ctrl-C and
resumes; ``ballpass benchmark`` writes a partial report and exits with 130."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd
import pytest

from ballpass.cli import main
from ballpass.datasets import generate, load
from ballpass.diagnose import LABELS, EnvelopeDiagnoser, run_benchmark, split_indices
from ballpass.diagnose import benchmark as B

MODELS = ["envelope", "logistic"]


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    """Four labels x 2 sizes x 2 sensors x 3 repeats at one speed, 0.25 s rows."""
    grid = {
        "dataset": {"duration_s": 0.5, "fs": 12_000, "repeats": 3, "seed": 11,
                    "segment_s": 0.25, "model": "impulse"},
        "grid": {"bearing": ["6205"], "fault": list(LABELS), "fault_width_mm": [0.3, 0.53],
                 "rpm": [1797], "resonance_hz": [3000], "noise_rms": [0.3],
                 "sensor": ["loaded", "unloaded"]},
    }
    out = tmp_path_factory.mktemp("resume") / "ds"
    generate(grid, out, n_jobs=1, progress=False)
    X, meta = load(out)
    return out, X, meta


def test_envelope_folds_equal_the_diagnoser_fitted_on_each_fold(dataset):
    # the evidence is computed once per row and reused by every fold: each fold's
    # verdicts must be those of a diagnoser fitted on that fold's healthy training rows
    # and predicting its test rows from the signals (the public path, no cache)
    _, X, meta = dataset
    result = run_benchmark(X, meta, splits=["run", "sensor"], models=["envelope"],
                           n_splits=3)
    rpm, y = meta["rpm"].to_numpy(float), meta["label"].to_numpy()
    for split in ("run", "sensor"):
        got = result.predictions[result.predictions.split == split]
        for k, (train, test) in enumerate(split_indices(meta, split, n_splits=3)):
            est = EnvelopeDiagnoser("6205", fs=12_000.0).fit(X[train], y[train], rpm[train])
            expected = est.predict(X[test], rpm[test])
            fold = got[got.fold == k]
            np.testing.assert_array_equal(fold["row"], test)
            np.testing.assert_array_equal(fold["y_pred"], expected)


class _Interrupt:
    """``_fit_predict`` that raises KeyboardInterrupt at its ``at``-th call."""

    def __init__(self, at: int):
        self.at, self.calls = at, 0
        self.real = B._fit_predict

    def __call__(self, *args, **kwargs):
        self.calls += 1
        if self.calls == self.at:
            raise KeyboardInterrupt
        return self.real(*args, **kwargs)


def test_interrupted_benchmark_keeps_finished_pairs_and_resumes(dataset, tmp_path,
                                                                monkeypatch):
    _, X, meta = dataset
    kwargs = dict(splits=["run", "random"], models=MODELS, n_splits=3)
    full = run_benchmark(X, meta, **kwargs)
    # 2 splits x 2 models x 3 folds = 12 fits; the 8th is the 2nd fold of the third pair
    stop = _Interrupt(8)
    monkeypatch.setattr(B, "_fit_predict", stop)
    part = run_benchmark(X, meta, checkpoint=tmp_path, **kwargs)
    assert part.info["interrupted"] and part.info["pairs_done"] == 2
    assert part.info["pairs_planned"] == 4
    pd.testing.assert_frame_equal(part.table, full.table.iloc[:2])
    # resumed: only the unfinished pairs are fitted again, and the report is complete
    again = _Interrupt(0)
    monkeypatch.setattr(B, "_fit_predict", again)
    resumed = run_benchmark(X, meta, checkpoint=tmp_path, **kwargs)
    assert again.calls == 6 and "interrupted" not in resumed.info
    pd.testing.assert_frame_equal(resumed.table, full.table)
    pd.testing.assert_frame_equal(resumed.predictions, full.predictions)
    # other settings: the kept work is not theirs and is discarded
    other = run_benchmark(X, meta, checkpoint=tmp_path, **{**kwargs, "n_splits": 2})
    assert again.calls == 6 + 8 and set(other.table["folds"]) == {2}  # 2 x 2 x 2 fits


def test_interrupt_during_the_row_work_keeps_finished_rows(dataset, tmp_path, monkeypatch):
    _, X, meta = dataset
    calls = []
    real = EnvelopeDiagnoser._evidence

    def evidence(self, x, rpm):
        calls.append(len(x))
        if len(calls) == 3 and stop:
            raise KeyboardInterrupt
        return real(self, x, rpm)

    stop = True

    monkeypatch.setattr(EnvelopeDiagnoser, "_evidence", evidence)
    kwargs = dict(splits=["run"], models=["envelope"], n_splits=3)
    part = run_benchmark(X, meta, checkpoint=tmp_path, **kwargs)
    assert part.info["interrupted"] and part.table.empty
    done_rows = sum(calls[:2])  # the two batches that finished
    calls.clear()
    stop = False
    resumed = run_benchmark(X, meta, checkpoint=tmp_path, **kwargs)
    assert sum(calls) == len(X) - done_rows  # only the rows not finished before
    assert resumed.table["n_test"].iloc[0] == len(X)


def test_cli_ctrl_c_writes_a_partial_report_exits_130_and_resumes(dataset, tmp_path,
                                                                   monkeypatch, capsys):
    path, _, _ = dataset
    out = tmp_path / "report"
    argv = ["benchmark", str(path), "--out", str(out), "--models", "envelope,knn",
            "--splits", "run", "--folds", "2", "-q"]
    monkeypatch.setattr(B, "_fit_predict", _Interrupt(3))
    assert main(argv) == 130
    text = (out / "results.md").read_text()
    assert "Partial report: interrupted" in text and "1 of 2" in text
    # one line, named like generate's (it began with an empty line and no command name)
    assert re.fullmatch(r"ballpass benchmark: interrupted; partial report of 1 of 2 "
                        r"split/model pairs: .*results.md; run the same command again to "
                        r"resume\n", capsys.readouterr().err)
    monkeypatch.setattr(B, "_fit_predict", _Interrupt(0))
    assert main(argv) == 0
    assert "Partial" not in (out / "results.md").read_text()
    assert len(pd.read_csv(out / "results.csv")) == 2
