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

Also the NJ 305 paper's scene of tests/test_rotor2.py in the error table, and 3. where the
48 kHz cost goes (CPU time of the steps, the output interpolation and the decimation).

Writes ``docs/rotor2_step.md``, ``docs/results/rotor2_step.csv``,
``docs/results/rotor2_step_cost.csv``, ``docs/results/rotor2_step_breakdown.csv`` and
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
from ballpass.simulate import _second_order as _I
from ballpass.simulate import rotor2 as R

FAULTS = {"healthy": None,
          "inner, ramped edges": bp.Fault("inner", width_mm=0.5, depth_mm=0.1),
          "inner, sharp edges": bp.Fault("inner", width_mm=0.5, depth_mm=0.1, edge="sharp")}


def scene(fault, duration: float) -> bp.Scene:
    """The model-cost reference scene."""
    return bp.Scene(bearing="6205", rpm=1797.0, radial_load_n=500.0, fault=fault,
                    duration_s=duration, fs=48_000.0)


def nj305(fault: bool) -> bp.Scene:
    """The NJ 305 paper's scene of tests/test_rotor2.py: 5 um clearance, 500 N, 1500 rpm,
    its 0.5 mm x 0.5 mm inner-race defect, 60 ms at 20 kHz (regular motion)."""
    b = bp.Bearing.catalog("NJ305").with_clearance(0.005)
    return bp.Scene(bearing=b, rpm=1500.0, radial_load_n=500.0, duration_s=0.06,
                    fault=bp.Fault("inner", width_mm=0.5, depth_mm=0.5) if fault else None,
                    fs=20_000.0, resonance_hz=8_000.0)


def errors(quick: bool) -> pd.DataFrame:
    """Output-acceleration error of rk4 and Newmark against dopri5 at rtol 1e-10."""
    steps = {"rk4": (0.1, 0.2, 0.3, 0.35, 0.4, 0.6) if not quick else (0.2, 0.3, 0.35, 0.4),
             "newmark": (0.0125, 0.025, 0.05) if not quick else (0.025, 0.05)}
    rows = []
    scenes = {name: scene(fault, 0.1 if quick else 0.2) for name, fault in FAULTS.items()}
    scenes.update({"NJ 305, 5 um clearance, healthy": nj305(False),
                   "NJ 305, 5 um clearance, 0.5 mm defect": nj305(True)})
    for name, s in scenes.items():
        omega = R.contact_omega(s)
        ref = bp.simulate(s, model="rotor2", solver="dopri5", rtol=1e-10).accel
        for solver, values in steps.items():
            for c in values:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")  # newmark rounds dt to the output grid
                    res = bp.simulate(s, model="rotor2", solver=solver, dt=c / omega)
                rows.append(dict(scene=name, solver=solver, omega_dt=res.info["dt_s"] * omega,
                                 dt_us=res.info["dt_s"] * 1e6, steps=res.info["n_steps"],
                                 restarts=res.info.get("n_contact_restarts", 0),
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
                             solver=res.info["solver"], steps=res.info["n_steps"],
                             restarts=res.info.get("n_contact_restarts", 0)))
    return pd.DataFrame(rows)


def breakdown(quick: bool) -> pd.DataFrame:
    """Where 1 s of the faulty scene at 48 kHz spends its CPU time (thread time, medians
    of interleaved rounds): the RK4 steps alone (outputs every 1 ms), the same with the
    outputs at the 192 kHz internal grid (quintic Hermite interpolation), the anti-alias
    decimation to 48 kHz, and the whole simulate call."""
    from ballpass.simulate._shared import OVERSAMPLE, to_output_rate

    s = scene(FAULTS["inner, ramped edges"], 1.0)
    bound = R._bind(s, R.Rotor2Parameters())
    minv = np.linalg.inv(np.eye(2) * bound.mass)

    def steps_only(n_out):
        h_out = 1.0 / n_out
        t_end = (n_out - 1) * h_out
        cr = R._crossings(s, bound.p, bound.levels, t_end)
        breaks, seg_dt = R._rk4_breaks(cr, bound, t_end, R.DT_RK4_OMEGA / bound.omega)
        out = [np.empty((n_out, 2)) for _ in range(3)]
        return lambda: R._rk4(bound.p.copy(), minv, bound.x0, np.zeros(2), h_out, n_out,
                              breaks, seg_dt, s.bearing.n_elements,
                              R._gap_tol(bound), 1e4, bound.x_scale,
                              n_out, *out)

    grid = np.random.default_rng(0).standard_normal((s.n_samples * OVERSAMPLE, 1))
    parts = {"RK4 steps (outputs every 1 ms)": steps_only(1000),
             "RK4 steps and outputs on the 192 kHz grid": steps_only(s.n_samples * OVERSAMPLE),
             "anti-alias decimation 192 -> 48 kHz": lambda: to_output_rate(grid, s.n_samples,
                                                                             OVERSAMPLE),
             "simulate (whole call)": lambda: bp.simulate(s, model="rotor2")}
    for run in parts.values():
        run()  # compile, warm
    rows = []
    for k in range(3 if quick else 7):
        for name, run in parts.items():
            c0 = time.thread_time()
            run()
            rows.append(dict(round=k, part=name, cpu_ms=1e3 * (time.thread_time() - c0)))
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
    ax.set_title("rotor2 against dopri5 (rtol 1e-10): 6205 at 1797 rpm, NJ 305 at 1500 rpm",
                 fontsize=9)
    ax.legend(fontsize=7)
    fig.savefig(RESULTS_DIR / "rotor2_step.png", dpi=110)


def page(err: pd.DataFrame, cst: pd.DataFrame, parts: pd.DataFrame) -> str:
    wide = cst.pivot(index="round", columns="model", values="wall_s")
    part = parts.groupby("part", sort=False)["cpu_ms"].median()
    total = part["simulate (whole call)"]
    steps_ms = part["RK4 steps (outputs every 1 ms)"]
    interp_ms = part["RK4 steps and outputs on the 192 kHz grid"] - steps_ms
    decim_ms = part["anti-alias decimation 192 -> 48 kHz"]
    part_tab = pd.DataFrame([
        {"part": "RK4 steps (4 force evaluations at 2 distinct times each)",
         "CPU ms": f"{steps_ms:.1f}", "share": f"{steps_ms / total:.0%}"},
        {"part": "outputs: quintic Hermite at the 192 kHz internal grid",
         "CPU ms": f"{interp_ms:.1f}", "share": f"{interp_ms / total:.0%}"},
        {"part": "anti-alias decimation to 48 kHz (as sr5)",
         "CPU ms": f"{decim_ms:.1f}", "share": f"{decim_ms / total:.0%}"},
        {"part": "the rest (binding, crossings, fresh output arrays, result)",
         "CPU ms": f"{total - steps_ms - interp_ms - decim_ms:.1f}",
         "share": f"{(total - steps_ms - interp_ms - decim_ms) / total:.0%}"},
        {"part": "whole call", "CPU ms": f"{total:.1f}", "share": "100%"}])
    nj = err[(err["solver"] == "rk4") & err["scene"].str.startswith("NJ 305")]
    nj_default = nj[np.isclose(nj["omega_dt"], R.DT_RK4_OMEGA, rtol=1e-3)]
    nj_035 = nj[np.isclose(nj["omega_dt"], 0.35, rtol=1e-3)]
    ratio = wide["rotor2"] / wide["sr5"]
    med = wide.median()
    spread = wide.max() - wide.min()
    steps = cst.groupby("model")["steps"].first()
    restarts = int(cst.loc[cst["model"] == "rotor2", "restarts"].iloc[0])
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
{R.RK4_RAMP_STEPS} steps across each ramp, and where a roller's contact closes or opens:
Palmgren's load K delta^(10/9) has no derivatives of order above 10/9 at delta = 0, and
a step across that kink errs at a lower order. A step over which a roller's compression
changes sign is retaken up to the root (Illinois regula falsi on the step's quintic
Hermite interpolant, to 1e-9 of the step), and the step on the kink's loaded side (after
a closure, before an opening) is split into {_I.GRADE_STEPS} steps at fractions
(k / {_I.GRADE_STEPS})^{_I.GRADE_POWER} from it (Simpson's rule on a load growing as
tau^(10/9) errs 110x less so). Contacts whose stiffness stays below
{R.GAP_STIFFNESS} of the static one within the step are stepped over (Hertz's balls to
{R.GAP_STIFFNESS ** 2:.2f} of the static compression, Palmgren's rollers to
{R.GAP_STIFFNESS ** 9:.1e}). `solver="newmark"` remains (the paper's method, at its old
default step).

Relative L2 error of the output acceleration against dopri5 at rtol 1e-10
(`rotor2_step.csv`; `restarts`: rk4's restarts on contact closures and openings):

{markdown_table(err_tab)}

At the default step the error is {default['error_l2'].min():.1e} to
{default['error_l2'].max():.1e} (limit 1e-2). The NJ 305 paper's scene (5 um clearance,
the regular 60 ms window of tests/test_rotor2.py) errs {nj_default['error_l2'].min():.1e}
to {nj_default['error_l2'].max():.1e} at the default step and {nj_035['error_l2'].min():.1e}
to {nj_035['error_l2'].max():.1e} at 0.35 / omega_c (healthy and with its defect): its
rollers leave and re-enter the load zone every pass and, with the defect, the rotor
bounces off all its rollers for moments after the first passage. Before the restarts on
contact closures rk4 erred 2.1e-2 there at the default step, 9.5e-3 at 0.2 / omega_c and
3.4e-3 at 0.1 / omega_c (not fourth order: each closure and opening was stepped over);
now the error falls about 12x per halved step there (15x healthy; fourth order is 16x,
and the defect's ramps take steps of their own, 1/8 of the ramp, which do not shrink
with dt above 0.12 / omega_c; tests/test_rotor2.py checks 0.15 against 0.3 / omega_c).
On the 6205 scenes (ball contacts, whose stiffness grows from zero) restarting at every
closure changed the error by 10 % for 1.4x the steps; there rk4 restarts a few dozen
times per second.

## Where the 48 kHz cost goes

CPU time (thread time, medians of interleaved rounds) of 1 s of the faulty scene at
48 kHz:

{markdown_table(part_tab)}

The step is not set by the output rate (33 000 steps of 32 us for 192 000 internal
outputs); the steps themselves are most of the cost. Two things were cut: the sines and
cosines of the roller and unbalance angles, two of each per time, now a small rotation
from the previous time (:func:`ballpass.simulate._kernels.cached_cos_sin`, shared with
sr5), and the output interpolation, which evaluated the five quintic Hermite weights and
an integer modulo per output and now three multiply-adds per component on coefficients
set once per step; and, in the rest, the binding computed the bearing's equilibrium and
stiffness three times and the crossings path by path (now once, and vectorised).

## Cost against sr5

1 s of the faulty scene, {len(wide)} interleaved rounds: rotor2 (rk4, {steps['rotor2']}
steps and {restarts} restarts on contact closures and openings)
{med['rotor2'] * 1e3:.0f} ms (spread {spread['rotor2'] * 1e3:.0f} ms), sr5
({steps['sr5']} steps) {med['sr5'] * 1e3:.0f} ms (spread {spread['sr5'] * 1e3:.0f} ms);
rotor2 / sr5 round by round: median {ratio.median():.2f}, range {ratio.min():.2f} -
{ratio.max():.2f}. With Newmark at 2.6 us (384 000 steps) rotor2 cost 25x sr5, and 2.0x
with this RK4 step while every force evaluation recomputed the roller angles, the defect
depths and the unbalance angle (four times per step, at two distinct times) and the
tangents only Newmark reads; both are now computed once per time and for Newmark only.
The check for contact closures and openings at every step end (the Z compressions at
the step's end state, whose kinematics the force has just cached) costs about a tenth
of the steps (10.7 against 9.6 ms of CPU for the steps alone with it switched off,
measured side by side once).

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
    parts = breakdown(args.quick)
    parts.to_csv(RESULTS_DIR / "rotor2_step_breakdown.csv", index=False)
    plot(err)
    text = page(err, cst, parts)
    (DOCS / "rotor2_step.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
