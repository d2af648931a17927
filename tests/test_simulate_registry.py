"""The model registry, scene needs, model="auto", solver-option checks and the kernel
cache stamp (issue 10 items 1-3; issue 16 item 6; issue 9 item 5 "stale kernels")."""

from __future__ import annotations

import json
import shutil
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import ballpass as bp
from ballpass.phenomena import DEFAULT_NEEDS, PHENOMENA
from ballpass.simulate import MODELS, resolve_model, scene_needs
from ballpass.simulate._cache import clear_stale_cache, source_fingerprint


@pytest.mark.parametrize("name", list(MODELS))
def test_registry_contract(name):
    m = MODELS[name]
    assert m.name == name
    assert m.represents <= set(PHENOMENA)
    assert m.relative_cost > 0 and m.description and m.reference
    assert m.default_solver in m.solvers
    assert set(m.fixed_step_solvers) <= set(m.solvers)
    scene = bp.Scene(bearing="6205", duration_s=0.01)
    verdict = m.accepts(scene)
    assert verdict is None or (isinstance(verdict, str) and verdict)


@pytest.mark.parametrize("name", list(MODELS))
def test_every_model_runs_the_shared_scene_contract(name):
    # what every model owes the rest of the toolkit, whatever its physics: the scene's
    # sampling, one channel per sensor in m/s^2 (finite, AC-coupled), the tachometer and
    # the fault crossings as ground truth, its own name and reason in info, and the same
    # result for the same seed
    m = MODELS[name]
    scene = bp.Scene(bearing="6205", rpm=1797.0, fault=bp.Fault("inner"), duration_s=0.05,
                     fs=24_000.0, resonance_hz=6_000.0, sensors=("loaded", "unloaded"))
    if m.accepts(scene) is not None:
        pytest.skip(f"{name} does not take the reference scene: {m.accepts(scene)}")
    res = bp.simulate(scene, model=name)
    assert res.info["model"] == name and res.info["model_reason"]
    assert res.info["solver"] in m.solvers
    assert res.fs == scene.fs and res.accel.shape == (2, scene.n_samples)
    assert res.sensor_names == ("loaded", "unloaded")
    assert np.all(np.isfinite(res.accel)) and np.any(res.accel != 0.0)
    # AC-coupled: the mean is zero to rounding (1e-12 of the largest sample)
    assert np.all(np.abs(res.accel.mean(axis=1)) <= 1e-12 * np.abs(res.accel).max())
    assert res.t.shape == (scene.n_samples,) and res.truth.label == "inner"
    if "envelope" in m.represents:
        # a model of the fault impacts lists them: an inner-race defect meets an element
        # BPFI times a second (within one pass)
        entries = res.truth.fault_crossings.entries()
        assert abs(entries.size - scene.frequencies.bpfi * scene.duration_s) <= 1.0
    np.testing.assert_array_equal(bp.simulate(scene, model=name).accel, res.accel)


def test_registry_is_sorted_by_cost_with_sr5_as_unit():
    costs = [m.relative_cost for m in MODELS.values()]
    assert costs == sorted(costs)
    assert MODELS["sr5"].relative_cost == 1.0


def test_scene_needs_from_fields():
    plain = bp.Scene(bearing="6205")
    assert scene_needs(plain) == DEFAULT_NEEDS
    ramp = bp.Scene(bearing="6205", rpm=(600.0, 1800.0))
    assert "varying_speed" in scene_needs(ramp)
    assert "contact_forces" in scene_needs(plain, return_forces=True)
    only = bp.Scene(bearing="6205", needs=("envelope",))
    assert scene_needs(only) == {"envelope"}


def test_unknown_need_is_refused_with_the_vocabulary():
    with pytest.raises(ValueError, match=r"unknown phenomenon 'sparks'.*envelope"):
        bp.Scene(bearing="6205", needs=("sparks",))
    with pytest.raises(TypeError, match="needs"):
        bp.Scene(bearing="6205", needs=(3,))


def test_plain_scene_resolves_to_sr5_and_says_why():
    scene = bp.Scene(bearing="6205", fault=bp.Fault("outer"), duration_s=0.02)
    res = bp.simulate(scene)
    assert res.info["model"] == "sr5"
    # impulse is cheaper but has no contact dynamics: the reason must say what it lacked
    assert "impulse lacks contact_dynamics" in res.info["model_reason"]


def test_requested_model_that_lacks_a_need_is_run_but_the_reason_says_so():
    scene = bp.Scene(bearing="6205", duration_s=0.02)
    res = bp.simulate(scene, model="sr4")
    assert res.info["model"] == "sr4"
    assert "does not represent envelope" in res.info["model_reason"]


def _cheapest_covering(needs, scene):
    """The rule of resolve_model: the cheapest model that can take the scene (a gearbox
    needs a gear pair) and represents the needs."""
    for m in MODELS.values():
        if needs <= m.represents and m.accepts(scene) is None:
            return m.name
    return None


@settings(max_examples=60, deadline=None)
@given(needs=st.sets(st.sampled_from(sorted(PHENOMENA))),
       ramp=st.booleans(), forces=st.booleans())
def test_auto_picks_the_cheapest_covering_model(needs, ramp, forces):
    scene = bp.Scene(bearing="6205", rpm=(900.0, 1800.0) if ramp else 1797.0,
                     needs=tuple(needs))
    wanted = set(needs or DEFAULT_NEEDS) | ({"varying_speed"} if ramp else set()) \
        | ({"contact_forces"} if forces else set())
    expected = _cheapest_covering(frozenset(wanted), scene)
    if expected is None:
        with pytest.raises(ValueError, match="no model represents"):
            resolve_model(scene, return_forces=forces)
    else:
        got = resolve_model(scene, return_forces=forces)
        assert got == expected
        assert wanted <= MODELS[got].represents


def test_unknown_model_is_refused():
    with pytest.raises(ValueError, match=r"model must be 'auto' or one of"):
        resolve_model(bp.Scene(bearing="6205"), "sr9")


@pytest.mark.parametrize(("solver", "kwargs", "match"), [
    ("dopri5", {"dt": 1e-5}, "dt=1e-05 applies to the fixed-step solvers"),
    ("rk4", {"rtol": 1e-9}, "rtol/atol apply to adaptive solvers"),
    ("rk4", {"atol": 2.0}, "rtol/atol apply to adaptive solvers"),
    ("euler", {}, "solver must be 'auto' or one of"),
    ("auto", {"rtol": 1e-9}, "rtol/atol apply to adaptive solvers"),  # sr5's default is rk4
])
def test_solver_options_the_solver_would_ignore_are_refused(solver, kwargs, match):
    scene = bp.Scene(bearing="6205", duration_s=0.01)
    with pytest.raises(ValueError, match=match):
        bp.simulate(scene, solver=solver, **kwargs)


def test_rounded_step_is_announced():
    scene = bp.Scene(bearing="6205", duration_s=0.01, fs=48_000)
    with pytest.warns(UserWarning, match=r"dt=1e-05 s rounded to"):
        res = bp.simulate(scene, solver="rk4", dt=1e-5)
    # 1e-5 s is not a divisor of the 5.2 us internal grid: the step used is the next
    # divisor below, 5.2083 us / 1, and info reports it
    assert res.info["dt_s"] == pytest.approx(1.0 / (4 * 48_000.0) / 1, rel=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bp.simulate(scene, solver="rk4", dt=1.0 / (4 * 48_000.0))  # exact: silent


def _copy_package(tmp_path):
    src = bp.simulate.__file__.rsplit("/", 1)[0]
    dst = tmp_path / "simulate"
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("__pycache__"))
    return dst


def test_fingerprint_follows_every_source_file(tmp_path):
    pkg = _copy_package(tmp_path)
    before = source_fingerprint(pkg)
    assert before == source_fingerprint(pkg)
    kernels = pkg / "_kernels.py"
    kernels.write_text(kernels.read_text() + "\n# an edit\n")
    assert source_fingerprint(pkg) != before


def test_stale_kernel_cache_is_cleared_and_a_current_one_kept(tmp_path):
    pkg = _copy_package(tmp_path)
    cache = pkg / "__pycache__"
    cache.mkdir()
    assert clear_stale_cache(pkg) == []  # nothing cached yet; stamps the folder
    cached = [cache / "_integrators.rk4-10.py311.nbi", cache / "_integrators.rk4-10.py311.1.nbc"]
    for f in cached:
        f.write_bytes(b"machine code")
    assert clear_stale_cache(pkg) == []  # sources unchanged: the cache is kept
    assert all(f.exists() for f in cached)
    # the bug this guards against: an edit of _kernels.py left _integrators' kernels,
    # which inline it, cached
    kernels = pkg / "_kernels.py"
    kernels.write_text(kernels.read_text().replace("import", "import", 1) + "\nX = 2\n")
    deleted = clear_stale_cache(pkg)
    assert sorted(deleted) == sorted(cached)
    assert not any(f.exists() for f in cached)


def test_dataset_grid_needs_resolve_the_model_each_row_records(tmp_path):
    grid = {"dataset": {"duration_s": 0.05, "fs": 12_000, "needs": ["envelope"]},
            "grid": {"bearing": ["6205"], "fault": ["outer", "inner"], "rpm": [1797],
                     "resonance_hz": [3000]}}
    bp.datasets.generate(grid, tmp_path / "ds", n_jobs=1, progress=False)
    X, meta = bp.datasets.load(tmp_path / "ds")
    assert list(meta["model"]) == ["impulse", "impulse"]
    # the stored scene carries its needs, and a row regenerates bit for bit
    assert json.loads(meta["scene"].iloc[0])["needs"] == ["envelope"]
    np.testing.assert_array_equal(bp.datasets.regenerate(meta.iloc[1]), X[1])
    with pytest.raises(ValueError, match=r"dataset.needs names an unknown phenomenon 'sparks'"):
        bp.datasets.read_grid({**grid, "dataset": {"needs": ["sparks"]}})


def test_first_call_reports_compile_time_apart_from_the_run():
    """Issue 14: the first simulation of a process compiles (or loads) the integrator;
    that time is reported as compile_time_s, not as the run, and the warm-up on a 2-point
    grid does not change the integration (same steps as a warm run)."""
    import json
    import subprocess
    import sys

    code = (
        "import json, ballpass as bp\n"
        "s = bp.Scene(bearing='6205', fault=bp.Fault('outer'), duration_s=0.05, fs=12000,"
        " resonance_hz=3000)\n"
        "a = bp.simulate(s).info; b = bp.simulate(s).info\n"
        "print(json.dumps([a['compile_time_s'], b['compile_time_s'], a['n_steps'],"
        " b['n_steps'], a['wall_time_s']]))\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=600, check=True)
    first, second, steps_a, steps_b, wall = json.loads(proc.stdout.splitlines()[-1])
    assert first > 0.0 and second == 0.0
    assert steps_a == steps_b
    # loading the kernels, even from numba's cache, takes ~0.4 s; integrating this 0.05 s
    # scene ~4 ms: a first-call wall time that still contained the load would exceed it
    assert 0.0 <= wall < first


@pytest.mark.parametrize(("fields", "need"), [
    ({"clearance_um": -3.0}, "mounted_clearance"),
    ({"resonances": ((4_000.0, 0.02, 0.5),)}, "structural_modes"),
    ({"fault": bp.Fault("outer", geometry="pit")}, "pit_faults"),
])
def test_auto_never_picks_a_model_that_drops_a_field_the_scene_sets(fields, need):
    # with needs=("envelope",) alone the impulse model would be cheapest, but it ignores
    # these three fields: auto must go to sr5, which honours them (intermittent ball
    # faults, which both honour, are tested in test_spin_drift.py)
    scene = bp.Scene(bearing="6205", needs=("envelope",), **fields)
    assert need in bp.simulate.scene_needs(scene)
    assert bp.simulate.resolve_model(scene) == "sr5"
    plain = bp.Scene(bearing="6205", needs=("envelope",))
    assert bp.simulate.resolve_model(plain) == "impulse"
    # asked for by name it is refused, naming what it lacks and who has it; run only
    # when the caller opts in, and then it says what it leaves out
    with pytest.raises(ValueError, match=f"model 'impulse' does not represent {need}, .*"
                                         "Models that do: sr5"):
        bp.simulate(scene.replace(duration_s=0.05), model="impulse")
    res = bp.simulate(scene.replace(duration_s=0.05), model="impulse",
                      allow_unrepresented=True)
    assert need in res.info["model_reason"]
