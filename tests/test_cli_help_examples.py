"""The examples in every subcommand's ``--help`` are commands the parser accepts, laid
out as a shell reads them.

A renamed or removed option leaves a stale example behind; a continuation line without
its backslash prints as one long line (the shell then runs it, but the help reads
wrong). Parsing is cheap: nothing is simulated.
"""

import shlex

import pytest

from ballpass.cli import build_parser

PARSER = build_parser()
SUBPARSERS = next(a for a in PARSER._actions if a.dest == "command").choices

#: help text is read in an 80-100 column terminal; argparse does not wrap the epilog
MAX_LINE = 100


def _commands(epilog: str) -> list[list[str]]:
    """The ``ballpass`` commands of an epilog: continuations joined, ``&&`` chains
    split, comments and ``>`` redirections dropped."""
    commands = []
    for line in epilog.replace("\\\n", " ").splitlines():
        if not line.strip().startswith("ballpass "):
            continue  # prose
        for part in line.split("&&"):
            words = shlex.split(part, comments=True)
            if words[:1] == ["ballpass"]:
                commands.append(words[: words.index(">")] if ">" in words else words)
    return commands


@pytest.mark.parametrize("name", sorted(SUBPARSERS))
def test_help_examples_parse(name):
    commands = _commands(SUBPARSERS[name].epilog or "")
    assert commands, f"`ballpass {name} --help` shows no example"
    for words in commands:
        args = PARSER.parse_args(words[1:])  # SystemExit (a usage error) fails the test
        assert args.command == words[1]


@pytest.mark.parametrize("name", sorted(SUBPARSERS))
def test_help_example_lines_fit_a_terminal(name):
    long = [line for line in (SUBPARSERS[name].epilog or "").splitlines()
            if len(line) > MAX_LINE]
    assert not long, long
