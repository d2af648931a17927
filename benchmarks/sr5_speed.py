"""sr5 against a naive numba RK4 of the same model, side by side.

The naive baseline integrates the full sr5 state (shaft, pedestal, resonator) with the
model's own right-hand side (``BearingModel.rhs``'s kernel, :func:`ballpass.simulate.
_kernels.rhs`, the equations scipy integrates in the work-precision study) by classical
RK4 at dt = 1/(4 fs) (the internal output grid), with no event handling, records the
sensor output at every step and decimates it with the same anti-alias filter as
``ballpass.simulate``. sr5 is timed through the whole of ``ballpass.simulate`` (events,
integration, decimation, ground truth) with its default solver, and also at the former
default step (eight grid intervals, omega dt = 0.35) for comparison.

Scenes: one second of a 6205 at 1797 rpm and 500 N, 48 kHz, 15 kHz / 5 % resonance, one
sensor; healthy and with the default 0.5 mm x 0.1 mm outer, inner and ball faults.
Errors: relative L2 of the output against dopri5 at rtol 1e-10 (as
``benchmarks/simulate_speed.py`` and the ``error_l2`` of the work-precision study).
Rounds interleave the methods scene by scene, so each ratio compares runs made moments
apart on the shared machine; the table gives medians with the range over rounds.
Writes ``docs/results/sr5_speed.{md,csv,png}``.

    python benchmarks/sr5_speed.py              # 9 rounds
    python benchmarks/sr5_speed.py --rounds 3   # a quick run
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import _machine  # benchmarks/_machine.py (scripts run from their folder)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from _paths import RESULTS_DIR as RESULTS
from _report import span, table, write_csv, write_page
from numba import njit  # noqa: E402

import ballpass as bp  # noqa: E402
from ballpass import __version__  # noqa: E402
from ballpass.simulate import _kernels as K  # noqa: E402
from ballpass.simulate._shared import OVERSAMPLE, to_output_rate  # noqa: E402
from ballpass.simulate._sr5_driver import build  # noqa: E402

FAULTS = ["healthy", "outer", "inner", "ball"]
#: target: sr5 at most this fraction of the naive RK4, at error <= TARGET_ERROR
TARGET_RATIO, TARGET_ERROR = 0.10, 1e-3
#: the former default step, eight internal grid intervals at 48 kHz (omega dt = 0.35)
FORMER_DT = 8 / (OVERSAMPLE * 48_000.0)


@njit(cache=False, error_model="numpy")
def naive_rk4(y0, p, walk, faults, sensors, n_res, dt, out):
    """Classical RK4 of the full sr5 state with the model's right-hand side, fixed step
    dt, sensor output (resonator mass acceleration) at every step into ``out``."""
    n = y0.shape[0]
    y = y0.copy()
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    kin = K.kinematics_scratch(int(p[K.P_Z]))
    buf = np.empty(16)
    acc = np.empty((1, sensors.shape[0]))
    nd = 4 + n_res
    w = p[K.P_WR]
    zeta = p[K.P_ZETA]
    for k in range(out.shape[0]):
        if k > 0:
            t = (k - 1) * dt
            K.rhs(t, y, k1, p, walk, faults, sensors, n_res, kin, buf, acc)
            for i in range(n):
                tmp[i] = y[i] + 0.5 * dt * k1[i]
            K.rhs(t + 0.5 * dt, tmp, k2, p, walk, faults, sensors, n_res, kin, buf, acc)
            for i in range(n):
                tmp[i] = y[i] + 0.5 * dt * k2[i]
            K.rhs(t + 0.5 * dt, tmp, k3, p, walk, faults, sensors, n_res, kin, buf, acc)
            for i in range(n):
                tmp[i] = y[i] + dt * k3[i]
            K.rhs(t + dt, tmp, k4, p, walk, faults, sensors, n_res, kin, buf, acc)
            for i in range(n):
                y[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
        for i in range(n_res):
            out[k, i] = -(2.0 * zeta * w * y[nd + 4 + i] + w * w * y[4 + i])


def run_naive(scene: bp.Scene) -> np.ndarray:
    """The naive baseline's decimated output, (n_sensors, n_samples)."""
    bm = build(scene)
    out = np.empty((scene.n_samples * OVERSAMPLE, len(scene.sensors)))
    naive_rk4(bm.y0, *bm.model, bm.n_res, 1.0 / (OVERSAMPLE * scene.fs), out)
    return to_output_rate(out, scene.n_samples, OVERSAMPLE)


def scene(kind: str, duration: float) -> bp.Scene:
    return bp.Scene("6205", rpm=1797.0, duration_s=duration, fs=48_000.0,
                    fault=None if kind == "healthy" else bp.Fault(kind))


def methods(sc: bp.Scene) -> dict:
    return {
        "naive RK4, dt = 1/(4 fs)": lambda: run_naive(sc)[0],
        "sr5 default": lambda: bp.simulate(sc).accel,
        "sr5, former step (8 grid intervals)": lambda: bp.simulate(sc, dt=FORMER_DT).accel,
    }


def measure(duration: float, rounds: int) -> pd.DataFrame:
    rows = []
    for kind in FAULTS:
        sc = scene(kind, duration)
        ref = bp.simulate(sc, solver="dopri5", rtol=1e-10).accel
        runs = methods(sc)
        errors = {}
        for name, fn in runs.items():  # warm-up (compilation) and error
            out = fn()
            errors[name] = float(np.linalg.norm(out - ref) / np.linalg.norm(ref))
        for r in range(rounds):
            for name, fn in runs.items():
                t0, c0 = time.perf_counter(), time.process_time()
                fn()
                rows.append(dict(scene=kind, method=name, round=r,
                                 wall_ms=1e3 * (time.perf_counter() - t0) / duration,
                                 cpu_ms=1e3 * (time.process_time() - c0) / duration,
                                 error=errors[name]))
        print(f"{kind}: " + ", ".join(f"{n} {e:.1e}" for n, e in errors.items()), flush=True)
    return pd.DataFrame(rows)


def summarise(runs: pd.DataFrame) -> pd.DataFrame:
    """Per scene and method: median and range of the wall and CPU time per simulated
    second, and of the ratio to the naive run of the same round."""
    naive = runs[runs.method.str.startswith("naive")].set_index(["scene", "round"])
    rows = []
    for (kind, name), g in runs.groupby(["scene", "method"], sort=False):
        base = naive.loc[[(kind, r) for r in g["round"]]]
        ratio = g.wall_ms.to_numpy() / base.wall_ms.to_numpy()
        cpu_ratio = g.cpu_ms.to_numpy() / base.cpu_ms.to_numpy()
        rows.append(dict(
            scene=kind, method=name, error=g.error.iloc[0],
            wall_ms=g.wall_ms.median(), wall_lo=g.wall_ms.min(), wall_hi=g.wall_ms.max(),
            cpu_ms=g.cpu_ms.median(),
            ratio=np.median(ratio), ratio_lo=ratio.min(), ratio_hi=ratio.max(),
            cpu_ratio=np.median(cpu_ratio)))
    return pd.DataFrame(rows)


def figure(summary: pd.DataFrame, path: Path) -> None:
    names = list(dict.fromkeys(summary.method))
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4))
    width = 0.8 / len(names)
    x = np.arange(len(FAULTS))
    for i, name in enumerate(names):
        s = summary[summary.method == name].set_index("scene").loc[FAULTS]
        err = [s.wall_ms - s.wall_lo, s.wall_hi - s.wall_ms]
        ax.bar(x + i * width, s.wall_ms, width, yerr=err, capsize=3, label=name, color=f"C{i}")
        if not name.startswith("naive"):
            rerr = [s.ratio - s.ratio_lo, s.ratio_hi - s.ratio]
            bx.bar(x + i * width, s.ratio, width, yerr=rerr, capsize=3, color=f"C{i}",
                   label=f"{name} (error {s.error.max():.0e} at most)")
    ax.set_yscale("log")
    ax.set_ylabel("wall time per simulated second, ms")
    ax.set_title("1 s at 48 kHz: median, range over rounds")
    bx.axhline(TARGET_RATIO, color="k", ls="--", lw=1, label=f"target {TARGET_RATIO:g}x")
    bx.set_ylabel("time / naive RK4 of the same round")
    bx.set_title("ratio to the naive RK4, side by side")
    for a in (ax, bx):
        a.set_xticks(x + width * (len(names) - 1) / 2, FAULTS)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write(runs: pd.DataFrame, duration: float, rounds: int) -> Path:
    import numba

    summary = summarise(runs)
    write_csv(runs, RESULTS / "sr5_speed.csv")
    RESULTS.mkdir(parents=True, exist_ok=True)
    figure(summary, RESULTS / "sr5_speed.png")
    lines = [
        "# sr5 against a naive RK4 of the same model",
        "",
        f"{duration:g} s of a 6205 at 1797 rpm and 500 N, 48 kHz, one sensor, faults 0.5 mm "
        f"x 0.1 mm. {rounds} interleaved rounds; medians with the range over rounds "
        f"(min-max). Produced by `python benchmarks/sr5_speed.py` on {_machine.machine()} "
        f"(shared with other jobs), numba {numba.__version__}, ballpass {__version__}. "
        "Naive: classical RK4 of the full state with the model's right-hand side at "
        "dt = 1/(4 fs), output at every step, same anti-alias decimation. Error: relative "
        "L2 of the output against dopri5 at rtol 1e-10.",
        "",
        f"Goal: error <= {TARGET_ERROR:g} at <= {TARGET_RATIO:g}x the naive "
        "RK4.",
        "",
    ]
    lines += table(["scene", "method", "error", "wall ms per simulated s",
                    "ratio to naive (wall)", "ratio (CPU time)"],
                   [(r.scene, r.method, f"{r.error:.1e}",
                     span(r.wall_ms, r.wall_lo, r.wall_hi, ".1f"),
                     span(r.ratio, r.ratio_lo, r.ratio_hi, ".3f"), f"{r.cpu_ratio:.3f}")
                    for r in summary.itertuples()], align="llrrrr")
    lines += ["", "![sr5 speed](sr5_speed.png)"]
    return write_page(RESULTS / "sr5_speed.md", lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=1.0, help="simulated s per scene")
    parser.add_argument("--rounds", type=int, default=9, help="interleaved timing rounds")
    args = parser.parse_args()
    runs = measure(args.duration, args.rounds)
    print(f"-> {write(runs, args.duration, args.rounds)}")


if __name__ == "__main__":
    main()
