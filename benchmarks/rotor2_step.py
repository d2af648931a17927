"""rotor2's step: error against dopri5 and cost against sr5 (``docs/rotor2_step.md``).

Two measurements on the scene of the model-cost table (6205, 1797 rpm, 500 N, inner-race
fault 0.5 x 0.1 mm, 48 kHz, zero clearance: the motion is regular, so trajectories of
different solvers can be compared):

1. ``error``: relative L2 error of the output acceleration (after the anti-alias
   decimation, the work-precision ``error_l2``) against dopri5 at rtol 1e-10 over 0.2 s,
   for rk4 and Newmark over a range of steps omega_c dt (omega_c the linearised contact
   frequency), healthy and with ramped or sharp defect edges.
2. ``cost``: wall time of 1 s of the scene with rotor2's default solver and with sr5's,
   interleaved rounds, medians with the spread, and the ratio round by round.

    python benchmarks/rotor2_step.py            # ~2 min on 2 busy cores
    python benchmarks/rotor2_step.py --quick    # fewer steps and rounds

Writes ``docs/rotor2_step.md``, ``docs/results/rotor2_step.csv`` and
``docs/results/rotor2_step.png``.
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np
import pandas as pd
from _paths import DOCS, RESULTS_DIR

import ballpass as bp
from ballpass.diagnose.report import markdown_table
from ballpass.simulate import rotor2 as R

FAULTS = {"healthy": None,
          "inner, ramped edges": bp.Fault("inner", width_mm=0.5, depth_mm=0.1),
          "inner, sharp edges": bp.Fault("inner", width_mm=0.5, depth_mm=0.1, edge="sharp")}


def scene(fault, duration: float) -> bp.Scene:
    """The model-cost reference scene."""
    return bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fault=fault,
                    duration_s=duration, fs=48_000.0)


def errors(quick: bool) -> pd.DataFrame:
    """Output-acceleration error of rk4 and Newmark against dopri5 at rtol 1e-10."""
    steps = {"rk4": (0.1, 0.2, 0.3, 0.35, 0.4, 0.6) if not quick else (0.2, 0.3, 0.35, 0.4),
             "newmark": (0.0125, 0.025, 0.05) if not quick else (0.025, 0.05)}
    rows = []
    for name, fault in FAULTS.items():
        s = scene(fault, 0.1 if quick else 0.2)
        omega = R.contact_omega(s)
        ref = bp.simulate(s, model="rotor2", solver="dopri5", rtol=1e-10).accel
        for solver, values in steps.items():
            for c in values:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")  # newmark rounds dt to the output grid
                    res = bp.simulate(s, model="rotor2", solver=solver, dt=c / omega)
                rows.append(dict(scene=name, solver=solver, omega_dt=res.info["dt_s"] * omega,
                                 dt_us=res.info["dt_s"] * 1e6, steps=res.info["n_steps"],
                                 error_l2=float(np.linalg.norm(res.accel - ref)
                                                / np.linalg.norm(ref))))
    return pd.DataFrame(rows)


def cost(quick: bool) -> pd.DataFrame:
    """Wall time of 1 s of the faulty scene, rotor2 (default) and sr5, interleaved."""
    s = scene(FAULTS["inner, ramped edges"], 1.0)
    for model in ("sr5", "rotor2"):
        bp.simulate(s.replace(duration_s=0.01), model=model)  # compile
    rows = []
    for k in range(5 if quick else 11):
        for model in ("sr5", "rotor2"):
            t0 = time.perf_counter()
            res = bp.simulate(s, model=model)
            rows.append(dict(round=k, model=model, wall_s=time.perf_counter() - t0,
                             solver=res.info["solver"], steps=res.info["n_steps"]))
    return pd.DataFrame(rows)


def plot(err: pd.DataFrame) -> None:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4), layout="constrained")
    for (name, solver), g in err.groupby(["scene", "solver"], sort=False):
        ax.loglog(g["omega_dt"], g["error_l2"], "o-" if solver == "rk4" else "s--",
                  label=f"{solver}, {name}", ms=4)
    ax.axhline(1e-2, color="k", lw=0.8, ls=":")
    ax.axvline(R.DT_RK4_OMEGA, color="tab:red", lw=0.8, ls=":", label="rk4 default")
    ax.set_xlabel("omega_c dt")
    ax.set_ylabel("relative L2 error of the acceleration")
    ax.set_title("rotor2 against dopri5 (rtol 1e-10), 6205, 1797 rpm, 500 N", fontsize=9)
    ax.legend(fontsize=7)
    fig.savefig(RESULTS_DIR / "rotor2_step.png", dpi=110)


def page(err: pd.DataFrame, cst: pd.DataFrame) -> str:
    wide = cst.pivot(index="round", columns="model", values="wall_s")
    ratio = wide["rotor2"] / wide["sr5"]
    med = wide.median()
    spread = wide.max() - wide.min()
    steps = cst.groupby("model")["steps"].first()
    err_tab = err.assign(omega_dt=err["omega_dt"].round(4), dt_us=err["dt_us"].round(2),
                         error_l2=err["error_l2"].map(lambda v: f"{v:.2g}"))
    default = err[(err["solver"] == "rk4")
                  & np.isclose(err["omega_dt"], R.DT_RK4_OMEGA, rtol=1e-3)]
    return f"""# rotor2's step: accuracy against dopri5, cost against sr5

Produced by `python benchmarks/rotor2_step.py` (shared 2-core machine: timings are noisy;
the ratio is taken round by round, the runs interleaved).

Scene: 6205, 1797 rpm, 500 N, zero clearance, 48 kHz output (the model-cost reference
scene), rotor2's default parameters (1 kg rotor, 200 N s/m). Its linearised contact mode
is omega_c = {R.contact_omega(scene(None, 0.1)) / (2 * np.pi):.0f} Hz with 1 % damping;
it rings after every roller pass and defect impact and carries most of the acceleration.

## What set the old step, and the step the accuracy needs

rotor2 used to step with Newmark average acceleration at dt = 0.025 / omega_c (2.7 us
here, rounded to 2.6 us, a divisor of the 5.2 us internal output spacing), chosen for a
period error (omega dt)^2 / 12 of 5e-5, and never longer than the output spacing.
Newmark is unconditionally stable, but it is second order: its phase error on the
ringing contact mode accumulates over the ~15 periods the mode takes to decay, and the
output acceleration reaches 1e-2 of the reference only at omega dt ~ 0.05 (table
below): no Newmark step is both within 1e-2 and cheap. The default is now classical
Runge-Kutta 4 (fourth order) at dt = {R.DT_RK4_OMEGA} / omega_c, steps independent of
the output grid (the outputs are the quintic Hermite interpolant of the step ends),
restarted at the fault edges and ramp ends, which rotor2 knows in closed form, with
{R.RK4_RAMP_STEPS} steps across each ramp. `solver="newmark"` remains (the paper's
method, at its old default step).

Relative L2 error of the output acceleration against dopri5 at rtol 1e-10
(`rotor2_step.csv`):

{markdown_table(err_tab)}

At the default step the error is {default['error_l2'].min():.1e} to
{default['error_l2'].max():.1e} (limit 1e-2); it falls 16x per halved step (fourth order).

## Cost against sr5

1 s of the faulty scene, {len(wide)} interleaved rounds: rotor2 (rk4, {steps['rotor2']}
steps) {med['rotor2'] * 1e3:.0f} ms (spread {spread['rotor2'] * 1e3:.0f} ms), sr5
({steps['sr5']} steps) {med['sr5'] * 1e3:.0f} ms (spread {spread['sr5'] * 1e3:.0f} ms);
rotor2 / sr5 round by round: median {ratio.median():.2f}, range {ratio.min():.2f} -
{ratio.max():.2f}. With Newmark at 2.6 us (384 000 steps) rotor2 cost 25x sr5, and 2.0x
with this RK4 step while every force evaluation recomputed the roller angles, the defect
depths and the unbalance angle (four times per step, at two distinct times) and the
tangents only Newmark reads; both are now computed once per time and for Newmark only.

![rotor2 error against step](results/rotor2_step.png)
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer steps and rounds")
    ap.add_argument("--reuse-errors", action="store_true",
                    help="take the error table from docs/results/rotor2_step.csv (time only)")
    args = ap.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    if args.reuse_errors:
        err = pd.read_csv(RESULTS_DIR / "rotor2_step.csv")
    else:
        err = errors(args.quick)
        err.to_csv(RESULTS_DIR / "rotor2_step.csv", index=False)
    print(err.to_string())
    cst = cost(args.quick)
    cst.to_csv(RESULTS_DIR / "rotor2_step_cost.csv", index=False)
    plot(err)
    text = page(err, cst)
    (DOCS / "rotor2_step.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
