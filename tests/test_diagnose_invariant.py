"""EvidenceTransformer: the diagnoser's evidence as features a machine cannot shift."""

from pathlib import Path

import numpy as np
import pytest
import sklearn
from sklearn.utils.estimator_checks import parametrize_with_checks

import ballpass as bp
from ballpass.diagnose import EvidenceTransformer, envelope_evidence, make_pipeline
from ballpass.diagnose.invariant import evidence_feature_names

DATA = Path(__file__).parent / "data"
FS = 12_000.0
ORDERS_6205 = {"outer": 3.5848, "inner": 5.4152}


@parametrize_with_checks([EvidenceTransformer()])
def test_sklearn_compatible(estimator, check):
    check(estimator)


def impacts(order: float, rpm: float, seconds: float = 1.0, seed: int = 0) -> np.ndarray:
    """Decaying 3 kHz bursts at ``order`` x shaft speed in a little white noise."""
    t = np.arange(round(seconds * FS)) / FS
    f = order * rpm / 60.0
    phase = (t * f) % 1.0 / f                               # s since the last impact
    x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    return x + 0.2 * np.random.default_rng(seed).standard_normal(t.size)


def test_names_match_the_columns_and_the_family_reads_highest():
    rpms = np.array([1730.0, 1797.0, 1730.0, 1797.0])
    X = np.stack([impacts(ORDERS_6205[k], r, seed=i) for i, (k, r) in
                  enumerate(zip(["outer", "outer", "inner", "inner"], rpms, strict=True))])
    tr = EvidenceTransformer("6205", fs=FS).set_output(transform="pandas")
    f = tr.fit_transform(X, rpm=rpms)
    assert f.columns.tolist() == evidence_feature_names()
    assert f.shape == (4, 3 + 27 + 48)
    # the family of the impacts reads highest, by a wide margin (noise reads a few dB)
    for row, family in enumerate(["outer", "outer", "inner", "inner"]):
        other = "inner" if family == "outer" else "outer"
        assert f[f"{family}_evidence_db"].iloc[row] > f[f"{other}_evidence_db"].iloc[row] + 6
    # the evidence columns are envelope_evidence's, not a copy that drifts from it
    ev = envelope_evidence(X, FS, "6205", rpms)
    np.testing.assert_array_equal(f["outer_1xBPFO_db"], ev.levels_db["outer"][:, 0])
    # 3xBPFO (10.75 orders) and 2xBPFI (10.83) share a slip window: judged for neither
    assert (f["outer_3xBPFO_db"] == 0).all() and (f["inner_2xBPFI_db"] == 0).all()


def test_the_envelope_spectrum_is_on_an_order_axis():
    # The same outer-race fault at two speeds 10 % apart: in Hz its BPFO moves by
    # 10.7 Hz, in orders it stays at 3.585, in the bin [3.5, 3.75). Planted: binning the
    # SES by frequency / 30 Hz (a fixed speed) puts the slow row's line at 3.23 orders,
    # in [3.0, 3.25), and fails.
    rpms = np.array([1620.0, 1797.0])
    X = np.stack([impacts(ORDERS_6205["outer"], r, seed=i) for i, r in enumerate(rpms)])
    f = EvidenceTransformer("6205", fs=FS).set_output(transform="pandas").fit_transform(
        X, rpm=rpms)
    ses = f.filter(like="ses_order_")
    assert (ses.idxmax(axis=1) == "ses_order_3.5").all()
    # and the line stands far above the median of the spectrum (impacts 5x the noise)
    assert (ses["ses_order_3.5"] > 15).all()


def test_no_feature_changes_with_the_gain_of_a_real_recording():
    # A real CWRU drive-end inner-race second in g, in m/s^2 and through amplifiers of
    # gain 1e-3 and 1e3: every feature is a ratio of levels of the same signal or an
    # order. The tolerance, 1e-6 dB, is float64 rounding of the rescaled samples
    # (1e-16 relative) magnified by the FFTs, far below any meaningful difference.
    # Planted: the order-SES in dB over a fixed 1 (m/s^2)^2 instead of its median moves
    # by 20 log10(gain) and fails.
    d = np.load(DATA / "cwru_12k_DE_IR007_0_DE_crop.npz")
    X = d["accel_g"].astype(float).reshape(2, 12_000)
    tr = EvidenceTransformer("6205", fs=FS, rpm=float(d["rpm"])).fit(X)
    reference = tr.transform(X)
    assert np.isfinite(reference[:, :3]).all()
    for gain in (9.80665, 1e-3, 1e3):
        np.testing.assert_allclose(tr.transform(gain * X), reference, rtol=0, atol=1e-6)
    # float32 input (as a .wav or a Parquet shard holds it) gives the same to 0.01 dB:
    # float32 keeps 7 digits, a level near the background moves by 4.3 dB x 1e-7
    np.testing.assert_allclose(tr.transform((1e3 * X).astype(np.float32)), reference,
                               rtol=0, atol=1e-2)


def test_quiet_rows_read_zero_and_short_rows_nan():
    X = np.zeros((2, 12_000))                             # no band holds any signal
    assert (EvidenceTransformer().fit_transform(X) == 0.0).all()
    assert np.isnan(EvidenceTransformer().fit_transform(np.ones((2, 100)))).all()


@pytest.mark.parametrize("params, match", [
    ({"harmonics": 0}, "harmonics must be an int >= 1"),
    ({"max_order": -1.0}, "max_order must be a positive number"),
    ({"order_step": 20.0}, "order_step = 20 exceeds max_order = 12"),
    ({"fs": -5.0}, "fs must be a finite number > 0"),
])
def test_bad_parameters_are_refused(params, match):
    with pytest.raises(ValueError, match=match):
        EvidenceTransformer(**params).fit(np.zeros((2, 1000)))


def test_the_evidence_pipeline_learns_faults_from_simulations():
    # Pipeline plumbing (rpm routed to the transformer, NaNs imputed): trained on a few
    # simulated runs, it names new runs' faults. The impulse model at a 20 dB impact-
    # to-noise ratio makes this easy on purpose; the sim-to-real score is a benchmark.
    def runs(seed0):
        X, y, rpm = [], [], []
        for i, kind in enumerate(["outer", "inner", None] * 4):
            r = 1730.0 + 20 * (i % 4)
            scene = bp.Scene("6205", rpm=r, fs=FS, duration_s=1.0, resonance_hz=3000,
                             fault=bp.Fault(kind) if kind else None, noise_rms=0.3,
                             seed=seed0 + i)
            X.append(bp.simulate(scene, model="impulse").accel)
            y.append(kind or "healthy")
            rpm.append(r)
        return np.array(X), np.array(y), np.array(rpm)

    X, y, rpm = runs(0)
    Xt, yt, rpmt = runs(100)
    pipe = make_pipeline("random_forest", features="evidence", fs=FS)
    with sklearn.config_context(enable_metadata_routing=True):
        pipe.fit(X, y, rpm=rpm)
        assert (pipe.predict(Xt, rpm=rpmt) == yt).mean() >= 11 / 12


def test_the_combined_features_are_the_evidence_then_the_dimensionless_ones():
    # Closed-form outer-race impacts at two speeds: the `combined` set is the `evidence`
    # set followed by the `dimensionless` set, column for column (the same transformers,
    # so exactly equal), the impacts' family reads highest in it, and no column moves
    # with the amplifier gain (1e-6 dB and 1e-9 relative: float64 rounding through the
    # FFTs; kurtosis and crest factor are ratios of moments). Planted: `combined` without
    # the fault bands is 21 columns short and fails.
    from ballpass.diagnose import make_features

    rpms = np.array([1730.0, 1797.0])
    X = np.stack([impacts(ORDERS_6205["outer"], r, seed=i) for i, r in enumerate(rpms)])

    def features(name, x):
        with sklearn.config_context(enable_metadata_routing=True):
            return make_features(name, fs=FS).fit_transform(x, rpm=rpms)

    combined = features("combined", X)
    np.testing.assert_array_equal(
        combined, np.hstack([features("evidence", X), features("dimensionless", X)]))
    assert combined.shape == (2, 78 + 27)
    names = evidence_feature_names()
    outer, inner = names.index("outer_evidence_db"), names.index("inner_evidence_db")
    assert (combined[:, outer] > combined[:, inner] + 6).all()
    np.testing.assert_allclose(features("combined", 1e3 * X), combined, rtol=1e-9, atol=1e-6)
