"""Sphinx configuration of the ballpass documentation site.

Build: ``python -m sphinx -W --keep-going -b html docs docs/_build/html`` (the test
suite does this in ``tests/test_docs.py``, warnings as errors). Pages are Markdown
(MyST) or reStructuredText; the API reference is generated from the numpydoc
docstrings; the gallery runs the scripts in ``examples/gallery`` and draws their figures.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("MPLBACKEND", "Agg")

import ballpass  # noqa: E402

project = "ballpass"
author = "the ballpass developers"
copyright = "2026, the ballpass developers"
release = version = ballpass.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build"] + [f"{gallery}/*.{ext}"
                                  for gallery in ("auto_examples", "auto_tutorials")
                                  for ext in ("ipynb", "py", "zip", "json", "md5")]
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
suppress_warnings = ["myst.xref_missing"]

templates_path = ["_templates"]
autosummary_generate = True
# scikit-learn's generated metadata-routing setters and inherited mixin methods document
# scikit-learn, not ballpass, and reference its own glossary
autodoc_default_options = {
    "members": True,
    "inherited-members": False,
    "exclude-members": "set_fit_request,set_predict_request,set_score_request,"
                       "set_transform_request,set_output,get_metadata_routing,score,"
                       "get_params,set_params,fit_transform",
}
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
numpydoc_xref_param_type = False

intersphinx_mapping = {}

sphinx_gallery_conf = {
    "examples_dirs": [str(ROOT / "examples" / "tutorials"), str(ROOT / "examples" / "gallery")],
    "gallery_dirs": ["auto_tutorials", "auto_examples"],
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
}

html_theme = "pydata_sphinx_theme"
html_title = f"ballpass {version}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2,
                      "show_nav_level": 2, "navigation_depth": 2}
html_static_path = ["_static"]
html_css_files = ["ballpass.css"]
# the site's whole table of contents in the left sidebar of every page, top-level ones too
html_sidebars = {"**": ["globaltoc.html"]}


def _skip_sklearn_routing(app, what, name, obj, skip, options):
    """Skip scikit-learn's generated ``set_*_request`` metadata-routing setters."""
    if name.startswith("set_") and name.endswith("_request"):
        return True
    return None


def setup(app):
    app.connect("autodoc-skip-member", _skip_sklearn_routing)
