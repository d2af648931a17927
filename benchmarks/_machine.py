"""What the benchmarks ran on, for the header of their result tables."""

from __future__ import annotations

import os
import platform
from pathlib import Path


def cpu_name() -> str:
    """The CPU model from /proc/cpuinfo, else what :mod:`platform` knows."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine() -> str:
    """``"<cpu>, <n> cores, Python <version>"``."""
    return f"{cpu_name()}, {os.cpu_count()} cores, Python {platform.python_version()}"
