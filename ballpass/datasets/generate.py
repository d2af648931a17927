"""Generate a dataset over a grid: plan shards, simulate them in parallel, store, resume.

Each shard is a pure function of the grid and its index (:func:`run_shard`): it
simulates its runs, cuts the rows and writes one Parquet file under a temporary name
that is renamed when complete. The parent process checks the grid's size against the
free memory and disk, plans the shards, skips those already complete (and intact:
their SHA-256 matches the manifest), compiles the kernels once, dispatches the rest
to worker processes forked from it (so they start with the kernels loaded, and die
with it) or to any :class:`concurrent.futures.Executor` (a Dask
``client.get_executor()`` runs them across machines), and keeps ``_manifest.json`` up
to date after every shard.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import hashlib
import math
import tempfile
import time
import warnings
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._resources import available_memory, free_disk, human_bytes, simulation_bytes
from .grid import Grid, Run, grid_differences, read_grid
from .store import (
    FEATURES_DIR,
    FORMAT_VERSION,
    LOCK_FILE,
    UNITS,
    file_sha256,
    is_temporary,
    read_manifest,
    remove_temporaries,
    shard_complete,
    shard_name,
    shard_problem,
    write_manifest,
    write_table,
)

__all__ = ["generate", "dry_run", "regenerate", "run_shard", "GenerateSummary", "Estimate"]


from ._shard import ShardSpec, _simulate_run, regenerate, run_shard
from ._workers import _dispatch, _n_workers, available_cores


# ----------------------------------------------------------------------------- planning
def _resolved_models(grid: Grid) -> list[tuple[str, Run]]:
    """(resolved model, first run) per grid point, in order; unknown models and solvers,
    and a model that would ignore what a scene's fields ask for (``fault_engagement < 1``
    needs ``intermittent_faults``), raise here: its rows' parameter columns would lie."""
    from ..simulate import MODELS, SOLVERS, resolve_model, unrepresented

    if grid.dataset["solver"] not in ("auto", *SOLVERS):
        raise ValueError(f"dataset.solver must be 'auto' or one of {sorted(SOLVERS)}, "
                         f"got {grid.dataset['solver']!r}")

    repeats = grid.dataset["repeats"]
    out = []
    for run in grid.runs[::repeats]:
        scene = run.build_scene()
        try:   # what the model leaves out is refused below, in the grid's terms
            model = resolve_model(scene, run.model, allow_unrepresented=True)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"model {run.model!r} (run {run.run_id}): {exc}") from None
        ignored = unrepresented(scene, model)
        if ignored:
            able = [m.name for m in MODELS.values() if ignored <= m.represents]
            raise ValueError(
                f"model {model!r} (run {run.run_id}, {scene.label}) does not represent "
                f"{', '.join(sorted(ignored))}, which the grid point asks for; its rows would "
                "be labelled with parameters their signals do not have. Use model = "
                f'"auto" or one of {able}.')
        out.append((model, run))
    return out


def simulator_fingerprint(models: list[tuple[str, Run]]) -> dict[str, str]:
    """What decides the signals of a grid, besides its seeds: stored in the manifest so
    that a resume with anything else is refused.

    Parameters
    ----------
    models : list of (str, Run)
        Resolved model and first run of every grid point (``_resolved_models``).

    Returns
    -------
    dict of str to str
        ``ballpass`` (version), ``simulator_sources`` (SHA-256 of the simulator's
        sources: kernels, integrators, model parameters,
        :func:`ballpass.simulate.source_fingerprint`), ``scenes`` (SHA-256 of every grid
        point's scene with all its defaults filled, and its resolved model: catches a
        changed default or catalogue entry), and the versions of ``numpy``, ``scipy``
        and ``numba``, whose arithmetic the signals depend on.
    """
    import numba
    import scipy

    from .. import __version__, simulate

    scenes = hashlib.sha256()
    for model, run in models:
        scenes.update(f"{model}\0{run.build_scene()!r}\0".encode())
    return {"ballpass": __version__, "simulator_sources": simulate.source_fingerprint(),
            "scenes": scenes.hexdigest(), "numpy": np.__version__,
            "scipy": scipy.__version__, "numba": numba.__version__}


_WARM_UP_S = 0.01  # s simulated per model to compile its kernels


def _warm_up(representatives: dict[str, Run], solver: str) -> None:
    """Compile (or load) every model's kernels in this process, before workers fork."""
    from ..simulate import simulate

    for run in representatives.values():
        scene = run.build_scene()
        simulate(scene.replace(duration_s=min(scene.duration_s, _WARM_UP_S)),
                 model=run.model, solver=solver)


def _check_existing(folder: Path, grid: Grid, fingerprint: dict) -> dict | None:
    """Check an existing output folder before any work; return its manifest if it has one.

    Raises
    ------
    ValueError
        The folder holds a dataset of another grid (the message lists the keys that
        differ) or of another simulator (the fingerprint entries that differ).
    FileExistsError
        The folder exists, is not empty and is not a ballpass dataset.
    """
    manifest = read_manifest(folder) if folder.is_dir() else None
    links = [p.name for p in (folder / FEATURES_DIR, *folder.glob("part-*.parquet"))
             if p.is_symlink()] if folder.is_dir() else []
    if links:   # a resume deletes damaged shards: never through a link to elsewhere
        raise ValueError(f"{folder} holds symbolic links ({', '.join(sorted(links))}) where "
                         "ballpass writes plain files; a resume could delete what they point "
                         "to. Nothing was done. Generate into a new --out folder.")
    if manifest is not None:
        untouched = "Nothing was done; the folder is untouched."
        if manifest["grid"] != grid.as_dict():
            diffs = grid_differences(manifest["grid"], grid.as_dict())
            raise ValueError(
                f"{folder} already holds a dataset of another grid; refusing to mix them. "
                f"Differences (stored -> this grid): {'; '.join(diffs)}. {untouched} Use "
                "the stored grid to resume, or a new --out folder (or delete this one to "
                "start over).")
        stored = manifest.get("fingerprint")
        if stored is None:
            raise ValueError(
                f"{folder} was generated by ballpass {manifest.get('ballpass_version')} "
                "before datasets recorded a simulator fingerprint: this simulator may give "
                f"other signals. {untouched} Finish it with that version, or generate into "
                "a new --out folder.")
        diffs = [f"{k}: {stored.get(k)} -> {v}" for k, v in fingerprint.items()
                 if stored.get(k) != v]
        if diffs:
            raise ValueError(
                f"{folder} was generated by another simulator than this one "
                f"({'; '.join(diffs)}): resuming would mix signals of two simulators in "
                f"one dataset. {untouched} Finish it with the installation that started "
                "it, or generate into a new --out folder (or delete this one to start "
                "over).")
        layout = ("index", "file", "runs", "n_rows")
        for stored_shard, planned in zip(manifest["shards"], _planned_shards(grid),
                                         strict=False):
            if [stored_shard.get(k) for k in layout] != [planned[k] for k in layout]:
                raise ValueError(
                    f"{folder}: the manifest's shard entry {stored_shard.get('index')} "
                    f"({', '.join(f'{k} {stored_shard.get(k)!r}' for k in layout)}) is not "
                    f"what its grid plans ({', '.join(f'{k} {planned[k]!r}' for k in layout)})"
                    f": the manifest was altered. {untouched} Generate into a new --out "
                    "folder.")
        if len(manifest["shards"]) != grid.n_shards:
            raise ValueError(
                f"{folder}: the manifest lists {len(manifest['shards'])} shards where its "
                f"grid plans {grid.n_shards}: the manifest was altered. {untouched} Generate "
                "into a new --out folder.")
    elif folder.exists() and (not folder.is_dir() or any(  # a kill can leave these behind
            not (is_temporary(p) or p.name == LOCK_FILE) for p in folder.iterdir())):
        raise FileExistsError(f"{folder} exists and is not an empty folder or a ballpass "
                              "dataset; choose another --out folder")
    return manifest


def _create_folder(folder: Path) -> None:
    """Create ``folder`` (and parents) and check it is writable.

    Raises
    ------
    PermissionError
        The folder cannot be created or written; folders created here are removed.
    """
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


def check_resources(grid: Grid, folder, n_workers: int = 1, rows_done: int = 0,
                    force: bool = False) -> dict:
    """Check a grid's disk and memory needs against this machine, before any work.

    Parameters
    ----------
    grid : Grid
        The grid (its rows are counted, not built).
    folder : str or os.PathLike or None
        Output folder (or where it will be created); None skips the disk check.
    n_workers : int, optional
        Worker processes that will each hold one shard and one simulation.
    rows_done : int, optional
        Rows already on disk (resume).
    force : bool, optional
        Warn instead of refusing.

    Returns
    -------
    dict
        ``disk_bytes`` (float32 signals still to write, an upper bound: zstd on
        byte-stream-split floats saves 5-15 %), ``disk_free``, ``memory_bytes`` (peak
        of ``n_workers`` workers: one simulation each plus three copies of a shard's
        signals while it is cut, converted and encoded) and ``memory_available``, bytes.

    Raises
    ------
    ValueError
        A need exceeds what is free, with the numbers, unless ``force``.
    """
    length = grid.signal_length
    shard_rows = grid.dataset["shard_size"] * grid.rows_per_run
    out = {
        "disk_bytes": 4 * length * (grid.n_rows - rows_done),
        "disk_free": free_disk(folder) if folder is not None else math.inf,
        "memory_bytes": n_workers * (simulation_bytes(grid.n_samples, len(grid.sensors))
                                     + 3 * 4 * length * shard_rows),
        "memory_available": available_memory(),
    }
    problems = []
    if out["disk_bytes"] > out["disk_free"]:
        problems.append(f"about {human_bytes(out['disk_bytes'])} of disk for "
                        f"{grid.n_rows - rows_done} rows of {length} float32 samples, and "
                        f"{folder} has {human_bytes(out['disk_free'])} free")
    if out["memory_bytes"] > out["memory_available"]:
        problems.append(f"about {human_bytes(out['memory_bytes'])} of memory for "
                        f"{n_workers} worker(s) (one {grid.dataset['duration_s']:g} s "
                        f"simulation and a shard of {shard_rows} rows each), and "
                        f"{human_bytes(out['memory_available'])} is available")
    if problems:
        message = f"the dataset needs {'; '.join(problems)}."
        if not force:
            raise ValueError(f"{message} Nothing was written. Shrink the grid (fewer rows, "
                             "shorter duration_s, lower fs, smaller shard_size, fewer jobs) "
                             "or pass force=True (--force) to start anyway.")
        warnings.warn(f"{message} Starting anyway (force=True).", stacklevel=3)
    return out


def _planned_shards(grid: Grid) -> list[dict]:
    """The shard entries of a new manifest of ``grid`` (none complete)."""
    shards = []
    for i in range(grid.n_shards):
        runs = grid.shard_runs(i)
        shards.append({"index": i, "file": shard_name(i), "runs": [runs.start, runs.stop],
                       "n_rows": len(runs) * grid.rows_per_run, "complete": False,
                       "features_complete": False, "bytes": 0})
    return shards


def _new_manifest(grid: Grid, fingerprint: dict) -> dict:
    from .. import __version__

    shards = _planned_shards(grid)
    return {
        "format": "ballpass-dataset", "format_version": FORMAT_VERSION,
        "ballpass_version": __version__, "fingerprint": fingerprint,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "status": "running", "grid": grid.as_dict(), "root_seed": grid.dataset["seed"],
        "n_runs": grid.n_runs, "n_rows": grid.n_rows, "fs": grid.dataset["fs"],
        "signal_length": grid.signal_length, "units": _units(grid), "shards": shards,
    }


def _units(grid: Grid) -> dict:
    """The dataset's units: a twin's signals are its machine's recordings and faults
    scaled to them, in whatever unit those recordings are (not m/s^2)."""
    if grid.machine is None:
        return UNITS
    return {**UNITS, "signal": f"the unit of the recordings {grid.machine['manifest']} lists"}


def _verify(folder: Path, shard: dict, key: str) -> bool:
    """Is the shard file (signals: ``key="sha256"``, features: ``"features_sha256"``)
    complete and intact? A damaged one is deleted (with a warning) to be made again.

    A file renamed into place just before a kill, with no checksum in the manifest yet,
    is accepted if it reads with its page CRCs verified and holds this shard's runs (a
    stray copy of another shard does not); its checksum is then recorded.
    """
    import pyarrow.parquet as pq

    sub = folder / FEATURES_DIR if key == "features_sha256" else folder
    path = sub / shard["file"]
    if not shard_complete(path, shard["n_rows"]):
        problem = "is missing" if not path.exists() else "is truncated or unreadable"
    elif shard.get(key) is not None:
        problem = shard_problem(path, shard, key)
    else:
        try:
            run_ids = pq.read_table(path, page_checksum_verification=True).column("run_id")
            start, stop = shard["runs"]
            problem = None if all(start <= r < stop for r in run_ids.to_pylist()) else (
                f"holds rows of runs outside this shard's runs {start} to {stop - 1} (a "
                "copy of another shard?)")
        except (OSError, ValueError, KeyError) as exc:
            problem = f"fails its page checksums or has no run_id column ({exc})"
        if problem is None:
            size, shard[key] = path.stat().st_size, file_sha256(path)
            shard["features_bytes" if key == "features_sha256" else "bytes"] = size
    if problem is not None and (path.exists() or shard.get(key) is not None):
        warnings.warn(f"shard {path} {problem}; generating it again", stacklevel=4)
        path.unlink(missing_ok=True)
    return problem is None


def _plan(grid: Grid, folder: Path, manifest: dict, features: bool) -> list[ShardSpec]:
    """Shards still to do: missing, unfinished or damaged (checksum) ones."""
    specs = []
    for shard in manifest["shards"]:
        i = shard["index"]
        was_complete = shard["complete"]
        shard["complete"] = _verify(folder, shard, "sha256") if (
            was_complete or (folder / shard["file"]).exists()) else False
        if not shard["complete"]:
            shard.update(bytes=0, sha256=None)
        has_features = shard.get("features_complete") or (
            folder / FEATURES_DIR / shard["file"]).exists()
        shard["features_complete"] = bool(
            shard["complete"] and has_features and _verify(folder, shard, "features_sha256"))
        if not shard["features_complete"]:   # stale (its signals are redone) or damaged
            (folder / FEATURES_DIR / shard["file"]).unlink(missing_ok=True)
        # a feature table the dataset had is made again with its shard
        need_features = (features or has_features) and not shard["features_complete"]
        if not shard["features_complete"]:
            shard.update(features_bytes=0, features_sha256=None)
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
    return available_cores() if n_jobs == -1 else n_jobs


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


def _run(specs, folder: Path, manifest: dict, n_workers: int, executor, progress: bool):
    """Dispatch the shards, recording each (with its checksum) in the manifest as it
    completes.

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
        for report in _dispatch(specs, n_workers, executor):
            shard = shards[report["index"]]
            if report["simulated"]:
                shard.update(complete=True, bytes=report["bytes"], sha256=report["sha256"])
                rows_written += report["n_rows"]
                models.update(report["models"])
                bar.update(report["n_rows"])
            if report["features_bytes"]:
                shard.update(features_complete=True, features_bytes=report["features_bytes"],
                             features_sha256=report["features_sha256"])
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

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets import generate
    >>> grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [1797],
    ...                  "resonance_hz": [3000]}}
    >>> summary = generate(grid, tempfile.mkdtemp(), progress=False)
    >>> summary.n_rows, summary.rows_written, summary.models
    (1, 1, {'impulse': 1})
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
             features: bool = False, progress: bool = True,
             force: bool = False) -> GenerateSummary:
    """Generate (or finish) a labelled dataset over a parameter grid.

    Parameters
    ----------
    grid : str or os.PathLike or dict or Grid
        A TOML grid file or the same dict (see :func:`~ballpass.datasets.read_grid`).
    out_dir : str or os.PathLike
        Dataset folder; created if missing. If it already holds this grid's dataset,
        only the missing shards are generated (resume).
    n_jobs : int, optional
        Local worker processes; -1 uses every core. Default 1 (in process). Capped at
        the shards to do and the cores available (a request above the cores warns).
        Workers are forked after the kernels are compiled and die with this process.
    executor : concurrent.futures.Executor, optional
        Run the shards on this executor instead, e.g. ``client.get_executor()`` of a
        Dask distributed client; the workers must see ``out_dir`` (shared storage).
    features : bool, optional
        Also write a feature table per shard under ``out_dir/_features`` (rows keyed
        like the signals), computed with :mod:`ballpass.features`.
    progress : bool, optional
        Show a progress bar with an ETA on stderr. Default True.
    force : bool, optional
        Start even if the estimated disk or memory need exceeds what is free
        (:func:`check_resources`); default False refuses.

    Returns
    -------
    GenerateSummary
        Rows, size on disk, wall time and signals per second.

    Raises
    ------
    ValueError
        Invalid grid or model; a grid too large for the free disk or memory;
        ``out_dir`` holds a dataset of another grid (the keys that differ are listed) or
        of another simulator (fingerprint: simulator sources, scene defaults, package
        versions), and the folder is left untouched.
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
    replaced atomically: a run killed at any moment loses only unfinished shards. A
    resume verifies every complete shard against its SHA-256 in the manifest and
    regenerates damaged ones (with a warning).

    Examples
    --------
    >>> import tempfile
    >>> from ballpass.datasets import generate, load
    >>> grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "repeats": 2, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797],
    ...                  "resonance_hz": [3000]}}
    >>> out = tempfile.mkdtemp() + "/quick"
    >>> summary = generate(grid, out, features=True, progress=False)
    >>> summary.n_rows
    4
    >>> X, meta = load(out)
    >>> X.shape, meta["label"].tolist()
    ((4, 3000), ['healthy', 'healthy', 'outer', 'outer'])
    >>> generate(grid, out, progress=False).rows_written    # resumed: nothing left to do
    0
    """
    t0 = time.perf_counter()
    grid = read_grid(grid)
    n_jobs = _check_jobs(n_jobs)
    if executor is not None and not isinstance(executor, cf.Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor, got {executor!r}")
    models = _resolved_models(grid)
    fingerprint = simulator_fingerprint(models)
    machine = None
    if grid.machine is not None:   # a twin: its recordings are part of what decides
        from .twin import check_machine, write_machine

        machine = check_machine(grid)
        fingerprint["machine"] = machine.sha256
    folder = Path(out_dir).resolve()
    manifest = _check_existing(folder, grid, fingerprint)
    rows_done = 0 if manifest is None else sum(s["n_rows"] for s in manifest["shards"]
                                               if s["complete"])
    workers = 1 if executor is not None else min(n_jobs, available_cores())
    check_resources(grid, folder, workers, rows_done, force)
    _create_folder(folder)
    manifest = manifest or _new_manifest(grid, fingerprint)
    with _exclusive(folder):
        remove_temporaries(folder)
        specs = _plan(grid, folder, manifest, features)
        manifest["status"] = "running"
        write_manifest(folder, manifest)
        if machine is not None:   # the learned paths, for the record
            write_machine(folder, machine)
        if any(s.simulate for s in specs):
            _warm_up({m: run for m, run in reversed(models)}, grid.dataset["solver"])
        n_workers = 1 if executor is not None else _n_workers(n_jobs, len(specs))
        try:
            rows_written, done_models = _run(specs, folder, manifest, n_workers, executor,
                                             progress)
        except KeyboardInterrupt as exc:
            remove_temporaries(folder)
            # the workers are stopped: every shard in place is kept on resume, also those
            # a worker finished while the parent had not yet heard of them (a fast model
            # finishes several per worker in that time)
            done = sum(s["complete"] or shard_complete(folder / s["file"], s["n_rows"])
                       for s in manifest["shards"])
            exc.add_note(f"{done} of {len(manifest['shards'])} shards written, rerun to "
                         "resume")
            raise
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

    Examples
    --------
    >>> from ballpass.datasets import dry_run
    >>> grid = {"dataset": {"duration_s": 0.5, "fs": 12_000, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797],
    ...                  "resonance_hz": [3000]}}
    >>> est = dry_run(grid)
    >>> est.n_rows, est.n_runs, bool(est.size_bytes > 0)
    (2, 2, True)
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


def dry_run(grid, out_dir=None, n_jobs: int = 1, force: bool = False) -> Estimate:
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
    force : bool, optional
        Estimate even if the disk or memory need exceeds what is free.

    Returns
    -------
    Estimate

    Raises
    ------
    ValueError
        As :func:`generate`, before any simulation: a grid too large for the free disk
        or memory is refused (unless ``force``).

    Examples
    --------
    >>> from ballpass.datasets import dry_run
    >>> grid = {"dataset": {"duration_s": 1.0, "fs": 48_000, "repeats": 10, "model": "impulse"},
    ...         "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner", "ball"],
    ...                  "rpm": [1730, 1797]}}
    >>> estimate = dry_run(grid)
    >>> estimate.n_rows, estimate.signal_length
    (80, 48000)
    """
    grid = read_grid(grid)
    n_jobs = _check_jobs(n_jobs)
    models = _resolved_models(grid)
    if grid.machine is not None:
        from .twin import check_machine

        check_machine(grid)
    folder = Path(out_dir) if out_dir is not None else None
    manifest = read_manifest(folder) if folder is not None and folder.is_dir() else None
    if manifest is not None and manifest["grid"] != grid.as_dict():
        manifest = None
    done = [] if manifest is None else [
        s for s in manifest["shards"] if shard_complete(folder / s["file"], s["n_rows"])]
    check_resources(grid, folder if folder is not None else Path.cwd(),
                    min(n_jobs, available_cores()), sum(s["n_rows"] for s in done), force)
    # a twin's first point is healthy (a copy of a recording): time its last, a fault
    representatives = {m: run for m, run in (models if grid.machine else reversed(models))}
    _warm_up(representatives, grid.dataset["solver"])
    seconds, row_bytes = {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        for model, run in representatives.items():
            t = time.perf_counter()
            signals, columns = _simulate_run(run, grid.dataset["solver"],
                                             grid.signal_length, grid.n_segments)
            seconds[model] = time.perf_counter() - t
            row_bytes[model] = write_table(Path(tmp) / "probe.parquet", columns,
                                           signals)[0] / len(signals)
    repeats = grid.dataset["repeats"]
    runs_per_model = Counter()
    for m, _ in models:
        runs_per_model[m] += repeats
    done = len(done)
    left = 1.0 - done / grid.n_shards
    work = sum(seconds[m] * n for m, n in runs_per_model.items()) * left
    workers = min(n_jobs, max(1, grid.n_shards - done))
    return Estimate(
        n_rows=grid.n_rows, n_runs=grid.n_runs, n_shards=grid.n_shards, shards_done=done,
        signal_length=grid.signal_length, n_jobs=n_jobs, seconds_per_run=seconds,
        time_s=work / workers,
        size_bytes=sum(row_bytes[m] * n * grid.rows_per_run for m, n in runs_per_model.items()),
        models=dict(runs_per_model))
