"""A twin of the HIT-SM self-built rig from one healthy recording, tested on the others.

For each input speed (600, 900 and 1200 rpm in turn), the twin's only input is that
speed's healthy recording: ``ballpass twin`` (faults at 600, 900 and 1200 rpm),
``ballpass generate``, then ``ballpass benchmark --real`` on every other recording of
the rig (inner- and outer-race faults of 2, 5 and 8 degree arcs at all three speeds,
healthy at the two other speeds), one-second segments. Nothing is tuned on them: the
twin's ranges are its defaults (:data:`ballpass.datasets.twin.TWIN_DEFAULTS`). The rig
has no ball faults: three-class scores (a "ball" verdict counts as wrong).

Run::

    PYTHONPATH=. python benchmarks/twin_hit.py --data ../shared/data/hit   # ~12 min, 2 cores

Writes ``twin_hit.md``, ``twin_hit.csv`` (one row per input speed and model: recall per
class, three-class balanced accuracy, its range over the training seeds) and
``twin_hit.png`` (confusion matrices of the recommended pipeline) to ``docs/results``
(the page to ``docs``).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd
from _paths import DOCS, results_in

SPEEDS = (600, 900, 1200)
LABELS = {"Normal": "healthy", "IR": "inner", "OR": "outer"}
MODELS = "envelope,recommended"
CLASSES = ("healthy", "outer", "inner", "ball")


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


def one_speed(data: Path, speed: int, work: Path, jobs: int) -> tuple[pd.DataFrame, pd.DataFrame]:
    healthy, test = manifests(data, speed, work)
    grid, ds, report = work / f"twin_{speed}.toml", work / f"ds_{speed}", work / f"rep_{speed}"
    ballpass("twin", healthy, "--rpm", *SPEEDS, "--out", grid)
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
    results.insert(0, "input", f"Normal_{speed}")
    results["generate_s"], results["benchmark_s"] = t1 - t0, t2 - t1
    predictions = pd.read_csv(report / "predictions.csv")
    predictions.insert(0, "input", f"Normal_{speed}")
    return results, predictions


def figure(predictions: pd.DataFrame, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rec = predictions[predictions["model"] == "recommended"]   # its first training seed
    inputs = list(dict.fromkeys(rec["input"]))
    fig, axes = plt.subplots(1, len(inputs), figsize=(4 * len(inputs), 3.6))
    truth = ["healthy", "outer", "inner"]
    for ax, name in zip(np.atleast_1d(axes), inputs, strict=True):
        part = rec[rec["input"] == name]
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
        ax.set_title(f"twin of {name}")
    np.atleast_1d(axes)[0].set_ylabel("true (HIT-SM segments)")
    fig.suptitle("HIT-SM rig, recommended pipeline trained on the twin only")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def markdown(table: pd.DataFrame) -> str:
    """The table as a Markdown pipe table (numbers to 3 digits, times to whole s)."""
    def cell(name, v):
        if isinstance(v, float):
            return f"{v:.0f}" if name.endswith("_s") else f"{v:.3f}"
        return str(v)
    rows = ["| " + " | ".join(table.columns) + " |", "|" + "---|" * len(table.columns)]
    rows += ["| " + " | ".join(cell(k, v) for k, v in row.items()) + " |"
             for _, row in table.iterrows()]
    return "\n".join(rows)


COLUMNS = ["input", "model", "n_test", "recall_healthy", "recall_outer", "recall_inner",
           "balanced_accuracy_3class", "min", "max", "generate_s", "benchmark_s"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--data", type=Path, required=True, help="folder of the HIT-SM .mat files")
    parser.add_argument("--out", type=Path, default=DOCS,
                        help="folder of the page (its table and figure go in OUT/results)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--speeds", type=int, nargs="+", default=list(SPEEDS))
    args = parser.parse_args()
    results, predictions = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for speed in args.speeds:
            r, p = one_speed(args.data, speed, Path(tmp), args.jobs)
            results.append(r)
            predictions.append(p)
    table = pd.concat(results)[COLUMNS].rename(
        columns={"min": "balanced_3class_seed_min", "max": "balanced_3class_seed_max"})
    results_dir = results_in(args.out)
    table.round(3).to_csv(results_dir / "twin_hit.csv", index=False)
    figure(pd.concat(predictions), results_dir / "twin_hit.png")
    lines = ["# A twin of the HIT-SM rig from one healthy recording", "",
             "Input: one healthy recording (5.12 s at one speed). Test: every other recording "
             "of the rig, one-second segments (inner and outer faults of 2/5/8 degree arcs at "
             "600/900/1200 rpm, healthy at the two other speeds). Goal: three-class balanced "
             "accuracy >= 0.9, every class recall >= 0.8. `balanced_3class_seed_min`/`_max`: "
             "range of the balanced accuracy over five training seeds. `generate_s`, "
             "`benchmark_s`: wall time of `ballpass generate --jobs 2` and "
             "`ballpass benchmark --real` (both models) on a 2-core machine shared with "
             "other work. Produced by `benchmarks/twin_hit.py`.", "",
             markdown(table), "", "![confusion](results/twin_hit.png)", ""]
    (args.out / "twin_hit.md").write_text("\n".join(lines))
    print(table.round(3).to_string(index=False))


if __name__ == "__main__":
    main()
