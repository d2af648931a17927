"""``ballpass bearings``: the bearing catalogue and its defect frequencies at an rpm.

Without ``--rpm`` it lists the catalogue (designation, element type, Z, element and pitch
diameters in mm, contact angle in degrees, source). With ``--rpm`` it adds the
characteristic frequencies in Hz for a rotating inner ring and a fixed outer ring
(:meth:`ballpass.Bearing.frequencies`): FTF, BSF, the ball-defect frequency 2xBSF,
BPFO and BPFI.
"""

from __future__ import annotations

import argparse

EXAMPLES = """\
examples:
  ballpass bearings                                     # the catalogue
  ballpass bearings --rpm 1797 --bearing 6205           # CWRU drive end at 1797 rpm
  ballpass bearings --rpm 1797 --bearing 6205 --format csv
  ballpass bearings --rpm 1500 --format json > freqs.json
"""

#: column key -> header used by the table format (units in the header)
_LABELS = {
    "designation": "designation",
    "element": "element",
    "Z": "Z",
    "d_mm": "d (mm)",
    "dp_mm": "d_p (mm)",
    "contact_angle_deg": "alpha (deg)",
    "rpm": "rpm",
    "shaft_hz": "shaft (Hz)",
    "ftf_hz": "FTF (Hz)",
    "bsf_hz": "BSF (Hz)",
    "ball_defect_2xbsf_hz": "ball defect (2xBSF) (Hz)",
    "bpfo_hz": "BPFO (Hz)",
    "bpfi_hz": "BPFI (Hz)",
    "source": "source",
}


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Add the ``bearings`` sub-parser to ``subparsers`` and return it."""
    parser = subparsers.add_parser(
        "bearings",
        help="list the bearing catalogue and the defect frequencies at an rpm",
        description=(
            "List the bearing catalogue (designation, Z, element diameter d, pitch\n"
            "diameter d_p, contact angle, source) and, with --rpm, the defect frequencies\n"
            "in Hz for a rotating inner ring and a fixed outer ring: FTF (cage), BSF (ball\n"
            "spin), the ball-defect frequency 2xBSF, BPFO and BPFI."
        ),
        epilog=EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument(
        "--rpm",
        type=float,
        default=None,
        help="shaft speed in rev/min (> 0); adds the defect frequencies in Hz",
    )
    parser.add_argument(
        "--bearing",
        metavar="NAME",
        default=None,
        help="show only this designation (case-insensitive), e.g. 6205",
    )
    parser.add_argument(
        "--format",
        choices=("table", "csv", "json"),
        default="table",
        help="output format (default: table)",
    )
    parser.set_defaults(func=run)
    return parser


def rows(bearing: str | None = None, rpm: float | None = None) -> list[dict]:
    """The rows ``ballpass bearings`` prints, one dict per bearing.

    Parameters
    ----------
    bearing : str, optional
        Designation to keep; default all of :meth:`ballpass.Bearing.catalog_names`.
    rpm : float, optional
        Shaft speed, rev/min, > 0. When given, each row gets ``rpm``, ``shaft_hz``,
        ``ftf_hz``, ``bsf_hz``, ``ball_defect_2xbsf_hz``, ``bpfo_hz``, ``bpfi_hz`` (Hz).

    Returns
    -------
    list of dict
        Keys as in the CSV header; lengths in mm, angles in degrees, frequencies in Hz.

    Raises
    ------
    ValueError
        Unknown ``bearing``, or ``rpm`` not a finite number > 0.

    Examples
    --------
    >>> from ballpass.commands.bearings import rows
    >>> round(rows("6205", rpm=1797.0)[0]["bpfo_hz"], 2)
    107.36
    """
    import math

    from ..bearing import Bearing

    if rpm is not None and (not math.isfinite(rpm) or rpm <= 0):
        raise ValueError(f"--rpm must be a finite number > 0 (rev/min), got {rpm!r}")
    names = Bearing.catalog_names() if bearing is None else [bearing]
    out = []
    for name in names:
        b = Bearing.catalog(name)
        row = {
            "designation": b.name,
            "element": b.element,
            "Z": b.n_elements,
            "d_mm": b.element_diameter_mm,
            "dp_mm": b.pitch_diameter_mm,
            "contact_angle_deg": b.contact_angle_deg,
        }
        if rpm is not None:
            f = b.frequencies(shaft_hz=rpm / 60.0)
            row.update(
                rpm=rpm,
                shaft_hz=f.shaft,
                ftf_hz=f.ftf,
                bsf_hz=f.bsf,
                ball_defect_2xbsf_hz=f.ball_defect,
                bpfo_hz=f.bpfo,
                bpfi_hz=f.bpfi,
            )
        row["source"] = b.source
        out.append(row)
    return out


def _cell(key: str, value) -> str:
    if isinstance(value, float):
        return f"{value:.2f}" if key.endswith("_hz") else f"{value:g}"
    return str(value)


def run(args: argparse.Namespace) -> int:
    """Print the catalogue (and frequencies) in the requested format; returns 0."""
    import sys

    from ._output import format_records

    text = format_records(rows(args.bearing, args.rpm), args.format, headers=_LABELS,
                          text_columns={"designation", "element", "source"}, cell=_cell)
    sys.stdout.write(text + "\n")
    return 0
