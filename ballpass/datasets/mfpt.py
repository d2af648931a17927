"""Loader for the MFPT bearing fault data set (Society for Machinery Failure Prevention Technology).

Each ``.mat`` file holds a struct ``bearing`` with fields ``gs`` (acceleration, g),
``sr`` (sampling rate, Hz), ``rate`` (shaft speed, Hz) and ``load`` (radial load, lbs;
stored as a number or a string), and the scalars BPFO, BPFI, FTF and BSF. Sampling
rates: 97 656 Hz for the baseline and the three constant-load outer-race files
(``baseline_1..3``, ``OuterRaceFault_1..3``), 48 828 Hz for the variable-load files
(``OuterRaceFault_vload_1..7``, ``InnerRaceFault_vload_1..7``). The label comes from
the name: ``baseline*`` -> healthy, ``*InnerRace*`` -> inner, ``*OuterRace*`` -> outer.

The bearing is the catalogue's ``"MFPT-NICE"`` (8 elements of 0.235 in on a 1.245 in
pitch circle): compute its frequencies from that geometry. The FTF stored in the files
(14.8375 Hz at 25 Hz) contradicts their own BPFO (81.125 Hz = 8 x 10.14 Hz); the
geometry gives FTF 10.14 Hz.

References
----------
.. [1] E. Bechhoefer, "Condition Based Maintenance Fault Database for Testing of
   Diagnostic and Prognostics Algorithms", MFPT data set (2013).
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass

import numpy as np

from .._validation import check_segment
from ..features._validation import check_fs
from .real import STANDARD_GRAVITY, _loadmat, _path, _samples, _scalar, read_all, segment_records

__all__ = ["MFPT_BEARING", "MfptRecord", "load_mfpt_mat", "load_mfpt"]

#: Catalogue name of the MFPT test bearing.
MFPT_BEARING = "MFPT-NICE"
#: N per lbf.
_LBF = 4.4482216152605
_LABELS = (("baseline", "healthy"), ("innerrace", "inner"), ("outerrace", "outer"))


@dataclass(frozen=True)
class MfptRecord:
    """One MFPT recording in SI units, with its label.

    Attributes
    ----------
    accel : ndarray of float64, shape (n_samples,)
        Acceleration, m/s^2 (converted from g).
    fs : float
        Sampling frequency, Hz (``bearing.sr``).
    rpm : float
        Shaft speed, rev/min (``60 * bearing.rate``).
    load_lbs : float
        Radial load, lbs (``bearing.load``; NaN when absent).
    label : str
        ``"healthy"``, ``"inner"``, ``"outer"`` or ``"unknown"`` (from the name).
    name : str
        File name without extension.
    bearing : str
        ``"MFPT-NICE"``.
    """

    accel: np.ndarray
    fs: float
    rpm: float
    load_lbs: float
    label: str
    name: str
    bearing: str = MFPT_BEARING

    def columns(self) -> dict:
        """The metadata columns of this recording (one row of ``load_mfpt``'s meta)."""
        return {
            "label": self.label,
            "bearing": self.bearing,
            "fault_width_mm": math.nan,
            "fault_angle_deg": math.nan,
            "load_lbs": self.load_lbs,
            "radial_load_n": self.load_lbs * _LBF,
            "rpm": self.rpm,
            "rpm_source": "file",
            "channel": "gs",
            "sensor": "gs",
            "dataset": "mfpt",
        }


def _label(stem: str) -> str:
    key = re.sub(r"[^a-z]", "", stem.lower())
    return next((label for word, label in _LABELS if word in key), "unknown")


def load_mfpt_mat(path) -> MfptRecord:
    """Load one MFPT ``.mat`` file in m/s^2, with fs, rpm, load and label.

    Parameters
    ----------
    path : str or os.PathLike
        An MFPT file, e.g. ``OuterRaceFault_vload_1.mat`` or ``baseline_1.mat``.

    Returns
    -------
    MfptRecord

    Raises
    ------
    ValueError
        Unreadable file, no ``bearing`` struct, or a field missing or invalid.
    FileNotFoundError
        No such file.

    Examples
    --------
    >>> from ballpass.datasets.mfpt import load_mfpt_mat
    >>> rec = load_mfpt_mat("InnerRaceFault_vload_1.mat")          # doctest: +SKIP
    >>> rec.fs, rec.rpm, rec.load_lbs, rec.label                    # doctest: +SKIP
    (48828.0, 1500.0, 0.0, 'inner')
    """
    path = _path(path)
    data = _loadmat(path)
    struct = data.get("bearing")
    names = getattr(getattr(struct, "dtype", None), "names", None) or ()
    missing = [f for f in ("gs", "sr", "rate") if f not in names]
    if missing:
        raise ValueError(f"{path.name}: not an MFPT file (needs a struct 'bearing' with "
                         f"fields gs, sr, rate; missing {missing})")
    fields = struct.ravel()[0]
    fs, rate = _scalar(fields["sr"]), _scalar(fields["rate"])
    if not fs > 0:
        raise ValueError(f"{path.name}: bearing.sr is not a positive sampling rate")
    if not rate > 0:
        raise ValueError(f"{path.name}: bearing.rate is not a positive shaft speed")
    load = _scalar(fields["load"]) if "load" in names else math.nan
    label = _label(path.stem)
    if label == "unknown":
        warnings.warn(f"{path.name}: the name does not say baseline, InnerRace or "
                      "OuterRace; label 'unknown'", stacklevel=2)
    return MfptRecord(
        accel=_samples(fields["gs"], f"{path.name}: bearing.gs") * STANDARD_GRAVITY,
        fs=fs,
        rpm=60.0 * rate,
        load_lbs=load,
        label=label,
        name=path.stem,
    )


def load_mfpt(paths, fs: float | None = None, segment_s: float = 1.0):
    """MFPT recordings as equal segments at one sampling rate, like ``datasets.load``.

    Files that cannot be read are skipped with a warning naming them. Segments of one
    file share their ``group`` (the file name).

    Parameters
    ----------
    paths : str, os.PathLike or iterable of them
        ``.mat`` files, or folders whose ``*.mat`` files are all taken.
    fs : float, optional
        Output sampling frequency, Hz. Default: the files' own rate when they share
        one; files of both rates (48 828 and 97 656 Hz) need ``fs`` (each is then
        resampled with :func:`scipy.signal.resample_poly`; 48828 halves the baseline).
    segment_s : float, optional
        Segment length, s (default 1.0).

    Returns
    -------
    X : ndarray of float32, shape (n_segments, round(segment_s * fs))
        Acceleration, m/s^2.
    meta : pandas.DataFrame
        One row per segment: ``file``, ``group``, ``segment``, ``label``, ``fs``,
        ``source_fs``, ``rpm``, ``rpm_source`` ("file"), ``load_lbs``,
        ``radial_load_n``, ``bearing`` ("MFPT-NICE"), ``channel``/``sensor``,
        ``fault_width_mm`` and ``fault_angle_deg`` (NaN: not given), ``start_s``,
        ``duration_s``, ``dataset``.

    Raises
    ------
    ValueError
        Bad arguments, files of several rates without ``fs``, or no readable file.

    Examples
    --------
    >>> from ballpass.datasets import load_mfpt
    >>> X, meta = load_mfpt("/path/to/mfpt", fs=48_828, segment_s=1.0)  # doctest: +SKIP
    >>> meta.groupby("label").size()                                    # doctest: +SKIP
    """
    if fs is not None:
        fs = check_fs(fs)
    records = read_all(paths, load_mfpt_mat)
    if fs is None:
        rates = sorted({rec.fs for _, rec in records})
        if len(rates) > 1:
            raise ValueError(f"the MFPT files have sampling rates {rates} Hz; pass fs to "
                             f"resample them to one rate (e.g. fs={rates[0]:g})")
        fs = rates[0] if rates else 48_828.0
    return segment_records(records, fs, check_segment(segment_s, fs))
