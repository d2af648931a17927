"""Cost of each sr5 option: wall time of 1 s of signal at 48 kHz, side by side.

Every option runs on the same scene (6205, 1797 rpm, 500 N, 0.5 mm outer-race fault,
one sensor), interleaved round by round so that the machine's load hits all alike;
the table gives the median over the rounds, the spread (min-max) and the ratio of
medians to the plain scene.

    python benchmarks/sr5_options_cost.py            # ~2 min on 2 cores

Writes ``docs/results/sr5_options_cost.md`` and ``.png``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from _paths import RESULTS_DIR
from _report import spread, table, write_page

import ballpass as bp
from ballpass.simulate import SR5Parameters

PLAIN = bp.Scene("6205", rpm=1797.0, fs=48_000.0, duration_s=1.0,
                 fault=bp.Fault("outer", width_mm=0.5, depth_mm=0.1))

#: option -> (scene changes, SR5Parameters keywords)
CASES = {
    "plain": ({}, {}),
    "waviness outer q=10": ({"waviness": bp.Waviness("outer", 10, 0.5)}, {}),
    "waviness ball q=2": ({"waviness": bp.Waviness("ball", 2, 0.5)}, {}),
    "edge blunt": ({"fault": bp.Fault("outer", 0.5, 0.1, edge="blunt")}, {}),
    "edge sharp": ({"fault": bp.Fault("outer", 0.5, 0.1, edge="sharp")}, {}),
    "pit geometry": ({"fault": bp.Fault("outer", 0.5, 0.1, geometry="pit")}, {}),
    "contact damping 10 s/m": ({}, {"contact_damping": 10.0}),
    "preload 5 um": ({"clearance_um": -5.0}, {}),
    "2 extra modes": ({"resonances": ((9000.0, 0.03, 0.5), (20000.0, 0.03, 0.5))}, {}),
    "background": ({"noise_rms": 0.5, "noise_slope_db_oct": -3.0,
                    "shaft_harmonics": (0.2, 0.1, 0.1, 0.3)}, {}),
    "ball, engagement 0.5": ({"fault": bp.Fault("ball", 0.5, 0.1, engagement=0.5)}, {}),
    "ball, engagement 1": ({"fault": bp.Fault("ball", 0.5, 0.1)}, {}),
    "free shaft support": ({}, {"shaft_support": "free"}),
}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args(argv)
    runs = {name: (PLAIN.replace(**sc), SR5Parameters(**pa)) for name, (sc, pa) in CASES.items()}
    for scene, params in runs.values():  # compile and warm up
        bp.simulate(scene, model="sr5", params=params)
    times = {name: [] for name in runs}
    for _ in range(args.rounds):
        for name, (scene, params) in runs.items():
            t0 = time.perf_counter()
            bp.simulate(scene, model="sr5", params=params)
            times[name].append(time.perf_counter() - t0)
    base = np.median(times["plain"])
    lines = table(["option", "median s (min-max)", "ratio to plain"],
                  [(name, spread(t, ".3f"), f"{np.median(t) / base:.2f}")
                   for name, t in times.items()], "lrr")
    print("\n".join(lines))
    out = RESULTS_DIR
    write_page(out / "sr5_options_cost.md", [
        "# Cost of the sr5 options (1 s at 48 kHz, rk4 default step)", "",
        f"Medians over {args.rounds} interleaved rounds on a shared 2-core machine; "
        "ratio of medians to the plain scene.", "", *lines])
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8, 4.5), layout="constrained")
    ax = fig.subplots()
    names = list(times)
    ax.barh(names, [np.median(times[n]) for n in names], color="tab:blue")
    ax.errorbar([np.median(times[n]) for n in names], names,
                xerr=[[np.median(times[n]) - min(times[n]) for n in names],
                      [max(times[n]) - np.median(times[n]) for n in names]],
                fmt="none", color="k", lw=0.8)
    ax.invert_yaxis()
    ax.set_xlabel("wall time for 1 s at 48 kHz, s (median, min-max)")
    ax.set_title("sr5 options: cost", fontsize=10)
    fig.savefig(out / "sr5_options_cost.png", dpi=100)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
