"""``ballpass examples [NAME]``: the example grids shipped with ballpass."""

from __future__ import annotations

import argparse

EXAMPLE = """\
examples:
  ballpass examples                          # the shipped grids, one line each
  ballpass generate quick --out out/quick    # a shipped grid by its name
  ballpass examples cwru_like_6205_12k > my_grid.toml   # a copy to edit

The grids install with ballpass (package data): their names work from any folder.
In Python: ballpass.datasets.example_grid("quick") is the file's path."""


def add_parser(subparsers) -> None:
    """Register the ``examples`` subcommand."""
    p = subparsers.add_parser(
        "examples",
        help="list the example dataset grids shipped with ballpass (or print one)",
        description="List the example dataset grids shipped with ballpass, one line each, "
                    "or print one grid's TOML to copy and edit. `ballpass generate NAME` "
                    "generates a listed grid by its name.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("name", nargs="?", metavar="NAME",
                   help="print this grid's TOML file instead of the list")
    p.set_defaults(func=run)


def run(args) -> int:
    """Run ``ballpass examples``; returns the exit code."""
    from ..datasets import example_grid, example_grids, read_grid

    if args.name is not None:
        print(example_grid(args.name).read_text(encoding="utf-8"), end="")
        return 0
    grids = example_grids()
    width = max(map(len, grids))
    for name, summary in grids.items():
        grid = read_grid(example_grid(name))
        print(f"{name:<{width}}  {grid.n_rows:>4} rows  {summary}")
    print("\ngenerate one: ballpass generate NAME --out DIR   (see it: ballpass examples NAME)")
    return 0
