"""The twin of a real machine: the all-pole path fit, and datasets made from a healthy
recording (``ballpass twin`` -> ``generate``).

Fixture: 1.5 s of the HIT-SM rig's healthy recording at 900 rpm (51.2 kHz), provenance in
tests/data/README.md, cut into two recordings so that the machine has two groups.
"""

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.linalg
import scipy.signal

from ballpass.datasets import generate, load, read_grid, regenerate, twin
from ballpass.datasets.twin import MACHINE_FILE
from ballpass.diagnose import split_indices
from ballpass.features.lpc import ar_fit, ar_order, ar_resonances, autocorrelation, levinson

CROP = Path(__file__).parent / "data" / "hit_Normal_900_crop.npy"
FS = 51_200.0


def _mode_poles(freqs_hz, dampings, fs):
    """Poles z = exp(s / fs) of modes of natural frequency f and damping ratio zeta."""
    poles = []
    for f, zeta in zip(freqs_hz, dampings, strict=True):
        s = 2 * np.pi * f * (-zeta + 1j * math.sqrt(1 - zeta**2))
        poles += [np.exp(s / fs), np.exp(np.conj(s) / fs)]
    return poles


# ----------------------------------------------------------------------------- lpc
def test_levinson_solves_the_yule_walker_equations():
    """The recursion against scipy's Toeplitz solver on the same autocorrelation (an
    independent solution of the same equations): equal to rounding."""
    x = np.random.default_rng(1).normal(size=5000).cumsum()
    r = autocorrelation(x, 12)
    a, errors = levinson(r, 12)
    reference = scipy.linalg.solve_toeplitz(r[:12], -r[1:13])
    np.testing.assert_allclose(a[1:], reference, rtol=1e-9, atol=1e-12)  # float rounding
    # the prediction error of order p: r[0] + sum a_k r[k] (Makhoul 1975, eq. 38)
    assert errors[-1] == pytest.approx(r[0] + a[1:] @ r[1:13], rel=1e-9)
    assert np.all(np.diff(errors) <= 0)   # error never grows with the order


def test_ar_fit_recovers_two_modes_of_a_known_ar_process():
    """White noise through two known modes (2.5 kHz at 3 %, 9 kHz at 1 %): the fit of
    order 4 gives their frequencies and damping ratios. Planted: ar_resonances without
    the fs scaling (frequencies in cycles/sample) fails; a sign slip in levinson's
    reflection coefficient fails."""
    fs = FS
    poles = _mode_poles([2500.0, 9000.0], [0.03, 0.01], fs)
    a_true = np.poly(poles).real
    x = scipy.signal.lfilter([1.0], a_true, np.random.default_rng(0).normal(size=400_000))
    a, sigma2 = ar_fit(x, 4)
    freq, zeta = ar_resonances(a, fs)
    # Yule-Walker estimates converge as 1/sqrt(N): with N = 4e5 a pole's radius and angle
    # are off by ~1e-3 of their distance to the unit circle; frequencies to 0.5 %, and the
    # damping (that distance itself) to 5 % of its value
    np.testing.assert_allclose(freq, [2500.0, 9000.0], rtol=5e-3)
    np.testing.assert_allclose(zeta, [0.03, 0.01], rtol=5e-2)
    # the driving noise had unit variance; its estimate within 1 % (chi2, N = 4e5: 0.2 %)
    assert sigma2 == pytest.approx(1.0, rel=1e-2)


def test_ar_order_by_akaike_does_not_underfit():
    """An AR(4) process: AIC's penalty (2 per order) is tiny beside the drop of
    N ln sigma^2 from order 3 to 4 (thousands at N = 4e5), so it never picks fewer than
    4; AIC is not consistent and may add an order or two, never many. Planted: an AIC
    without its N (penalty dominating) picks 1 and fails."""
    poles = _mode_poles([2500.0, 9000.0], [0.03, 0.01], FS)
    x = scipy.signal.lfilter([1.0], np.poly(poles).real,
                             np.random.default_rng(2).normal(size=400_000))
    assert 4 <= ar_order(x, FS, max_order=20) <= 7
    assert ar_order(x, FS) <= round(FS * 1e-3)   # default cap: one pole per kHz of fs


def test_lpc_refuses_bad_input():
    with pytest.raises(ValueError, match="order must be an int in"):
        ar_fit(np.random.default_rng(0).normal(size=100), 60)
    with pytest.raises(ValueError, match="constant"):
        ar_fit(np.ones(100), 2)
    with pytest.raises(ValueError, match="fs"):
        ar_order(np.random.default_rng(0).normal(size=100), -1.0)


# ----------------------------------------------------------------------------- twin
@pytest.fixture(scope="module")
def machine(tmp_path_factory):
    """Two healthy recordings of one machine (the crop's halves, 0.75 s each) and their
    manifest, without a label column."""
    folder = tmp_path_factory.mktemp("machine")
    x = np.load(CROP)
    half = x.size // 2
    np.save(folder / "first.npy", x[:half])
    np.save(folder / "second.npy", x[half:])
    pd.DataFrame({"path": ["first.npy", "second.npy"], "fs": [FS, FS], "rpm": [900, 900],
                  "bearing": ["6205", "6205"]}).to_csv(folder / "healthy.csv", index=False)
    return folder, {"first": x[:half], "second": x[half:]}


@pytest.fixture(scope="module")
def dataset(machine, tmp_path_factory):
    folder, _ = machine
    grid = twin(folder / "healthy.csv", rpm=[900], out=folder / "grids" / "twin.toml",
                duration_s=0.25, draws=6, seed=0)
    out = tmp_path_factory.mktemp("ds") / "twin"
    summary = generate(grid, out, progress=False)
    X, meta = load(out)
    return grid, out, summary, X, meta


def test_twin_grid_names_the_machine(machine, dataset):
    folder, _ = machine
    grid_path = dataset[0]
    text = grid_path.read_text()
    assert 'manifest = "../healthy.csv"' in text   # relative to the grid's folder
    grid = read_grid(grid_path)
    assert grid.machine == {"manifest": str((folder / "healthy.csv").resolve())}
    assert grid.dataset["fs"] == FS and grid.axes["bearing"] == ["6205"]
    assert grid.axes["fault"] == ["healthy", "outer", "inner", "ball"]
    assert set(grid.distributions) >= {"level_db", "fault_width_mm"}


def test_healthy_rows_are_segments_of_the_recordings(machine, dataset):
    """Every healthy row is the recording's samples from its stored start, exactly (the
    fixture is float32, stored as float32); its group is the recording; both recordings
    serve. Planted: adding the fault signal to healthy rows too fails."""
    _, recordings = machine
    *_, X, meta = dataset
    healthy = meta.index[meta["label"] == "healthy"]
    assert len(healthy) == 6
    for i in healthy:
        rec = recordings[meta.at[i, "background"]]
        start = round(meta.at[i, "background_start_s"] * FS)
        np.testing.assert_array_equal(X[i], rec[start:start + X.shape[1]])
        assert meta.at[i, "group"] == meta.at[i, "background"]
        assert meta.at[i, "rpm"] == 900.0 and math.isnan(meta.at[i, "level_db"])
        assert math.isnan(meta.at[i, "radial_load_n"])   # a real segment's load is unknown
    # each healthy row picks one of the two 900 rpm recordings (p = 1/2 each): at seed 0
    # both serve (all six on one side would have p = 1/32)
    assert set(meta.loc[healthy, "background"]) == {"first", "second"}


def test_fault_rows_sit_at_their_level_over_the_background(machine, dataset):
    """A fault row minus its background segment is the fault through the path; its RMS
    over the background's is level_db (closed form of the scaling). The float32 storage
    rounds each sample by 6e-8 of its size, so 1e-4 holds at -10 dB. Planted: scaling to
    the recording's RMS instead of the segment's fails."""
    _, recordings = machine
    *_, X, meta = dataset
    faults = meta.index[meta["label"] != "healthy"]
    assert set(meta.loc[faults, "label"]) == {"outer", "inner", "ball"}
    for i in faults:
        rec = recordings[meta.at[i, "background"]]
        start = round(meta.at[i, "background_start_s"] * FS)
        background = rec[start:start + X.shape[1]].astype(float)
        fault = X[i].astype(float) - background
        ratio = fault.std() / background.std()
        assert 20 * np.log10(ratio) == pytest.approx(meta.at[i, "level_db"], abs=1e-3)
        assert -10 <= meta.at[i, "level_db"] <= 15
        assert meta.at[i, "group"] == f"run {meta.at[i, 'run_id']}"
    # ground truth as for a simulated row
    assert meta.loc[faults, "fault_width_mm"].between(0.2, 3.0).all()
    assert meta.loc[faults, "slip"].between(0.005, 0.02).all()
    assert meta.loc[faults, "impact_spread"].between(0.0, 1.0).all()
    assert meta.loc[meta["label"] == "healthy", "impact_spread"].isna().all()


def test_impact_sizes_are_log_normal_with_mean_one():
    """The sizes of a row's impacts: log-normal, the standard deviation of their log the
    row's impact_spread, their mean 1 (so the spread changes the impacts' shape, and
    level_db alone their level). Closed forms: E[m] = 1 and, for independent sizes over
    impacts that do not overlap, the fourth-moment ratio E[m^4] / E[m^2]^2 =
    exp(4 sigma^2), the factor by which the spread multiplies the kurtosis of a sparse
    impact train (e at sigma = 0.5). With n = 10^6 draws at sigma = 0.5 the sample mean
    is within 5e-4 (its standard error), the log's standard deviation within 4e-4 and
    the moment ratio within about 2 % (4 standard errors of a fourth moment of a
    log-normal at this sigma); tolerances 3 to 5 standard errors. Planted: dropping the
    -sigma^2/2 (mean exp(sigma^2 / 2) = 1.13) fails; a spread of 0 or NaN gives
    identical impacts, bit for bit."""
    from ballpass.datasets.twin import _impact_sizes

    rng = np.random.default_rng(5)
    m = _impact_sizes(rng, 1_000_000, 0.5)
    assert m.mean() == pytest.approx(1.0, abs=2.5e-3)
    assert np.log(m).std() == pytest.approx(0.5, abs=2e-3)
    assert np.mean(m**4) / np.mean(m**2) ** 2 == pytest.approx(math.exp(1.0), rel=0.08)
    for spread in (0.0, math.nan, None):
        np.testing.assert_array_equal(_impact_sizes(rng, 7, spread), np.ones(7))


def test_the_spread_axis_leaves_the_other_draws(dataset):
    """Drawing impact_spread, or fixing it at 0 (identical impacts, the twin before the
    axis existed), gives the same scenes and levels run by run: the spread is drawn after
    every other axis. Planted: the axis drawn before level_db (its place in the order of
    the fault axes) changes every later draw and fails."""
    grid = read_grid(dataset[0])
    raw = grid.as_dict()
    raw["grid"]["impact_spread"] = [0.0]
    fixed = read_grid(raw)
    assert [r.scene for r in grid.runs] == [r.scene for r in fixed.runs]
    assert ([r.columns.get("level_db") for r in grid.runs]
            == [r.columns.get("level_db") for r in fixed.runs])


def _fault_kurtosis(recordings, folder):
    """Kurtosis of each row of a twin dataset less its background segment (the fault
    through the path), and the dataset."""
    import scipy.stats

    X, meta = load(folder)
    kurt = []
    for i in meta.index:
        rec = recordings[meta.at[i, "background"]]
        start = round(meta.at[i, "background_start_s"] * FS)
        kurt.append(scipy.stats.kurtosis(X[i].astype(float) - rec[start:start + X.shape[1]],
                                         fisher=False))
    return np.asarray(kurt), X, meta


def test_the_spread_makes_a_row_more_impulsive(machine, tmp_path):
    """Two twins of the same scenes, one with identical impacts (impact_spread 0), one
    with sizes spread by 1: the second's fault rows are more impulsive (kurtosis of the
    fault signal, background removed; median over rows). Expected factor up to e^4 for
    impacts that never overlap and many impacts per row; with ~13 impacts per 0.25 s
    row, the load zone's own modulation and overlapping rings, a factor above 2 of the
    medians is asked, far below that. Planted: impacts' sizes drawn but not applied
    fails (ratio 1)."""
    folder, recordings = machine
    medians = {}
    for spread in (0.0, 1.0):
        grid = read_grid(twin(folder / "healthy.csv", rpm=[900], out=folder / "g.toml",
                              duration_s=0.25, draws=12, seed=1)).as_dict()
        grid["grid"].update(fault=["outer"], impact_spread=[spread], level_db=[0.0])
        generate(grid, tmp_path / f"s{spread}", progress=False)
        medians[spread] = np.median(_fault_kurtosis(recordings, tmp_path / f"s{spread}")[0])
    assert medians[1.0] > 2.0 * medians[0.0]   # 5.1 at this seed (Hertzian edges)


def _outer_scene(**kw):
    import ballpass as bp

    spec = dict(bearing="6205", fault=bp.Fault("outer", width_mm=1.0, depth_mm=0.3),
                rpm=900.0, duration_s=0.5, fs=FS, radial_load_n=500.0, slip=0.0,
                resonance_hz=FS / 4, needs=("envelope",))
    return bp.Scene(**{**spec, **kw})


@pytest.mark.parametrize("kind", ["outer", "inner", "ball"])
def test_a_passage_lasts_the_defect_width_over_the_rolling_speed(kind):
    """passage_times: w / v against the impulse model's own kinematics (an independent
    computation: the cage-angle integration and the edge-crossing search), the entry to
    exit time of every passage of a 1 mm defect at 900 rpm without slip. The crossings
    are found to 1e-13 s and the speed is constant: 1e-6 relative. Planted: the inner
    race's radius for the outer race's (a factor 1.5) fails; the cage rate for the inner
    race's relative rate fails."""
    import ballpass as bp
    from ballpass.datasets.twin import passage_times

    scene = _outer_scene(fault=bp.Fault(kind, width_mm=1.0, depth_mm=0.3))
    # a ball defect's passage lasts as long on either race (its own surface speed)
    passage_s, edge_s, drop = passage_times(scene, "outer" if kind == "ball" else None)
    crossings = bp.simulate(scene, model="impulse").truth.fault_crossings
    edges = np.asarray(crossings.edge)
    # a passage: a crossing and the same element's next one of the other edge (an
    # inner-race defect's paths run backwards through it, so its names are swapped)
    durations = []
    for i in range(len(edges)):
        later = [j for j in range(i + 1, len(edges))
                 if crossings.element[j] == crossings.element[i]]
        if later and edges[i] != edges[later[0]]:
            durations.append(crossings.time_s[later[0]] - crossings.time_s[i])
    durations = np.asarray(durations)
    short = durations[durations < 0.5 * durations.max()]   # passages, not the gaps
    assert short.size > 3
    np.testing.assert_allclose(short, passage_s, rtol=1e-6)
    assert 0 < edge_s <= 0.5 * passage_s and 0 < drop <= 1


def test_the_edge_lasts_while_the_ball_regains_its_deflection():
    """The edge: x_c / v with x_c = sqrt(2 r delta), r = 1 / (1/R_b - 1/R_o) the
    relative radius of the ball in the concave outer race, delta the most loaded
    element's Hertzian deflection, here taken independently from the force the impulse
    model releases at the load line into a defect deeper than the deflection,
    dQ = K delta^1.5 (impact_amplitudes, K of the bearing's Hertz stiffness). Same
    formulas, another path through the code: 1e-9. Planted: the ball's diameter for its
    radius (a factor sqrt 2) fails; the ball's radius alone (a factor 0.91) fails."""
    import ballpass as bp
    from ballpass.datasets.twin import passage_times
    from ballpass.simulate.impulse import impact_amplitudes

    scene = _outer_scene(fault=bp.Fault("outer", width_mm=3.0, depth_mm=1.0), gravity=False)
    passage_s, edge_s, drop = passage_times(scene)
    b = scene.bearing
    dq = impact_amplitudes(scene, np.zeros(1), np.full(1, 1e-3))[0]
    delta = (dq / b.hertz_stiffness()) ** (1 / 1.5)
    speed = 3.0e-3 / passage_s
    assert drop == 1.0   # the 1 mm deep, 3 mm wide defect takes the whole load
    r = 1.0 / (2.0 / b.element_diameter_m - 2.0 / (b.pitch_diameter_m + b.element_diameter_m))
    assert edge_s == pytest.approx(math.sqrt(2.0 * r * delta) / speed, rel=1e-9)


def test_a_ball_defects_edges_follow_the_race_it_strikes():
    """A 1 mm ball defect at 500 N drops (40 um on the inner race, 26 um on the outer)
    beyond the most loaded ball's deflection delta: the ball loses its whole load on
    either race (drop share 1) and regains it over x_c = sqrt(2 r delta), r =
    1 / (1/R_b +- 1/R_race) the pair's relative radius: the inner edge is
    sqrt(r_i / r_o) = 0.82x the outer one, the passage the same. delta independently
    from the force the impulse model releases at the load line into a deep defect, as
    above (1e-9). Without a race the ball defect is refused. Planted: the ball's own
    radius for r (both edges alike) fails."""
    import ballpass as bp
    from ballpass.datasets.twin import passage_times
    from ballpass.simulate.impulse import impact_amplitudes

    scene = _outer_scene(fault=bp.Fault("ball", width_mm=1.0, depth_mm=0.3), gravity=False)
    b = scene.bearing
    rb = 0.5 * b.element_diameter_m
    delta = (impact_amplitudes(scene, np.zeros(1), np.full(1, 1e-3))[0]
             / b.hertz_stiffness()) ** (1 / 1.5)
    (p_in, e_in, d_in), (p_out, e_out, d_out) = (passage_times(scene, "inner"),
                                                 passage_times(scene, "outer"))
    assert p_in == p_out and d_in == d_out == 1.0
    speed = 1e-3 / p_in
    for edge, r in ((e_in, 1 / (1 / rb + 1 / b.inner_race_radius_m)),
                    (e_out, 1 / (1 / rb - 1 / b.outer_race_radius_m))):
        assert edge == pytest.approx(math.sqrt(2 * r * delta) / speed, rel=1e-9)
    with pytest.raises(ValueError, match="race must be 'inner' or 'outer'"):
        passage_times(scene)


def test_the_edge_kernel_is_the_hertzian_load_return():
    """The load comes back as (1 - drop u^2)^1.5, u = x / x_c from 1 to 0 (closed form):
    the kernel's running sum is that load, normalized, at the sample ends, for a full
    (drop 1) and a partial (drop 0.3) return; round(edge_s fs) samples, at least 1.
    Planted: a linear load return (exponent 1) fails."""
    from ballpass.datasets.twin import edge_kernel

    for drop in (1.0, 0.3):
        k = edge_kernel(20 / FS, FS, 1.5, drop)
        assert k.size == 20 and k.sum() == pytest.approx(1.0, abs=1e-12)
        u = 1.0 - np.arange(1, 21) / 20
        load = (1.0 - drop * u**2) ** 1.5
        np.testing.assert_allclose(np.cumsum(k), (load - (1 - drop) ** 1.5)
                                   / (1 - (1 - drop) ** 1.5), atol=1e-12)
    assert edge_kernel(0.0, FS).tolist() == [1.0]   # no edge: one point


def test_a_passage_is_seen_in_the_train_from_entry_to_exit():
    """One passage ending at t0 (between samples): the train is non-zero from the entry
    edge's first sample, (t0 - w/v) fs, to the exit's last, t0 fs, each end within a
    sample (the split of a point between two samples); the load taken at the entry
    comes back at the exit (sum 0 to rounding); the exit edge carries the step.
    Planted: the entry placed at the exit time (no passage) fails."""
    from ballpass.datasets.twin import _passage_train, edge_kernel

    t0, passage_s = 0.1000123, 1.134e-3
    edge = edge_kernel(10 / FS, FS)
    train = _passage_train(np.array([t0]), np.array([2.0]), 8192, FS, passage_s, edge)
    nonzero = np.flatnonzero(np.abs(train) > 1e-12)
    assert abs(nonzero[0] - (t0 - passage_s) * FS) < 1.0
    assert abs(nonzero[-1] - t0 * FS) < 1.0
    assert (nonzero[-1] - nonzero[0]) / FS == pytest.approx(passage_s, abs=2 / FS)
    assert train.sum() == pytest.approx(0.0, abs=1e-12)
    half = (nonzero[0] + nonzero[-1]) // 2
    assert train[half:].sum() == pytest.approx(2.0, abs=1e-12)


def test_correlated_sizes_have_the_stated_lag_one_correlation():
    """impact_correlation rho: the logarithms of successive sizes are a stationary AR(1)
    with lag-1 correlation rho, standard deviation the spread, mean size 1. With 4e5
    draws at rho 0.6 the lag-1 estimate's standard error is sqrt((1 - rho^2) / n) =
    1.3e-3 (tolerance 0.01, 8 s.e.), the log's standard deviation within 3e-3 and the
    mean within 0.01 (the correlation widens their errors by sqrt((1 + rho)/(1 - rho))
    = 2). Planted: without the sqrt(1 - rho^2) gain the log's standard deviation is
    0.625, fails. rho 0 or NaN draws exactly the independent sizes."""
    from ballpass.datasets.twin import _impact_sizes

    m = _impact_sizes(np.random.default_rng(3), 400_000, 0.5, 0.6)
    g = np.log(m)
    g0 = g - g.mean()
    assert np.mean(g0[1:] * g0[:-1]) / g0.var() == pytest.approx(0.6, abs=0.01)
    assert g.std() == pytest.approx(0.5, abs=0.01)
    assert m.mean() == pytest.approx(1.0, abs=0.01)
    base = _impact_sizes(np.random.default_rng(4), 50, 0.5)
    for rho in (0.0, math.nan, None):
        np.testing.assert_array_equal(_impact_sizes(np.random.default_rng(4), 50, 0.5, rho),
                                      base)


def test_the_edges_spread_an_impact_and_regenerate(machine, tmp_path):
    """Two twins of the same draws, point impacts (impact_edges 0) and Hertzian edges
    (1): the edges spread each impact over tens of samples, so the fault rows' kurtosis
    (background removed, median over rows) falls (by 5.5 at this seed; asked: by more
    than 1.5). A row with edges and correlated sizes regenerates bit for bit. Planted:
    edges computed but the point train used fails the ratio."""
    folder, recordings = machine
    medians = {}
    for edges in (0.0, 1.0):
        grid = read_grid(twin(folder / "healthy.csv", rpm=[900], out=folder / "g.toml",
                              duration_s=0.25, draws=8, seed=2)).as_dict()
        grid["grid"].update(fault=["outer", "inner"], impact_edges=[edges], level_db=[0.0],
                            impact_correlation=[0.5])
        generate(grid, tmp_path / f"e{edges}", progress=False)
        kurt, X, meta = _fault_kurtosis(recordings, tmp_path / f"e{edges}")
        medians[edges] = np.median(kurt)
    assert medians[0.0] > 1.5 * medians[1.0]   # 5.5 at this seed
    assert (meta["impact_edges"] == 1.0).all() and (meta["impact_correlation"] == 0.5).all()
    np.testing.assert_array_equal(regenerate(meta.iloc[-1]), X[-1])


def test_the_datasets_manifest_states_the_recordings_unit(dataset):
    """A twin's signals are in its recordings' unit, so its manifest does not claim m/s^2
    as a simulated dataset's does (planted: the simulated units always; fails)."""
    from ballpass.datasets.store import read_manifest

    _, out, *_ = dataset
    unit = read_manifest(out)["units"]["signal"]
    assert unit != "m/s^2" and "healthy.csv" in unit


def test_the_learned_path_is_stored(dataset):
    _, out, *_ = dataset
    stored = json.loads((Path(out) / MACHINE_FILE).read_text())
    assert [r["name"] for r in stored["recordings"]] == ["first", "second"]
    for r in stored["recordings"]:
        assert 1 <= r["order"] <= 51 and len(r["a"]) == r["order"] + 1
        assert all(0 < f < 0.45 * FS for f in r["resonances_hz"])


def test_groups_keep_a_recording_out_of_training(dataset):
    """In every fold of the grouped split, a recording whose segments are tested has no
    segment in training."""
    *_, meta = dataset
    folds = split_indices(meta, "run", n_splits=2)
    assert folds
    for train, test in folds:
        tested = set(meta.loc[test, "background"][meta.loc[test, "label"] == "healthy"])
        trained = set(meta.loc[train, "background"][meta.loc[train, "label"] == "healthy"])
        assert not tested & trained


def test_twin_rows_regenerate_bit_for_bit(dataset):
    *_, X, meta = dataset
    for label in ("healthy", "outer", "inner", "ball"):
        i = meta.index[meta["label"] == label][0]
        np.testing.assert_array_equal(regenerate(meta.loc[i]), X[i])


def test_twin_dataset_resumes(dataset):
    grid, out, summary, *_ = dataset
    assert summary.rows_written == 24
    assert generate(grid, out, progress=False).rows_written == 0


# ----------------------------------------------------------------------------- bad input
def test_twin_refuses_bad_input(machine, tmp_path):
    folder, _ = machine
    for rpm in ([0], [-600], [900, float("nan")]):
        with pytest.raises(ValueError, match="rpm must be shaft speeds > 0"):
            twin(folder / "healthy.csv", rpm=rpm, out=tmp_path / "t.toml")
    table = pd.read_csv(folder / "healthy.csv")
    table["path"] = [str(folder / p) for p in table["path"]]
    table.assign(label=["healthy", "inner"]).to_csv(tmp_path / "faulty.csv", index=False)
    with pytest.raises(ValueError, match="healthy recordings only; second .inner."):
        twin(tmp_path / "faulty.csv", rpm=[900], out=tmp_path / "t.toml")
    table.assign(fs=[FS, 48_000.0]).to_csv(tmp_path / "rates.csv", index=False)
    with pytest.raises(ValueError, match="one machine, but its recordings have fs"):
        twin(tmp_path / "rates.csv", rpm=[900], out=tmp_path / "t.toml")
    with pytest.raises(ValueError, match="duration_s = 2 s is longer"):
        twin(folder / "healthy.csv", rpm=[900], out=tmp_path / "t.toml", duration_s=2.0)
    assert not (tmp_path / "t.toml").exists()


def test_generate_refuses_a_twin_at_another_rate(dataset, tmp_path):
    """A grid whose fs is not the recordings' is refused before any work."""
    grid = read_grid(dataset[0]).as_dict()
    grid["dataset"]["fs"] = 48_000.0
    with pytest.raises(ValueError, match="dataset.fs = 48000 Hz, but the twin's recordings"):
        generate(grid, tmp_path / "ds", progress=False)
    assert not (tmp_path / "ds").exists()


def test_level_db_needs_a_machine():
    for axis in ("level_db", "impact_spread", "impact_edges", "impact_correlation"):
        with pytest.raises(ValueError, match=f"{axis} .* needs a .machine. table"):
            read_grid({"grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [900],
                                axis: [0.0]}})
    with pytest.raises(ValueError, match="impact_spread .* outside the allowed range"):
        read_grid({"grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [900],
                            "impact_spread": {"uniform": [-1.0, 1.0]}}})
    with pytest.raises(ValueError, match="impact_correlation .* outside the allowed range"):
        read_grid({"grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [900],
                            "impact_correlation": {"uniform": [0.0, 1.0]}}})


def test_impact_edges_is_zero_or_one(dataset):
    grid = read_grid(dataset[0]).as_dict()
    for bad in ([0.5], {"uniform": [0.0, 1.0]}, {"choice": [0.0, 0.5]}):
        grid["grid"]["impact_edges"] = bad
        with pytest.raises(ValueError, match="impact_edges must list 0 .* and/or 1"):
            read_grid(grid)
    grid["grid"]["impact_edges"] = {"choice": [0, 1]}   # the twin's default: drawn per row
    assert read_grid(grid).axes["impact_edges"].params == (0.0, 1.0)


def test_twin_command(machine, tmp_path, capsys):
    """``ballpass twin``: writes the grid; bad speeds are one error line naming --rpm's
    values and write nothing."""
    from ballpass.cli import main

    folder, _ = machine
    out = tmp_path / "twin.toml"
    assert main(["twin", str(folder / "healthy.csv"), "--rpm", "600", "900", "--out",
                 str(out), "--draws", "3", "--duration", "0.5"]) == 0
    grid = read_grid(out)
    assert grid.axes["rpm"] == [600.0, 900.0] and grid.dataset["draws"] == 3
    bad = tmp_path / "bad.toml"
    assert main(["twin", str(folder / "healthy.csv"), "--rpm", "0", "--out", str(bad)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "rpm must be shaft speeds > 0" in err[0]
    assert not bad.exists()


def test_benchmark_of_a_twin_reports_the_twins_recommended_pipeline(dataset, tmp_path):
    """``ballpass benchmark`` on a twin's dataset (it holds ``_machine.json``) reports
    :data:`RECOMMENDED_TWIN` as model ``recommended`` and names it in the report; on any
    other dataset :data:`RECOMMENDED`. Planted: the CLI not passing the twin's pipeline
    names the random forest in the report; fails."""
    from ballpass.cli import main
    from ballpass.commands.benchmark import _recommended_for
    from ballpass.diagnose._names import CLASSIFIERS, RECOMMENDED, RECOMMENDED_TWIN

    assert RECOMMENDED_TWIN != RECOMMENDED  # else this test could not tell them apart
    _, out, *_ = dataset
    assert _recommended_for(out) == RECOMMENDED_TWIN
    assert _recommended_for(tmp_path) == RECOMMENDED
    report = tmp_path / "rep"
    assert main(["benchmark", str(out), "--splits", "run", "--models", "recommended",
                 "--folds", "2", "--out", str(report), "-q"]) == 0
    models = (report / "results.md").read_text().split("## Models")[1]
    assert CLASSIFIERS[RECOMMENDED_TWIN[0]] in models, models
    assert f"`{RECOMMENDED_TWIN[1]}` features" in models, models


def test_benchmark_refuses_an_unknown_recommended_pipeline(dataset):
    from ballpass.datasets import load
    from ballpass.diagnose import run_benchmark

    X, meta = load(dataset[1])
    with pytest.raises(ValueError, match="recommended must be"):
        run_benchmark(X, meta, splits=["run"], models=["recommended"],
                      recommended=("random_forest", "volts"))
