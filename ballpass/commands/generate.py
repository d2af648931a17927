"""``ballpass generate GRID --out DIR``: a labelled dataset over a parameter grid."""

from __future__ import annotations

import argparse

EXAMPLE = """\
examples:
  ballpass generate quick --out out/quick --jobs 2      # a shipped grid (ballpass examples)
  ballpass generate cwru_like_6205_12k --out out/cwru --dry-run
  ballpass generate grid.toml --out /mnt/cluster/ds --scheduler tcp://head-node:8786

Run the same command again to resume an interrupted dataset: complete shards are kept."""


#: seconds to wait for a Dask scheduler to answer
SCHEDULER_TIMEOUT_S = 5


def add_parser(subparsers) -> None:
    """Register the ``generate`` subcommand."""
    from ._output import jobs
    from .features import add_quiet_argument

    p = subparsers.add_parser(
        "generate",
        help="simulate a labelled dataset over a TOML parameter grid",
        description="Simulate every run of a TOML grid into a folder of Parquet shards with "
                    "a _manifest.json; resumable, parallel (local processes or a Dask cluster).",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("grid", metavar="GRID", help="TOML grid file (see docs/datasets.md), or "
                   "the name of a grid shipped with ballpass (`ballpass examples` lists them)")
    p.add_argument("--out", metavar="DIR", help="dataset folder (created; resumed if it "
                   "holds this grid's dataset); required unless --dry-run")
    p.add_argument("--jobs", "-j", type=jobs, default=1, metavar="N",
                   help="local worker processes, -1 for every core (default 1)")
    p.add_argument("--dry-run", action="store_true",
                   help="print rows, estimated time and disk, and write nothing")
    p.add_argument("--features", action="store_true",
                   help="also write a feature table per shard under DIR/_features")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="run the shards on a running Dask scheduler, e.g. tcp://host:8786 "
                        "(needs `pip install ballpass[cluster]`; DIR must be shared storage)")
    p.add_argument("--force", action="store_true",
                   help="start even if the estimated disk or memory need exceeds what is free")
    add_quiet_argument(p)
    p.set_defaults(func=run)


def resolve_grid(text: str):
    """GRID as given: a file's path, or a shipped example's name (``quick``)."""
    from pathlib import Path

    from ..datasets import example_grid, example_grids

    path = Path(text)
    if path.exists():
        return text
    if path.suffix or len(path.parts) != 1:
        raise ValueError(f"GRID {text}: no such file (a grid is a TOML file or the name of "
                         f"a shipped grid: {', '.join(example_grids())})")
    if text not in example_grids():
        raise ValueError(f"GRID {text!r} is neither a file nor a grid shipped with ballpass "
                         f"({', '.join(example_grids())}; `ballpass examples` lists them)")
    return example_grid(text)


def run(args) -> int:
    """Run ``ballpass generate``; returns the exit code."""
    from ..datasets import dry_run, generate, read_grid
    from ..datasets.grid import drawn_axes
    from ._output import compile_notice, show_progress

    args.grid = resolve_grid(args.grid)
    compile_notice()  # both paths simulate (dry-run times one run per model)
    if args.dry_run:
        print(dry_run(args.grid, out_dir=args.out, n_jobs=args.jobs, force=args.force))
        grid = read_grid(args.grid)
        for axis, description in drawn_axes(grid).items():
            print(f"drawn     {axis}: {description} ({grid.dataset.get('draws', 1)} draw(s) per "
                  "grid point)")
        return 0
    if args.out is None:
        raise ValueError("--out DIR is required (unless --dry-run)")
    if args.scheduler is None:
        summary = generate(args.grid, args.out, n_jobs=args.jobs, features=args.features,
                           progress=show_progress(args), force=args.force)
    else:
        try:
            from distributed import Client
        except ImportError:
            raise ValueError("--scheduler needs Dask distributed: "
                             "pip install 'ballpass[cluster]'") from None
        try:
            client = Client(args.scheduler, timeout=SCHEDULER_TIMEOUT_S)
        except (OSError, TimeoutError) as exc:
            raise ValueError(f"--scheduler {args.scheduler}: no Dask scheduler answered "
                             f"within {SCHEDULER_TIMEOUT_S} s ({exc}); start one with "
                             "`dask scheduler` or check the address") from None
        with client:
            summary = generate(args.grid, args.out, executor=client.get_executor(),
                               features=args.features, progress=show_progress(args),
                               force=args.force)
    print(summary)
    return 0
