"""Work-precision of the gearbox model's default RK4 step (DT_DEFAULT_OMEGA).

The gearbox model steps RK4 at ``DT_DEFAULT_OMEGA / omega_max`` (its fastest linearised
mode), rounded down to a divisor of the internal output grid 1/(4 fs). Like sr5's
default (``DT_SR5_OMEGA``, benchmarks/sr5_speed.py), it must keep the output's relative
L2 error below 1e-3 against a tight reference.

For each scene (Tran, Furch & Cu's 6208 at 2000 rpm with 5 um runout on both wheels: the helical
constant-mesh pair and the 1st-speed spur pair, healthy, with a tooth fault, with a
bearing fault, with both) and each omega_max dt = theta, the output rate is chosen so
that one step spans one internal grid interval, fs = omega_max / (4 theta): the rule's
worst case (at other rates the rounding down makes the step smaller). The resonance sits
at 0.3 fs, where Sawalhi & Randall's 15 kHz sits in a 48 kHz record. Error: relative
L2 of the sensor output against the same model at 1/32 of the step (the reference).
Its convergence is shown by the error of 1/16 of the step against it: with RK4's
fourth order the reference's own error is about that divided by 15.

    python benchmarks/gearbox_step.py               # ~6 min on a shared core
    python benchmarks/gearbox_step.py --duration 0.05

Writes ``docs/results/gearbox_step.{md,csv,png}``.
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import _machine  # benchmarks/_machine.py (scripts run from their folder)
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from _paths import RESULTS_DIR as RESULTS
from _report import table, write_csv, write_page

import ballpass as bp  # noqa: E402
from ballpass import __version__  # noqa: E402
from ballpass.simulate._sr5_driver import DT_DEFAULT_OMEGA  # noqa: E402
from ballpass.simulate.gearbox import build_gearbox  # noqa: E402

#: the project's accuracy goal for a default step (relative L2 of the output)
TARGET_ERROR = 1e-3
#: omega_max dt studied (the rate is fs = omega_max / (4 theta)); RK4 is stable to 2.83
THETAS = (0.15, 0.25, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0)
#: reference: this many steps per grid interval; convergence check at half as many
N_REF = 32
RPM = 2000.0
#: resonance frequency / fs (15 kHz at 48 kHz)
RESONANCE_FRACTION = 0.3


def scenes() -> dict[str, dict]:
    """name -> Scene keywords (fs is set per theta)."""
    crack = bp.GearFault("crack", stiffness_loss=0.5)
    spall = bp.GearFault("spall", tooth=3, stiffness_loss=0.3)

    def pair(preset, fault=None):
        return bp.GearPair.preset(preset, eccentricity_um=(5.0, 5.0), fault=fault)

    return {
        "helical, healthy": dict(gears=pair("tran-furch-cu")),
        "spur, healthy": dict(gears=pair("tran-furch-cu-1st")),
        "helical, pinion crack": dict(gears=pair("tran-furch-cu", crack)),
        "spur, pinion spall": dict(gears=pair("tran-furch-cu-1st", spall)),
        "helical, inner spall 4x2 mm (Tran, Furch & Cu)": dict(
            gears=pair("tran-furch-cu"), fault=bp.Fault("inner", width_mm=4.0, depth_mm=2.0)),
        "spur, inner 0.5x0.1 mm": dict(
            gears=pair("tran-furch-cu-1st"), fault=bp.Fault("inner", width_mm=0.5, depth_mm=0.1)),
        "helical crack + outer 0.5x0.1 mm": dict(
            gears=pair("tran-furch-cu", crack),
            fault=bp.Fault("outer", width_mm=0.5, depth_mm=0.1)),
    }


def run(scene: bp.Scene, n_sub: int) -> np.ndarray:
    """Sensor output with ``n_sub`` RK4 steps per internal grid interval."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # dt rounded to a divisor of the grid (by 1 ulp)
        return bp.simulate(scene, model="gearbox", dt=1.0 / (4.0 * scene.fs * n_sub)).accel


def rel_l2(x: np.ndarray, ref: np.ndarray) -> float:
    return float(np.linalg.norm(x - ref) / np.linalg.norm(ref))


def measure(duration: float) -> pd.DataFrame:
    rows = []
    for name, kw in scenes().items():
        base = bp.Scene(bearing="6208", rpm=RPM, duration_s=duration, fs=48_000.0, **kw)
        omega = build_gearbox(base).omega_max
        for theta in THETAS:
            fs = omega / (4.0 * theta)
            sc = base.replace(fs=fs, resonance_hz=RESONANCE_FRACTION * fs)
            ref = run(sc, N_REF)
            rows.append(dict(scene=name, theta=theta, fs_hz=fs, dt_us=1e6 / (4.0 * fs),
                             omega_max=omega, error=rel_l2(run(sc, 1), ref),
                             error_half=rel_l2(run(sc, 2), ref),
                             reference_check=rel_l2(run(sc, N_REF // 2), ref)))
            r = rows[-1]
            print(f"{name:40s} theta {theta:.2f} fs {fs:8.0f} error {r['error']:.2e} "
                  f"(dt/2 {r['error_half']:.2e}; dt/{N_REF // 2} {r['reference_check']:.1e})",
                  flush=True)
    return pd.DataFrame(rows)


def largest_safe_theta(runs: pd.DataFrame) -> float:
    """Largest studied theta at which every scene errs below TARGET_ERROR (all smaller
    thetas too)."""
    worst = runs.groupby("theta").error.max().sort_index()
    safe = 0.0
    for theta, err in worst.items():
        if err > TARGET_ERROR:
            break
        safe = theta
    return safe


def figure(runs: pd.DataFrame, path: Path) -> None:
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    for i, (name, g) in enumerate(runs.groupby("scene", sort=False)):
        ax.loglog(g.theta, g.error, "o-", color=f"C{i}", label=name)
        ax.loglog(g.theta, g.reference_check, ":", color=f"C{i}", lw=1)
    th = np.array(THETAS)
    first = runs[runs.theta == min(THETAS)].error.max()
    ax.loglog(th, first * (th / th[0]) ** 4, "k-", lw=0.6, alpha=0.5, label="slope 4 (RK4)")
    ax.axhline(TARGET_ERROR, color="k", ls="--", lw=1, label=f"goal {TARGET_ERROR:g}")
    ax.axvline(DT_DEFAULT_OMEGA, color="r", ls="--", lw=1,
               label=f"default omega dt = {DT_DEFAULT_OMEGA:g}")
    ax.set_xlabel("omega_max dt (one step per grid interval 1/(4 fs))")
    ax.set_ylabel("relative L2 error of the output")
    ax.set_title(f"gearbox RK4 against 1/{N_REF} of the step (dotted: 1/{N_REF // 2})")
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write(runs: pd.DataFrame, duration: float) -> Path:
    write_csv(runs, RESULTS / "gearbox_step.csv")
    figure(runs, RESULTS / "gearbox_step.png")
    safe = largest_safe_theta(runs)
    at_default = runs[np.isclose(runs.theta, DT_DEFAULT_OMEGA)]
    lines = [
        "# Work-precision of the gearbox model's default step",
        "",
        f"{duration:g} s of Tran, Furch & Cu's 6208 at {RPM:g} rpm with 5 um runout on both "
        f"wheels, resonance at {RESONANCE_FRACTION:g} fs, one sensor. One RK4 step per internal "
        "grid interval at fs = omega_max / (4 theta), the worst case of the default rule. Error: "
        f"relative L2 of the output against 1/{N_REF} of the step; 'dt/2': half the step; "
        f"'reference check': 1/{N_REF // 2} of the step against the reference (the "
        "reference's own error is about a fifteenth of it). Produced by "
        f"`python benchmarks/gearbox_step.py` on {_machine.machine()}, ballpass "
        f"{__version__}.",
        "",
        f"Default `DT_DEFAULT_OMEGA` = {DT_DEFAULT_OMEGA:g}: largest error there "
        f"{at_default.error.max():.1e} (goal {TARGET_ERROR:g}); largest studied theta with "
        f"every scene below the goal: {safe:g}.",
        "",
    ]
    lines += table(["scene", "omega_max dt", "fs, Hz", "dt, us", "error", "dt/2",
                    "reference check"],
                   [(r.scene, f"{r.theta:.2f}", f"{r.fs_hz:.0f}", f"{r.dt_us:.2f}",
                     f"{r.error:.1e}", f"{r.error_half:.1e}", f"{r.reference_check:.1e}")
                    for r in runs.itertuples()], align="lrrrrrr")
    lines += ["", "![gearbox step](gearbox_step.png)"]
    return write_page(RESULTS / "gearbox_step.md", lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=0.2, help="simulated s per scene")
    args = parser.parse_args()
    runs = measure(args.duration)
    print(f"-> {write(runs, args.duration)}")


if __name__ == "__main__":
    main()
