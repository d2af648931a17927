"""Loaders for real recordings: the Case Western Reserve University (CWRU) bearing data.

The CWRU Bearing Data Center files (MATLAB ``.mat``) hold the drive-end (``X105_DE_time``),
fan-end (``_FE_time``) and sometimes base (``_BA_time``) accelerometer signals and the
motor speed (``X105RPM``); the record number differs per file, so variables are found
by suffix. Two pitfalls catch most users:

* **The values are in g**, not m/s^2. The loaders multiply by 9.80665.
* **Sampling rates differ**: the fault files named ``12k_*`` are sampled at 12 kHz,
  those named ``48k_*`` and the **normal-baseline files (``Normal_*``, records
  97-100) at 48 kHz**. Mixing them without resampling shifts every frequency by 4x.
  The rate is inferred from the file name; pass ``fs`` when a name does not tell.

The drive-end bearing is an SKF 6205-2RS JEM, the fan-end bearing an SKF 6203-2RS JEM.
Faults are EDM pits of 0.007-0.040 in (0.178-1.016 mm); outer-race faults sit at
6 o'clock (centre of the load zone, 0 deg in ballpass's convention), 3 o'clock
(orthogonal, 90 deg) or 12 o'clock (opposite, 180 deg).

References
----------
.. [1] CWRU Bearing Data Center, https://engineering.case.edu/bearingdatacenter
.. [2] W. A. Smith, R. B. Randall, "Rolling element bearing diagnostics using the Case
   Western Reserve University data: A benchmark study", MSSP 64-65 (2015) 100-131.
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import numpy as np

from ..features._validation import check_fs

__all__ = ["STANDARD_GRAVITY", "CWRU_BEARINGS", "CwruRecord", "load_cwru_mat", "load_cwru"]

#: m/s^2 per g (CWRU records acceleration in g).
STANDARD_GRAVITY = 9.80665
#: Bearing at each accelerometer position of the CWRU rig.
CWRU_BEARINGS = {"DE": "6205", "FE": "6203"}
#: Record numbers of the normal-baseline files (sampled at 48 kHz).
_NORMAL_RECORDS = range(97, 101)
_FAULT_NAME = re.compile(
    r"^(?P<rate>12|48)k_(?P<end>DE|FE)_(?P<kind>IR|OR|B)(?P<size>\d{3})(?:@(?P<pos>\d+))?"
    r"_(?P<load>\d)$",
    re.IGNORECASE,
)
_NORMAL_NAME = re.compile(r"^normal_(?P<load>\d)(?:_(?P<rate>12|48)k)?$", re.IGNORECASE)
_KINDS = {"IR": "inner", "OR": "outer", "B": "ball"}
_CLOCK_DEG = {"6": 0.0, "3": 90.0, "12": 180.0}


@dataclass(frozen=True)
class CwruRecord:
    """One channel of a CWRU recording, in SI units, with its label.

    Attributes
    ----------
    accel : ndarray of float64, shape (n_samples,)
        Acceleration, m/s^2 (converted from g).
    fs : float
        Sampling frequency, Hz.
    rpm : float or None
        Motor speed recorded in the file, rev/min (None if absent).
    channel : str
        ``"DE"``, ``"FE"`` or ``"BA"``.
    bearing : str or None
        Catalogue name of the bearing at that accelerometer (``"6205"`` at DE,
        ``"6203"`` at FE, None for the base).
    label : str
        ``"healthy"``, ``"inner"``, ``"outer"``, ``"ball"``, or ``"unknown"`` when the
        file name does not follow the CWRU pattern.
    fault_end : str or None
        Bearing that carries the fault (``"DE"``/``"FE"``); None when healthy/unknown.
    fault_width_mm : float
        Fault diameter, mm (NaN when healthy/unknown).
    fault_angle_deg : float
        Outer-race fault position, degrees from the load-zone centre (NaN otherwise).
    load_hp : int or None
        Motor load, hp.
    name : str
        File name without extension.
    """

    accel: np.ndarray
    fs: float
    rpm: float | None
    channel: str
    bearing: str | None
    label: str
    fault_end: str | None
    fault_width_mm: float
    fault_angle_deg: float
    load_hp: int | None
    name: str


def _parse_name(stem: str) -> dict:
    """Label, fault geometry, load and sampling rate from a CWRU file name."""
    out = {
        "label": "unknown",
        "fault_end": None,
        "fault_width_mm": math.nan,
        "fault_angle_deg": math.nan,
        "load_hp": None,
        "fs": None,
    }
    match = _FAULT_NAME.match(stem)
    if match:
        out.update(
            label=_KINDS[match["kind"].upper()],
            fault_end=match["end"].upper(),
            fault_width_mm=int(match["size"]) * 1e-3 * 25.4,
            fault_angle_deg=_CLOCK_DEG.get(match["pos"], math.nan),
            load_hp=int(match["load"]),
            fs=1000.0 * int(match["rate"]),
        )
        return out
    match = _NORMAL_NAME.match(stem)
    if match:
        # The normal baseline is 48 kHz even when the name does not say so.
        out.update(
            label="healthy", load_hp=int(match["load"]), fs=1000.0 * int(match["rate"] or 48)
        )
        return out
    record = re.fullmatch(r"x?(\d+)", stem, re.IGNORECASE)
    if record and int(record[1]) in _NORMAL_RECORDS:
        out.update(label="healthy", load_hp=int(record[1]) - 97, fs=48_000.0)
    return out


def load_cwru_mat(path, channel: str = "DE", fs: float | None = None) -> CwruRecord:
    """Load one channel of a CWRU ``.mat`` file in m/s^2, with fs, rpm and label.

    Parameters
    ----------
    path : str or os.PathLike
        A CWRU file, e.g. ``12k_DE_OR007@6_0.mat`` or ``Normal_0_48k.mat``.
    channel : {"DE", "FE", "BA"}, optional
        Accelerometer: drive end (default), fan end or base.
    fs : float, optional
        Sampling frequency, Hz. Default: from the file name (``12k`` -> 12 kHz,
        ``48k`` and the normal baseline -> 48 kHz). A value contradicting the name
        warns.

    Returns
    -------
    CwruRecord

    Raises
    ------
    ValueError
        Channel absent from the file, or fs neither given nor inferable.

    Examples
    --------
    >>> from ballpass.datasets.real import load_cwru_mat
    >>> rec = load_cwru_mat("12k_DE_OR007@6_0.mat")                  # doctest: +SKIP
    >>> rec.fs, rec.rpm, rec.label, round(rec.fault_width_mm, 3)     # doctest: +SKIP
    (12000.0, 1796.0, 'outer', 0.178)
    """
    import scipy.io

    path = Path(path)
    channel = str(channel).upper()
    if channel not in ("DE", "FE", "BA"):
        raise ValueError(f"channel must be 'DE', 'FE' or 'BA', got {channel!r}")
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    info = _parse_name(path.stem)
    if fs is None:
        if info["fs"] is None:
            raise ValueError(
                f"cannot infer fs from the file name {path.name!r}; pass fs (Hz): CWRU "
                "fault files are 12000 or 48000, the normal baseline 48000"
            )
        fs = info["fs"]
    else:
        fs = check_fs(fs)
        if info["fs"] is not None and fs != info["fs"]:
            warnings.warn(
                f"{path.name}: fs={fs:g} Hz given but the file name says {info['fs']:g} Hz",
                stacklevel=2,
            )
    data = scipy.io.loadmat(path)
    signals = sorted(k for k in data if k.endswith(f"_{channel}_time"))
    speeds = sorted(k for k in data if k.endswith("RPM"))
    if not signals:
        found = sorted({k.split("_")[1] for k in data if k.endswith("_time")})
        raise ValueError(f"{path.name} has no {channel} channel; it has {found}")
    # Some files carry variables of two records; prefer the one the RPM belongs to.
    prefix = speeds[0][: -len("RPM")] if speeds else None
    key = next((k for k in signals if k.startswith(f"{prefix}_")), signals[0])
    rpm = float(np.ravel(data[speeds[0]])[0]) if speeds else None
    accel = np.ravel(data[key]).astype(np.float64) * STANDARD_GRAVITY
    return CwruRecord(
        accel=accel,
        fs=float(fs),
        rpm=rpm,
        channel=channel,
        bearing=CWRU_BEARINGS.get(channel),
        label=info["label"],
        fault_end=info["fault_end"],
        fault_width_mm=info["fault_width_mm"],
        fault_angle_deg=info["fault_angle_deg"],
        load_hp=info["load_hp"],
        name=path.stem,
    )


def _mat_paths(paths) -> list[Path]:
    if isinstance(paths, (str, Path)):
        paths = [paths]
    if not isinstance(paths, Iterable):
        raise TypeError(f"paths must be a path or an iterable of paths, got {paths!r}")
    out: list[Path] = []
    for p in map(Path, paths):
        out.extend(sorted(p.glob("*.mat")) if p.is_dir() else [p])
    if not out:
        raise ValueError(f"no .mat files in {paths!r}")
    return out


def load_cwru(paths, fs: float = 12_000.0, segment_s: float = 1.0, channel: str = "DE"):
    """CWRU recordings as equal segments at one sampling rate, like ``datasets.load``.

    Each file is loaded with :func:`load_cwru_mat` (g -> m/s^2, fs from the name),
    resampled to ``fs`` with :func:`scipy.signal.resample_poly` (the 48 kHz baseline
    comes down to 12 kHz by default) and cut into non-overlapping segments of
    ``segment_s``; the remainder is dropped. Segments of one file share their
    ``group`` (the file name): split train/test by group, never by segment, or
    segments of one recording leak across folds.

    Parameters
    ----------
    paths : str, os.PathLike or iterable of them
        ``.mat`` files, or folders whose ``*.mat`` files are all taken.
    fs : float, optional
        Output sampling frequency, Hz (default 12000).
    segment_s : float, optional
        Segment length, s (default 1.0).
    channel : {"DE", "FE", "BA"}, optional
        Accelerometer (default ``"DE"``).

    Returns
    -------
    X : ndarray of float32, shape (n_segments, round(segment_s * fs))
        Acceleration, m/s^2.
    meta : pandas.DataFrame
        One row per segment: ``label``, ``bearing``, ``fault_width_mm``,
        ``fault_angle_deg``, ``fault_end``, ``load_hp``, ``rpm``, ``sensor``,
        ``segment``, ``start_s``, ``duration_s``, ``fs``, ``source_fs``, ``group``,
        ``file``.

    Examples
    --------
    >>> from ballpass.datasets import load_cwru
    >>> X, meta = load_cwru("/path/to/cwru", fs=12_000, segment_s=1.0)   # doctest: +SKIP
    >>> meta.groupby("label").size()                                     # doctest: +SKIP
    """
    import pandas as pd
    import scipy.signal

    fs = check_fs(fs)
    if not (isinstance(segment_s, (int, float)) and math.isfinite(segment_s) and segment_s > 0):
        raise ValueError(f"segment_s must be a finite number > 0 s, got {segment_s!r}")
    length = round(segment_s * fs)
    if length < 2:
        raise ValueError(f"segment_s * fs must give at least 2 samples, got {segment_s * fs:g}")
    segments, rows = [], []
    for path in _mat_paths(paths):
        rec = load_cwru_mat(path, channel=channel)
        ratio = Fraction(float(fs) / rec.fs).limit_denominator(1000)
        x = rec.accel
        if ratio != 1:
            x = scipy.signal.resample_poly(x, ratio.numerator, ratio.denominator)
        n = len(x) // length
        segments.append(x[: n * length].reshape(n, length))
        rows.extend(
            {
                "label": rec.label,
                "bearing": rec.bearing,
                "fault_width_mm": rec.fault_width_mm,
                "fault_angle_deg": rec.fault_angle_deg,
                "fault_end": rec.fault_end,
                "load_hp": rec.load_hp,
                "rpm": rec.rpm,
                "sensor": rec.channel,
                "segment": k,
                "start_s": k * length / fs,
                "duration_s": length / fs,
                "fs": float(fs),
                "source_fs": rec.fs,
                "group": rec.name,
                "file": str(path),
            }
            for k in range(n)
        )
    X = np.concatenate(segments).astype(np.float32)
    return X, pd.DataFrame(rows)
