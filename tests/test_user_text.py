"""What a user reads names papers by their authors and links what exists.

The README, the docs pages (and the tables they show), the gallery and tutorials, the
docstrings and the command-line help are read by people who have none of the
project's working notes: a "seed 003", an issue number, "the digest" or a path into a
team folder (``../shared/...``) names nothing they can look up. File names such as
``seed001_ratios.png`` stay allowed: the words are matched with their spaces.
Every relative link and image of the README and of the pages must point at a file of
the repository, so moving a figure without its links fails here.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GENERATED = {"_build", "auto_examples", "auto_tutorials", "generated"}
PAGES = [ROOT / "README.md",
         *sorted(p for p in (ROOT / "docs").rglob("*")
                 if p.suffix in (".md", ".rst") and not GENERATED & set(p.parts))]
EXAMPLES = sorted(p for p in (ROOT / "examples").rglob("*") if p.suffix in (".py", ".rst"))
#: working-note words: "seed 00x" (not seed00x_ file names), issue numbers, the team's
#: digest of the papers (DIGEST.md; "digest" alone is also a hash, which users may read
#: of), the team's shared folder
WORDS = re.compile(r"seed 00\d|\bissues?\b|digest\.md|(?:our|the) digest\b(?! of the rec)"
                   r"|digest of the papers|\.\./shared|\bshared/", re.I)
#: a Markdown link or image target, without its title
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)")


def _docstrings(path: Path) -> list[tuple[int, str]]:
    """(line, text) of the docstrings of a module, with every string constant of the
    command-line modules (their help and epilog texts are what ``--help`` prints)."""
    tree = ast.parse(path.read_text())
    cli = path.parent.name == "commands" or path.name == "cli.py"
    found = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc:
                found.append((getattr(node, "lineno", 1), doc))
        elif cli and isinstance(node, ast.Constant) and isinstance(node.value, str):
            found.append((node.lineno, node.value))
    return found


def _hits(text: str) -> list[str]:
    return [m.group(0) for m in WORDS.finditer(text)]


@pytest.mark.parametrize("path", PAGES + EXAMPLES, ids=lambda p: str(p.relative_to(ROOT)))
def test_pages_and_examples_name_no_working_notes(path):
    bad = [f"line {n}: {line.strip()[:90]}" for n, line in
           enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if _hits(line)]
    assert not bad, "\n".join(bad)


def test_docstrings_and_help_name_no_working_notes():
    # planted: "our digest of the papers" back in ballpass/dynamics.py's module docstring
    bad = [f"{p.relative_to(ROOT)}:{line}: {_hits(text)}"
           for p in sorted((ROOT / "ballpass").rglob("*.py"))
           for line, text in _docstrings(p) if _hits(text)]
    assert not bad, "\n".join(bad)


def test_the_scan_catches_the_words_and_spares_file_names():
    assert _hits("see seed 003 and issue 9; DIGEST.md; ../shared/data; team shared/data")
    assert len(_hits("seed 003, issue 9, DIGEST.md, ../shared/x")) == 4
    assert not _hits("![ratios](results/seed001_ratios.png) benchmarks/seed004.py, "
                     "a shared machine, shared memory")


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_and_images_resolve(page):
    # planted: docs/index.md's figure back at quickstart_outer.png (moved to results/)
    text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S)
    missing = []
    for target in LINK.findall(text):
        if re.match(r"[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            continue  # a URL or an anchor of the page itself
        if not (page.parent / target.split("#")[0]).exists():
            missing.append(target)
    assert not missing, f"{page.relative_to(ROOT)} links files that do not exist: {missing}"


def test_readme_is_a_front_page():
    # the README is the front page (what ballpass is, the two commands, one figure, a
    # short example, links); the docs site carries the rest. Planted: 100 lines of
    # results appended fail here (the README once grew to 707 lines).
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    assert len(lines) <= 250, f"README.md has {len(lines)} lines; move the detail to docs/"
    figures = [t for t in LINK.findall("\n".join(lines)) if t.endswith(".png")]
    # its one figure is the one `ballpass simulate ... --plot` writes, kept with the results
    assert figures == ["docs/results/quickstart_outer.png"]
