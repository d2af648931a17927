"""Honest sim-to-real reports: balanced and three-class scores, the spread over training
seeds, one prediction per real segment and model, the recommended pipeline named."""

import numpy as np
import pandas as pd
import pytest

import ballpass as bp
from ballpass.cli import main
from ballpass.diagnose import benchmark as benchmark_module
from ballpass.diagnose import report as report_module
from ballpass.diagnose import run_benchmark, write_report
from ballpass.diagnose._names import CLASSIFIERS, FEATURE_SETS, RECOMMENDED
from ballpass.diagnose.benchmark import _scores
from ballpass.diagnose.report import sim2real_table

FS = 12_000.0


def test_scores_by_hand():
    # 4 healthy (3 right), 2 outer (both right), 2 inner (1 right, 1 called ball),
    # 2 ball (none right)
    y_true = ["healthy"] * 4 + ["outer"] * 2 + ["inner"] * 2 + ["ball"] * 2
    y_pred = ["healthy"] * 3 + ["outer"] + ["outer"] * 2 + ["inner", "ball"] + ["inner"] * 2
    s = _scores(np.array(y_true), np.array(y_pred))
    assert s["accuracy"] == pytest.approx(6 / 10)
    # recalls 0.75, 1, 0.5, 0: balanced over the four classes 0.5625
    assert s["balanced_accuracy"] == pytest.approx((0.75 + 1 + 0.5 + 0) / 4)
    # three classes: the 8 normal/outer/inner rows, 6 right ("ball" on inner is wrong)
    assert s["accuracy_3class"] == pytest.approx(6 / 8)
    assert s["balanced_accuracy_3class"] == pytest.approx((0.75 + 1 + 0.5) / 3)
    # a class absent from the test rows is left out of the balanced scores
    s = _scores(np.array(["healthy", "outer"]), np.array(["healthy", "healthy"]))
    assert s["balanced_accuracy"] == pytest.approx(0.5)


@pytest.fixture(scope="module")
def sim_and_real():
    """Simulated training runs, and 'real' rows from other seeds with files and groups."""
    def runs(kinds, seed0, rpm=1797.0):
        X = [bp.simulate(bp.Scene("6205", rpm=rpm, fs=FS, duration_s=1.0, resonance_hz=3000,
                                  fault=bp.Fault(k) if k != "healthy" else None,
                                  noise_rms=0.4, seed=seed0 + i), model="impulse").accel
             for i, k in enumerate(kinds)]
        return np.array(X)

    kinds = ["healthy", "outer", "inner", "ball"] * 4
    X = runs(kinds, 0)
    meta = pd.DataFrame({"label": kinds, "group": range(len(kinds)), "rpm": 1797.0,
                         "bearing": "6205", "fs": FS})
    real_kinds = ["healthy", "healthy", "outer", "outer", "inner", "inner", "ball", "ball"]
    Xr = runs(real_kinds, 1000, rpm=1772.0)
    files = [f"{k}_{i // 2}.mat" for i, k in enumerate(real_kinds)]
    meta_r = pd.DataFrame({"label": real_kinds, "group": files, "file": files,
                           "rpm": 1772.0, "bearing": "6205", "fs": FS})
    return X, meta, Xr, meta_r


def test_sim2real_spread_predictions_and_recommended(sim_and_real, tmp_path, monkeypatch):
    X, meta, Xr, meta_r = sim_and_real
    assert RECOMMENDED[0] in CLASSIFIERS and RECOMMENDED[1] in FEATURE_SETS
    # "recommended" as k nearest neighbours on the evidence features: the same plumbing,
    # without five fits of a 300-tree forest (seconds each on a busy machine)
    monkeypatch.setattr(benchmark_module, "RECOMMENDED", ("knn", "evidence"))
    monkeypatch.setattr(report_module, "RECOMMENDED", ("knn", "evidence"))
    # logistic on the evidence features shares them with "recommended": one feature
    # computation
    result = run_benchmark(X, meta, real=(Xr, meta_r), splits=["sim2real"],
                           models=["envelope", "logistic", "recommended"],
                           features="evidence", seeds=5)
    pred = result.predictions
    # one row per real segment and model, with the recording's file and group
    assert len(pred) == 3 * len(Xr)
    assert not pred.duplicated(["model", "row"]).any()
    assert (pred.split == "sim2real").all()
    assert (pred.file.to_numpy() == np.tile(meta_r.file, 3)).all()
    assert {"model", "y_true", "y_pred", "file", "group"} <= set(pred.columns)
    # five training seeds per learned model, one for the seedless diagnoser
    spread = result.spread
    assert spread.groupby("model").size().to_dict() == {
        "envelope": 1, "logistic": 5, "recommended": 5}
    assert sorted(spread.loc[spread.model == "recommended", "seed"]) == [0, 1, 2, 3, 4]
    # the table is the first seed's, scored from the predictions
    first = spread[(spread.model == "recommended") & (spread.seed == 0)].iloc[0]
    row = result.table.set_index("model").loc["recommended"]
    assert row["balanced_accuracy"] == first["balanced_accuracy"]
    part = pred[pred.model == "recommended"]
    assert row["accuracy"] == pytest.approx((part.y_true == part.y_pred).mean())

    paths = write_report(result, tmp_path)
    text = paths["markdown"].read_text()
    assert "Three classes (normal, outer, inner" in text and "5 training seeds" in text
    # every pipeline is named step by step
    assert "`recommended`: `evidence` features" in text and "k nearest neighbours" in text
    assert "`logistic`: `evidence` features" in text
    assert paths["spread"].exists() and paths["confusion_sim2real"].exists()
    table = sim2real_table(result).set_index("model")
    assert table.loc["recommended", "seeds"] == 5 and table.loc["envelope", "seeds"] == 1


def test_bad_train_seeds_are_refused(sim_and_real, tmp_path):
    X, meta, Xr, meta_r = sim_and_real
    with pytest.raises(ValueError, match=r"seeds \(--train-seeds\) must be an int >= 1"):
        run_benchmark(X, meta, real=(Xr, meta_r), splits=["sim2real"], seeds=0)
    with pytest.raises(SystemExit):
        main(["benchmark", str(tmp_path / "none"), "--out", str(tmp_path / "r"),
              "--train-seeds", "x"])
