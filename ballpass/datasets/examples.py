"""Example dataset grids shipped with the package (``ballpass/examples/*.toml``).

They install with ballpass (package data), so ``ballpass generate quick --out ds``
works from any folder; ``ballpass examples`` lists them.

Examples
--------
>>> from ballpass.datasets import example_grid, example_grids
>>> example_grid("quick").name
'quick.toml'
>>> "quick" in example_grids()
True
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

__all__ = ["example_grid", "example_grids"]


def _folder():
    return resources.files("ballpass") / "examples"


def example_grids() -> dict[str, str]:
    """The shipped example grids: name -> one line saying what each is.

    The line is the first sentence of the grid file's leading comment.

    Examples
    --------
    >>> from ballpass.datasets import example_grids
    >>> example_grids()["quick"]
    'A tiny grid to try `ballpass generate` in a few seconds'
    """
    out = {}
    for entry in sorted(_folder().iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            out[entry.name.removesuffix(".toml")] = _summary(entry.read_text(encoding="utf-8"))
    return out


def _summary(text: str) -> str:
    """First sentence of the leading comment block (up to '.', ':' or a command line)."""
    words = []
    for line in text.splitlines():
        if not line.startswith("#") or line.startswith("#   "):
            break
        words.append(line.lstrip("#").strip())
    sentence = " ".join(words)
    cut = min((i for i in (sentence.find(". "), sentence.find(": "), sentence.find(":"))
               if i >= 0), default=len(sentence))
    return sentence[:cut].rstrip(".")


def example_grid(name: str) -> Path:
    """Path of a shipped example grid, for :func:`ballpass.datasets.generate`.

    Parameters
    ----------
    name : str
        One of :func:`example_grids` (``"quick"``, ``"cwru_like_6205_12k"``, ...); a
        trailing ``.toml`` is allowed.

    Returns
    -------
    pathlib.Path
        The installed TOML file (read it, copy it to edit it, or pass it to ``generate``).

    Raises
    ------
    ValueError
        No example of that name; the message lists them.

    Examples
    --------
    >>> import ballpass as bp
    >>> grid = bp.datasets.read_grid(bp.datasets.example_grid("quick"))
    >>> len(grid.runs)
    8
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    names = example_grids()
    key = name.removesuffix(".toml")
    if key not in names:
        raise ValueError(f"no example grid {name!r}; the shipped ones are "
                         f"{', '.join(names)} (`ballpass examples` says what each is)")
    return Path(str(_folder() / f"{key}.toml"))
