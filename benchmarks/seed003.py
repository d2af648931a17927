"""The NJ 305 rotor paper reproduction: the rotor on an NJ 305 roller bearing (model ``rotor2``).

The NJ 305 rotor paper ("Dynamic behaviour of rotor roller bearing system with bearing defects")
simulates a 1 kg rigid rotor on an NJ 305 with
0.25 mm diametral clearance, 200 N s/m damping, a 50 g x 20 um unbalance and a 0.5 x 0.5
mm inner-race defect, integrated with Newmark-beta. It reports (section 5) the inner-race
line at 166.73/100.04/66.69/55.55 Hz at 1500/900/600/500 rpm, displacement amplitudes of
0.7-4 um at that line, and that "as the clearance increases the dynamic behaviour
becomes complicated". This script checks each claim with ballpass and measures the
solvers:

1. ``solvers``: the default rk4 and Newmark at their default steps against dopri5 at
   rtol 1e-10, and dopri5 at rtol 1e-8 against 1e-10 (the floor any two solvers reach on
   that scene); wall times.
2. ``ceiling``: the largest BPFI line the seed's notch can make in a rotor resting on its
   rollers, in closed form (:func:`line_ceiling`), against the seed's amplitudes.
3. ``lines``: the x-displacement spectrum at the four speeds, for the seed's set-up (0.125
   mm radial clearance, gravity only) and for a regular one (5 um, 500 N).
4. ``bifurcation``: Poincare sections over the clearance (0-0.125 mm) and the speed
   (500-2000 rpm) with the 0-1 test for chaos on each section.

    python benchmarks/seed003.py            # ~5 min on 2 cores
    python benchmarks/seed003.py --quick    # shorter records, fewer values

Writes ``docs/results/seed003_*.csv`` and ``docs/results/seed003_*.png``; docs/seed003.md
quotes them.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import pandas as pd
from _paths import DOCS
from _paths import RESULTS_DIR as RESULTS

import ballpass as bp
from ballpass.simulate import Rotor2Parameters

#: the NJ 305 rotor paper section 5.1, verbatim: rpm -> (theoretical Hz, theoretical um, measured
# Hz,
#: measured um)
SEED_TABLE = {1500: (166.7, 4.0, 167.75, 3.5), 900: (99.43, 1.67, 101.75, 2.5),
              600: (65.6, 2.0, 67.0, 1.5), 500: (55.0, 1.3, 56.25, 0.7)}
#: the NJ 305 rotor paper section 5 (computed with the BPFI formula)
SEED_SECTION5 = {1500: 166.73, 900: 100.04, 600: 66.69, 500: 55.55}
DEFECT = bp.Fault("inner", width_mm=0.5, depth_mm=0.5)  # the NJ 305 rotor paper section 3.6


def scene(clearance_mm: float, load_n: float, rpm: float, duration: float, fs: float,
          fault=DEFECT) -> bp.Scene:
    """An NJ 305 scene; rotor2 ignores the resonance (any valid value)."""
    b = bp.Bearing.catalog("NJ305").with_clearance(clearance_mm)
    return bp.Scene(bearing=b, rpm=rpm, radial_load_n=load_n, fault=fault,
                    duration_s=duration, fs=fs, resonance_hz=0.4 * fs)


def _rel(x, ref, n=None):
    """Relative L2 error of the dynamic part of the displacement (first n samples)."""
    x, ref = x[:, :n], ref[:, :n]
    return float(np.linalg.norm(x - ref) / np.linalg.norm(ref - ref.mean(axis=1, keepdims=True)))


def solvers(quick: bool) -> pd.DataFrame:
    """Newmark (default step) and dopri5 (1e-8) against dopri5 at rtol 1e-10."""
    duration = 0.1 if quick else 0.3
    cases = [("regular, healthy", 0.005, 500.0, None),
             ("regular, inner defect", 0.005, 500.0, DEFECT),
             ("seed set-up, healthy", 0.125, 0.0, None),
             ("seed set-up, inner defect", 0.125, 0.0, DEFECT)]
    rows = []
    for name, c, load, fault in cases:
        s = scene(c, load, 1500.0, duration, 20_000.0, fault)
        runs = {}
        for key, kw in (("ref", dict(solver="dopri5", rtol=1e-10)),
                        ("dopri5", dict(solver="dopri5", rtol=1e-8)), ("default", {}),
                        ("newmark", dict(solver="newmark"))):
            bp.simulate(s.replace(duration_s=0.01), model="rotor2", **kw)  # compile
            t0 = time.perf_counter()
            runs[key] = bp.simulate(s, model="rotor2", return_forces=True, **kw)
            runs[key].info["wall"] = time.perf_counter() - t0
        ref = runs["ref"].truth.displacement
        n50 = int(0.05 * s.fs)
        for key in ("default", "newmark", "dopri5"):
            x = runs[key].truth.displacement
            info = runs[key].info
            rows.append(dict(scene=name, solver=info["solver"] + (" (default)" if key == "default"
                                                                  else ""),
                             step=(f"dt = {info['dt_s'] * 1e6:.2f} us" if "dt_s" in info
                                   else "rtol = 1e-8"),
                             err_50ms=_rel(x, ref, n50), err_full=_rel(x, ref),
                             wall_s=runs[key].info["wall"],
                             ref_wall_s=runs["ref"].info["wall"]))
    df = pd.DataFrame(rows)
    df.attrs["duration"] = duration
    return df


def cost_ratio(quick: bool) -> dict:
    """Wall time per simulated second, rotor2 and sr5 (default solvers), medians of 3."""
    duration = 0.2 if quick else 0.5
    out = {}
    for model, s in (("sr5", bp.Scene(bearing="NJ305", rpm=1500, radial_load_n=500,
                                      duration_s=duration, fs=48_000.0)),
                     ("rotor2", bp.Scene(bearing="NJ305", rpm=1500, radial_load_n=500,
                                         duration_s=duration, fs=48_000.0))):
        bp.simulate(s.replace(duration_s=0.01), model=model)
        times = []
        for _ in range(3):
            t0 = time.perf_counter()
            bp.simulate(s, model=model)
            times.append(time.perf_counter() - t0)
        out[model] = (float(np.median(times)), float(np.ptp(times)))
    return out


def _spectrum(x, fs):
    win = np.hanning(x.size)
    amp = 2 * np.abs(np.fft.rfft((x - x.mean()) * win, 8 * x.size)) / win.sum()
    return np.fft.rfftfreq(8 * x.size, 1 / fs), amp


def lines(quick: bool):
    """Spectra of x at the seed's four speeds for two set-ups."""
    revs = 12 if quick else 40
    setups = {"seed set-up (c = 0.125 mm, gravity only)": (0.125, 0.0),
              "regular (c = 5 um, 500 N)": (0.005, 500.0)}
    rows, spectra = [], {}
    for label, (c, load) in setups.items():
        for rpm in SEED_TABLE:
            s = scene(c, load, rpm, revs * 60 / rpm, 3000.0 * rpm / 1500)
            res = bp.simulate(s, model="rotor2", return_forces=True)
            x = res.truth.displacement[0, s.n_samples // 4:]
            f, amp = _spectrum(x, s.fs)
            bpfi = s.frequencies.bpfi
            near = np.abs(f - bpfi) < 0.5 * s.shaft_hz
            k = np.flatnonzero(near)[np.argmax(amp[near])]
            band = f > 0.5 * s.shaft_hz
            top = np.flatnonzero(band)[np.argmax(amp[band])]
            spectra[(label, rpm)] = (f, amp, bpfi)
            rows.append(dict(setup=label, rpm=rpm, seed_section5_hz=SEED_SECTION5[rpm],
                             seed_theory_hz=SEED_TABLE[rpm][0], seed_measured_hz=SEED_TABLE[rpm][2],
                             bpfi_hz=bpfi, line_hz=f[k], line_um=amp[k] * 1e6,
                             seed_theory_um=SEED_TABLE[rpm][1], seed_measured_um=SEED_TABLE[rpm][3],
                             largest_line_hz=f[top], largest_line_um=amp[top] * 1e6,
                             p2p_x_um=np.ptp(x) * 1e6))
    return pd.DataFrame(rows), spectra


def line_ceiling() -> pd.DataFrame:
    """Largest BPFI line a 0.5 x 0.5 mm inner-race notch can put in the displacement,
    from the kinematics alone (no model run).

    While a roller is in the notch the rotor can drop at most the roller's geometric
    drop h (``Fault.effective_depth_mm``: a 9.25 mm cylinder bridging a 0.5 mm wide notch
    in the convex inner race)
    and, supported by gravity alone, at most the free fall g tau^2 / 2 in the notch
    crossing time tau. The notch is under some roller a fraction Z w / (2 pi r_i) of the
    time (Z rollers meet it per inner-ring turn, each for w / (2 pi r_i) of the turn).
    A non-negative pulse train's Fourier amplitude at any frequency is at most twice its
    mean, so |X(BPFI)| <= 2 min(h, g tau^2 / 2) Z w / (2 pi r_i), for a rotor that stays
    on its rollers (quasi-static below the contact mode: BPFI / f_c < 0.1, so the
    dynamic amplification 1 / (1 - (BPFI / f_c)^2) is below 1.01).
    """
    b = bp.Bearing.catalog("NJ305").with_clearance(0.125)
    h = DEFECT.effective_depth_mm(b) * 1e-3
    r_i = 0.5 * (b.pitch_diameter_mm - b.element_diameter_mm) * 1e-3
    duty = b.n_elements * DEFECT.width_mm * 1e-3 / (2 * np.pi * r_i)
    f_c = bp.simulate.rotor2.contact_omega(scene(0.125, 0.0, 1500.0, 0.1, 3000.0)) / (2 * np.pi)
    rows = []
    for rpm, (_, theory_um, _, measured_um) in SEED_TABLE.items():
        s = scene(0.125, 0.0, rpm, 0.1, 3000.0)
        surface = (s.shaft_hz - s.frequencies.ftf) * 2 * np.pi * r_i  # notch past a roller
        tau = DEFECT.width_mm * 1e-3 / surface
        drop = min(h, 0.5 * bp.scene.STANDARD_GRAVITY * tau**2)
        ceiling = 2 * drop * duty
        rows.append(dict(rpm=rpm, bpfi_hz=s.frequencies.bpfi, drop_um=h * 1e6,
                         crossing_ms=tau * 1e3, free_fall_um=0.5 * 9.80665 * tau**2 * 1e6,
                         duty=duty, ceiling_um=ceiling * 1e6,
                         ceiling_any_drop_um=2 * h * duty * 1e6,
                         paper_theory_um=theory_um, paper_measured_um=measured_um,
                         theory_over_ceiling=theory_um / (ceiling * 1e6),
                         bpfi_over_contact=s.frequencies.bpfi / f_c))
    return pd.DataFrame(rows)


def _sweep(base: bp.Scene, parameter: str, values, discard: float) -> pd.DataFrame:
    df = bp.dynamics.bifurcation_diagram(base, parameter, values, discard_s=discard,
                                         n_jobs=2, params=Rotor2Parameters())
    k = {v: (bp.dynamics.zero_one_test(g["x_m"].to_numpy())
             if len(g) >= bp.dynamics.MIN_POINTS_01 else np.nan)
         for v, g in df.groupby("parameter")}
    df["K"] = df["parameter"].map(k)
    return df


def bifurcation(quick: bool):
    """Poincare sections over clearance (2000 rpm, the seed's speed) and over speed."""
    # 100 section points after a 30-revolution transient (quick: 20 after 10)
    skip, revs = (10, 30) if quick else (30, 130)
    n = 6 if quick else 14
    rpm = 2000.0
    base = scene(0.125, 0.0, rpm, revs * 60 / rpm, 4000.0, fault=None)
    clear = _sweep(base, "radial_clearance_mm", np.linspace(0.0, 0.125, n), skip * 60 / rpm)
    speeds = np.linspace(500.0, 2000.0, n)
    # the same duration at every speed: at least `revs` revolutions at the slowest
    base_s = base.replace(duration_s=revs * 60 / speeds[0])
    speed = _sweep(base_s, "rpm", speeds, skip * 60 / speeds[0])
    return clear, speed


def plot_lines(spectra: dict) -> None:
    """The spectra figure: x amplitude at the four speeds, two set-ups."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(4, 2, figsize=(10, 9), layout="constrained", sharex="row")
    for j, label in enumerate(dict.fromkeys(k[0] for k in spectra)):
        for i, rpm in enumerate(SEED_TABLE):
            f, amp, bpfi = spectra[(label, rpm)]
            ax = axes[i, j]
            keep = f < 2.5 * bpfi
            ax.plot(f[keep], amp[keep] * 1e6, lw=0.8)
            ax.axvline(bpfi, color="tab:red", ls="--", lw=0.8, label=f"BPFI {bpfi:.2f} Hz")
            ax.axvline(SEED_TABLE[rpm][2], color="tab:green", ls=":", lw=0.8,
                       label=f"seed measured {SEED_TABLE[rpm][2]} Hz")
            ax.set_title(f"{label}, {rpm} rpm", fontsize=9)
            ax.set_ylabel("x amplitude (um)")
            ax.legend(fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("Frequency (Hz)")
    fig.savefig(RESULTS / "seed003_lines.png", dpi=110)


def plot_bifurcations(clear: pd.DataFrame, speed: pd.DataFrame) -> None:
    """Sections over clearance and speed; the 0-1 test K where a section is long enough."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(11, 7), layout="constrained")
    for col, (df, name) in enumerate(((clear, "radial clearance (mm)"), (speed, "rpm"))):
        bp.dynamics.plot_bifurcation(df, ax=axes[0, col], s=1)
        axes[0, col].set_xlabel(name)
        # x minus the clearance is the elastic approach: shows small clearances too
        rel = df.assign(x_m=df["x_m"] - (df["parameter"] * 1e-3 if col == 0 else 0.125e-3))
        bp.dynamics.plot_bifurcation(rel, ax=axes[1, col], s=1)
        axes[1, col].set_ylabel("x - clearance at the section (um)")
        axes[1, col].set_xlabel(name)
        k = df.groupby("parameter")["K"].first().dropna()
        if len(k):
            twin = axes[1, col].twinx()
            twin.plot(k.index, k.values, "o-", color="tab:red", ms=3, lw=0.8)
            twin.set_ylim(-0.05, 1.05)
            twin.set_ylabel(f"0-1 test K (red; sections of >= {bp.dynamics.MIN_POINTS_01} points)")
    fig.savefig(RESULTS / "seed003_bifurcation.png", dpi=110)


def _print(df: pd.DataFrame, **kw) -> None:
    print(df.to_string(float_format=lambda v: f"{v:.3g}", **kw))


#: CSVs in docs/results/ the page is written from
CSVS = {"solvers": "seed003_solvers.csv", "cost": "seed003_cost.csv",
        "ceiling": "seed003_ceiling.csv", "lines": "seed003_lines.csv",
        "clearance": "seed003_bifurcation_clearance.csv",
        "speed": "seed003_bifurcation_speed.csv",
        # written by benchmarks/seed003_chaos.py (section 5 of the page)
        "chaos_agreement": "seed003_chaos_agreement.csv",
        "chaos_lyapunov": "seed003_chaos_lyapunov.csv", "chaos_sweep": "seed003_chaos_sweep.csv",
        "chaos_diagrams": "seed003_chaos_diagrams.csv"}


def _sections(df: pd.DataFrame) -> pd.DataFrame:
    """Poincare sections summarised per parameter value."""
    return df.groupby("parameter").agg(
        points=("x_m", "size"), mean_x_um=("x_m", lambda v: v.mean() * 1e6),
        spread_x_um=("x_m", lambda v: np.ptp(v) * 1e6),
        spread_y_um=("y_m", lambda v: np.ptp(v) * 1e6), K=("K", "first")).reset_index()


def _span(values, fmt: str = "{:.2g}") -> str:
    return f"{fmt.format(min(values))}-{fmt.format(max(values))}"


def _chaos(d: dict) -> dict:
    """Section 5's tables and numbers from benchmarks/seed003_chaos.py's CSVs."""
    from ballpass.diagnose.report import markdown_table

    agree = d["chaos_agreement"]
    wide = agree.pivot_table(index=["rpm", "solver"], columns="t_ms", values="max_diff_um",
                             sort=False)
    wide.columns = [f"{c} ms" for c in wide.columns]
    wide = wide.map(lambda v: f"{v:.1e}").reset_index()
    # the growth rate of the two DOP853 runs' difference between 5 and 60 ms: a
    # Lyapunov estimate from the solvers alone
    ivp = agree[agree.solver.str.startswith("solve_ivp DOP853")].set_index(["rpm", "t_ms"])
    growth = {rpm: float(np.log(ivp.loc[(rpm, 60), "max_diff_um"]
                                / ivp.loc[(rpm, 5), "max_diff_um"]) / 0.055)
              for rpm in ivp.index.get_level_values(0).unique()}
    lyap_tab = d["chaos_lyapunov"][["clearance_mm", "contact_damping_ns_m", "rpm",
                                    "lyapunov_1_s", "at_half_1_s", "per_roller_pass",
                                    "doubling_ms"]].rename(columns={
                         "lyapunov_1_s": "exponent (1/s)", "at_half_1_s": "after half (1/s)",
                         "per_roller_pass": "per roller pass", "doubling_ms": "doubling (ms)"})
    lyap = d["chaos_lyapunov"]
    damped = lyap[lyap.contact_damping_ns_m > 0]
    lyap = lyap[lyap.contact_damping_ns_m == 0]
    sweep = d["chaos_sweep"].copy()
    sweep["unbalance_kg_m"] = sweep["unbalance_kg_m"].map(lambda v: f"{v:.0e}" if v else "0")

    def cell(kind, rel):
        return f"{kind.replace('non-periodic', 'NP').replace('period ', 'P')} ({rel:.0e})"

    sweep["roller"] = [cell(k, r) for k, r in zip(sweep.roller_strobe, sweep.roller_spread_rel,
                                                 strict=True)]
    sweep["shaft"] = [cell(k, r) for k, r in zip(sweep.shaft_strobe, sweep.shaft_spread_rel,
                                                strict=True)]
    sw = sweep.pivot_table(index=["unbalance_kg_m", "contact_damping_ns_m", "clearance_mm"],
                           columns="rpm", values=["roller", "shaft"], aggfunc="first")
    sw.columns = [f"{a}, {b:.0f} rpm" for a, b in sw.columns]
    periodic = sweep[sweep.roller_strobe.str.startswith("period")
                     | sweep.shaft_strobe.str.startswith("period")]
    diag = d["chaos_diagrams"].groupby(["setting", "rpm"], sort=False).agg(
        points=("x_um", "size"), section=("section", "first"),
        spread_rel=("spread_rel", "first"), orbit_um=("orbit_um", "first")).reset_index()
    dsum = diag.groupby(["setting", "section"], sort=False).agg(
        speeds=("rpm", lambda v: ", ".join(f"{x:.0f}" for x in v)),
        spread_rel=("spread_rel", lambda v: _span(v))).reset_index()
    big = lyap[lyap.clearance_mm == lyap.clearance_mm.max()].lyapunov_1_s
    small = lyap[(lyap.clearance_mm > 0) & (lyap.clearance_mm < lyap.clearance_mm.max())]
    zero = lyap[lyap.clearance_mm == 0].lyapunov_1_s
    return dict(
        agree_tab=markdown_table(wide), lyap_tab=markdown_table(lyap_tab),
        sweep_tab=markdown_table(sw.reset_index()), diag_tab=markdown_table(dsum),
        growth=" / ".join(f"{v:.0f} 1/s at {k:.0f} rpm" for k, v in growth.items()),
        lam_big=_span(big, "{:.0f}"), lam_small=_span(small.lyapunov_1_s, "{:.0f}"),
        small_mm=float(small.clearance_mm.iloc[0]) if len(small) else float("nan"),
        lam_zero=" and ".join(f"{v:.0f}" for v in zero),
        dbl=_span(lyap[lyap.clearance_mm == lyap.clearance_mm.max()].doubling_ms, "{:.1f}"),
        n_periodic=len(periodic), n_sweep=len(sweep),
        lam_damped=" and ".join(f"{r.lyapunov_1_s:.0f} 1/s at {r.rpm:.0f} rpm"
                                for r in damped.itertuples()))


def page(d: dict) -> str:
    """docs/seed003.md from the tables of one run (``CSVS``)."""
    from ballpass.diagnose.report import markdown_table

    sol = d["solvers"].copy()
    err = {(r.scene, r.solver.split()[0]): r for r in sol.itertuples()}
    for col in ("err_50ms", "err_full"):
        sol[col] = sol[col].map(lambda v: f"{v:.2g}")
    sol = sol.rename(columns={"err_50ms": "error, 50 ms", "err_full": "error, 0.3 s",
                              "wall_s": "wall (s)", "ref_wall_s": "reference wall (s)"})
    sol["scene"] = sol["scene"].str.replace("seed set-up", "paper's set-up")
    cost = d["cost"].set_index("model")
    ceil = d["ceiling"][["rpm", "bpfi_hz", "crossing_ms", "free_fall_um", "ceiling_um",
                         "ceiling_any_drop_um", "paper_theory_um", "paper_measured_um",
                         "theory_over_ceiling", "bpfi_over_contact"]]
    lines = d["lines"].copy()
    lines["setup"] = lines["setup"].str.replace("seed set-up", "paper's set-up")
    seed = lines[lines.setup.str.startswith("paper")]
    regular = lines[lines.setup.str.startswith("regular")]
    lines = lines[["setup", "rpm", "bpfi_hz", "line_hz", "line_um", "seed_theory_um",
                   "seed_measured_um", "largest_line_hz", "largest_line_um", "p2p_x_um"]
                  ].rename(columns={"seed_theory_um": "paper theory (um)",
                                    "seed_measured_um": "paper measured (um)"})
    clear, speed = _sections(d["clearance"]), _sections(d["speed"])
    small = clear[clear.parameter > 0].iloc[0]
    k = speed["K"].dropna()
    dt = {key: float(r.step.split()[2]) for key, r in err.items() if r.step.startswith("dt")}
    measured = d["ceiling"]["paper_measured_um"] / d["ceiling"]["ceiling_um"]
    values = dict(
        sol_tab=markdown_table(sol), ceil_tab=markdown_table(ceil),
        lines_tab=markdown_table(lines), clear_tab=markdown_table(clear),
        speed_tab=markdown_table(speed),
        pp=f"{_span(seed.p2p_x_um, '{:.0f}')} µm",
        seed_lines=" / ".join(f"{v:.2f}" for v in seed.line_um),
        ceilings=" / ".join(f"{v:.2g}" for v in d["ceiling"]["ceiling_um"]),
        ratios=" / ".join(f"{v:.2g}" for v in d["ceiling"]["theory_over_ceiling"]),
        c_small=small.spread_x_um, c_small_mm=small.parameter,
        c_big=clear.spread_x_um.iloc[-1], k_range=_span(k),
        dt_reg=dt[("regular, healthy", "rk4")],
        e_reg_h=err[("regular, healthy", "rk4")].err_50ms,
        e_reg_d=err[("regular, inner defect", "rk4")].err_50ms,
        d_h=err[("seed set-up, healthy", "dopri5")].err_50ms,
        dt_nm=dt[("seed set-up, inner defect", "newmark")],
        e_nm=err[("seed set-up, inner defect", "newmark")].err_50ms,
        dt_seed=dt[("seed set-up, inner defect", "rk4")],
        e_rk=err[("seed set-up, inner defect", "rk4")].err_50ms,
        c_r2=cost.loc["rotor2", "median_s"], s_r2=cost.loc["rotor2", "spread_s"],
        c_sr5=cost.loc["sr5", "median_s"], s_sr5=cost.loc["sr5", "spread_s"],
        c_ratio=cost.loc["rotor2", "median_s"] / cost.loc["sr5", "median_s"],
        r_t=_span(d["ceiling"]["theory_over_ceiling"], "{:.2g}") + "x",
        r_m=_span(measured, "{:.2g}") + "x",
        seed_range=_span(seed.line_um, "{:.1f}"),
        ceil_range=_span(d["ceiling"]["ceiling_um"]),
        drop=f"{d['ceiling']['drop_um'].iloc[0]:.1f}",
        any_drop=f"{d['ceiling']['ceiling_any_drop_um'].iloc[0]:.2f}",
        reg_range=_span(regular.line_um),
        s_range=_span(speed.spread_x_um, "{:.0f}"))
    return PAGE.format(**values, **_chaos(d))


#: the page's text (a template: ``page`` fills in the tables and the numbers quoted in
#: the prose from the CSVs)
PAGE = (Path(__file__).resolve().parent / "seed003_page.md").read_text()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="shorter records, fewer values")
    ap.add_argument("--replot", action="store_true",
                    help="redraw the bifurcation figure and rewrite docs/seed003.md from "
                         "the CSVs (no simulation)")
    args = ap.parse_args()
    RESULTS.mkdir(parents=True, exist_ok=True)
    import matplotlib

    matplotlib.use("Agg")
    t0 = time.perf_counter()
    if args.replot:
        clear = pd.read_csv(RESULTS / "seed003_bifurcation_clearance.csv")
        speed = pd.read_csv(RESULTS / "seed003_bifurcation_speed.csv")
        for df, name in ((clear, "radial_clearance_mm"), (speed, "rpm")):
            df.attrs["parameter"] = name
            short = df.groupby("parameter")["x_m"].transform("size") < \
                bp.dynamics.MIN_POINTS_01
            df.loc[short, "K"] = np.nan
            df.to_csv(RESULTS / f"seed003_bifurcation_{'clearance' if name != 'rpm' else 'speed'}"
                      ".csv", index=False)
    else:
        sol = solvers(args.quick)
        sol.to_csv(RESULTS / "seed003_solvers.csv", index=False)
        _print(sol, index=False)
        cost = cost_ratio(args.quick)
        pd.DataFrame([dict(model=m, median_s=v[0], spread_s=v[1]) for m, v in cost.items()]
                     ).to_csv(RESULTS / "seed003_cost.csv", index=False)
        print("cost (median, spread) s:", cost, "rotor2/sr5 =",
              cost["rotor2"][0] / cost["sr5"][0])
        ceil = line_ceiling()
        ceil.to_csv(RESULTS / "seed003_ceiling.csv", index=False)
        _print(ceil, index=False)
        tab, spectra = lines(args.quick)
        tab.to_csv(RESULTS / "seed003_lines.csv", index=False)
        _print(tab, index=False)
        plot_lines(spectra)
        clear, speed = bifurcation(args.quick)
        clear.to_csv(RESULTS / "seed003_bifurcation_clearance.csv", index=False)
        speed.to_csv(RESULTS / "seed003_bifurcation_speed.csv", index=False)
    plot_bifurcations(clear, speed)
    for name, df in (("clearance", clear), ("speed", speed)):
        print(name)
        _print(df.groupby("parameter").agg(points=("x_m", "size"),
                                           spread_um=("x_m", lambda v: np.ptp(v) * 1e6),
                                           K=("K", "first")))
    (DOCS / "seed003.md").write_text(page({k: pd.read_csv(RESULTS / f) for k, f in CSVS.items()}))
    print(f"total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
