"""``ballpass plot INPUT...``: waveform, squared envelope spectrum with fault markers, kurtogram."""

from __future__ import annotations

import argparse

EXAMPLE = """\
examples:
  ballpass simulate --fault inner --out inner.npz && ballpass plot inner.npz --out inner.png
  ballpass plot 12k_DE_IR007_0.mat --out figs/          # CWRU: g -> m/s^2, fs from the name
  ballpass plot Normal_0_48k.mat --rpm 1796 --band 2000 5000
  ballpass plot out/quick --max-figures 5 --out figs/   # first rows of a dataset

Inputs are those of `ballpass features` (see `ballpass features --help` for the CWRU
pitfalls: values in g, the normal baseline sampled at 48 kHz)."""


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register ``plot`` on the ``ballpass`` command."""
    from .features import add_input_arguments, add_quiet_argument

    p = subparsers.add_parser(
        "plot",
        help="overview figure per signal: waveform, SES with fault markers, kurtogram",
        description="Draw, for every signal of the inputs, its waveform, its squared "
        "envelope spectrum (band from the fast kurtogram unless --band) with the bearing's "
        "fault frequencies and harmonics marked, and the kurtogram, into PNG files.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_input_arguments(p)
    p.add_argument(
        "--out",
        "-o",
        default=".",
        metavar="PATH",
        help="folder for the figures (default: current folder), or a .png (.pdf, .svg, "
        ".jpg) file when there is one signal",
    )
    p.add_argument(
        "--max-figures",
        type=int,
        default=50,
        metavar="N",
        help="draw at most N figures (default 50)",
    )
    add_quiet_argument(p)
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    """Draw the figures; returns the exit code."""
    from pathlib import Path

    from ._output import FIGURE_SUFFIXES, check_output_path, show_progress
    from .features import load_inputs, plot_signals

    if args.max_figures < 1:
        raise ValueError(f"--max-figures must be >= 1, got {args.max_figures}")
    out = Path(args.out)
    suffix = out.suffix.lower()
    single = suffix in FIGURE_SUFFIXES
    check_output_path(out, option="--out", suffixes=FIGURE_SUFFIXES, folder=not single)
    signals = load_inputs(args)
    band = tuple(args.band) if args.band is not None else None
    if single:
        if len(signals) != 1:
            raise ValueError(
                f"--out {out.name} names one figure but the inputs hold "
                f"{len(signals)} signals; give a folder"
            )
        plot_signals(signals, out.parent, band, names=[out.stem], suffix=suffix)
        print(f"figure -> {out}")
        return 0
    shown = signals[: args.max_figures]
    paths = plot_signals(shown, out, band, progress=show_progress(args))
    skipped = len(signals) - len(shown)
    print(
        f"{len(paths)} figure(s) -> {out}"
        + (f" ({skipped} more skipped; --max-figures)" if skipped else "")
    )
    return 0
