"""Statistical indicators: closed forms, scipy agreement, invariances, validation."""

import numpy as np
import pytest
import scipy.stats

from ballpass import features as F


def sine(n=1000, cycles=5, amplitude=3.0):
    """An integer number of cycles, so the sample moments equal the continuous ones."""
    return amplitude * np.sin(2 * np.pi * cycles * np.arange(n) / n)


def test_sine_closed_forms():
    """Sine of amplitude a: rms a/sqrt2, crest sqrt2, Pearson kurtosis 3/2, skewness 0.

    For whole cycles sampled uniformly the discrete sums of sin^2 and sin^4 are exact,
    and the mean of |sin| over m samples per cycle is (2/m) cot(pi/m) exactly (-> 2/pi,
    giving the textbook shape factor pi/(2 sqrt2) and impulse factor pi/2). So every
    value is checked at rounding level, rtol 1e-12.
    """
    a, m = 3.0, 200  # amplitude; samples per cycle (1000 samples, 5 cycles)
    ind = F.indicators(sine(n=1000, cycles=5, amplitude=a))
    mean_abs = a * (2 / m) / np.tan(np.pi / m)
    np.testing.assert_allclose(ind["rms"], a / np.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(ind["peak"], a, rtol=1e-12)
    np.testing.assert_allclose(ind["peak_to_peak"], 2 * a, rtol=1e-12)
    np.testing.assert_allclose(ind["crest_factor"], np.sqrt(2), rtol=1e-12)
    np.testing.assert_allclose(ind["kurtosis"], 1.5, rtol=1e-12)
    assert abs(ind["skewness"]) < 1e-12
    np.testing.assert_allclose(ind["shape_factor"], a / np.sqrt(2) / mean_abs, rtol=1e-12)
    np.testing.assert_allclose(ind["impulse_factor"], a / mean_abs, rtol=1e-12)
    np.testing.assert_allclose(ind["shape_factor"], np.pi / (2 * np.sqrt(2)), rtol=1e-4)
    assert list(ind) == list(F.INDICATORS)


def test_gaussian_noise_kurtosis_is_three():
    """Pearson kurtosis of Gaussian noise is 3; its standard error is sqrt(24/n) = 0.015
    for n = 1e5, so 5 standard errors: 0.08."""
    x = np.random.default_rng(0).standard_normal(100_000)
    assert abs(F.indicators(x)["kurtosis"] - 3.0) < 0.08


def test_agree_with_scipy_stats():
    x = np.random.default_rng(1).gamma(2.0, size=(3, 5000)) - 1.0  # skewed, with a mean
    ind = F.indicators(x)
    # The moments are formed as scipy.stats forms them: equal to rounding (rtol 1e-13;
    # measured: bit for bit). A moment about 0 instead of the mean, or an unbiased
    # estimator, differs by > 1e-4.
    np.testing.assert_allclose(ind["kurtosis"], scipy.stats.kurtosis(x, axis=-1, fisher=False),
                               rtol=1e-13)
    np.testing.assert_allclose(ind["skewness"], scipy.stats.skew(x, axis=-1), rtol=1e-13)
    np.testing.assert_allclose(ind["rms"], np.sqrt(np.mean(x**2, axis=-1)))
    np.testing.assert_allclose(ind["peak_to_peak"], np.ptp(x, axis=-1))
    a = np.abs(x)
    np.testing.assert_allclose(ind["clearance_factor"], a.max(-1) / np.mean(np.sqrt(a), -1) ** 2)


@pytest.mark.parametrize("scale", [-3.7, 0.01, 250.0])
def test_scale_invariance(scale):
    """Level indicators scale with |a|; shape indicators do not (skewness flips sign with
    a). Only rounding differs: rtol 1e-12."""
    x = np.random.default_rng(2).laplace(size=4000)
    base, scaled = F.indicators(x), F.indicators(scale * x)
    for name in ("rms", "peak", "peak_to_peak"):
        np.testing.assert_allclose(scaled[name], abs(scale) * base[name], rtol=1e-12)
    for name in ("crest_factor", "kurtosis", "shape_factor", "impulse_factor", "clearance_factor"):
        np.testing.assert_allclose(scaled[name], base[name], rtol=1e-12)
    np.testing.assert_allclose(scaled["skewness"], np.sign(scale) * base["skewness"], rtol=1e-12)


def test_batched_equals_loop_axis_and_float32():
    X = np.random.default_rng(3).standard_t(5, size=(2, 3, 2000))
    batch = F.indicators(X)
    assert batch["rms"].shape == (2, 3)
    for i in range(2):
        for j in range(3):
            one = F.indicators(X[i, j])
            for name in F.INDICATORS:
                np.testing.assert_allclose(batch[name][i, j], one[name], rtol=1e-12)
    moved = F.indicators(np.moveaxis(X, -1, 0), axis=0)
    np.testing.assert_allclose(moved["kurtosis"], batch["kurtosis"], rtol=1e-12)
    # float32 storage: values agree to float32 resolution (~1e-7; kurtosis sums 4th
    # powers, so allow 1e-5).
    single = F.indicators(X.astype(np.float32))
    for name in F.INDICATORS:
        np.testing.assert_allclose(single[name], batch[name], rtol=1e-5, atol=1e-6)


def test_ratios():
    rng = np.random.default_rng(4)
    healthy = rng.standard_normal(20_000)
    faulty = 2.0 * healthy
    faulty[::500] += 30.0  # impacts
    r = F.indicator_ratios(faulty, healthy)
    assert set(r) == set(F.INDICATORS)
    assert r["rms"] > 2.0 and r["kurtosis"] > 3.0 and r["crest_factor"] > 1.5
    np.testing.assert_allclose(F.indicator_ratios(3 * healthy, healthy)["rms"], 3.0, rtol=1e-12)
    # broadcast: several faulty signals against one healthy reference
    batch = F.indicator_ratios(np.stack([faulty, healthy]), healthy)
    np.testing.assert_allclose(batch["rms"], [r["rms"], 1.0], rtol=1e-12)


@pytest.mark.parametrize("x", [np.array([]), np.array([1.0]), np.array([1.0, np.nan, 0.0])])
def test_bad_input(x):
    with pytest.raises(ValueError, match="^x "):
        F.indicators(x)
    with pytest.raises(ValueError, match="^x "):
        F.indicator_ratios(x, np.ones(10))


@pytest.mark.parametrize("seed", range(3))
def test_moments_are_those_of_scipy_stats_on_many_shapes(seed):
    """Heavy tails, a large mean, impulses, batches: Pearson kurtosis and skewness equal
    scipy.stats.kurtosis(fisher=False) and skew (bias=True) to 1e-13 relative."""
    rng = np.random.default_rng(seed)
    x = np.stack([rng.standard_t(3, 4001), 1e3 + rng.laplace(size=4001),
                  np.where(rng.random(4001) < 0.01, 50.0, 0.0) + rng.standard_normal(4001)])
    ind = F.indicators(x.reshape(3, 1, -1))
    np.testing.assert_allclose(ind["kurtosis"][:, 0], scipy.stats.kurtosis(x, axis=-1,
                               fisher=False), rtol=1e-13)
    np.testing.assert_allclose(ind["skewness"][:, 0], scipy.stats.skew(x, axis=-1), rtol=1e-13)


def test_variance_lost_in_rounding_reads_as_constant(recwarn):
    """A signal of a large constant that changes only in its last bit (a stuck sensor
    around 1e8) has moments below rounding: scipy.stats warns and returns NaN there. The
    indicators give the dead-channel value 0, without NaN or warning."""
    x = 1e8 + np.spacing(1e8) * (np.random.default_rng(5).random(1000) < 0.5)
    assert np.ptp(x) > 0  # not exactly constant
    ind = F.indicators(x)
    assert ind["kurtosis"] == 0.0 and ind["skewness"] == 0.0
    assert all(np.isfinite(v) for v in ind.values())
    assert not recwarn.list


def test_offset_sine_closed_forms_use_the_rms_not_the_std():
    """1 + sin: the level indicators include the mean (DC), the moments do not.

    rms = sqrt(1 + 1/2) = sqrt(1.5) while the standard deviation is sqrt(0.5), so a
    crest factor over the std instead of the RMS reads 2 / sqrt(0.5) = 2.83 instead of
    2 / sqrt(1.5) = 1.633 (likewise the shape factor, sqrt(0.5) instead of sqrt(1.5));
    moments about 0 instead of the mean give a kurtosis 2.2 instead of 1.5. For whole
    cycles sampled uniformly the sums of sin, sin^2, sin^3 and sin^4 are exact and
    1 + sin >= 0, so mean(|x|) = 1: rtol 1e-12. mean(sqrt(1 + sin)) = 2 sqrt(2) / pi
    only in the limit (sqrt(1 + sin) has kinks where sin = -1): at 200 samples per cycle
    the clearance factor is 4e-5 from pi^2 / 4 (measured), hence rtol 2e-4.
    """
    x = 1.0 + sine(n=1000, cycles=5, amplitude=1.0)
    ind = F.indicators(x)
    np.testing.assert_allclose(ind["rms"], np.sqrt(1.5), rtol=1e-12)
    np.testing.assert_allclose(ind["peak"], 2.0, rtol=1e-12)
    np.testing.assert_allclose(ind["peak_to_peak"], 2.0, rtol=1e-12)
    np.testing.assert_allclose(ind["crest_factor"], 2.0 / np.sqrt(1.5), rtol=1e-12)
    np.testing.assert_allclose(ind["kurtosis"], 1.5, rtol=1e-12)
    assert abs(ind["skewness"]) < 1e-12
    np.testing.assert_allclose(ind["shape_factor"], np.sqrt(1.5), rtol=1e-12)
    np.testing.assert_allclose(ind["impulse_factor"], 2.0, rtol=1e-12)
    np.testing.assert_allclose(ind["clearance_factor"], np.pi**2 / 4, rtol=2e-4)
    # the scikit-learn transformer reports the same values
    row = F.IndicatorTransformer().fit_transform(x[None])[0]
    np.testing.assert_allclose(row, [ind[name] for name in F.INDICATORS], rtol=1e-12)
