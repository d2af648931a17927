"""Helpers shared by the tests that interrupt or kill ``ballpass`` subprocesses."""

from __future__ import annotations

from pathlib import Path


def children(pid: int) -> list[int]:
    """Live (not zombie) processes whose parent is ``pid`` (reads /proc: Linux only)."""
    out = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid and fields[0] != "Z":
            out.append(int(stat.parent.name))
    return out
