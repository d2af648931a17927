"""The ``ballpass`` command: one entry point, one subcommand per job.

Each subcommand lives in :mod:`ballpass.commands` as a module with
``add_parser(subparsers)``; that function builds the sub-parser and sets
``func=run``. Heavy imports happen inside ``run`` so ``ballpass --help`` is instant.
"""

from __future__ import annotations

import argparse
import importlib
import sys

#: subcommand name -> module under ballpass.commands
SUBCOMMANDS = {
    "simulate": "simulate",
    "bearings": "bearings",
    "features": "features",
    "plot": "plot",
    "generate": "generate",
    "info": "info",
    "benchmark": "benchmark",
    "work-precision": "work_precision",
    "bifurcation": "bifurcation",
}


def build_parser() -> argparse.ArgumentParser:
    """Return the top-level parser with every available subcommand."""
    from . import __version__

    parser = argparse.ArgumentParser(
        prog="ballpass",
        description="Rolling-element-bearing vibration: simulate, analyse, diagnose, generate.",
    )
    parser.add_argument("--version", action="version", version=f"ballpass {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for module_name in SUBCOMMANDS.values():
        try:
            module = importlib.import_module(f".commands.{module_name}", __package__)
        except ModuleNotFoundError as exc:
            if exc.name == f"{__package__}.commands.{module_name}":
                continue  # subcommand not installed in this build
            raise
        module.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the ``ballpass`` command; returns the process exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "func", None) is None:
        parser.print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except (ValueError, TypeError, FileNotFoundError, FileExistsError, PermissionError) as exc:
        print(f"ballpass {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
