"""A twin of a real machine from its healthy recordings: simulated faults heard through
the machine's own transmission path, over its own background.

:func:`twin` writes a ready grid for a machine whose healthy recordings a manifest lists
(:mod:`ballpass.datasets.manifest`): faults of every kind over a range of sizes at the
speeds asked for, the machine's bearing and sampling rate, a ``[machine]`` table naming
the manifest, and the ``level_db`` axis, the fault's level over the background.
:func:`~ballpass.datasets.generate` then makes each row as follows.

*Transmission path.* A healthy recording is the structure's response to broadband
excitation (rolling, friction, the rest of the machine), so its spectrum is the path's
(Sawalhi & Randall 2005 model a healthy bearing signal the same way, to prewhiten it).
An all-pole model of it, ``1 / A(z)`` (:func:`ballpass.features.lpc.ar_fit`, order by
Akaike's criterion, :func:`ballpass.features.lpc.ar_order`), is the learned path. It is
fitted once per recording and process (cached), written to the dataset folder
(``_machine.json``), and refitted bit for bit by :func:`~ballpass.datasets.regenerate`.

*Fault rows.* The bearing's impacts come from the ``impulse`` model's kinematics (the
defect crossings of McFadden & Smith 1984 with random slip, the Stribeck load zone and
the sensor's transmission factor; :mod:`ballpass.simulate.impulse`), before its own
resonator: each is the housing-acceleration step of one defect passage, its size
multiplied by a log-normal factor of its own (mean 1, log standard deviation
``impact_spread``, drawn per row: the random amplitudes of Antoni & Randall 2003; a ball
does not strike a real spall the same way twice; their logarithms correlated from one
impact to the next by ``impact_correlation``, 0 by default). With ``impact_edges = 1``
a passage is what the ball goes through over a defect of width w at the
rolling speed v: the load leaves over the entry edge and comes back over the exit edge,
w / v later (the entry and exit of Sawalhi & Randall 2008), each edge as long as a ball
pivoting on a sharp edge takes to lose or regain its Hertzian deflection, with the
curvature of the race it strikes (a ball defect's inner-race strikes drop deeper than
its outer-race ones: :func:`passage_times`, :func:`edge_kernel`); with 0, one point
impact at the exit, split linearly between the two samples around its time (the twin
before the axis). The twin's grid draws one of the two per row: they bracket a real passage (the
quasi-static edges put less energy high in the band than a real exit, the point impact
is more impulsive than the rig's faults). The train drives ``1 / A(z)``;
the result is scaled so that its RMS over the row is ``level_db`` above the RMS of the
background, and a segment of a real healthy recording is added: one of the recordings
whose speed is nearest the row's, and the segment's start, drawn from the row's seed.

*Healthy rows* are that: segments of the real healthy recordings, unchanged (float32
as stored), at the recording's own speed (their load, slip and clearance NaN: unknown).
Their ``group`` is the recording's name, so no split puts segments of one recording on
both sides; a fault row's group is its run.

Every row keeps the columns of a simulated row (its scene, the fault's size and angle,
the slip, the load) and adds ``level_db``, ``impact_spread``, ``impact_edges``,
``impact_correlation``, ``machine`` (the
manifest), ``background`` (the recording) and ``background_start_s``; ``resonance_hz``,
``resonance_damping``, ``snr_db`` and ``noise_rms`` are NaN (the learned path and the
real background replace them).

References: P. D. McFadden, J. D. Smith, J. Sound Vib. 96 (1984) 69-82; N. Sawalhi,
R. B. Randall, "Simulating gear and bearing interactions in the presence of faults",
MSSP 22 (2008) 1924-1951; J. Antoni,
R. B. Randall, "A stochastic model for simulation and diagnostics of rolling element
bearings with localized faults", J. Vib. Acoust. 125 (2003) 282-289; N. Sawalhi,
R. B. Randall, "Spectral kurtosis enhancement using autoregressive models", ACAM 2005;
J. Makhoul, Proc. IEEE 63 (1975) 561-580.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["twin", "Machine", "MachineRecording", "load_machine", "check_machine",
           "twin_signal", "MACHINE_FILE", "TWIN_DEFAULTS"]

#: file of the learned paths in a twin dataset's folder
MACHINE_FILE = "_machine.json"
#: key of the twin's own random stream (the background's start) under the run's seed;
#: the impulse model uses the seed's own stream for the slip
_STREAM = 7

#: default ranges of a twin's grid, each with its source (see :func:`twin`)
TWIN_DEFAULTS = {
    "duration_s": 1.0,
    "draws": 40,
    "fault_width_mm": (0.2, 3.0),
    "fault_depth_mm": 0.3,
    "fault_angle_deg": (-60.0, 60.0),
    "level_db": (-10.0, 15.0),
    "impact_spread": (0.0, 1.0),
    "impact_edges": (0, 1),
    "impact_correlation": 0.0,
    "radial_load_n": (150.0, 1500.0),
    "slip": (0.005, 0.02),
}


# ----------------------------------------------------------------------------- machine
@dataclass(frozen=True)
class MachineRecording:
    """One healthy recording of a twin's machine and the path learned from it.

    Attributes
    ----------
    name : str
        Recording (file) name, also the ``group`` of its healthy rows.
    rpm : float
        Shaft speed, rev/min.
    fs : float
        Sampling frequency, Hz.
    accel : ndarray of float64, shape (n_samples,)
        The recording, in its own units.
    a : ndarray, shape (order + 1,)
        ``A(z)`` of the learned path ``1 / A(z)`` (:func:`ballpass.features.lpc.ar_fit`).
    order : int
        Its order (Akaike's criterion, :func:`ballpass.features.lpc.ar_order`).
    """

    name: str
    rpm: float
    fs: float
    accel: np.ndarray
    a: np.ndarray
    order: int


@dataclass(frozen=True)
class Machine:
    """The healthy recordings of a twin's machine (:func:`load_machine`).

    Attributes
    ----------
    manifest : str
        Absolute path of the manifest.
    bearing : str
        Catalogue bearing of every recording.
    fs : float
        Sampling frequency of every recording, Hz.
    recordings : tuple of MachineRecording
    sha256 : str
        Digest of the recordings' samples and speeds (a dataset refuses to resume on
        other recordings).
    """

    manifest: str
    bearing: str
    fs: float
    recordings: tuple
    sha256: str

    def nearest(self, rpm: float) -> tuple:
        """The recordings whose speed is nearest ``rpm`` (all of a tie), in order."""
        gap = min(abs(r.rpm - rpm) for r in self.recordings)
        return tuple(r for r in self.recordings if abs(r.rpm - rpm) == gap)

    def describe(self) -> dict:
        """JSON-able summary: per recording its name, speed, samples, path order and
        resonances (Hz, damping ratio) below 0.45 fs."""
        from ..features.lpc import ar_resonances

        out = []
        for r in self.recordings:
            freq, zeta = ar_resonances(r.a, r.fs)
            keep = (freq > 0) & (freq < 0.45 * r.fs) & (zeta < 1)
            out.append({"name": r.name, "rpm": r.rpm, "n_samples": int(r.accel.size),
                        "order": r.order, "a": r.a.tolist(),
                        "resonances_hz": np.round(freq[keep], 1).tolist(),
                        "damping": np.round(zeta[keep], 4).tolist()})
        return {"manifest": self.manifest, "bearing": self.bearing, "fs": self.fs,
                "sha256": self.sha256, "recordings": out}


def _healthy_records(manifest) -> list:
    """``[(path, Recording)]`` of a twin's manifest, checked: every row healthy (or
    unlabelled), one bearing, one sampling rate."""
    from .manifest import manifest_records

    found = manifest_records(manifest)
    labels = {rec.label for _, rec in found}
    if labels - {"healthy", "unknown"}:
        named = [f"{rec.name} ({rec.label})" for _, rec in found
                 if rec.label not in ("healthy", "unknown")]
        raise ValueError(f"manifest {manifest}: a twin learns from healthy recordings only; "
                         f"{', '.join(named)} {'is' if len(named) == 1 else 'are'} not "
                         "healthy. List the machine's healthy recordings (label healthy or "
                         "no label)")
    for key in ("bearing", "fs"):
        values = sorted({str(getattr(rec, key)) for _, rec in found})
        if len(values) != 1:
            raise ValueError(f"manifest {manifest}: a twin is one machine, but its "
                             f"recordings have {key} {values}; list recordings of one "
                             f"{'bearing' if key == 'bearing' else 'sampling rate'}")
    return found


@functools.lru_cache(maxsize=8)
def load_machine(manifest: str) -> Machine:
    """Read a twin's healthy recordings and learn each one's path; cached per process.

    Parameters
    ----------
    manifest : str
        Absolute path of the manifest of the machine's healthy recordings.

    Returns
    -------
    Machine

    Raises
    ------
    ValueError
        A row is labelled with a fault, the recordings mix bearings or rates, or none
        can be read.
    """
    from ..features.lpc import ar_fit, ar_order

    digest = hashlib.sha256()
    recordings = []
    found = _healthy_records(manifest)
    for _, rec in found:
        x = np.ascontiguousarray(rec.accel, dtype=float)
        order = ar_order(x, rec.fs)
        a, _ = ar_fit(x, order)
        recordings.append(MachineRecording(name=rec.name, rpm=float(rec.rpm),
                                           fs=float(rec.fs), accel=x, a=a, order=order))
        digest.update(f"{rec.name}\0{rec.rpm!r}\0{rec.fs!r}\0".encode())
        digest.update(x.tobytes())
    return Machine(manifest=str(manifest), bearing=str(found[0][1].bearing),
                   fs=recordings[0].fs, recordings=tuple(recordings),
                   sha256=digest.hexdigest())


def check_machine(grid) -> Machine:
    """Check a twin's grid against its machine before any work; return the machine.

    Raises
    ------
    ValueError
        The grid's sampling rate or bearing is not the recordings', a row is longer
        than the shortest recording, or the manifest lists a fault.
    """
    machine = load_machine(grid.machine["manifest"])
    where = f"the twin's recordings ({grid.machine['manifest']})"
    if grid.dataset["fs"] != machine.fs:
        raise ValueError(f"dataset.fs = {grid.dataset['fs']:g} Hz, but {where} are sampled "
                         f"at {machine.fs:g} Hz: a twin's rows have its recordings' rate. "
                         f"Set dataset.fs = {machine.fs:g}")
    bearings = grid.axes["bearing"]
    if list(bearings) != [machine.bearing]:
        raise ValueError(f"grid.bearing = {bearings}, but {where} are of the "
                         f"{machine.bearing}: set grid.bearing = [\"{machine.bearing}\"]")
    shortest = min(r.accel.size for r in machine.recordings)
    if grid.n_samples > shortest:
        raise ValueError(f"dataset.duration_s = {grid.dataset['duration_s']:g} s is longer "
                         f"than the shortest of {where} ({shortest / machine.fs:g} s): a "
                         "row's background is a segment of one recording")
    return machine


def write_machine(folder, machine: Machine) -> None:
    """Write the learned paths (:meth:`Machine.describe`) to ``folder/_machine.json``."""
    from ..signalio import atomic_write

    text = json.dumps(machine.describe(), indent=1)
    atomic_write(Path(folder) / MACHINE_FILE, lambda tmp: tmp.write_text(text))


# ----------------------------------------------------------------------------- rows
def _pulse_train(times: np.ndarray, steps: np.ndarray, n: int, fs: float) -> np.ndarray:
    """Impacts as samples: each step split linearly between the two samples around its
    time (its centre of mass stays at the impact time). Shape (n,)."""
    pos = times * fs
    k = np.floor(pos).astype(np.int64)
    frac = pos - k
    out = np.zeros(n + 1)
    keep = (k >= 0) & (k < n)
    np.add.at(out, k[keep], steps[keep] * (1.0 - frac[keep]))
    np.add.at(out, k[keep] + 1, steps[keep] * frac[keep])
    return out[:n]


def _impact_sizes(rng: np.random.Generator, n: int, spread, correlation=None) -> np.ndarray:
    """Relative sizes of ``n`` successive impacts: log-normal, the standard deviation of
    their logarithm ``spread`` (no axis, NaN or 0: all 1), their mean 1 (the median
    exp(-spread^2 / 2)), the random amplitudes of Antoni & Randall's cyclostationary
    model of a bearing fault. Their logarithms are a stationary first-order
    autoregression with lag-1 correlation ``correlation`` in [0, 1) (no axis, NaN or 0:
    independent from impact to impact, drawn as before the axis existed): a load or
    speed that drifts over several impacts makes neighbours alike."""
    if spread is None or not spread > 0:   # also NaN
        return np.ones(n)
    g = rng.standard_normal(n)
    if correlation is not None and correlation > 0 and n > 1:
        import scipy.signal

        # g_k = rho g_(k-1) + sqrt(1 - rho^2) e_k from g_0 = e_0: unit variance throughout
        gain = math.sqrt(1.0 - correlation**2)
        g = scipy.signal.lfilter([gain], [1.0, -correlation], g,
                                 zi=[(1.0 - gain) * g[0]])[0]
    return np.exp(spread * g - 0.5 * spread**2)


def passage_times(scene, race: str | None = None) -> tuple[float, float, float]:
    """How long one defect passage and each of its edges last, s.

    A defect of width w (along the rolling direction) passes the contact at the speed
    v of the contact point relative to the defective surface: the outer race
    r_o 2 pi FTF, the inner race r_i 2 pi (f_r - FTF), a ball (d / 2) 2 pi BSF, with
    the raceway radii (d_p +- d) / 2 and the rates of
    :meth:`ballpass.Bearing.frequencies`; the passage lasts w / v (the time from the
    entry crossing to the exit crossing of the impulse model's kinematics, without
    slip). Two surfaces pivoting over a sharp edge part by x^2 / (2 r) at a distance x
    from it, r = 1 / (1/R_b +- 1/R_race) their relative radius in the rolling plane
    (R_b = d/2, + on the convex inner race, - in the concave outer race: the
    curvature of :meth:`ballpass.Fault.effective_depth_mm`), so the contact deflection
    delta (the Stribeck deflection of the most loaded element,
    :func:`ballpass.simulate.impulse.impact_amplitudes`), or the defect's effective
    depth h against that race when smaller, goes or comes back over
    x_c = sqrt(2 r min(delta, h)) (at most w / 2): the edge lasts x_c / v.

    Parameters
    ----------
    scene : Scene
        A scene with one fault, at constant speed.
    race : {"inner", "outer"} or None, optional
        The race struck: a race fault's own (None); required for a ball fault, which
        strikes both.

    Returns
    -------
    passage_s, edge_s : float
        w / v and x_c / v, s.
    drop : float
        min(delta, h) / delta, in (0, 1]: the share of the deflection the ball loses
        (1: it leaves the load entirely, 0 without a load).
    """
    from ..simulate.impulse import _DEFAULTS, _load_zone

    fault, b = scene.faults[0], scene.bearing
    depth = fault.effective_depth_mm(b, race) * 1e-3   # refuses a race it cannot strike
    race = race or fault.kind
    shaft_hz = scene.speed.rpm_start / 60.0
    rates = b.frequencies(shaft_hz)
    radius = 0.5 * b.element_diameter_m
    speed = {"outer": b.outer_race_radius_m * 2 * math.pi * rates.ftf,
             "inner": b.inner_race_radius_m * 2 * math.pi * (shaft_hz - rates.ftf),
             "ball": radius * 2 * math.pi * rates.bsf}[fault.kind]
    relative = 1.0 / (1.0 / radius + (1.0 / b.inner_race_radius_m if race == "inner"
                                      else -1.0 / b.outer_race_radius_m))
    width = fault.width_mm * 1e-3
    _, zone = _load_zone(scene, _DEFAULTS)
    delta = (zone.deflection_m - b.radial_clearance_m) * math.cos(b.contact_angle_rad)
    drop = min(delta, depth)
    if not drop > 0:
        return width / speed, 0.0, 0.0
    reach = min(math.sqrt(2.0 * relative * drop), 0.5 * width)
    return width / speed, reach / speed, drop / delta


def edge_kernel(edge_s: float, fs: float, exponent: float = 1.5,
                drop: float = 1.0) -> np.ndarray:
    """How the load comes back at a defect's exit edge, sample by sample, summing to 1.

    The contact deflection returns as delta (1 - drop (x / x_c)^2) while the distance x
    to the edge falls from x_c to 0 at constant speed (:func:`passage_times`), and the
    load with it as its Hertzian power ``exponent`` (3/2 for a ball): entry k of the
    kernel is the load's increment over sample k, of ``round(edge_s fs)`` samples
    (at least 1). Reversed and negated, it is the load going at the entry edge.

    Parameters
    ----------
    edge_s : float
        Edge duration, s (:func:`passage_times`).
    fs : float
        Sampling frequency, Hz.
    exponent : float, optional
        Hertz load-deflection exponent n.
    drop : float, optional
        Share of the deflection lost in the defect, in (0, 1] (:func:`passage_times`).

    Returns
    -------
    ndarray, shape (n_edge,)
    """
    n_edge = max(1, round(edge_s * fs))
    load = (1.0 - drop * np.linspace(1.0, 0.0, n_edge + 1) ** 2) ** exponent
    return np.diff(load) / (load[-1] - load[0])


def _passage_train(times: np.ndarray, steps: np.ndarray, n: int, fs: float,
                   passage_s: float, edge: np.ndarray) -> np.ndarray:
    """Defect passages as samples: each load step ``steps[k]`` released by the edge
    kernel ``edge`` reversed at the entry, ``passage_s`` before ``times[k]``, and taken
    back by ``edge`` ending at ``times[k]`` (each placed as :func:`_pulse_train` places
    a point). A passage inside the row sums to 0: the load it takes away comes back.
    Shape (n,)."""
    m = edge.size
    exits = _pulse_train(times, steps, n + m - 1, fs)
    entries = _pulse_train(times - passage_s, steps, n, fs)
    return np.convolve(exits, edge)[m - 1:m - 1 + n] - np.convolve(entries, edge[::-1])[:n]


def _rms(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean((x - x.mean()) ** 2)))


def twin_signal(run, scene) -> tuple[np.ndarray, dict, dict]:
    """The signal of one twin run (see the module docstring).

    Parameters
    ----------
    run : Run
        A run of a twin's grid (``run.machine`` set, ``run.columns["level_db"]``).
    scene : Scene
        Its scene (one sensor).

    Returns
    -------
    accel : ndarray of float64, shape (1, n_samples)
        Background plus the fault through the learned path, in the recording's units.
    info : dict
        ``model`` and ``solver`` of the row.
    columns : dict
        Columns that differ from a simulated row's (``group``, the speed of a healthy
        row, NaN resonance and noise fields) and the twin's own (``machine``,
        ``background``, ``background_start_s``).
    """
    import scipy.signal

    from ..simulate.impulse import _impacts

    machine = load_machine(run.machine)
    n = scene.n_samples
    rng = np.random.default_rng(np.random.SeedSequence(scene.seed, spawn_key=(_STREAM,)))
    nearest = machine.nearest(scene.speed.rpm_start)
    rec = nearest[int(rng.integers(len(nearest)))]
    start = int(rng.integers(0, rec.accel.size - n + 1))
    background = rec.accel[start:start + n]
    columns = {"resonance_hz": math.nan, "resonance_damping": math.nan,
               "snr_db": math.nan, "noise_rms": math.nan, "machine": machine.manifest,
               "background": rec.name, "background_start_s": start / rec.fs}
    if not scene.faults:
        accel = background.copy()
        # a real segment: its speed is the recording's, its load, slip and clearance
        # unknown (not the grid point's, which made nothing of it)
        columns.update(group=rec.name, rpm=rec.rpm, rpm_start=rec.rpm, rpm_end=rec.rpm,
                       radial_load_n=math.nan, slip=math.nan, clearance_um=math.nan)
    else:
        times, steps, (before, _fault, face, _edges) = _impacts(scene)
        steps = steps[0] * _impact_sizes(rng, times.size, run.columns.get("impact_spread"),
                                         run.columns.get("impact_correlation"))
        if run.columns.get("impact_edges", 0.0) == 1.0:
            # the race each impact strikes: a ball defect's face (0 outer, 1 inner) at
            # its exit crossing, each race with its own edges
            kind = scene.faults[0].kind
            races = (np.where(face[np.searchsorted(before, times)] == 1, "inner", "outer")
                     if kind == "ball" else np.full(times.size, kind))
            train = np.zeros(n)
            for race in np.unique(races):
                passage_s, edge_s, drop = passage_times(scene, str(race))
                edge = edge_kernel(edge_s, scene.fs, scene.bearing.load_exponent, drop or 1.0)
                struck = races == race
                train += _passage_train(times[struck], steps[struck], n, scene.fs, passage_s,
                                        edge)
        else:   # one point impact per passage (the twin before impact_edges)
            train = _pulse_train(times, steps, n, scene.fs)
        fault = scipy.signal.lfilter([1.0], rec.a, train)
        fault -= fault.mean()
        size = _rms(fault)
        if size > 0:   # a defect that never strikes (out of the load zone) stays silent
            fault *= _rms(background) * 10.0 ** (run.columns["level_db"] / 20.0) / size
        accel = background + fault
        columns["group"] = f"run {run.run_id}"
    return accel[None, :], {"model": "impulse", "solver": "ar-path"}, columns


# ----------------------------------------------------------------------------- grid
def _check_rpm(rpm) -> list[float]:
    values = [rpm] if isinstance(rpm, (int, float)) else list(rpm)
    if not values:
        raise ValueError("rpm must list at least one shaft speed, rev/min")
    out = []
    for v in values:
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or (
                not math.isfinite(v) or v <= 0):
            raise ValueError(f"rpm must be shaft speeds > 0 rev/min, got {v!r}")
        out.append(float(v))
    if len(set(out)) != len(out):
        raise ValueError(f"rpm has duplicate speeds {out}")
    return out


def _toml_path(manifest: Path, out: Path) -> str:
    """The manifest as the grid names it: relative to the grid's folder when both sit
    on one drive, else absolute."""
    try:
        return Path(os.path.relpath(manifest, out.parent)).as_posix()
    except ValueError:   # another drive (Windows)
        return manifest.as_posix()


def twin(manifest, rpm, out, *, duration_s: float = TWIN_DEFAULTS["duration_s"],
         draws: int = TWIN_DEFAULTS["draws"], seed: int = 0) -> Path:
    """Write a ready grid of a twin of the machine whose healthy recordings ``manifest``
    lists.

    The grid has outer-race, inner-race and ball faults and the healthy class at each
    speed of ``rpm``, ``draws`` rows of each per speed, the recordings' bearing and
    sampling rate, and a ``[machine]`` table naming the manifest; ``generate`` then
    learns the machine's path from the recordings (see the module docstring). Drawn per
    row, each range with its source in the file: fault width, outer-race fault angle,
    radial load, slip, ``level_db``, the fault's RMS over the background's, and
    ``impact_spread``, the log standard deviation of the impacts' sizes, and
    ``impact_edges``, a defect passage as one point impact or with its entry and
    exit edges; fixed: ``impact_correlation = [0]`` (independent sizes).

    Parameters
    ----------
    manifest : str or os.PathLike
        A manifest (CSV or Parquet, :func:`~ballpass.datasets.load_manifest`) of healthy
        recordings of one machine: one bearing, one sampling rate; ``label`` may be
        absent, and is ``healthy`` where given.
    rpm : float or sequence of float
        Shaft speeds of the fault rows, rev/min, > 0.
    out : str or os.PathLike
        The grid file to write (``.toml``); the manifest is named relative to its folder.
    duration_s : float, optional
        Seconds per row, at most the shortest recording. Default 1.
    draws : int, optional
        Rows per class and speed, >= 1. Default 40.
    seed : int, optional
        The grid's root seed, >= 0.

    Returns
    -------
    pathlib.Path
        ``out``.

    Raises
    ------
    ValueError
        ``rpm`` not positive, ``draws`` < 1, ``duration_s`` not positive or longer
        than a recording, a recording labelled with a fault, recordings of several
        bearings or rates, or no readable recording; nothing is written.

    Examples
    --------
    >>> import numpy as np, pandas as pd, tempfile, pathlib
    >>> from ballpass.datasets import read_grid, twin
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> np.save(folder / "healthy.npy", np.random.default_rng(0).normal(size=60_000))
    >>> pd.DataFrame({"path": ["healthy.npy"], "fs": [12_000], "rpm": [1797],
    ...               "bearing": ["6205"]}).to_csv(folder / "healthy.csv", index=False)
    >>> path = twin(folder / "healthy.csv", rpm=[1730, 1797], out=folder / "twin.toml")
    >>> grid = read_grid(path)
    >>> grid.n_runs, grid.dataset["fs"], pathlib.Path(grid.machine["manifest"]).name
    (320, 12000.0, 'healthy.csv')
    """
    from .._validation import check_number
    from ..signalio import atomic_write

    speeds = _check_rpm(rpm)
    check_number("duration_s", duration_s, 0.0, lo_open=True, unit="s")
    if isinstance(draws, bool) or not isinstance(draws, (int, np.integer)) or draws < 1:
        raise ValueError(f"draws must be an int >= 1, got {draws!r}")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be an int >= 0, got {seed!r}")
    manifest = Path(manifest).resolve()
    if not manifest.is_file():
        raise ValueError(f"manifest: no such file: {manifest}")
    out = Path(out)
    found = _healthy_records(manifest)
    rec = found[0][1]
    shortest = min(r.accel.size / r.fs for _, r in found)
    if duration_s > shortest:
        raise ValueError(f"duration_s = {duration_s:g} s is longer than the shortest "
                         f"recording ({shortest:g} s)")
    text = _GRID_TEMPLATE.format(
        names=", ".join(r.name for _, r in found), bearing=rec.bearing, fs=rec.fs,
        manifest=json.dumps(_toml_path(manifest, out.resolve())),
        duration_s=duration_s, draws=draws, seed=seed,
        rpm=", ".join(f"{v:g}" for v in speeds), d=TWIN_DEFAULTS, resonance_hz=rec.fs / 4,
        n_runs=4 * draws * len(speeds))
    atomic_write(out, lambda tmp: tmp.write_text(text))
    return out


_GRID_TEMPLATE = """\
# A twin of the machine whose healthy recordings {manifest} lists ({names}):
# simulated faults heard through the machine's own transmission path (an all-pole model
# learned from the recordings), over segments of the recordings as background; healthy
# rows are the recordings' own segments. Written by `ballpass twin`; then
#   ballpass generate twin.toml --out twin-ds --jobs 2
#   ballpass benchmark twin-ds --real labelled.csv --splits sim2real --out twin-report
# Rows: 4 classes (healthy, outer, inner, ball) x {draws} draws x speeds = {n_runs}.

[dataset]
duration_s = {duration_s:g}  # s per row (a segment of one recording as background)
fs = {fs:g}            # Hz, the recordings' rate
draws = {draws}             # rows per class and speed, each with its own drawn values
seed = {seed}
model = "impulse"      # the bearing's impacts (kinematics, slip, load zone), no resonator:
needs = ["envelope"]   # the learned path replaces it

[machine]
manifest = {manifest}

[grid]
bearing = ["{bearing}"]
fault = ["healthy", "outer", "inner", "ball"]
rpm = [{rpm}]
# the impulse model's own resonator is not used (the learned path replaces it; the rows'
# resonance_hz is NaN); a scene still needs one inside the band: fs / 4
resonance_hz = [{resonance_hz:g}]
# defect widths from the seeded faults of test rigs (0.18-1.0 mm, the CWRU data centre's
# EDM faults) to spalls of a few mm (Sawalhi & Randall, MSSP 2011, simulate spalls of
# 1-3 mm); drawn on a log scale. The depth of a wide defect is the ball's drop into it.
fault_width_mm = {{ log_uniform = [{d[fault_width_mm][0]:g}, {d[fault_width_mm][1]:g}] }}
fault_depth_mm = [{d[fault_depth_mm]:g}]
# an outer-race defect anywhere in the load zone (+-60 deg of its centre: the Stribeck
# load zone of a radially loaded ball bearing with a small clearance spans +-60-90 deg;
# Harris & Kotzalas, Rolling Bearing Analysis, 2006)
fault_angle_deg = {{ uniform = [{d[fault_angle_deg][0]:g}, {d[fault_angle_deg][1]:g}] }}
# the fault's RMS over the background's, dB. From -10 dB, where it changes the overall
# level by 0.4 dB, below the repeatability of an overall reading (the earliest faults
# envelope analysis is for), to +15 dB, where it multiplies the overall level by 5.8:
# two steps of the ISO 10816-1 evaluation zones (each a factor 2.5, 8 dB), from a new
# machine's zone A into zone C/D
level_db = {{ uniform = [{d[level_db][0]:g}, {d[level_db][1]:g}] }}
# how much the impacts' sizes differ from one passage to the next: the standard deviation
# of their logarithm (independent log-normal sizes, mean kept), the random amplitudes of
# Antoni & Randall's model of a localized fault (J. Vib. Acoust. 2003), who leave their
# spread open. From 0, McFadden & Smith's identical impacts (J. Sound Vib. 1984), to 1,
# sizes a factor e apart at one standard deviation: a ball striking a rough, widening
# spall at a new point each time. A judgement, not a published range
impact_spread = {{ uniform = [{d[impact_spread][0]:g}, {d[impact_spread][1]:g}] }}
# a defect passage as the ball sees it (1): the load leaves over the entry edge and comes
# back over the exit edge, w / v apart (w the defect's width, v the rolling speed over
# it: the entry and exit of Sawalhi & Randall, MSSP 2008), each edge lasting as long as
# a ball pivoting on a sharp edge takes to lose or regain its Hertzian deflection; or one
# point impact at the exit (0), as McFadden & Smith's train. The two bracket a real
# passage: the quasi-static edges are smoother than a real exit (too little energy high
# in the band), the point impact sharper (too impulsive); each row draws one of them
impact_edges = {{ choice = [{d[impact_edges][0]:g}, {d[impact_edges][1]:g}] }}
# lag-1 correlation of the logarithms of successive impacts' sizes: 0, independent (as
# Antoni & Randall's model draws them); up to 1, a load or speed drifting over several
# impacts. No published value: kept at 0 (correlated sizes brought the kurtosis of the
# HIT-SM twin's fault rows no nearer the rig's, docs/twin.md)
impact_correlation = [{d[impact_correlation]:g}]
# radial load from light to normal service, P/C = 0.01-0.1 of a 6205-size bearing's
# basic dynamic rating (SKF catalogue: about 0.01 C to roll without skidding)
radial_load_n = {{ log_uniform = [{d[radial_load_n][0]:g}, {d[radial_load_n][1]:g}] }}
# random rolling-element slip, 1-2 % (Randall & Antoni, MSSP 2011), drawn over 0.5-2 %
slip = {{ uniform = [{d[slip][0]:g}, {d[slip][1]:g}] }}
"""
