"""Write ``multibody_reference.npz``: the multibody model's output on a few short scenes,
from the code before its right-hand side was made cheaper (commit 4c0980f), for
tests/test_multibody_reference.py.

    PYTHONPATH=. python tests/data/make_multibody_reference.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import ballpass as bp

#: short scenes covering each branch of the right-hand side: an inner-race notch at
#: 48 kHz (the cost scene of benchmarks/models_cost.py), ball and outer notches at once
#: with two sensors (the transmission weights), a run-up without gravity, and the
#: Rosenbrock-W solver
SCENES = {
    "inner_48k": (dict(rpm=1797.0, radial_load_n=500.0,
                       fault=bp.Fault("inner", width_mm=0.5, depth_mm=0.1), fs=48_000.0,
                       resonance_hz=15_000.0), "rk4"),
    "ball_outer_two_sensors": (dict(rpm=1500.0, radial_load_n=300.0,
                                    fault=(bp.Fault("outer", angle_deg=10.0),
                                           bp.Fault("ball", width_mm=0.4, element=2)),
                                    sensors=("loaded", "unloaded")), "rk4"),
    "run_up_rosw": (dict(rpm=(1200.0, 2400.0), radial_load_n=800.0, gravity=False,
                         fault=bp.Fault("inner", angle_deg=30.0), fs=12_000.0,
                         resonance_hz=3_500.0), "rosw"),
}


def scene(name: str) -> bp.Scene:
    return bp.Scene("6205", duration_s=0.01, **SCENES[name][0])


def run(name: str):
    return bp.simulate(scene(name), model="multibody", solver=SCENES[name][1],
                       return_forces=True)


def outputs(res) -> dict[str, np.ndarray]:
    """The signal, the contact loads, the ball angles, the ring displacements and the
    fault crossings of one run."""
    c = res.truth.fault_crossings
    tr = res.truth
    return {"accel": np.asarray(res.accel), "q_inner": np.asarray(tr.contact_forces),
            "q_outer": np.asarray(tr.outer_contact_forces),
            "angles": np.asarray(tr.element_angles), "disp": np.asarray(tr.displacement),
            "crossing_time_s": c.time_s, "crossing_fault": c.fault,
            "crossing_element": c.element, "crossing_edge": c.edge.astype("U10")}


def main() -> None:
    arrays = {}
    for name in SCENES:
        for key, value in outputs(run(name)).items():
            arrays[f"{name}/{key}"] = value
    np.savez_compressed(Path(__file__).with_name("multibody_reference.npz"), **arrays)


if __name__ == "__main__":
    main()
