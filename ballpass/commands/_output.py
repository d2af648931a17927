"""What the subcommands share about their outputs: path checks, figures, progress, notices."""

from __future__ import annotations

import sys
from pathlib import Path

from ..signalio import check_output_path

#: Figure formats the subcommands write (matplotlib's, by extension).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")

__all__ = ["FIGURE_SUFFIXES", "check_output_path", "figure_writer", "show_progress",
           "compile_notice"]


def figure_writer(fig, path, dpi: int = 120):
    """``write(tmp)`` that saves ``fig`` in the format of ``path``'s extension.

    For :func:`ballpass.signalio.atomic_write`: the temporary name has no image
    extension, so the format is given explicitly.
    """
    fmt = Path(path).suffix.lstrip(".").lower()
    return lambda tmp: fig.savefig(tmp, format=fmt, dpi=dpi)


def show_progress(args) -> bool:
    """Progress bars go to stderr, only when it is a terminal and ``--quiet`` is not set."""
    return not getattr(args, "quiet", False) and sys.stderr.isatty()


def kernels_cached() -> bool:
    """True when numba holds kernels compiled from the current simulator sources.

    The simulator stamps each cache folder with the fingerprint of its sources
    (:mod:`ballpass.simulate._cache`) and deletes kernels of another fingerprint; numba
    writes one index file (``*.nbi``) per cached function beside the stamp.
    """
    from ..simulate._cache import STAMP_NAME, cache_dirs, source_fingerprint

    fingerprint = source_fingerprint()
    for folder in cache_dirs():
        try:
            if (folder / STAMP_NAME).read_text() == fingerprint and any(
                    folder.glob("*.nbi")):
                return True
        except OSError:
            continue
    return False


def compile_notice() -> None:
    """Say once, on stderr, that the first simulation compiles the kernels."""
    if not kernels_cached():
        print("ballpass: compiling the simulator's kernels (first run after an install or "
              "an update; about a minute, cached afterwards)", file=sys.stderr, flush=True)
