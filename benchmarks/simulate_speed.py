"""Simulator speed: wall time per simulated second of sr5, per solver, with its error.

One second of a 6205 at 1797 rpm and 500 N, 48 kHz output, the default 15 kHz / 5 %
resonance, one loaded-zone sensor; healthy and with the default 0.5 mm x 0.1 mm outer,
inner and ball faults. Each solver setting is timed through the whole of
:func:`ballpass.simulate` (events, integration, decimation), best of ``--repeats``
calls after a warm-up call (numba compilation is not timed), and its relative L2 error
measured against dopri5 at rtol 1e-10. Writes ``docs/results/simulate_speed.md``.

    python benchmarks/simulate_speed.py               # 1 s per scene, 7 repeats
    python benchmarks/simulate_speed.py --repeats 2   # a quick run
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import _machine  # benchmarks/_machine.py (scripts run from their folder)
import numpy as np
from _paths import RESULTS_DIR as RESULTS
from _report import table, write_page

import ballpass as bp
from ballpass import __version__

FAULTS = ["healthy", "outer", "inner", "ball"]
#: (solver, keyword arguments, label); None = the default settings
SETTINGS = [
    ("rk4", {}, "default (omega dt = 0.3)"),
    ("rk4", {"dt": 4 / 192_000}, "dt = 20.8 us"),
    ("rk4", {"dt": 3 / 192_000}, "dt = 15.6 us"),
    ("rk4", {"dt": 2 / 192_000}, "dt = 10.4 us"),
    ("dopri5", {"rtol": 1e-4}, "rtol = 1e-4"),
    ("dopri5", {}, "default (rtol = 1e-6)"),
    ("dopri5", {"rtol": 1e-8}, "rtol = 1e-8"),
]
#: the issue's targets for 1 s of sr5 at 48 kHz
TARGET_MS, TARGET_ERROR = 20.0, 1e-3


def scene(kind: str, duration: float) -> bp.Scene:
    return bp.Scene("6205", rpm=1797.0, duration_s=duration, fs=48_000.0,
                    fault=None if kind == "healthy" else bp.Fault(kind))


def measure(duration: float, repeats: int) -> list[dict]:
    records = []
    for kind in FAULTS:
        sc = scene(kind, duration)
        ref = bp.simulate(sc, solver="dopri5", rtol=1e-10).accel
        for solver, kwargs, label in SETTINGS:
            bp.simulate(sc, solver=solver, **kwargs)  # warm-up: compilation, caches
            best = np.inf
            for _ in range(repeats):
                t0 = time.perf_counter()
                res = bp.simulate(sc, solver=solver, **kwargs)
                best = min(best, time.perf_counter() - t0)
            err = float(np.linalg.norm(res.accel - ref) / np.linalg.norm(ref))
            records.append(dict(scene=kind, solver=solver, setting=label,
                                ms_per_s=1e3 * best / duration, steps=res.info["n_steps"],
                                rejected=res.info["n_rejected"], error=err,
                                integration_ms=1e3 * res.info["integration_time_s"] / duration))
            print(f"{kind:8s} {solver:7s} {label:26s} {1e3 * best / duration:8.1f} ms/s "
                  f"error {err:.2e}", flush=True)
    return records


def machine() -> str:
    import numba

    return (f"{_machine.machine()} (one used), numba {numba.__version__}, "
            f"ballpass {__version__}")


def write(records: list[dict], duration: float, repeats: int) -> Path:
    lines = [
        "# Simulator speed",
        "",
        f"Wall time per simulated second of `ballpass.simulate` (model sr5, 6205 at 1797 "
        f"rpm and 500 N, {duration:g} s at 48 kHz, 15 kHz / 5 % resonance, one sensor; "
        "faults 0.5 mm wide, 0.1 mm deep), best of "
        f"{repeats} after a warm-up call, and the relative L2 error of the acceleration "
        "against dopri5 at rtol 1e-10. Produced by `python benchmarks/simulate_speed.py` "
        f"on {machine()}; the machine was shared, so the minimum over repeats is "
        "reported.",
        "",
        f"Target: 1 s of sr5 output at <= {TARGET_ERROR:g} relative error in "
        f"<= {TARGET_MS:g} ms on one core.",
        "",
    ]
    rows = []
    for r in records:
        ms = f"{r['ms_per_s']:.1f}"
        if r["ms_per_s"] <= TARGET_MS and r["error"] <= TARGET_ERROR:
            ms = f"**{ms}**"
        rows.append((r["scene"], r["solver"], r["setting"], ms, f"{r['integration_ms']:.1f}",
                     f"{r['steps']} ({r['rejected']})", f"{r['error']:.1e}"))
    lines += table(["scene", "solver", "setting", "ms per simulated s", "of which integration",
                    "steps (rejected)", "relative L2 error"], rows, align="lllrrrr")
    lines += ["", "Bold: within both targets. The first call of a solver in a fresh "
              "environment also compiles the numba kernels (cached on disk afterwards)."]
    return write_page(RESULTS / "simulate_speed.md", lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=1.0, help="simulated s per scene")
    parser.add_argument("--repeats", type=int, default=7, help="timed calls per setting")
    args = parser.parse_args()
    records = measure(args.duration, args.repeats)
    print(f"-> {write(records, args.duration, args.repeats)}")


if __name__ == "__main__":
    main()
