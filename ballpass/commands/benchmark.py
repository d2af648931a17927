"""``ballpass benchmark DATASET --out DIR``: classifier benchmark without leakage."""

from __future__ import annotations

import argparse
from pathlib import Path

EXAMPLE = """\
examples:
  ballpass generate quick --out out/quick --jobs 2
  ballpass benchmark out/quick --out out/quick-bench --models envelope,logistic
  ballpass generate sim2real_cwru --out out/sim2real --jobs 2
  ballpass benchmark out/sim2real --real path/to/cwru --out out/sim2real-bench
  ballpass benchmark out/sim2real --real recordings.csv --out out/rig-bench  # a manifest

Writes DIR/results.md, DIR/results.csv, DIR/predictions.csv and one confusion-matrix PNG
per split. Splits never put rows of one run (or recording) on both sides, except
`random`, which is reported as optimistic.

Finished work is kept in DIR/_checkpoint: Ctrl-C writes the report of what is finished
(marked partial) and exits with 130; the same command again resumes where it stopped."""


def _names(text: str) -> list[str]:
    return [t.strip() for t in text.split(",") if t.strip()]


def add_parser(subparsers) -> None:
    """Register the ``benchmark`` subcommand."""
    from ..diagnose._names import FEATURE_SETS, MODELS, SPLITS
    from .features import add_quiet_argument

    p = subparsers.add_parser(
        "benchmark",
        help="cross-validate the envelope diagnoser and classifier pipelines on a dataset",
        description="Benchmark the physics-based envelope diagnoser and learned pipelines "
                    "(features + random forest, gradient boosting, SVM, kNN, logistic "
                    "regression) on a dataset made by `ballpass generate`, over splits that "
                    "keep runs together: by run, leave one speed / load / fault size out, "
                    "loaded -> unloaded sensor, and simulation -> real recordings (--real: "
                    "per-class recall, balanced accuracy, three and four classes, the spread "
                    "over training seeds, and the pipeline recommended for simulation-to-real "
                    "as model `recommended`).",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("dataset", metavar="DATASET", help="dataset folder (ballpass generate)")
    p.add_argument("--out", metavar="DIR", required=True, help="report folder (created)")
    p.add_argument("--real", metavar="DIR|MANIFEST",
                   help="folder of CWRU or MFPT .mat recordings, or a manifest table of "
                        "labelled recordings of any rig (path, fs, rpm, bearing, label per "
                        "row): adds the sim2real split (train on DATASET, test on them, "
                        "resampled to DATASET's fs and cut into segments as long as "
                        "DATASET's rows)")
    p.add_argument("--channel", default="DE", choices=["DE", "FE", "BA"],
                   help="accelerometer of CWRU recordings for --real (default DE)")
    p.add_argument("--splits", type=_names, metavar="A,B",
                   help=f"comma-separated subset of {','.join(SPLITS)} (default: all the "
                        "data can form)")
    p.add_argument("--models", type=_names, metavar="A,B",
                   help=f"comma-separated subset of {','.join(MODELS)} (default all)")
    p.add_argument("--features", default="dimensionless",
                   choices=list(FEATURE_SETS),
                   help="feature set of the learned pipelines (default dimensionless: no "
                        "feature scales with the sensor gain)")
    p.add_argument("--folds", type=int, default=5, metavar="K",
                   help="folds of the k-fold splits (default 5)")
    p.add_argument("--seed", type=int, default=0, help="shuffling and model seed (default 0)")
    p.add_argument("--train-seeds", type=int, default=5, metavar="N",
                   help="sim2real: train each learned model with N seeds (--seed, --seed + 1, "
                        "...) and report the median and range of its scores (default 5)")
    add_quiet_argument(p)
    p.set_defaults(func=run)


def _check_real_rpm(meta) -> None:
    """Refuse real recordings without a speed, naming the files."""
    missing = sorted(meta.loc[~(meta["rpm"].astype(float) > 0), "group"].unique())
    if missing:
        raise ValueError(f"no shaft speed for {len(missing)} real recording(s) "
                         f"({', '.join(missing[:5])}{', ...' if len(missing) > 5 else ''}): "
                         "name them with their motor load (e.g. 12k_DE_IR028_2.mat) or "
                         "store the speed in the file")


def _not_the_twins_own(real, dataset):
    """The real rows that are not recordings a twin's dataset was built from: those are
    its healthy rows (and the background of its fault rows), so scoring them scores
    memory; says on stderr what was left out. Other datasets: ``real`` unchanged."""
    import sys

    from ..datasets.manifest import read_manifest as read_table
    from ..datasets.store import read_manifest

    machine = (read_manifest(dataset) or {}).get("grid", {}).get("machine")
    if machine is None:
        return real
    try:
        own = {Path(row["path"]).resolve() for row in read_table(machine["manifest"])}
    except (OSError, ValueError):
        return real  # the twin's manifest is gone or changed: nothing to compare with
    Xr, meta = real
    keep = ~meta["file"].map(lambda f: Path(f).resolve() in own).to_numpy()
    if not keep.any():
        raise ValueError("--real: every recording is one the twin was built from "
                         f"({machine['manifest']}); test it on other recordings")
    if not keep.all():
        left = meta.loc[~keep, "group"].unique()
        print(f"ballpass benchmark: left out {len(left)} real recording(s) the twin was "
              f"built from ({', '.join(map(str, left))}): its healthy rows are their "
              "segments, so testing on them would score memory; give healthy recordings "
              "it has not heard", file=sys.stderr)
    return Xr[keep], meta.loc[keep].reset_index(drop=True)


def _same_bearing(real, bearing: str):
    """The real rows about the simulated ``bearing`` (a CWRU fan-end fault file is about
    the 6203 whichever accelerometer heard it); says on stderr what was left out."""
    import sys

    Xr, meta = real
    names = meta["bearing"].astype(str)
    keep = (names == bearing).to_numpy()
    if not keep.any():
        raise ValueError(f"--real: none of the recordings is about the simulated bearing "
                         f"{bearing} (they are about {sorted(names.unique())}); simulate "
                         "that bearing, or give recordings of this one")
    if not keep.all():
        other = meta.loc[~keep]
        print(f"ballpass benchmark: left out {other['group'].nunique()} real recording(s) "
              f"about another bearing ({', '.join(sorted(names[~keep].unique()))}"
              f"; e.g. {other['group'].iloc[0]}): the dataset simulates the {bearing}; "
              "benchmark them against a dataset of their bearing", file=sys.stderr)
    return Xr[keep], meta.loc[keep].reset_index(drop=True)


def _recommended_for(dataset) -> tuple[str, str]:
    """The pipeline reported as model ``recommended``: the one for a twin's dataset (it
    holds the learned paths, ``_machine.json``) or the one for simulation-to-real."""
    from ..datasets.twin import MACHINE_FILE
    from ..diagnose._names import RECOMMENDED, RECOMMENDED_TWIN

    return RECOMMENDED_TWIN if (Path(dataset) / MACHINE_FILE).exists() else RECOMMENDED


def run(args) -> int:
    """Run ``ballpass benchmark``; returns the exit code (130 when interrupted)."""
    import sys

    import pandas as pd

    from .._validation import check_segment
    from ..datasets import load
    from ..datasets.grid import drawn_axes
    from ..datasets.manifest import read_recordings
    from ..datasets.real import segment_records
    from ..datasets.store import read_manifest
    from ..diagnose import run_benchmark, write_report
    from ._output import check_output_path, show_progress

    check_output_path(args.out, option="--out", folder=True)
    if args.real is not None and not Path(args.real).exists():
        raise FileNotFoundError(f"--real: no such file or folder: {args.real}")
    X, meta = load(args.dataset)
    manifest = read_manifest(args.dataset) or {}
    drawn = set(drawn_axes(manifest["grid"])) if "grid" in manifest else set()
    real = None
    if args.real is not None:
        rates = sorted(meta["fs"].unique())
        if len(rates) != 1:
            raise ValueError(f"{args.dataset} mixes sampling rates {rates} Hz; benchmark "
                             "needs one rate")
        fs = float(rates[0])
        found = read_recordings(args.real, channel=args.channel, require_label=True)
        real = _not_the_twins_own(
            segment_records(found, fs, check_segment(X.shape[1] / fs, fs)), args.dataset)
        bearings = sorted(meta["bearing"].astype(str).unique())
        if len(bearings) == 1:
            real = _same_bearing(real, bearings[0])
        _check_real_rpm(real[1])
    result = run_benchmark(X, meta, real=real, splits=args.splits, models=args.models,
                           features=args.features, n_splits=args.folds,
                           random_state=args.seed, seeds=args.train_seeds,
                           progress=show_progress(args),
                           checkpoint=Path(args.out) / "_checkpoint", drawn=drawn,
                           recommended=_recommended_for(args.dataset))
    if result.table.empty and not result.info.get("interrupted", False):
        # every split asked for was skipped: nothing to report
        why = "; ".join(f"{split}: {reason}" for split, reason in result.skipped.items())
        raise ValueError(f"no split could be formed on {args.dataset} ({why}); choose "
                         "others with --splits (run keeps runs together on any dataset)")
    paths = write_report(result, args.out)
    interrupted = result.info.get("interrupted", False)
    if not result.table.empty:
        with pd.option_context("display.width", 140, "display.max_rows", 200):
            print(result.table.drop(columns="optimistic").round(3).to_string(index=False))
    if interrupted:
        # one line, as generate's: ballpass <command>: interrupted; how far it got
        print(f"ballpass benchmark: interrupted; partial report of "
              f"{result.info['pairs_done']} of {result.info['pairs_planned']} split/model "
              f"pairs: {paths['markdown']}; run the same command again to resume",
              file=sys.stderr)
        return 130
    print(f"\nreport: {paths['markdown']}")
    return 0
