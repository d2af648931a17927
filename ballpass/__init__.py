"""ballpass: rolling-element-bearing vibration in plain Python.

A fast Sawalhi-Randall simulator with exact ground truth (:func:`simulate`), the
standard envelope-analysis toolbox (:mod:`ballpass.features`), physics-based and
learned diagnosis (:mod:`ballpass.diagnose`) and labelled datasets over parameter
grids (:mod:`ballpass.datasets`).

Importing ``ballpass`` is cheap: numba, scipy, pandas and matplotlib load only when
the part that needs them is first used.

Examples
--------
>>> import ballpass as bp
>>> scene = bp.Scene(bearing="6205", rpm=1797.0, fault=bp.Fault("outer"), fs=48_000.0)
>>> res = bp.simulate(scene)            # doctest: +SKIP
"""

from __future__ import annotations

import importlib

from .bearing import Bearing, BearingFrequencies
from .gears import GearFault, GearPair
from .scene import Fault, Scene, Sensor, SpeedProfile
from .waviness import Waviness

__version__ = "0.1.0"

__all__ = [
    "Bearing",
    "BearingFrequencies",
    "Fault",
    "GearFault",
    "GearPair",
    "Scene",
    "Sensor",
    "SpeedProfile",
    "Waviness",
    "simulate",
    "features",
    "diagnose",
    "datasets",
    "plot",
    "dynamics",
    "__version__",
]

_LAZY_SUBMODULES = {"features", "diagnose", "datasets", "plot", "dynamics"}


def __getattr__(name: str):
    if name in _LAZY_SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    if name == "simulate":
        # the subpackage is callable: ``bp.simulate(scene)`` runs a simulation and
        # ``bp.simulate.resolve_model`` etc. are its other functions
        return importlib.import_module(".simulate", __name__)
    raise AttributeError(f"module 'ballpass' has no attribute {name!r}")
