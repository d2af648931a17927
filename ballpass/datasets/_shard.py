"""One shard of a dataset, a pure function of the grid and its index: simulate its runs,
cut the rows, write one Parquet file (and its feature table) under a temporary name that
is renamed when complete; :func:`regenerate` rebuilds one row bit for bit.

This is the code that runs in the worker processes (or on a Dask cluster) of
:func:`ballpass.datasets.generate`.
"""

from __future__ import annotations

import json
import math
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .grid import TWIN_AXES, Run, scene_from_dict
from .store import (
    FEATURES_DIR,
    UNITS,
    load,
    shard_name,
    write_table,
)

#: metadata columns of a dataset, in stored order (the signal column comes first)
COLUMNS = (
    "label", "bearing", "fault_width_mm", "fault_depth_mm", "fault_angle_deg",
    "fault_engagement", "rpm", "rpm_start", "rpm_end", "radial_load_n", "clearance_um", "slip",
    "snr_db", "noise_rms", "resonance_hz", "resonance_damping", "sensor",
    "segment", "start_s", "duration_s", "fs", "run_id", "group", "repeat", "seed", "model",
    "solver", "scene",
)


def _simulate_run(run: Run, solver: str, signal_length: int, n_segments: int):
    """Simulate one run and cut it into rows.

    Returns
    -------
    signals : ndarray of float32, shape (n_sensors * n_segments, signal_length)
        m/s^2; rows ordered by sensor, then segment.
    columns : dict of lists
        Label and parameter columns, one value per row.
    """
    scene = run.build_scene()
    if run.machine is not None:   # a twin's run: learned path and real background
        from .twin import twin_signal

        accel, info, extra = twin_signal(run, scene)
        sensor_names = (scene.sensors[0].name,)
    else:
        from ..simulate import simulate

        res = simulate(scene, model=run.model, solver=solver)
        accel, info, extra = np.atleast_2d(res.accel), res.info, {}
        sensor_names = res.sensor_names
    fault = scene.faults[0] if scene.faults else None
    speed = scene.speed
    scene_json = json.dumps(run.scene, sort_keys=True)
    per_run = {
        "label": scene.label,
        "bearing": scene.bearing.name,
        "fault_width_mm": fault.width_mm if fault else math.nan,
        "fault_depth_mm": fault.depth_mm if fault else math.nan,
        "fault_angle_deg": fault.angle_deg if fault else math.nan,
        "fault_engagement": fault.engagement if fault else math.nan,
        "rpm_start": speed.rpm_start,
        "rpm_end": speed.rpm_end,
        "radial_load_n": scene.radial_load_n,
        "clearance_um": math.nan if scene.clearance_um is None else scene.clearance_um,
        "slip": scene.slip,
        "snr_db": math.inf if scene.snr_db is None else scene.snr_db,
        "noise_rms": scene.noise_rms or 0.0,
        "resonance_hz": scene.resonance_hz,
        "resonance_damping": scene.resonance_damping,
        "fs": scene.fs,
        "duration_s": signal_length / scene.fs,
        "run_id": run.run_id,
        "group": run.run_id,
        "repeat": run.repeat,
        "seed": run.seed,
        "model": info["model"],
        "solver": info["solver"],
        "scene": scene_json,
        **run.columns,  # realism axes, and which draw of a drawn grid
        **extra,
    }
    signals, rows = [], []
    for k, sensor in enumerate(sensor_names):
        for seg in range(n_segments):
            start = seg * signal_length
            signals.append(accel[k, start:start + signal_length])
            t_mid = (start + 0.5 * signal_length) / scene.fs
            rows.append({**per_run, "sensor": sensor, "segment": seg, "start_s": start / scene.fs,
                         # mean speed over the row: a linear ramp's value at its mid-time
                         "rpm": extra.get("rpm", float(speed.rpm_at(t_mid, scene.duration_s)))})
    keys = dict.fromkeys((*COLUMNS, *run.columns, *extra))
    columns = {key: [row[key] for row in rows] for key in keys}
    return np.asarray(signals, dtype=np.float32), columns


#: metadata columns :func:`regenerate` needs
_ROW_KEYS = ("scene", "model", "solver", "run_id", "repeat", "sensor", "segment", "duration_s")


def regenerate(row) -> np.ndarray:
    """Simulate one stored row again; the result equals the stored signal exactly.

    Parameters
    ----------
    row : mapping
        A row of the metadata returned by :func:`~ballpass.datasets.load` (a
        ``pandas.Series`` or dict with at least ``scene``, ``model``, ``solver``,
        ``run_id``, ``repeat``, ``sensor``, ``segment`` and ``duration_s``).

    Returns
    -------
    ndarray of float32, shape (signal_length,)
        The row's signal, m/s^2.

    Raises
    ------
    ValueError
        The row lacks a column, or its ``scene``, ``sensor`` or ``segment`` do not
        describe a stored row.

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets import generate, load, regenerate
    >>> grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "repeats": 2, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797],
    ...                  "resonance_hz": [3000]}}
    >>> out = tempfile.mkdtemp() + "/quick"
    >>> _ = generate(grid, out, progress=False)
    >>> X, meta = load(out)
    >>> bool((regenerate(meta.iloc[3]) == X[3]).all())    # bit for bit from its row
    True
    """
    missing = [k for k in _ROW_KEYS if k not in row]
    if missing:
        raise ValueError(f"row lacks {missing}: pass a row of the metadata returned by "
                         "ballpass.datasets.load (all columns)")
    try:
        scene = json.loads(row["scene"])
        if not isinstance(scene, dict):
            raise TypeError(f"a JSON object is expected, got {type(scene).__name__}")
        built = scene_from_dict(scene)
        machine = row.get("machine")   # a twin's row: its manifest and level
        run = Run(run_id=int(row["run_id"]), repeat=int(row["repeat"]), model=row["model"],
                  scene=scene, machine=machine if isinstance(machine, str) else None,
                  columns={k: float(row[k]) for k in TWIN_AXES if k in row}
                  if isinstance(machine, str) else {})
        length = round(float(row["duration_s"]) * built.fs)
        segment = int(row["segment"])
    except (TypeError, ValueError) as exc:
        raise ValueError(f"row['scene'] = {str(row['scene'])[:80]!r} is not a stored dataset "
                         f"scene: {exc}") from None
    names = [s.name for s in built.sensors]
    if row["sensor"] not in names or not 0 <= segment < built.n_samples // max(length, 1):
        raise ValueError(f"row['sensor'] = {row['sensor']!r} and row['segment'] = {segment} "
                         f"do not name a row of this scene (sensors {names}, segments of "
                         f"{length} samples)")
    signals, columns = _simulate_run(run, row["solver"], length, segment + 1)
    return signals[names.index(row["sensor"]) * (segment + 1) + segment]


# ----------------------------------------------------------------------------- shards
@dataclass(frozen=True)
class ShardSpec:
    """Everything one shard needs; picklable, so it runs on any worker.

    Attributes
    ----------
    index : int
        Shard number.
    folder : str
        Absolute path of the dataset folder (shared storage on a cluster).
    runs : tuple of Run
        The shard's runs.
    solver : str
        Solver requested for every run.
    signal_length, n_segments : int
        Samples per row; rows cut from each run and sensor.
    n_rows : int
        Rows the shard holds.
    simulate : bool
        Simulate and write the signal shard (False: it exists, only features are missing).
    features : bool
        Also write the shard's feature table.
    """

    index: int
    folder: str
    runs: tuple
    solver: str
    signal_length: int
    n_segments: int
    n_rows: int
    simulate: bool = True
    features: bool = False


def run_shard(spec: ShardSpec) -> dict:
    """Simulate and write one shard; return a small report.

    Pure apart from the files it writes: the same spec always writes the same rows.

    Returns
    -------
    dict
        ``index``, ``n_rows``, ``bytes`` and ``sha256`` (signal shard, if simulated),
        ``features_bytes`` and ``features_sha256`` (if written), ``models`` (Counter of
        resolved models) and ``simulated`` (bool).
    """
    folder = Path(spec.folder)
    path = folder / shard_name(spec.index)
    report = {"index": spec.index, "n_rows": spec.n_rows, "models": Counter(),
              "simulated": spec.simulate, "bytes": 0, "features_bytes": 0}
    if spec.simulate:
        parts = []
        for run in spec.runs:
            try:
                parts.append(_simulate_run(run, spec.solver, spec.signal_length,
                                           spec.n_segments))
            except Exception as exc:
                exc.add_note(f"in dataset run {run.run_id} (shard {spec.index}); complete "
                             "shards are kept, run generate again to resume")
                raise
        signals = np.concatenate([p[0] for p in parts])
        columns = {k: [v for p in parts for v in p[1][k]] for k in parts[0][1]}
        report["models"] = Counter(p[1]["model"][0] for p in parts)
        report["bytes"], report["sha256"] = write_table(
            path, columns, signals, metadata={"shard": spec.index, "units": UNITS})
    if spec.features:
        if not spec.simulate:
            signals, meta = load(path)
            columns = meta.to_dict(orient="list")
        report["features_bytes"], report["features_sha256"] = _write_features(
            folder, spec.index, signals, columns)
    return report


#: metadata columns repeated in the feature table (its rows follow the signal shard's)
FEATURE_KEYS = ("label", "bearing", "fault_width_mm", "fault_depth_mm", "rpm", "radial_load_n",
                "snr_db", "sensor", "segment", "run_id", "group")


def feature_columns(signals: np.ndarray, fs: float, bearing, rpm) -> dict[str, np.ndarray]:
    """Features of stored signals: :func:`ballpass.features.indicators` and the fault-band
    levels of :func:`ballpass.features.fault_band_features` (demodulation band from the
    kurtogram), both from one :func:`ballpass.features.envelope_analysis` per bearing.

    Parameters
    ----------
    signals : ndarray, shape (n_rows, n_samples)
        Signals as stored (float32), m/s^2.
    fs : float
        Sampling rate, Hz.
    bearing, rpm : array_like, shape (n_rows,)
        Catalogue bearing name and mean shaft speed (rpm) of each row.

    Returns
    -------
    dict of str to ndarray of shape (n_rows,)
        Indicators (units of the signal or dimensionless) and fault-band levels (dB).
    """
    from .. import features

    bearing, rpm = np.asarray(bearing), np.asarray(rpm, dtype=float)
    names = list(features.INDICATORS) + features.fault_band_names()
    out = {name: np.empty(len(signals)) for name in names}
    for name in np.unique(bearing):
        rows = bearing == name
        result = features.envelope_analysis(signals[rows], fs, rpm=rpm[rows], bearing=str(name))
        for key, value in (result.indicators | result.fault_bands).items():
            out[key][rows] = value
    return out


def _write_features(folder: Path, index: int, signals: np.ndarray,
                    columns: dict) -> tuple[int, str]:
    """Write the feature table of one shard: :data:`FEATURE_KEYS` then the features;
    return its size (bytes) and SHA-256."""
    out = {k: list(columns[k]) for k in FEATURE_KEYS}
    out.update(feature_columns(signals, columns["fs"][0], columns["bearing"], columns["rpm"]))
    (folder / FEATURES_DIR).mkdir(exist_ok=True)
    return write_table(folder / FEATURES_DIR / shard_name(index), out)
