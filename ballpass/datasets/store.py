"""On-disk dataset format: a folder with ``manifest.json`` and Parquet shards.

Layout::

    DIR/manifest.json            grid, package version, root seed, units, shard list, status
    DIR/.lock                    held (flock) by the process generating the dataset
    DIR/part-00000.parquet       one signal per row + label and parameter columns
    DIR/part-00001.parquet       ...
    DIR/features/part-00000.parquet   optional feature table, same rows and keys

Each row holds one signal in the ``signal`` column, a ``fixed_size_list<float32>``
of the dataset's ``signal_length`` samples (m/s^2, zstd-compressed with
byte-stream-split encoding), next to its label, parameters, ``run_id``, ``group``,
``sensor``, ``segment``, the run's ``seed``, the resolved ``model`` and ``solver`` and
the run's scene as JSON (``scene``), from which :func:`~ballpass.datasets.regenerate`
rebuilds it bit for bit. Shards are written under a temporary name and renamed
(:func:`os.replace`) when complete; the manifest is replaced the same way. Plain
``pandas.read_parquet`` and DuckDB read the shards (the signal comes back as an
object column of arrays); :func:`load` returns it as one float32 matrix.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np

from ..signalio import atomic_write

__all__ = ["load", "info", "read_manifest", "MANIFEST", "UNITS"]

MANIFEST = "manifest.json"
FEATURES_DIR = "features"
LOCK_FILE = ".lock"
FORMAT_VERSION = 1

#: units of the stored columns
UNITS = {
    "signal": "m/s^2", "fs": "Hz", "duration_s": "s", "start_s": "s", "rpm": "rpm",
    "rpm_start": "rpm", "rpm_end": "rpm", "radial_load_n": "N", "fault_width_mm": "mm",
    "fault_depth_mm": "mm", "fault_angle_deg": "deg from the load line", "slip": "1",
    "snr_db": "dB (inf = noise-free)", "noise_rms": "m/s^2 (0 = none)", "resonance_hz": "Hz",
    "resonance_damping": "1",
}


def human_bytes(n: float) -> str:
    """A size in bytes as text with a decimal unit (B, kB, MB, GB)."""
    for unit in ("B", "kB", "MB"):
        if n < 1000:
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.1f} {unit}"
        n /= 1000
    return f"{n:.1f} GB"


def shard_name(index: int) -> str:
    """File name of shard ``index``."""
    return f"part-{index:05d}.parquet"


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
    """Write ``manifest.json`` atomically (strict JSON)."""
    text = json.dumps(manifest, indent=1, allow_nan=False)
    atomic_write(folder / MANIFEST, lambda p: p.write_text(text))


def read_manifest(folder) -> dict | None:
    """The manifest of a dataset folder, or None if it has none.

    Raises
    ------
    ValueError
        If ``manifest.json`` exists but is not a ballpass manifest.
    """
    path = Path(folder) / MANIFEST
    if not path.is_file():
        return None
    try:
        manifest = json.loads(path.read_text())
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path} is not valid JSON: {exc}") from None
    if not isinstance(manifest, dict) or manifest.get("format") != "ballpass-dataset":
        raise ValueError(f"{path} is not a ballpass dataset manifest")
    return manifest


def write_table(path: Path, columns: dict, signals: np.ndarray | None = None,
                metadata: dict | None = None) -> int:
    """Write one Parquet shard atomically; return its size, bytes.

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
        flat = pa.array(np.ascontiguousarray(signals, dtype=np.float32).ravel())
        arrays["signal"] = pa.FixedSizeListArray.from_arrays(flat, signals.shape[1])
        encoding["signal.list.element"] = "BYTE_STREAM_SPLIT"
    arrays.update({k: pa.array(v) for k, v in columns.items()})
    table = pa.table(arrays)
    if metadata is not None:
        table = table.replace_schema_metadata({"ballpass": json.dumps(metadata)})
    atomic_write(path, lambda p: pq.write_table(
        table, p, compression="zstd", row_group_size=128,
        use_dictionary=[k for k in columns if table.schema.field(k).type == pa.string()],
        column_encoding=encoding or None))
    return path.stat().st_size


def shard_complete(path: Path, n_rows: int) -> bool:
    """True when ``path`` is a readable Parquet file with ``n_rows`` rows."""
    import pyarrow.parquet as pq

    try:
        return pq.read_metadata(path).num_rows == n_rows
    except (OSError, ValueError):  # missing, truncated or not Parquet
        return False


def _shard_paths(path, subfolder: str | None = None,
                 warn: bool = True) -> tuple[list[Path], dict | None]:
    """Complete shard files of a dataset folder (or one shard file) and its manifest."""
    path = Path(path)
    if path.is_file():
        return [path], None
    manifest = read_manifest(path)
    if manifest is None:
        raise FileNotFoundError(f"{path} holds no {MANIFEST}: not a ballpass dataset")
    base = path / subfolder if subfolder else path
    key = "features_complete" if subfolder else "complete"
    files = [base / s["file"] for s in manifest["shards"] if s.get(key)]
    if warn and manifest["status"] != "complete":
        warnings.warn(f"{path}: dataset is incomplete ({len(files)} of "
                      f"{len(manifest['shards'])} shards); run `ballpass generate` again to "
                      "finish it", stacklevel=3)
    return files, manifest


def _filter_expression(filters):
    """pandas-style filters (list of tuples, or list of lists for OR) or an Expression."""
    import pyarrow.compute as pc
    import pyarrow.parquet as pq

    if filters is None or isinstance(filters, pc.Expression):
        return filters
    return pq.filters_to_expression(filters)


def _read(files: list[Path], columns, filters):
    import pyarrow.dataset as ds

    if not files:
        raise ValueError("the dataset has no complete shards (yet): run `ballpass generate` "
                         "to write them")
    dataset = ds.dataset([str(f) for f in files], format="parquet")
    if columns is not None:
        columns = list(dict.fromkeys(columns))
        unknown = set(columns) - set(dataset.schema.names)
        if unknown:
            raise ValueError(f"unknown column(s) {sorted(unknown)}; the dataset has "
                             f"{dataset.schema.names}")
    return dataset.to_table(columns=columns, filter=_filter_expression(filters))


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
        ``segment``, ``seed``, ``model``, ...

    Examples
    --------
    >>> X, meta = load("out/cwru_like")                            # doctest: +SKIP
    >>> X, meta = load("out/cwru_like", filters=[("sensor", "==", "loaded")])  # doctest: +SKIP
    """
    files, _ = _shard_paths(path)
    cols = None if columns is None else ["signal", *columns]
    table = _read(files, cols, filters)
    signal = table.column("signal")
    length = signal.type.list_size
    X = signal.combine_chunks().flatten().to_numpy().reshape(-1, length)
    meta = table.drop_columns(["signal"]).to_pandas()
    return X, meta


def load_features(path, filters=None):
    """The feature table of a dataset written with ``features=True``, as a DataFrame."""
    files, _ = _shard_paths(path, FEATURES_DIR)
    return _read(files, None, filters).to_pandas()


#: columns whose distinct combinations form an operating condition in :func:`info`
CONDITION_COLUMNS = ("bearing", "rpm", "radial_load_n", "sensor")


def info(path) -> dict:
    """Summarise a dataset without reading its signals.

    Parameters
    ----------
    path : str or os.PathLike
        Dataset folder.

    Returns
    -------
    dict
        ``status``, ``n_rows``, ``n_runs``, ``shards_complete``, ``shards_total``,
        ``fs`` (Hz), ``duration_s`` (s per row), ``signal_length``, ``size_bytes`` (on
        disk), ``ballpass_version``, ``labels`` (pandas Series: rows per label) and
        ``conditions`` (DataFrame: rows per label for each condition, columns
        ``bearing, rpm, radial_load_n, sensor``).
    """
    path = Path(path)
    files, manifest = _shard_paths(path, warn=False)
    meta = (_read(files, ["label", *CONDITION_COLUMNS, "run_id"], None).to_pandas()
            if files else None)
    size = sum(f.stat().st_size for f in path.rglob("*") if f.is_file())
    out = {
        "path": str(path),
        "status": manifest["status"],
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
        "features": any(s.get("features_complete") for s in manifest["shards"]),
    }
    if meta is not None:
        out["labels"] = meta["label"].value_counts().sort_index()
        out["conditions"] = (meta.groupby([*CONDITION_COLUMNS, "label"]).size()
                             .unstack("label", fill_value=0))
    return out
