"""``ballpass info DIR``: what a dataset folder holds."""

from __future__ import annotations

import argparse

EXAMPLE = """\
example:
  ballpass generate quick --out out/quick && ballpass info out/quick"""


def add_parser(subparsers) -> None:
    """Register the ``info`` subcommand."""
    p = subparsers.add_parser(
        "info",
        help="summarise a dataset folder: rows per label and condition, fs, duration, size",
        description="Summarise a dataset written by `ballpass generate` without reading "
                    "its signals.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("dir", metavar="DIR", help="dataset folder")
    p.set_defaults(func=run)


def run(args) -> int:
    """Run ``ballpass info``; returns the exit code."""
    import pandas as pd

    from ..datasets import info
    from ..datasets.store import human_bytes, read_manifest

    d = info(args.dir)
    machine = (read_manifest(args.dir) or {}).get("grid", {}).get("machine")
    # a twin's rows are its machine's recordings and faults scaled to them: their unit
    unit = ("m/s^2" if machine is None
            else f"in the units of the recordings {machine['manifest']} lists")
    print(f"dataset   {d['path']}  (ballpass {d['ballpass_version']}, {d['status']})")
    print(f"rows      {d['n_rows']} of {d['n_rows_planned']}  ({d['n_runs']} runs, "
          f"{d['shards_complete']}/{d['shards_total']} shards)")
    print(f"signals   {d['signal_length']} samples at {d['fs']:g} Hz = "
          f"{d['duration_s']:g} s, float32, {unit}")
    print(f"size      {human_bytes(d['size_bytes'])} on disk"
          f"{'; with feature table' if d['features'] else ''}")
    for axis, description in d["drawn"].items():
        print(f"drawn     {axis}: {description}, one value per draw")
    if d["n_rows"]:
        print("\nrows per label")
        print(d["labels"].to_string())
        print("\nrows per condition and label")
        with pd.option_context("display.max_rows", 200, "display.width", 120):
            print(d["conditions"].to_string())
            if d.get("fault_sizes") is not None:
                print("\nfaulty rows per fault size (mm) and label")
                print(d["fault_sizes"].to_string())
    return 0
