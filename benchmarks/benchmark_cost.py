"""What ``ballpass benchmark`` costs against generating its dataset, and what fewer trees cost.

Two measurements:

* **cost**: ``--runs`` times, interleaved so that both see the same machine load,
  ``ballpass generate GRID --jobs 2`` into a fresh folder, then ``ballpass benchmark``
  with its defaults on that dataset, each a subprocess timed by the wall clock. GRID is
  the shipped CWRU-like grid (``cwru_like_6205_12k``: 104 one-second rows) at 48 kHz.
  The ratio is taken per pair; the page gives its median and range.
* **trees**: the random forest with 100 and with 300 trees on the same folds and the
  same per-row features (one checkpoint folder, the pairs refitted), on the 48 kHz
  dataset and on a small drawn grid (the shipped ``sim2real_cwru`` with ``draws = 20``):
  balanced accuracy pooled over the folds, and its median and range over the folds.

Run::

    PYTHONPATH=. nice -n 10 python benchmarks/benchmark_cost.py   # ~15 min on 2 busy cores

Writes ``docs/benchmark_cost.md``, ``docs/results/benchmark_cost.csv``,
``docs/results/benchmark_trees.csv`` and ``docs/results/benchmark_cost.png``.
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
from _paths import DOCS, ROOT, results_in
from sklearn.metrics import balanced_accuracy_score

from ballpass.datasets import example_grid, generate, load
from ballpass.diagnose import pipelines, run_benchmark
from ballpass.diagnose.report import markdown_table
from ballpass.signalio import atomic_write


def grid_file(name: str, folder: Path, tag: str = "", **settings) -> Path:
    """A shipped grid with some settings changed (``[dataset]`` keys are added where
    missing), as a TOML file; ``noise_rms`` replaces the grid's ``snr_db``."""
    text = Path(example_grid(name)).read_text()
    if "noise_rms" in settings:
        text = re.sub(r"(?m)^snr_db = .*$", f"noise_rms = {settings.pop('noise_rms')}", text)
    for key, value in settings.items():  # the shipped grids set each key once, at a line start
        line = f"{key} = {value}"
        text, found = re.subn(rf"(?m)^{key} = .*$", line, text)
        if not found:
            text = text.replace("[dataset]\n", f"[dataset]\n{line}\n", 1)
    path = folder / f"{name}{tag}.toml"
    path.write_text(text)
    return path


def wall(args: list[str]) -> float:
    """Seconds a ``python -m ballpass ...`` subprocess takes (run from the repository)."""
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "ballpass", *args, "-q"], cwd=ROOT, check=True,
                   stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def cost(grids: dict, folder: Path, runs: int) -> pd.DataFrame:
    """Generation and benchmark wall times, run by run, the grids interleaved."""
    rows = []
    for k in range(runs):
        for model, grid in grids.items():
            data, report = folder / f"ds_{model}{k}", folder / f"report_{model}{k}"
            gen = wall(["generate", str(grid), "--out", str(data), "--jobs", "2"])
            bench = wall(["benchmark", str(data), "--out", str(report)])
            rows.append({"model": model, "run": k, "generate_s": gen, "benchmark_s": bench,
                         "ratio": bench / gen, "rows": len(load(data, columns=["label"])[1])})
            print(f"{model} run {k}: generate {gen:.1f} s, benchmark {bench:.1f} s, "
                  f"ratio {bench / gen:.1f}", flush=True)
    return pd.DataFrame(rows)


def per_fold(pred: pd.DataFrame) -> pd.Series:
    return pred.groupby(["split", "fold"]).apply(
        lambda p: balanced_accuracy_score(p["y_true"], p["y_pred"]), include_groups=False)


def trees(datasets: dict, folder: Path) -> pd.DataFrame:
    rows = []
    for name, path in datasets.items():
        X, meta = load(path)
        checkpoint = folder / f"ckpt_{name}"
        for n in (300, 100):
            for old in checkpoint.glob("pairs/*.parquet"):  # refit, keep per-row features
                old.unlink()
            pipelines._names.FOREST_TREES = n
            result = run_benchmark(X, meta, models=["random_forest"], checkpoint=checkpoint,
                                   drawn=set(meta.columns) & {"rpm", "radial_load_n",
                                                              "fault_width_mm"}
                                   if "draw" in meta else None)
            folds = per_fold(result.predictions)
            for r in result.table.itertuples():
                f = folds.loc[r.split]
                rows.append({"dataset": name, "split": r.split, "trees": n, "folds": r.folds,
                             "balanced_accuracy": r.balanced_accuracy,
                             "fold_median": float(f.median()), "fold_min": float(f.min()),
                             "fold_max": float(f.max())})
            print(pd.DataFrame(rows).tail(len(result.table)).round(3).to_string(), flush=True)
    pipelines._names.FOREST_TREES = 100
    return pd.DataFrame(rows)


def figure(times: pd.DataFrame, forest: pd.DataFrame, path: Path) -> None:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 4))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.3, top=0.9, wspace=0.3)
    ax, bx = fig.subplots(1, 2, width_ratios=[1, 2.2])
    x = np.arange(len(times))
    ax.bar(x - 0.2, times["generate_s"], 0.4, label="generate (--jobs 2)")
    ax.bar(x + 0.2, times["benchmark_s"], 0.4, label="benchmark (defaults)")
    for k, r in enumerate(times.itertuples()):
        ax.text(k + 0.2, r.benchmark_s, f"{r.ratio:.1f}x", ha="center", va="bottom",
                fontsize=8)
    ax.set_ylim(0, 1.45 * times["benchmark_s"].max())  # room for the ratios and legend
    ax.set_xticks(x, [f"{r.model}\nrun {r.run}" for r in times.itertuples()], fontsize=7)
    ax.set_ylabel("wall time (s)")
    ax.set_title("104 rows of 1 s at 48 kHz", fontsize=9)
    ax.legend(fontsize=8, loc="upper left")
    cases = forest[["dataset", "split"]].drop_duplicates().reset_index(drop=True)
    for n, dx, colour in ((300, -0.2, "C2"), (100, 0.2, "C3")):
        part = cases.merge(forest[forest["trees"] == n], on=["dataset", "split"])
        bx.errorbar(np.arange(len(part)) + dx, part["balanced_accuracy"],
                    yerr=[part["balanced_accuracy"] - part["fold_min"],
                          part["fold_max"] - part["balanced_accuracy"]],
                    fmt="o", color=colour, capsize=3, label=f"{n} trees")
    bx.set_xticks(np.arange(len(cases)), [f"{d}\n{s}" for d, s in
                                          zip(cases["dataset"], cases["split"], strict=True)],
                  rotation=45, ha="right", fontsize=7)
    bx.set_ylabel("balanced accuracy (bar: fold range)")
    bx.set_title("random forest: pooled over folds, same folds and features", fontsize=9)
    bx.legend(fontsize=8)
    atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"))


PAGE = """# What `ballpass benchmark` costs against generating its dataset

Generated by `benchmarks/benchmark_cost.py` on a 2-core machine shared with other work:
wall times, so compare the ratios, each taken within one pair run side by side.

## Benchmark against generation

`ballpass generate` (`--jobs 2`) of the CWRU-like grid at 48 kHz ({rows} rows of 1 s), then
`ballpass benchmark` with its defaults on it, {runs} times interleaved; the grid as
shipped (model `auto`: the Sawalhi & Randall model), and with the cheapest generator
(the `impulse` model; noise 0.5 m/s² RMS instead of the SNR it cannot take).

{cost}

Ratio benchmark / generation, median (range) over the runs: {ratios}.

![generation and benchmark times; forest with 100 and 300 trees](results/benchmark_cost.png)

## Trees of the random forest

The random forest with 300 and with 100 trees, on the same folds and per-row features;
balanced accuracy pooled over the folds, and its median (range) over the folds.

{trees}
"""


def measure(runs: int, skip_trees: bool, results: Path) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Both measurements, their tables written as they finish."""
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        grids = {"sr5": grid_file("cwru_like_6205_12k", folder, fs=48_000),
                 # the cheapest generator: the benchmark's share is largest
                 "impulse": grid_file("cwru_like_6205_12k", folder, "_impulse", fs=48_000,
                                      model='"impulse"', noise_rms=[0.5])}
        times = cost(grids, folder, runs)
        atomic_write(results / "benchmark_cost.csv", lambda t: times.to_csv(t, index=False))
        if skip_trees:
            return times, pd.read_csv(results / "benchmark_trees.csv")
        drawn = grid_file("sim2real_cwru", folder, draws=20)
        generate(drawn, folder / "drawn", n_jobs=2, progress=False)
        forest = trees({"CWRU-like 48 kHz": folder / "ds_sr50",
                        "sim2real_cwru, 20 draws": folder / "drawn"}, folder)
        atomic_write(results / "benchmark_trees.csv", lambda t: forest.to_csv(t, index=False))
    return times, forest


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=DOCS)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--skip-trees", action="store_true",
                        help="reuse the trees table of a previous run")
    parser.add_argument("--tables-only", action="store_true",
                        help="write the page and figure from the tables of a previous run")
    args = parser.parse_args()
    results = results_in(args.out)
    if args.tables_only:
        times = pd.read_csv(results / "benchmark_cost.csv")
        forest = pd.read_csv(results / "benchmark_trees.csv")
    else:
        times, forest = measure(args.runs, args.skip_trees, results)
    figure(times, forest, results / "benchmark_cost.png")
    shown = forest.assign(**{"fold median (range)": [
        f"{r.fold_median:.3f} ({r.fold_min:.3f}-{r.fold_max:.3f})"
        for r in forest.itertuples()]})
    trees_md = markdown_table(shown[["dataset", "split", "trees", "folds", "balanced_accuracy",
                                     "fold median (range)"]])
    ratios = "; ".join(f"`{m}` **{r.median():.1f}x** ({r.min():.1f}-{r.max():.1f}x)"
                       for m, r in times.groupby("model", sort=False)["ratio"])
    page = PAGE.format(rows=int(times["rows"].iloc[0]), runs=times["run"].nunique(),
                       cost=markdown_table(times), ratios=ratios, trees=trees_md)
    atomic_write(args.out / "benchmark_cost.md", lambda t: t.write_text(page))
    print(page)


if __name__ == "__main__":
    main()
