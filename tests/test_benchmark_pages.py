"""The benchmark scripts' shared report code, where they write, and the pages they write.

The scripts in ``benchmarks/`` are run from their folder (``python benchmarks/x.py``), so
they import their helpers ``_paths`` and ``_report`` as top-level modules; the tests put
that folder on the path the same way.
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pandas as pd
import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"


@pytest.fixture
def bench(monkeypatch):
    """Import a benchmark script (or helper) by name, as when run from benchmarks/."""
    monkeypatch.syspath_prepend(str(BENCHMARKS))

    def load(name: str):
        spec = importlib.util.spec_from_file_location(name, BENCHMARKS / f"{name}.py")
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        return mod

    return load


@pytest.mark.parametrize("script", ["seed003", "seed004"])
def test_page_is_written_from_its_csvs(bench, script):
    # docs/seed00x.md is what benchmarks/seed00x.py writes from the committed CSVs in
    # docs/results: a hand edit of the page, CSVs regenerated without the page, or a
    # figure link the script does not write, fail here
    mod, paths = bench(script), bench("_paths")
    frames = {k: pd.read_csv(paths.RESULTS_DIR / f) for k, f in mod.CSVS.items()}
    assert mod.page(frames) == (paths.DOCS / f"{script}.md").read_text()


def test_scripts_take_their_folders_from_paths():
    # one constant for where results go: a script that names "docs" or a "results"
    # folder itself (the old benchmarks/results, or a page's figure written beside it)
    # fails here. Planted: RESULTS = Path(__file__).parent / "results" in one script.
    named = re.compile(r"""(/|\()\s*["'](docs|results)["']|Path\(["']docs""")
    offenders = [p.name for p in sorted(BENCHMARKS.glob("*.py"))
                 if p.name != "_paths.py" and named.search(p.read_text())]
    assert not offenders, f"take DOCS / RESULTS_DIR / results_in from _paths: {offenders}"


def test_results_folder_is_beside_the_pages(bench, tmp_path):
    paths = bench("_paths")
    assert paths.RESULTS_DIR == paths.DOCS / "results" == ROOT / "docs" / "results"
    # a page written to --out links results/<name>: its tables go to out/results
    assert paths.results_in(tmp_path / "site") == tmp_path / "site" / "results"
    assert (tmp_path / "site" / "results").is_dir()


def test_spread_is_the_median_with_the_range(bench):
    report = bench("_report")
    # an odd count's median is its middle value, not the mean (4.33 here): planted
    # np.mean in median_range fails this
    assert report.median_range([10.0, 1.0, 2.0]) == (2.0, 1.0, 10.0)
    assert report.spread([10.0, 1.0, 2.0]) == "2.00 (1.00-10.00)"
    assert report.spread([1.0, 2.0, 4.0, 10.0], ".1f") == "3.0 (1.0-10.0)"  # even: mean of 2 and 4
    assert report.spread([0.5]) == "0.50"  # one round has no range to show
    with pytest.raises(ValueError, match="at least one value"):
        report.median_range([])


def test_table_lines(bench):
    report = bench("_report")
    lines = report.table(["name", "ms"], [("a", 1.5), ("b", "2")], align="lr")
    assert lines == ["| name | ms |", "|---|---:|", "| a | 1.5 |", "| b | 2 |"]
    assert report.table(["x"], [])[1] == "|---|"  # left by default
    with pytest.raises(ValueError, match="align must be one of 'l'/'r' per column"):
        report.table(["a", "b"], [], align="l")
    with pytest.raises(ValueError, match="a row has 1 cells for 2 columns"):
        report.table(["a", "b"], [("only",)])


def test_write_page_and_csv(bench, tmp_path):
    report = bench("_report")
    page = report.write_page(tmp_path / "new" / "t.md", ["# T", "", "text", ""])
    assert page.read_text() == "# T\n\ntext\n"  # folder made, one final newline
    frame = pd.DataFrame({"a": [1, 2]})
    csv = report.write_csv(frame, tmp_path / "t.csv")
    pd.testing.assert_frame_equal(pd.read_csv(csv), frame)  # no index column


def test_docs_top_holds_pages_only():
    # pages at the top of docs/, what the scripts write in docs/results/ (rule in
    # docs/development.md). Planted: a CSV written beside its page fails here.
    stray = sorted(p.name for p in (ROOT / "docs").iterdir()
                   if p.is_file() and p.suffix not in (".md", ".rst") and p.name != "conf.py")
    assert not stray, f"move to docs/results/ (and link as results/<name>): {stray}"
