"""Loaders for real recordings: the Case Western Reserve University (CWRU) bearing data.

The CWRU Bearing Data Center files (MATLAB ``.mat``) hold the drive-end (``X105_DE_time``),
fan-end (``_FE_time``) and sometimes base (``_BA_time``) accelerometer signals and the
motor speed (``X105RPM``); the record number differs per file, so variables are found
by suffix. Pitfalls that catch most users:

* **The values are in g**, not m/s^2. The loaders multiply by 9.80665.
* **Sampling rates differ**: the fault files named ``12k_*`` are sampled at 12 kHz,
  those named ``48k_*`` and the **normal-baseline files (``Normal_*``, records
  97-100) at 48 kHz**. Mixing them without resampling shifts every frequency by 4x.
* **Files come under several names**: as the data centre serves them (``105.mat``,
  ``97.mat``), as download scripts rename them (``12k_DE_IR007_0.mat``,
  ``12k_Drive_End_IR007_0.mat``, ``IR007_0.mat``, ``Normal_0.mat``,
  ``Normal_Normal_0.mat``, ``Normal_0_48k.mat``). The sampling rate, label and motor
  load come from the name where it says them, otherwise from the record number (the
  file name's or the variables') looked up in the official numbering
  (:mod:`ballpass.datasets._cwru_table`).
* **The speed is not always stored**: the 0.028 in files carry no RPM variable (the
  loaders fill the nominal speed of the motor load, 1797/1772/1750/1730 rpm for 0-3 hp,
  and say so in ``rpm_source``). A stored speed more than 1 % off the nominal speed of
  the load is kept but flagged (``rpm_mismatch``, ``rpm_nominal``) -- unless the record
  number names another load that the speed fits: ``12k_FE_OR014@3_0`` stores 1774 rpm
  at "0 hp", but holds record 309, the 1 hp test (1772 rpm nominal), and its
  shaft-harmonic comb peaks at 1773.6 rpm; the name is wrong, so it loads as 1 hp.
  A file with neither a stored speed nor a known load (a renamed file of an unlisted
  record) gets the speed of its own shaft-harmonic comb, searched over the rig's range
  (``rpm_source = "estimated"``), when the record is long enough and the comb clear.

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

from .._validation import check_segment
from ..features._validation import check_fs
from ._cwru_table import NOMINAL_RPM, RECORDS

__all__ = [
    "STANDARD_GRAVITY",
    "CWRU_BEARINGS",
    "NOMINAL_RPM",
    "CwruRecord",
    "load_cwru_mat",
    "load_cwru",
    "load_real",
    "read_mat",
]

#: m/s^2 per g (CWRU and MFPT record acceleration in g).
STANDARD_GRAVITY = 9.80665
#: Bearing at each accelerometer position of the CWRU rig.
CWRU_BEARINGS = {"DE": "6205", "FE": "6203"}
#: A stored speed further than this from the nominal speed of the motor load is flagged.
#: 1 %: the rig's speed at one load scatters by a few rpm (0.2-0.3 %) between records.
RPM_TOLERANCE = 0.01
#: Speed range of the CWRU induction motor, rpm: 1730 (3 hp) to 1797 (0 hp) nominal,
#: below the 1800 rpm synchronous speed; a speed nothing states is searched in it,
#: widened by a few rpm of scatter on each side.
RIG_RPM_RANGE = (1720.0, 1800.0)
_KINDS = {"ir": "inner", "or": "outer", "b": "ball"}
_CLOCK_DEG = {6: 0.0, 3: 90.0, 12: 180.0}
_RATE = re.compile(r"(?:^|_)(12|48)k(?=_|$)")
_END = re.compile(r"(?:^|_)(de|fe|drive_end|fan_end)(?=_|$)")
_FAULT = re.compile(r"(?:^|_)(ir|or|b)(\d{3})(?:@(\d{1,2}))?_(\d)(?=_|$)")
_NORMAL = re.compile(r"(?:^|_)normal(?:_normal)?_(\d)(?=_|$)")
_NUMBER = re.compile(r"x?(\d{2,4})")
_VARIABLE = re.compile(r"X(\d+)_(DE|FE|BA)_time")


@dataclass(frozen=True)
class CwruRecord:
    """One channel of a CWRU recording, in SI units, with its label.

    Attributes
    ----------
    accel : ndarray of float64, shape (n_samples,)
        Acceleration, m/s^2 (converted from g).
    fs : float
        Sampling frequency, Hz.
    rpm : float
        Motor speed, rev/min: the file's, else the nominal speed of the motor load,
        else NaN (see ``rpm_source``).
    channel : str
        ``"DE"``, ``"FE"`` or ``"BA"``.
    bearing : str or None
        Catalogue name of the bearing the label is about: for a fault file the faulty
        bearing (``"6205"`` at the drive end, ``"6203"`` at the fan end) whichever
        accelerometer heard it, whose fault lines a diagnosis must look for; otherwise
        (also for a fault file whose name and record number do not say the end, e.g. a
        renamed ``IR007_0.mat``, with a warning) the bearing at that accelerometer
        (``"6205"`` at DE, ``"6203"`` at FE, None for the base).
    label : str
        ``"healthy"``, ``"inner"``, ``"outer"``, ``"ball"``, or ``"unknown"`` when
        neither the name nor the record number tells.
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
    rpm_source : str
        ``"file"`` (the file's RPM variable), ``"nominal"`` (filled from the motor
        load), ``"estimated"`` (neither: the signal's shaft-harmonic comb, searched
        over :data:`RIG_RPM_RANGE`) or ``"unknown"`` (no clear comb; ``rpm`` is NaN).
    rpm_nominal : float
        Nominal speed of the motor load, rpm (NaN when the load is unknown).
    rpm_mismatch : bool
        The stored speed differs from ``rpm_nominal`` by more than 1 %.
    record : int or None
        CWRU record number of the variables (``X105_DE_time`` -> 105).
    fault_clock : int or None
        Outer-race fault position, o'clock (3, 6 or 12).
    """

    accel: np.ndarray
    fs: float
    rpm: float
    channel: str
    bearing: str | None
    label: str
    fault_end: str | None
    fault_width_mm: float
    fault_angle_deg: float
    load_hp: int | None
    name: str
    rpm_source: str = "file"
    rpm_nominal: float = math.nan
    rpm_mismatch: bool = False
    record: int | None = None
    fault_clock: int | None = None

    def columns(self) -> dict:
        """The metadata columns of this recording (one row of ``load_cwru``'s meta)."""
        return {
            "label": self.label,
            "bearing": self.bearing,
            "fault_width_mm": self.fault_width_mm,
            "fault_size_in": self.fault_width_mm / 25.4,
            "fault_angle_deg": self.fault_angle_deg,
            "fault_clock": self.fault_clock,
            "fault_end": self.fault_end,
            "load_hp": self.load_hp,
            "rpm": self.rpm,
            "rpm_source": self.rpm_source,
            "rpm_nominal": self.rpm_nominal,
            "rpm_mismatch": self.rpm_mismatch,
            "record": self.record,
            "channel": self.channel,
            "sensor": self.channel,
            "dataset": "cwru",
        }


def _parse_name(stem: str) -> dict:
    """What a CWRU file name says: rate, faulty end, fault kind/size/position, load.

    Keys absent from the name are None. A name that is only a number (``105``,
    ``X105``) is a record number, looked up in the official table.
    """
    s = stem.lower()
    out = dict.fromkeys(("fs", "end", "kind", "size_in", "clock", "load_hp", "record"))
    number = _NUMBER.fullmatch(s)
    if number:
        out["record"] = int(number[1])
        return out
    if rate := _RATE.search(s):
        out["fs"] = 1000.0 * int(rate[1])
    if end := _END.search(s):
        out["end"] = "DE" if end[1].startswith("d") else "FE"
    if fault := _FAULT.search(s):
        out.update(kind=_KINDS[fault[1]], size_in=int(fault[2]) / 1000.0,
                   load_hp=int(fault[4]))
        out["clock"] = int(fault[3]) if fault[3] else None
    elif normal := _NORMAL.search(s):
        out.update(kind="healthy", load_hp=int(normal[1]), size_in=0.0)
    return out


def _merge_with_record(info: dict, record: int | None) -> tuple[dict, dict, list]:
    """Fill what the name leaves open from the record's entry of the CWRU table.

    Returns the merged fields, the table's fields (empty for an unknown record) and the
    keys on which the name and the table disagree (the name's value is kept).
    """
    test = RECORDS.get(record)
    table, differ = {}, []
    if test is not None:
        table = {"fs": test.fs, "end": test.end, "kind": test.kind, "size_in": test.size_in,
                 "clock": test.clock, "load_hp": test.load_hp}
        differ = [k for k, v in table.items()
                  if info[k] is not None and v is not None and info[k] != v]
        if "kind" not in differ:  # another test altogether: its rate and load do not apply
            info = {k: (v if v is not None else table.get(k)) for k, v in info.items()}
    if info["kind"] == "healthy" and info["fs"] is None:
        info["fs"] = 48_000.0  # the normal baseline is only distributed at 48 kHz
    return info, table, differ


def _fits(rpm: float, load) -> bool:
    """The speed is within :data:`RPM_TOLERANCE` of the nominal speed of ``load`` hp."""
    nominal = NOMINAL_RPM.get(load, math.nan)
    return abs(rpm - nominal) <= RPM_TOLERANCE * nominal


def _scalar(value) -> float:
    """A finite number from a MATLAB variable (a 1x1 array, a string '25'), else NaN."""
    flat = np.ravel(np.asarray(value))
    if flat.size != 1:
        return math.nan
    try:
        out = float(str(flat[0]).strip()) if flat.dtype.kind in "US" else float(flat[0])
    except (TypeError, ValueError):
        return math.nan
    return out if math.isfinite(out) else math.nan


def _loadmat(path: Path) -> dict:
    """``scipy.io.loadmat`` with its many failure modes turned into one ValueError."""
    import scipy.io

    try:
        return scipy.io.loadmat(path)
    except NotImplementedError:
        raise ValueError(f"{path.name}: MATLAB v7.3 (HDF5) files are not supported; "
                         "save it with -v7 or read it with h5py") from None
    except Exception as exc:  # scipy raises ValueError, TypeError, OSError, MatReadError...
        reason = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise ValueError(f"{path.name}: not a readable MATLAB .mat file ({reason})") from None


def _samples(value, name: str) -> np.ndarray:
    """A signal variable as a finite 1-D float64 array (raises ValueError otherwise)."""
    arr = np.asarray(value)
    if arr.dtype.kind not in "fiu" or arr.ndim > 2 or (arr.ndim == 2 and min(arr.shape) != 1):
        raise ValueError(f"{name} is not a signal vector (dtype {arr.dtype}, shape {arr.shape})")
    arr = arr.ravel().astype(np.float64)
    if arr.size < 2:
        raise ValueError(f"{name} holds {arr.size} sample(s)")
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} contains NaN or inf")
    return arr


def _path(path) -> Path:
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    return path


def _check_channel(channel) -> str:
    """A CWRU accelerometer, any case: ``"DE"`` (drive end), ``"FE"`` (fan end) or
    ``"BA"`` (base), upper case; a ValueError naming them otherwise."""
    channel = str(channel).upper()
    if channel not in ("DE", "FE", "BA"):
        raise ValueError(f"channel must be 'DE', 'FE' or 'BA', got {channel!r}")
    return channel

def load_cwru_mat(path, channel: str = "DE", fs: float | None = None) -> CwruRecord:
    """Load one channel of a CWRU ``.mat`` file in m/s^2, with fs, rpm and label.

    Parameters
    ----------
    path : str or os.PathLike
        A CWRU file under any of its usual names, e.g. ``12k_DE_OR007@6_0.mat``,
        ``Normal_0_48k.mat``, ``Normal_Normal_0.mat``, ``105.mat`` or ``97.mat``.
    channel : {"DE", "FE", "BA"}, optional
        Accelerometer: drive end (default), fan end or base.
    fs : float, optional
        Sampling frequency, Hz. Default: from the file name (``12k`` -> 12 kHz,
        ``48k`` and the normal baseline -> 48 kHz), else from the record number. A
        value contradicting the name warns.

    Returns
    -------
    CwruRecord

    Raises
    ------
    ValueError
        Unreadable file, channel absent, or fs neither given nor inferable.
    FileNotFoundError
        No such file.

    Examples
    --------
    >>> from ballpass.datasets.real import load_cwru_mat
    >>> rec = load_cwru_mat("12k_DE_OR007@6_0.mat")                  # doctest: +SKIP
    >>> rec.fs, rec.rpm, rec.rpm_source, rec.label                    # doctest: +SKIP
    (12000.0, 1796.0, 'file', 'outer')
    """
    channel = _check_channel(channel)
    if fs is not None:
        fs = check_fs(fs)
    path = _path(path)
    data = _loadmat(path)
    variables = {m[0]: (int(m[1]), m[2]) for k in data if (m := _VARIABLE.fullmatch(k))}
    speeds = sorted(k for k in data if k.endswith("RPM"))
    signals = sorted(k for k, (_, ch) in variables.items() if ch == channel)
    if not signals:
        found = sorted({ch for _, ch in variables.values()})
        raise ValueError(f"{path.name} has no {channel} channel (variables X<number>_"
                         f"{channel}_time); it has {found or 'no CWRU signal variables'}")
    # Some files carry variables of two records; prefer the one the RPM belongs to.
    prefix = speeds[0][: -len("RPM")] if speeds else None
    key = next((k for k in signals if k.startswith(f"{prefix}_")), signals[0])
    record = variables[key][0]
    info = _parse_name(path.stem)
    number = info["record"] or record
    info, table, differ = _merge_with_record(info, number)
    stored = _scalar(data[f"{prefix}RPM"]) if speeds else math.nan
    if speeds and not stored > 0:
        warnings.warn(f"{path.name}: stored speed {prefix}RPM is not a positive number; "
                      "ignored", stacklevel=2)
        stored = math.nan
    if "load_hp" in differ and _fits(stored, table["load_hp"]) \
            and not _fits(stored, info["load_hp"]):
        # the record number and the stored speed agree against the name: a misnamed file
        warnings.warn(f"{path.name}: the name says {info['load_hp']} hp, but its variables "
                      f"are CWRU record {number}, the {table['load_hp']} hp record, and its "
                      f"stored {stored:g} rpm fits {table['load_hp']} hp "
                      f"({NOMINAL_RPM[table['load_hp']]:g} rpm nominal); using "
                      f"{table['load_hp']} hp", stacklevel=2)
        info["load_hp"] = table["load_hp"]
        differ.remove("load_hp")
    if differ:
        said = ", ".join(f"{k}={info[k]!r}" for k in differ)
        listed = ", ".join(f"{k}={table[k]!r}" for k in differ)
        warnings.warn(f"{path.name}: the name says {said}, but its variables are CWRU record "
                      f"{number}, which the data centre lists as {listed}; using the name",
                      stacklevel=2)
    if fs is None:
        if info["fs"] is None:
            raise ValueError(
                f"cannot infer fs from the file name {path.name!r} or its record number "
                f"{record}; pass fs (Hz): CWRU fault files are 12000 or 48000, the normal "
                "baseline 48000"
            )
        fs = info["fs"]
    elif info["fs"] is not None and fs != info["fs"]:
        warnings.warn(f"{path.name}: fs={fs:g} Hz given but the file name says "
                      f"{info['fs']:g} Hz", stacklevel=2)
    accel = _samples(data[key], f"{path.name}: {key}") * STANDARD_GRAVITY
    load = info["load_hp"]
    nominal = NOMINAL_RPM.get(load, math.nan)
    if stored > 0:
        rpm, source = stored, "file"
    elif math.isfinite(nominal):
        rpm, source = nominal, "nominal"
    else:
        rpm, source = _speed_from_signal(accel, float(fs), path.name)
    mismatch = source == "file" and math.isfinite(nominal) and not _fits(rpm, load)
    if mismatch:
        warnings.warn(f"{path.name}: stored speed {rpm:g} rpm differs from the nominal "
                      f"{nominal:g} rpm at {load} hp by {100 * abs(rpm / nominal - 1):.1f} %; "
                      "kept, flagged in rpm_mismatch", stacklevel=2)
    kind = info["kind"] or "unknown"
    faulty = kind in _KINDS.values()
    if faulty and info["end"] is None:
        warnings.warn(f"{path.name}: neither the name nor the record number {record} says "
                      "which bearing (drive or fan end) is faulty; the fault is read as the "
                      f"{channel} accelerometer's bearing's", stacklevel=2)
    return CwruRecord(
        accel=accel,
        fs=float(fs),
        rpm=float(rpm),
        channel=channel,
        bearing=(CWRU_BEARINGS[info["end"]] if faulty and info["end"] is not None
                 else CWRU_BEARINGS.get(channel)),
        label=kind,
        fault_end=info["end"] if faulty else None,
        fault_width_mm=info["size_in"] * 25.4 if faulty else math.nan,
        fault_angle_deg=_CLOCK_DEG.get(info["clock"], math.nan),
        load_hp=load,
        name=path.stem,
        rpm_source=source,
        rpm_nominal=nominal,
        rpm_mismatch=bool(mismatch),
        record=record,
        fault_clock=info["clock"] if kind == "outer" else None,
    )


def _speed_from_signal(accel: np.ndarray, fs: float, name: str) -> tuple[float, str]:
    """Speed of a record that states none, from its shaft-harmonic comb over the rig's
    range (:data:`RIG_RPM_RANGE`): ``(rpm, "estimated")``, or ``(nan, "unknown")`` when
    the record is shorter than the speed check needs or its comb is not clear."""
    from ..diagnose.evidence import MIN_COMB_DB, SPEED_CHECK_S
    from ..diagnose.speed import estimate_shaft_speed

    lo, hi = RIG_RPM_RANGE
    centre, tolerance = 0.5 * (lo + hi), 0.5 * (hi - lo) / (0.5 * (lo + hi))
    if accel.size >= SPEED_CHECK_S * fs:
        found, comb, _ = estimate_shaft_speed(accel[None, :], fs, np.array([centre]),
                                              tolerance=tolerance)
        if comb[0] >= MIN_COMB_DB:
            warnings.warn(f"{name}: no stored speed and no motor load in the name; "
                          f"estimated {found[0]:.1f} rpm from the signal's shaft-harmonic "
                          f"comb ({comb[0]:.0f} dB above the background; rpm_source "
                          "'estimated')", stacklevel=3)
            return float(found[0]), "estimated"
        why = f"its shaft-harmonic comb stands only {comb[0]:.1f} dB above the background"
    else:
        why = f"the record is shorter than the {SPEED_CHECK_S:g} s a speed estimate needs"
    warnings.warn(f"{name}: no stored speed and no motor load in the name, and {why}; rpm "
                  "is NaN (pass it to the diagnoser yourself)", stacklevel=3)
    return math.nan, "unknown"


def mat_paths(paths) -> list[Path]:
    """The ``.mat`` files of ``paths`` (files, or folders whose ``*.mat`` are all taken)."""
    if isinstance(paths, (str, Path)):
        paths = [paths]
    if not isinstance(paths, Iterable):
        raise TypeError(f"paths must be a path or an iterable of paths, got "
                        f"{type(paths).__name__}")
    out: list[Path] = []
    for p in map(Path, paths):
        if p.is_dir():
            out.extend(sorted(p.glob("*.mat")))
        elif p.exists():
            out.append(p)
        else:
            raise FileNotFoundError(f"no such file or folder: {p}")
    if not out:
        raise ValueError(f"no .mat files in {', '.join(map(str, paths))}")
    return out


def segment_records(records, fs: float, length: int):
    """Resample records to ``fs`` and cut them into segments of ``length`` samples.

    Parameters
    ----------
    records : iterable of (path, record)
        ``record`` has ``accel`` (m/s^2), ``fs`` (Hz), ``name`` and ``columns()``.
    fs : float
        Output sampling frequency, Hz.
    length : int
        Samples per segment; the remainder of each record is dropped.

    Returns
    -------
    X : ndarray of float32, shape (n_segments, length)
    meta : pandas.DataFrame
        ``record.columns()`` plus ``segment``, ``start_s``, ``duration_s``, ``fs``,
        ``source_fs``, ``group`` (the record's own ``group`` column, else the file name)
        and ``file``.
    """
    import pandas as pd
    import scipy.signal

    segments, rows = [], []
    for path, rec in records:
        # exact for the integer rates of real files (12000/48828 = 1000/4069, where a
        # coarse approximation would shift every frequency by 8 ppm or more)
        ratio = (Fraction(float(fs)) / Fraction(float(rec.fs))).limit_denominator(100_000)
        x = rec.accel
        if ratio != 1:
            x = scipy.signal.resample_poly(x, ratio.numerator, ratio.denominator)
        n = len(x) // length
        if n == 0:
            warnings.warn(f"skipped {path.name}: {len(x) / fs:.3g} s is shorter than one "
                          f"segment of {length / fs:g} s", stacklevel=3)
            continue
        segments.append(x[: n * length].reshape(n, length))
        columns = rec.columns()
        rows.extend(
            columns | {"segment": k, "start_s": k * length / fs, "duration_s": length / fs,
                       "fs": float(fs), "source_fs": rec.fs,
                       "group": columns.get("group", rec.name),
                       "file": str(path)}
            for k in range(n)
        )
    if not segments:
        raise ValueError("no recording could be loaded (see the warnings above)")
    return np.concatenate(segments).astype(np.float32), pd.DataFrame(rows)


def read_all(paths, read) -> list:
    """``[(path, read(path))]`` over the .mat files, skipping unreadable ones with a warning."""
    out = []
    for path in mat_paths(paths):
        try:
            out.append((path, read(path)))
        except (ValueError, OSError) as exc:
            reason = str(exc).removeprefix(f"{path.name}: ")
            warnings.warn(f"skipped {path.name}: {reason}", stacklevel=3)
    return out


def load_cwru(paths, fs: float = 12_000.0, segment_s: float = 1.0, channel: str = "DE",
              *, source_fs: float | None = None):
    """CWRU recordings as equal segments at one sampling rate, like ``datasets.load``.

    Each file is loaded with :func:`load_cwru_mat` (g -> m/s^2, fs from the name or
    the record number), resampled to ``fs`` with :func:`scipy.signal.resample_poly`
    (the 48 kHz files come down to 12 kHz by default) and cut into non-overlapping
    segments of ``segment_s``; the remainder is dropped. A file that cannot be read
    (corrupt, truncated, no such channel, unknown rate) is skipped with a warning
    naming it and why. Segments of one file share their ``group`` (the file name):
    split train/test by group, never by segment, or segments of one recording leak
    across folds.

    Parameters
    ----------
    paths : str, os.PathLike or iterable of them
        ``.mat`` files, or folders whose ``*.mat`` files are all taken.
    fs : float, optional
        Output sampling frequency, Hz (default 12000).
    segment_s : float, optional
        Segment length, s (default 1.0); at least 64 samples at ``fs``.
    channel : {"DE", "FE", "BA"}, optional
        Accelerometer (default ``"DE"``).
    source_fs : float, optional
        Sampling rate of files whose name and record number do not tell it, Hz.

    Returns
    -------
    X : ndarray of float32, shape (n_segments, round(segment_s * fs))
        Acceleration, m/s^2.
    meta : pandas.DataFrame
        One row per segment: ``file``, ``group``, ``segment``, ``label``, ``fs``,
        ``source_fs``, ``rpm``, ``rpm_source`` ("file", "nominal", "estimated";
        "unknown" with rpm NaN), ``rpm_nominal``, ``rpm_mismatch``, ``load_hp``, ``bearing``,
        ``channel`` (also as ``sensor``), ``fault_end``, ``fault_width_mm``,
        ``fault_size_in``, ``fault_clock``, ``fault_angle_deg``, ``record``,
        ``start_s``, ``duration_s``, ``dataset``.

    Raises
    ------
    ValueError
        Bad arguments, or no file could be loaded.

    Examples
    --------
    >>> from ballpass.datasets import load_cwru
    >>> X, meta = load_cwru("/path/to/cwru", fs=12_000, segment_s=1.0)   # doctest: +SKIP
    >>> meta.groupby(["label", "rpm_source"]).size()                     # doctest: +SKIP
    """
    fs = check_fs(fs)
    length = check_segment(segment_s, fs)
    channel = _check_channel(channel)
    if source_fs is not None:
        source_fs = check_fs(source_fs)

    def read(path):
        try:
            return load_cwru_mat(path, channel=channel)
        except ValueError as exc:
            if source_fs is None or not str(exc).startswith("cannot infer fs"):
                raise
            return load_cwru_mat(path, channel=channel, fs=source_fs)

    return segment_records(read_all(paths, read), fs, length)


def _mat_variables(path: Path) -> list[str] | None:
    """Names of the variables of a ``.mat`` file; None when it cannot be read."""
    import scipy.io

    try:
        return [name for name, _, _ in scipy.io.whosmat(path)]
    except Exception:  # unreadable: let the CWRU reader report it
        return None


def read_mat(path, channel: str = "DE", fs: float | None = None):
    """One real recording from a ``.mat`` file, CWRU or MFPT (told apart by content).

    Returns a :class:`CwruRecord` or :class:`ballpass.datasets.mfpt.MfptRecord`; both
    have ``accel`` (m/s^2), ``fs``, ``rpm``, ``label``, ``bearing``, ``name`` and
    ``columns()``. ``channel`` applies to CWRU files, ``fs`` overrides their rate.
    """
    path = _path(path)
    names = _mat_variables(path)
    if names is not None and "bearing" in names:
        from .mfpt import load_mfpt_mat

        return load_mfpt_mat(path)
    if names is not None and not any(_VARIABLE.fullmatch(name) for name in names):
        raise ValueError(not_cwru_nor_mfpt(path, names))
    return load_cwru_mat(path, channel=channel, fs=fs)


def not_cwru_nor_mfpt(path: Path, names: list[str]) -> str:
    """The message for a .mat file whose variables are neither CWRU's nor MFPT's."""
    held = ", ".join(names[:5]) + (", ..." if len(names) > 5 else "") or "nothing"
    return (f"{path.name} is neither a CWRU recording (variables X<number>_DE_time, "
            f"_FE_time, _BA_time) nor an MFPT one (a struct `bearing`); it holds {held}")


def load_real(paths, fs: float, segment_s: float = 1.0, channel: str = "DE"):
    """CWRU and/or MFPT ``.mat`` recordings as segments at one rate (see :func:`load_cwru`).

    Each file is read by :func:`read_mat` (its kind told by content), resampled to
    ``fs`` and segmented; unreadable files are skipped with a warning.

    Examples
    --------
    >>> from ballpass.datasets.real import load_real
    >>> X, meta = load_real("/path/to/mfpt", fs=48_828)                  # doctest: +SKIP
    """
    fs = check_fs(fs)
    length = check_segment(segment_s, fs)
    return segment_records(read_all(paths, lambda p: read_mat(p, channel=channel)), fs, length)
