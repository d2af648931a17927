"""Generate a dataset over a grid: plan shards, simulate them in parallel, store, resume.

Each shard is a pure function of the grid and its index (:func:`run_shard`): it
simulates its runs, cuts the rows and writes one Parquet file under a temporary name
that is renamed when complete. The parent process plans the shards, skips those
already complete, dispatches the rest to joblib worker processes (default) or to any
:class:`concurrent.futures.Executor` (a Dask ``client.get_executor()`` runs them
across machines), and keeps ``manifest.json`` up to date after every shard.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import json
import math
import os
import tempfile
import time
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .grid import Grid, Run, read_grid
from .store import (
    FEATURES_DIR,
    FORMAT_VERSION,
    LOCK_FILE,
    UNITS,
    human_bytes,
    is_temporary,
    load,
    read_manifest,
    remove_temporaries,
    shard_complete,
    shard_name,
    write_manifest,
    write_table,
)

__all__ = ["generate", "dry_run", "regenerate", "run_shard", "GenerateSummary", "Estimate"]


# ----------------------------------------------------------------------------- one run
#: metadata columns of a dataset, in stored order (the signal column comes first)
COLUMNS = (
    "label", "bearing", "fault_width_mm", "fault_depth_mm", "fault_angle_deg", "rpm",
    "rpm_start", "rpm_end", "radial_load_n", "slip", "snr_db", "noise_rms", "resonance_hz",
    "resonance_damping", "sensor",
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
    from ..simulate import simulate

    scene = run.build_scene()
    res = simulate(scene, model=run.model, solver=solver)
    accel = np.atleast_2d(res.accel)
    fault = scene.faults[0] if scene.faults else None
    speed = scene.speed
    scene_json = json.dumps(run.scene, sort_keys=True)
    per_run = {
        "label": scene.label,
        "bearing": scene.bearing.name,
        "fault_width_mm": fault.width_mm if fault else math.nan,
        "fault_depth_mm": fault.depth_mm if fault else math.nan,
        "fault_angle_deg": fault.angle_deg if fault else math.nan,
        "rpm_start": speed.rpm_start,
        "rpm_end": speed.rpm_end,
        "radial_load_n": scene.radial_load_n,
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
        "model": res.info["model"],
        "solver": res.info["solver"],
        "scene": scene_json,
    }
    signals, rows = [], []
    for k, sensor in enumerate(res.sensor_names):
        for seg in range(n_segments):
            start = seg * signal_length
            signals.append(accel[k, start:start + signal_length])
            t_mid = (start + 0.5 * signal_length) / scene.fs
            rows.append({**per_run, "sensor": sensor, "segment": seg, "start_s": start / scene.fs,
                         # mean speed over the row: a linear ramp's value at its mid-time
                         "rpm": float(speed.rpm_at(t_mid, scene.duration_s))})
    columns = {key: [row[key] for row in rows] for key in COLUMNS}
    return np.asarray(signals, dtype=np.float32), columns


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

    Examples
    --------
    >>> X, meta = load("out/quick")                                  # doctest: +SKIP
    >>> (regenerate(meta.iloc[3]) == X[3]).all()                     # doctest: +SKIP
    True
    """
    scene = json.loads(row["scene"])
    run = Run(run_id=int(row["run_id"]), repeat=int(row["repeat"]), model=row["model"],
              scene=scene)
    length = round(float(row["duration_s"]) * scene["fs"])
    n_segments = int(row["segment"]) + 1
    signals, columns = _simulate_run(run, row["solver"], length, n_segments)
    i = next(i for i, (s, g) in enumerate(zip(columns["sensor"], columns["segment"],
                                              strict=True))
             if s == row["sensor"] and g == int(row["segment"]))
    return signals[i]


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
        ``index``, ``n_rows``, ``bytes`` (signal shard), ``features_bytes``,
        ``models`` (Counter of resolved models) and ``simulated`` (bool).
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
        report["bytes"] = write_table(path, columns, signals,
                                      metadata={"shard": spec.index, "units": UNITS})
    if spec.features:
        if not spec.simulate:
            signals, meta = load(path)
            columns = meta.to_dict(orient="list")
        report["features_bytes"] = _write_features(folder, spec.index, signals, columns)
    return report


#: metadata columns repeated in the feature table (its rows follow the signal shard's)
FEATURE_KEYS = ("label", "bearing", "fault_width_mm", "fault_depth_mm", "rpm", "radial_load_n",
                "snr_db", "sensor", "segment", "run_id", "group")


def feature_columns(signals: np.ndarray, fs: float, bearing, rpm) -> dict[str, np.ndarray]:
    """Features of stored signals: :func:`ballpass.features.indicators` and
    :func:`ballpass.features.fault_band_features` (demodulation band from the kurtogram).

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

    out = dict(features.indicators(signals))
    bearing, rpm = np.asarray(bearing), np.asarray(rpm, dtype=float)
    bands = {name: np.empty(len(signals)) for name in features.fault_band_names()}
    for name in np.unique(bearing):
        rows = bearing == name
        for key, value in features.fault_band_features(signals[rows], fs, str(name),
                                                       rpm[rows]).items():
            bands[key][rows] = value
    return out | bands


def _write_features(folder: Path, index: int, signals: np.ndarray, columns: dict) -> int:
    """Write the feature table of one shard: :data:`FEATURE_KEYS` then the features."""
    out = {k: list(columns[k]) for k in FEATURE_KEYS}
    out.update(feature_columns(signals, columns["fs"][0], columns["bearing"], columns["rpm"]))
    (folder / FEATURES_DIR).mkdir(exist_ok=True)
    return write_table(folder / FEATURES_DIR / shard_name(index), out)


def _dispatch(specs: list[ShardSpec], n_jobs: int, executor):
    """Run the shards; yield their reports as they complete."""
    if executor is not None:
        futures = [executor.submit(run_shard, s) for s in specs]
        try:
            for fut in cf.as_completed(futures):
                yield fut.result()
        finally:
            for fut in futures:
                fut.cancel()
    elif n_jobs == 1:
        yield from map(run_shard, specs)
    else:
        from joblib import Parallel, delayed

        yield from Parallel(n_jobs=n_jobs, return_as="generator_unordered")(
            delayed(run_shard)(s) for s in specs)


# ----------------------------------------------------------------------------- planning
def _resolved_models(grid: Grid) -> list[tuple[str, Run]]:
    """(resolved model, first run) per grid point, in order; unknown models and solvers
    raise here."""
    from ..simulate import SOLVERS, resolve_model

    if grid.dataset["solver"] not in ("auto", *SOLVERS):
        raise ValueError(f"dataset.solver must be 'auto' or one of {sorted(SOLVERS)}, "
                         f"got {grid.dataset['solver']!r}")

    repeats = grid.dataset["repeats"]
    out = []
    for run in grid.runs[::repeats]:
        try:
            out.append((resolve_model(run.build_scene(), run.model), run))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"model {run.model!r} (run {run.run_id}): {exc}") from None
    return out


_WARM_UP_S = 0.01  # s simulated per model to compile its kernels


def _warm_up(representatives: dict[str, Run], solver: str) -> None:
    """Compile every model's kernels in this process, so workers load the numba cache."""
    from ..simulate import simulate

    for run in representatives.values():
        scene = run.build_scene()
        simulate(scene.replace(duration_s=min(scene.duration_s, _WARM_UP_S)),
                 model=run.model, solver=solver)


def _prepare_folder(folder: Path, grid: Grid) -> dict | None:
    """Check the output folder before any work; return its manifest if it has one.

    Raises
    ------
    ValueError
        The folder holds a dataset of another grid or ballpass version.
    FileExistsError
        The folder exists, is not empty and is not a ballpass dataset.
    PermissionError
        The folder cannot be created or written.
    """
    from .. import __version__

    manifest = read_manifest(folder) if folder.is_dir() else None
    if manifest is not None:
        if manifest["grid"] != grid.as_dict():
            raise ValueError(
                f"{folder} already holds a dataset of another grid; refusing to mix them. "
                "Use a new --out folder (or delete this one to start over).")
        if manifest["ballpass_version"] != __version__:
            raise ValueError(
                f"{folder} was generated by ballpass {manifest['ballpass_version']}, this is "
                f"{__version__}: signals would differ. Finish it with that version or use a "
                "new folder.")
    elif folder.exists() and (not folder.is_dir() or any(  # a kill can leave these behind
            not (is_temporary(p) or p.name == LOCK_FILE) for p in folder.iterdir())):
        raise FileExistsError(f"{folder} exists and is not an empty folder or a ballpass "
                              "dataset; choose another --out folder")
    created = []
    try:
        for parent in reversed([folder, *folder.parents]):
            if not parent.exists():
                parent.mkdir()
                created.append(parent)
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".probe", suffix=".tmp"):
            pass
    except OSError as exc:
        for d in reversed(created):
            d.rmdir()
        raise PermissionError(f"cannot write to output folder {folder}: "
                              f"{exc.strerror or exc}") from None
    return manifest


def _new_manifest(grid: Grid) -> dict:
    from .. import __version__

    rows_per_run = grid.rows_per_run
    shards = []
    for i in range(grid.n_shards):
        runs = grid.shard_runs(i)
        shards.append({"index": i, "file": shard_name(i), "runs": [runs.start, runs.stop],
                       "n_rows": len(runs) * rows_per_run, "complete": False,
                       "features_complete": False, "bytes": 0})
    return {
        "format": "ballpass-dataset", "format_version": FORMAT_VERSION,
        "ballpass_version": __version__, "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "status": "running", "grid": grid.as_dict(), "root_seed": grid.dataset["seed"],
        "n_runs": grid.n_runs, "n_rows": grid.n_rows, "fs": grid.dataset["fs"],
        "signal_length": grid.signal_length, "units": UNITS, "shards": shards,
    }


def _plan(grid: Grid, folder: Path, manifest: dict, features: bool) -> list[ShardSpec]:
    """Shards still to do; marks complete files (e.g. renamed just before a kill) as such."""
    specs = []
    for shard in manifest["shards"]:
        i = shard["index"]
        shard["complete"] = shard_complete(folder / shard["file"], shard["n_rows"])
        shard["bytes"] = (folder / shard["file"]).stat().st_size if shard["complete"] else 0
        shard["features_complete"] = shard_complete(
            folder / FEATURES_DIR / shard["file"], shard["n_rows"])
        need_features = features and not shard["features_complete"]
        if not shard["complete"] or need_features:
            specs.append(ShardSpec(
                index=i, folder=str(folder), runs=tuple(grid.runs[r] for r in
                                                        grid.shard_runs(i)),
                solver=grid.dataset["solver"], signal_length=grid.signal_length,
                n_segments=grid.n_segments, n_rows=shard["n_rows"],
                simulate=not shard["complete"], features=need_features))
    return specs


def _check_jobs(n_jobs) -> int:
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, int) or n_jobs == 0 or n_jobs < -1:
        raise ValueError(f"n_jobs must be a positive int or -1 (all cores), got {n_jobs!r}")
    return (os.cpu_count() or 1) if n_jobs == -1 else n_jobs


@contextlib.contextmanager
def _exclusive(folder: Path):
    """Hold an exclusive lock on ``folder/.lock`` so two generate calls cannot interleave.

    ``flock`` locks die with their process, so a killed run never leaves a stale lock.
    Without :mod:`fcntl` (Windows) no lock is taken.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows
        yield
        return
    with open(folder / LOCK_FILE, "a") as fh:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise FileExistsError(f"{folder} is being generated by another process right "
                                  "now; wait for it to finish (or stop it)") from None
        yield


def _run(specs, folder: Path, manifest: dict, n_jobs: int, executor, progress: bool):
    """Dispatch the shards, recording each in the manifest as it completes.

    Returns
    -------
    rows_written : int
    models : Counter
        Runs simulated per resolved model.
    """
    from tqdm.auto import tqdm

    shards = {s["index"]: s for s in manifest["shards"]}
    rows_written = 0
    models: Counter = Counter()
    with tqdm(total=sum(s.n_rows for s in specs if s.simulate), unit="signal",
              disable=not (progress and specs), desc="generate", smoothing=0.1) as bar:
        for report in _dispatch(specs, n_jobs, executor):
            shard = shards[report["index"]]
            if report["simulated"]:
                shard.update(complete=True, bytes=report["bytes"])
                rows_written += report["n_rows"]
                models.update(report["models"])
                bar.update(report["n_rows"])
            if report["features_bytes"]:
                shard["features_complete"] = True
            write_manifest(folder, manifest)
    return rows_written, models


# ----------------------------------------------------------------------------- public
@dataclass(frozen=True)
class GenerateSummary:
    """What :func:`generate` did.

    Attributes
    ----------
    path : str
        Dataset folder.
    n_rows : int
        Rows the dataset holds (complete shards).
    rows_written : int
        Rows simulated and written by this call.
    shards_written, shards_skipped : int
        Shards written by this call; shards found complete and skipped (resume).
    feature_shards_written : int
        Feature-table shards written by this call.
    size_bytes : int
        Size of the dataset on disk, bytes.
    wall_time_s : float
        Duration of the call, s (warm-up included).
    signals_per_s : float
        ``rows_written / wall_time_s``.
    models : dict
        Runs simulated per resolved model.
    """

    path: str
    n_rows: int
    rows_written: int
    shards_written: int
    shards_skipped: int
    feature_shards_written: int
    size_bytes: int
    wall_time_s: float
    signals_per_s: float
    models: dict

    def __str__(self) -> str:
        models = ", ".join(f"{m}: {n}" for m, n in sorted(self.models.items())) or "none"
        return (f"{self.path}: {self.n_rows} rows; wrote {self.rows_written} rows in "
                f"{self.shards_written} shards (skipped {self.shards_skipped} complete), "
                f"{self.feature_shards_written} feature-table shards, "
                f"{human_bytes(self.size_bytes)} on disk, {self.wall_time_s:.1f} s, "
                f"{self.signals_per_s:.1f} signals/s; runs per model: {models}")


def generate(grid, out_dir, n_jobs: int = 1, executor: cf.Executor | None = None,
             features: bool = False, progress: bool = True) -> GenerateSummary:
    """Generate (or finish) a labelled dataset over a parameter grid.

    Parameters
    ----------
    grid : str or os.PathLike or dict or Grid
        A TOML grid file or the same dict (see :func:`~ballpass.datasets.read_grid`).
    out_dir : str or os.PathLike
        Dataset folder; created if missing. If it already holds this grid's dataset,
        only the missing shards are generated (resume).
    n_jobs : int, optional
        Local worker processes (joblib/loky); -1 uses every core. Default 1 (in process).
    executor : concurrent.futures.Executor, optional
        Run the shards on this executor instead, e.g. ``client.get_executor()`` of a
        Dask distributed client; the workers must see ``out_dir`` (shared storage).
    features : bool, optional
        Also write a feature table per shard under ``out_dir/features`` (rows keyed
        like the signals), computed with :mod:`ballpass.features`.
    progress : bool, optional
        Show a progress bar with an ETA on stderr. Default True.

    Returns
    -------
    GenerateSummary
        Rows, size on disk, wall time and signals per second.

    Raises
    ------
    ValueError
        Invalid grid or model, or ``out_dir`` holds a dataset of another grid.
    FileExistsError
        ``out_dir`` is a non-empty folder that is not a ballpass dataset.
    PermissionError
        ``out_dir`` cannot be written. All checks run before any simulation.

    Notes
    -----
    Every run's seed is child ``run_id`` of ``numpy.random.SeedSequence(seed)``
    (:func:`~ballpass.datasets.grid.run_seed`) and is stored with its rows, so the
    dataset does not depend on ``n_jobs``, the executor or interruptions. Shards
    are written under a temporary name and renamed when complete, and the manifest is
    replaced atomically: a run killed at any moment loses only unfinished shards.

    Examples
    --------
    >>> from ballpass.datasets import generate, load
    >>> summary = generate("examples/quick.toml", "out/quick", n_jobs=2)  # doctest: +SKIP
    >>> X, meta = load("out/quick")                                       # doctest: +SKIP
    """
    t0 = time.perf_counter()
    grid = read_grid(grid)
    n_jobs = _check_jobs(n_jobs)
    if executor is not None and not isinstance(executor, cf.Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor, got {executor!r}")
    models = _resolved_models(grid)
    folder = Path(out_dir).resolve()
    manifest = _prepare_folder(folder, grid) or _new_manifest(grid)
    with _exclusive(folder):
        remove_temporaries(folder)
        specs = _plan(grid, folder, manifest, features)
        manifest["status"] = "running"
        write_manifest(folder, manifest)
        if any(s.simulate for s in specs):
            _warm_up({m: run for m, run in reversed(models)}, grid.dataset["solver"])
        rows_written, done_models = _run(specs, folder, manifest, n_jobs, executor, progress)
        complete = all(s["complete"] and (s["features_complete"] or not features)
                       for s in manifest["shards"])
        manifest["status"] = "complete" if complete else "running"
        write_manifest(folder, manifest)
    wall = time.perf_counter() - t0
    return GenerateSummary(
        path=str(folder),
        n_rows=sum(s["n_rows"] for s in manifest["shards"] if s["complete"]),
        rows_written=rows_written,
        shards_written=sum(s.simulate for s in specs),
        shards_skipped=len(manifest["shards"]) - sum(s.simulate for s in specs),
        feature_shards_written=sum(s.features for s in specs),
        size_bytes=sum(f.stat().st_size for f in folder.rglob("*") if f.is_file()),
        wall_time_s=wall, signals_per_s=rows_written / wall if wall > 0 else 0.0,
        models=dict(done_models))


@dataclass(frozen=True)
class Estimate:
    """What :func:`dry_run` predicts for a grid.

    Attributes
    ----------
    n_rows, n_runs, n_shards : int
        Rows (signals), simulations and shards of the whole dataset.
    shards_done : int
        Shards already complete in ``out_dir`` (resume), 0 without one.
    signal_length : int
        Samples per row.
    n_jobs : int
        Workers assumed for ``time_s``.
    seconds_per_run : dict
        Measured wall time of one run per resolved model, s (warm, in this process).
    time_s : float
        Estimated wall time of the remaining runs with ``n_jobs`` workers, s.
    size_bytes : float
        Estimated size of the whole dataset on disk, bytes (from the compressed
        size of one measured run).
    models : dict
        Runs per resolved model.
    """

    n_rows: int
    n_runs: int
    n_shards: int
    shards_done: int
    signal_length: int
    n_jobs: int
    seconds_per_run: dict
    time_s: float
    size_bytes: float
    models: dict

    def __str__(self) -> str:
        per_run = self.n_rows // self.n_runs
        models = ", ".join(f"{m}: {self.models[m]} runs at {t * 1e3:.0f} ms per run"
                           for m, t in self.seconds_per_run.items())
        return "\n".join([
            f"rows      {self.n_rows} ({self.n_runs} runs x {per_run} rows per run), "
            f"{self.signal_length} samples each",
            f"shards    {self.n_shards} ({self.shards_done} already complete)",
            f"models    {models}",
            f"estimate  {self.time_s:.0f} s with {self.n_jobs} job(s), "
            f"{human_bytes(self.size_bytes)} on disk",
        ])


def dry_run(grid, out_dir=None, n_jobs: int = 1) -> Estimate:
    """Estimate rows, time and disk of :func:`generate` without writing anything.

    Simulates one run per resolved model (after compiling it) to time it and to measure
    the compressed size of its rows.

    Parameters
    ----------
    grid : str or os.PathLike or dict or Grid
        The grid.
    out_dir : str or os.PathLike, optional
        If it holds this grid's dataset, complete shards are left out of the time estimate.
    n_jobs : int, optional
        Workers assumed for the time estimate (-1: every core). Default 1.

    Returns
    -------
    Estimate
    """
    grid = read_grid(grid)
    n_jobs = _check_jobs(n_jobs)
    models = _resolved_models(grid)
    representatives = {m: run for m, run in reversed(models)}
    _warm_up(representatives, grid.dataset["solver"])
    seconds, row_bytes = {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        for model, run in representatives.items():
            t = time.perf_counter()
            signals, columns = _simulate_run(run, grid.dataset["solver"],
                                             grid.signal_length, grid.n_segments)
            seconds[model] = time.perf_counter() - t
            row_bytes[model] = write_table(Path(tmp) / "probe.parquet", columns,
                                           signals) / len(signals)
    repeats = grid.dataset["repeats"]
    runs_per_model = Counter()
    for m, _ in models:
        runs_per_model[m] += repeats
    done = 0
    folder = Path(out_dir) if out_dir is not None else None
    manifest = read_manifest(folder) if folder is not None and folder.is_dir() else None
    if manifest is not None and manifest["grid"] == grid.as_dict():
        done = sum(shard_complete(folder / s["file"], s["n_rows"]) for s in manifest["shards"])
    left = 1.0 - done / grid.n_shards
    work = sum(seconds[m] * n for m, n in runs_per_model.items()) * left
    workers = min(n_jobs, max(1, grid.n_shards - done))
    return Estimate(
        n_rows=grid.n_rows, n_runs=grid.n_runs, n_shards=grid.n_shards, shards_done=done,
        signal_length=grid.signal_length, n_jobs=n_jobs, seconds_per_run=seconds,
        time_s=work / workers,
        size_bytes=sum(row_bytes[m] * n * grid.rows_per_run for m, n in runs_per_model.items()),
        models=dict(runs_per_model))
