"""A twin of the HIT-SM self-built rig from one healthy recording, tested on the others.

For each input speed (600, 900 and 1200 rpm in turn), the twin's only input is that
speed's healthy recording: ``ballpass twin`` (faults at 600, 900 and 1200 rpm),
``ballpass generate``, then ``ballpass benchmark --real`` on every other recording of
the rig (inner- and outer-race faults of 2, 5 and 8 degree arcs at all three speeds,
healthy at the two other speeds), one-second segments. Nothing is tuned on them: the
twin's ranges are its defaults (:data:`ballpass.datasets.twin.TWIN_DEFAULTS`). The rig
has no ball faults: three-class scores (a "ball" verdict counts as wrong).

Variants of the twin side by side in one run, from the same draws (:data:`TWINS`: the
grid lines each changes): point impacts (``impact_edges = [0]``, the twin before the
Hertzian edges), Hertzian edges only (each defect passage with its entry and exit edges,
``[1]``) and the default, which draws one of the two per row; ``--twins`` adds the
edges with identical or correlated impact sizes;
the impulsiveness (kurtosis) and the spectral median frequency of the twin's fault
rows beside the rig's fault seconds, with the Kolmogorov-Smirnov distance between the
twin's and the rig's log-kurtosis.

Run::

    PYTHONPATH=. python benchmarks/twin_hit.py --data ../shared/data/hit   # ~25 min, 2 shared cores

Writes ``twin_hit.md``, ``twin_hit.csv`` (one row per twin, input speed and model:
recall per class, three-class balanced accuracy, its range over the training seeds),
``twin_hit_kurtosis.csv`` and ``twin_hit.png`` (confusion matrices of the recommended
pipeline) to ``docs/results`` (the page to ``docs``).
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd
import scipy.signal
import scipy.stats
from _paths import DOCS, results_in
from _report import write_page

SPEEDS = (600, 900, 1200)
LABELS = {"Normal": "healthy", "IR": "inner", "OR": "outer"}
MODELS = "envelope,recommended"
CLASSES = ("healthy", "outer", "inner", "ball")
#: the twins compared: name -> {axis: value} of the grid lines it changes ({}: as written)
TWINS = {
    "point impacts": {"impact_edges": "[0]"},
    "Hertzian edges": {"impact_edges": "[1]"},
    "both, drawn per row": {},
    "edges, identical sizes": {"impact_edges": "[1]", "impact_spread": "[0]"},
    "edges, correlated sizes": {"impact_edges": "[1]",
                                "impact_correlation": "{ uniform = [0, 0.95] }"},
}
#: the twins a run compares unless --twins names others: each passage shape and the default
COMPARED = ("point impacts", "Hertzian edges", "both, drawn per row")
#: the twin the figure shows: the default
DEFAULT_TWIN = "both, drawn per row"


def variant(text: str, lines: dict) -> str:
    """The grid ``text`` with the line of each axis of ``lines`` set to its value; an axis
    without exactly one line in the grid is an error (the grid template changed)."""
    for axis, value in lines.items():
        text, n = re.subn(rf"^{axis} = .*$", f"{axis} = {value}", text, flags=re.M)
        if n != 1:
            raise ValueError(f"the twin's grid has {n} lines of {axis}, not 1")
    return text


def manifests(data: Path, speed: int, work: Path) -> tuple[Path, Path]:
    """The twin's manifest (the healthy recording at ``speed``) and the test manifest
    (every other recording, labelled)."""
    rows = []
    for path in sorted(data.glob("*.mat")):
        state, rpm = path.stem.split("_")
        rows.append({"path": str(path.resolve()), "fs": 51_200, "rpm": int(rpm),
                     "bearing": "6205", "label": LABELS[state.rstrip("0123456789")]})
    table = pd.DataFrame(rows)
    own = (table["label"] == "healthy") & (table["rpm"] == speed)
    healthy, test = work / f"healthy_{speed}.csv", work / f"test_{speed}.csv"
    table[own].drop(columns="label").to_csv(healthy, index=False)
    table[~own].to_csv(test, index=False)
    return healthy, test


def ballpass(*args) -> None:
    subprocess.run([sys.executable, "-m", "ballpass", *map(str, args)], check=True)


def signal_stats(X, labels) -> pd.DataFrame:
    """Kurtosis and spectral median frequency (Hz: half the power below it, Welch
    spectrum of 1024-sample segments at 51.2 kHz) of every fault row, with its label."""
    faults = (labels != "healthy").to_numpy()
    freq, power = scipy.signal.welch(X[faults], 51_200, nperseg=1024, axis=1)
    share = np.cumsum(power, axis=1) / power.sum(axis=1, keepdims=True)
    return pd.DataFrame({"label": labels[faults].to_numpy(),
                         "kurtosis": scipy.stats.kurtosis(X[faults], axis=1, fisher=False),
                         "median_hz": freq[np.argmax(share >= 0.5, axis=1)]})


def kurtosis(ds: Path) -> pd.DataFrame:
    """:func:`signal_stats` of the fault rows of a twin dataset."""
    from ballpass.datasets import load

    X, meta = load(ds)
    return signal_stats(X, meta["label"])


def one_twin(grid: Path, test: Path, work: Path, jobs: int):
    """Generate one twin and benchmark it on the test recordings: (results, predictions,
    kurtosis of its fault rows)."""
    ds, report = work / "ds", work / "rep"
    t0 = time.perf_counter()
    ballpass("generate", grid, "--out", ds, "--jobs", jobs, "--quiet")
    t1 = time.perf_counter()
    ballpass("benchmark", ds, "--real", test, "--splits", "sim2real", "--models", MODELS,
             "--out", report, "--quiet")
    t2 = time.perf_counter()
    results = pd.read_csv(report / "results.csv")
    seeds = pd.read_csv(report / "sim2real_seeds.csv")
    spread = seeds.groupby("model")["balanced_accuracy_3class"].agg(["min", "max"])
    results = results.join(spread, on="model")
    results["generate_s"], results["benchmark_s"] = t1 - t0, t2 - t1
    return results, pd.read_csv(report / "predictions.csv"), kurtosis(ds)


def one_speed(data: Path, speed: int, seed: int, work: Path, jobs: int,
              names=COMPARED):
    """The twins ``names`` of one input speed from the grid seed ``seed``: (results,
    predictions, kurtosis), each with the columns ``twin``, ``input`` and ``twin_seed``."""
    healthy, test = manifests(data, speed, work)
    written = work / f"twin_{speed}_{seed}.toml"
    ballpass("twin", healthy, "--rpm", *SPEEDS, "--out", written, "--seed", seed)
    out = []
    for k, name in enumerate(names):
        grid = written.with_name(f"twin_{speed}_{seed}_{k}.toml")
        grid.write_text(variant(written.read_text(), TWINS[name]))
        (work / f"{speed}_{seed}_{k}").mkdir()
        parts = one_twin(grid, test, work / f"{speed}_{seed}_{k}", jobs)
        for part in parts:
            part.insert(0, "twin_seed", seed)
            part.insert(0, "input", f"Normal_{speed}")
            part.insert(0, "twin", name)
        out.append(parts)
    return [pd.concat(p) for p in zip(*out, strict=True)]


def real_kurtosis(test: Path) -> pd.DataFrame:
    """:func:`signal_stats` of the rig's one-second fault segments (a test manifest's)."""
    from ballpass.datasets import load_manifest

    X, meta = load_manifest(test, segment_s=1.0)[:2]
    return signal_stats(X, meta["label"])


def figure(predictions: pd.DataFrame, path: Path) -> None:
    """Confusion matrices of the recommended pipeline: a row per twin, a column per input."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rec = predictions[predictions["model"] == "recommended"]   # its first training seed
    rec = rec[rec["twin"].isin(COMPARED)]   # each passage shape and the default
    twins, inputs = list(dict.fromkeys(rec["twin"])), list(dict.fromkeys(rec["input"]))
    fig, axes = plt.subplots(len(twins), len(inputs), figsize=(4 * len(inputs),
                                                               3.3 * len(twins)),
                             squeeze=False)
    truth = ["healthy", "outer", "inner"]
    for row, twin_name in zip(axes, twins, strict=True):
        for ax, name in zip(row, inputs, strict=True):
            part = rec[(rec["twin"] == twin_name) & (rec["input"] == name)]
            counts = pd.crosstab(part["y_true"], part["y_pred"]).reindex(
                index=truth, columns=list(CLASSES), fill_value=0)
            share = counts.div(counts.sum(axis=1), axis=0).to_numpy()
            ax.imshow(share, vmin=0, vmax=1, cmap="Blues")
            for i in range(share.shape[0]):
                for j in range(share.shape[1]):
                    ax.text(j, i, f"{counts.iat[i, j]}", ha="center", va="center",
                            color="white" if share[i, j] > 0.5 else "black")
            ax.set_xticks(range(len(CLASSES)), CLASSES)
            ax.set_yticks(range(len(truth)), truth)
            ax.set_xlabel("predicted")
            ax.set_title(f"{twin_name}, twin of {name}", fontsize=10)
        row[0].set_ylabel("true (HIT-SM segments)")
    fig.suptitle("HIT-SM rig, recommended pipeline trained on the twin only "
                 "(segments of all twin seeds), for each passage shape and the default")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def markdown(table: pd.DataFrame) -> str:
    """The table as a Markdown pipe table (numbers to 3 digits, times to whole s)."""
    def cell(name, v):
        if isinstance(v, float):
            if v != v:   # NaN: no such value (the rig has no ball faults)
                return "-"
            if name.endswith(("_s", "_s_max")):
                return f"{v:.0f}"
            if name.endswith("_hz"):
                return f"{v:.0f}"
            return f"{v:.1f}" if name.startswith("kurtosis") else f"{v:.3f}"
        return str(v)
    rows = ["| " + " | ".join(table.columns) + " |", "|" + "---|" * len(table.columns)]
    rows += ["| " + " | ".join(cell(k, v) for k, v in row.items()) + " |"
             for _, row in table.iterrows()]
    return "\n".join(rows)


def kurtosis_table(twins: pd.DataFrame, real: pd.DataFrame) -> pd.DataFrame:
    """Per source and class: median and 10-90 % range of the fault rows' kurtosis, the
    Kolmogorov-Smirnov distance of their log-kurtosis from the rig's fault seconds of the
    class (0: the same distribution; NaN for a class the rig lacks), and the median of
    their spectral median frequency, Hz."""
    both = pd.concat([twins.assign(source="twin: " + twins["twin"]),
                      real.assign(source="HIT-SM fault seconds")])
    g = both.groupby(["source", "label"], sort=False)
    q = g["kurtosis"].quantile([0.1, 0.5, 0.9]).unstack()
    q = q.set_axis(["kurtosis_p10", "kurtosis_median", "kurtosis_p90"], axis=1)
    rig = {label: np.log(part["kurtosis"]) for label, part in real.groupby("label")}
    q["ks_log_kurtosis"] = [
        scipy.stats.ks_2samp(np.log(part["kurtosis"]), rig[label]).statistic
        if label in rig else np.nan for (_, label), part in g]
    q["median_hz"] = g["median_hz"].median()
    return q.reset_index()


COLUMNS = ["twin", "input", "model", "twin_seed", "n_test", "recall_healthy",
           "recall_outer", "recall_inner", "balanced_accuracy_3class", "min", "max",
           "generate_s", "benchmark_s"]
RECALLS = ["recall_healthy", "recall_outer", "recall_inner"]


def summary(table: pd.DataFrame) -> pd.DataFrame:
    """Per twin, input and model: recalls and balanced accuracy averaged over the twin
    seeds, the balanced accuracy's range over them, and the longest wall times."""
    g = table.groupby(["twin", "input", "model"], sort=False)
    out = g[RECALLS + ["balanced_accuracy_3class"]].mean()
    out["balanced_twin_seed_min"] = g["balanced_accuracy_3class"].min()
    out["balanced_twin_seed_max"] = g["balanced_accuracy_3class"].max()
    spread = table["balanced_3class_seed_max"] - table["balanced_3class_seed_min"]
    out["training_seed_spread_max"] = spread.groupby(
        [table["twin"], table["input"], table["model"]], sort=False).max()
    out["generate_s_max"], out["benchmark_s_max"] = g["generate_s"].max(), g["benchmark_s"].max()
    return out.reset_index()


INTRO = (
    "Input: one healthy recording (5.12 s at one speed). Test: every other recording of the "
    "rig, one-second segments (inner and outer faults of 2/5/8 degree arcs at 600/900/1200 "
    "rpm, healthy at the two other speeds). Goal: three-class balanced accuracy >= 0.9, every "
    "class recall >= 0.8. Three twins of each input, side by side in one run from the same "
    "draws: `point impacts` (one point impact per defect passage, `impact_edges = [0]`), "
    "`Hertzian edges` (`[1]`: the load leaves over the entry edge and comes back over the "
    "exit edge, w / v apart) and `both, drawn per row` (the default, "
    "`{ choice = [0, 1] }`: the two bracket a real passage); `--twins` adds others. Each twin "
    "is drawn from three grid seeds (`ballpass twin --seed`): recalls and balanced accuracy "
    "are their means, `balanced_twin_seed_min`/`_max` the balanced accuracy's range over "
    "them, `training_seed_spread_max` the largest range over five training seeds of one twin. "
    "`generate_s_max`, `benchmark_s_max`: longest wall time of `ballpass generate --jobs 2` "
    "and `ballpass benchmark --real` (both models) on a 2-core machine shared with other "
    "work. Produced by `benchmarks/twin_hit.py`; every run in `results/twin_hit.csv`.")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--data", type=Path, required=True, help="folder of the HIT-SM .mat files")
    parser.add_argument("--out", type=Path, default=DOCS,
                        help="folder of the page (its table and figure go in OUT/results)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--speeds", type=int, nargs="+", default=list(SPEEDS))
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2],
                        help="grid seeds of the twins (ballpass twin --seed)")
    parser.add_argument("--twins", nargs="+", choices=list(TWINS), default=list(COMPARED),
                        help="the variants of the twin to compare (default: point impacts, "
                             "the Hertzian edges and both drawn per row)")
    parser.add_argument("--page-only", action="store_true",
                        help="rebuild the page from the tables of an earlier run")
    args = parser.parse_args()
    if args.page_only:
        page(args.out)
        return
    results, predictions, kurt = [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for speed in args.speeds:
            for seed in args.seeds:
                r, p, k = one_speed(args.data, speed, seed, Path(tmp), args.jobs, args.twins)
                results.append(r)
                predictions.append(p)
                kurt.append(k)
        real = real_kurtosis(Path(tmp) / f"test_{args.speeds[0]}.csv")
    table = pd.concat(results)[COLUMNS].rename(
        columns={"min": "balanced_3class_seed_min", "max": "balanced_3class_seed_max"})
    table = table.sort_values(["input", "model", "twin"], key=lambda c: c.map(
        {f"Normal_{v}": i for i, v in enumerate(SPEEDS)}) if c.name == "input" else c,
        kind="stable")
    kurt_table = kurtosis_table(pd.concat(kurt), real)
    results_dir = results_in(args.out)
    table.round(3).to_csv(results_dir / "twin_hit.csv", index=False)
    kurt_table.round({"kurtosis_p10": 1, "kurtosis_median": 1, "kurtosis_p90": 1,
                      "ks_log_kurtosis": 3, "median_hz": 0}).to_csv(
        results_dir / "twin_hit_kurtosis.csv", index=False)
    figure(pd.concat(predictions), results_dir / "twin_hit.png")
    page(args.out)


def page(out: Path) -> None:
    """Write the page from the tables in ``out/results`` (``--page-only`` rebuilds it
    alone)."""
    table = pd.read_csv(results_in(out) / "twin_hit.csv")
    kurt_table = pd.read_csv(results_in(out) / "twin_hit_kurtosis.csv")
    write_page(out / "twin_hit.md", [
        "# A twin of the HIT-SM rig from one healthy recording", "", INTRO, "",
        markdown(summary(table)), "",
        "Impulsiveness: kurtosis of the twins' one-second fault rows (all three inputs) "
        "and of the rig's fault seconds, 10th percentile, median, 90th percentile; "
        "`ks_log_kurtosis`, the Kolmogorov-Smirnov distance between the log-kurtosis of a "
        "twin's rows and of the rig's seconds of the class (0: one distribution, 1: no "
        "overlap); `median_hz`, the median over rows of the frequency below which half "
        "a row's power lies (Welch, 1024 samples).", "",
        markdown(kurt_table), "", "![confusion](results/twin_hit.png)"])
    print(summary(table).round(3).to_string(index=False))
    print(kurt_table.to_string(index=False))


if __name__ == "__main__":
    main()
