"""Work-precision of the simulator on representative scenes, against scipy.

Runs :func:`ballpass.simulate.work_precision` (every ballpass solver over its step
size / tolerance sweep, scipy ``solve_ivp`` RK45, DOP853, LSODA and Radau over
tolerances, all on the same sr5 equations, errors against ballpass dopri5 at rtol
1e-10) on a subset of the representative set -- healthy, outer, inner, ball; 300 and
6000 rpm; 0.1 mm and 2 mm wide faults -- chosen so that every kind, speed and size
appears and the whole runs in well under an hour on two cores:

====================  ==========  =========  ==============
scene                 rpm         width      simulated
====================  ==========  =========  ==============
healthy               300, 6000   --         0.5 s, 0.2 s
outer                 6000, 300   0.1, 2 mm  0.2 s, 0.5 s
inner                 300, 6000   0.1, 2 mm  0.5 s, 0.2 s
ball                  6000, 300   0.1, 2 mm  0.2 s, 0.5 s
====================  ==========  =========  ==============

(6205, 500 N, 48 kHz, 15 kHz / 5 % resonance, faults 0.1 mm deep; 0.5 s at 300 rpm
holds 9 outer-race impacts.) Writes ``docs/work_precision.md`` (tables, speed-up at
equal error), ``docs/results/work_precision.png`` (log-log plots) and
``docs/results/work_precision.csv`` (every run).

    python benchmarks/work_precision.py                  # the set above
    python benchmarks/work_precision.py --quick          # two short scenes, no Radau
"""

from __future__ import annotations

import argparse
import math
import time

import matplotlib

matplotlib.use("Agg")
import _machine  # benchmarks/_machine.py (scripts run from their folder)
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402
from _paths import DOCS, RESULTS_DIR

import ballpass as bp  # noqa: E402
from ballpass import __version__  # noqa: E402
from ballpass.simulate import plot_work_precision, speedup, work_precision  # noqa: E402

#: (kind, rpm, width mm, simulated s)
SCENES = [
    ("healthy", 300.0, None, 0.5),
    ("healthy", 6000.0, None, 0.2),
    ("outer", 6000.0, 0.1, 0.2),
    ("outer", 300.0, 2.0, 0.5),
    ("inner", 300.0, 0.1, 0.5),
    ("inner", 6000.0, 2.0, 0.2),
    ("ball", 6000.0, 0.1, 0.2),
    ("ball", 300.0, 2.0, 0.5),
]
QUICK = [("outer", 6000.0, 0.1, 0.05), ("inner", 300.0, 2.0, 0.2)]
LEVELS = (1e-2, 1e-3, 1e-4)


def make_scene(kind, rpm, width, duration) -> bp.Scene:
    fault = None if kind == "healthy" else bp.Fault(kind, width_mm=width, depth_mm=0.1)
    return bp.Scene("6205", rpm=rpm, fault=fault, duration_s=duration, fs=48_000.0)


def name(kind, rpm, width, duration) -> str:
    size = "" if width is None else f" {width:g} mm"
    return f"{kind}{size}, {rpm:g} rpm"


def run(scenes, methods, time_limit) -> list[tuple[str, pd.DataFrame]]:
    results = []
    for spec in scenes:
        label = name(*spec)
        print(f"== {label}, {spec[3]:g} s", flush=True)
        t0 = time.perf_counter()
        table = work_precision(make_scene(*spec), scipy_methods=methods,
                               scipy_time_limit=time_limit, progress=True)
        print(f"   {time.perf_counter() - t0:.0f} s", flush=True)
        table.insert(0, "scene", label)
        results.append((label, table))
    return results


def fmt_ratio(v: float) -> str:
    return "--" if not math.isfinite(v) else f"{v:.0f}x"


def write(results, methods, time_limit, quick) -> None:
    RESULTS_DIR.mkdir(parents=True, exist_ok=True)
    everything = pd.concat([t for _, t in results], ignore_index=True)
    everything.to_csv(RESULTS_DIR / "work_precision.csv", index=False)

    n = len(results)
    cols = 2 if n > 1 else 1
    rows = -(-n // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6.2 * cols, 4.0 * rows), squeeze=False)
    for ax, (label, table) in zip(axes.flat, results, strict=False):
        plot_work_precision(table, ax=ax, title=f"{label}, {table.attrs['duration_s']:g} s")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.tight_layout()
    fig.savefig(RESULTS_DIR / "work_precision.png", dpi=110)
    plt.close(fig)

    lines = [
        "# Work-precision: ballpass solvers against scipy",
        "",
        "Wall time against error of every ballpass solver and of scipy's `solve_ivp` "
        f"({', '.join(methods) or 'none'}) on the same sr5 equations, for a 6205 at 500 N "
        "sampled at 48 kHz (15 kHz / 5 % resonance, faults 0.1 mm deep). Produced by "
        f"`python benchmarks/work_precision.py{' --quick' if quick else ''}` with ballpass "
        f"{__version__} on {_machine.machine()} (shared, so timings are noisy).",
        "",
        "How it is measured (`ballpass.simulate.work_precision`):",
        "",
        "* error: relative L2 error of the output acceleration after the anti-alias "
        "decimation (`error_l2`), and the largest error of the squared-envelope-spectrum "
        "amplitudes at harmonics 1-3 of the scene's fault frequency relative to the "
        "tallest (`error_ses`), both against ballpass dopri5 at rtol 1e-10;",
        "* every integration is restarted at the same non-smooth points (fault edges, "
        "slip-walk knots): scipy gets the event handling ballpass has;",
        "* ballpass time: `integrate` including the event search, best of 3; scipy time: "
        "stepping plus dense output at the output grid, one run, a method's sweep stopped "
        f"after a run longer than {time_limit:g} s;",
        "* speed-up: wall time of the fastest scipy method over the ballpass solver's to "
        "reach the same error, interpolated log-log along each method's Pareto front, or "
        "its cheapest run's time when even that is more accurate (no extrapolation: -- "
        "where a curve does not reach the error).",
        "",
        "![work-precision](results/work_precision.png)",
        "",
        "## Speed-up over the fastest scipy method at equal error",
        "",
    ]
    for error in ("error_l2", "error_ses"):
        lines += [f"`{error}`:", "",
                  "| scene | solver | " + " | ".join(f"at {lv:g}" for lv in LEVELS) + " |",
                  "|---|---|" + "---:|" * len(LEVELS)]
        for label, table in results:
            ratios = speedup(table, error=error, at=LEVELS)
            for method, row in ratios.iterrows():
                lines.append(f"| {label} | {method} | "
                             + " | ".join(fmt_ratio(v) for v in row) + " |")
        lines.append("")
    lines += ["## Every run", "",
              "Wall time per simulated second (s) and errors; `status` other than ok: the "
              "run was stopped by the time limit.", ""]
    for label, table in results:
        lines += [f"### {label}, {table.attrs['duration_s']:g} s "
                  f"(reference: {table.attrs['reference_wall_s']:.2f} s)", "",
                  "| method | setting | s per simulated s | steps | error_l2 | error_ses | "
                  "status |", "|---|---|---:|---:|---:|---:|---|"]
        for r in table.itertuples():
            lines.append(f"| {r.method} | {r.setting} | {r.wall_per_sim_s:.3g} | "
                         f"{r.n_steps} | {r.error_l2:.1e} | {r.error_ses:.1e} | {r.status} |")
        lines.append("")
    (DOCS / "work_precision.md").write_text("\n".join(lines))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="two short scenes and no Radau (a few minutes)")
    parser.add_argument("--scipy-time-limit", type=float, default=120.0,
                        help="seconds before a scipy method's sweep is stopped (120)")
    args = parser.parse_args()
    scenes = QUICK if args.quick else SCENES
    methods = ("RK45", "DOP853", "LSODA") if args.quick else ("RK45", "DOP853", "LSODA",
                                                             "Radau")
    results = run(scenes, methods, args.scipy_time_limit)
    write(results, methods, args.scipy_time_limit, args.quick)
    print(f"-> {DOCS / 'work_precision.md'}, {RESULTS_DIR}/work_precision.{{png,csv}}")


if __name__ == "__main__":
    main()
