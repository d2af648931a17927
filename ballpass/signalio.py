"""Read and write signal files: acceleration channels with their sampling rate and metadata.

Three formats, chosen by the file extension:

``.npz``
    NumPy archive with arrays ``accel`` (n_channels, n_samples), ``fs`` (Hz),
    ``channels`` (str) and ``meta_json`` (a JSON string). Exact, compact, numpy only.
``.csv``
    Comment lines ``# fs=<Hz>`` and ``# meta=<JSON>``, then a header ``t_s,<channel>,...``
    and one row per sample (9 significant digits: exact for float32). For spreadsheets
    and other tools.
``.parquet``
    Columns ``t_s`` and one per channel; ``fs``, ``channels`` and ``meta`` as JSON under
    the key ``ballpass`` of the Arrow schema metadata. Exact and columnar.

Acceleration is in m/s^2 and time in s. Writes are atomic: the file is written under a
temporary name in the target folder and renamed, so a reader never sees half a file.

Examples
--------
>>> import numpy as np, tempfile, pathlib
>>> from ballpass.signalio import read_signal, write_signal
>>> path = pathlib.Path(tempfile.mkdtemp()) / "run.parquet"
>>> _ = write_signal(path, np.zeros((2, 100)), 12_000.0, channels=["loaded", "unloaded"],
...                  meta={"rpm": 1797.0})
>>> sig = read_signal(path)
>>> sig.accel.shape, sig.fs, sig.channels, sig.meta["rpm"]
((2, 100), 12000.0, ('loaded', 'unloaded'), 1797.0)
"""

from __future__ import annotations

import json
import math
import os
import uuid
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = [
    "SUFFIXES",
    "SignalFile",
    "atomic_write",
    "atomic_write_many",
    "check_output_path",
    "read_signal",
    "signal_writer",
    "write_signal",
]

#: File extensions understood by :func:`read_signal` and :func:`write_signal`.
SUFFIXES = (".npz", ".csv", ".parquet")
#: Extensions that name a file: a new output folder ending in one is a mistake.
_FILE_SUFFIXES = SUFFIXES + (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".mat", ".json",
                             ".md", ".txt")
_TIME = "t_s"
_ARROW_KEY = b"ballpass"


@dataclass(frozen=True)
class SignalFile:
    """Contents of a signal file.

    Attributes
    ----------
    accel : ndarray, shape (n_channels, n_samples)
        Acceleration, m/s^2 (float32 or float64 as stored; float64 from CSV).
    fs : float
        Sampling frequency, Hz.
    channels : tuple of str
        Channel names, one per row of ``accel``.
    meta : dict
        Free-form metadata (JSON types), e.g. ``rpm``, ``bearing``, the scene.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from ballpass.signalio import read_signal, write_signal
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.npz"
    >>> _ = write_signal(path, np.ones((2, 50)), 12_000.0, channels=["loaded", "unloaded"])
    >>> sig = read_signal(path)
    >>> sig.accel.shape, sig.fs, sig.channels
    ((2, 50), 12000.0, ('loaded', 'unloaded'))
    """

    accel: np.ndarray
    fs: float
    channels: tuple[str, ...]
    meta: dict = field(default_factory=dict)

    def channel(self, name: str) -> np.ndarray:
        """The signal of one channel, shape (n_samples,).

        Examples
        --------
        >>> import numpy as np
        >>> from ballpass.signalio import SignalFile
        >>> sig = SignalFile(np.arange(6.0).reshape(2, 3), 12_000.0, ("loaded", "unloaded"))
        >>> sig.channel("unloaded")
        array([3., 4., 5.])
        """
        if name not in self.channels:
            raise ValueError(f"channel must be one of {self.channels}, got {name!r}")
        return self.accel[self.channels.index(name)]


def _suffix(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise ValueError(f"path must end in one of {', '.join(SUFFIXES)}; got {path.name!r}")
    return suffix


def _json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"meta values must be JSON-serialisable, got {type(value).__name__}")


def check_output_path(path, *, option: str = "path", suffixes=None,
                      folder: bool = False) -> Path:
    """Check, before any work, that a file or folder can be written at ``path``.

    Nothing is created: the nearest existing ancestor must be a folder in which a file
    can be created (probed with a temporary file, removed at once), no file may stand
    where a folder is needed, and ``path`` itself must not be a folder (for a file) or a
    file (for a folder).

    Parameters
    ----------
    path : str or os.PathLike
        The output file or folder.
    option : str, optional
        Name of the option or argument, for the message (e.g. ``"--out"``).
    suffixes : sequence of str, optional
        Allowed file extensions (lower case, with the dot).
    folder : bool, optional
        ``path`` is a folder (created later) rather than a file.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ValueError
        Wrong extension, a folder where a file is wanted or the reverse, a new folder
        named like a file (``figs.png``).
    PermissionError
        The folder cannot be written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> check_output_path(pathlib.Path(tempfile.mkdtemp()) / "new" / "x.npz", option="--out",
    ...                   suffixes=(".npz",)).name
    'x.npz'
    """
    import tempfile

    path = Path(path)
    if not folder and suffixes is not None and path.suffix.lower() not in suffixes:
        allowed = " or ".join([", ".join(suffixes[:-1]), suffixes[-1]] if len(suffixes) > 1
                              else suffixes)
        raise ValueError(f"{option} must end in {allowed}, got {str(path)!r}")
    if folder and path.exists() and not path.is_dir():
        raise ValueError(f"{option} {path} is a file, not a folder")
    if folder and not path.exists() and path.suffix.lower() in _FILE_SUFFIXES:
        raise ValueError(f"{option} must be a folder, got {str(path)!r}, a "
                         f"{path.suffix} file's name")
    if not folder and path.is_dir():
        raise ValueError(f"{option} {path} is a folder, not a file")
    ancestor = path if folder and path.is_dir() else path.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        raise ValueError(f"{option} {path}: {ancestor} is a file, so no folder can be made "
                         "there")
    try:
        with tempfile.TemporaryFile(dir=ancestor):
            pass
    except OSError as exc:
        raise PermissionError(f"{option} {path}: cannot write in {ancestor} "
                              f"({exc.strerror or exc})") from None
    return path


def atomic_write(path, write) -> None:
    """Write a file atomically: ``write(tmp_path)`` into the target folder, then rename.

    Parameters
    ----------
    path : str or os.PathLike
        Final file name; parent folders are created.
    write : callable
        Called with the temporary :class:`pathlib.Path` to fill. If it raises, the
        temporary file is removed, ``path`` is left as it was and the original error
        propagates (an error while removing the temporary file never replaces it); an
        :class:`OSError` that names no file (a full disk) is raised again naming
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ballpass.signalio import atomic_write
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "notes" / "run.txt"
    >>> atomic_write(target, lambda tmp: tmp.write_text("done"))
    >>> target.read_text()
    'done'
    >>> def broken(tmp):
    ...     tmp.write_text("half")
    ...     raise RuntimeError("disk full")
    >>> atomic_write(target, broken)
    Traceback (most recent call last):
        ...
    RuntimeError: disk full
    >>> target.read_text(), sorted(p.name for p in target.parent.iterdir())   # untouched
    ('done', ['run.txt'])
    """
    atomic_write_many([(path, write)])


def atomic_write_many(items) -> None:
    """Write several files all or nothing: every temporary file first, then the renames.

    Parameters
    ----------
    items : sequence of (path, write)
        As for :func:`atomic_write`. If any ``write`` fails, no target is touched.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from ballpass.signalio import atomic_write_many
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> def fail(tmp):
    ...     raise OSError("no space left")
    >>> atomic_write_many([(folder / "a.txt", lambda tmp: tmp.write_text("a")),
    ...                    (folder / "b.txt", fail)])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    OSError: cannot write .../b.txt: no space left
    >>> list(folder.iterdir())                    # all or nothing: a.txt was not written
    []
    """
    pending = []
    try:
        for path, write in items:
            path = Path(path)
            try:
                path.parent.mkdir(parents=True, exist_ok=True)
            except (FileExistsError, NotADirectoryError):
                raise ValueError(f"cannot write {path}: a file stands where a folder of its "
                                 "path should be") from None
            # a unique hidden name beside the target (same file system, so the rename
            # is atomic); created with the process umask, like any file the user writes
            tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
            pending.append((tmp, path))
            try:
                write(tmp)
                with open(tmp, "rb+") as fh:
                    os.fsync(fh.fileno())
            except OSError as exc:   # a full disk says so without a path: name the file
                if exc.filename not in (None, str(tmp)):
                    raise
                if exc.errno is None:
                    raise OSError(f"cannot write {path}: {exc}") from exc
                raise OSError(exc.errno, exc.strerror, str(path)) from exc
        for tmp, path in pending:
            os.replace(tmp, path)
    except BaseException:
        for tmp, _ in pending:
            try:
                tmp.unlink(missing_ok=True)
            except OSError:  # never mask the original error with the cleanup's own
                pass
        raise


def write_signal(path, accel, fs: float, *, channels=None, meta=None) -> Path:
    """Write acceleration channels, their sampling rate and metadata to a file.

    Parameters
    ----------
    path : str or os.PathLike
        Target file; the extension (``.npz``, ``.csv``, ``.parquet``) selects the
        format. Parent folders are created.
    accel : array_like, shape (n_samples,) or (n_channels, n_samples)
        Acceleration, m/s^2; float32 stays float32 in ``.npz`` and ``.parquet``.
    fs : float
        Sampling frequency, Hz, > 0.
    channels : sequence of str, optional
        Unique channel names (not ``"t_s"``); default ``["accel"]`` for one channel,
        ``["accel_0", "accel_1", ...]`` for several.
    meta : dict, optional
        JSON-serialisable metadata (NumPy scalars and arrays are converted).

    Returns
    -------
    pathlib.Path
        The written file.

    Raises
    ------
    ValueError
        Unknown extension, bad shape, ``fs <= 0``, or bad channel names.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from ballpass.signalio import write_signal
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "sig.csv"
    >>> write_signal(out, np.ones(4), 1000.0).read_text().splitlines()[:3]
    ['# fs=1000.0', '# meta={}', 't_s,accel']
    """
    path = Path(path)
    atomic_write(path, signal_writer(path, accel, fs, channels=channels, meta=meta))
    return path


def signal_writer(path, accel, fs: float, *, channels=None, meta=None):
    """Validate a signal and return ``write(tmp_path)`` that writes it in ``path``'s format.

    For :func:`atomic_write_many` (a signal and its figure, all or nothing); the
    arguments are those of :func:`write_signal`, checked here before anything is written.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from ballpass.signalio import atomic_write, read_signal, signal_writer
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
    >>> atomic_write(path, signal_writer(path, np.zeros(10), 12_000.0, meta={"rpm": 1797}))
    >>> read_signal(path).meta["rpm"]
    1797
    >>> signal_writer(path, np.zeros(10), fs=-1.0)
    Traceback (most recent call last):
        ...
    ValueError: fs must be a finite number > 0 Hz, got -1.0
    """
    from .features._validation import check_fs

    path = Path(path)
    suffix = _suffix(path)
    data = np.asarray(accel)
    if not (np.issubdtype(data.dtype, np.floating) or np.issubdtype(data.dtype, np.integer)):
        raise TypeError(f"accel must be a real numeric array, got dtype {data.dtype}")
    if data.ndim == 1:
        data = data[None, :]
    if data.ndim != 2 or data.shape[1] == 0:
        raise ValueError(
            f"accel must have shape (n_samples,) or (n_channels, n_samples) with n_samples "
            f">= 1, got {np.shape(accel)}"
        )
    if not np.issubdtype(data.dtype, np.floating):
        data = data.astype(np.float64)
    fs = check_fs(fs)
    if channels is None:
        channels = ["accel"] if len(data) == 1 else [f"accel_{i}" for i in range(len(data))]
    channels = [str(c) for c in channels]
    if len(channels) != len(data) or len(set(channels)) != len(channels) or _TIME in channels:
        raise ValueError(
            f"channels must be {len(data)} unique names other than {_TIME!r}, got {channels}"
        )
    meta_json = json.dumps(dict(meta or {}), default=_json_default)

    if suffix == ".npz":

        def write(tmp: Path) -> None:
            with open(tmp, "wb") as fh:
                np.savez(
                    fh,
                    accel=data,
                    fs=np.float64(fs),
                    channels=np.array(channels),
                    meta_json=np.array(meta_json),
                )

    elif suffix == ".csv":
        import pandas as pd

        def write(tmp: Path) -> None:
            frame = pd.DataFrame({_TIME: np.arange(data.shape[1]) / fs})
            for name, row in zip(channels, data, strict=True):
                frame[name] = row
            with open(tmp, "w", newline="") as fh:
                fh.write(f"# fs={fs!r}\n# meta={meta_json}\n")
                frame.to_csv(fh, index=False, float_format="%.9g")

    else:
        import pyarrow as pa
        import pyarrow.parquet as pq

        def write(tmp: Path) -> None:
            columns = {_TIME: pa.array(np.arange(data.shape[1]) / fs)}
            columns.update({name: pa.array(row) for name, row in zip(channels, data, strict=True)})
            info = json.dumps({"fs": fs, "channels": channels, "meta": json.loads(meta_json)})
            table = pa.table(columns).replace_schema_metadata({_ARROW_KEY: info.encode()})
            pq.write_table(table, tmp, write_page_checksum=True)

    return write


def _fs_from_time(t: np.ndarray, path: Path) -> float:
    if t.size < 2:
        raise ValueError(f"{path.name}: no fs recorded and fewer than 2 time stamps to infer it")
    step = float(np.median(np.diff(t)))
    if not step > 0:
        raise ValueError(f"{path.name}: no fs recorded and the t_s column is not increasing")
    return 1.0 / step


def _ends_with_newline(path: Path) -> bool:
    """Whether the file's last byte is a line break (an empty file has none)."""
    with open(path, "rb") as fh:
        fh.seek(0, 2)
        if fh.tell() == 0:
            return False
        fh.seek(-1, 2)
        return fh.read(1) == b"\n"


def read_signal(path) -> SignalFile:
    """Read a file written by :func:`write_signal` (or a compatible one).

    CSV and Parquet files from other tools work if they have a ``t_s`` column (fs is
    then inferred from its median step) or the ``# fs=`` comment / schema metadata;
    every other column is a channel.

    Parameters
    ----------
    path : str or os.PathLike
        ``.npz``, ``.csv`` or ``.parquet`` file.

    Returns
    -------
    SignalFile
        ``accel`` (n_channels, n_samples), ``fs`` (Hz), ``channels``, ``meta``.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from ballpass.signalio import read_signal, write_signal
    >>> out = write_signal(pathlib.Path(tempfile.mkdtemp()) / "s.npz", np.ones(8), 100.0)
    >>> read_signal(out).accel.shape
    (1, 8)
    """
    path = Path(path)
    suffix = _suffix(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such signal file: {path}")
    try:
        sig = _read(path, suffix)
    except (ValueError, TypeError, KeyError, OSError, EOFError, zipfile.BadZipFile) as exc:
        if isinstance(exc, ValueError) and str(exc).startswith(f"{path.name}:"):
            raise  # already says what is wrong
        reason = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
        if "pickle" in reason:  # numpy's advice about allow_pickle does not apply here
            reason = "not a NumPy .npz archive"
        raise ValueError(f"{path.name}: not a readable {suffix} signal file ({reason})") \
            from None
    dtype = sig.accel.dtype
    if dtype.kind == "c":
        raise TypeError(f"{path.name}: the signal is complex ({dtype}); a vibration signal "
                        "is real: store its real part")
    if dtype.kind not in "fiu" or sig.accel.ndim != 2 or sig.accel.shape[1] == 0:
        raise ValueError(f"{path.name}: accel must be a real numeric (n_channels, n_samples) "
                         f"array, got dtype {dtype} and shape {sig.accel.shape}")
    if not (math.isfinite(sig.fs) and sig.fs > 0):
        raise ValueError(f"{path.name}: fs must be a finite number > 0 Hz, got {sig.fs!r}")
    return sig


def _read(path: Path, suffix: str) -> SignalFile:
    """The contents of a signal file, unchecked (see :func:`read_signal`)."""
    if suffix == ".npz":
        with np.load(path, allow_pickle=False) as archive:
            missing = {"accel", "fs"} - set(archive.files)
            if missing:
                raise ValueError(f"{path.name}: not a ballpass .npz signal (no {sorted(missing)})")
            accel = np.atleast_2d(archive["accel"])
            channels = (
                [str(c) for c in archive["channels"]]
                if "channels" in archive.files
                else [f"accel_{i}" for i in range(len(accel))]
            )
            meta = json.loads(str(archive["meta_json"])) if "meta_json" in archive.files else {}
            return SignalFile(accel, float(archive["fs"]), tuple(channels), meta)

    if suffix == ".csv":
        import pandas as pd

        header: dict[str, str] = {}
        n_comments = 0
        with open(path) as fh:
            for line in fh:
                if not line.startswith("#"):
                    break
                key, _, value = line[1:].strip().partition("=")
                header[key.strip()] = value
                n_comments += 1
        if "fs" in header and not _ends_with_newline(path):
            # write_signal ends every line: a last line without its end was cut short
            raise ValueError(f"{path.name} ends in the middle of a line: the file is "
                             "truncated (a CSV written by ballpass ends with a line break)")
        frame = pd.read_csv(path, skiprows=n_comments)
        meta = json.loads(header["meta"]) if "meta" in header else {}
        fs = float(header["fs"]) if "fs" in header else None
        names = [c for c in frame.columns if c != _TIME]
        accel = frame[names].to_numpy(dtype=np.float64).T
        time = frame[_TIME].to_numpy(dtype=float) if _TIME in frame.columns else None
    else:
        import pyarrow.parquet as pq

        # page CRCs (which write_signal writes) are checked: flipped bytes are refused
        table = pq.read_table(path, page_checksum_verification=True)
        info = json.loads((table.schema.metadata or {}).get(_ARROW_KEY, b"{}"))
        meta = info.get("meta", {})
        fs = info.get("fs")
        names = info.get("channels") or [c for c in table.column_names if c != _TIME]
        accel = np.stack([table.column(c).to_numpy() for c in names])
        time = table.column(_TIME).to_numpy() if _TIME in table.column_names else None
    if fs is None:
        if time is None:
            raise ValueError(f"{path.name}: neither fs metadata nor a {_TIME!r} column")
        fs = _fs_from_time(time, path)
    return SignalFile(accel, float(fs), tuple(str(n) for n in names), meta)
