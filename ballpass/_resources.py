"""Memory and disk of this machine, and the memory a simulation needs.

Used to refuse work that cannot fit before any of it starts (a :class:`~ballpass.Scene`
whose output would not fit in memory, a dataset grid larger than the free disk).
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

__all__ = ["available_memory", "free_disk", "simulation_bytes", "human_bytes"]

#: peak bytes held by :func:`ballpass.simulate` per output sample: a fixed part (time
#: axis, event tables) and a part per sensor channel (the float64 trace at the internal
#: rate, 4x oversampled, its polyphase decimation and the noisy output). Measured with
#: ``tracemalloc`` on 0.5-2 s of sr5 at 48 kHz: 40 + 36 per sensor bytes per sample;
#: rounded up for margin.
_BYTES_PER_SAMPLE = 48
_BYTES_PER_SAMPLE_AND_SENSOR = 40


def simulation_bytes(n_samples: int, n_sensors: int) -> int:
    """Peak memory of one simulation with ``n_samples`` output samples per sensor, bytes."""
    return n_samples * (_BYTES_PER_SAMPLE + _BYTES_PER_SAMPLE_AND_SENSOR * n_sensors)


def available_memory() -> int:
    """Memory a new allocation can get without swapping, bytes.

    ``MemAvailable`` of ``/proc/meminfo`` on Linux; elsewhere the physical memory.
    """
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):  # pragma: no cover - no sysconf (Windows)
        return 2**63 - 1


def free_disk(path) -> int:
    """Free bytes on the file system that holds ``path`` (or its nearest existing parent)."""
    path = Path(path).resolve()
    while not path.exists() and path != path.parent:
        path = path.parent
    return shutil.disk_usage(path).free


def human_bytes(n: float) -> str:
    """A size in bytes as text with a decimal unit (B, kB, MB, GB, TB)."""
    for unit in ("B", "kB", "MB", "GB"):
        if n < 1000:
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1000
    return f"{n:.1f} TB"
