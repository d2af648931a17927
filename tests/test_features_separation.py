"""Discrete/random separation (ballpass.features.separate_discrete): the periodic part
of known synthetic signals is removed, the random part kept, and a bearing fault hidden
under strong periodic lines reappears in the squared envelope spectrum."""

import numpy as np
import pytest

from ballpass.features import envelope_spectrum, separate_discrete

FS = 20_000.0
N = 40_000  # 2 s
T = np.arange(N) / FS
RPM_A, RPM_B = 1500.0, 1500.0 * 15 / 32  # a pinion shaft and its gear's shaft


def _periodic(rng, rpm, n_harm, scale=1.0):
    """Harmonics of one shaft with random phases and 1/k amplitudes."""
    f0 = rpm / 60.0
    k = np.arange(1, n_harm + 1)[:, None]
    return scale * np.sum(np.cos(2 * np.pi * k * f0 * T + rng.uniform(0, 2 * np.pi, (n_harm, 1)))
                          / k, axis=0)


def _bearing_impacts(rng, rate_hz, resonance_hz=4000.0, jitter=0.01):
    """Impulse responses of a 4 kHz resonance (5 % damping) at ``rate_hz`` with random
    period jitter (slip): cyclostationary, not periodic."""
    periods = (1.0 + jitter * rng.standard_normal(int(rate_hz * T[-1]) + 2)) / rate_hz
    times = np.cumsum(periods)
    times = times[times < T[-1] - 0.01]
    x = np.zeros(N)
    w = 2 * np.pi * resonance_hz
    for t0 in times:
        i0 = int(np.ceil(t0 * FS))
        tau = T[i0:i0 + 200] - t0
        x[i0:i0 + 200] += np.exp(-0.05 * w * tau) * np.sin(w * tau)
    return x


def _prominence(x, rate_hz, band=(3000.0, 5000.0)):
    """SES line at rate_hz over the median SES level within +-30 Hz of it."""
    f, a = envelope_spectrum(x, FS, band=band)
    near = (np.abs(f - rate_hz) < 30) & (np.abs(f - rate_hz) > 3)
    line = a[np.abs(f - rate_hz) <= 1.0].max()
    return line / np.median(a[near])


def test_tsa_keeps_random_removes_periodic_two_shafts():
    rng = np.random.default_rng(1)
    periodic = _periodic(rng, RPM_A, 200) + _periodic(rng, RPM_B, 200)
    noise = 0.3 * rng.standard_normal(N)
    discrete, residual = separate_discrete(periodic + noise, FS, rpm=[RPM_A, RPM_B])
    np.testing.assert_allclose(discrete + residual, periodic + noise, atol=1e-12)
    # the synchronous average of K revolutions keeps noise/sqrt(K) of the random part
    # (K = 50 pinion, 23 gear revolutions): the residual differs from the noise by
    # about sqrt(1/50 + 1/23) = 0.25 of its rms; 0.35 leaves room for the estimate's
    # own scatter. A planted off-by-one revolution count or a wrong angle scale fails.
    k_a, k_b = RPM_A / 60 * T[-1], RPM_B / 60 * T[-1]
    bound = 1.4 * np.sqrt(1 / k_a + 1 / k_b)
    assert np.std(residual - noise) < bound * np.std(noise)
    # without noise one shaft's periodic part is removed to the interpolation error of
    # the angular resampling (cubic splines on a 4x upsampled signal): 1e-3 of its rms
    one = _periodic(rng, RPM_A, 200)
    assert np.std(separate_discrete(one, FS, rpm=RPM_A)[1]) < 1e-3 * np.std(one)
    # two shafts: each shaft's lines that are not the other's harmonics leak into the
    # other's average by O(1/K) with K >= 23 revolutions: 3 % of the periodic rms
    _d, res_clean = separate_discrete(periodic, FS, rpm=[RPM_A, RPM_B])
    assert np.std(res_clean) < 0.03 * np.std(periodic)
    # one shaft only: the other shaft's lines stay in the residual
    _d, res_a = separate_discrete(periodic + noise, FS, rpm=RPM_A)
    assert np.std(res_a - noise) > 0.5 * np.std(noise)


@pytest.mark.parametrize("pulses_per_rev", [1, 2])
def test_tacho_gives_the_same_separation_as_rpm(pulses_per_rev):
    rng = np.random.default_rng(2)
    x = _periodic(rng, RPM_A, 100) + 0.2 * rng.standard_normal(N)
    tacho = (np.mod(pulses_per_rev * RPM_A / 60 * T, 1.0) < 0.1).astype(float)
    _d, r_rpm = separate_discrete(x, FS, rpm=RPM_A)
    _d, r_tacho = separate_discrete(x, FS, tacho=tacho, pulses_per_rev=pulses_per_rev)
    # the tachometer's pulses are located to a fraction of a sample (linear
    # interpolation of the edge): the two residuals agree to 2 % of the signal
    assert np.std(r_rpm - r_tacho) < 0.02 * np.std(x)


# "lp" is left out: an AR(100) model cannot predict the 98 lines of this signal (SES
# prominence after it: 1.5); it needs fewer, stronger lines
@pytest.mark.parametrize("method", ["tsa", "drs"])
def test_masked_bearing_fault_found_after_separation(method):
    rng = np.random.default_rng(3)
    bpfi = 7.43 * RPM_A / 60  # not a harmonic of either shaft
    # a gear-like periodic part: mesh harmonics (15 pinion teeth) with sidebands at both
    # shaft rates, strong through the 3-5 kHz demodulation band, mask the impacts
    f_a, f_b = RPM_A / 60, RPM_B / 60
    periodic = np.zeros(N)
    for h in range(1, 15):
        for side_a, side_b, amp in [(0, 0, 1.0), (1, 0, 0.3), (-1, 0, 0.3), (0, 1, 0.3),
                                    (0, -1, 0.3), (2, 0, 0.1), (-2, 0, 0.1)]:
            f = 15 * h * f_a + side_a * f_a + side_b * f_b
            periodic += 8.0 * amp * np.cos(2 * np.pi * f * T + rng.uniform(0, 2 * np.pi))
    bearing = _bearing_impacts(rng, bpfi)
    x = periodic + bearing + 0.05 * rng.standard_normal(N)
    # found = the SES line at BPFI stands 10x above its neighbourhood (a healthy
    # signal's ratio is ~1-3); the clean bearing signal's ratio is far above
    assert _prominence(bearing, bpfi) > 30
    assert _prominence(x, bpfi) < 10
    _d, residual = separate_discrete(x, FS, rpm=[RPM_A, RPM_B] if method == "tsa" else None,
                                     method=method)
    assert _prominence(residual, bpfi) > 10


def test_axis_and_batches():
    rng = np.random.default_rng(4)
    x = np.stack([_periodic(rng, RPM_A, 50) + 0.1 * rng.standard_normal(N) for _ in range(2)])
    d0, r0 = separate_discrete(x, FS, rpm=RPM_A)
    d1, r1 = separate_discrete(x.T, FS, rpm=RPM_A, axis=0)
    np.testing.assert_allclose(r0, r1.T, atol=1e-12)
    np.testing.assert_allclose(r0[1], separate_discrete(x[1], FS, rpm=RPM_A)[1], atol=1e-12)


@pytest.mark.parametrize("kwargs, exc, match", [
    (dict(method="cepstrum"), ValueError, "method must be one of"),
    (dict(method="tsa"), ValueError, "needs the shaft speed"),
    (dict(rpm=-100.0), ValueError, "rpm must be finite and > 0"),
    (dict(rpm=1.0), ValueError, "at least 2 shaft revolutions"),
    (dict(rpm=1500.0, tacho=np.zeros(N)), ValueError, "not both"),
    (dict(method="lp", order=0), ValueError, "order must be an int >= 1"),
    (dict(method="lp", order=N), ValueError, "order must be < n_samples"),
    (dict(method="drs", delay=N), ValueError, "must not exceed n_samples"),
    (dict(fs=-1.0), ValueError, "fs must be"),
])
def test_bad_input(kwargs, exc, match):
    x = np.ones(N)
    fs = kwargs.pop("fs", FS)
    with pytest.raises(exc, match=match):
        separate_discrete(x, fs, **kwargs)


def test_bad_signal():
    with pytest.raises(ValueError, match="NaN"):
        separate_discrete(np.full(100, np.nan), FS, rpm=RPM_A)
    with pytest.raises(TypeError, match="real numeric"):
        separate_discrete(np.array(["a"] * 100), FS, rpm=RPM_A)


def test_linear_prediction_removes_a_few_strong_lines():
    rng = np.random.default_rng(5)
    bpfi = 7.43 * RPM_A / 60
    # five strong mesh-like tones in the 3-5 kHz band: an AR(100) model predicts them
    tones = sum(30.0 * np.cos(2 * np.pi * f * T + rng.uniform(0, 2 * np.pi))
                for f in (3125.0, 3500.0, 3875.0, 4250.0, 4625.0))
    bearing = _bearing_impacts(rng, bpfi)
    x = tones + bearing + 0.05 * rng.standard_normal(N)
    assert _prominence(x, bpfi) < 10
    _d, residual = separate_discrete(x, FS, method="lp")
    assert _prominence(residual, bpfi) > 10
    # the first `order` samples have no past: predicted backwards, they carry no
    # start-up transient (a forward-only filter leaves the tones there, ~100x the rms)
    assert np.max(np.abs(residual[:100])) < 10 * np.std(residual[1000:])
