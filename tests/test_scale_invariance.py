"""Scale does not decide: a recording times a constant (another amplifier gain, g instead
of m/s^2, a sensor of other sensitivity) gets the same verdicts and the same features."""

from pathlib import Path

import numpy as np
import pytest
import scipy.signal
import sklearn

from ballpass.diagnose import EnvelopeDiagnoser, envelope_evidence, make_features, make_pipeline

DATA = Path(__file__).parent / "data"
FS = 12_000.0
#: g -> m/s^2, and amplifiers far below and above it; 1e-6 and 1e6 cover a recording in
#: micro-g or a raw 24-bit integer count
GAINS = (9.80665, 1e-6, 1e-3, 1e3, 1e6)
#: float64 rounding of the rescaled samples (1e-16 relative) magnified by the FFTs and
#: the dB conversion: far below any difference a threshold or a tree split could see
TOL_DB = 1e-6


def real_segments():
    """One-second segments of real CWRU drive-end records (in g): two inner-race, two
    outer-race, and the healthy recording resampled from 48 to 12 kHz."""
    X, rpm, labels = [], [], []
    for name, label in (("cwru_12k_DE_IR007_0_DE_crop.npz", "inner"),
                        ("cwru_12k_DE_OR007at6_0_DE_crop.npz", "outer"),
                        ("cwru_12k_DE_IR021_0_DE_crop.npz", "inner"),
                        ("cwru_12k_DE_OR021at6_0_DE_crop.npz", "outer")):
        d = np.load(DATA / name)
        X += list(d["accel_g"].astype(float).reshape(-1, 12_000))
        rpm += [float(d["rpm"])] * 2
        labels += [label] * 2
    d = np.load(DATA / "cwru_Normal_0_48k_DE_crop.npz")
    X.append(scipy.signal.resample_poly(d["accel_g"].astype(float), 1, 4))
    rpm.append(float(d["rpm"]))
    labels.append("healthy")
    return np.array(X), np.array(rpm), np.array(labels)


X, RPM, LABELS = real_segments()


@pytest.mark.parametrize("gain", GAINS)
def test_the_diagnoser_gives_the_same_verdicts_and_evidence(gain):
    est = EnvelopeDiagnoser("6205", fs=FS)
    reference = est.predict(X, rpm=RPM)
    assert (reference == LABELS).all()        # the segments are diagnosable at all
    assert (est.predict(gain * X, rpm=RPM) == reference).all()
    ev, ev_gain = (envelope_evidence(x, FS, "6205", RPM) for x in (X, gain * X))
    for family in ("outer", "inner", "ball"):
        np.testing.assert_allclose(ev_gain.evidence_db[family], ev.evidence_db[family],
                                   rtol=0, atol=TOL_DB)


@pytest.mark.parametrize("gain", (1e-3, 1e3))
def test_thresholds_fitted_at_one_gain_hold_at_another(gain):
    # A baseline recorded through one amplifier, the machine diagnosed through another:
    # the thresholds are dB over a background, so the gain cancels.
    healthy = X[LABELS == "healthy"]
    est = EnvelopeDiagnoser("6205", fs=FS).fit(healthy, ["healthy"], rpm=RPM[-1:])
    assert (est.predict(gain * X, rpm=RPM) == est.predict(X, rpm=RPM)).all()


@pytest.mark.parametrize("features", ["dimensionless", "bands", "evidence"])
def test_unitless_feature_sets_do_not_move_and_a_trained_model_agrees(features):
    # Planted: adding "rms" to the dimensionless indicators moves that column by the
    # gain and fails the first assertion.
    step = make_features(features, fs=FS)
    with sklearn.config_context(enable_metadata_routing=True):
        reference = step.transform(X, rpm=RPM)
        for gain in GAINS:
            np.testing.assert_allclose(step.transform(gain * X, rpm=RPM), reference,
                                       rtol=1e-9, atol=TOL_DB)
        # a model trained on the recordings as stored predicts the same at any gain
        pipe = make_pipeline("random_forest", features=features, fs=FS)
        pipe.fit(X, LABELS, rpm=RPM)
        for gain in GAINS:
            assert (pipe.predict(gain * X, rpm=RPM) == pipe.predict(X, rpm=RPM)).all()


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e200, 1e300])
def test_envelope_functions_at_extreme_scales(scale):
    """Found by benchmarks/abuse_sweep.py: at 1e+-100..200 the spectral kurtosis and the
    envelope evidence were inf/NaN (|X|^4, squared envelopes overflowing), the envelope
    was inf and order_envelope_spectrum refused the signal in scipy's words. Computed on
    a copy scaled exactly by a power of two, the scale-free results agree to rounding
    (1e-9: the rescaled samples differ by one rounding of x * scale) and the scaled ones
    are exact multiples, inf only beyond the float range."""
    from ballpass import features as F

    x = np.random.default_rng(3).standard_normal(12_000)
    _, sk = F.spectral_kurtosis(x, FS)
    _, sk_s = F.spectral_kurtosis(x * scale, FS)
    assert np.allclose(sk_s, sk, rtol=1e-9, atol=1e-9)
    ev, ev_s = envelope_evidence(x, FS, "6205", 1797), envelope_evidence(x * scale, FS,
                                                                        "6205", 1797)
    for fault in ev.evidence_db:
        assert np.allclose(ev_s.evidence_db[fault], ev.evidence_db[fault], atol=TOL_DB)
    e, e_s = F.envelope(x, FS, (2000, 4000)), F.envelope(x * scale, FS, (2000, 4000))
    assert np.allclose(e_s / scale, e, rtol=1e-9)
    # unit^2 beyond the float range at these scales: 0 or inf, never NaN nor a refusal
    _, amp_s = F.order_envelope_spectrum(x * scale, FS, rpm=1797, band=(2000, 4000))
    assert not np.isnan(amp_s).any()
