"""On-disk dataset format: a folder of Parquet shards with ``_manifest.json``.

Layout::

    DIR/_manifest.json           grid, simulator fingerprint, root seed, units, shards
                                 (rows, bytes and SHA-256 of each), status
    DIR/.lock                    held (flock) by the process generating the dataset
    DIR/part-00000.parquet       one signal per row + label and parameter columns
    DIR/part-00001.parquet       ...
    DIR/_features/part-00000.parquet   optional feature table, same rows and keys

Parquet readers skip names starting with ``_`` or ``.``, so the folder reads as it is:
``pandas.read_parquet(DIR)``, ``pyarrow.dataset.dataset(DIR)``, DuckDB's
``read_parquet('DIR/*.parquet')`` and ``polars.read_parquet('DIR/*.parquet')`` (polars
descends into every sub-folder, so it needs the glob) see the signal shards only.
Datasets of the first layout (``manifest.json``, ``features/``, no checksums) still load.

Each row holds one signal in the ``signal`` column, a ``fixed_size_list<float32>``
of the dataset's ``signal_length`` samples (m/s^2, zstd-compressed with
byte-stream-split encoding), next to its label, parameters, ``run_id``, ``group``,
``sensor``, ``segment``, the run's ``seed``, the resolved ``model`` and ``solver`` and
the run's scene as JSON (``scene``), from which :func:`~ballpass.datasets.regenerate`
rebuilds it bit for bit. Shards are written under a temporary name and renamed
(:func:`os.replace`) when complete; the manifest is replaced the same way and records
the SHA-256 of every complete shard, which :func:`load`, :func:`info` and a resuming
:func:`~ballpass.datasets.generate` verify (a resume regenerates a damaged shard).
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings
from pathlib import Path

import numpy as np

from .._resources import human_bytes
from ..signalio import atomic_write
from .grid import drawn_axes

__all__ = ["load", "info", "read_manifest", "MANIFEST", "UNITS", "CorruptShardError", "human_bytes"]

MANIFEST = "_manifest.json"
FEATURES_DIR = "_features"
#: names of the first layout (format_version 1), still read
LEGACY_MANIFEST = "manifest.json"
LEGACY_FEATURES_DIR = "features"
LOCK_FILE = ".lock"
FORMAT_VERSION = 2

#: units of the stored columns
UNITS = {
    "signal": "m/s^2", "fs": "Hz", "duration_s": "s", "start_s": "s", "rpm": "rpm",
    "rpm_start": "rpm", "rpm_end": "rpm", "radial_load_n": "N",
    "clearance_um": "um (negative: preload; NaN = the bearing's catalogue clearance)",
    "fault_width_mm": "mm",
    "fault_depth_mm": "mm", "fault_angle_deg": "deg from the load line",
    "fault_engagement": "1 (share of ball spin revolutions struck)", "slip": "1",
    "snr_db": "dB (inf = noise-free)", "noise_rms": "m/s^2 (0 = none)", "resonance_hz": "Hz",
    "resonance_damping": "1",
}


class CorruptShardError(ValueError):
    """A shard of a dataset is missing, truncated or altered (its checksum differs)."""


def shard_name(index: int) -> str:
    """File name of shard ``index``."""
    return f"part-{index:05d}.parquet"


def features_dir(manifest: dict) -> str:
    """Sub-folder of the feature table of a dataset with this manifest."""
    return FEATURES_DIR if manifest.get("format_version", 1) >= 2 else LEGACY_FEATURES_DIR


def is_temporary(path: Path) -> bool:
    """True for the temporary files this module writes (``.<name>.<random>.tmp``)."""
    return path.name.startswith(".") and path.name.endswith(".tmp")


def remove_temporaries(folder: Path) -> None:
    """Delete temporary files left by a killed run (never complete shards)."""
    for sub in (folder, folder / FEATURES_DIR):
        if sub.is_dir():
            for tmp in filter(is_temporary, sub.iterdir()):
                tmp.unlink(missing_ok=True)


def write_manifest(folder: Path, manifest: dict) -> None:
    """Write ``_manifest.json`` atomically (strict JSON)."""
    text = json.dumps(manifest, indent=1, allow_nan=False)
    atomic_write(folder / MANIFEST, lambda p: p.write_text(text))


def read_manifest(folder) -> dict | None:
    """The manifest of a dataset folder, or None if it has none.

    Reads ``_manifest.json``, or ``manifest.json`` of the first layout.

    Raises
    ------
    ValueError
        If the manifest exists but is not a ballpass manifest, or lists no shards.
    """
    folder = Path(folder)
    path = folder / MANIFEST
    if not path.is_file():
        path = folder / LEGACY_MANIFEST
        if not path.is_file():
            return None
    try:
        manifest = json.loads(path.read_text())
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise ValueError(f"{path} is not valid JSON: {exc}") from None
    except RecursionError:
        raise ValueError(f"{path} is not a ballpass dataset manifest: its JSON is nested "
                         "too deeply to read") from None
    if not isinstance(manifest, dict) or manifest.get("format") != "ballpass-dataset":
        raise ValueError(f"{path} is not a ballpass dataset manifest")
    shards = manifest.get("shards")
    if (not isinstance(shards, list) or not shards
            or not all(isinstance(s, dict) and {"file", "n_rows", "complete"} <= set(s)
                       for s in shards)):
        raise ValueError(f"{path} lists no shards (or shards without file, n_rows and "
                         "complete): the manifest is damaged. Generate the dataset again "
                         "into a new folder.")
    _check_version(path, manifest)
    _check_fields(path, manifest)
    _check_shard_entries(path, shards)
    total = sum(s["n_rows"] for s in shards)
    if manifest.get("n_rows", total) != total:
        raise ValueError(f"{path} records n_rows = {manifest['n_rows']!r} but its shards "
                         f"hold {total} rows: the manifest was altered. Generate the "
                         "dataset again into a new folder.")
    return manifest


def _check_version(path: Path, manifest: dict) -> None:
    """Refuse a manifest of a format this ballpass does not know."""
    version = manifest.get("format_version", 1)
    if isinstance(version, bool) or version not in range(1, FORMAT_VERSION + 1):
        raise ValueError(
            f"{path} has format_version {version!r}; this ballpass reads format versions "
            f"1 to {FORMAT_VERSION}. Read it with the ballpass that wrote it (a newer "
            "one: `pip install -U ballpass`), or generate the dataset again.")


def _whole(value, least: int = 0) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= least


#: the top-level fields every format version writes and readers use: name -> (test,
#: what the value must be)
_FIELDS = {
    "grid": (lambda v: isinstance(v, dict) and isinstance(v.get("dataset"), dict)
             and isinstance(v.get("grid"), dict), "a table with 'dataset' and 'grid' tables"),
    "n_rows": (_whole, "a whole number >= 0"),
    "n_runs": (_whole, "a whole number >= 0"),
    "root_seed": (_whole, "a whole number >= 0"),
    "fs": (lambda v: isinstance(v, (int, float)) and not isinstance(v, bool)
           and math.isfinite(v) and v > 0, "a positive number (Hz)"),
    "signal_length": (lambda v: _whole(v, 1), "a whole number >= 1"),
    "status": (lambda v: isinstance(v, str), "a text"),
}


def _check_fields(path: Path, manifest: dict) -> None:
    """Refuse a manifest missing a field the readers use, or holding a value of the
    wrong type or range there (a damaged or altered manifest), naming the field."""
    for key, (valid, what) in _FIELDS.items():
        if key not in manifest:
            raise ValueError(f"{path} has no {key!r}: the manifest is damaged. Generate the "
                             "dataset again into a new folder.")
        if not valid(manifest[key]):
            raise ValueError(f"{path}: {key} is {str(manifest[key])[:60]!r}, not {what}: "
                             "the manifest was altered. Generate the dataset again into a "
                             "new folder.")


def _check_shard_entries(path: Path, shards: list) -> None:
    """Each entry must name its own shard file, as the writer names it, in the folder.

    Entry ``i`` has ``index`` ``i`` and ``file`` ``part-0000i.parquet`` (nothing else:
    no folder, no ``..``, no absolute path, no other name), a whole ``n_rows`` >= 1 and
    a boolean ``complete``. So nothing outside the dataset folder is ever read, written
    or deleted because of what a manifest says.
    """
    seen = set()
    for position, shard in enumerate(shards):
        file, index = shard["file"], shard.get("index", position)
        expected = shard_name(position)
        if file != expected or index != position or isinstance(index, bool):
            twice = " (listed twice)" if file in seen else ""
            raise ValueError(
                f"{path}: shard entry {position} names file {file!r}{twice} with index "
                f"{index!r}, where ballpass writes shard {position} as {expected!r} in the "
                "dataset folder. The manifest was altered; nothing was read, written or "
                "deleted. Generate the dataset again into a new folder.")
        seen.add(file)
        n_rows = shard["n_rows"]
        if isinstance(n_rows, bool) or not isinstance(n_rows, int) or n_rows < 1:
            raise ValueError(f"{path}: shard {file} has n_rows {n_rows!r}, not a whole "
                             "number >= 1: the manifest was altered. Generate the dataset "
                             "again into a new folder.")
        for key in ("complete", "features_complete"):
            if not isinstance(shard.get(key, False), bool):
                raise ValueError(f"{path}: shard {file} has {key} {shard[key]!r}, not true "
                                 "or false: the manifest was altered. Generate the dataset "
                                 "again into a new folder.")


def file_sha256(path: Path) -> str:
    """SHA-256 of a file's bytes, hex."""
    with open(path, "rb") as fh:
        return hashlib.file_digest(fh, "sha256").hexdigest()


def write_table(path: Path, columns: dict, signals: np.ndarray | None = None,
                metadata: dict | None = None) -> tuple[int, str]:
    """Write one Parquet shard atomically; return its size (bytes) and SHA-256 (hex).

    The file is built in memory, hashed and written once, so the checksum is of the
    bytes written, without reading them back.

    Parameters
    ----------
    path : Path
        Final file name; the data goes to a temporary name first.
    columns : dict
        Column name -> sequence of values (one per row).
    signals : ndarray, shape (n_rows, L), optional
        Signals, stored as float32 in a ``fixed_size_list<float32>[L]`` column ``signal``.
    metadata : dict, optional
        JSON-able dict stored under the schema metadata key ``ballpass``.
    """
    import pyarrow as pa
    import pyarrow.parquet as pq

    arrays = {}
    encoding = {}
    if signals is not None:
        flat = pa.array(np.ascontiguousarray(signals, dtype=np.float32).reshape(-1))
        arrays["signal"] = pa.FixedSizeListArray.from_arrays(flat, signals.shape[1])
        encoding["signal.list.element"] = "BYTE_STREAM_SPLIT"
    arrays.update({k: pa.array(v) for k, v in columns.items()})
    table = pa.table(arrays)
    if metadata is not None:
        table = table.replace_schema_metadata({"ballpass": json.dumps(metadata)})
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink, compression="zstd", row_group_size=128,
                   use_dictionary=[k for k in columns
                                   if table.schema.field(k).type == pa.string()],
                   column_encoding=encoding or None, write_page_checksum=True)
    data = sink.getvalue()

    def write(tmp: Path) -> None:
        with open(tmp, "wb") as fh:
            fh.write(data)

    atomic_write(path, write)
    return data.size, hashlib.sha256(data).hexdigest()


def shard_complete(path: Path, n_rows: int) -> bool:
    """True when ``path`` is a readable Parquet file with ``n_rows`` rows."""
    import pyarrow.parquet as pq

    try:
        return pq.read_metadata(path).num_rows == n_rows
    except (OSError, ValueError):  # missing, truncated or not Parquet
        return False


def shard_problem(path: Path, shard: dict, key: str = "sha256") -> str | None:
    """What is wrong with a shard the manifest lists as complete, or None if it is intact.

    Checks that the file exists, has the recorded size and the recorded SHA-256
    (``shard[key]``; shards of the first layout carry no checksum), and that it holds
    the ``n_rows`` the manifest records (read from the file's footer, so an altered
    count is never reported as fact).
    """
    import pyarrow.parquet as pq

    # a shard or feature folder inside the dataset that links elsewhere is not read (a
    # link to the whole dataset folder is the user's own choice, and fine)
    if path.is_symlink() or (path.parent.name in (FEATURES_DIR, LEGACY_FEATURES_DIR)
                             and path.parent.is_symlink()):
        return "is a symbolic link (ballpass writes plain files in the dataset folder)"
    if not path.is_file():
        return "is missing (deleted or moved)"
    expected = shard.get(key)
    if expected is not None:
        size = path.stat().st_size
        recorded = shard.get("features_bytes" if key == "features_sha256" else "bytes")
        if recorded and size != recorded:
            return (f"has {size} bytes where the manifest records {recorded} (truncated or "
                    "altered)")
        if file_sha256(path) != expected:
            return "is corrupted: its SHA-256 differs from the one recorded in the manifest"
    try:
        rows = pq.read_metadata(path).num_rows
    except (OSError, ValueError):
        return "is not a readable Parquet file"
    if rows != shard["n_rows"]:
        return (f"holds {rows} rows where the manifest records {shard['n_rows']} (the "
                "manifest or the file was altered)")
    return None


def _shard_paths(path, features: bool = False,
                 warn: bool = True) -> tuple[list[Path], dict | None]:
    """Complete, verified shard files of a dataset folder (or one shard file) and its
    manifest.

    Raises
    ------
    CorruptShardError
        A shard listed as complete is missing or fails its checksum.
    """
    path = Path(path)
    if path.is_file():
        return [path], None
    if not path.is_dir():
        raise FileNotFoundError(f"{path} does not exist")
    manifest = read_manifest(path)
    if manifest is None:
        raise FileNotFoundError(f"{path} holds no {MANIFEST}: not a ballpass dataset")
    base = path / features_dir(manifest) if features else path
    complete, key = (("features_complete", "features_sha256") if features
                     else ("complete", "sha256"))
    files = []
    for shard in manifest["shards"]:
        if shard.get(complete):
            file = base / shard["file"]
            problem = shard_problem(file, shard, key)
            if problem is not None:
                raise CorruptShardError(
                    f"shard {file} {problem}. Run `ballpass generate` with the same grid "
                    f"and --out {path} again to regenerate it.")
            files.append(file)
    stray = sorted(p.name for p in path.glob("part-*.parquet")
                   if p.name not in {s["file"] for s in manifest["shards"]})
    if stray:
        warnings.warn(f"{path} holds {', '.join(stray)}, which its manifest does not list: "
                      "not part of the dataset (ballpass ignores them, other Parquet "
                      "readers of the folder would not); remove them", stacklevel=3)
    if warn and manifest.get("status") != "complete":
        warnings.warn(f"{path}: dataset is incomplete ({len(files)} of "
                      f"{len(manifest['shards'])} shards); run `ballpass generate` again to "
                      "finish it", stacklevel=3)
    return files, manifest


def _filter_expression(filters, names: list[str]):
    """pandas-style filters (list of tuples, or list of lists for OR) or an Expression,
    checked against the dataset's column ``names``."""
    import pyarrow.compute as pc
    import pyarrow.parquet as pq

    if filters is None or isinstance(filters, pc.Expression):
        return filters
    groups = filters if filters and all(isinstance(f, list) for f in filters) else [filters]
    for group in groups:
        if not isinstance(group, (list, tuple)) or not group:
            raise ValueError(f"filters must be a non-empty list of (column, op, value) "
                             f"tuples (or a list of such lists), got {filters!r}")
        for term in group:
            if not isinstance(term, (list, tuple)) or len(term) != 3:
                raise ValueError(f"filters: each term must be (column, op, value), "
                                 f"got {term!r}")
            if term[0] not in names:
                raise ValueError(f"filters: unknown column {term[0]!r}; the dataset has "
                                 f"{names}")
    try:
        return pq.filters_to_expression(filters)
    except (TypeError, ValueError, NotImplementedError) as exc:
        raise ValueError(f"filters {filters!r}: {exc}") from None


def _read(files: list[Path], columns, filters):
    import pyarrow as pa
    import pyarrow.dataset as ds

    if not files:
        raise ValueError("the dataset has no complete shards (yet): run `ballpass generate` "
                         "to write them")
    # page CRCs are verified as pages are read (shards written since format 2 carry them)
    fmt = ds.ParquetFileFormat(default_fragment_scan_options=ds.ParquetFragmentScanOptions(
        page_checksum_verification=True))
    try:
        dataset = ds.dataset([str(f) for f in files], format=fmt)
    except (OSError, pa.ArrowInvalid) as exc:
        raise CorruptShardError(f"cannot read the shards {[str(f) for f in files]}: {exc}"
                                ) from None
    names = dataset.schema.names
    if columns is not None:
        columns = list(dict.fromkeys(columns))
        unknown = set(columns) - set(names)
        if unknown:
            raise ValueError(f"unknown column(s) {sorted(unknown)}; the dataset has {names}")
    expression = _filter_expression(filters, names)
    try:
        return dataset.to_table(columns=columns, filter=expression)
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError, pa.ArrowTypeError) as exc:
        if filters is not None:
            raise ValueError(f"filters {filters!r} cannot be applied: {exc}") from None
        raise CorruptShardError(f"cannot read the shards: {exc}") from None
    except OSError as exc:
        raise CorruptShardError(f"cannot read the shards: {exc}") from None


#: metadata columns added since the first datasets -> (the column they follow, the value
#: every fault row written before had: the grid could not set another). A dataset resumes
#: only with its own grid, so all fault rows of a dataset begun before the column have
#: it, also those written after: :func:`load` fills it where a shard lacks the column (or
#: the column is missing). Healthy rows get NaN, as do all rows for ``clearance_um``
#: (NaN: the bearing's catalogue clearance, the only one the grid could give).
ADDED_COLUMNS = {"fault_engagement": ("fault_angle_deg", 1.0),
                 "clearance_um": ("radial_load_n", np.nan)}


def _fill_added_columns(meta, insert: bool) -> None:
    """Give rows written before a column of :data:`ADDED_COLUMNS` existed its value
    then: the old value for fault rows, NaN for healthy ones (in place; ``insert``: also
    add the column to a table of a dataset that has none)."""
    for name, (after, old) in ADDED_COLUMNS.items():
        if "label" not in meta or (name not in meta and not insert):
            continue
        if name not in meta:
            meta.insert(int(meta.columns.get_loc(after)) + 1
                        if after in meta else len(meta.columns), name, np.nan)
        missing = meta[name].isna() & (meta["label"] != "healthy")
        meta.loc[missing, name] = old


def load(path, columns=None, filters=None):
    """Load a dataset (or one shard) as a signal matrix and a metadata table.

    Parameters
    ----------
    path : str or os.PathLike
        A dataset folder written by :func:`~ballpass.datasets.generate`, or one of its
        Parquet shards. Only complete shards are read; an unfinished dataset warns.
    columns : list of str, optional
        Metadata columns to return (default: all). The signal is always loaded.
    filters : list of tuples or pyarrow.compute.Expression, optional
        Row filter, in the ``pandas.read_parquet`` form, e.g.
        ``[("label", "in", ["outer", "inner"]), ("rpm", ">=", 1750)]``; a list of such
        lists is OR-ed.

    Returns
    -------
    X : ndarray of float32, shape (n_rows, signal_length)
        Signals, m/s^2, in shard and row order.
    meta : pandas.DataFrame
        One row per signal: ``label``, the parameters, ``run_id``, ``group``, ``sensor``,
        ``segment``, ``seed``, ``model``, ... Rows written before a parameter column
        existed get the value they were simulated with (``fault_engagement`` 1 for a
        fault row of a dataset written before that column, ``clearance_um`` NaN: the
        bearing's catalogue clearance).

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets import generate, load
    >>> grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "repeats": 2, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797],
    ...                  "resonance_hz": [3000]}}
    >>> out = tempfile.mkdtemp() + "/quick"
    >>> _ = generate(grid, out, progress=False)
    >>> X, meta = load(out, filters=[("label", "==", "outer")])
    >>> X.shape, X.dtype, meta["label"].unique().tolist()
    ((2, 3000), dtype('float32'), ['outer'])
    """
    files, _ = _shard_paths(path)
    cols = None if columns is None else ["signal", *columns]
    table = _read(files, cols, filters)
    signal = table.column("signal")
    length = signal.type.list_size
    X = signal.combine_chunks().flatten().to_numpy().reshape(-1, length)
    meta = table.drop_columns(["signal"]).to_pandas()
    _fill_added_columns(meta, insert=columns is None)
    return X, meta


def load_features(path, filters=None):
    """The feature table of a dataset written with ``features=True``, as a DataFrame.

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets import generate
    >>> grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "repeats": 2, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797],
    ...                  "resonance_hz": [3000]}}
    >>> out = tempfile.mkdtemp() + "/quick"
    >>> _ = generate(grid, out, features=True, progress=False)
    >>> from ballpass.datasets import load_features
    >>> table = load_features(out)
    >>> len(table), "crest_factor" in table.columns
    (4, True)
    """
    files, _ = _shard_paths(path, features=True)
    return _read(files, None, filters).to_pandas()


def _live_status(folder: Path, manifest: dict) -> str:
    """The manifest's status, but ``"interrupted"`` for a run that says ``"running"``
    while no process holds the folder's lock (it was killed or stopped)."""
    status = manifest.get("status")
    if status != "running":
        return status
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows: no lock to ask
        return status
    try:
        with open(folder / LOCK_FILE, "rb") as fh:
            fcntl.flock(fh, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except BlockingIOError:
        return status          # a generate holds it right now
    except FileNotFoundError:
        pass
    except OSError:            # cannot ask (e.g. unreadable lock): say what the file says
        return status
    return "interrupted"


#: columns whose distinct combinations form an operating condition in :func:`info`
CONDITION_COLUMNS = ("bearing", "rpm", "radial_load_n", "sensor")
#: Fault-size columns that ``info`` breaks the faulty rows down by (mm).
SIZE_COLUMNS = ("fault_width_mm", "fault_depth_mm")


def info(path) -> dict:
    """Summarise a dataset without decoding its signals (their shards are checksummed).

    Parameters
    ----------
    path : str or os.PathLike
        Dataset folder.

    Returns
    -------
    dict
        ``status`` (``"complete"``, ``"running"`` while a generate works on it, or
        ``"interrupted"``: stopped before the end, rerun generate to resume), ``n_rows``,
        ``n_runs``, ``shards_complete``, ``shards_total``,
        ``fs`` (Hz), ``duration_s`` (s per row), ``signal_length``, ``size_bytes`` (on
        disk), ``ballpass_version``, ``labels`` (pandas Series: rows per label) and
        ``conditions`` (DataFrame: rows per label for each condition, columns
        ``bearing, rpm, radial_load_n, sensor``) and ``fault_sizes`` (DataFrame: faulty
        rows per fault width and depth, mm, and label; for sizes drawn from a
        distribution, their count, minimum, median and maximum per label; None without
        faulty rows).

    Raises
    ------
    CorruptShardError
        A complete shard (signals or features) is missing or fails its SHA-256: every
        shard is read once to verify it.

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets import generate
    >>> grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "repeats": 2, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797],
    ...                  "resonance_hz": [3000]}}
    >>> out = tempfile.mkdtemp() + "/quick"
    >>> _ = generate(grid, out, progress=False)
    >>> from ballpass.datasets import info
    >>> summary = info(out)
    >>> summary["status"], summary["n_rows"], summary["fs"], summary["signal_length"]
    ('complete', 4, 12000.0, 3000)
    >>> summary["labels"].to_dict()
    {'healthy': 2, 'outer': 2}
    """
    path = Path(path)
    if path.is_file():
        raise ValueError(f"{path} is a file; info takes a dataset folder")
    files, manifest = _shard_paths(path, warn=False)
    has_features = any(s.get("features_complete") for s in manifest["shards"])
    if has_features:
        _shard_paths(path, features=True, warn=False)     # verify the feature table too
    meta = None
    if files:
        import pyarrow.parquet as pq

        present = set(pq.read_schema(files[0]).names)
        meta = _read(files, ["label", *CONDITION_COLUMNS, "run_id",
                             *(c for c in SIZE_COLUMNS if c in present)], None).to_pandas()
    size = sum(f.stat().st_size for f in path.rglob("*") if f.is_file())
    out = {
        "path": str(path),
        "status": _live_status(path, manifest),
        "ballpass_version": manifest["ballpass_version"],
        "shards_complete": len(files),
        "shards_total": len(manifest["shards"]),
        "n_rows": 0 if meta is None else len(meta),
        "n_rows_planned": manifest["n_rows"],
        "n_runs": 0 if meta is None else meta["run_id"].nunique(),
        "fs": manifest["fs"],
        "duration_s": manifest["signal_length"] / manifest["fs"],
        "signal_length": manifest["signal_length"],
        "size_bytes": size,
        "features": has_features,
        "drawn": drawn_axes(manifest["grid"]) if "grid" in manifest else {},
    }
    if meta is not None:
        out["labels"] = meta["label"].value_counts().sort_index()
        out["conditions"] = (meta.groupby([*CONDITION_COLUMNS, "label"]).size()
                             .unstack("label", fill_value=0))
        out["fault_sizes"] = _fault_sizes(meta)
    return out


def _fault_sizes(meta):
    """Faulty rows per fault size and label: a count per (width, depth) when the sizes are
    a few listed values, else (sizes drawn from a distribution) the range of each."""
    sizes = [c for c in SIZE_COLUMNS if c in meta.columns]
    faulty = meta[meta["label"] != "healthy"]
    if not sizes or faulty.empty:
        return None
    if faulty[sizes].drop_duplicates().shape[0] <= 24:
        return faulty.groupby([*sizes, "label"]).size().unstack("label", fill_value=0)
    return faulty.groupby("label")[sizes].describe().loc[
        :, (slice(None), ["count", "min", "50%", "max"])]
