"""scikit-learn transformers over the feature functions."""

import numpy as np
import pytest
import sklearn
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import make_pipeline
from sklearn.utils.estimator_checks import parametrize_with_checks

from ballpass import features as F


@parametrize_with_checks([F.IndicatorTransformer(), F.FaultBandTransformer()])
def test_sklearn_compatible(estimator, check):
    check(estimator)


def test_indicator_transformer_matches_function_and_pandas_output():
    X = np.random.default_rng(0).standard_normal((5, 2000))
    tr = F.IndicatorTransformer(indicators=["kurtosis", "rms"]).set_output(transform="pandas")
    out = tr.fit_transform(X)
    assert out.columns.tolist() == ["kurtosis", "rms"]
    np.testing.assert_allclose(out["rms"], F.indicators(X)["rms"])
    with pytest.raises(ValueError, match="^indicators"):
        F.IndicatorTransformer(indicators=["rms", "nope"]).fit(X)


def test_fault_band_transformer_per_row_rpm():
    """Rows at different speeds: per-row rpm puts each row's BPFO window on its line."""
    fs, n = 12_000.0, 24_000
    t = np.arange(n) / fs
    rpms = np.array([1500.0, 1800.0])
    bpfo = 3.5848 * rpms / 60
    X = np.stack([np.exp(-600 * ((t * f) % 1 / f)) * np.sin(2 * np.pi * 3000 * t) for f in bpfo])
    X += 0.05 * np.random.default_rng(2).standard_normal(X.shape)
    tr = F.FaultBandTransformer("6205", fs=fs, rpm=1650.0).set_output(transform="pandas")
    right = tr.fit_transform(X, rpm=rpms)
    wrong = tr.transform(X)  # the single default rpm looks 9 % off both lines
    assert (right["bpfo_1"] > 15).all()
    assert (right["bpfo_1"] - wrong["bpfo_1"] > 10).all()
    assert right.columns.tolist() == F.fault_band_names()


def test_rpm_routed_through_a_pipeline():
    """sklearn metadata routing carries per-row rpm through a Pipeline to transform."""
    rng = np.random.default_rng(1)
    X = rng.standard_normal((6, 4000))
    y = np.array([0, 1] * 3)
    rpm = np.linspace(1700, 1800, 6)
    with sklearn.config_context(enable_metadata_routing=True):
        pipe = make_pipeline(
            F.FaultBandTransformer(fs=12_000.0, harmonics=1).set_transform_request(rpm=True),
            LogisticRegression().set_fit_request(sample_weight=False),
        )
        pipe.fit(X, y, rpm=rpm)
        direct = F.FaultBandTransformer(fs=12_000.0, harmonics=1).transform(X, rpm=rpm)
        np.testing.assert_allclose(pipe[0].transform(X, rpm=rpm), direct)
        assert pipe.predict(X, rpm=rpm).shape == (6,)
