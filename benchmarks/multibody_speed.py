"""Multibody speed against sr5, side by side, and the multibody RK4's work-precision.

Scene: seed 000's operating point (ER-16K, 35 Hz, 110 N, Table 1), 48 kHz output, the
default 15 kHz resonance, healthy and with a 1.0 x 0.5 mm outer-race fault at 0 deg.

* Cost: wall time of the whole :func:`ballpass.simulate` call per simulated second,
  multibody (default step) and sr5 (default rk4) interleaved in one run, ``--repeats``
  times each after a warm-up call (compilation not timed); medians with min-max spread
  and the ratio of the medians.
* Work-precision: the multibody RK4 at omega_max dt = 0.25 ... 1.0 (the default is
  0.5), relative L2 error of the output acceleration and of the contact forces against
  a reference run at omega_max dt = 0.0625 (RK4 converges as dt^4, so the reference's
  own error is 256 times below the default's).

Writes ``benchmarks/results/multibody_speed.md`` and ``docs/multibody_work_precision.png``.

    python benchmarks/multibody_speed.py               # 0.2 s scenes, 5 repeats
    python benchmarks/multibody_speed.py --repeats 2   # a quick run
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import _machine  # benchmarks/_machine.py (scripts run from their folder)
import numpy as np

import ballpass as bp
from ballpass.signalio import atomic_write
from ballpass.simulate.multibody import build

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "benchmarks" / "results"
DOCS = ROOT / "docs"
FAULTS = {"healthy": None, "outer 1.0 x 0.5 mm": bp.Fault("outer", width_mm=1.0, depth_mm=0.5)}
OMEGA_DTS = (0.25, 0.5, 0.75, 1.0)
NOTE = ("The errors do not fall as dt^4 (the step is fine enough for the contact and "
        "traction modes: omega dt = 0.25-1): unloaded balls rattle in their pockets and a "
        "ball flies and rebounds inside the notch, non-smooth motions on which small "
        "differences grow over the run. The healthy acceleration is 1 % of the static "
        "load's, so force differences of 2e-4 are 30 % of it. omega_max dt = 0.75 and 1 "
        "round to the same step (two per 5.2 us output interval).")


def scene(fault, duration_s):
    return bp.Scene(bearing="ER-16K", rpm=2100.0, radial_load_n=110.0, fault=fault,
                    duration_s=duration_s, fs=48_000.0)


def timed(sc, model, **kw):
    t = time.perf_counter()
    res = bp.simulate(sc, model=model, return_forces=True, **kw)
    return time.perf_counter() - t, res


def cost(repeats, duration_s):
    rows = []
    for name, fault in FAULTS.items():
        sc = scene(fault, duration_s)
        timed(sc.replace(duration_s=0.01), "multibody")
        timed(sc.replace(duration_s=0.01), "sr5")
        walls = {"multibody": [], "sr5": []}
        for _ in range(repeats):  # interleaved: both see the same machine load
            for model in walls:
                walls[model].append(timed(sc, model)[0] / duration_s)
        mb, sr = np.array(walls["multibody"]), np.array(walls["sr5"])
        rows.append((name, np.median(mb), mb.min(), mb.max(), np.median(sr), sr.min(),
                     sr.max(), np.median(mb) / np.median(sr)))
    return rows


def work_precision(duration_s):
    rows = []
    for name, fault in FAULTS.items():
        sc = scene(fault, duration_s)
        omega = build(sc).omega_max
        _, ref = timed(sc, "multibody", dt=0.0625 / omega)
        for od in OMEGA_DTS:
            wall, res = timed(sc, "multibody", dt=od / omega)
            err_a = np.linalg.norm(res.accel - ref.accel) / np.linalg.norm(ref.accel)
            err_q = (np.linalg.norm(res.truth.contact_forces - ref.truth.contact_forces)
                     / np.linalg.norm(ref.truth.contact_forces))
            rows.append((name, od, res.info["dt_s"], wall / duration_s, err_a, err_q))
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--duration", type=float, default=0.2, help="simulated seconds per run")
    args = ap.parse_args()
    c = cost(args.repeats, args.duration)
    wp = work_precision(min(args.duration, 0.05))
    lines = [
        "# Multibody speed against sr5, and its work-precision",
        "",
        f"Machine: {_machine.machine()} (shared: timings are noisy). ballpass "
        f"{bp.__version__}. `python benchmarks/multibody_speed.py --repeats {args.repeats} "
        f"--duration {args.duration}`.",
        "",
        "Seed 000 operating point: ER-16K, 35 Hz, 110 N, 48 kHz output. Wall time of the "
        "whole `simulate` call per simulated second, medians of "
        f"{args.repeats} interleaved runs (min-max):",
        "",
        "| scene | multibody s/s | sr5 s/s | ratio of medians |",
        "|---|---|---|---|",
    ]
    for name, m, mlo, mhi, s, slo, shi, ratio in c:
        lines.append(f"| {name} | {m:.3g} ({mlo:.3g}-{mhi:.3g}) | {s:.3g} ({slo:.3g}-{shi:.3g}) "
                     f"| {ratio:.0f} |")
    lines += [
        "",
        "Work-precision of the multibody RK4 (relative L2 error against omega_max dt = "
        "0.0625, 0.05 s):",
        "",
        "| scene | omega_max dt | dt (us) | s per simulated s | error, acceleration | "
        "error, contact forces |",
        "|---|---|---|---|---|---|",
    ]
    for name, od, dt, wall, ea, eq in wp:
        lines.append(f"| {name} | {od:g}{' (default)' if od == 0.5 else ''} | {dt * 1e6:.2f} "
                     f"| {wall:.3g} | {ea:.1e} | {eq:.1e} |")
    lines += ["", NOTE]
    RESULTS.mkdir(exist_ok=True)
    text = "\n".join(lines) + "\n"
    atomic_write(RESULTS / "multibody_speed.md", lambda tmp: tmp.write_text(text))
    print("\n".join(lines))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    for name in FAULTS:
        sel = [r for r in wp if r[0] == name]
        ax.loglog([r[3] for r in sel], [r[4] for r in sel], "o-", label=f"{name}: acceleration")
        ax.loglog([r[3] for r in sel], [r[5] for r in sel], "s--", label=f"{name}: forces")
    ax.set_xlabel("wall time per simulated second, s")
    ax.set_ylabel("relative L2 error")
    ax.set_title("multibody RK4, ER-16K 35 Hz 110 N")
    ax.legend(fontsize=7)
    fig.tight_layout()
    atomic_write(DOCS / "multibody_work_precision.png",
                 lambda tmp: fig.savefig(tmp, format="png", dpi=110))


if __name__ == "__main__":
    main()
