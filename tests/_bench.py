"""Import a benchmark script as a module, the way it runs from ``benchmarks/``: its
helpers (``_paths``, ``_report``, ``_machine``) are top-level modules there."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

BENCHMARKS = Path(__file__).resolve().parent.parent / "benchmarks"


def load_benchmark(name: str, module_name: str | None = None):
    """The module of ``benchmarks/<name>.py`` (``benchmarks/`` put on ``sys.path`` first)."""
    if str(BENCHMARKS) not in sys.path:
        sys.path.insert(0, str(BENCHMARKS))
    spec = importlib.util.spec_from_file_location(module_name or name, BENCHMARKS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
