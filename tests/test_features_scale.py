"""Scale robustness: the same signal at 1e-300 or 1e200 m/s^2 gives the same scale-free
results (shape indicators, kurtogram, fault-band levels) and scaled results (RMS, SES)
that are the unit-scale ones times the scale wherever the float range holds them.

Before, a signal of 1e200 squared to inf (kurtogram NaN, crest factor 0) and one of
1e-300 to 0 (crest factor inf). The analyses now work on a copy scaled exactly to unit
peak. Tolerances: the scaled inputs ``x * s`` differ from ``x`` by one rounding per
sample (s is no power of two), so results agree to 1e-9 relative, not bit for bit;
a power-of-two scale gives bit-identical results.
"""

import numpy as np
import pytest

from ballpass import features as F

FS = 12_000.0
BPFO = 1797 / 60 * 3.5848    # the 6205's BPFO at 1797 rpm, Hz


@pytest.fixture(scope="module")
def x():
    t = np.arange(24_000) / FS
    phase = (t * BPFO) % 1.0 / BPFO                  # time since the last impact, s
    ring = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    return ring + 0.2 * np.random.default_rng(0).standard_normal(t.size)


SCALES = [1e200, 1e-300, 1e300, 1e-305]
SHAPE = ("crest_factor", "kurtosis", "skewness", "shape_factor", "impulse_factor",
         "clearance_factor")


@pytest.mark.parametrize("s", SCALES)
def test_indicators_are_scale_free_and_levels_scale(x, s):
    ref, got = F.indicators(x), F.indicators(x * s)
    for name in SHAPE:
        np.testing.assert_allclose(got[name], ref[name], rtol=1e-9, err_msg=name)
    for name in ("rms", "peak", "peak_to_peak"):
        assert np.isfinite(got[name])
        np.testing.assert_allclose(got[name] / s, ref[name], rtol=1e-9, err_msg=name)


def test_power_of_two_scale_is_bit_identical(x):
    ref, got = F.indicators(x), F.indicators(np.ldexp(x, 600))
    assert all(got[k] == ref[k] for k in SHAPE)
    assert got["rms"] == np.ldexp(ref["rms"], 600)


@pytest.mark.parametrize("s", SCALES)
def test_kurtogram_and_fault_bands_are_scale_free(x, s):
    ref, got = F.fast_kurtogram(x, FS), F.fast_kurtogram(x * s, FS)
    assert got.best_band == ref.best_band
    np.testing.assert_allclose(got.kurtosis, ref.kurtosis, rtol=1e-9, atol=1e-12)
    a, b = F.fault_band_features(x, FS, "6205", 1797), F.fault_band_features(x * s, FS,
                                                                            "6205", 1797)
    assert a["bpfo_1"] > 10           # the signal's fault shows
    for name in a:
        np.testing.assert_allclose(b[name], a[name], rtol=1e-9, atol=1e-9, err_msg=name)


@pytest.mark.parametrize("s, squared", [(1e200, False), (1e-300, False), (1e150, True),
                                        (1e-150, True)])
def test_envelope_spectrum_scales_with_the_signal(x, s, squared):
    """unit (|envelope|) or unit^2 (squared): 1e-300 and 1e200 m/s^2 amplitude spectra,
    1e+-150 squared ones (1e+-300 m^2/s^4) are all within the float range."""
    f, ref = F.envelope_spectrum(x, FS, (2000, 4000), squared=squared)
    _, got = F.envelope_spectrum(x * s, FS, (2000, 4000), squared=squared)
    assert np.isfinite(got).all()
    np.testing.assert_allclose(got / s / (s if squared else 1.0), ref, rtol=1e-9,
                               atol=1e-12 * ref.max())


def test_squared_envelope_beyond_the_float_range_is_inf_not_nan(x):
    _, ses = F.envelope_spectrum(x * 1e200, FS, (2000, 4000), squared=True)
    assert not np.isnan(ses).any() and np.isinf(ses.max())


@pytest.mark.parametrize("s", [1e200, 1e-300])
def test_envelope_analysis_is_scale_free(x, s):
    ref = F.envelope_analysis(x, FS, bearing="6205", rpm=1797)
    got = F.envelope_analysis(x * s, FS, bearing="6205", rpm=1797)
    assert got.band == ref.band
    for name in ref.fault_bands:
        np.testing.assert_allclose(got.fault_bands[name], ref.fault_bands[name], rtol=1e-9,
                                   atol=1e-9, err_msg=name)
    for name in SHAPE:
        np.testing.assert_allclose(got.indicators[name], ref.indicators[name], rtol=1e-9)
    assert not np.isnan(got.ses).any()


def test_bandpass_scales_and_refuses_unstable_orders(x):
    y = F.bandpass(x, FS, (2000, 4000))
    np.testing.assert_allclose(F.bandpass(x * 1e-300, FS, (2000, 4000)) / 1e-300, y,
                               rtol=1e-9, atol=1e-12)
    # this band's order-98 sections lost their accuracy: unit noise came out at RMS
    # 2.5e12 where a Butterworth's gain never exceeds 1; refused at the design
    noise = np.random.default_rng(0).standard_normal(12_000)
    with pytest.raises(ValueError, match=r"order=98: .* numerically unstable .* use a lower "
                                         "order"):
        F.bandpass(noise, FS, (653.843, 2992.77), order=98)
    ok = F.bandpass(noise, FS, (653.843, 2992.77), order=40)      # a stable order
    assert np.std(ok) < np.std(noise)
    with pytest.raises(ValueError, match="order=100: .* cannot be designed"):
        F.bandpass(noise, FS, (0, 5990), order=100)       # scipy: OverflowError before
