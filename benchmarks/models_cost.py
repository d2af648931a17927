"""Cost of every registered model per simulated second, relative to sr5, side by side.

The reference scene: a 6205 at 1797 rpm and 500 N with the default 0.5 mm x 0.1 mm
inner-race fault (the fault with the most events per second), 48 kHz output, the
default 15 kHz / 5 % resonance, one loaded-zone sensor, 1 s. Every model in
``ballpass.simulate.MODELS`` (whatever is registered when the script runs) is timed
through the whole of :func:`ballpass.simulate` with its default solver, after a warm-up
call (numba compilation is not timed). The models run interleaved, one call each per
round, so a round's ratios share the machine's state; the table gives the median
wall time per simulated second and the median and interquartile range of the per-round
ratio to sr5. A model that cannot take the reference scene is listed with its reason.

Writes ``docs/models_cost.md``, ``docs/results/models_cost.csv`` and
``docs/results/models_cost.png``,
and regenerates the model table (from :func:`ballpass.simulate.model_table` and this
measurement) between the ``models-table`` markers of ``docs/models.md`` and
``docs/hierarchy.md``; the ``relative_cost`` of each model in the code cites this table.

    python benchmarks/models_cost.py                # 1 s scene, 15 rounds
    python benchmarks/models_cost.py --rounds 3     # a quick run
"""

from __future__ import annotations

import argparse
import time

import _machine  # benchmarks/_machine.py (scripts run from their folder)
import numpy as np
from _paths import DOCS, RESULTS_DIR
from _report import table as md_table
from _report import write_csv, write_page

import ballpass as bp
from ballpass import __version__

BEGIN, END = "<!-- models-table: begin -->", "<!-- models-table: end -->"
#: a model slower than this per call gets fewer rounds (s)
BUDGET_S = 60.0


#: the reference scene (48 kHz, 15 kHz resonance: relative_cost cites it) and a
#: CWRU-like 12 kHz one with a 3.5 kHz resonance
SCENES = {"48 kHz": (48_000.0, 15_000.0), "12 kHz": (12_000.0, 3_500.0)}


#: back-to-back calls per model and round (models faster than 1 s per call)
REPEATS = 3
#: back-to-back calls of a fast model fill at least this long, s
WARM_S = 0.05


def reference_scene(duration: float, config: str = "48 kHz") -> bp.Scene:
    fs, resonance = SCENES[config]
    return bp.Scene("6205", rpm=1797.0, radial_load_n=500.0, fault=bp.Fault("inner"),
                    duration_s=duration, fs=fs, resonance_hz=resonance)


def measure(duration: float, rounds: int, config: str) -> tuple[list[dict], dict[str, str]]:
    scene = reference_scene(duration, config)
    models, skipped = [], {}
    for name, m in bp.simulate.MODELS.items():
        reason = m.accepts(scene)
        if reason:
            skipped[name] = reason
            continue
        bp.simulate(scene.replace(duration_s=min(duration, 0.05)), model=name)  # compile
        t0 = time.perf_counter()
        bp.simulate(scene, model=name)  # warm caches; its time sets the round budget
        models.append((name, time.perf_counter() - t0))
    records = []
    for r in range(rounds):
        times = {}
        for name, first in models:
            if r > 0 and first * r > BUDGET_S:
                continue  # a very slow model: enough rounds for a median
            # the median of back-to-back calls (REPEATS, or as many as fill WARM_S for a
            # fast model; one for slow models): a model run right after a multi-second one
            # starts with cold caches, which is not how a dataset runs it (the impulse
            # model's first call after the multibody costs 3x its next ones); rounds still
            # interleave the models side by side
            calls = []
            n_calls = max(REPEATS, int(np.ceil(WARM_S / first))) if first < 1.0 else 1
            for _ in range(n_calls):
                t0, c0 = time.perf_counter(), time.thread_time()
                bp.simulate(scene, model=name)
                calls.append(((time.perf_counter() - t0) / duration,
                              (time.thread_time() - c0) / duration))
            times[name] = tuple(np.median(np.array(calls), axis=0))
        for name, (t, c) in times.items():
            ref = times.get("sr5", (np.nan, np.nan))
            records.append(dict(scene=config, round=r, model=name, s_per_sim_s=t,
                                cpu_s_per_sim_s=c, ratio_to_sr5=t / ref[0],
                                cpu_ratio_to_sr5=c / ref[1]))
    return records, skipped


def summarise(records: list[dict]):
    import pandas as pd

    df = pd.DataFrame(records)
    rows = []
    for (config, name), g in df.groupby(["scene", "model"], sort=False):
        q = g["ratio_to_sr5"].quantile([0.25, 0.5, 0.75])
        rows.append(dict(scene=config, model=name, rounds=len(g),
                         ms_per_sim_s=1e3 * g["s_per_sim_s"].median(),
                         ms_per_sim_s_min=1e3 * g["s_per_sim_s"].min(),
                         ratio_median=q[0.5], ratio_q25=q[0.25], ratio_q75=q[0.75],
                         cpu_ratio_median=g["cpu_ratio_to_sr5"].median(),
                         speedup_vs_sr5=1.0 / q[0.5],
                         relative_cost_in_code=bp.simulate.MODELS[name].relative_cost))
    return pd.DataFrame(rows).sort_values(["scene", "ratio_median"], ascending=[False, True])


def write(table, skipped: dict, duration: float, rounds: int) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    write_csv(table, RESULTS_DIR / "models_cost.csv", float_format="%.5g")
    lines = [
        "# Cost of each model per simulated second (benchmarks/models_cost.py)",
        "",
        f"Reference scene: 6205, 1797 rpm, 500 N, inner-race fault 0.5 x 0.1 mm, 48 kHz "
        f"output with the default 15 kHz resonance (``relative_cost`` cites it; also at "
        f"12 kHz with 3.5 kHz), {duration:g} s, one sensor; default solver of each model; "
        f"{rounds} interleaved rounds. ballpass {__version__}; {_machine.machine()}.",
        "",
        "Wall time is what a user waits; the machine is shared, so the CPU time of the "
        "simulating thread (``time.thread_time``, which leaves out the time other "
        "processes held the cores) and the fastest round are given beside it.",
        "",
    ]
    rows = [(row.scene, row.model, f"{row.ms_per_sim_s:.2f} ({row.ms_per_sim_s_min:.2f})",
             f"{row.ratio_median:.4f}", f"{row.ratio_q25:.4f} - {row.ratio_q75:.4f}",
             f"{row.cpu_ratio_median:.4f}", f"{row.speedup_vs_sr5:.1f}x",
             f"{row.relative_cost_in_code:g}") for row in table.itertuples()]
    rows += [("", name, f"not measured: {reason}", "", "", "", "",
              f"{bp.simulate.MODELS[name].relative_cost:g}") for name, reason in skipped.items()]
    lines += md_table(["scene", "model", "ms per simulated s, median (fastest)",
                       "cost / sr5, median", "IQR of the ratio", "CPU-time ratio, median",
                       "speed-up vs sr5", "relative_cost in the code"], rows, "llrrlrrr")
    write_page(DOCS / "models_cost.md", lines)

    table = table[table["scene"] == "48 kHz"]
    fig, ax = plt.subplots(figsize=(6, 3.2))
    y = np.arange(len(table))
    ms = table["ms_per_sim_s"].to_numpy()
    sr5_ms = float(table.loc[table["model"] == "sr5", "ms_per_sim_s"].iloc[0])
    lo = sr5_ms * table["ratio_q25"].to_numpy()
    hi = sr5_ms * table["ratio_q75"].to_numpy()
    ax.barh(y, ms, color="tab:blue")
    ax.errorbar(sr5_ms * table["ratio_median"].to_numpy(), y,
                xerr=[sr5_ms * table["ratio_median"].to_numpy() - lo,
                      hi - sr5_ms * table["ratio_median"].to_numpy()],
                fmt="none", color="k", capsize=3, label="IQR of the ratio to sr5")
    ax.set_yticks(y, table["model"])
    ax.set_xscale("log")
    ax.set_xlabel("wall time per simulated second, ms (median)")
    ax.set_title("Cost per simulated second per model (6205 inner fault, 48 kHz)")
    for yi, (m, r) in enumerate(zip(np.maximum(ms, hi), table["ratio_median"], strict=True)):
        ax.text(m, yi + 0.3, f"  {r:.3g} x sr5", va="center", fontsize=8)
    ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(RESULTS_DIR / "models_cost.png", dpi=120)


def registry_markdown(table) -> str:
    """The registry (:func:`ballpass.simulate.model_table`) with the measured costs."""
    reg = bp.simulate.model_table()
    measured = dict(zip(table.loc[table["scene"] == "48 kHz", "model"],
                        table.loc[table["scene"] == "48 kHz", "ratio_median"], strict=True))
    phenomena = [c for c in reg.columns if c in bp.simulate.PHENOMENA]
    lines = ["| model | represents | relative_cost (sr5 = 1) | measured | solvers | what it is |",
             "|---|---|---:|---:|---|---|"]
    for row in reg.to_dict("records"):
        rep = ", ".join(p for p in phenomena if row[p])
        got = f"{measured[row['model']]:.3g}" if row["model"] in measured else "-"
        lines.append(f"| `{row['model']}` | {rep} | {row['relative_cost']:g} | {got} | "
                     f"{row['solvers']} | {row['description']} |")
    return "\n".join(lines)


def update_tables(table) -> None:
    """Replace the text between the models-table markers of docs/models.md and docs/hierarchy.md."""
    block = f"{BEGIN}\n{registry_markdown(table)}\n{END}"
    for path in (DOCS / "models.md", DOCS / "hierarchy.md"):
        text = path.read_text()
        if BEGIN in text and END in text:
            head, rest = text.split(BEGIN, 1)
            path.write_text(head + block + rest.split(END, 1)[1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=1.0, help="simulated s per call")
    parser.add_argument("--rounds", type=int, default=15, help="interleaved rounds")
    args = parser.parse_args()
    records, skipped = [], {}
    for config in SCENES:
        rec, skip = measure(args.duration, args.rounds, config)
        records += rec
        skipped.update(skip)
    table = summarise(records)
    write(table, skipped, args.duration, args.rounds)
    update_tables(table)
    print((DOCS / "models_cost.md").read_text())


if __name__ == "__main__":
    main()
