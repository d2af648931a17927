"""Which learned pipeline to recommend for a twin: every pipeline on the HIT-SM twin.

The twin of the HIT-SM self-built rig (as in ``twin_hit.py``: each speed's healthy
recording in turn the twin's only input, the rig's other recordings the test, one-second
segments, three classes) is benchmarked with all five classifiers on each unitless
feature set (``dimensionless``, ``evidence``, ``combined``), three twins (grid seeds 0, 1,
2) per input, two training seeds each. The rule, fixed before any score was seen, is the
one of the simulation-to-real choice: the highest mean three-class balanced accuracy
over the inputs and twins. Leave-one-input-out says whether the choice hinges on one
recording: each input left out in turn, the pipeline chosen on the other two, and its
score on the one left out. The choice is
:data:`ballpass.diagnose._names.RECOMMENDED_TWIN`.

Run::

    PYTHONPATH=. python benchmarks/twin_pipelines.py --data ../shared/data/hit  # ~25 min
    PYTHONPATH=. python benchmarks/twin_pipelines.py --summary-only   # from the CSV

Writes ``twin_pipelines.csv`` (one row per feature set, classifier, input and twin: the
benchmark's sim2real scores), ``twin_pipelines.md`` (the table and the choice) and
``twin_pipelines.png`` to ``docs/results``.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import pandas as pd
from _paths import RESULTS_DIR
from _report import table, write_csv, write_page
from twin_hit import SPEEDS, ballpass, manifests

FEATURE_SETS = ("dimensionless", "evidence", "combined")
CLASSIFIERS = "random_forest,gradient_boosting,svm,logistic,knn"
TWIN_SEEDS = (0, 1, 2)
SCORE = "balanced_accuracy_3class"


def run(data: Path, work: Path, jobs: int) -> pd.DataFrame:
    """Every pipeline on every twin: the benchmark's sim2real rows, with ``features``,
    ``input`` (rpm of the twin's healthy recording) and ``twin_seed``."""
    rows = []
    for speed in SPEEDS:
        for seed in TWIN_SEEDS:
            folder = work / f"{speed}_{seed}"
            folder.mkdir(parents=True)
            healthy, test = manifests(data, speed, folder)
            grid = folder / "twin.toml"
            ballpass("twin", healthy, "--rpm", *SPEEDS, "--out", grid, "--seed", seed)
            ballpass("generate", grid, "--out", folder / "ds", "--jobs", jobs, "--quiet")
            for features in FEATURE_SETS:
                report = folder / f"rep_{features}"
                ballpass("benchmark", folder / "ds", "--real", test, "--splits", "sim2real",
                         "--models", CLASSIFIERS, "--features", features,
                         "--train-seeds", 2, "--out", report, "--quiet")
                part = pd.read_csv(report / "results.csv")
                part["features"], part["input"], part["twin_seed"] = features, speed, seed
                rows.append(part)
    return pd.concat(rows, ignore_index=True)


def summary(runs: pd.DataFrame) -> tuple[pd.DataFrame, pd.DataFrame]:
    """(mean score per pipeline and input, with a ``mean`` column, best first;
    leave-one-input-out: per input left out, the pipeline the other inputs choose and
    its score on the one left out)."""
    per_input = runs.groupby(["features", "model", "input"])[SCORE].mean().unstack("input")
    inputs = list(per_input.columns)
    per_input["mean"] = per_input[inputs].mean(axis=1)
    per_input = per_input.sort_values("mean", ascending=False)
    held = []
    for out in inputs:
        chosen = per_input[[i for i in inputs if i != out]].mean(axis=1).idxmax()
        held.append({"left_out": out, "features": chosen[0], "model": chosen[1],
                     SCORE: per_input.loc[chosen, out]})
    return per_input, pd.DataFrame(held)


def figure(per_input: pd.DataFrame, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    labels = [f"{m} / {f}" for f, m in per_input.index]
    ax.barh(labels[::-1], per_input["mean"].to_numpy()[::-1], color="tab:blue")
    ax.axvline(0.9, color="k", ls="--", lw=1, label="goal 0.9")
    ax.set_xlabel("three-class balanced accuracy, mean over inputs and twins")
    ax.set_xlim(0.3, 1.0)
    ax.legend(loc="lower right")
    ax.set_title("Pipelines trained on the HIT-SM twin, tested on the rig")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def page(runs: pd.DataFrame, results: Path) -> None:
    per_input, held = summary(runs)
    inputs = [c for c in per_input.columns if c != "mean"]
    best = per_input.index[0]
    lines = [
        "# Every learned pipeline on the HIT-SM twin", "",
        "Every learned pipeline trained on a twin of the HIT-SM rig (`benchmarks/"
        "twin_pipelines.py`): three-class balanced accuracy on the rig's other recordings, "
        f"one-second segments, mean over {runs['twin_seed'].nunique()} twins per input "
        "(each the mean of two training seeds). Best first.", "",
        *table(["classifier", "features", *[f"input {i} rpm" for i in inputs], "mean"],
               [(m, f, *[f"{per_input.loc[(f, m), i]:.3f}" for i in inputs],
                 f"{per_input.loc[(f, m), 'mean']:.3f}") for f, m in per_input.index]),
        "", f"Chosen (highest mean): {best[1]} on `{best[0]}`.", "",
        "Leave one input out (the pipeline chosen on the other two inputs, scored on the "
        "one left out):", "",
        *table(["left out (rpm)", "chosen", f"{SCORE} on it"],
               [(r.left_out, f"{r.model} / {r.features}", f"{getattr(r, SCORE):.3f}")
                for r in held.itertuples()]),
    ]
    write_page(results / "twin_pipelines.md", lines)
    figure(per_input, results / "twin_pipelines.png")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, help="folder of the HIT-SM .mat files")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--summary-only", action="store_true",
                        help="rebuild the table and figure from twin_pipelines.csv")
    args = parser.parse_args()
    csv = RESULTS_DIR / "twin_pipelines.csv"
    if not args.summary_only:
        if args.data is None:
            parser.error("--data is required unless --summary-only")
        with tempfile.TemporaryDirectory() as work:
            write_csv(run(args.data, Path(work), args.jobs), csv)
    page(pd.read_csv(csv), RESULTS_DIR)


if __name__ == "__main__":
    main()
