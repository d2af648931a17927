"""``ballpass twin MANIFEST --rpm ... --out twin.toml``: a ready grid of a real machine."""

from __future__ import annotations

import argparse

EXAMPLE = """\
examples:
  ballpass twin healthy.csv --rpm 600 900 1200 --out twin.toml
  ballpass generate twin.toml --out twin-ds --jobs 2
  ballpass benchmark twin-ds --real labelled.csv --splits sim2real --out twin-report

MANIFEST lists healthy recordings of one machine (columns path, fs, rpm, bearing; label
absent or "healthy"). generate learns the machine's transmission path from them (an
all-pole model of their spectrum), drives it with simulated bearing impacts and adds
segments of the recordings as background; healthy rows are the recordings' own
segments."""


def add_parser(subparsers) -> None:
    """Register the ``twin`` subcommand."""
    from ..datasets.twin import TWIN_DEFAULTS

    p = subparsers.add_parser(
        "twin",
        help="write a grid that simulates faults on a real machine from its healthy "
             "recordings",
        description="Write a ready dataset grid (TOML) for the machine whose healthy "
                    "recordings MANIFEST lists: outer, inner and ball faults over a range "
                    "of sizes and levels at the given speeds, heard through the machine's "
                    "learned transmission path over its real background.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("manifest", metavar="MANIFEST",
                   help="CSV or Parquet table of the machine's healthy recordings")
    p.add_argument("--rpm", type=float, nargs="+", required=True, metavar="RPM",
                   help="shaft speeds of the simulated faults, rev/min (> 0)")
    p.add_argument("--out", metavar="FILE", required=True, help="grid file to write (.toml)")
    p.add_argument("--draws", type=int, default=TWIN_DEFAULTS["draws"], metavar="N",
                   help=f"rows per class and speed (default {TWIN_DEFAULTS['draws']})")
    p.add_argument("--duration", type=float, default=TWIN_DEFAULTS["duration_s"],
                   metavar="S", help="seconds per row (default 1)")
    p.add_argument("--seed", type=int, default=0, help="root seed of the grid (default 0)")
    p.set_defaults(func=run)


#: The arguments of :func:`ballpass.datasets.twin.twin` a refusal may start with, and the
#: command's names for them.
OPTION_OF = {"rpm": "--rpm", "draws": "--draws", "duration_s": "--duration", "seed": "--seed",
             "manifest": "MANIFEST"}


def _check_is_a_manifest(path: str) -> None:
    """Refuse a recording given where its manifest is needed, saying how to list it."""
    from pathlib import Path

    from ..datasets.manifest import is_manifest
    from ..datasets.recordings import RECORDING_SUFFIXES

    file = Path(path)
    if file.is_file() and file.suffix.lower() in RECORDING_SUFFIXES and not is_manifest(file):
        raise ValueError(f"MANIFEST {path} is a recording, not a table of them: list the "
                         "machine's healthy recordings in a .csv with the columns path, fs, "
                         f"rpm, bearing (a row: {file.name},<fs Hz>,<rpm>,<bearing>)")


def run(args) -> int:
    """Run ``ballpass twin``; returns the exit code."""
    from ..datasets.twin import twin
    from ._output import check_output_path
    from .simulate import named_as_typed

    check_output_path(args.out, option="--out", suffixes=(".toml",))
    _check_is_a_manifest(args.manifest)
    try:
        path = twin(args.manifest, rpm=args.rpm, out=args.out, duration_s=args.duration,
                    draws=args.draws, seed=args.seed)
    except (ValueError, FileNotFoundError) as exc:
        raise named_as_typed(exc, OPTION_OF) from None
    print(f"wrote {path}; next: ballpass generate {path} --out DIR")
    return 0
