"""The documentation site builds with warnings as errors and its gallery runs.

Skipped when the ``docs`` extra (sphinx, numpydoc, sphinx-gallery, myst-parser,
pydata-sphinx-theme) is not installed; the README's test command installs it.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytest.importorskip("sphinx")
pytest.importorskip("sphinx_gallery")
pytest.importorskip("numpydoc")
pytest.importorskip("myst_parser")


def test_site_builds_without_warnings(tmp_path):
    # -W: any warning (a broken reference, a docstring numpydoc cannot parse, a gallery
    # script that raises) fails the build; --keep-going lists them all at once
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
           "-d", str(tmp_path / "doctrees"), str(ROOT / "docs"), str(tmp_path / "html")]
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT,
                          env={**__import__("os").environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr[-6000:]
    html = tmp_path / "html"
    assert (html / "index.html").exists()
    gallery = sorted((html / "auto_examples").glob("plot_*.html"))
    assert len(gallery) == len(list((ROOT / "examples" / "gallery").glob("plot_*.py")))
    # the tutorials are executed at build time: each page shows what its code printed
    tutorials = sorted((html / "auto_tutorials").glob("plot_*.html"))
    assert len(tutorials) == len(list((ROOT / "examples" / "tutorials").glob("plot_*.py"))) == 3
    for page in tutorials:
        assert "sphx-glr-script-out" in page.read_text(), page.name
    # every gallery page carries at least one figure the script drew
    for page in gallery:
        assert "sphx-glr-single-img" in page.read_text() or "sphx-glr-multi-img" in \
            page.read_text(), page.name
