"""``ballpass work-precision``: wall time against error of the solvers for one scene."""

from __future__ import annotations

import argparse

from .simulate import add_scene_arguments, scene_from_args

EXAMPLE = """\
examples:
  ballpass work-precision --fault outer --duration 0.05 --scipy RK45 --plot wp.png
  ballpass work-precision --fault inner --rpm 6000 --duration 0.2 --csv wp.csv
  ballpass work-precision --fault healthy --fs 12000 --resonance 3000 --no-scipy

Each ballpass solver is swept over step sizes (rk4) or tolerances (dopri5), each
scipy solve_ivp method over tolerances, on the same equations; errors are measured
against ballpass dopri5 at rtol 1e-10. scipy runs take seconds to minutes per
simulated second: start with a short --duration.
"""


#: most timing repeats accepted: the best of a few runs is the timing; 10**9 ran forever
MAX_REPEATS = 100

def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register ``work-precision`` on the ``ballpass`` command."""
    from .features import add_quiet_argument

    p = subparsers.add_parser(
        "work-precision",
        help="wall time against error of the ballpass solvers and scipy for a scene",
        description="Measure wall time and error (relative L2 of the acceleration, error "
        "of the squared-envelope-spectrum fault lines) of every ballpass solver and of "
        "scipy's solve_ivp methods on one scene; print the table and the speed-up at "
        "equal error, and draw a log-log plot.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_scene_arguments(p)
    p.add_argument("--model", default="auto", choices=("auto", "sr5", "sr4"),
                   help="auto (default), sr5 or sr4")
    p.add_argument("--scipy", nargs="+", default=None, metavar="METHOD",
                   help="solve_ivp methods to compare (default: RK45 DOP853 LSODA Radau)")
    p.add_argument("--no-scipy", action="store_true", help="compare the ballpass solvers only")
    p.add_argument("--scipy-time-limit", type=float, default=120.0, metavar="S",
                   help="stop a scipy method's sweep after a run longer than this (120 s)")
    p.add_argument("--repeats", type=int, default=3,
                   help="timing repeats of each ballpass run, best counts (default 3)")
    p.add_argument("--error", default="error_l2",
                   choices=["error_l2", "error_ses", "error_ses_db"],
                   help="error measure of the plot and the speed-up (default error_l2)")
    p.add_argument("--csv", default=None, help="also write the table to this CSV file")
    p.add_argument("--plot", default="work_precision.png", metavar="PNG",
                   help="log-log plot of the table (default work_precision.png)")
    add_quiet_argument(p)
    p.set_defaults(func=run)
    return p


def run(args) -> int:
    """Measure, print the table and the speed-ups, write the plot (and the CSV)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    from ballpass.signalio import atomic_write_many
    from ballpass.simulate.work_precision import (
        SCIPY_METHODS,
        plot_work_precision,
        speedup,
        work_precision,
    )

    from ._output import (
        FIGURE_SUFFIXES,
        check_output_path,
        compile_notice,
        figure_writer,
        show_progress,
    )

    csv = None if args.csv is None else check_output_path(args.csv, option="--csv",
                                                           suffixes=(".csv",))
    plot = check_output_path(args.plot, option="--plot", suffixes=FIGURE_SUFFIXES)
    if not 1 <= args.repeats <= MAX_REPEATS:
        raise ValueError(f"--repeats must be an int from 1 to {MAX_REPEATS} (the best of "
                         f"a few runs is the timing), got {args.repeats}")
    unknown = sorted(set(args.scipy or ()) - set(SCIPY_METHODS))
    if unknown:
        raise ValueError(f"--scipy takes {', '.join(SCIPY_METHODS)}, got {', '.join(unknown)}")
    if not args.scipy_time_limit > 0:
        raise ValueError(f"--scipy-time-limit must be > 0 s, got {args.scipy_time_limit}")
    if args.snr is not None:
        raise ValueError(f"--snr {args.snr:g}: work-precision compares noise-free signals "
                         "(noise would be the error); leave it out")
    scene = scene_from_args(args)
    compile_notice()
    methods = () if args.no_scipy else tuple(args.scipy or SCIPY_METHODS)
    table = work_precision(scene, model=args.model, scipy_methods=methods, repeats=args.repeats,
                    scipy_time_limit=args.scipy_time_limit,
                           progress=show_progress(args))
    with pd.option_context("display.width", 200, "display.max_columns", 20,
                           "display.float_format", "{:.3g}".format):
        print()
        print(table.drop(columns=["family"]).to_string(index=False))
        if methods:
            print(f"\nspeed-up over the fastest scipy method at equal {args.error}:")
            print(speedup(table, error=args.error).to_string())
    title = (f"{scene.bearing.name} {scene.label} at {scene.speed.mean_rpm:g} rpm, "
             f"{scene.duration_s:g} s at {scene.fs:g} Hz")
    ax = plot_work_precision(table, error=args.error, title=title)
    ax.figure.tight_layout()
    writes = [(plot, figure_writer(ax.figure, plot))]
    if csv is not None:
        writes.append((csv, lambda tmp: table.to_csv(tmp, index=False)))
    atomic_write_many(writes)
    plt.close(ax.figure)
    if csv is not None:
        print(f"table -> {csv}")
    print(f"plot -> {plot}")
    return 0
