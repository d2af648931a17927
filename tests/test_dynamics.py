"""ballpass.dynamics: Poincare sections, bifurcation diagrams, the 0-1 test, and the
``ballpass bifurcation`` command."""

import math

import numpy as np
import pandas as pd
import pytest

import ballpass as bp
from ballpass.cli import main
from ballpass.simulate.result import FaultCrossings, GroundTruth, SimulationResult

# a linear isotropic rotor m x'' + c x' + k x = m_u e w^2 (cos wt, sin wt)
M_R, C_R, K_R, MUE = 1.0, 200.0, 4.0e6, 0.05 * 20e-6


def _linear_rotor_result(rpm, duration=0.5, fs=10_000.0):
    """Closed-form response of the linear rotor, started at rest at the origin: the
    steady whirl plus the free response that cancels it at t = 0."""
    scene = bp.Scene(bearing="NJ305", rpm=rpm, duration_s=duration, fs=fs,
                     resonance_hz=0.4 * fs)
    w = rpm * math.pi / 30
    t = np.arange(scene.n_samples) / fs
    h = MUE * w * w / (K_R - M_R * w * w + 1j * C_R * w)  # complex whirl amplitude
    z = h * np.exp(1j * w * t)  # x + i y, steady
    wn = math.sqrt(K_R / M_R)
    zeta = C_R / (2 * math.sqrt(K_R * M_R))
    wd = wn * math.sqrt(1 - zeta**2)
    # free response z_f with z_f(0) = -h, z_f'(0) = -i w h
    a, b = -h, (-1j * w * h + zeta * wn * (-h)) / wd
    z = z + np.exp(-zeta * wn * t) * (a * np.cos(wd * t) + b * np.sin(wd * t))
    empty = np.empty(0)
    truth = GroundTruth(
        label="healthy", faults=(), frequencies=scene.frequencies,
        shaft_angle=scene.speed.shaft_angle(t, duration), rpm=np.full(t.size, rpm),
        fault_crossings=FaultCrossings(empty, empty.astype(int), empty.astype(int),
                                       empty.astype(str)),
        effective_depth_mm=(), displacement=np.vstack((z.real, z.imag)))
    res = SimulationResult(accel=np.zeros(t.size), fs=fs, t=t, scene=scene,
                           sensor_names=("loaded",), truth=truth)
    return res, h


def test_poincare_of_linear_unbalanced_rotor_is_one_point():
    res, h = _linear_rotor_result(1500.0)
    pts = bp.dynamics.poincare_section(res, discard_s=0.1)
    # 25 rev/s over 0.4 s; the strobe sits at shaft angle 2 pi k, where the steady whirl
    # is at (Re h, Im h): one point. The transient decays as exp(-50 t): e^-5 by 0.1 s,
    # so the points agree with it to 1e-2 of |h| at worst, far better later
    assert pts.shape == (10, 2)
    np.testing.assert_allclose(pts[-5:], np.tile([h.real, h.imag], (5, 1)),
                               atol=1e-5 * abs(h))
    assert np.ptp(pts[-5:], axis=0).max() < 1e-5 * abs(h)
    # strobed by the cage (FTF, incommensurate with the whirl) the same motion is a
    # circle of radius |h|, not a point
    cage = bp.dynamics.poincare_section(res, strobe="cage", discard_s=0.2)
    np.testing.assert_allclose(np.hypot(cage[:, 0], cage[:, 1]), abs(h), rtol=1e-4)
    assert np.ptp(cage[:, 0]) > 0.5 * abs(h)


def test_poincare_refuses_bad_input():
    res, _ = _linear_rotor_result(1500.0)
    with pytest.raises(ValueError, match="strobe"):
        bp.dynamics.poincare_section(res, strobe="ball")
    with pytest.raises(ValueError, match="discard_s"):
        bp.dynamics.poincare_section(res, discard_s=0.5)
    nodisp = SimulationResult(accel=res.accel, fs=res.fs, t=res.t, scene=res.scene,
                              sensor_names=res.sensor_names,
                              truth=GroundTruth(**{**res.truth.__dict__, "displacement": None}))
    with pytest.raises(ValueError, match="return_forces=True"):
        bp.dynamics.poincare_section(nodisp)
    with pytest.raises(TypeError, match="res must be the SimulationResult.*ndarray"):
        bp.dynamics.poincare_section(res.accel)  # the samples, not the result


def _rotor_scene(**kw):
    b = bp.Bearing.catalog("NJ305").with_clearance(0.005)
    return bp.Scene(bearing=b, rpm=1200.0, radial_load_n=500.0, duration_s=0.25,
                    fs=4000.0, resonance_hz=1500.0, **kw)


def test_bifurcation_over_speed():
    scene = _rotor_scene()
    speeds = [600.0, 1200.0, 1800.0]
    df = bp.dynamics.bifurcation_diagram(scene, "rpm", speeds, discard_s=0.1,
                                         progress=False)
    assert list(df.columns) == ["parameter", "point", "x_m", "y_m"]
    assert df.attrs["parameter"] == "rpm"
    # one point per revolution after 0.1 s: 1.5, 3, 4.5 revolutions -> 1-2, 3, 4-5
    counts = df.groupby("parameter").size()
    for rpm in speeds:
        assert abs(counts[rpm] - rpm / 60 * 0.15) <= 1
    # the rotor sits on its rollers: x = clearance + the static approach of the
    # Stribeck distribution, within the varying compliance (~0.1 um at 500 N)
    static = scene.bearing.load_distribution(500.0 + 9.80665).deflection_m
    np.testing.assert_allclose(df["x_m"], static, atol=0.3e-6)


def test_bifurcation_over_clearance_and_errors_before_work(monkeypatch):
    scene = _rotor_scene()
    values = [0.0, 0.02, 0.05]
    df = bp.dynamics.bifurcation_diagram(scene, "radial_clearance_mm", values,
                                         discard_s=0.1, progress=False)
    means = df.groupby("parameter")["x_m"].mean()
    # the rotor drops by the clearance: x - c is the elastic approach, which the
    # clearance changes little at 500 N (fewer loaded rollers: a little more)
    approach = np.array([means[v] - v * 1e-3 for v in values])
    assert np.all((approach > 1e-6) & (approach < 6e-6))
    assert np.all(np.diff(approach) >= -1e-8)

    import ballpass.simulate as sim

    def boom(*a, **k):  # no simulation may start before every value is checked
        raise AssertionError("simulate called")

    monkeypatch.setattr(sim, "simulate", boom)
    with pytest.raises(ValueError, match="parameter must be one of .*radial_load_n"):
        bp.dynamics.bifurcation_diagram(scene, "stiffness", [1.0], progress=False)
    with pytest.raises(ValueError, match=r"radial_clearance_mm=-0\.5"):
        bp.dynamics.bifurcation_diagram(scene, "radial_clearance_mm", [0.01, -0.5],
                                        progress=False)
    with pytest.raises(ValueError, match="rpm"):
        bp.dynamics.bifurcation_diagram(scene, "rpm", [600, -5], progress=False)
    with pytest.raises(ValueError, match="values"):
        bp.dynamics.bifurcation_diagram(scene, "rpm", [], progress=False)
    with pytest.raises(ValueError, match=r"got \[600\.0, nan\]$"):  # a list, not array(...)
        bp.dynamics.bifurcation_diagram(scene, "rpm", np.array([600, np.nan]), progress=False)
    with pytest.raises(ValueError, match="seed takes whole numbers, got 1.5"):  # not seed 1
        bp.dynamics.bifurcation_diagram(scene, "seed", [1.5], progress=False)
    ramp = scene.replace(rpm=(600.0, 1200.0))
    with pytest.raises(ValueError, match="parameter must be one of"):
        bp.dynamics.bifurcation_diagram(ramp, "rpm", [600], progress=False)


def test_zero_one_test_separates_chaos_from_regular_motion():
    x = np.empty(2000)
    x[0] = 0.3
    for i in range(x.size - 1):  # logistic map at r = 3.97: chaotic
        x[i + 1] = 3.97 * x[i] * (1 - x[i])
    assert bp.dynamics.zero_one_test(x) > 0.9
    n = np.arange(2000)
    quasi = np.cos(0.9 * n) + 0.5 * np.cos(0.9 * math.sqrt(2) * n)  # quasi-periodic
    assert bp.dynamics.zero_one_test(quasi) < 0.1
    y = np.empty(2000)
    y[0] = 0.3
    for i in range(y.size - 1):  # r = 3.5: period 4
        y[i + 1] = 3.5 * y[i] * (1 - y[i])
    assert bp.dynamics.zero_one_test(y[100:]) < 0.1
    with pytest.raises(ValueError, match="300"):
        bp.dynamics.zero_one_test(x[:299])


def test_plots_return_axes():
    res, _ = _linear_rotor_result(1500.0)
    ax = bp.dynamics.plot_poincare(bp.dynamics.poincare_section(res))
    assert ax.get_ylabel().startswith("y")
    df = pd.DataFrame({"parameter": [1.0, 2.0], "point": [0, 0], "x_m": [1e-4, 2e-4],
                       "y_m": [0.0, 0.0]})
    ax = bp.dynamics.plot_bifurcation(df, coordinate="y_m")
    assert ax.get_xlabel() == "parameter"


def test_cli_bifurcation_writes_csv_and_figure(tmp_path, capsys):
    out, png = tmp_path / "b.csv", tmp_path / "b.png"
    code = main(["bifurcation", "--parameter", "radial_load_n", "--values", "200", "400",
                 "--clearance", "0.005", "--duration", "0.15", "--fs", "2000", "--quiet",
                 "--out", str(out), "--plot", str(png)])
    assert code == 0
    df = pd.read_csv(out)
    assert list(df.columns) == ["radial_load_n", "point", "x_m", "y_m"]
    assert set(df["radial_load_n"]) == {200.0, 400.0}
    assert png.stat().st_size > 1000
    assert main(["bifurcation", "--parameter", "nope", "--values", "1", "--out",
                 str(out)]) == 2
    assert "parameter must be one of" in capsys.readouterr().err
    # a bad output path is refused before any simulation
    assert main(["bifurcation", "--parameter", "rpm", "--values", "900", "--out",
                 str(tmp_path / "b.txt")]) == 2
    assert "--out" in capsys.readouterr().err


def test_speed_ramp_is_strobed_by_the_tachometer():
    # rotor2 on a run-up: the strobe instants follow the shaft angle, so every whole
    # revolution after the transient gives exactly one point, at its instant
    scene = _rotor_scene().replace(rpm=(600.0, 1800.0))
    res = bp.simulate(scene, model="rotor2", return_forces=True)
    assert "varying_speed" in bp.simulate.MODELS["rotor2"].represents
    pts = bp.dynamics.poincare_section(res, discard_s=0.05)
    angle = res.truth.shaft_angle
    first = math.ceil(np.interp(0.05, res.t, angle) / (2 * math.pi))
    last = math.floor(angle[-1] / (2 * math.pi))
    assert pts.shape == (last - first + 1, 2)
    # the run-up raises the unbalance force (w^2) but the rotor stays on its rollers
    static = scene.bearing.load_distribution(500.0 + 9.80665).deflection_m
    np.testing.assert_allclose(pts[:, 0], static, atol=0.3e-6)


# ------------------------------------------------------------ Lyapunov exponent
def _lorenz(t, y):
    """Lorenz (1963) with its classical sigma = 10, rho = 28, beta = 8/3."""
    return [10.0 * (y[1] - y[0]), y[0] * (28.0 - y[2]) - y[1], y[0] * y[1] - 8.0 / 3.0 * y[2]]


def test_lyapunov_lorenz_published_value():
    # The Lorenz system's largest exponent is 0.9056 (Sprott, Chaos and Time-Series
    # Analysis, 2003, table A.1). A finite average over 150 time units (about 700 of its
    # ~0.2 orbit periods) wanders by a few per cent: measured 0.913-0.926 over 100-200
    # units; 6 % allows that and still fails a log10 (0.39), a missing renormalization
    # (each interval then logs the whole growth so far: 19.8) or a rate per
    # renormalization counted twice. Planted once each (log10, no renormalization):
    # both failed. ~3 s.
    lam, running = bp.dynamics.largest_lyapunov_exponent(
        _lorenz, [1.0, 1.0, 1.0], 150.0, renormalize_s=1.0, transient_s=20.0,
        rtol=1e-9, atol=1e-9)
    assert lam == pytest.approx(0.9056, rel=0.06)
    assert running.shape == (150,)


def test_lyapunov_damped_oscillator_closed_form():
    # x'' + 2 zeta w x' + w^2 x = 0 is linear: any separation decays like
    # exp(-zeta w t) times a bounded oscillation, so the exponent is -zeta w exactly and
    # the average over T errs by at most ln(bound) / T. In the norm of (x, x' / w) (the
    # scale) the bound is about (1 + zeta) / (1 - zeta) ~ 1.1: 0.1 / 300 = 3e-4, 0.1 % of
    # 0.3; 0.5 % leaves room for the integrator (planted sign error: +0.3, failed).
    zeta, w = 0.05, 6.0
    lam, _ = bp.dynamics.largest_lyapunov_exponent(
        lambda t, y: [y[1], -w * w * y[0] - 2 * zeta * w * y[1]], [1.0, 0.0], 300.0,
        renormalize_s=0.7, d0=1e-6, scale=[1.0, w])
    assert lam == pytest.approx(-zeta * w, rel=5e-3)


def test_lyapunov_scale_makes_units_irrelevant():
    # the same oscillator in other units (x in um, x' in um/s): with the scale stating
    # the units the exponent cannot change (catches a scale applied one way only)
    zeta, w, u = 0.05, 6.0, 1e-6
    rhs = lambda t, y: [y[1], -w * w * y[0] - 2 * zeta * w * y[1]]  # noqa: E731
    a, _ = bp.dynamics.largest_lyapunov_exponent(rhs, [1.0, 0.0], 60.0, renormalize_s=1.0)
    b, _ = bp.dynamics.largest_lyapunov_exponent(rhs, [u, 0.0], 60.0, renormalize_s=1.0,
                                                 scale=[u, u], atol=1e-18)
    assert b == pytest.approx(a, rel=1e-6)


@pytest.mark.parametrize("kw, match", [
    (dict(duration=0.0), "duration must be > 0"),
    (dict(renormalize_s=-1.0), "renormalize_s must be > 0"),
    (dict(duration=0.5), r"duration must be >= renormalize_s"),
    (dict(transient_s=-1.0), "transient_s must be >= 0"),
    (dict(d0=0.1), r"d0 must be in \(0, 1e-3\]"),
    (dict(scale=[1.0]), "scale must hold 2 positive values"),
    (dict(scale=[1.0, 0.0]), "scale must hold 2 positive values"),
])
def test_lyapunov_bad_input(kw, match):
    args = dict(duration=10.0, renormalize_s=1.0) | kw
    with pytest.raises(ValueError, match=match):
        bp.dynamics.largest_lyapunov_exponent(lambda t, y: [y[1], -y[0]], [1.0, 0.0], **args)
