"""One recording from a file in any common format: what the ``ballpass`` command and
:func:`ballpass.datasets.load_manifest` read.

Formats, chosen by the file extension:

``.npz``, ``.parquet``, and ``.csv`` with a ``# fs=`` line or a ``t_s`` column
    Signal files written by ``ballpass simulate`` (:mod:`ballpass.signalio`): they
    state their rate, their channels and often the speed, bearing and label.
``.csv`` otherwise
    A plain table of numbers, with or without a header line, separated by commas,
    semicolons or tabs: one numeric column, or the one ``column`` names (a header name,
    or the column's index, from 0, in a file without a header). ``fs`` must be given.
``.npy``
    A NumPy array: shape ``(n_samples,)``, or ``(n_channels, n_samples)`` (one recording
    per row). ``fs`` must be given.
``.wav``
    PCM or float WAV at its own rate; one recording per channel. Integer samples are
    divided by the full scale of their type (32768 for 16-bit), so they read in
    fractions of full scale; the sensor's calibration is not in the file.
``.mat``
    A CWRU Bearing Data Center or MFPT recording (told apart by content, see
    :mod:`ballpass.datasets.real`), or any MATLAB (v5-v7) file: its only variable, or
    the one ``variable`` names (then ``fs`` must be given).

Samples are taken in the units stored (m/s^2 for ballpass files, converted from g for
CWRU and MFPT files, as stored otherwise): the envelope diagnoser's evidence is a ratio
in dB and does not depend on them, scale-bearing features such as ``rms`` do.

A ``fs`` that contradicts a rate the file states (a WAV header, a signal file, an MFPT
struct) raises a :class:`RecordingMismatch`; so do a ``column``, ``variable`` or
``channel`` the file does not hold, and a file that holds several signals when nothing
says which one. A file that cannot be read at all (missing, corrupt, NaN samples)
raises a plain ``ValueError`` or ``OSError``: a manifest skips such a row with a
warning, but stops at a mismatch, which is a mistake in the table.

Examples
--------
>>> import numpy as np, tempfile, pathlib
>>> from ballpass.datasets.recordings import read_recording
>>> path = pathlib.Path(tempfile.mkdtemp()) / "rec.csv"
>>> _ = path.write_text("accel\\n" + "\\n".join(map(str, np.sin(np.arange(100)))))
>>> rec, = read_recording(path, fs=12_000)
>>> rec.accel.shape, rec.fs, rec.name, rec.channel
((100,), 12000.0, 'rec', 'accel')
"""

from __future__ import annotations

import csv
import math
import struct
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..features._validation import check_fs
from .real import _samples

__all__ = ["RECORDING_SUFFIXES", "Recording", "RecordingMismatch", "check_recording",
           "from_real", "read_recording"]

#: File extensions :func:`read_recording` reads.
RECORDING_SUFFIXES = (".npz", ".parquet", ".csv", ".npy", ".wav", ".mat")
_DELIMITERS = (",", ";", "\t")
#: Rows of a plain CSV file that :func:`check_recording` reads.
_PROBE_ROWS = 16
#: What a file that does not state its rate asks for: the rate, as the command-line
#: option and as the manifest column.
_GIVE_FS = "give fs > 0 Hz (--fs / fs)"


class RecordingMismatch(ValueError):
    """What was asked of a file does not fit it (a rate it contradicts, a column,
    variable or channel it lacks, several signals and none chosen)."""


@dataclass(frozen=True)
class Recording:
    """One signal of a file, with what is known about it.

    Attributes
    ----------
    accel : ndarray of float64, shape (n_samples,)
        Samples, in the units stored (m/s^2 for ballpass, CWRU and MFPT files).
    fs : float
        Sampling frequency, Hz.
    name : str
        File name without extension.
    channel : str
        Channel, column or variable the samples come from.
    rpm : float
        Shaft speed, rev/min, when the file states it (else NaN).
    bearing : str or None
        Catalogue name of the bearing, when the file states it.
    label : str
        ``"healthy"``, ``"inner"``, ``"outer"``, ``"ball"`` when the file states it,
        else ``"unknown"``.
    info : dict
        Further metadata columns (for CWRU and MFPT files, their loaders' columns).

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.datasets.recordings import Recording
    >>> Recording(np.zeros(4), 12_000.0, "rec", "accel", rpm=1797.0).columns()["rpm"]
    1797.0
    """

    accel: np.ndarray
    fs: float
    name: str
    channel: str
    rpm: float = math.nan
    bearing: str | None = None
    label: str = "unknown"
    info: dict = field(default_factory=dict)

    def columns(self) -> dict:
        """The metadata columns of this recording (one row of a loader's meta)."""
        return self.info | {"label": self.label, "bearing": self.bearing, "rpm": self.rpm,
                            "channel": self.channel, "sensor": self.channel}


def read_recording(path, *, fs=None, column=None, variable=None, channel=None,
                   mat_channel: str = "DE") -> list[Recording]:
    """The recording(s) of one file, as :class:`Recording` objects.

    Parameters
    ----------
    path : str or os.PathLike
        A file with one of :data:`RECORDING_SUFFIXES` (see the module's docstring).
    fs : float, optional
        Sampling frequency, Hz: required for plain ``.csv``, ``.npy`` and generic
        ``.mat`` files; must agree with the rate a file states (WAV, signal files,
        MFPT); overrides the rate a CWRU file's name implies (with a warning).
    column : str, optional
        Column of a plain CSV file (a header name, or an index from 0).
    variable : str, optional
        Variable of a generic ``.mat`` file (default: its only variable).
    channel : str or int, optional
        The one channel to keep: a channel name of a signal file, an index (from 0) of
        a WAV channel or an ``.npy`` row, ``"DE"``/``"FE"``/``"BA"`` of a CWRU file.
        Default: every channel (of a CWRU file: ``mat_channel``).
    mat_channel : {"DE", "FE", "BA"}, optional
        CWRU accelerometer when ``channel`` is not given (default ``"DE"``).

    Returns
    -------
    list of Recording
        One per channel kept (plain CSV, generic ``.mat``, CWRU and MFPT: one).

    Raises
    ------
    RecordingMismatch
        ``fs`` contradicts the file, or ``column``/``variable``/``channel`` does not
        fit it, or several numeric columns and no ``column``.
    ValueError
        Unsupported extension, ``fs`` missing where the file has none, an unreadable
        file or samples that are not finite numbers.
    FileNotFoundError
        No such file.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from ballpass.datasets.recordings import read_recording
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "rec.npy"
    >>> np.save(path, np.ones((2, 50)))
    >>> [r.channel for r in read_recording(path, fs=1000.0)]
    ['0', '1']
    >>> read_recording(path)
    Traceback (most recent call last):
        ...
    ValueError: rec.npy: a .npy file does not state its sampling rate; give fs > 0 Hz (--fs / fs)
    """
    return _recordings(Path(path), fs, column, variable, channel, mat_channel, probe=False)


def check_recording(path, *, fs=None, column=None, variable=None, channel=None,
                    mat_channel: str = "DE") -> list[str] | None:
    """What :func:`read_recording` would refuse in a file, found from its header only.

    Reads what a file says about itself without its samples where that is cheap
    (the columns and first rows of a plain CSV, the shape of a ``.npy`` array, a WAV
    header, the variable names of a ``.mat`` file), so that a table of many recordings
    can be checked whole before any of them is read. Signal files written by ballpass
    and MFPT files are left to :func:`read_recording`.

    Parameters
    ----------
    path, fs, column, variable, channel, mat_channel
        As for :func:`read_recording`.

    Returns
    -------
    list of str or None
        The names of the channels the file would give, when the header tells them.

    Raises
    ------
    RecordingMismatch, ValueError, FileNotFoundError
        As :func:`read_recording` would for the same file.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from ballpass.datasets.recordings import check_recording
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "rec.npy"
    >>> np.save(path, np.ones((3, 50)))
    >>> check_recording(path, fs=1000.0)
    ['0', '1', '2']
    >>> check_recording(path, fs=1000.0, channel=5)
    Traceback (most recent call last):
        ...
    ballpass.datasets.recordings.RecordingMismatch: rec.npy: no channel '5'; it has 0, 1, 2
    """
    return _recordings(Path(path), fs, column, variable, channel, mat_channel, probe=True)


def _recordings(path: Path, fs, column, variable, channel, mat_channel: str, probe: bool):
    """:func:`read_recording` (``probe`` False) or :func:`check_recording` (True)."""
    suffix = path.suffix.lower()
    if suffix not in RECORDING_SUFFIXES:
        raise ValueError(f"{path.name}: a recording must be a "
                         f"{', '.join(RECORDING_SUFFIXES[:-1])} or {RECORDING_SUFFIXES[-1]} "
                         "file")
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    if fs is not None:
        fs = check_fs(fs)
    if suffix == ".mat":
        found = _read_mat(path, fs, variable, channel, mat_channel, probe)
        return found if probe else [found]
    if suffix == ".csv" and not _is_signal_csv(path):
        found = _read_plain_csv(path, fs, column, nrows=_PROBE_ROWS if probe else None)
        return [found.channel] if probe else [found]
    if suffix == ".npy":
        names, rows, stated = _read_npy(path, mmap=probe)
    elif suffix == ".wav":
        header = _read_wav(path, mmap=probe)
        if header is None:  # a WAV that cannot be mapped: read_recording decides
            return None
        names, rows, stated = header
    elif probe:
        return None  # ballpass signal files: read_recording decides
    else:
        return _read_signal_file(path, fs, channel)
    if stated is None:
        stated = _rate_given(path, fs, f"{suffix} file")
    _check_rate(path, fs, stated)
    picked = _pick(path, names, rows, channel)
    if probe:
        return [name for name, _ in picked]
    return [Recording(_samples(row, f"{path.name}: channel {name}"), float(stated), path.stem,
                      name)
            for name, row in picked]


def from_real(rec) -> Recording:
    """A :class:`Recording` of a CWRU or MFPT record (its loader's columns in ``info``)."""
    columns = rec.columns()
    return Recording(rec.accel, float(rec.fs), rec.name, str(columns["channel"]),
                     rpm=float(rec.rpm), bearing=rec.bearing, label=rec.label, info=columns)


def _rate_given(path: Path, fs, what: str):
    """``fs`` (Hz) for a ``what`` (e.g. ``"plain .csv file"``) that does not state its
    sampling rate; a ValueError asking for it when None."""
    if fs is None:
        raise ValueError(f"{path.name}: a {what} does not state its sampling rate; "
                         + _GIVE_FS)
    return fs


def _check_rate(path: Path, fs, stated: float) -> None:
    """A RecordingMismatch when the given ``fs`` contradicts the file's own rate."""
    if fs is not None and not math.isclose(fs, stated, rel_tol=1e-9):
        raise RecordingMismatch(f"{path.name}: fs {fs:g} Hz given, but the file states "
                                f"{stated:g} Hz")


def _pick(path: Path, names: list[str], rows, channel) -> list:
    """``[(name, row)]``: every channel, or the one ``channel`` names (a name or index)."""
    if channel is None:
        return list(zip(names, rows, strict=True))
    key = str(channel)
    if key not in names:
        raise RecordingMismatch(f"{path.name}: no channel {key!r}; it has "
                                f"{', '.join(names)}")
    return [(key, rows[names.index(key)])]


def _read_signal_file(path: Path, fs, channel) -> list[Recording]:
    from ..signalio import read_signal

    sig = read_signal(path)
    _check_rate(path, fs, sig.fs)
    label = sig.meta.get("label")
    rpm = sig.meta.get("rpm")
    return [Recording(
        np.asarray(row, dtype=np.float64), float(sig.fs), path.stem, name,
        rpm=float(rpm) if rpm is not None else math.nan,
        bearing=sig.meta.get("bearing"),
        label=label if isinstance(label, str) and label else "unknown",
    ) for name, row in _pick(path, list(sig.channels), sig.accel, channel)]


def _is_signal_csv(path: Path) -> bool:
    """A CSV written by :mod:`ballpass.signalio`: ``# fs=`` comment or ``t_s`` column."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            for line in fh:
                if not line.startswith("#"):
                    return line.strip().split(",")[0] == "t_s"
                if line[1:].strip().startswith("fs="):
                    return True
    except (OSError, UnicodeDecodeError):
        return False  # the plain reader says what is wrong
    return False


def _read_plain_csv(path: Path, fs, column, nrows: int | None = None) -> Recording:
    """One numeric column of a plain CSV file (see :func:`read_recording`); its first
    ``nrows`` rows only when given."""
    import pandas as pd

    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:
            lines = [line for line in fh if line.strip() and not line.startswith("#")][:2]
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path.name}: not a readable text file ({exc})") from None
    if not lines:
        raise ValueError(f"{path.name}: the file holds no rows")
    sep, decimal, header = _csv_layout(lines)
    data = lines[1] if header == 0 and len(lines) > 1 else lines[0]
    names, values = (len(next(csv.reader([line], delimiter=sep))) for line in (lines[0], data))
    if names != values:  # pandas would take the surplus first values as the row index
        raise RecordingMismatch(f"{path.name}: the header names {names} column(s) but the "
                                f"first row holds {values} value(s) between {sep!r}; save "
                                "it with one separator per column")
    try:
        frame = pd.read_csv(path, sep=sep, decimal=decimal, header=header, comment="#",
                            nrows=nrows, encoding="utf-8-sig")
    except (ValueError, OSError) as exc:
        reason = str(exc).splitlines()[0][:120]
        raise ValueError(f"{path.name}: not a readable CSV file ({reason})") from None
    frame.columns = [str(c).strip() for c in frame.columns]
    numeric = [c for c in frame.columns if pd.api.types.is_numeric_dtype(frame[c])]
    what = "columns" if header == 0 else "columns (no header: numbered from 0)"
    if column is None:
        if len(numeric) != 1:
            found = ", ".join(numeric) if numeric else "none"
            raise RecordingMismatch(f"{path.name}: {len(numeric)} numeric {what} ({found}); "
                                    "name the signal's column (--column / column)")
        column = numeric[0]
    column = str(column)
    if column not in frame.columns:
        raise RecordingMismatch(f"{path.name}: no column {column!r}; its {what}: "
                                f"{', '.join(frame.columns)}")
    if column not in numeric:
        raise RecordingMismatch(f"{path.name}: column {column!r} is not numeric")
    fs = _rate_given(path, fs, "plain .csv file")
    return Recording(_samples(frame[column].to_numpy(), f"{path.name}: column {column!r}"),
                     fs, path.stem, column)


def _csv_layout(lines: list[str]) -> tuple[str, str, int | None]:
    """Separator, decimal mark and header row (0, or None) of a plain CSV file from its
    first one or two lines. Values are separated by commas, semicolons or tabs; with
    semicolons or tabs, or one column under a header, a comma in the values is a
    decimal comma (spreadsheets in many locales write ``-3,6;0,5``)."""
    first = lines[0]
    sep = next((d for d in _DELIMITERS if d in first), None)
    header = None if all(_is_number(v.replace(",", ".")) for v in
                         first.strip().split(sep or ",")) else 0
    data = lines[1] if header == 0 and len(lines) > 1 else first
    if sep == "," or "," not in data:
        return sep or ",", ".", header
    if sep is None:  # one column: its values hold no separator, the comma is a decimal
        return ";", ",", header
    return sep, ",", header


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _read_npy(path: Path, mmap: bool = False):
    """Channel names, rows and stated rate (None) of a .npy file; ``mmap``: the array
    memory-mapped, its samples not read."""
    try:
        arr = np.load(path, allow_pickle=False, mmap_mode="r" if mmap else None)
    except (ValueError, OSError, EOFError) as exc:
        reason = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise ValueError(f"{path.name}: not a readable .npy file ({reason})") from None
    if arr.ndim == 2 and 1 in arr.shape:
        arr = arr.ravel()
    if arr.ndim == 1:
        arr = arr[None, :]
    if arr.ndim != 2 or arr.shape[0] > arr.shape[1]:
        raise ValueError(f"{path.name}: holds an array of shape {arr.shape}; a recording "
                         "is (n_samples,) or (n_channels, n_samples)")
    return [str(i) for i in range(len(arr))], arr, None


def _read_wav(path: Path, mmap: bool = False):
    """Channel names, rows and rate of a WAV file; ``mmap``: the samples memory-mapped
    and not scaled (None when the format cannot be mapped, as 24-bit PCM)."""
    import scipy.io.wavfile

    try:
        with warnings.catch_warnings():  # unknown chunks (cue points, metadata) are fine
            warnings.simplefilter("ignore", scipy.io.wavfile.WavFileWarning)
            rate, data = scipy.io.wavfile.read(path, mmap=mmap)
    except (ValueError, OSError, EOFError, struct.error) as exc:
        if mmap and "mmap" in str(exc):
            return None
        reason = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        raise ValueError(f"{path.name}: not a readable WAV file ({reason})") from None
    if data.dtype.kind in "iu" and not mmap:
        info = np.iinfo(data.dtype)
        mid = (int(info.max) + int(info.min) + 1) / 2.0  # 8-bit WAV is unsigned, centred on 128
        data = (data.astype(np.float64) - mid) / (int(info.max) + 1 - mid)
    rows = np.atleast_2d(data.T) if data.ndim == 2 else data[None, :]
    return [str(i) for i in range(len(rows))], rows, float(rate)


def _read_mat(path: Path, fs, variable, channel, mat_channel: str, probe: bool = False):
    """A CWRU or MFPT recording, or the named ``variable`` of any .mat file; ``probe``:
    only what the variable names tell (see :func:`check_recording`)."""
    from .mfpt import MfptRecord
    from .real import _loadmat, _mat_variables, read_mat

    names = _mat_variables(path)
    if probe:
        return _probe_mat(path, names, fs, variable, str(channel or mat_channel).upper())
    if variable is None:
        try:
            rec = read_mat(path, channel=str(channel or mat_channel).upper(), fs=fs)
        except ValueError as exc:
            if "neither a CWRU recording" in str(exc):
                if names is not None and len(names) == 1:
                    variable = names[0]  # a logger's file with one signal: take it
                else:
                    raise RecordingMismatch(f"{exc}; name the signal's variable "
                                            "(--variable / variable)") from None
            elif " has no " in str(exc) and "channel" in str(exc):
                raise RecordingMismatch(str(exc)) from None
            else:
                raise
        else:
            if isinstance(rec, MfptRecord):
                _check_rate(path, fs, rec.fs)  # its struct states the rate
            return from_real(rec)
    if names is not None and variable not in names:
        held = ", ".join(names[:8]) + (", ..." if len(names) > 8 else "") or "nothing"
        raise RecordingMismatch(f"{path.name}: no variable {variable!r}; it holds {held}")
    data = _loadmat(path)
    if variable not in data:
        raise RecordingMismatch(f"{path.name}: no variable {variable!r}")
    fs = _rate_given(path, fs, "generic .mat variable")
    return Recording(_samples(data[variable], f"{path.name}: {variable}"), fs, path.stem,
                     str(variable))


def _probe_mat(path: Path, names, fs, variable, channel: str) -> list[str] | None:
    """:func:`check_recording` of a .mat file from its variable names."""
    from .real import _VARIABLE, not_cwru_nor_mfpt

    if names is None:
        raise ValueError(f"{path.name}: not a readable MATLAB .mat file")
    if variable is None:
        cwru = {m[2] for name in names if (m := _VARIABLE.fullmatch(name))}
        if cwru and channel not in cwru:
            raise RecordingMismatch(f"{path.name} has no {channel} channel (variables "
                                    f"X<number>_{channel}_time); it has {sorted(cwru)}")
        if cwru or "bearing" in names:
            return [channel] if cwru else None
        if len(names) != 1:
            raise RecordingMismatch(f"{not_cwru_nor_mfpt(path, names)}; name the signal's "
                                    "variable (--variable / variable)")
        variable = names[0]
    if variable not in names:
        held = ", ".join(names[:8]) + (", ..." if len(names) > 8 else "") or "nothing"
        raise RecordingMismatch(f"{path.name}: no variable {variable!r}; it holds {held}")
    _rate_given(path, fs, "generic .mat variable")
    return [str(variable)]
