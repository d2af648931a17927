"""A model named by the caller that cannot represent what the scene states is refused
(naming what is missing and which model has it), unless the caller opts in with
``allow_unrepresented=True``: a labelled simulation that silently lacks what its scene
states is wrong data. Also the flags and durations that were accepted silently.
"""

import numpy as np
import pytest

import ballpass as bp
from ballpass.datasets import read_grid

SHORT = {"duration_s": 0.05, "fs": 12_000, "resonance_hz": 3000}


@pytest.mark.parametrize("scene, model, missing, able", [
    (bp.Scene(bearing="6205", gears=bp.GearPair((20, 40)), **SHORT), "impulse",
     "gear_mesh", "gearbox"),
    (bp.Scene(bearing="6205", needs=("envelope",), **SHORT), "sr4", "envelope",
     "impulse, sr5"),
    (bp.Scene(bearing="6205", needs=("ball_dynamics",), **SHORT), "sr5", "ball_dynamics",
     "multibody"),
    (bp.Scene(bearing="6205", clearance_um=5.0, **SHORT), "impulse", "mounted_clearance",
     "sr5"),
])
def test_named_model_that_drops_what_the_scene_states_is_refused(scene, model, missing,
                                                                 able):
    with pytest.raises(ValueError, match=f"model '{model}' does not represent {missing}, "
                                         f"which the scene asks for.*Models that do: {able}"):
        bp.simulate(scene, model=model)
    with pytest.raises(ValueError, match=f"does not represent {missing}"):
        bp.simulate.resolve_model(scene, model)
    assert bp.simulate.unrepresented(scene, model) == {missing}


def test_opting_in_runs_the_model_and_says_what_it_left_out():
    gears = bp.GearPair((20, 40))
    scene = bp.Scene(bearing="6205", gears=gears, **SHORT)
    res = bp.simulate(scene, model="impulse", allow_unrepresented=True)
    assert "gear_mesh, which the scene asks for" in res.info["model_reason"]
    # what the caller opted into: no mesh at all. The healthy bearing gives the impulse
    # model nothing to strike, so its signal is zero, where the gearbox model's largest
    # line is the mesh at 20 x 29.95 Hz = 599 Hz (measured: 600 Hz bin, 0.05 s)
    assert not np.any(res.accel)


def test_a_plain_scene_still_runs_on_any_model_it_fits():
    """The defaults (envelope, contact dynamics) guide auto; they are no statement."""
    scene = bp.Scene(bearing="6205", fault=bp.Fault("outer"), **SHORT)
    assert bp.simulate(scene, model="impulse").info["model"] == "impulse"


@pytest.mark.parametrize("kwargs, error, says", [
    ({"return_forces": "yes"}, TypeError, "return_forces must be True or False, got 'yes'"),
    ({"allow_unrepresented": 1}, TypeError, "allow_unrepresented must be True or False"),
])
def test_flags_must_be_booleans(kwargs, error, says):
    with pytest.raises(error, match=says):
        bp.simulate(bp.Scene(bearing="6205", **SHORT), **kwargs)


def test_duration_below_one_sample_refused():
    with pytest.raises(ValueError, match=r"duration_s=1e-05 s is shorter than one sample at "
                                         r"fs=12000 Hz; give at least 8.33e-05 s"):
        bp.Scene(bearing="6205", duration_s=1e-5, fs=12_000, resonance_hz=3000)
    assert bp.Scene(bearing="6205", duration_s=1 / 12_000, fs=12_000,
                    resonance_hz=3000).n_samples == 1


@pytest.mark.parametrize("grid, where", [
    ({"dataset": {"model": "foo"}, "grid": {}}, "dataset.model"),
    ({"dataset": {}, "grid": {"model": ["sr5", "foo"]}}, r"grid.model\[1\]"),
])
def test_unknown_model_in_a_grid_refused_by_read_grid(grid, where):
    grid = {"dataset": {"duration_s": 0.1, **grid["dataset"]},
            "grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [1797], **grid["grid"]}}
    with pytest.raises(ValueError, match=f"{where}: unknown model 'foo'; use 'auto' or one "
                                         "of .*'impulse'"):
        read_grid(grid)


@pytest.mark.parametrize("model", ["auto", "sr5", "impulse"])
def test_unknown_solver_in_a_grid_refused_by_read_grid(model):
    # found by benchmarks/abuse_sweep.py: "foo" was kept and left to the simulator,
    # which for model "auto" picked a solver of its own
    grid = {"dataset": {"duration_s": 0.1, "model": model, "solver": "foo"},
            "grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [1797]}}
    with pytest.raises(ValueError, match=f"dataset.solver: unknown solver 'foo' for model "
                                         f"'{model}'; use 'auto' or one of"):
        read_grid(grid)


def test_element_of_a_race_fault_refused():
    # found by benchmarks/abuse_sweep.py: element picks the ball of a ball fault and was
    # ignored on a race fault, also out of range (99 on a 9-ball bearing)
    with pytest.raises(ValueError, match="fault element=99 picks the rolling element of a "
                                         "ball fault; a outer-race fault has none"):
        bp.Scene(bearing="6205", fault=bp.Fault("outer", element=99), **SHORT)
    assert bp.Scene(bearing="6205", fault=bp.Fault("ball", element=3), **SHORT)
