"""Envelope analysis: closed forms, batching, dtypes, validation, order tracking."""

import numpy as np
import pytest
import scipy.signal

import ballpass as bp
from ballpass import features as F

FS = 12_000.0
N = 12_000  # 1 s: bin k of the spectrum is k Hz
A, M, FC, FM = 2.0, 0.4, 3000.0, 50.0  # carrier amplitude, modulation depth, Hz, Hz


def am_tone():
    """A (1 + m cos 2 pi fm t) cos 2 pi fc t with fc and fm on exact FFT bins."""
    t = np.arange(N) / FS
    return A * (1 + M * np.cos(2 * np.pi * FM * t)) * np.cos(2 * np.pi * FC * t)


def impulse_train(fs, n, rate, f_res, rng, noise=0.1, damping=800.0):
    """Decaying resonance at f_res (Hz) struck `rate` times per second, plus white noise."""
    t = np.arange(n) / fs
    phase = (t * rate) % 1.0 / rate  # time since the last strike, s
    x = np.exp(-damping * phase) * np.sin(2 * np.pi * f_res * phase)
    return x + noise * rng.standard_normal(n)


# ---------------------------------------------------------------- closed forms
@pytest.mark.parametrize("window", ["boxcar", "hann"])
def test_am_tone_lines_exact_without_filter(window):
    """Envelope line A m at fm; SES lines 2 m A^2 at fm and m^2 A^2 / 2 at 2 fm.

    band=(0, fs/2) skips the filter and the tones sit on exact bins, so the analytic
    signal and the spectra are exact up to FFT round-off: rtol 1e-9.
    """
    x = am_tone()
    e = F.envelope(x, FS, band=(0, FS / 2))
    t = np.arange(N) / FS
    np.testing.assert_allclose(e, A * (1 + M * np.cos(2 * np.pi * FM * t)), rtol=1e-9)

    f, es = F.envelope_spectrum(x, FS, band=(0, FS / 2), squared=False, window=window)
    assert f[int(FM)] == FM
    np.testing.assert_allclose(es[int(FM)], A * M, rtol=1e-9)
    assert es[int(2 * FM)] < 1e-9 * A  # the plain envelope is a pure cosine

    f, ses = F.envelope_spectrum(x, FS, band=(0, FS / 2), window=window)
    np.testing.assert_allclose(ses[int(FM)], 2 * M * A**2, rtol=1e-9)
    np.testing.assert_allclose(ses[int(2 * FM)], M**2 * A**2 / 2, rtol=1e-9)
    assert ses[0] == pytest.approx(0.0, abs=1e-9)  # mean removed
    if window == "boxcar":  # no leakage: every other bin is round-off
        others = np.delete(ses, [int(FM), int(2 * FM)])
        assert others.max() < 1e-9


def test_am_tone_through_band_filter():
    """With a band-pass, the lines scale by the filter's |H|^2 at carrier and sidebands.

    The Hann window is ~0 where sosfiltfilt's edge transients live, so the only
    deviation left is numerical: rtol 1e-6 (measured 1e-8).
    """
    band = (2000.0, 4000.0)
    sos = scipy.signal.butter(4, band, "bandpass", fs=FS, output="sos")
    _, h = scipy.signal.sosfreqz(sos, worN=[FC - FM, FC, FC + FM], fs=FS)
    g = np.abs(h) ** 2  # forward-backward filtering squares the magnitude
    g0, g1 = g[1], 0.5 * (g[0] + g[2])
    f, ses = F.squared_envelope_spectrum(am_tone(), FS, band)
    np.testing.assert_allclose(ses[int(FM)], 2 * A**2 * g0 * g1 * M, rtol=1e-6)
    np.testing.assert_allclose(ses[int(2 * FM)], A**2 * M**2 * g1**2 / 2, rtol=1e-6)
    # The filter must actually act: an out-of-band tone disappears from the envelope.
    t = np.arange(N) / FS
    hum = 5.0 * np.cos(2 * np.pi * 300 * t)
    _, ses_hum = F.envelope_spectrum(am_tone() + hum, FS, band)
    np.testing.assert_allclose(ses_hum[int(FM)], ses[int(FM)], rtol=1e-3)


def test_bandpass_matches_scipy_sosfiltfilt():
    x = np.random.default_rng(1).standard_normal(4000)
    sos = scipy.signal.butter(4, (500, 1500), "bandpass", fs=FS, output="sos")
    np.testing.assert_allclose(
        F.bandpass(x, FS, (500, 1500)), scipy.signal.sosfiltfilt(sos, x), rtol=1e-12, atol=1e-12
    )
    lp = scipy.signal.butter(4, 1000, "lowpass", fs=FS, output="sos")
    np.testing.assert_allclose(F.bandpass(x, FS, (0, 1000)), scipy.signal.sosfiltfilt(lp, x))
    np.testing.assert_array_equal(F.bandpass(x, FS, (0, FS / 2)), x)


def test_cepstrum_prewhitening_flattens_and_keeps_phase():
    x = np.random.default_rng(2).standard_normal(2048) * np.hanning(2048)
    y = F.cepstrum_prewhiten(x)
    X, Y = np.fft.rfft(x), np.fft.rfft(y)
    np.testing.assert_allclose(np.abs(Y), 1.0, rtol=1e-9)
    np.testing.assert_allclose(np.angle(Y[1:-1]), np.angle(X[1:-1]), atol=1e-9)


def test_prewhitening_reveals_impacts_under_a_strong_tone():
    """A shaft-harmonic tone 30x stronger than the impacts hides them from the SES of
    the full band; after pre-whitening the impact rate is the strongest SES line."""
    rng = np.random.default_rng(3)
    x = impulse_train(FS, N, 87.0, 3000.0, rng, noise=0.05)
    x += (
        30.0
        * np.cos(2 * np.pi * 150 * np.arange(N) / FS)
        * (1 + 0.5 * np.cos(2 * np.pi * 13 * np.arange(N) / FS))
    )
    f, raw = F.envelope_spectrum(x, FS, band=(0, FS / 2))
    f, cpw = F.envelope_spectrum(x, FS, band=(0, FS / 2), prewhiten=True)
    low = (f > 5) & (f < 500)
    assert f[low][np.argmax(raw[low])] == 13.0
    assert f[low][np.argmax(cpw[low])] == 87.0


def test_auto_band_finds_impacts_in_low_frequency_noise():
    """band=None demodulates around the resonance, not the loud low-frequency hum."""
    rng = np.random.default_rng(4)
    x = impulse_train(FS, N, 107.0, 3500.0, rng)
    x += (
        3.0
        * scipy.signal.sosfilt(
            scipy.signal.butter(2, 200, fs=FS, output="sos"), rng.standard_normal(N)
        )
        * 10
    )
    f, ses = F.envelope_spectrum(x, FS)
    low = (f > 5) & (f < 500)
    assert f[low][np.argmax(ses[low])] == 107.0


# ---------------------------------------------------------------- shapes, dtypes
def test_batched_equals_loop_and_axis():
    """Rows get their own automatically chosen band; a batch must equal the loop."""
    rng = np.random.default_rng(5)
    X = np.stack(
        [impulse_train(FS, 6000, r, fr, rng) for r, fr in [(90, 2000), (130, 4500), (70, 3000)]]
    )
    f, batch = F.envelope_spectrum(X, FS)
    loop = np.stack([F.envelope_spectrum(row, FS)[1] for row in X])
    np.testing.assert_allclose(batch, loop, rtol=1e-12, atol=1e-15)
    f, by_axis0 = F.envelope_spectrum(X.T, FS, axis=0)
    np.testing.assert_allclose(by_axis0.T, batch, rtol=1e-12, atol=1e-15)
    X3 = X.reshape(3, 1, -1)
    assert F.envelope(X3, FS, band=(1000, 5000)).shape == X3.shape


def test_float32_input():
    """float32 input is computed in float64: agreement to float32 resolution (1e-6)."""
    x = am_tone()
    f, ses64 = F.envelope_spectrum(x, FS, band=(2000, 4000))
    f, ses32 = F.envelope_spectrum(x.astype(np.float32), FS, band=(2000, 4000))
    assert ses32.dtype == np.float64
    np.testing.assert_allclose(ses32, ses64, rtol=1e-5, atol=1e-6 * ses64.max())


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        (dict(x=np.array([])), "x"),
        (dict(x=np.array([1.0])), "x"),
        (dict(x=np.array([1.0, np.nan, 2.0])), "x"),
        (dict(x=np.ones(100), band=(1000.0, 7000.0)), "band"),
        (dict(x=np.ones(100), band=(3000.0, 2000.0)), "band"),
        (dict(x=np.ones(100), band=(-1.0, 2000.0)), "band"),
        (dict(x=np.ones(100), fs=0.0), "fs"),
        (dict(x=np.ones(100), fs=-12_000.0), "fs"),
        (dict(x=np.ones(100), fs=np.inf), "fs"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name):
    args = dict(x=np.ones(100), fs=FS, band=(1000.0, 2000.0)) | kwargs
    for func in (F.envelope_spectrum, F.envelope, F.bandpass):
        with pytest.raises(ValueError, match=rf"^{name} "):
            func(args["x"], args["fs"], args["band"])


def test_bad_types():
    with pytest.raises(TypeError, match="^band"):
        F.envelope_spectrum(np.ones(100), FS, band=1000.0)
    with pytest.raises(TypeError, match="^x"):
        F.envelope_spectrum(np.ones(100) + 1j, FS)
    with pytest.raises(TypeError, match="^fs"):
        F.envelope_spectrum(np.ones(100), "12k")


# ---------------------------------------------------------------- order tracking
def run_up(fs=FS, seconds=2.0, rpm0=900.0, rpm1=1800.0, order=3.5848):
    """Impacts at a fixed shaft order during a linear run-up, ringing 3 kHz."""
    n = int(fs * seconds)
    rpm = np.linspace(rpm0, rpm1, n)
    t, revs = F.shaft_revolutions(n, fs, rpm=rpm)
    strikes = np.flatnonzero(np.diff(np.floor(revs * order)) > 0) + 1
    pulses = np.zeros(n)
    pulses[strikes] = 1.0
    ring = np.exp(-800 * t[:300]) * np.sin(2 * np.pi * 3000 * t[:300])
    x = np.convolve(pulses, ring)[:n] + 0.05 * np.random.default_rng(6).standard_normal(n)
    return x, rpm, revs, t


def test_order_envelope_spectrum_is_sharp_during_a_run_up():
    """During a 15 -> 30 Hz run-up the fault line smears over 54-108 Hz in the SES, but
    sits at its order (3.5848, resolution 1/45 rev) in the order spectrum."""
    x, rpm, revs, _ = run_up()
    orders, amp = F.order_envelope_spectrum(x, FS, rpm=rpm, band=(2000, 4000))
    above = orders > 1  # skip the low-order hump of the envelope's slow variation
    assert orders[above][np.argmax(amp[above])] == pytest.approx(3.5848, abs=1.0 / revs[-1])
    # Sharpness: the order line stands far above its neighbourhood; the Hz SES has none.
    peak = amp.max() / np.median(amp[(orders > 1) & (orders < 10)])
    f, ses = F.envelope_spectrum(x, FS, band=(2000, 4000))
    smeared = ses[(f > 50) & (f < 120)].max() / np.median(ses[(f > 15) & (f < 150)])
    assert peak > 5 * smeared


def test_tachometer_gives_the_same_order_spectrum():
    """A once-per-revolution tachometer reproduces the rpm-profile result: both place
    the line on the same order bin (angle from PCHIP between pulses vs. integral)."""
    x, rpm, revs, _ = run_up()
    tacho = (np.sin(2 * np.pi * revs) > 0.99).astype(float)  # narrow pulse per rev
    o1, a1 = F.order_envelope_spectrum(x, FS, rpm=rpm, band=(2000, 4000))
    o2, a2 = F.order_envelope_spectrum(x, FS, tacho=tacho, band=(2000, 4000))
    assert o1[np.argmax(a1)] == pytest.approx(o2[np.argmax(a2)], abs=1.5 / revs[-1])


def test_order_track_resamples_a_constant_order_tone():
    x, rpm, revs, _ = run_up()
    tone = np.cos(2 * np.pi * 5 * revs)
    r, xa = F.order_track(tone, FS, rpm=rpm, samples_per_rev=100)
    inner = slice(10, -10)  # the cubic spline is least accurate at the very ends
    np.testing.assert_allclose(xa[inner], np.cos(2 * np.pi * 5 * r[inner]), atol=1e-5)


def test_order_tracking_bad_input():
    with pytest.raises(ValueError, match="exactly one of rpm"):
        F.order_track(np.ones(100), FS)
    with pytest.raises(ValueError, match="^rpm"):
        F.order_track(np.ones(100), FS, rpm=np.zeros(100))
    with pytest.raises(ValueError, match="^rpm"):
        F.order_track(np.ones(100), FS, rpm=np.ones(50))
    with pytest.raises(ValueError, match="^tacho"):
        F.order_track(np.ones(100), FS, tacho=np.zeros(100))


def test_public_names_via_package():
    assert bp.features.envelope_spectrum is F.envelope_spectrum


def test_band_is_chosen_before_prewhitening():
    """The automatic band comes from the raw signal's kurtogram, then the signal is
    pre-whitened. Chosen after pre-whitening, the content floor means nothing (every bin
    has unit magnitude) and a dead band above the anti-aliasing cut-off, holding only
    faint clicks at 37 Hz, wins: its SES then shows the clicks, not the 107 Hz impacts.
    """
    rng = np.random.default_rng(5)
    fs, n = 12_000.0, 24_000
    # Impacts with 1 % random spacing jitter (rolling elements slip): pre-whitening
    # removes strictly periodic (discrete) content, not this cyclostationary one.
    times = np.cumsum(np.full(300, 1 / 107.0) * (1 + 0.01 * rng.standard_normal(300)))
    pulses = np.zeros(n)
    pulses[np.round(times[times < n / fs] * fs).astype(int)] = 1.0
    t = np.arange(240) / fs
    ring = np.exp(-800 * t) * np.sin(2 * np.pi * 3_000.0 * t)
    x = np.convolve(pulses, ring)[:n] + 0.2 * rng.standard_normal(n)
    x = scipy.signal.sosfiltfilt(scipy.signal.butter(12, 4_500, fs=fs, output="sos"), x)
    clicks = np.zeros(n)
    clicks[(np.arange(0, n / fs, 1 / 37.0) * fs).astype(int)] = 0.02
    band = scipy.signal.butter(4, (4_950, 5_200), "bandpass", fs=fs, output="sos")
    x = x + scipy.signal.sosfiltfilt(band, clicks)
    f, ses = F.envelope_spectrum(x, fs, prewhiten=True)
    low = (f > 20) & (f < 250)
    assert f[low][np.argmax(ses[low])] == pytest.approx(107.0, abs=0.5)
    at = lambda hz: ses[np.argmin(np.abs(f - hz))]  # noqa: E731
    assert at(107.0) > 10 * at(37.0)


def test_cached_window_is_get_window_and_read_only():
    """The Hann window of the spectra is computed once per length and shared: it must
    equal scipy's and refuse writes (a caller scaling it in place would corrupt every
    later spectrum)."""
    from ballpass.features.envelope import _window

    w = _window("hann", 1000)
    np.testing.assert_array_equal(w, scipy.signal.get_window("hann", 1000))
    assert _window("hann", 1000) is w
    with pytest.raises(ValueError, match="read-only"):
        w *= 2.0


@pytest.mark.parametrize("pulses_per_rev", [2, 3])
def test_a_multi_pulse_tachometer_gives_the_angle_and_orders_of_the_rpm_profile(pulses_per_rev):
    """A tachometer with p pulses per revolution during a run-up: pulse k is at k / p
    revolutions, so the angle it gives equals the rpm profile's integral at the pulse
    times, and the order spectrum shows the fault line at the same order. A pulse is
    located to within one sample by the edge of a sampled step, i.e. 30 rev/s / 12 kHz
    = 0.0025 rev at the top speed: 0.005 rev. Pulses multiplied by p instead of divided
    turn the angle p^2 times too fast and move the line from 3.58 to 3.58 / p^2."""
    x, rpm, revs, t = run_up()
    tacho = (np.sin(2 * np.pi * pulses_per_rev * revs) > 0.99).astype(float)
    t_p, r_p = F.shaft_revolutions(t.size, FS, tacho=tacho, pulses_per_rev=pulses_per_rev)
    true = np.interp(t_p, t, revs)
    assert r_p[-1] == pytest.approx(true[-1] - true[0], abs=0.005)
    np.testing.assert_allclose(r_p - r_p[0], true - true[0], atol=0.005)
    o1, a1 = F.order_envelope_spectrum(x, FS, rpm=rpm, band=(2000, 4000))
    o2, a2 = F.order_envelope_spectrum(x, FS, tacho=tacho, pulses_per_rev=pulses_per_rev,
                                       band=(2000, 4000))
    # the first three harmonics of the line sit on the same order (resolution 1/45 rev,
    # the tachometer's span a pulse shorter: 1.5 bins, as above), and the two spectra
    # agree bin by bin (interpolated: correlation 0.993 measured for p = 1, 2, 3)
    for h in (1, 2, 3):
        near1, near2 = np.abs(o1 - h * 3.5848) < 0.2, np.abs(o2 - h * 3.5848) < 0.2
        assert (o2[near2][np.argmax(a2[near2])]
                == pytest.approx(o1[near1][np.argmax(a1[near1])], abs=1.5 / revs[-1]))
    shown = (o1 > 1) & (o1 < 12)
    assert np.corrcoef(a1[shown], np.interp(o1, o2, a2)[shown])[0, 1] > 0.95
