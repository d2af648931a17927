"""The benchmark does each row's work once, and each pipeline's fit once per fold."""

from __future__ import annotations

import numpy as np
import pandas as pd
from sklearn.ensemble import HistGradientBoostingClassifier

import ballpass as bp
from ballpass.diagnose import benchmark as benchmark_module
from ballpass.diagnose import run_benchmark
from ballpass.diagnose.rules import EnvelopeDiagnoser


def _dataset():
    """Eight short impulse-model runs, two segments each (16 rows, one speed)."""
    faults = ["outer", "inner", "ball", None] * 2
    X, meta = [], []
    for i, f in enumerate(faults):
        scene = bp.Scene("6205", rpm=1797, fs=12_000, duration_s=0.5, resonance_hz=3_000,
                         fault=bp.Fault(f) if f else None, noise_rms=0.5, seed=i)
        x = bp.simulate(scene, model="impulse").accel
        for k in range(2):
            X.append(x[k * 3_000:(k + 1) * 3_000])
            meta.append({"label": f or "healthy", "group": i, "rpm": 1797.0,
                         "bearing": "6205", "fs": 12_000.0})
    return np.stack(X), pd.DataFrame(meta)


def test_rows_once_and_recommended_not_refitted(monkeypatch):
    X, meta = _dataset()
    # `recommended` set to gradient boosting on the default features, whatever it is now
    monkeypatch.setattr(benchmark_module, "RECOMMENDED", ("gradient_boosting", "dimensionless"))
    seen = {"evidence_rows": 0, "boosting_fits": 0}
    evidence, fit = EnvelopeDiagnoser._evidence, HistGradientBoostingClassifier.fit

    def counted_evidence(self, x, rpm, *a, **k):
        seen["evidence_rows"] += len(x)
        return evidence(self, x, rpm, *a, **k)

    def counted_fit(self, *a, **k):
        seen["boosting_fits"] += 1
        return fit(self, *a, **k)

    monkeypatch.setattr(EnvelopeDiagnoser, "_evidence", counted_evidence)
    monkeypatch.setattr(HistGradientBoostingClassifier, "fit", counted_fit)
    result = run_benchmark(X, meta, splits=["run", "random"], n_splits=2,
                           models=["envelope", "gradient_boosting", "recommended"])
    folds = int(result.table.groupby("split")["folds"].first().sum())
    # Each row's evidence once, however many splits and folds reuse it (the bug this
    # catches: evidence recomputed per fold, 16 rows x 4 folds).
    assert seen["evidence_rows"] == len(X)
    # `recommended` is then gradient boosting: one fit per fold, not two
    assert seen["boosting_fits"] == folds
    pred = result.predictions.set_index(["split", "fold", "row"])
    by_model = {m: pred[pred.model == m].y_pred for m in ("recommended", "gradient_boosting")}
    assert (by_model["recommended"] == by_model["gradient_boosting"]).all()
