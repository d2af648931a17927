"""Write ``impulse_reference.npz``: the impulse model's output on a few scenes, for
tests/test_impulse_reference.py. First written by the code before its fixed cost was
cut (commit 09c66d7); rewritten when the defects' depths took the race's curvature
(``Fault.effective_depth_mm`` against the race struck), which changed every scene's
impact sizes, and nothing else (crossing times, elements and edges as before).

    PYTHONPATH=. python tests/data/make_impulse_reference.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import ballpass as bp

#: short scenes covering each branch of the model: race and ball faults, a run-up and a
#: run-down, two faults, two sensors, no gravity, noise, a 12 kHz output
SCENES = {
    "inner_48k": dict(rpm=1797.0, radial_load_n=500.0, fault=bp.Fault("inner"), fs=48_000.0,
                      resonance_hz=15_000.0),
    "outer_two_sensors": dict(rpm=1500.0, fault=bp.Fault("outer", angle_deg=10.0),
                              sensors=("loaded", "unloaded"), seed=3),
    "ball": dict(rpm=1730.0, fault=bp.Fault("ball", width_mm=0.4, element=2), seed=5),
    "run_up": dict(rpm=(600.0, 2400.0), fault=bp.Fault("outer"), seed=7),
    "run_down_inner": dict(rpm=(2000.0, 900.0), fault=bp.Fault("inner", angle_deg=30.0),
                           gravity=False, seed=11),
    "two_faults_noise": dict(rpm=1797.0, fault=(bp.Fault("outer"), bp.Fault("ball")),
                             snr_db=10.0, seed=13),
    "cwru_12k": dict(rpm=1772.0, radial_load_n=300.0, fault=bp.Fault("inner", width_mm=0.18),
                     fs=12_000.0, resonance_hz=3_500.0, seed=17),
}


def scene(name: str) -> bp.Scene:
    return bp.Scene("6205", duration_s=0.05, **SCENES[name])


def outputs(res) -> dict[str, np.ndarray]:
    """What a user sees of one run but the sample times, the shaft angle and the speed
    (the test checks those against their closed forms)."""
    c = res.truth.fault_crossings
    return {"accel": np.asarray(res.accel), "crossing_time_s": c.time_s, "crossing_fault": c.fault,
            "crossing_element": c.element, "crossing_edge": c.edge.astype("U10"),
            "n_impacts": np.array(res.info["n_impacts"])}


def main() -> None:
    arrays = {}
    for name in SCENES:
        for key, value in outputs(bp.simulate(scene(name), model="impulse")).items():
            arrays[f"{name}/{key}"] = value
    np.savez_compressed(Path(__file__).with_name("impulse_reference.npz"), **arrays)


if __name__ == "__main__":
    main()
