"""``ballpass bifurcation``: a bifurcation diagram of the rotor over one parameter.

Runs :func:`ballpass.dynamics.bifurcation_diagram` (model ``rotor2`` by default, seed
003's rotor on an NJ 305) over the values of one parameter, writes the Poincare points
as CSV and draws the diagram (:func:`ballpass.dynamics.plot_bifurcation`).
"""

from __future__ import annotations

import argparse

EXAMPLES = """\
examples:
  ballpass bifurcation --parameter rpm --range 500 2000 16 --out rpm.csv --plot rpm.png
  ballpass bifurcation --parameter radial_clearance_mm --values 0 0.01 0.05 0.125 \\
      --fault inner --rpm 1500 --duration 2 --jobs 2 --out clearance.csv --plot c.png
  ballpass bifurcation --parameter radial_load_n --range 0 500 11 --strobe cage --out load.csv
"""


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register ``bifurcation`` on the ``ballpass`` command."""
    from ._output import jobs
    from .features import add_quiet_argument

    p = subparsers.add_parser(
        "bifurcation",
        help="bifurcation diagram of the rotor (Poincare sections over a parameter)",
        description="Simulate the rotor (model rotor2, the NJ 305 rotor paper) for each value "
        "of one parameter, strobe its displacement once per shaft (or cage) revolution after "
        "the transient, and write the points (parameter, point, x_m, y_m; m) as CSV. "
        "Parameters: any numeric scene field (rpm, radial_load_n, ...) or "
        "radial_clearance_mm of the bearing.",
        epilog=EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--parameter", required=True,
                   help="rpm, radial_load_n, radial_clearance_mm or another numeric scene field")
    values = p.add_mutually_exclusive_group(required=True)
    values.add_argument("--values", type=float, nargs="+", help="the parameter's values")
    values.add_argument("--range", type=float, nargs=3, metavar=("START", "STOP", "NUM"),
                        help="NUM values evenly spaced from START to STOP")
    p.add_argument("--bearing", default="NJ305", help="catalogue designation (default NJ305)")
    p.add_argument("--clearance", type=float, default=None,
                   help="radial clearance, mm (default: the catalogue's, 0.125 for NJ305)")
    p.add_argument("--rpm", type=float, default=1500.0, help="shaft speed, rpm (default 1500)")
    p.add_argument("--load", type=float, default=0.0,
                   help="radial load besides the rotor's weight, N (default 0)")
    p.add_argument("--fault", choices=["healthy", "outer", "inner", "ball"], default="healthy",
                   help="localized defect (default healthy)")
    p.add_argument("--width", type=float, default=0.5, help="defect width, mm (default 0.5)")
    p.add_argument("--depth", type=float, default=0.5, help="defect depth, mm (default 0.5)")
    p.add_argument("--duration", type=float, default=1.0, help="seconds per run (default 1)")
    p.add_argument("--discard", type=float, default=None,
                   help="transient to drop, s (default: half the duration)")
    p.add_argument("--fs", type=float, default=10_000.0, help="output rate, Hz (default 10000)")
    p.add_argument("--strobe", choices=["shaft", "cage"], default="shaft",
                   help="strobe once per shaft (default) or cage revolution")
    p.add_argument("--model", default="rotor2", help="model (default rotor2)")
    p.add_argument("--jobs", type=jobs, default=1, help="parallel processes (-1 = all cores)")
    p.add_argument("--out", "-o", required=True, help="CSV file of the section points")
    p.add_argument("--plot", default=None, metavar="PNG", help="also draw the diagram")
    add_quiet_argument(p)
    p.set_defaults(func=run)
    return p


def run(args: argparse.Namespace) -> int:
    """Compute the diagram, write the CSV (and the figure); returns 0."""
    import numpy as np

    import ballpass as bp

    from ..signalio import atomic_write_many
    from ._output import (
        FIGURE_SUFFIXES,
        check_output_path,
        compile_notice,
        figure_writer,
        show_progress,
    )
    from .simulate import OPTION_OF, named_as_typed

    options = {**OPTION_OF, "discard_s": "--discard", "radial_clearance_mm": "--clearance",
               "parameter": "--parameter", "model": "--model", "strobe": "--strobe"}
    # every output and value is checked before the first simulation
    out = check_output_path(args.out, option="--out", suffixes=(".csv",))
    plot = None if args.plot is None else check_output_path(args.plot, option="--plot",
                                                            suffixes=FIGURE_SUFFIXES)
    if args.range is not None:
        start, stop, num = args.range
        if num != int(num) or not 1 <= num <= bp.dynamics.MAX_VALUES:
            raise ValueError(f"--range NUM must be a whole number from 1 to "
                             f"{bp.dynamics.MAX_VALUES:,} (one simulation each), got {num:g}")
        values = np.linspace(start, stop, int(num))
    else:
        values = np.asarray(args.values)
        if len(values) > bp.dynamics.MAX_VALUES:   # as many as --range allows
            raise ValueError(f"--values takes at most {bp.dynamics.MAX_VALUES:,} values (one "
                             f"simulation each), got {len(values):,}")
    try:
        bearing = bp.Bearing.catalog(args.bearing)
        if args.clearance is not None:
            bearing = bearing.with_clearance(args.clearance)
        fault = None if args.fault == "healthy" else bp.Fault(
            args.fault, width_mm=args.width, depth_mm=args.depth)
        # rotor2 has no structural resonance; any valid value below Nyquist will do
        scene = bp.Scene(bearing=bearing, rpm=args.rpm, radial_load_n=args.load, fault=fault,
                         duration_s=args.duration, fs=args.fs, resonance_hz=0.4 * args.fs)
        compile_notice()
        df = bp.dynamics.bifurcation_diagram(scene, args.parameter, values, model=args.model,
                                             strobe=args.strobe, discard_s=args.discard,
                                             n_jobs=args.jobs, progress=show_progress(args))
    except ValueError as exc:
        raise named_as_typed(exc, options) from None
    table = df.rename(columns={"parameter": args.parameter})
    writes = [(out, lambda tmp: table.to_csv(tmp, index=False))]
    if plot is not None:
        from ..plot import _pyplot

        fig, ax = _pyplot().subplots(figsize=(7, 4), layout="constrained")
        bp.dynamics.plot_bifurcation(df, ax=ax)
        writes.append((plot, figure_writer(fig, plot)))
    atomic_write_many(writes)
    print(f"{len(df)} section points over {len(values)} values of {args.parameter} -> {out}")
    if plot is not None:
        print(f"plot -> {plot}")
    return 0
