"""``ballpass models``: the model hierarchy, and which model ``auto`` runs for some needs.

Without ``--needs`` it lists the registry (:data:`ballpass.simulate.MODELS`), cheapest
first: each model's cost per simulated second relative to ``sr5``, its solvers (the
first is the default) and the phenomena it represents. With ``--needs`` it adds the
model ``model="auto"`` picks for a scene that asks for those phenomena
(:func:`ballpass.simulate.resolve_model`), or why none can.
"""

from __future__ import annotations

import argparse

EXAMPLES = """\
examples:
  ballpass models                                   # the hierarchy, cheapest first
  ballpass models --needs envelope                  # the cheapest that draws an envelope
  ballpass models --needs ball_dynamics contact_forces
  ballpass models --format json > models.json
"""

_HEADERS = {"model": "model", "relative_cost": "cost (x sr5)", "solvers": "solvers",
            "represents": "represents", "reference": "reference"}


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register ``models`` on the ``ballpass`` command."""
    from ..phenomena import PHENOMENA

    p = subparsers.add_parser(
        "models",
        help="list the simulation models (cost, solvers, phenomena) and what auto picks",
        description="List the simulation models, cheapest first: cost per simulated "
        "second relative to sr5, solvers (the first is the default) and the phenomena each "
        "represents. With --needs, also the model that model='auto' runs for a scene "
        "asking for those phenomena.",
        epilog=EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("--needs", nargs="+", metavar="PHENOMENON", choices=sorted(PHENOMENA),
                   default=None, help="phenomena a scene asks for: " + ", ".join(
                       sorted(PHENOMENA)) + "; prints the model auto picks")
    p.add_argument("--bearing", default=None,
                   help="bearing of the scene --needs describes (default 6205; a roller "
                   "bearing changes which models can take it)")
    p.add_argument("--format", choices=("table", "csv", "json"), default="table",
                   help="output format (default: table)")
    p.set_defaults(func=run)
    return p


def rows(with_reference: bool = False) -> list[dict]:
    """The rows ``ballpass models`` prints, cheapest model first.

    Parameters
    ----------
    with_reference : bool, optional
        Add each model's ``reference`` (the papers it follows).

    Returns
    -------
    list of dict
        ``model``, ``relative_cost`` (wall time per simulated second / sr5's),
        ``solvers`` (default first), ``represents`` (phenomena, comma-separated).

    Examples
    --------
    >>> from ballpass.commands.models import rows
    >>> first = rows()[0]
    >>> first["model"], "envelope" in first["represents"]
    ('impulse', True)
    """
    from ..simulate import MODELS

    out = []
    for model in MODELS.values():
        row = {"model": model.name, "relative_cost": model.relative_cost,
               "solvers": ", ".join(model.solvers),
               "represents": ", ".join(sorted(model.represents))}
        if with_reference:
            row["reference"] = model.reference
        out.append(row)
    return out


def run(args: argparse.Namespace) -> int:
    """Print the hierarchy and, with ``--needs``, the model auto picks; returns 0."""
    import sys

    import ballpass as bp

    from ._output import format_records

    # the scene of --needs is checked (and resolved) before anything is printed
    answer = None
    if args.needs is None and args.bearing is not None:
        raise ValueError("--bearing describes the scene of --needs: give --needs too")
    if args.needs is not None:
        scene = bp.Scene(bearing=args.bearing or "6205", needs=tuple(args.needs))
        answer = (f"needs {', '.join(sorted(args.needs))} on a {scene.bearing.name}: "
                  f"model='auto' runs {bp.simulate.resolve_model(scene)}\n")
    records = rows(with_reference=args.format != "table")
    sys.stdout.write(format_records(
        records, args.format, headers=_HEADERS,
        text_columns={"model", "solvers", "represents", "reference"},
        cell=lambda key, value: f"{value:g}" if key == "relative_cost" else str(value)) + "\n")
    if answer is not None:
        # the machine-readable formats stay parseable: the answer goes to stderr
        (sys.stdout if args.format == "table" else sys.stderr).write(answer)
    return 0
