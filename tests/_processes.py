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


def cpu_seconds(pid: int) -> float:
    """CPU time (user + system, s) process ``pid`` has used so far (reads /proc: Linux
    only). On a loaded machine it measures how far a child got better than the clock."""
    import os

    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def default_sigint() -> None:
    """``preexec_fn`` of a child that must receive Ctrl-C: SIGINT back to its default, as
    in a terminal. A shell starts background jobs (``pytest ... &``) with SIGINT ignored
    and children inherit that, so Python would not install its KeyboardInterrupt."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)
