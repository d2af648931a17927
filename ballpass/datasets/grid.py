"""Dataset grids: a TOML file (or the same dict) expanded into simulation runs.

A grid has two tables. ``[dataset]`` holds the settings shared by every run
(duration, sampling rate, repeats, root seed, model, segmenting, shard size);
``[grid]`` holds the axes: every key is a list of values and the runs are the
Cartesian product of the axes, times ``repeats``. Healthy runs do not multiply
over the fault axes (width, depth, angle, engagement), and race-fault runs do not
multiply over ``fault_engagement``, which only ball faults have (a race defect lies
on the track on every pass; :class:`~ballpass.Fault` refuses ``engagement < 1`` for
it). ``sensor`` is not an axis of the product: its values are the channels of one
run (one simulation, one row per sensor, same ``run_id``). A numeric axis may also
be a distribution, ``{uniform = [lo, hi]}``, drawn anew for each of ``[dataset]
draws`` runs per grid point (domain randomization; see :func:`read_grid`).

Everything is validated by :func:`read_grid` before any simulation work: unknown
keys, empty lists, reversed or non-positive ranges, wrong types and values a
:class:`~ballpass.Scene` would refuse raise ``ValueError`` naming the key.

Examples
--------
>>> from ballpass.datasets import read_grid
>>> g = read_grid({
...     "dataset": {"duration_s": 0.1, "fs": 12000, "repeats": 2},
...     "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"],
...              "fault_width_mm": [0.18, 0.53], "rpm": {"start": 1730, "stop": 1797, "step": 67},
...              "resonance_hz": [3000], "sensor": ["loaded", "unloaded"]},
... })
>>> g.n_runs, g.n_rows                 # (1 healthy + 2 outer) x 2 rpm x 2 repeats; x 2 sensors
(12, 24)
>>> g = read_grid({"grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "ball"],
...                         "fault_engagement": [0.3, 1.0], "rpm": [1797]}})
>>> g.n_runs                          # 1 healthy + 1 outer + 1 ball x 2 engagements
4
>>> [r.scene.get("fault") for r in g.runs]        # doctest: +NORMALIZE_WHITESPACE
[None, {'kind': 'outer'}, {'kind': 'ball', 'engagement': 0.3},
 {'kind': 'ball', 'engagement': 1.0}]
"""

from __future__ import annotations

import itertools
import json
import math
import os
import tomllib
from dataclasses import asdict, dataclass, field, fields
from functools import cached_property
from pathlib import Path

import numpy as np

from .._validation import check_segment
from ..phenomena import check_needs
from ..scene import Fault, Scene, Sensor
from .distributions import DISTRIBUTIONS, Distribution, is_distribution, parse_distribution

__all__ = ["Grid", "Run", "read_grid", "run_seed", "scene_from_dict", "count_points",
           "grid_differences", "drawn_axes", "draw_seed", "FAULT_VALUES", "MAX_RUNS"]

#: values of the ``fault`` axis
FAULT_VALUES = ("healthy", "outer", "inner", "ball")

#: [dataset] key -> default (None: not set)
DATASET_DEFAULTS: dict[str, object] = {
    "duration_s": 1.0,
    "fs": 48_000.0,
    "repeats": 1,
    "seed": 0,
    "model": "auto",
    "solver": "auto",
    "segment_s": None,
    "shard_size": None,
    "needs": None,
    "draws": None,  # 1; left out of the stored grid so grids without draws keep theirs
}

#: [grid] axes of the realism fields of :class:`~ballpass.Scene` (extra structural modes,
#: coloured background, shaft lines) and of the sensor's angle; each is also a column
REALISM_AXES = (
    "noise_slope_db_oct",
    *(f"resonance{k}_{p}" for k in (2, 3) for p in ("hz", "damping", "gain")),
    *(f"shaft_harmonic_{k}x" for k in (1, 2, 3, 4)),
    "sensor_angle_deg",
)
#: damping ratio and gain of an extra mode whose axis leaves them out
MODE_DEFAULTS = {"damping": 0.05, "gain": 1.0}
#: [grid] axes; runs follow this order, with the fault axes (size, angle, engagement)
#: varying fastest; drawn axes are drawn in this order, so an axis added last
#: (``impact_spread``) leaves the other draws of an older grid as they were
AXES = (
    "bearing", "fault", "fault_width_mm", "fault_depth_mm", "fault_angle_deg",
    "fault_engagement", "level_db", "rpm", "radial_load_n", "clearance_um", "slip", "snr_db",
    "noise_rms",
    "resonance_hz", "resonance_damping", *REALISM_AXES, "model", "sensor", "impact_spread",
    "fault_spin_drift_deg", "impact_edges", "impact_correlation",
)
REQUIRED_AXES = ("bearing", "fault", "rpm")
_FAULT_AXES = {"fault_width_mm": "width_mm", "fault_depth_mm": "depth_mm",
               "fault_angle_deg": "angle_deg", "fault_engagement": "engagement",
               "fault_spin_drift_deg": "spin_drift_deg"}
#: fault axes of ball faults only: race-fault points do not multiply over them
_BALL_AXES = ("fault_engagement", "fault_spin_drift_deg")
#: axes of a twin's fault rows (a grid with a [machine] table, :mod:`.twin`): the fault's
#: RMS over the real background's, dB, the spread of its impacts' sizes (standard
#: deviation of their logarithm), whether a passage has its Hertzian entry and exit
#: edges (1) or is one point impact (0), and the lag-1 correlation of the sizes'
#: logarithms; not Scene fields, columns of their own
TWIN_AXES = ("level_db", "impact_spread", "impact_edges", "impact_correlation")
#: axes that healthy points do not multiply over
_FAULT_ONLY = (*_FAULT_AXES, *TWIN_AXES)
_SCENE_AXES = ("radial_load_n", "clearance_um", "slip", "snr_db", "noise_rms", "resonance_hz",
               "resonance_damping")
_NUMERIC_AXES = (*_FAULT_AXES, *TWIN_AXES, "rpm", *_SCENE_AXES, *REALISM_AXES)
_SENSOR_KEYS = {f.name for f in fields(Sensor)}

#: target size of one shard, bytes of float32 signal (shard_size default)
_SHARD_BYTES = 32 * 2**20
_MAX_SHARD_RUNS = 256
_MIN_SHARDS = 16
#: most runs of one dataset: its manifest and run table are held in memory (about 1 kB
#: per run); a larger study is several datasets
MAX_RUNS = 10_000_000
#: most listed grid points (combinations of listed axis values): each is validated as a
#: Scene in Python, about 0.1 ms a point, so 200 000 take some 20 s; more values are
#: drawn from distributions (validated once at their extremes) with ``[dataset] draws``
MAX_POINTS = 200_000


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _expand_range(key: str, spec: dict) -> list[float]:
    """``{start, stop, step}`` -> ``start, start + step, ...`` up to ``stop`` inclusive."""
    unknown = set(spec) - {"start", "stop", "step"}
    missing = {"start", "stop", "step"} - set(spec)
    if unknown or missing:
        raise ValueError(
            f"grid.{key}: a range is a table with keys start, stop, step, and a "
            f"distribution a table with one key of {list(DISTRIBUTIONS)}; "
            f"got keys {sorted(spec)}"
        )
    for name in ("start", "stop", "step"):
        if not _is_number(spec[name]) or not math.isfinite(spec[name]):
            raise ValueError(f"grid.{key}.{name} must be a finite number, got {spec[name]!r}")
    start, stop, step = (float(spec[k]) for k in ("start", "stop", "step"))
    if step <= 0:
        raise ValueError(f"grid.{key}: range step must be > 0, got {step:g}")
    if stop < start:
        raise ValueError(f"grid.{key}: range stop {stop:g} is below start {start:g}")
    n = int(math.floor((stop - start) / step + 1e-9)) + 1
    if n > MAX_RUNS:  # counted before building the list
        raise ValueError(
            f"grid.{key}: range {{start = {start:g}, stop = {stop:g}, step = {step:g}}} has "
            f"{n:.3g} values; a dataset holds at most {MAX_RUNS:,} runs. Use a larger step.")
    # rounding to 12 significant digits removes the float drift of start + k*step
    return [float(f"{start + k * step:.12g}") for k in range(n)]


def _axis_values(key: str, raw, fs: float) -> list | Distribution:
    """Validate one [grid] axis and return its list of normalized values, or its
    :class:`~ballpass.datasets.distributions.Distribution` (``fs``, Hz, bounds the
    resonances)."""
    if is_distribution(raw):
        return parse_distribution(key, raw, fs)
    if isinstance(raw, dict) and key in _NUMERIC_AXES:
        return _expand_range(key, raw)
    values = raw if isinstance(raw, list) else [raw]
    if not values:
        raise ValueError(f"grid.{key} is an empty list; give at least one value or drop the key")
    out = []
    for i, v in enumerate(values):
        where = f"grid.{key}[{i}]"
        if key == "bearing":
            if not isinstance(v, str):
                raise ValueError(f"{where} must be a catalogue bearing name, got {v!r}")
        elif key == "fault":
            if v not in FAULT_VALUES:
                raise ValueError(f"{where} must be one of {FAULT_VALUES}, got {v!r}")
        elif key == "model":
            _check_model_name(where, v)
        elif key == "sensor":
            v = _sensor_value(where, v)
        elif key == "rpm" and isinstance(v, list):
            if len(v) != 2 or not all(_is_number(x) for x in v):
                raise ValueError(f"{where}: a speed ramp is [start_rpm, end_rpm], got {v!r}")
            v = [float(x) for x in v]
        elif key == "snr_db" and v == "inf":
            v = math.inf
        elif not _is_number(v):
            raise ValueError(f"{where} must be a number, got {type(v).__name__} ({v!r})")
        else:
            v = float(v)
        out.append(v)
    if key == "sensor":
        names = [s if isinstance(s, str) else s["name"] for s in out]
        if len(set(names)) != len(names):
            raise ValueError(f"grid.sensor names must be unique, got {names}")
    elif len({json.dumps(v) for v in out}) != len(out):
        raise ValueError(f"grid.{key} has duplicate values {out}; use [dataset] repeats instead")
    return out


def _check_model_name(where: str, name) -> None:
    """Refuse a model that is neither ``"auto"`` nor in the registry, naming those."""
    from ..simulate import MODELS

    if name != "auto" and name not in MODELS:
        raise ValueError(f"{where}: unknown model {name!r}; use 'auto' or one of "
                         f"{list(MODELS)}")


def _check_solver_name(where: str, name: str, model: str) -> None:
    """Refuse a solver that is neither ``"auto"`` nor one of the model's (any model's
    for ``model="auto"``), naming those: a misspelt solver is not silently replaced."""
    from ..simulate import MODELS

    models = MODELS.values() if model == "auto" else [MODELS[model]]
    known = sorted({s for m in models for s in m.solvers})
    if name != "auto" and name not in known:
        raise ValueError(f"{where}: unknown solver {name!r} for model {model!r}; use "
                         f"'auto' or one of {known}")


def _sensor_value(where: str, v) -> str | dict:
    """A sensor is "loaded", "unloaded" or a table of :class:`~ballpass.Sensor` fields."""
    try:
        if isinstance(v, str):
            return Sensor.named(v).name
        if isinstance(v, dict):
            unknown = set(v) - _SENSOR_KEYS
            if unknown:
                raise ValueError(f"unknown keys {sorted(unknown)}; allowed: {sorted(_SENSOR_KEYS)}")
            return asdict(Sensor(**v))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{where}: {exc}") from None
    raise ValueError(f'{where} must be "loaded", "unloaded" or a table with keys '
                     f"{sorted(_SENSOR_KEYS)}, got {v!r}")


def _dataset_settings(raw: dict) -> dict:
    """Validate the [dataset] table; return it with defaults filled (None entries dropped)."""
    unknown = set(raw) - set(DATASET_DEFAULTS)
    if unknown:
        raise ValueError(f"unknown [dataset] key(s) {sorted(unknown)}; "
                         f"allowed: {sorted(DATASET_DEFAULTS)}")
    out = {**DATASET_DEFAULTS, **raw}
    for key in ("duration_s", "fs", "segment_s"):
        v = out[key]
        if v is not None and (not _is_number(v) or not math.isfinite(v) or v <= 0):
            raise ValueError(f"dataset.{key} must be a positive number, got {v!r}")
        out[key] = None if v is None else float(v)
    for key, lo in (("repeats", 1), ("seed", 0), ("shard_size", 1), ("draws", 1)):
        v = out[key]
        if v is not None and (isinstance(v, bool) or not isinstance(v, int) or v < lo):
            raise ValueError(f"dataset.{key} must be an int >= {lo}, got {v!r}")
    if not isinstance(out["solver"], str):
        raise ValueError(f"dataset.solver must be a str, got {out['solver']!r}")
    _check_model_name("dataset.model", out["model"])
    _check_solver_name("dataset.solver", out["solver"], out["model"])
    if out["needs"] is not None:  # phenomena every run asks for (Scene(needs=...))
        out["needs"] = sorted(check_needs(out["needs"], "dataset.needs"))
    if out["segment_s"] is not None and out["segment_s"] > out["duration_s"]:
        raise ValueError(f"dataset.segment_s={out['segment_s']:g} s is longer than "
                         f"dataset.duration_s={out['duration_s']:g} s")
    if out["segment_s"] is not None:
        check_segment(out["segment_s"], out["fs"], "dataset.segment_s")
    return {k: v for k, v in out.items() if v is not None}


def _json_safe(value):
    """Replace infinities (noise-free ``snr_db``) by the string "inf" for strict JSON, and
    distributions by their table."""
    if isinstance(value, Distribution):
        return value.as_dict()
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    if isinstance(value, list):
        return [_json_safe(v) for v in value]
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    return value


def run_seed(root: int, run_id: int) -> int:
    """Seed of run ``run_id``: child ``run_id`` of ``SeedSequence(root).spawn(...)``, as an int.

    ``SeedSequence(root, spawn_key=(run_id,))`` is exactly the ``run_id``-th child that
    ``SeedSequence(root).spawn(n)`` returns, for any ``n > run_id``; its first 64-bit
    state word, shifted to 63 bits so it fits a Parquet int64, is the scene's seed.
    """
    state = np.random.SeedSequence(root, spawn_key=(run_id,)).generate_state(1, np.uint64)
    return int(state[0] >> np.uint64(1))


def draw_seed(root: int, draw_id: int) -> int:
    """Seed of the drawn values of draw ``draw_id`` (one per grid point and draw, shared
    by its repeats): ``SeedSequence(root, spawn_key=(draw_id, 1))`` as a 63-bit int,
    a stream apart from every run's (whose key is ``(run_id,)``). The draw's values are
    ``Distribution.draw(numpy.random.default_rng(seed))`` over its drawn axes in the
    order of the grid's axes.

    Examples
    --------
    >>> from ballpass.datasets.grid import draw_seed, run_seed
    >>> draw_seed(2015, 0) != run_seed(2015, 0)
    True
    """
    state = np.random.SeedSequence(root, spawn_key=(draw_id, 1)).generate_state(1, np.uint64)
    return int(state[0] >> np.uint64(1))


def scene_from_dict(spec: dict) -> Scene:
    """Build the :class:`~ballpass.Scene` of a run from its JSON-able keyword dict.

    ``spec`` holds :class:`~ballpass.Scene` keyword arguments, with ``fault`` as a dict of
    :class:`~ballpass.Fault` fields (or None), ``sensors`` as a list of
    :class:`~ballpass.Sensor` field dicts and a ramp ``rpm`` as ``[start, end]`` (rpm).
    This is the form stored in the ``scene`` column of every dataset row.
    """
    kwargs = dict(spec)
    if kwargs.get("fault") is not None:
        kwargs["fault"] = Fault(**kwargs["fault"])
    if "sensors" in kwargs:
        kwargs["sensors"] = tuple(Sensor(**s) for s in kwargs["sensors"])
    if isinstance(kwargs.get("rpm"), list):
        kwargs["rpm"] = tuple(kwargs["rpm"])
    return Scene(**kwargs)


@dataclass(frozen=True)
class Run:
    """One simulation of a dataset: a scene, a model, a seed.

    Attributes
    ----------
    run_id : int
        Index of the run in the grid's order, from 0; shared by all rows of the run.
    repeat : int
        Which repeat of its grid point this run is, from 0.
    model : str
        Model requested (``"auto"`` or a registered model name).
    scene : dict
        JSON-able keyword arguments of the run's :class:`~ballpass.Scene`, including
        its seed (see :func:`scene_from_dict`).
    columns : dict, optional
        Dataset columns of the run beyond the scene's own: the values of its realism
        axes (:data:`REALISM_AXES`) and, in a grid with drawn axes, ``draw`` (which draw
        of its grid point) and ``draw_seed`` (see :func:`draw_seed`); in a twin's grid,
        ``level_db``, ``impact_spread``, ``impact_edges`` and ``impact_correlation``
        (NaN for a healthy run).
    machine : str, optional
        A twin's run (:mod:`ballpass.datasets.twin`): absolute path of the manifest of
        the machine's healthy recordings, whose learned path and background make its
        signal. None: a simulated run.
    """

    run_id: int
    repeat: int
    model: str
    scene: dict
    columns: dict = field(default_factory=dict)
    machine: str | None = None

    @property
    def seed(self) -> int:
        """The scene's seed (int)."""
        return self.scene["seed"]

    def build_scene(self) -> Scene:
        """The validated :class:`~ballpass.Scene` of this run."""
        return scene_from_dict(self.scene)


@dataclass(frozen=True)
class Grid:
    """A validated dataset grid; build it with :func:`read_grid`.

    Attributes
    ----------
    dataset : dict
        The [dataset] settings with defaults filled: ``duration_s`` (s), ``fs`` (Hz),
        ``repeats``, ``seed`` (root seed), ``model`` (unless the grid has a model axis),
        ``solver``, ``shard_size`` (runs per shard) and optionally ``segment_s`` (s)
        and ``needs`` (phenomena every run asks for).
    axes : dict
        The [grid] axes as lists of normalized values (ranges expanded).
    machine : dict or None
        The [machine] table of a twin (:mod:`ballpass.datasets.twin`), its ``manifest``
        an absolute path; None for a simulated grid.

    Examples
    --------
    >>> from ballpass.datasets import read_grid
    >>> grid = read_grid({
    ...     "dataset": {"duration_s": 1.0, "fs": 48_000, "repeats": 3, "segment_s": 0.25,
    ...                 "shard_size": 4},
    ...     "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"], "rpm": [1797]},
    ... })
    >>> grid.n_runs, grid.rows_per_run, grid.n_rows     # 2 points x 3 repeats; 4 segments each
    (6, 4, 24)
    >>> grid.runs[0].scene["fs"], grid.dataset["model"]
    (48000.0, 'auto')
    """

    dataset: dict
    axes: dict
    _points: tuple = field(repr=False, compare=False)
    machine: dict | None = None

    # ------------------------------------------------------------ derived sizes
    @property
    def sensors(self) -> tuple:
        """Sensor channels of every run (names or field dicts), in row order."""
        return tuple(self.axes.get("sensor", ["loaded"]))

    @property
    def n_samples(self) -> int:
        """Samples simulated per run and sensor, ``round(duration_s * fs)``."""
        return max(1, round(self.dataset["duration_s"] * self.dataset["fs"]))

    @property
    def signal_length(self) -> int:
        """Samples per row: one segment, or the whole run when not segmented."""
        seg = self.dataset.get("segment_s")
        return self.n_samples if seg is None else max(1, round(seg * self.dataset["fs"]))

    @property
    def n_segments(self) -> int:
        """Rows cut from each run and sensor (non-overlapping; the remainder is dropped)."""
        return self.n_samples // self.signal_length

    @property
    def distributions(self) -> dict:
        """The drawn axes: name -> :class:`~ballpass.datasets.distributions.Distribution`."""
        return {k: v for k, v in self.axes.items() if isinstance(v, Distribution)}

    @property
    def n_runs(self) -> int:
        """Simulations: grid points times draws times repeats."""
        return len(self._points) * self.dataset.get("draws", 1) * self.dataset["repeats"]

    @property
    def rows_per_run(self) -> int:
        """Rows per run: sensors times segments."""
        return len(self.sensors) * self.n_segments

    @property
    def n_rows(self) -> int:
        """Rows (signals) of the dataset."""
        return self.n_runs * self.rows_per_run

    @property
    def n_shards(self) -> int:
        """Parquet shards, of ``shard_size`` runs each (the last may be shorter)."""
        return -(-self.n_runs // self.dataset["shard_size"])

    def shard_runs(self, index: int) -> range:
        """Run ids of shard ``index``.

        Examples
        --------
        Five runs in shards of two:

        >>> from ballpass.datasets import read_grid
        >>> grid = read_grid({"dataset": {"duration_s": 0.1, "repeats": 5, "shard_size": 2},
        ...                   "grid": {"bearing": ["6205"], "fault": ["outer"], "rpm": [1797]}})
        >>> [grid.shard_runs(i) for i in range(grid.n_shards)]
        [range(0, 2), range(2, 4), range(4, 5)]
        """
        size = self.dataset["shard_size"]
        return range(index * size, min((index + 1) * size, self.n_runs))

    # ------------------------------------------------------------ runs
    @cached_property
    def runs(self) -> tuple[Run, ...]:
        """Every run, in ``run_id`` order: the draws of one grid point are adjacent, and
        the repeats of one draw (same drawn values, own seeds)."""
        repeats, draws = self.dataset["repeats"], self.dataset.get("draws", 1)
        root = self.dataset["seed"]
        drawn_axes = self.distributions
        realism = [k for k in REALISM_AXES if k in self.axes]
        out = []
        for p, (model, base, values) in enumerate(self._points):
            for d in range(draws):
                draw_id = p * draws + d
                columns = {}
                if drawn_axes:
                    seed = draw_seed(root, draw_id)
                    rng = np.random.default_rng(seed)
                    # every axis is drawn (a stable stream); a point keeps the ones it has
                    # (no fault size for a healthy point, no engagement for a race fault)
                    draw = {k: dist.draw(rng) for k, dist in drawn_axes.items()}
                    values = {**values, **{k: v for k, v in draw.items() if k in values}}
                    base = _point_scene(self.dataset, list(self.sensors), values)
                    columns = {"draw": d, "draw_seed": seed}
                columns.update({k: values[k] for k in realism})
                if "fault_spin_drift_deg" in self.axes:
                    # a column of its own when the grid has the axis: 0 for a race fault
                    # (a fixed axis), NaN for a healthy bearing
                    columns["fault_spin_drift_deg"] = values.get(
                        "fault_spin_drift_deg", 0.0 if values["fault"] != "healthy" else math.nan)
                if self.machine is not None:
                    columns.update({k: values.get(k, math.nan) for k in TWIN_AXES
                                    if k in self.axes})
                machine = None if self.machine is None else self.machine["manifest"]
                for r in range(repeats):
                    run_id = draw_id * repeats + r
                    scene = {**base, "seed": run_seed(root, run_id)}
                    out.append(Run(run_id=run_id, repeat=r, model=model, scene=scene,
                                   columns=columns, machine=machine))
        return tuple(out)

    def as_dict(self) -> dict:
        """The normalized grid as a strict-JSON dict; ``read_grid`` of it gives this grid.

        Examples
        --------
        >>> from ballpass.datasets import read_grid
        >>> grid = read_grid({"dataset": {"duration_s": 1.0, "segment_s": 0.25},
        ...                   "grid": {"bearing": ["6205"], "fault": ["ball"], "rpm": [900]}})
        >>> grid.as_dict()["dataset"]["segment_s"]
        0.25
        >>> read_grid(grid.as_dict()) == grid                # round trip
        True
        """
        out = {"dataset": dict(self.dataset), "grid": dict(self.axes)}
        if self.machine is not None:
            out["machine"] = dict(self.machine)
        return _json_safe(out)


def _load_source(source) -> dict:
    if isinstance(source, dict):
        return source
    if isinstance(source, (str, os.PathLike)):
        path = Path(source)
        try:
            with path.open("rb") as fh:
                return tomllib.load(fh)
        except tomllib.TOMLDecodeError as exc:
            raise ValueError(f"{path}: not a valid TOML grid file: {exc}") from None
        except UnicodeDecodeError as exc:   # a binary file (or another encoding)
            raise ValueError(f"{path}: not a TOML text file (byte {exc.object[exc.start]:#04x} "
                             f"at position {exc.start} is not UTF-8); give the grid's .toml "
                             "file") from None
    raise TypeError(f"grid must be a TOML file path, a dict or a Grid, got {type(source).__name__}")


def _point_scene(dataset: dict, sensors: list, values: dict) -> dict:
    """JSON-able Scene kwargs of one grid point (without its seed)."""
    scene = {"bearing": values["bearing"], "rpm": values["rpm"],
             "duration_s": dataset["duration_s"], "fs": dataset["fs"],
             "sensors": [asdict(Sensor.named(s)) if isinstance(s, str) else s
                         for s in sensors]}
    if values["fault"] != "healthy":
        scene["fault"] = {"kind": values["fault"],
                          **{arg: values[k] for k, arg in _FAULT_AXES.items() if k in values}}
    for key in _SCENE_AXES:
        if key in values:
            scene[key] = None if values[key] == math.inf else values[key]
    _realism_scene(scene, values)
    if "needs" in dataset:
        scene["needs"] = list(dataset["needs"])
    return scene


def _realism_scene(scene: dict, values: dict) -> None:
    """Set the Scene fields of the realism axes (:data:`REALISM_AXES`) in ``scene``."""
    if "noise_slope_db_oct" in values:
        scene["noise_slope_db_oct"] = values["noise_slope_db_oct"]
    modes = [[values[f"resonance{k}_hz"],
              *(values.get(f"resonance{k}_{p}", default) for p, default in MODE_DEFAULTS.items())]
             for k in (2, 3) if f"resonance{k}_hz" in values]
    if modes:
        scene["resonances"] = modes
    levels = [values.get(f"shaft_harmonic_{k}x") for k in (1, 2, 3, 4)]
    if any(v is not None for v in levels):
        last = max(i for i, v in enumerate(levels) if v is not None)
        scene["shaft_harmonics"] = [0.0 if v is None else v for v in levels[:last + 1]]
    if "sensor_angle_deg" in values:
        sensor = scene["sensors"][0]
        name = sensor["name"] if sensor["name"] not in ("loaded", "unloaded") else "sensor"
        scene["sensors"] = [{**sensor, "angle_deg": values["sensor_angle_deg"], "name": name}]


def _check_realism_axes(axes: dict) -> None:
    """Refuse a mode's damping or gain without its frequency, a third mode without a
    second, and a drawn sensor angle with several sensors."""
    for k in (2, 3):
        given = [a for a in (f"resonance{k}_damping", f"resonance{k}_gain") if a in axes]
        if given and f"resonance{k}_hz" not in axes:
            raise ValueError(f"grid.{given[0]} needs grid.resonance{k}_hz, the mode's "
                             "frequency (Hz)")
    if "resonance3_hz" in axes and "resonance2_hz" not in axes:
        raise ValueError("grid.resonance3_hz needs grid.resonance2_hz: give the extra "
                         "modes in order")
    if "sensor_angle_deg" in axes and len(axes.get("sensor", ["loaded"])) > 1:
        raise ValueError(f"grid.sensor_angle_deg sets the angle of the one sensor, but "
                         f"grid.sensor has {len(axes['sensor'])}: use one sensor, or give "
                         "each sensor's angle_deg in its table")


def read_grid(source) -> Grid:
    """Read and validate a dataset grid.

    Parameters
    ----------
    source : str or os.PathLike or dict or Grid
        A TOML file, or the same content as a dict with tables ``"dataset"`` and
        ``"grid"``. A :class:`Grid` is returned unchanged.

    Returns
    -------
    Grid

    Raises
    ------
    ValueError
        Malformed TOML, unknown tables, keys or axes, empty lists, reversed or
        non-positive ranges, values of the wrong type, duplicate values, or a grid
        point that :class:`~ballpass.Scene` refuses (the message names the point).

    Notes
    -----
    ``[dataset] needs`` (a list of phenomenon names, e.g. ``["envelope"]``) is passed to
    every run as ``Scene(needs=...)``, so ``model = "auto"`` runs the cheapest model
    that covers it (see :func:`ballpass.simulate.resolve_model`); each row records the
    model that ran.

    ``[grid]`` axes (each a list; a bare value is a one-value list; numeric axes also
    accept a range table ``{start, stop, step}`` with ``stop`` included):

    ``bearing`` (catalogue names), ``fault`` ("healthy", "outer", "inner", "ball"),
    ``fault_width_mm``, ``fault_depth_mm``, ``fault_angle_deg`` (fault rows only),
    ``fault_engagement`` (ball rows only: ``Fault(engagement=...)``, the share of the
    ball's spin revolutions, in (0, 1], on which its defect strikes; see below),
    ``fault_spin_drift_deg`` (ball rows only: ``Fault(spin_drift_deg=...)``, how far
    the ball's spin axis wanders, in [0, 90] deg; a metadata column of its own, 0 for
    race faults and NaN for healthy rows; like ``fault_engagement`` it needs a model
    that represents ``intermittent_faults``),
    ``rpm`` (a value or a ``[start, end]`` ramp), ``radial_load_n`` (N),
    ``clearance_um`` (mounted radial clearance, um, in (-50, 200); negative is a preload,
    which loads every ball so that outer-race faults out of the load zone strike;
    ``Scene(clearance_um=...)``; left out: the bearing's catalogue clearance), ``slip``,
    ``snr_db`` (dB; ``inf`` = noise-free) or ``noise_rms`` (absolute sensor noise,
    m/s^2), ``resonance_hz`` (Hz), ``resonance_damping`` (ratio), ``model``, and
    ``sensor`` ("loaded", "unloaded" or a table of :class:`~ballpass.Sensor` fields),
    the channels of each run. Axes left out take the :class:`~ballpass.Scene`
    defaults; ``bearing``, ``fault`` and ``rpm`` are required.

    The realism axes (:data:`REALISM_AXES`) set the rest of the machine:
    ``noise_slope_db_oct`` (slope of the background noise, dB/octave, in [-12, 12]),
    ``resonance2_hz``/``_damping``/``_gain`` and ``resonance3_*`` (further structural
    modes, ``Scene(resonances=...)``; damping 0.05 and gain 1 when left out),
    ``shaft_harmonic_1x`` ... ``_4x`` (shaft-rate lines, m/s^2 each,
    ``Scene(shaft_harmonics=...)``) and ``sensor_angle_deg`` (the angle of the one
    sensor, degrees from the load line). Each is stored as a column of its own.

    **A twin.** A ``[machine]`` table, ``manifest = "healthy.csv"`` (relative to the
    TOML file, or absolute), makes the grid a twin of a real machine
    (:mod:`ballpass.datasets.twin`, written by :func:`~ballpass.datasets.twin`): its
    rows are simulated faults through the machine's learned transmission path over
    segments of its healthy recordings, and healthy rows are those segments. Its
    ``level_db`` axis (required there, refused elsewhere) is the fault's RMS over the
    background's, dB; its optional axes (refused elsewhere) ``impact_spread``, the
    standard deviation of the logarithm of its impacts' sizes, ``impact_correlation``,
    their lag-1 correlation, and ``impact_edges``, 0 or 1 (a list, or drawn with
    ``{ choice = [0, 1] }``): a defect passage as one point impact or with its
    Hertzian entry and exit edges; healthy
    points multiply over none of them; one sensor.

    **Drawn axes.** Every numeric axis may instead be a distribution (see
    :mod:`ballpass.datasets.distributions`): ``{uniform = [lo, hi]}``,
    ``{log_uniform = [lo, hi]}``, ``{normal = [mean, sigma]}`` or ``{choice = [...]}``.
    A drawn axis adds no points to the product; ``[dataset] draws = N`` (default 1)
    gives each grid point N draws, each of ``repeats`` runs. Draw ``d`` of point ``p``
    takes its values from its own seed, :func:`draw_seed` ``(seed, p * draws + d)``
    (stored in the ``draw_seed`` column beside ``draw``; the drawn values are in their
    columns and in the row's ``scene``, so :func:`~ballpass.datasets.regenerate` gives
    the row bit for bit). A distribution is checked against its field's range before
    any work (a normal reaching beyond it at 4 sigma is refused, not clipped), and
    every grid point is validated with each drawn axis at its extremes. A grid
    without drawn axes keeps its run ids, seeds and scenes.

    ``fault_engagement`` multiplies the ball points only: healthy, outer- and
    inner-race points appear once per combination of the other axes, with the
    :class:`~ballpass.Fault` default engagement 1 (a race defect is on the track on
    every pass), so ``fault = ["healthy", "outer", "inner", "ball"]`` with two widths
    and ``fault_engagement = [0.3, 0.6]`` gives 1 + 2 + 2 + 2 x 2 = 9 points per
    combination of the other axes. A grid without the axis keeps its run ids, seeds
    and scenes (its ball faults strike on every revolution, as before). The axis is
    refused without a ``"ball"`` fault (it would change nothing). Scenes with
    ``engagement < 1`` need a model that represents ``intermittent_faults`` (sr5,
    sr4, gearbox, impulse; ``model = "auto"`` picks one); :func:`~ballpass.datasets.generate`
    refuses, before any work, a model that would ignore it. List the engagements to
    cover, give a range table, e.g. ``{start = 0.2, stop = 0.7, step = 0.1}``, or draw
    them per run, ``{uniform = [0.2, 0.7]}`` (docs/sim2real.md recommends 0.2-0.7 for
    training sets meant for real machines).

    Examples
    --------
    >>> from ballpass.datasets import read_grid
    >>> grid = read_grid({"dataset": {"duration_s": 0.5, "fs": 48_000},
    ...                   "grid": {"bearing": ["6205"], "fault": ["healthy", "inner"],
    ...                            "rpm": {"start": 1730, "stop": 1797, "step": 67}}})
    >>> grid.axes["rpm"], grid.n_runs
    ([1730.0, 1797.0], 4)
    >>> read_grid({"grid": {"bearing": ["6205"], "fault": ["cracked"], "rpm": [1797]}})
    Traceback (most recent call last):
        ...
    ValueError: grid.fault[0] must be one of ('healthy', 'outer', 'inner', 'ball'), got 'cracked'
    >>> read_grid({"grid": {"bearing": ["6205"], "fault": ["ball"], "rpm": [1797],
    ...                     "fault_engagement": [0.5, 1.5]}})   # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    ValueError: grid.fault_engagement[1] = 1.5 is outside (0, 1]: ...
    """
    if isinstance(source, Grid):
        return source
    raw = _load_source(source)
    unknown = set(raw) - {"dataset", "grid", "machine"}
    if unknown:
        raise ValueError(f"unknown table(s) {sorted(unknown)}; a grid has [dataset] and "
                         "[grid] (and [machine] for a twin)")
    for table in ("dataset", "grid", "machine"):
        if not isinstance(raw.get(table, {}), dict):
            raise ValueError(f"[{table}] must be a table, got {raw[table]!r}")
    dataset = _dataset_settings(raw.get("dataset", {}))
    grid_raw = raw.get("grid", {})
    unknown = set(grid_raw) - set(AXES)
    if unknown:
        raise ValueError(f"unknown grid axis/axes {sorted(unknown)}; allowed: {list(AXES)}")
    missing = [k for k in REQUIRED_AXES if k not in grid_raw]
    if missing:
        raise ValueError(f"grid is missing required axis/axes {missing}")
    if "model" in grid_raw:
        if "model" in raw.get("dataset", {}):
            raise ValueError("give the model either as [dataset] model or as the grid.model "
                             "axis")
        del dataset["model"]
    axes = {k: _axis_values(k, grid_raw[k], dataset["fs"]) for k in AXES if k in grid_raw}
    _check_ball_axes(axes)
    _check_realism_axes(axes)
    machine = _machine_table(raw, source, axes)
    if dataset.get("draws", 1) > 1 and not any(isinstance(v, Distribution)
                                               for v in axes.values()):
        raise ValueError(f"dataset.draws = {dataset['draws']} needs a drawn axis (e.g. "
                         "resonance_hz = { uniform = [2000, 6000] }); without one every draw "
                         "is the same: use dataset.repeats")

    _check_count(dataset, axes)
    points = _expand(dataset, axes)
    if "shard_size" not in dataset:
        run_bytes = 4 * len(axes.get("sensor", ["loaded"])) * max(
            1, round(dataset["duration_s"] * dataset["fs"]))
        n_runs = len(points) * dataset["repeats"] * dataset.get("draws", 1)
        dataset["shard_size"] = max(1, min(_SHARD_BYTES // run_bytes, _MAX_SHARD_RUNS,
                                           -(-n_runs // _MIN_SHARDS)))
    return Grid(dataset=dataset, axes=axes, _points=points, machine=machine)


def _machine_table(raw: dict, source, axes: dict) -> dict | None:
    """The validated [machine] table of a twin (its manifest made absolute: relative to
    the TOML file's folder, or to the current folder for a dict), or None; the twin's
    axes and constraints are checked (see :mod:`ballpass.datasets.twin`)."""
    if "machine" not in raw:
        given = [k for k in TWIN_AXES if k in axes]
        if given:
            what = {"level_db": "the fault's level over a real machine's background",
                    "impact_spread": "the spread of a twin's impact sizes",
                    "impact_edges": "the shape of a twin's defect passages",
                    "impact_correlation": "the correlation of a twin's impact sizes"}[given[0]]
            raise ValueError(f"grid.{given[0]} is {what}: it needs a [machine] table "
                             "naming the healthy recordings (ballpass twin writes one)")
        return None
    table = raw["machine"]
    unknown = set(table) - {"manifest"}
    if unknown or "manifest" not in table:
        raise ValueError(f"[machine] has one key, manifest (the table of the machine's "
                         f"healthy recordings); got keys {sorted(table)}")
    if not isinstance(table["manifest"], str) or not table["manifest"].strip():
        raise ValueError(f"machine.manifest must be a path, got {table['manifest']!r}")
    base = (Path(source).parent if isinstance(source, (str, os.PathLike)) else Path.cwd())
    manifest = (base / table["manifest"]).resolve()
    if "level_db" not in axes:
        raise ValueError("a twin's grid (with [machine]) needs grid.level_db, the fault's RMS "
                         "over the background's, dB, e.g. level_db = { uniform = [-10, 15] }")
    edges = axes.get("impact_edges", [0.0])
    drawn = isinstance(edges, Distribution)
    if (drawn and edges.kind != "choice") or any(
            v not in (0.0, 1.0) for v in (edges.params if drawn else edges)):
        raise ValueError(f"grid.impact_edges must list 0 (a passage is one point impact) "
                         f"and/or 1 (its Hertzian entry and exit edges), or draw them with "
                         f"{{ choice = [0, 1] }}; got {edges}")
    if len(axes.get("sensor", ["loaded"])) != 1:
        raise ValueError("a twin's grid has one sensor, the machine's accelerometer; "
                         f"grid.sensor has {len(axes['sensor'])}")
    return {"manifest": str(manifest)}


def _check_ball_axes(axes: dict) -> None:
    """Refuse engagements outside (0, 1], spin drifts outside [0, 90] deg and either
    axis without ball faults."""
    engagements = axes.get("fault_engagement", ())
    for i, v in enumerate(() if isinstance(engagements, Distribution) else engagements):
        if not 0.0 < v <= 1.0:
            raise ValueError(
                f"grid.fault_engagement[{i}] = {v:g} is outside (0, 1]: it is the share of "
                "a ball's spin revolutions on which its defect strikes (Fault(engagement=...); "
                "1 = every revolution)")
    drifts = axes.get("fault_spin_drift_deg", ())
    for i, v in enumerate(() if isinstance(drifts, Distribution) else drifts):
        if not 0.0 <= v <= 90.0:
            raise ValueError(
                f"grid.fault_spin_drift_deg[{i}] = {v:g} is outside [0, 90]: it is how far "
                "a ball's spin axis wanders, deg (Fault(spin_drift_deg=...); 0 = a fixed axis)")
    for axis in _BALL_AXES:
        if axis in axes and "ball" not in axes["fault"]:
            raise ValueError(
                f"grid.{axis} applies to ball faults only (a race defect lies on the "
                f"track on every pass), and grid.fault = {axes['fault']} has no \"ball\": add "
                "\"ball\" or drop the axis")


def _fault_axes_of(kind: str, axes) -> list[str]:
    """The fault axes (of ``axes``, in order) that a point of fault ``kind`` multiplies over:
    none for healthy points, no ball-only axis for race faults."""
    if kind == "healthy":
        return []
    return [k for k in axes if k in _FAULT_ONLY and (kind == "ball" or k not in _BALL_AXES)]


def count_points(axes: dict) -> int:
    """Grid points of validated axes, counted without building them: healthy points do
    not multiply over the fault axes, race-fault points not over the ball-only ones."""
    other = math.prod(_n_values(v) for k, v in axes.items()
                      if k not in _FAULT_ONLY and k not in ("sensor", "fault"))
    return other * sum(math.prod(_n_values(axes[k]) for k in _fault_axes_of(kind, axes))
                       for kind in axes["fault"])


def _n_values(values) -> int:
    """Points an axis adds to the product: a drawn axis adds none (one value per run)."""
    return 1 if isinstance(values, Distribution) else len(values)


def _sizes(axes: dict) -> str:
    """The grid's size for a refusal, e.g. ``"4 fault x 100 rpm"``: the axes that add
    points, sensors left out (they add channels, not runs); empty for one point."""
    return " x ".join(f"{_n_values(v)} {k}" for k, v in axes.items()
                      if _n_values(v) > 1 and k != "sensor")


def _check_count(dataset: dict, axes: dict) -> None:
    """Refuse a grid of more than :data:`MAX_RUNS` runs before expanding it."""
    n_points = count_points(axes)
    n_runs = n_points * dataset["repeats"] * dataset.get("draws", 1)
    if n_runs > MAX_RUNS:
        raise ValueError(
            f"the grid has {n_runs:.3g} runs ({_sizes(axes) or '1 point'}, x {dataset['repeats']} "
            f"repeats x {dataset.get('draws', 1)} draws); a dataset holds at most "
            f"{MAX_RUNS:,} runs. Use fewer values or "
            "repeats, or split the study into several datasets.")


def _check_points(axes: dict) -> None:
    """Refuse more than :data:`MAX_POINTS` listed grid points before building them."""
    n_points = count_points(axes)
    if n_points > MAX_POINTS:
        raise ValueError(
            f"the grid lists {n_points:.3g} points ({_sizes(axes)}); at most {MAX_POINTS:,} are "
            "checked one by one. List fewer values, or draw an axis from a distribution "
            "(e.g. rpm = { uniform = [600, 1800] } with [dataset] draws = N), whose values "
            "are checked once at their extremes.")


def drawn_axes(grid) -> dict[str, str]:
    """The drawn axes of a grid, described: axis -> ``"uniform 2500 - 4500"``.

    Parameters
    ----------
    grid : Grid or dict
        A grid, or its :meth:`Grid.as_dict` form (as a dataset's manifest stores it).

    Examples
    --------
    >>> from ballpass.datasets.grid import drawn_axes, read_grid
    >>> grid = read_grid({"dataset": {"draws": 4},
    ...                   "grid": {"bearing": "6205", "fault": "outer", "rpm": 1797,
    ...                            "resonance_hz": {"uniform": [2500, 4500]}}})
    >>> drawn_axes(grid), grid.n_runs
    ({'resonance_hz': 'uniform 2500 - 4500'}, 4)
    """
    if isinstance(grid, Grid):
        return {k: d.describe() for k, d in grid.distributions.items()}
    fs = grid["dataset"]["fs"]
    return {k: parse_distribution(k, v, fs).describe() for k, v in grid["grid"].items()
            if is_distribution(v)}


def grid_differences(stored: dict, new: dict, prefix: str = "") -> list[str]:
    """Keys whose values differ between two grids as dicts (:meth:`Grid.as_dict`).

    Returns
    -------
    list of str
        One line per differing key, ``"dataset.seed: 3 -> 4"``; a key missing on one
        side shows as ``(absent)``.
    """
    out = []
    for key in sorted(set(stored) | set(new)):
        a, b = stored.get(key, "(absent)"), new.get(key, "(absent)")
        if isinstance(a, dict) and isinstance(b, dict):
            out += grid_differences(a, b, f"{prefix}{key}.")
        elif a != b:
            out.append(f"{prefix}{key}: {json.dumps(a)} -> {json.dumps(b)}")
    return out


def _expand(dataset: dict, axes: dict) -> tuple:
    """Grid points as (model, scene kwargs, axis values) in product order; each validated
    as a Scene. A drawn axis takes its representative value here, and every point is
    also validated with each drawn axis at its extremes in turn."""
    product_axes = [k for k in AXES if k in axes and k != "sensor"]
    other_axes = [k for k in product_axes if k not in _FAULT_ONLY]
    sensors = axes.get("sensor", ["loaded"])
    drawn = {k: v for k, v in axes.items() if isinstance(v, Distribution)}
    listed = {k: [v.representative] if k in drawn else v for k, v in axes.items()}

    def checked(values_f: dict) -> dict:
        """The point's scene, validated, and with each drawn axis at its extremes."""
        scene = _point_scene(dataset, sensors, values_f)
        checks = [values_f] + [{**values_f, k: edge} for k, dist in drawn.items()
                               if k in values_f for edge in dist.extremes]
        for check in checks:
            try:
                scene_from_dict({**_point_scene(dataset, sensors, check), "seed": 0})
            except (TypeError, ValueError) as exc:
                point = ", ".join(f"{k}={v!r}" for k, v in check.items())
                raise ValueError(f"grid point ({point}): {exc}") from None
        return scene

    # the last point first: the extremes of every axis, where a bad value usually sits,
    # are refused at once rather than after building every point before them
    last = {k: listed[k][-1] for k in other_axes}
    checked({**last, **{k: listed[k][-1] for k in _fault_axes_of(last["fault"], product_axes)}})
    _check_points(axes)
    points = []
    for combo in itertools.product(*(listed[k] for k in other_axes)):
        values = dict(zip(other_axes, combo, strict=True))
        fault_axes = _fault_axes_of(values["fault"], product_axes)
        for fcombo in itertools.product(*(listed[k] for k in fault_axes)):
            values_f = {**values, **dict(zip(fault_axes, fcombo, strict=True))}
            points.append((values_f.get("model") or dataset["model"], checked(values_f),
                           values_f))
    return tuple(points)
