"""Labelled datasets: simulated over parameter grids, or loaded from real recordings.

Simulated datasets
------------------
read_grid     validate a TOML grid file (or dict) into a :class:`Grid` of runs
generate      simulate a grid into a dataset folder, in parallel, resumable
dry_run       estimate rows, time and disk of a grid without writing
load          a dataset folder as ``(X float32 (n, L), meta DataFrame)``
load_features the feature table written by ``generate(..., features=True)``
regenerate    simulate one stored row again, bit for bit
info          what a dataset folder holds (counts per label and condition, fs, size)
example_grid  path of a grid shipped with the package (``example_grids`` lists them)

Real recordings
---------------
load_cwru     Case Western Reserve University bearing data (.mat) in the same shape
load_cwru_mat one CWRU .mat recording
load_mfpt     the MFPT (Society for Machinery Failure Prevention Technology) bearing data
load_manifest recordings of any rig listed in a table (CSV or Parquet), one row each
twin          a ready grid of a real machine from its healthy recordings (a manifest):
              faults through its learned transmission path, over its own background
smith_randall_grades  Smith & Randall's (2015) grade of each CWRU 12 kHz drive-end record
fetch_cwru    download CWRU records by number into a local cache, checked
fetch_mfpt    download and unpack the MFPT data sets into a local cache
fetch         any file, once, into the cache (SHA-256 checked, atomic)

Importing this package loads numpy only; numba, pyarrow and pandas load on first use.
"""

from __future__ import annotations

import importlib

# Eager imports (numpy only; pyarrow, pandas and numba load on first use). They also
# make ``ballpass.datasets.generate`` the function rather than its module.
from .examples import example_grid, example_grids
from .generate import dry_run, generate, regenerate
from .grid import Grid, read_grid
from .store import info, load, load_features
from .twin import twin

__all__ = [
    "Grid",
    "read_grid",
    "generate",
    "dry_run",
    "load",
    "load_features",
    "regenerate",
    "info",
    "example_grid",
    "example_grids",
    "load_cwru",
    "load_cwru_mat",
    "load_mfpt",
    "load_manifest",
    "smith_randall_grades",
    "twin",
    "fetch",
    "fetch_cwru",
    "fetch_mfpt",
]


def __getattr__(name: str):
    if name in ("load_cwru", "load_cwru_mat"):  # scipy.io loads only for real recordings
        return getattr(importlib.import_module(".real", __name__), name)
    if name in ("fetch", "fetch_cwru", "fetch_mfpt"):
        return getattr(importlib.import_module(".download", __name__), name)
    if name == "load_mfpt":
        return getattr(importlib.import_module(".mfpt", __name__), name)
    if name == "load_manifest":
        return getattr(importlib.import_module(".manifest", __name__), name)
    if name == "smith_randall_grades":
        return getattr(importlib.import_module(".published", __name__), name)
    raise AttributeError(f"module 'ballpass.datasets' has no attribute {name!r}")


def __dir__():
    return sorted(__all__)
