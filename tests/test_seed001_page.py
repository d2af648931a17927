"""docs/seed001.md's findings table is what benchmarks/seed001_ratios.py writes from the
CSVs beside it (a page that no longer matches its numbers fails here)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "benchmarks" / "seed001_ratios.py"


def test_findings_on_the_page_are_the_scripts(monkeypatch):
    monkeypatch.syspath_prepend(str(SCRIPT.parent))   # the script imports its _paths helper
    spec = importlib.util.spec_from_file_location("seed001_ratios", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    found = module.findings(pd.read_csv(ROOT / "docs" / "results" / "seed001_ratios.csv"),
                            pd.read_csv(ROOT / "docs" / "results" / "seed001_nabhan2020.csv"))
    page = (ROOT / "docs" / "seed001.md").read_text()
    start, end = module.FINDINGS_MARKERS
    section = page.split(start)[1].split(end)[0]
    assert section.strip() == module.render_findings(found)
