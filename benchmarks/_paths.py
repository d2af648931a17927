"""Where the benchmark scripts write: pages in ``docs/``, tables and figures in ``docs/results/``.

A page (Markdown the docs site shows, e.g. ``docs/diagnosis.md``) sits at the top of
``docs/``; every CSV, PNG and generated Markdown table that is not a page goes into
``RESULTS_DIR``, and a page links them as ``results/<name>``. Scripts with
an ``--out`` folder for the page write its tables and figures to ``results_in(out)``, so
the links hold wherever the page goes.
"""

from __future__ import annotations

from pathlib import Path

#: the repository's root folder
ROOT = Path(__file__).resolve().parents[1]
#: the documentation pages
DOCS = ROOT / "docs"
#: the tables and figures the benchmarks write (CSV, PNG, Markdown tables that are not pages)
RESULTS_DIR = DOCS / "results"


def results_in(pages: Path) -> Path:
    """The results folder beside the pages in ``pages`` (created if missing)."""
    out = Path(pages) / RESULTS_DIR.name
    out.mkdir(parents=True, exist_ok=True)
    return out

