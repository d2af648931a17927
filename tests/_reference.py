"""A model's stored reference outputs: ``tests/data/make_<model>_reference.py`` (its
scenes and what it keeps of a run) and the ``<model>_reference.npz`` it wrote."""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

import numpy as np

DATA = Path(__file__).parent / "data"


def reference(model: str):
    """(the make script as a module, {"scene/key": stored array}) of ``model``."""
    if str(DATA) not in sys.path:
        sys.path.insert(0, str(DATA))
    script = importlib.import_module(f"make_{model}_reference")
    with np.load(DATA / f"{model}_reference.npz") as archive:
        return script, {key: archive[key] for key in archive.files}
