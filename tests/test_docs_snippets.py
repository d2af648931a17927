"""The snippets of the README and of the docs pages name the API and the CLI as they are.

The snippets are not run (several simulate for seconds, others read recordings a fresh
clone does not have); instead every call reached from ``ballpass`` (``bp.plot.x(...)``,
a name imported from ``ballpass.datasets``) must resolve to an existing object and
pass only keywords its signature accepts. A renamed function or argument leaves a
snippet that fails for the reader (a tutorial once passed ``max_hz=`` for ``fmax=``).
Likewise every ``ballpass ...`` command of a shell block must be accepted by the parser.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re
import shlex
from pathlib import Path

import pytest

import ballpass
from ballpass.cli import build_parser

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md",
         *sorted(p for p in (ROOT / "docs").rglob("*.md") if "_build" not in p.parts)]


def _blocks(page: Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", page.read_text(), re.S)


def _ballpass_names(tree: ast.AST) -> dict[str, object]:
    """Local name -> object for ``import ballpass as bp`` and ``from ballpass... import``."""
    names = {"bp": ballpass}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update({a.asname or a.name: ballpass for a in node.names
                          if a.name == "ballpass"})
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("ballpass"):
            module = importlib.import_module(node.module)
            for alias in node.names:
                assert hasattr(module, alias.name), f"{node.module} has no {alias.name}"
                names[alias.asname or alias.name] = getattr(module, alias.name)
    return names


def _problems(source: str) -> list[str]:
    tree = ast.parse(source)
    names = _ballpass_names(tree)
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        chain, func = [], node.func
        while isinstance(func, ast.Attribute):
            chain.insert(0, func.attr)
            func = func.value
        if not isinstance(func, ast.Name) or func.id not in names:
            continue  # a call on a result (res.plot()), not on the API
        obj, dotted = names[func.id], func.id
        for attr in chain:
            dotted += f".{attr}"
            if not hasattr(obj, attr):
                found.append(f"{dotted} does not exist")
                break
            obj = getattr(obj, attr)
        else:
            try:
                params = inspect.signature(obj).parameters
            except (TypeError, ValueError):
                continue  # no introspectable signature
            if any(p.kind is p.VAR_KEYWORD for p in params.values()):
                continue
            found += [f"{dotted}() takes no {kw.arg}=" for kw in node.keywords
                      if kw.arg is not None and kw.arg not in params]
    return found


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(ROOT)) for p in PAGES])
def test_snippets_name_the_api_as_it_is(page):
    problems = [p for block in _blocks(page) for p in _problems(block)]
    assert not problems, problems


def test_the_check_finds_a_stale_keyword_and_a_missing_function():
    """The check itself: the bug it guards against is reported."""
    assert _problems("import ballpass as bp\nbp.plot.envelope_spectrum(f, a, max_hz=600)\n"
                     "bp.features.no_such_thing(x)") == [
        "bp.plot.envelope_spectrum() takes no max_hz=",
        "bp.features.no_such_thing does not exist"]


def _shell_commands(page: Path) -> list[list[str]]:
    """Arguments of each ``ballpass`` (or ``.venv/bin/ballpass``) command in shell blocks."""
    commands = []
    for block in re.findall(r"```(?:bash|sh|shell|console)\n(.*?)```", page.read_text(), re.S):
        for line in block.replace("\\\n", " ").splitlines():
            for part in re.split(r"&&|;|\|", line):
                words = shlex.split(part, comments=True)
                at = next((i for i, w in enumerate(words) if w.split("/")[-1] == "ballpass"
                           and (i == 0 or words[i - 1] != "install")), None)
                if at is not None:
                    args = words[at + 1:]
                    commands.append(args[: args.index(">")] if ">" in args else args)
    return commands


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(ROOT)) for p in PAGES])
def test_shell_snippets_parse(page, capsys):
    parser = build_parser()
    for args in _shell_commands(page):
        try:
            parser.parse_args(args)
        except SystemExit:
            pytest.fail(f"ballpass {' '.join(args)}: {capsys.readouterr().err.strip()}")
