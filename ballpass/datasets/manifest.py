"""Recordings of any rig listed in a table (a manifest): one row per recording.

A manifest is a CSV or Parquet table with the columns

============  ========  ==============================================================
column        needed    meaning
============  ========  ==============================================================
``path``      yes       the recording: absolute, or relative to the manifest's folder;
                        any format :func:`ballpass.datasets.recordings.read_recording`
                        reads (.csv, .npy, .wav, .mat, .npz, .parquet)
``fs``        yes       sampling frequency, Hz (checked against a rate the file states)
``rpm``       yes       shaft speed, rev/min
``bearing``   yes       catalogue name (``ballpass bearings`` lists them)
``label``     scoring   ``healthy``, ``inner``, ``outer`` or ``ball``: required where
                        results are scored (``require_label=True``), optional elsewhere
``variable``  no        the signal's variable in a generic ``.mat`` file (default:
                        its only variable)
``column``    no        the signal's column in a plain ``.csv`` file
``channel``   no        the channel of a file that holds several (a name, an index from
                        0, or ``DE``/``FE``/``BA`` of a CWRU file)
``group``     no        recordings of one run or machine, kept on one side of every
                        train/test split (default: the file name)
``load``      no        the operating load, in the user's unit (copied to the meta)
============  ========  ==============================================================

What the table states wins over what a file implies (a CWRU file's name); a
sampling rate the file itself states (WAV header, signal file, MFPT struct) must agree.
The table is checked whole before any file is opened: a missing column, an empty or
invalid value, an unknown bearing or label is a ``ValueError`` naming the row (rows
count from 1, the header not included). Then every file's header is checked before any
recording is read (:func:`ballpass.datasets.recordings.check_recording`): a row whose
``column``, ``variable`` or ``channel`` the file lacks, or whose ``fs`` it contradicts,
is a ``ValueError`` too (the table is wrong; ballpass and MFPT files, whose headers are
not read apart, are checked when read). A file that cannot be read at all (missing,
corrupt, NaN samples) is skipped with a warning naming the row and the reason, and the
other rows go on.

Examples
--------
>>> import numpy as np, pandas as pd, tempfile, pathlib
>>> from ballpass.datasets import load_manifest
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> np.save(folder / "a.npy", np.random.default_rng(0).normal(size=24_000))
>>> pd.DataFrame({"path": ["a.npy"], "fs": [12_000], "rpm": [1797], "bearing": ["6205"],
...               "label": ["healthy"]}).to_csv(folder / "recordings.csv", index=False)
>>> X, meta = load_manifest(folder / "recordings.csv")
>>> X.shape, meta.loc[0, ["label", "bearing", "group"]].tolist()
((2, 12000), ['healthy', '6205', 'a'])
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

from .._validation import check_segment
from ..features._validation import check_fs
from .recordings import _DELIMITERS, Recording, RecordingMismatch, check_recording, read_recording

__all__ = ["LABELS", "REQUIRED", "OPTIONAL", "is_manifest", "read_manifest",
           "manifest_records", "load_manifest", "read_recordings"]

#: Columns every manifest has.
REQUIRED = ("path", "fs", "rpm", "bearing")
#: Columns a manifest may have (``label`` is required where results are scored).
OPTIONAL = ("label", "variable", "column", "channel", "group", "load")
#: Labels a manifest may give.
LABELS = ("healthy", "inner", "outer", "ball")
_TABLE_SUFFIXES = (".csv", ".parquet")
#: What each needed column holds, for the message about an empty cell.
_NEEDS = {"path": "the recording's file", "fs": "sampling rate, Hz > 0",
          "rpm": "shaft speed, rev/min > 0", "bearing": "a name `ballpass bearings` lists",
          "label": ", ".join(LABELS)}


def is_manifest(path) -> bool:
    """True when ``path`` is a CSV or Parquet table with a ``path`` column (a manifest,
    not a signal file).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "m.csv"
    >>> _ = path.write_text("path,fs,rpm,bearing\\na.npy,12000,1797,6205\\n")
    >>> is_manifest(path), is_manifest(path.parent)
    (True, False)
    """
    path = Path(path)
    if not path.is_file() or path.suffix.lower() not in _TABLE_SUFFIXES:
        return False
    try:
        if path.suffix.lower() == ".csv":
            return "path" in _csv_header(path)[1]
        import pyarrow.parquet as pq

        return "path" in (_column_name(name) for name in pq.read_schema(path).names)
    except (OSError, UnicodeDecodeError, ValueError):
        return False  # not a table: the signal readers say what is wrong


def _column_name(name) -> str:
    """A manifest's column as ballpass names it: ``Path``, ``FS `` and ``fs`` are one."""
    return str(name).strip().strip('"').lower()


def _csv_header(path: Path) -> tuple[str, list[str]]:
    """The delimiter of a CSV table (comma, semicolon or tab, as for a plain CSV
    recording: spreadsheets in many locales write semicolons) and its column names."""
    with open(path, newline="", encoding="utf-8-sig") as fh:
        first = next((line for line in fh if line.strip() and not line.startswith("#")), "")
    sep = next((d for d in _DELIMITERS if d in first), ",")
    return sep, [_column_name(name) for name in first.split(sep)]


def _where(source: str, i: int, row) -> str:
    """``recordings.csv row 3 (a.wav)``: how messages name a row."""
    path = row.get("path")
    return f"{source} row {i + 1}" + (f" ({path})" if _given(path) else "")


def _given(value) -> bool:
    """The cell holds something (not None, NaN or blank)."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return False
    return str(value).strip() != ""


def _number(value, name: str, where: str) -> float:
    try:
        out = float(value)
    except (TypeError, ValueError):
        out = math.nan
    if not (math.isfinite(out) and out > 0):
        raise ValueError(f"{where}: {name} must be a finite number > 0, got {value!r}")
    return out


def _text(value) -> str | None:
    """A cell as text; an index that pandas wrote as a float (``1.0``) as ``1``."""
    if not _given(value):
        return None
    text = str(value).strip()
    return text[:-2] if text.endswith(".0") and text[:-2].isdigit() else text


def read_manifest(manifest, *, require_label: bool = False):
    """A manifest table, checked whole: one validated dict per row.

    Parameters
    ----------
    manifest : str, os.PathLike or pandas.DataFrame
        The ``.csv`` or ``.parquet`` table (or the table itself, whose relative paths
        are then taken from the current folder).
    require_label : bool, optional
        Every row must carry a ``label`` (where results are scored).

    Returns
    -------
    rows : list of dict
        Per row: ``path`` (a :class:`pathlib.Path`, resolved against the manifest's
        folder), ``fs``, ``rpm`` (floats), ``bearing`` (the catalogue's spelling),
        ``label`` (or None), ``variable``, ``column``, ``channel``, ``group``, ``load``
        (or None) and ``row`` (counted from 1).

    Raises
    ------
    ValueError
        Not a CSV/Parquet table, a required column missing, or a row with a missing or
        invalid value, an unknown bearing or label; the message names the row.

    Examples
    --------
    >>> import pandas as pd
    >>> from ballpass.datasets.manifest import read_manifest
    >>> table = pd.DataFrame({"path": ["a.wav"], "fs": [51200], "rpm": [600],
    ...                       "bearing": ["6205"]})
    >>> read_manifest(table)[0]["fs"]
    51200.0
    >>> read_manifest(table.assign(bearing="6299"))
    Traceback (most recent call last):
        ...
    ValueError: manifest row 1 (a.wav): unknown bearing '6299'; the catalogue has: ...
    """
    import pandas as pd

    from ..bearing import Bearing

    if isinstance(manifest, pd.DataFrame):
        table, folder, source = manifest, Path.cwd(), "manifest"
    else:
        path = Path(manifest)
        if not path.is_file():
            raise FileNotFoundError(f"no such manifest: {path}")
        if path.suffix.lower() not in _TABLE_SUFFIXES:
            raise ValueError(f"{path.name}: a manifest must be a .csv or .parquet table")
        try:
            table = (pd.read_parquet(path) if path.suffix.lower() == ".parquet"
                     else pd.read_csv(path, sep=_csv_header(path)[0], comment="#", dtype=str,
                                      skipinitialspace=True, encoding="utf-8-sig"))
        except (ValueError, OSError) as exc:
            reason = str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__
            raise ValueError(f"{path.name}: not a readable manifest table ({reason})") from None
        folder, source = path.parent, path.name
    table = table.rename(columns=_column_name)
    needed = REQUIRED + (("label",) if require_label else ())
    missing = [c for c in needed if c not in table.columns]
    if missing:
        raise ValueError(f"{source}: the manifest has no column {', '.join(missing)} "
                         f"(needed: {', '.join(needed)}; it has {', '.join(table.columns)})")
    rows = []
    for i, raw in enumerate(table.to_dict("records")):
        if not any(_given(value) for value in raw.values()):
            continue  # an empty row (",,,"): spreadsheets write them after the table
        where = _where(source, i, raw)
        absent = [c for c in needed if not _given(raw.get(c))]
        if absent:
            raise ValueError(f"{where}: no {', '.join(absent)} given ("
                             + "; ".join(f"{c}: {_NEEDS[c]}" for c in absent) + ")")
        try:
            bearing = Bearing.catalog(str(raw["bearing"]).strip()).name
        except ValueError as exc:
            raise ValueError(f"{where}: {exc}") from None
        label = _text(raw.get("label"))
        if label is not None and label.lower() not in LABELS:
            raise ValueError(f"{where}: label must be one of {', '.join(LABELS)}, "
                             f"got {label!r}")
        file = Path(str(raw["path"]).strip()).expanduser()
        rows.append({
            "row": i + 1,
            "where": where,
            "path": file if file.is_absolute() else folder / file,
            "fs": _number(raw["fs"], "fs (Hz)", where),
            "rpm": _number(raw["rpm"], "rpm", where),
            "bearing": bearing,
            "label": None if label is None else label.lower(),
            **{key: _text(raw.get(key)) for key in ("variable", "column", "channel", "group",
                                                     "load")},
        })
    if not rows:
        raise ValueError(f"{source}: the manifest lists no recording")
    return rows


def _one_channel(row: dict, channels) -> None:
    """A row must name one recording: a file of several channels needs ``channel``."""
    if channels is not None and len(channels) > 1:
        raise RecordingMismatch(f"{row['path'].name} holds {len(channels)} channels "
                                f"({', '.join(channels)}); name one in the manifest's "
                                "channel column")


def _file(row: dict, read) -> list:
    """``read`` (read_recording or check_recording) applied to a checked row's file."""
    channel = row["channel"]
    mat = row["path"].suffix.lower() == ".mat" and row["variable"] is None
    return read(row["path"], fs=row["fs"], column=row["column"], variable=row["variable"],
                channel=channel, mat_channel=(channel or "DE").upper() if mat else "DE")


def _record(row: dict) -> Recording:
    """The one recording a checked manifest row names, with the row's statements."""
    from dataclasses import replace

    found = _file(row, read_recording)
    _one_channel(row, [r.channel for r in found])
    rec = found[0]
    stated = {"manifest_row": row["row"], "group": row["group"] or rec.name,
              "dataset": rec.info.get("dataset", "manifest")}
    if row["load"] is not None:
        stated["load"] = row["load"]
    return replace(rec, rpm=row["rpm"], bearing=row["bearing"],
                   label=row["label"] or rec.label,
                   info=rec.info | {"rpm_source": "manifest"} | stated)


def manifest_records(manifest, *, require_label: bool = False) -> list[tuple[Path, Recording]]:
    """``[(path, Recording)]`` for the rows of a manifest, whole and at their own rates.

    The table is checked whole first (:func:`read_manifest`), then every row's file
    header, then each row's file is read. Its ``rpm``, ``bearing``, ``label`` (when
    given) and ``group`` are the row's.

    Parameters
    ----------
    manifest : str, os.PathLike or pandas.DataFrame
        See :func:`read_manifest`.
    require_label : bool, optional
        Every row must carry a ``label``.

    Returns
    -------
    list of (pathlib.Path, Recording)
        In row order, unreadable rows left out (each with a warning).

    Raises
    ------
    ValueError
        The table is invalid, a row asks for a column, variable, channel or rate that its
        file contradicts, or no row could be read.

    Examples
    --------
    >>> import numpy as np, pandas as pd, tempfile, pathlib
    >>> from ballpass.datasets.manifest import manifest_records
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> np.save(folder / "a.npy", np.zeros(1000))
    >>> table = pd.DataFrame({"path": [str(folder / "a.npy"), str(folder / "gone.wav")],
    ...                       "fs": [12e3, 12e3], "rpm": [1797, 1797], "bearing": "6205"})
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     found = manifest_records(table)
    >>> [rec.name for _, rec in found], "skipped manifest row 2" in str(caught[0].message)
    (['a'], True)
    """
    rows = read_manifest(manifest, require_label=require_label)
    readable = [row for row in rows if _attempt(row, _check) is not None]  # headers first
    out = [(row["path"], rec) for row in readable if (rec := _attempt(row, _record))]
    if not out:
        raise ValueError("no recording of the manifest could be read (see the warnings "
                         "above)")
    return out


def _check(row: dict) -> bool:
    """What a row's file header contradicts (:func:`check_recording`); True if none."""
    _one_channel(row, _file(row, check_recording))
    return True


def _attempt(row: dict, step):
    """``step(row)``; a contradiction is an error naming the row, an unreadable file a
    warning naming it (and None)."""
    try:
        return step(row)
    except RecordingMismatch as exc:
        raise ValueError(f"{row['where']}: {_reason(exc, row['path'])}") from None
    except (ValueError, OSError) as exc:
        warnings.warn(f"skipped {row['where']}: {_reason(exc, row['path'])}", stacklevel=4)
        return None


def _reason(exc: BaseException, path: Path) -> str:
    text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return text.removeprefix(f"{path.name}: ").removeprefix(f"{path.name} ")


def load_manifest(manifest, fs: float | None = None, segment_s: float = 1.0, *,
                  require_label: bool = False):
    """Recordings listed in a manifest as equal segments at one rate, like ``load_cwru``.

    Each row's recording is read (see :mod:`ballpass.datasets.manifest` for the
    columns and what is checked), resampled to ``fs`` with
    :func:`scipy.signal.resample_poly` and cut into non-overlapping segments of
    ``segment_s``; the remainder of each recording is dropped, and a recording shorter
    than one segment is skipped with a warning. Recordings of different lengths thus
    give different numbers of segments; segments of one ``group`` (default: the file
    name) belong together: split train/test by group, never by segment.

    Parameters
    ----------
    manifest : str, os.PathLike or pandas.DataFrame
        The ``.csv`` or ``.parquet`` manifest (or the table itself, relative paths then
        from the current folder).
    fs : float, optional
        Output sampling frequency, Hz. Default: the rows' rate when they share one;
        rows of several rates need ``fs``.
    segment_s : float, optional
        Segment length, s (default 1.0).
    require_label : bool, optional
        Every row must carry a ``label`` (set it where the results are scored).

    Returns
    -------
    X : ndarray of float32, shape (n_segments, round(segment_s * fs))
        Samples in the units stored (m/s^2 for ballpass, CWRU and MFPT files).
    meta : pandas.DataFrame
        One row per segment: ``file``, ``group``, ``manifest_row``, ``segment``,
        ``label`` ("unknown" where neither the table nor the file says), ``bearing``,
        ``rpm``, ``rpm_source`` ("manifest"), ``fs``, ``source_fs``, ``channel`` (also as
        ``sensor``), ``load`` (when given), ``start_s``, ``duration_s``, ``dataset``;
        for CWRU and MFPT files also their loaders' columns.

    Raises
    ------
    ValueError
        An invalid table or row (named), rows of several rates without ``fs``, or no
        readable recording.

    Examples
    --------
    >>> from ballpass.datasets import load_manifest
    >>> X, meta = load_manifest("recordings.csv", fs=12_000)        # doctest: +SKIP
    >>> meta.groupby(["group", "label"]).size()                     # doctest: +SKIP
    """
    from .real import segment_records

    if fs is not None:
        fs = check_fs(fs)
    records = manifest_records(manifest, require_label=require_label)
    if fs is None:
        rates = sorted({rec.fs for _, rec in records})
        if len(rates) > 1:
            raise ValueError(f"the manifest's recordings have sampling rates {rates} Hz; "
                             f"pass fs to resample them to one rate (e.g. fs={rates[0]:g})")
        fs = rates[0]
    return segment_records(records, fs, check_segment(segment_s, fs))


def read_recordings(source, *, fs=None, column=None, variable=None, channel: str = "DE",
                    require_label: bool = False) -> list[tuple[Path, Recording]]:
    """``[(path, Recording)]`` of any source of real recordings, whole and at their rates.

    The one place that tells the sources apart, for the ``ballpass`` commands that read
    recordings (``features``, ``diagnose``, ``plot``, ``benchmark --real``):

    * a manifest (:func:`is_manifest`): its rows (:func:`manifest_records`); ``fs``,
      ``column`` and ``variable`` are then the table's, per row;
    * a folder: its ``.mat`` recordings, each read as a single file is (CWRU, MFPT, or
      with ``fs`` a logger's file of one variable or of ``variable``); unreadable ones
      skipped with a warning;
    * a file: its recording(s) (:func:`ballpass.datasets.recordings.read_recording`).

    Parameters
    ----------
    source : str or os.PathLike
    fs : float, optional
        Sampling frequency of a file that does not state it (or of CWRU files), Hz.
    column, variable : str, optional
        Column of a plain CSV file, variable of a generic ``.mat`` file.
    channel : {"DE", "FE", "BA"}, optional
        CWRU accelerometer (default ``"DE"``).
    require_label : bool, optional
        A manifest must give every row's label.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from ballpass.datasets.manifest import read_recordings
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "rec.npy"
    >>> np.save(path, np.zeros(1000))
    >>> [(p.name, rec.fs) for p, rec in read_recordings(path, fs=12_000)]
    [('rec.npy', 12000.0)]
    """
    from .real import read_all

    path = Path(source)
    if is_manifest(path):
        given = [f"--{name}" for name, value in (("fs", fs), ("column", column),
                                                  ("variable", variable)) if value is not None]
        if given:
            warnings.warn(f"{path.name} is a manifest, which states {', '.join(given)} per "
                          "row: ignored for it", stacklevel=2)
        return manifest_records(path, require_label=require_label)
    if path.is_dir():
        if not any(path.glob("*.mat")):
            from .recordings import RECORDING_SUFFIXES

            files = sorted(p.name for p in path.iterdir()
                           if p.suffix.lower() in RECORDING_SUFFIXES)
            hint = (f"; give its signal files as inputs ({path / '*'}{Path(files[0]).suffix})"
                    if files else "")
            raise ValueError(f"{path} is a folder without _manifest.json or .mat files: "
                             f"neither a dataset nor a folder of recordings{hint}")
        # each file as a single one is read: CWRU, MFPT, or (with fs) any logger's .mat
        found = read_all(path, lambda p: read_recording(p, fs=fs, variable=variable,
                                                        mat_channel=channel))
        if not found:
            raise ValueError(f"{path}: none of its .mat files could be read (the warnings "
                             "above say why)")
        return [(file, rec) for file, recs in found for rec in recs]
    return [(path, rec) for rec in read_recording(path, fs=fs, column=column,
                                                  variable=variable, mat_channel=channel)]
