"""The result files of the benchmarks: medians with their spread, Markdown tables, pages.

Timings on a shared machine are reported as the median of interleaved rounds with the
range over the rounds (``spread``); a table is built by ``table`` and a page or table
file written whole by ``write_page`` (never half-written: ``atomic_write``).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from pathlib import Path

import numpy as np

from ballpass.signalio import atomic_write


def median_range(values) -> tuple[float, float, float]:
    """``(median, min, max)`` of repeated measurements (any non-empty sequence)."""
    v = np.asarray(values, dtype=float)
    if v.size == 0:
        raise ValueError("median_range needs at least one value")
    return float(np.median(v)), float(v.min()), float(v.max())


def span(median: float, lo: float, hi: float, fmt: str = ".2f") -> str:
    """``"median (lo-hi)"`` with each number in the format ``fmt``."""
    return f"{median:{fmt}} ({lo:{fmt}}-{hi:{fmt}})"


def spread(values, fmt: str = ".2f") -> str:
    """The median of ``values`` with their range, ``"1.23 (1.10-1.40)"``; one value alone."""
    med, lo, hi = median_range(values)
    return f"{med:{fmt}}" if np.size(values) == 1 else span(med, lo, hi, fmt)


def table(header: Sequence[str], rows: Iterable[Sequence], align: str | None = None) -> list[str]:
    """Lines of a Markdown table.

    ``header`` holds the column titles, ``rows`` the cells of each row (each written with
    ``str``), ``align`` one letter per column: ``"l"`` or ``"r"`` (default: all left).
    """
    align = "l" * len(header) if align is None else align
    if len(align) != len(header) or set(align) - {"l", "r"}:
        raise ValueError(f"align must be one of 'l'/'r' per column ({len(header)}), got {align!r}")
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---:" if a == "r" else "---" for a in align) + "|"]
    for row in rows:
        cells = [str(c) for c in row]
        if len(cells) != len(header):
            raise ValueError(f"a row has {len(cells)} cells for {len(header)} columns: {cells}")
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def write_page(path: Path, lines: Iterable[str]) -> Path:
    """Write Markdown ``lines`` to ``path`` (its folder created), ending in one newline."""
    text = "\n".join(lines).rstrip("\n") + "\n"
    atomic_write(path, lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    return Path(path)


def write_csv(frame, path: Path, **to_csv) -> Path:
    """Write a pandas DataFrame to ``path`` (its folder created, no index column)."""
    atomic_write(path, lambda tmp: frame.to_csv(tmp, index=False, **to_csv))
    return Path(path)
