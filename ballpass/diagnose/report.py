"""Benchmark reports: a Markdown and CSV table and one confusion-matrix figure per split.

Figures are built with :class:`matplotlib.figure.Figure` (no pyplot, no global state),
so reports can be written from scripts, servers and loops.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ._names import CLASSIFIERS, FEATURE_SETS, LABELS, MODELS, RECOMMENDED, SPLITS
from .benchmark import MIN_GROUPS_PER_CLASS, BenchmarkResult

__all__ = ["plot_confusion", "markdown_table", "write_report"]

_COLUMNS = ["split", "model", "folds", "n_test", "accuracy", "accuracy_fold_min",
            "accuracy_fold_max", "balanced_accuracy", "macro_f1",
            *(f"recall_{c}" for c in LABELS)]


def plot_confusion(matrix, *, labels=LABELS, title: str | None = None, ax=None):
    """Draw a confusion matrix: colour = recall (row-normalised), text = counts.

    Parameters
    ----------
    matrix : array_like of int, shape (n_labels, n_labels)
        Counts; rows true, columns predicted.
    labels : sequence of str, optional
        Class names in the order of the rows (default :data:`~ballpass.diagnose.LABELS`).
    title : str, optional
        Axes title.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on; a new figure (without pyplot) when omitted.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.diagnose import plot_confusion
    >>> counts = np.array([[9, 1, 0, 0], [0, 8, 2, 0], [0, 0, 10, 0], [1, 0, 0, 9]])
    >>> ax = plot_confusion(counts, title="held-out runs")
    >>> ax.get_title(), [t.get_text() for t in ax.get_xticklabels()]
    ('held-out runs', ['healthy', 'outer', 'inner', 'ball'])
    """
    if ax is None:
        from matplotlib.figure import Figure

        ax = Figure(figsize=(3.2, 3.0)).add_subplot()
    m = np.asarray(matrix, dtype=float)
    totals = m.sum(axis=1, keepdims=True)
    recall = np.divide(m, totals, out=np.zeros_like(m), where=totals > 0)
    ax.imshow(recall, vmin=0.0, vmax=1.0, cmap="Blues")
    for i, j in np.ndindex(m.shape):
        ax.text(j, i, f"{int(m[i, j])}", ha="center", va="center", fontsize=8,
                color="white" if recall[i, j] > 0.6 else "black")
    ticks = np.arange(len(labels))
    ax.set_xticks(ticks, labels, rotation=45, ha="right", fontsize=8)
    ax.set_yticks(ticks, labels, fontsize=8)
    ax.set_xlabel("predicted")
    ax.set_ylabel("true")
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def _cell(value) -> str:
    if isinstance(value, float | np.floating):
        return "–" if math.isnan(value) else f"{value:.3f}"
    return str(value)


def markdown_table(frame) -> str:
    """A pandas DataFrame as a GitHub-flavoured Markdown table (floats to 3 decimals)."""
    head = "| " + " | ".join(map(str, frame.columns)) + " |"
    rule = "|" + "|".join("---" for _ in frame.columns) + "|"
    body = ["| " + " | ".join(_cell(v) for v in row) + " |"
            for row in frame.itertuples(index=False)]
    return "\n".join([head, rule, *body])


def _figure(result: BenchmarkResult, split: str, path: Path) -> None:
    from matplotlib.figure import Figure

    models = [m for (s, m) in result.confusion if s == split]
    cols = min(3, len(models))
    rows = -(-len(models) // cols)
    # Fixed margins, no layout engine: a constrained layout re-measured every text of
    # the figure on each draw and cost most of the report's time. In inches: room
    # for the y labels on the left, the rotated x labels below, the title above.
    width, height = 3.3 * cols, 3.2 * rows + 0.3
    fig = Figure(figsize=(width, height))
    fig.subplots_adjust(left=0.85 / width,
                        right=1 - 0.1 / width, bottom=0.85 / height, top=1 - 0.55 / height,
                        wspace=0.45, hspace=0.55)
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for ax, model in zip(axes, models, strict=False):
        plot_confusion(result.confusion[split, model], title=model, ax=ax)
    for ax in axes[len(models):]:
        ax.set_visible(False)
    tag = " (optimistic)" if split == "random" else ""
    fig.suptitle(f"{split}{tag}: {SPLITS[split]}", fontsize=9)
    fig.savefig(path, dpi=110)


def _spread(values) -> str:
    """Median and range of a score over training seeds: ``0.85 (0.80-0.90)``."""
    values = np.asarray(values, dtype=float)
    if np.isnan(values).all():
        return "–"
    lo, mid, hi = np.nanmin(values), np.nanmedian(values), np.nanmax(values)
    return f"{mid:.3f}" if lo == hi else f"{mid:.3f} ({lo:.3f}–{hi:.3f})"


def sim2real_table(result: BenchmarkResult):
    """The simulation-to-real scores per model: three classes (normal, outer, inner; a
    "ball" answer on them counts as an error) and four, median and range over the
    training seeds (:attr:`BenchmarkResult.spread`), and each class's recall.

    Returns
    -------
    pandas.DataFrame
        One row per model; empty without a ``sim2real`` split.
    """
    import pandas as pd

    spread = result.spread
    if not len(spread):
        return pd.DataFrame()
    rows = []
    for model, part in spread[spread["split"] == "sim2real"].groupby("model", sort=False):
        rows.append({
            "model": model,
            "seeds": len(part),
            "3-class accuracy": _spread(part["accuracy_3class"]),
            "3-class balanced": _spread(part["balanced_accuracy_3class"]),
            **{f"recall {c}": _spread(part[f"recall_{c}"]) for c in LABELS},
            "4-class balanced": _spread(part["balanced_accuracy"]),
        })
    return pd.DataFrame(rows)


def pipeline_description(model: str, features: str, recommended=RECOMMENDED) -> str:
    """How a benchmark model is built, step by step, in words (``"recommended"``: the
    pipeline ``recommended``, (classifier, feature set), whatever ``features`` is).

    Examples
    --------
    >>> from ballpass.diagnose.report import pipeline_description
    >>> pipeline_description("knn", "bands")         # doctest: +ELLIPSIS
    '`bands` features (fault-band SES levels only (dB)) -> median imputation -> ...'
    """
    if model == "envelope":
        return MODELS["envelope"]
    name, feature_set = tuple(recommended) if model == "recommended" else (model, features)
    return (f"`{feature_set}` features ({FEATURE_SETS[feature_set]}) -> median imputation "
            f"-> standard scaling -> {CLASSIFIERS[name]}")


def write_report(result: BenchmarkResult, out_dir, *, title: str = "Classifier benchmark"
                 ) -> dict[str, Path]:
    """Write a benchmark as ``results.md``, ``results.csv``, ``predictions.csv`` and PNGs.

    Parameters
    ----------
    result : BenchmarkResult
        From :func:`ballpass.diagnose.run_benchmark`.
    out_dir : str or os.PathLike
        Folder (created).
    title : str, optional
        Heading of the Markdown report.

    Returns
    -------
    dict of str to pathlib.Path
        ``"markdown"``, ``"csv"``, ``"predictions"`` and ``"confusion_<split>"`` per split.

    Examples
    --------
    Six simulated runs (three faults, three healthy), scored with runs held out:

    >>> import tempfile
    >>> import numpy as np, pandas as pd
    >>> import ballpass as bp
    >>> from ballpass.diagnose import run_benchmark, write_report
    >>> faults = ["outer", "inner", "outer", "inner", None, None]
    >>> scenes = [bp.Scene("6205", rpm=1797, fs=12_000, duration_s=1.0, resonance_hz=3_000,
    ...                    fault=bp.Fault(f) if f else None, noise_rms=0.5, seed=i)
    ...           for i, f in enumerate(faults)]
    >>> X = np.stack([bp.simulate(s, model="impulse").accel for s in scenes])
    >>> meta = pd.DataFrame({"label": [f or "healthy" for f in faults], "group": range(6),
    ...                      "rpm": 1797.0, "bearing": "6205", "fs": 12_000.0})
    >>> result = run_benchmark(X, meta, splits=["run"], models=["envelope"], n_splits=2)
    >>> paths = write_report(result, tempfile.mkdtemp())
    >>> sorted(paths), paths["markdown"].name
    (['confusion_run', 'csv', 'markdown', 'predictions'], 'results.md')
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = {"markdown": out / "results.md", "csv": out / "results.csv",
             "predictions": out / "predictions.csv"}
    table = result.table
    table.to_csv(paths["csv"], index=False)
    result.predictions.to_csv(paths["predictions"], index=False)
    if len(result.spread):
        paths["spread"] = out / "sim2real_seeds.csv"
        result.spread.to_csv(paths["spread"], index=False)

    info = result.info
    lines = [f"# {title}", ""]
    if info.get("interrupted"):
        lines += [f"**Partial report: interrupted** after {info['pairs_done']} of "
                  f"{info['pairs_planned']} split/model pairs; the missing ones are not "
                  "scored. The same command again resumes where it stopped.", ""]
    lines.append(
        f"{info['rows']} rows in {info['groups']} groups (runs or recordings), bearing "
        f"{info['bearing']}, fs {info['fs']:g} Hz, {info['samples_per_row']} samples per row; "
        f"labels {info['labels']}. Learned models use the `{info['features']}` feature set."
    )
    if "real_rows" in info:
        lines.append(f"Real recordings: {info['real_rows']} rows in {info['real_groups']} "
                     "groups (test set of `sim2real` only).")
    if info.get("few_groups"):
        lines += ["", f"**Warning:** classes with fewer than {MIN_GROUPS_PER_CLASS} groups "
                  f"(runs or recordings): {info['few_groups']}. Their recall rests on a "
                  "handful of cases; add runs (`repeats`) before trusting it."]
    lines += ["", "Scores pool the out-of-fold predictions of all folds (`accuracy_fold_min` "
              "and `accuracy_fold_max`: the spread over the folds); macro F1 averages "
              "over the classes present in the test rows; recall is NaN (–) for an absent "
              "class. Groups never straddle train and test, except in the `random` split, "
              "which is **optimistic** (segments of one run on both sides) and shown only "
              "for comparison.", ""]
    for split in dict.fromkeys(table["split"]) if len(table) else []:
        part = table[table["split"] == split]
        tag = " — OPTIMISTIC, not an estimate of real performance" if split == "random" else ""
        rule = info.get("fold_rules", {}).get(split, SPLITS[split])
        lines += [f"## `{split}`{tag}", "", f"Folds: {rule}.", "",
                  markdown_table(part[_COLUMNS[1:]]), ""]
        if split == "sim2real" and len(result.spread):
            lines += ["Three classes (normal, outer, inner; a \"ball\" answer on them is an "
                      "error) and four; median (range) over "
                      f"{info.get('seeds', 1)} training seeds (the classifiers' random "
                      "state; a new simulated dataset moves scores more). Every prediction "
                      "of the first seed is in `predictions.csv`, every seed's scores in "
                      "`sim2real_seeds.csv`.", "",
                      markdown_table(sim2real_table(result)), ""]
        png = out / f"confusion_{split}.png"
        _figure(result, split, png)
        paths[f"confusion_{split}"] = png
        lines += [f"![confusion matrices, {split}]({png.name})", ""]
    if result.skipped:
        lines += ["## Splits not formed", ""]
        lines += [f"* `{s}`: {why}" for s, why in result.skipped.items()]
        lines.append("")
    chosen = info.get("recommended", RECOMMENDED)
    lines += ["## Models", ""] + [f"* `{m}`: {pipeline_description(m, info['features'], chosen)}"
                                  for m in dict.fromkeys(table.get("model", ()))]
    paths["markdown"].write_text("\n".join(lines) + "\n")
    return paths
