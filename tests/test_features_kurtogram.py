"""Spectral kurtosis and the fast kurtogram."""

import math
from pathlib import Path

import numpy as np
import pytest
import scipy.fft
import scipy.signal

import ballpass as bp
from ballpass import features as F
from ballpass.features.kurtogram import _band_signals, _four_step, _tree

FS = 48_000.0


def impulses_in_noise(rng, n=48_000, fs=FS, f_res=9_000.0, rate=110.0, noise=0.5, zeta=0.02):
    """Impulses every 1/rate s through a resonance (damping ratio zeta), in white noise."""
    t = np.arange(n) / fs
    pulses = np.zeros(n)
    pulses[np.floor(np.arange(0, n / fs, 1 / rate) * fs).astype(int)] = 1.0
    m = int(fs / (zeta * f_res))  # about six decay time constants
    ring = np.exp(-2 * np.pi * zeta * f_res * t[:m]) * np.sin(2 * np.pi * f_res * t[:m])
    return scipy.signal.fftconvolve(pulses, ring)[:n] + noise * rng.standard_normal(n)


@pytest.mark.parametrize("f_res", [3_300.0, 9_500.0, 17_000.0])
def test_best_band_contains_the_excited_resonance(f_res):
    res = F.fast_kurtogram(impulses_in_noise(np.random.default_rng(0), f_res=f_res), FS)
    lo, hi = res.best_band
    assert lo <= f_res <= hi
    # Impulsive: for Gaussian noise a band of level <= 5 reads 0 +- 2/sqrt(750) = 0.07.
    assert res.best_kurtosis > 0.5


def test_grid_structure():
    """Antoni's 1/3-binary rows: levels 0, 1, log2 3, 2, 1 + log2 3, ..., nlevel."""
    res = F.fast_kurtogram(np.random.default_rng(1).standard_normal(48_000), FS, nlevel=7)
    assert res.kurtosis.shape == (14, 3 * 2**7)
    np.testing.assert_allclose(res.levels[:5], [0, 1, np.log2(3), 2, 1 + np.log2(3)])
    np.testing.assert_allclose(res.bandwidths, FS / 2 / 2**res.levels)
    assert res.freqs[0] == pytest.approx(FS / 2 / 384 / 2)
    assert res.density_db.shape == res.kurtosis.shape


def test_gaussian_noise_kurtogram_near_zero():
    """White Gaussian noise: every band's complex envelope is circular Gaussian, K = 0.

    Each band of row l holds about n / 2**(l+1) independent complex samples, so its
    estimate has standard deviation about 2 / sqrt(n / 2**(l+1)) (Antoni 2006);
    5 standard deviations bound all 14 x up to 128 bands with margin.
    """
    n = 48_000
    res = F.fast_kurtogram(np.random.default_rng(2).standard_normal(n), FS, nlevel=7)
    sigma = 2.0 / np.sqrt(n / 2 ** (res.levels + 1))
    assert np.all(np.abs(res.kurtosis) < 5 * sigma[:, None])


def test_stft_spectral_kurtosis_of_gaussian_noise_within_confidence_bound():
    """SK of Gaussian noise is 0 with standard deviation 2/sqrt(K) for K independent
    segments (Antoni 2006, sec. 4). With 3-sigma bounds, 0.27 % of bins may exceed by
    chance: allow 1 % (of 129 bins: 1). The mean over bins is 0 within 3 sigma/sqrt(bins).
    """
    k = 400
    x = np.random.default_rng(3).standard_normal(256 * k)
    f, sk = F.spectral_kurtosis(x, FS, nperseg=256, noverlap=0)
    assert f.shape == sk.shape == (129,)
    sigma = 2.0 / np.sqrt(k - 1)  # the STFT keeps only segments inside the signal
    assert np.mean(np.abs(sk) > 3 * sigma) <= 0.01
    assert abs(sk.mean()) < 3 * sigma / np.sqrt(f.size)


def test_stft_spectral_kurtosis_peaks_at_the_resonance():
    x = impulses_in_noise(np.random.default_rng(4), f_res=9_000.0)
    f, sk = F.spectral_kurtosis(x, FS, nperseg=256)
    assert abs(f[np.argmax(sk)] - 9_000.0) < 1_000.0  # within the resonance's half-power band


def cut_off_with_spikes(rng, cutoff, spike_band, spike_height):
    """12 kHz impacts at 3 kHz, low-passed at `cutoff` (an anti-aliasing filter), plus a
    few band-limited spikes in `spike_band` (Hz)."""
    fs, n = 12_000.0, 24_000
    x = impulses_in_noise(rng, n=n, fs=fs, f_res=3_000.0, rate=107.0, noise=0.2)
    x = scipy.signal.sosfiltfilt(scipy.signal.butter(12, cutoff, fs=fs, output="sos"), x)
    spikes = np.zeros(n)
    spikes[rng.choice(n, 4, replace=False)] = spike_height
    sos = scipy.signal.butter(4, spike_band, "bandpass", fs=fs, output="sos")
    return x + scipy.signal.sosfiltfilt(sos, spikes), fs


def test_content_floor_skips_dead_bands():
    """Above an anti-aliasing cut-off the spectrum is ~60 dB down; a few spikes there
    have enormous kurtosis (the CWRU 12 kHz files show this at 5.6-6 kHz). Such bands
    must not be chosen; the impacts at 3 kHz must."""
    x, fs = cut_off_with_spikes(np.random.default_rng(5), 4_500, (4_950, 5_200), 0.02)
    unrestricted = F.fast_kurtogram(x, fs, floor_db=-200.0)
    assert unrestricted.best_band[0] >= 4_500.0  # the artefact wins without the floor
    res = F.fast_kurtogram(x, fs)
    assert res.best_band[0] <= 3_000.0 <= res.best_band[1]
    assert not res.admissible[res.density_db < -20].any()


def test_bands_reaching_nyquist_are_not_chosen():
    """Clicks just below fs/2 strong enough to count as content (not 20 dB down) still
    do not win: the band hugging Nyquist holds anti-aliasing artefacts."""
    x, fs = cut_off_with_spikes(np.random.default_rng(6), 5_900, (5_500, 5_950), 10.0)
    res = F.fast_kurtogram(x, fs)
    top = res.kurtosis[:, -1].argmax()
    assert res.kurtosis[top, -1] > 3 * res.best_kurtosis  # the clicks are the most impulsive
    assert res.density_db[top, -1] > res.floor_db
    assert res.best_band[1] < fs / 2 and res.best_band[0] <= 3_000.0 <= res.best_band[1]


def test_min_bandwidth_is_respected():
    x = impulses_in_noise(np.random.default_rng(6))
    res = F.fast_kurtogram(x, FS, min_bandwidth=3_000.0)
    assert res.best_band[1] - res.best_band[0] >= 3_000.0
    narrow = F.fast_kurtogram(x, FS, min_bandwidth=0.0)
    assert narrow.best_kurtosis >= res.best_kurtosis


def test_batched_equals_loop_and_float32():
    rng = np.random.default_rng(7)
    X = np.stack([impulses_in_noise(rng, n=12_000, f_res=f) for f in (3_000.0, 12_000.0)])
    batch = F.fast_kurtogram(X, FS)
    assert batch.best_band.shape == (2, 2)
    for i, row in enumerate(X):
        one = F.fast_kurtogram(row, FS)
        np.testing.assert_allclose(batch.kurtosis[i], one.kurtosis, rtol=1e-10, atol=1e-12)
        assert tuple(batch.best_band[i]) == one.best_band
        # float32 storage changes the input by ~1e-7 relative; the grid follows.
        single = F.fast_kurtogram(row.astype(np.float32), FS)
        np.testing.assert_allclose(single.kurtosis, one.kurtosis, atol=1e-4)
        assert single.best_band == one.best_band


def test_short_signals_fall_back_to_the_full_band():
    res = F.fast_kurtogram(np.random.default_rng(8).standard_normal(100), FS)
    assert res.levels.tolist() == [0.0]
    assert res.best_band == (0.0, FS / 2)


@pytest.mark.parametrize(
    ("args", "kwargs", "name"),
    [
        ((np.array([]), FS), {}, "x"),
        ((np.ones(1), FS), {}, "x"),
        ((np.r_[np.ones(50), np.inf], FS), {}, "x"),
        ((np.ones((0, 100)), FS), {}, "x"),  # a batch of no signals
        ((np.ones(100), 0.0), {}, "fs"),
        ((np.ones(100), FS), {"nlevel": 6}, "nlevel"),
        ((np.ones(100), FS), {"nlevel": -1}, "nlevel"),
        ((np.ones(100), FS), {"min_bandwidth": -5.0}, "min_bandwidth"),
    ],
)
def test_kurtogram_bad_input(args, kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        F.fast_kurtogram(*args, **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [({"nperseg": 1}, "nperseg"), ({"noverlap": 300}, "noverlap"), ({"nperseg": 1024}, "x")],
)
def test_spectral_kurtosis_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        F.spectral_kurtosis(np.ones(1000), FS, **kwargs)


def test_plot_method(tmp_path):
    res = F.fast_kurtogram(impulses_in_noise(np.random.default_rng(9), n=12_000), FS)
    ax = res.plot()
    assert ax.get_xlabel() == "Frequency (Hz)"
    assert len(ax.patches) == 1  # the best band is outlined
    ax.figure.savefig(tmp_path / "k.png")
    with pytest.raises(ValueError, match="one signal"):
        F.fast_kurtogram(np.ones((2, 1000)), FS).plot()


# ---------------------------------------------------------------- golden references
def _level2_band_value(x, fs, centre_hz):
    """Kurtogram value of the level-2 band (width fs/8) centred at ``centre_hz``."""
    res = F.fast_kurtogram(x, fs, nlevel=3)
    row = int(np.flatnonzero(res.levels == 2.0)[0])
    col = int(np.argmin(np.abs(res.freqs - centre_hz)))
    return res.kurtosis[row, col]


@pytest.mark.parametrize("tones, expected", [
    # one tone: the complex envelope has constant modulus, E|c|^4 / (E|c|^2)^2 = 1
    ([(2250.0, 1.0)], -1.0),
    # two equal tones: |c|^2 = 2 + 2 cos(dw t), E|c|^2 = 2, E|c|^4 = 6 -> 6/4 - 2
    ([(2150.0, 1.0), (2350.0, 1.0)], -0.5),
    # AM tone, depth m = 1 (carrier 1, sidebands 1/2): (1 + 3m^2 + 3m^4/8) / (1 + m^2/2)^2 - 2
    ([(2250.0, 1.0), (2200.0, 0.5), (2300.0, 0.5)], (1 + 3 + 3 / 8) / 1.5**2 - 2),
])
def test_kurtosis_of_signals_with_a_closed_form(tones, expected):
    """Golden values: Antoni's kurtosis E|c|^4 / (E|c|^2)^2 - 2 of the complex envelope of
    tones on exact FFT bins, inside the flat part of the level-2 band 1500-3000 Hz (the
    raised-cosine edges start 375 Hz from its centre). Exact up to rounding."""
    fs, n = 12_000.0, 12_000
    t = np.arange(n) / fs
    x = sum(a * np.cos(2 * np.pi * f * t) for f, a in tones)
    assert _level2_band_value(x, fs, 2250.0) == pytest.approx(expected, abs=1e-9)


# ------------------------------------------------ fast path against a plain reference
CWRU = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "cwru"


def band_weights(n, fs, n_bands, j):
    """Bins and weights of band j of a row of n_bands, from the definition: the band
    (j + 1/2 +- 1/2) fs / (2 n_bands) gathers the bins within 3/4 of its width of its
    centre (n_taps of them, the plan's FFT-friendly count); weight 1 within 1/4 width of
    the centre, raised-cosine edges to 0 at 3/4 (-6 dB at the nominal edges), 1 beyond
    the centre towards 0 Hz or fs/2 for the edge bands, 0 outside [0, fs/2]."""
    df, width = fs / n, 0.5 * fs / n_bands
    centre = (j + 0.5) * width
    n_taps = scipy.fft.next_fast_len(math.ceil(1.5 * width / df) + 1)
    k = round((centre - 0.75 * width) / df) + np.arange(n_taps)
    u = np.abs(k * df - centre) / width
    w = np.clip(0.5 + 0.5 * np.cos(2 * np.pi * (np.clip(u, 0.25, 0.75) - 0.25)), 0.0, 1.0)
    if j == 0:
        w[k * df < centre] = 1.0
    if j == n_bands - 1:
        w[k * df > centre] = 1.0
    w[(k < 0) | (k > n // 2)] = 0.0
    return k, w


def reference_kurtogram(x, fs, nlevel):
    """The kurtogram band by band, as the definition reads, with none of the fast path's
    machinery (plan, numba loops, four-step FFTs, shared buffer and weights, grid by
    index): each band's bins of numpy.fft.rfft(x - mean) times its weights, numpy.fft.ifft
    at the band's n_taps points, kurtosis E|c|^4 / (E|c|^2)^2 - 2 and power density
    sum |bins|^2 / sum w^2 relative to the mean |X|^2, repeated over the band's columns."""
    spectrum = np.fft.rfft(x - x.mean())
    mean_power = np.mean(np.abs(spectrum) ** 2)
    rows = [1] + [b for k in range(1, nlevel + 1) for b in ([3 * 2 ** (k - 2)] * (k > 1) + [2**k])]
    n_cols = math.lcm(*rows)
    kurt, dens = np.empty((2, len(rows), n_cols))
    for r, n_bands in enumerate(rows):
        span = n_cols // n_bands
        for j in range(n_bands):
            k, w = band_weights(x.size, fs, n_bands, j)
            bins = np.where(w > 0, spectrum[np.clip(k, 0, spectrum.size - 1)] * w, 0)
            p = np.abs(np.fft.ifft(bins)) ** 2
            kurt[r, j * span:(j + 1) * span] = np.mean(p**2) / np.mean(p) ** 2 - 2
            density = np.sum(np.abs(bins) ** 2) / np.sum(w**2) / mean_power
            dens[r, j * span:(j + 1) * span] = 10 * np.log10(density)
    return kurt, dens


def assert_matches_reference(x, fs, nlevel=None):
    res = F.fast_kurtogram(x, fs, nlevel=nlevel)
    for row, kurt, dens in zip(np.reshape(x, (-1, x.shape[-1])),
                               res.kurtosis.reshape((-1,) + res.kurtosis.shape[-2:]),
                               res.density_db.reshape((-1,) + res.kurtosis.shape[-2:]),
                               strict=True):
        ref_k, ref_d = reference_kurtogram(row, fs, res.levels.size // 2)
        # Both are exact up to rounding: FFTs of up to 73 000 points (relative error
        # ~1e-15 log n) and means of as many terms summed in another order. Measured:
        # 2e-14 at most; a wrong edge weight, a dropped bin or a skipped tail sample
        # moves values by more than 1e-6 (the planted bugs of the report).
        np.testing.assert_allclose(kurt, ref_k, rtol=1e-11, atol=1e-11)
        np.testing.assert_allclose(dens, ref_d, rtol=0, atol=1e-10)
    return res


@pytest.mark.parametrize(("n", "fs"), [(48_000, FS), (97_656, 97_656.0), (12_000, 12_000.0),
                                       (4_001, 12_000.0)])
def test_fast_kurtogram_equals_the_band_by_band_reference(n, fs):
    """1 s at 48 kHz and at MFPT's 97 656 Hz take the four-step path in their widest
    rows (36 015 taps; 73 500 and 36 750), 12 kHz and an odd length the direct one; bands
    reaching below 0 Hz and past fs/2 (the edge rows) gather zeros there."""
    x = impulses_in_noise(np.random.default_rng(10), n=n, fs=fs, f_res=0.3 * fs)
    res = assert_matches_reference(x, fs)
    assert any(row.split is not None for row in _tree(n, fs, res.levels.size // 2).rows) \
        == (n >= 48_000)


def test_batched_fast_kurtogram_equals_the_reference_per_signal():
    X = np.random.default_rng(11).standard_t(4, size=(2, 3, 6_000))
    assert_matches_reference(X, 12_000.0)


@pytest.mark.parametrize("n", [36_015, 73_500, 4 * 9 * 25 * 49])
def test_four_step_transform_is_the_inverse_fft_reordered(n):
    """_band_signals with a split returns ifft(b)[k1 + n1 k2] at [k1, k2] of each
    (n1, n2) block, for a batch of transforms; rounding-level agreement (1e-13 of the
    largest value) for these 36 000-73 000-point transforms."""
    b = np.random.default_rng(12).standard_normal((2, 3, 2 * n)).view(complex)
    n1, n2, _ = split = _four_step(n)
    assert n1 * n2 == n and n1 <= math.isqrt(n) < n2 + 1
    expected = np.fft.ifft(b, axis=-1)
    out = _band_signals(b.copy(), split)
    reordered = out.reshape(2, 3, n1, n2).swapaxes(-1, -2).reshape(2, 3, n)
    np.testing.assert_allclose(reordered, expected, rtol=0, atol=1e-13 * abs(expected).max())


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_fast_kurtogram_equals_the_reference_on_real_recordings():
    """Drive-end and fan-end records of three fault types: same grid to rounding, so the
    same best band (the script of the report checks all 392 one-second segments)."""
    files = [CWRU / name for name in ("12k_DE_IR007_0.mat", "12k_FE_OR007@3_0.mat",
                                      "12k_DE_B021_0.mat")]
    X, _ = bp.datasets.load_cwru(files, fs=12_000)
    assert_matches_reference(X[::5].astype(float), 12_000.0)


def _impacts_under_low_knocks():
    """BPFI impacts of a 6205 at 1797 rpm ringing a 3 kHz resonance, plus two smooth
    150 Hz knocks (Gaussian bursts, 10 ms: all their energy below 300 Hz) that are far
    more impulsive than the fault: the kurtogram's largest kurtosis sits in 0-375 Hz,
    below the fault's own lines."""
    fs, n = 12_000.0, 12_000
    t = np.arange(n) / fs
    bpfi = 162.2
    phase = (t * bpfi) % 1.0 / bpfi
    x = np.exp(-900 * phase) * np.sin(2 * np.pi * 3000 * phase)
    for t0 in (0.125, 0.61):
        x += 20 * np.exp(-0.5 * ((t - t0) / 0.01) ** 2) * np.cos(2 * np.pi * 150 * (t - t0))
    return x + 0.3 * np.random.default_rng(0).standard_normal(n), fs


def test_band_lies_above_the_fault_lines_it_must_carry():
    x, fs = _impacts_under_low_knocks()
    # without the rule (every band admissible down to 0 Hz) the knocks' band wins
    assert F.fast_kurtogram(x, fs, fault_hz=0.0).best_band == (0.0, 375.0)
    # default: no band starting at 0 Hz below the full band (it has no carrier)
    lo, hi = F.fast_kurtogram(x, fs).best_band
    assert lo > 0 or hi == fs / 2
    # with the highest line to read (3 x BPFI + a shaft order = 517 Hz at 1797 rpm) the
    # band lies above it, and it holds the 3 kHz resonance the impacts ring
    lo, hi = F.fast_kurtogram(x, fs, fault_hz=517.0).best_band
    assert lo >= 517.0 and lo <= 3000.0 <= hi
    # envelope_analysis with rpm and bearing applies it: BPFI reads > 10 dB above its
    # background there, against < 6 dB (the diagnoser's threshold) in the default band
    with_bearing = F.envelope_analysis(x, fs, rpm=1797.0, bearing="6205")
    assert with_bearing.band == (lo, hi) and with_bearing.fault_bands["bpfi_1"] > 10
    plain = F.envelope_analysis(x, fs)
    levels = F.fault_band_levels(plain.freqs, plain.ses, "6205", 1797.0)
    assert levels["bpfi_1"] < 6
    # fault_band_features chooses the same band (0.2 dB: the circular against padded
    # filtering of the two, as in test_features_analysis)
    feats = F.fault_band_features(x, fs, "6205", 1797.0)
    assert abs(feats["bpfi_1"] - with_bearing.fault_bands["bpfi_1"]) < 0.2


def test_fault_hz_per_signal_and_its_fallback():
    x, fs = _impacts_under_low_knocks()
    res = F.fast_kurtogram(np.stack([x, x]), fs, fault_hz=[0.0, 517.0])
    assert tuple(res.best_band[0]) == (0.0, 375.0) and res.best_band[1][0] >= 517.0
    # no band above 5990 Hz has content and width: the full band is the fallback
    assert F.fast_kurtogram(x, fs, fault_hz=5990.0).best_band == (0.0, fs / 2)


@pytest.mark.parametrize("bad", [-1.0, np.nan, 6000.0, [100.0, 200.0, 300.0]])
def test_fault_hz_is_validated(bad):
    x, fs = _impacts_under_low_knocks()
    with pytest.raises(ValueError, match="fault_hz"):
        F.fast_kurtogram(np.stack([x, x]), fs, fault_hz=bad)
