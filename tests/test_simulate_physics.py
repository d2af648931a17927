"""Physics of the simulated signals: force balance, load distribution, envelope lines.

Scenes here use a CWRU-like structural resonance (3 kHz, 1 % damping) at 12 kHz: its
squared-envelope impulse decays over 1/(2 zeta omega) = 2.7 ms, longer than a defect
period, so the SES harmonics of a defect frequency fall off from the fundamental the way
they do on real rigs. (With the 15 kHz / 5 % default the SES pulse lasts 0.1 ms and all
harmonics below ~1.5 kHz are equally tall, so "the largest line" would be ill-posed.)
"""

import math

import numpy as np
import pytest

import ballpass as bp
from ballpass.features import bandpass, envelope_spectrum

FS = 12_000.0
RESONANCE = dict(resonance_hz=3000.0, resonance_damping=0.01)
BAND = (2000.0, 4000.0)  # the resonance +- 1 kHz, the demodulation band


def scene(kind=None, rpm=1797.0, **kw):
    fault = bp.Fault(kind, width_mm=0.5, depth_mm=0.1) if kind else None
    base = dict(bearing="6205", rpm=rpm, fault=fault, duration_s=1.0, fs=FS, **RESONANCE)
    base.update(kw)
    return bp.Scene(**base)


def line(freqs, ses, f0, tol):
    """Largest SES value within f0 +- tol."""
    sel = (freqs >= f0 - tol) & (freqs <= f0 + tol)
    return ses[sel].max()


def background(freqs, ses, lo=5.0, hi=500.0):
    """Median SES level in [lo, hi]: the floor lines are compared against."""
    sel = (freqs >= lo) & (freqs <= hi)
    return np.median(ses[sel])


def tolerance(f0):
    # 1 Hz frequency resolution of a 1 s record, plus 3 sigma of the slip-induced line
    # spread: a 1 % random walk over ~f0 impacts wanders by ~3 % of f0 / sqrt(f0) Hz.
    return 1.0 + 0.03 * np.sqrt(f0)


# ----------------------------------------------------------------------- static balance
def test_static_force_balance_and_quasi_static_loads():
    sc = scene(None, rpm=1200.0, radial_load_n=800.0)
    res = bp.simulate(sc, return_forces=True)
    params = bp.simulate.SR5Parameters()
    q = res.truth.contact_forces
    psi = res.truth.element_angles
    u_s, _v_s, u_p, _v_p = res.truth.displacement
    g = 9.80665
    f_contact_u = np.sum(q * np.cos(psi), axis=0)
    # shaft: support spring (about its rest position, the static start) + contact force
    # = radial load + weight, on average over the run. 1 % as the issue asks; the
    # residual is the mean of the dynamic part only.
    u_rest = res.truth.displacement[0, 0]
    shaft = params.shaft_stiffness * np.mean(u_s - u_rest) + np.mean(f_contact_u)
    assert shaft == pytest.approx(sc.radial_load_n + params.shaft_mass * g, rel=0.01)
    # pedestal: its spring carries the contact force plus its own weight
    pedestal = params.pedestal_stiffness * np.mean(u_p)
    assert pedestal == pytest.approx(np.mean(f_contact_u) + params.pedestal_mass * g, rel=0.01)

    # at t = 0 the run starts from the quasi-static solution: same loads as bearing.py's
    # exact Stribeck solve for the same stiffness and the same element positions
    b = sc.bearing
    dist = b.load_distribution(sc.radial_load_n + params.shaft_mass * g,
                               cage_angle_deg=float(np.degrees(psi[0, 0])))
    order = np.argsort(np.mod(dist.element_angles_deg, 360.0))
    mine = np.argsort(np.mod(np.degrees(psi[:, 0]), 360.0))
    # 1e-6 relative: both are converged root solves of the same equations
    np.testing.assert_allclose(q[mine, 0], dist.element_loads_n[order], rtol=1e-6, atol=1e-6)
    # and on average over the run the most loaded element carries the quasi-static Q_max
    # of a rotating ball set: between the ball-on-load-line and straddling values (2 %
    # for dynamic oscillation around the quasi-static state)
    qmax_on = b.load_distribution(sc.radial_load_n + params.shaft_mass * g).q_max_n
    qmax_straddle = b.load_distribution(sc.radial_load_n + params.shaft_mass * g,
                                        cage_angle_deg=20.0).q_max_n
    lo, hi = sorted([qmax_on, qmax_straddle])
    assert lo * 0.98 <= np.mean(q.max(axis=0)) <= hi * 1.02


def test_separated_contacts_carry_exactly_zero_force():
    res = bp.simulate(scene("outer", rpm=1500.0, duration_s=0.3), return_forces=True)
    q = res.truth.contact_forces
    angle = np.mod(np.degrees(res.truth.element_angles) + 180.0, 360.0) - 180.0
    # zero clearance: the load zone is +-90 deg; elements well outside it are separated
    unloaded = np.abs(angle) > 100.0
    assert unloaded.sum() > 1000
    assert np.all(q[unloaded] == 0.0)
    assert np.all(q >= 0.0)
    # and the loaded zone does carry load
    assert np.all(q[np.abs(angle) < 30.0] > 0.0)


# ------------------------------------------------------------------------ envelope lines
@pytest.mark.parametrize("rpm", [900.0, 1797.0, 2700.0])
def test_outer_race_fault_peaks_at_bpfo(rpm):
    sc = scene("outer", rpm=rpm)
    res = bp.simulate(sc)
    f, ses = envelope_spectrum(res.accel, FS, band=BAND)
    sel = (f >= 5.0) & (f <= 500.0)
    peak = f[sel][np.argmax(ses[sel])]
    bpfo = sc.frequencies.bpfo
    assert abs(peak - bpfo) <= tolerance(bpfo)


def assert_family(f, ses, f0, tol, sideband, sideband_tol, rivals, rival_factor):
    """The defect line f0 stands clear of the floor (the median SES level in 5-500 Hz,
    itself raised by the many modulation lines): 10x, 20 dB in SES amplitude; its
    sidebands at f0 +- ``sideband`` 5x; and it is taller than ``rival_factor`` times
    the lines of the other defect frequencies."""
    floor = background(f, ses)
    main = line(f, ses, f0, tol)
    assert main > 10.0 * floor
    assert line(f, ses, f0 - sideband, sideband_tol) > 5.0 * floor
    assert line(f, ses, f0 + sideband, sideband_tol) > 5.0 * floor
    for rival in rivals:
        assert main > rival_factor * line(f, ses, rival, tol)


@pytest.mark.parametrize("rpm", [900.0, 1797.0, 2700.0])
def test_inner_race_fault_shows_bpfi_with_shaft_sidebands(rpm):
    sc = scene("inner", rpm=rpm)
    fr = sc.frequencies
    f, ses = envelope_spectrum(bp.simulate(sc).accel, FS, band=BAND)
    # sidebands at +- shaft speed: the fault passes the load zone once a turn; and it is
    # the inner race, not another defect frequency, that shows (3x)
    tol = tolerance(fr.bpfi)
    assert_family(f, ses, fr.bpfi, tol, fr.shaft, tol, (fr.bpfo, fr.ball_defect), 3.0)


@pytest.mark.parametrize("rpm", [900.0, 1797.0, 2700.0])
def test_ball_fault_shows_ball_defect_family_with_cage_sidebands(rpm):
    sc = scene("ball", rpm=rpm)
    fr = sc.frequencies
    f, ses = envelope_spectrum(bp.simulate(sc).accel, FS, band=BAND)
    tol = tolerance(fr.ball_defect)
    # the defective ball carries the defect round with the cage: FTF sidebands. BPFO =
    # Z * FTF is itself a harmonic of the cage modulation of a ball fault (impacts only
    # in the load zone, half of each cage turn), so demand only that the ball-defect
    # line is the taller one
    assert_family(f, ses, fr.ball_defect, tol, fr.ftf, 1.0, (fr.bpfo, fr.bpfi), 1.0)
    # a family: the second harmonic stands out too
    floor = background(f, ses)
    assert line(f, ses, 2 * fr.ball_defect, 2 * tol) > 5.0 * floor


@pytest.mark.parametrize("kind", ["outer", "inner", "ball"])
def test_healthy_lines_at_least_10_db_below_faulty(kind):
    noise = dict(noise_rms=0.5)  # the same absolute sensor noise on both, m/s^2
    faulty = scene(kind, rpm=1500.0, **noise)
    healthy = scene(None, rpm=1500.0, **noise)
    fr = faulty.frequencies
    f0 = {"outer": fr.bpfo, "inner": fr.bpfi, "ball": fr.ball_defect}[kind]
    f, ses_f = envelope_spectrum(bp.simulate(faulty).accel, FS, band=BAND)
    _, ses_h = envelope_spectrum(bp.simulate(healthy).accel, FS, band=BAND)
    tol = tolerance(f0)
    for k in (1, 2):
        # 10 dB in amplitude of the squared envelope: a factor 10 ** (10 / 20)
        assert line(f, ses_h, k * f0, k * tol) * 10 ** 0.5 <= line(f, ses_f, k * f0, k * tol)


# ------------------------------------------------------------------------ fault position
def test_fault_angle_wraps():
    a = bp.simulate(scene("outer", duration_s=0.2, fault=bp.Fault("outer", angle_deg=359.9)))
    b = bp.simulate(scene("outer", duration_s=0.2, fault=bp.Fault("outer", angle_deg=-0.1)))
    c = bp.simulate(scene("outer", duration_s=0.2, fault=bp.Fault("outer", angle_deg=719.9)))
    np.testing.assert_array_equal(a.accel, b.accel)
    # 719.9 - 360 = 359.9 up to one rounding of the float: the signals agree to
    # round-off amplified by the impacts, far below the signal level
    np.testing.assert_allclose(c.accel, a.accel, atol=1e-6 * np.abs(a.accel).max())


def test_outer_fault_in_unloaded_zone_is_much_weaker():
    loaded = bp.simulate(scene("outer", fault=bp.Fault("outer", angle_deg=0.0)))
    unloaded = bp.simulate(scene("outer", fault=bp.Fault("outer", angle_deg=180.0)))
    f, ses_l = envelope_spectrum(loaded.accel, FS, band=BAND)
    _, ses_u = envelope_spectrum(unloaded.accel, FS, band=BAND)
    bpfo = loaded.scene.frequencies.bpfo
    # no element is loaded at 180 deg with zero clearance: the defect opens no load
    # change and the BPFO line drops by orders of magnitude (20 dB is a loose bound)
    tol = tolerance(bpfo)
    assert line(f, ses_u, bpfo, tol) * 10 < line(f, ses_l, bpfo, tol)


def test_loaded_and_unloaded_sensors_differ_through_the_transfer_path():
    sc = scene("outer", sensors=("loaded", "unloaded"), duration_s=0.5)
    res = bp.simulate(sc)
    # impacts at 0 deg reach the 180 deg sensor through the attenuated path, at
    # exp(-2 kappa) = 0.2 of the force; the resonant response scales alike (up to x2.5
    # for the rigid-body pedestal motion both sensors share)
    ratio = np.std(res.channel("unloaded")) / np.std(res.channel("loaded"))
    assert 0.1 < ratio < 0.5


def test_sensor_sees_inner_race_impacts_by_angular_distance():
    # 5 % damping: each impact's ringing dies within 1 ms, before the next one (6 ms)
    sc = scene("inner", sensors=("loaded", "unloaded"), slip=0.0, resonance_damping=0.05)
    res = bp.simulate(sc, return_forces=True)
    cross = res.truth.fault_crossings
    exits = cross.time_s[cross.edge == "exit"]
    elements = cross.element[cross.edge == "exit"]
    idx = np.round(exits * FS).astype(int)
    keep = idx + 12 < len(res.t)
    idx, elements = idx[keep], elements[keep]
    where = np.degrees(res.truth.element_angles[elements, idx])
    where = np.abs(np.mod(where + 180.0, 360.0) - 180.0)  # distance from the load line
    resonant = {name: bandpass(res.channel(name), FS, BAND) for name in res.sensor_names}
    peak = {name: np.array([np.abs(x[i:i + 12]).max() for i in idx])
            for name, x in resonant.items()}
    share = peak["unloaded"] / peak["loaded"]
    # the transmission factor exp(-kappa (1 - cos)) grows for the 180 deg sensor and
    # shrinks for the 0 deg one as the impact moves away from the load line: impacts
    # 30-60 deg out give the unloaded sensor a larger share than those within 15 deg.
    # (Pure transmission factors predict x1.6 at 45 deg; each sensor's resonator also
    # carries the other contacts' varying-compliance response, which dilutes it: we
    # measured x1.19 and ask for a clear, monotone >10 %; the medians' spread is ~2 %.)
    near, off = share[where < 15.0], share[(where > 30.0) & (where < 60.0)]
    assert near.size > 5 and off.size > 5
    assert np.median(off) > 1.1 * np.median(near)


# ------------------------------------------------------------------------- ground truth
def test_fault_crossings_follow_the_kinematics():
    sc = scene("outer", slip=0.0, duration_s=0.5)
    res = bp.simulate(sc)
    entries = res.truth.fault_crossings.entries()
    # with no slip an outer-race defect is entered once per ball pass: every 1 / BPFO
    np.testing.assert_allclose(np.diff(entries), 1.0 / sc.frequencies.bpfo, rtol=1e-9)
    sc = scene("inner", slip=0.0, duration_s=0.5)
    entries = bp.simulate(sc).truth.fault_crossings.entries()
    np.testing.assert_allclose(np.diff(entries), 1.0 / sc.frequencies.bpfi, rtol=1e-9)
    sc = scene("ball", slip=0.0, duration_s=0.5)
    entries = bp.simulate(sc).truth.fault_crossings.entries()
    np.testing.assert_allclose(np.diff(entries), 1.0 / sc.frequencies.ball_defect, rtol=1e-9)


def test_slip_sets_the_spread_of_impact_intervals():
    """Scene.slip is the standard deviation of the inter-impact period over the nominal
    period. sr5's outer-race impacts (the ground truth's defect entries) over 24 runs of
    0.5 s, each with its own seed (its own slip walk) and fault angle: the angles cover
    one element spacing evenly, because a pass at a fraction u of a walk interval mixes
    two increments and its spread varies with u (0.71 to 1.22 of the slip). The pooled
    RMS deviation from the nominal period (1272 intervals) measures 0.0193 for slip
    0.02; its sampling error is 2.2 % (the spread of 40 such 24-run estimates, measured
    with the impulse model, which shares sr5's slip walk and crossings), so a bound of
    8 % (3.7 sigma) still tells a spread 0.8x the stated slip (0.0157) from it."""
    slip, n_runs, spacing_deg = 0.02, 24, 360.0 / 9  # a 6205 has 9 balls
    deviations, means = [], []
    for i in range(n_runs):
        sc = scene("outer", slip=slip, duration_s=0.5, seed=i,
                   fault=bp.Fault("outer", angle_deg=spacing_deg * (i + 0.5) / n_runs))
        d = np.diff(bp.simulate(sc, model="sr5").truth.fault_crossings.entries())
        deviations.append(d * sc.frequencies.bpfo - 1.0)
        means.append(np.mean(d) * sc.frequencies.bpfo)
    spread = np.sqrt(np.mean(np.concatenate(deviations) ** 2))
    assert spread == pytest.approx(slip, rel=0.08)
    # the cage keeps its mean speed: the mean interval is the nominal period within 3
    # sigma of a random walk's drift over 53 periods, averaged over 24 independent walks
    # (slip sqrt(1.5) / sqrt(53 * 24) per period)
    assert np.mean(means) == pytest.approx(1.0, abs=3 * slip * np.sqrt(1.5 / (53 * n_runs)))


def test_the_signal_strikes_when_the_ground_truth_says():
    """The slip spread above is read from the ground truth's defect entries; the signal
    must show the same impact train. With 2 % slip at 48 kHz (default 15 kHz resonance,
    no noise), the largest sample within half a period after each entry lags it by a
    constant 13-18 samples (measured: the ring builds up after the entry), so the
    signal's intervals are the truth's to a few samples, slip included. A signal driven
    by another slip walk than the truth reports drifts away from it by slip sqrt(n)
    periods, tens of samples within the 54 passes: the lags must stay within 8 samples
    (1.8 % of the 446-sample period) of each other."""
    sc = scene("outer", slip=0.02, duration_s=0.5, fs=48_000.0, resonance_hz=15_000.0,
               resonance_damping=0.05,
               fault=bp.Fault("outer", angle_deg=10.0))
    res = bp.simulate(sc, model="sr5")
    period = sc.fs / sc.frequencies.bpfo  # samples
    lags = []
    for t in res.truth.fault_crossings.entries():
        i0 = math.ceil(t * sc.fs)
        window = np.abs(res.accel[i0:i0 + int(0.5 * period)])
        if window.size == int(0.5 * period):  # a whole half period recorded
            lags.append(i0 + np.argmax(window) - t * sc.fs)
    assert len(lags) > 50
    assert np.ptp(lags) < 8.0 and 0.0 <= min(lags)


def test_run_up_follows_the_speed_profile():
    sc = scene("outer", rpm=(600.0, 1800.0), slip=0.0, duration_s=1.0)
    res = bp.simulate(sc)
    entries = res.truth.fault_crossings.entries()
    mid = 0.5 * (entries[1:] + entries[:-1])
    rpm_mid = sc.speed.rpm_at(mid, sc.duration_s)
    bpfo_order = sc.bearing.frequencies(1.0).bpfo
    # each ball-pass interval is 1 / BPFO at the speed of that moment; the speed changes
    # by < 2 % within one interval, so the midpoint speed predicts it to 1e-3
    np.testing.assert_allclose(np.diff(entries), 60.0 / (rpm_mid * bpfo_order), rtol=1e-3)
    # the tachometer channel integrates the ramp: 2 pi / 60 (600 t + 1200 t^2 / 2)
    t_end = res.t[-1]
    expected = 2 * np.pi / 60.0 * (600.0 * t_end + 600.0 * t_end**2)
    assert res.truth.shaft_angle[-1] == pytest.approx(expected, rel=1e-12)
    assert res.truth.rpm[0] == 600.0 and res.truth.rpm[-1] == pytest.approx(1800.0, rel=1e-3)
