"""What the subcommands share about their outputs: path checks, figures, progress, notices."""

from __future__ import annotations

import os
import sys
from pathlib import Path

from ..signalio import check_output_path

#: Figure formats the subcommands write (matplotlib's, by extension).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")

__all__ = ["FIGURE_SUFFIXES", "check_output_path", "figure_writer", "show_progress",
           "compile_notice", "format_records"]


#: Suffixes of the tables the commands write.
TABLE_SUFFIXES = (".csv", ".parquet")


def write_table(frame, out: Path) -> None:
    """Write ``frame`` to ``out`` atomically: CSV for ``.csv``, else Parquet."""
    from ..signalio import atomic_write

    if out.suffix.lower() == ".csv":
        atomic_write(out, lambda tmp: frame.to_csv(tmp, index=False))
    else:
        atomic_write(out, lambda tmp: frame.to_parquet(tmp, index=False))


def figure_writer(fig, path, dpi: int = 120):
    """``write(tmp)`` that saves ``fig`` in the format of ``path``'s extension.

    For :func:`ballpass.signalio.atomic_write`: the temporary name has no image
    extension, so the format is given explicitly.
    """
    fmt = Path(path).suffix.lstrip(".").lower()
    return lambda tmp: fig.savefig(tmp, format=fmt, dpi=dpi)


def jobs(value: str) -> int:
    """argparse type of ``--jobs``: a positive int, or -1 for every core."""
    import argparse

    try:
        n = int(value)
    except ValueError:
        n = 0
    if n < 1 and n != -1:
        raise argparse.ArgumentTypeError(
            f"must be a positive number of processes or -1 (every core), got {value!r}")
    return n


def show_progress(args) -> bool:
    """Progress bars go to stderr, only when it is a terminal and ``--quiet`` is not set."""
    return not getattr(args, "quiet", False) and sys.stderr.isatty()


def kernels_cached() -> bool:
    """True when numba holds kernels compiled from the current simulator sources.

    The simulator stamps each cache folder with the fingerprint of its sources
    (:mod:`ballpass.simulate._cache`) and deletes kernels of another fingerprint; numba
    writes one index file (``*.nbi``) per cached function beside the stamp. With
    ``NUMBA_CACHE_DIR`` set, only the folders below it count: numba uses no other.
    """
    from ..simulate._cache import STAMP_NAME, cache_dirs, source_fingerprint

    fingerprint = source_fingerprint()
    folders = cache_dirs()
    root = os.environ.get("NUMBA_CACHE_DIR")
    if root:  # numba then reads and writes kernels there only, not in __pycache__
        folders = [folder for folder in folders if folder.is_relative_to(Path(root))]
    for folder in folders:
        try:
            if (folder / STAMP_NAME).read_text() == fingerprint and any(
                    folder.glob("*.nbi")):
                return True
        except OSError:
            continue
    return False


def compile_notice() -> None:
    """Say once, on stderr, that the first simulation compiles the kernels.

    Said before the work starts, so the library's own once-per-process notice on the
    ``"ballpass"`` logger (at the first simulation) is marked as said: one line, not two.
    """
    if not kernels_cached():
        print("ballpass: compiling the simulator's kernels (first run after an install or "
              "an update; about a minute, cached afterwards)", file=sys.stderr, flush=True)
        from .. import simulate

        simulate._compile_checked = True


def format_records(records: list[dict], fmt: str, *, headers: dict | None = None,
                   text_columns=(), cell=str) -> str:
    """Rows of dicts as an aligned text table, CSV or JSON (what ``--format`` offers).

    Parameters
    ----------
    records : list of dict
        One dict per row, the same keys in the same order.
    fmt : {"table", "csv", "json"}
    headers : dict, optional
        Key -> column header of the table (units in the header); default the keys.
    text_columns : collection of str, optional
        Keys aligned left in the table; the others (numbers) align right.
    cell : callable, optional
        ``cell(key, value) -> str`` for the table's cells; default ``str(value)``.

    Returns
    -------
    str
        Without a trailing newline.

    Examples
    --------
    >>> from ballpass.commands._output import format_records
    >>> print(format_records([{"model": "sr5", "cost": 1.0}], "table",
    ...                      text_columns={"model"}))
    model  cost
    -----  ----
    sr5     1.0
    >>> format_records([{"model": "sr5", "cost": 1.0}], "csv").splitlines()
    ['model,cost', 'sr5,1.0']
    """
    import csv
    import io
    import json

    keys = list(records[0])
    if fmt == "json":
        return json.dumps(records, indent=2)
    if fmt == "csv":
        buf = io.StringIO()
        writer = csv.DictWriter(buf, fieldnames=keys, lineterminator="\n")
        writer.writeheader()
        writer.writerows(records)
        return buf.getvalue().rstrip("\n")
    show = cell if cell is not str else (lambda key, value: str(value))
    headers = headers or {}
    cells = [[headers.get(k, k) for k in keys]] + [[show(k, r[k]) for k in keys]
                                                    for r in records]
    widths = [max(len(row[i]) for row in cells) for i in range(len(keys))]
    lines = []
    for j, row in enumerate(cells):
        lines.append("  ".join(
            c.ljust(w) if (k in text_columns or j == 0) else c.rjust(w)
            for k, c, w in zip(keys, row, widths, strict=True)).rstrip())
        if j == 0:
            lines.append("  ".join("-" * w for w in widths))
    return "\n".join(lines)
