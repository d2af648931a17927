"""What a simulation returns: the signals and the exact ground truth that produced them."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..bearing import BearingFrequencies
from ..scene import Fault, Scene

__all__ = ["SimulationResult", "GroundTruth", "FaultCrossings"]


class Deferred:
    """An array computed on first use: ``function(*args)``, evaluated once and kept.

    A model passes one for an output that costs more to fill than to describe (the
    sample times, the tachometer channel and the speed of a 48 kHz record are three
    arrays as long as the signal), so a caller who never reads it never pays for it.
    Picklable when ``function`` and ``args`` are.
    """

    __slots__ = ("function", "args", "value")

    def __init__(self, function: Callable, *args) -> None:
        self.function, self.args, self.value = function, args, None

    def __call__(self) -> np.ndarray:
        if self.value is None:
            self.value = self.function(*(a() if isinstance(a, Deferred) else a
                                         for a in self.args))
            self.args = ()
        return self.value

    def __getstate__(self):
        return self.function, self.args, self.value

    def __setstate__(self, state) -> None:
        self.function, self.args, self.value = state


class _OnFirstAccess:
    """A dataclass field that accepts a :class:`Deferred` and reads as its value.

    The value lives in the instance's ``__dict__`` under the field's own name (so
    ``vars()`` and ``__dict__`` copies keep working); a :class:`Deferred` there is
    evaluated on the first read and replaced by its array. Has no default: reading it
    on the class raises AttributeError, which tells ``dataclass`` the field is required.
    """

    def __set_name__(self, owner, name: str) -> None:
        self.name = name

    def __get__(self, obj, owner=None):
        if obj is None:
            raise AttributeError(self.name)
        value = obj.__dict__[self.name]
        if isinstance(value, Deferred):
            value = value()
            obj.__dict__[self.name] = value
        return value

    def __set__(self, obj, value) -> None:
        obj.__dict__[self.name] = value


def sample_times(n_samples: int, fs: float) -> np.ndarray:
    """The output sample times ``arange(n_samples) / fs``, s (one array, not two)."""
    t = np.arange(n_samples, dtype=np.float64)
    t /= fs
    return t


def _shaft_angle(scene: Scene, t: np.ndarray) -> np.ndarray:
    """The tachometer channel at the sample times ``t`` (s): shaft angle, rad."""
    return scene.speed.shaft_angle(t, scene.duration_s)


def _rpm(scene: Scene, t: np.ndarray) -> np.ndarray:
    """The shaft speed at the sample times ``t`` (s), rpm."""
    speed = scene.speed
    if speed.is_constant:
        return np.full(t.shape, float(speed.rpm_start))
    return speed.rpm_at(t, scene.duration_s) * np.ones_like(t)


@dataclass(frozen=True)
class FaultCrossings:
    """Times at which rolling elements cross fault edges.

    Attributes
    ----------
    time_s : ndarray (n,)
        Crossing times, s, increasing.
    fault : ndarray of int (n,)
        Index into ``GroundTruth.faults``.
    element : ndarray of int (n,)
        Rolling element (for a ball defect: 0 = the defect meets the outer race,
        1 = the inner race).
    edge : ndarray of str (n,)
        ``"entry"`` / ``"exit"`` for the defect's edges, ``"ramp_end"`` /
        ``"ramp_start"`` for the ends of the half-cosine ramps inside a ramped defect.
    """

    time_s: np.ndarray
    fault: np.ndarray
    element: np.ndarray
    edge: np.ndarray = _OnFirstAccess()

    def entries(self, fault: int | None = None) -> np.ndarray:
        """Times (s) at which an element enters a defect (optionally one fault only)."""
        mask = self.edge == "entry"
        if fault is not None:
            mask &= self.fault == fault
        return self.time_s[mask]

    def __len__(self) -> int:
        return int(self.time_s.shape[0])


@dataclass(frozen=True)
class GroundTruth:
    """Exactly what the simulated bearing did.

    Attributes
    ----------
    label : str
        ``"healthy"``, ``"outer"``, ``"inner"``, ``"ball"`` or kinds joined by ``"+"``.
    faults : tuple of Fault
    frequencies : BearingFrequencies
        Defect frequencies at the mean shaft speed, Hz.
    shaft_angle : ndarray (n_samples,)
        Tachometer channel: shaft angle turned since t = 0 at each output sample, rad.
    rpm : ndarray (n_samples,)
        Instantaneous shaft speed at each output sample, rpm.
    fault_crossings : FaultCrossings
        When each fault edge was crossed.
    effective_depth_mm : tuple of float
        Depth the mating surfaces drop into each fault, mm
        (:meth:`ballpass.Fault.effective_depth_mm`): a race fault's against its own
        race; a ball fault's against the inner race, the deeper of its two strikes
        (its outer-race strike is ``fault.effective_depth_mm(bearing, "outer")``). The
        ``nabhan2020`` model reports the ball's own sagitta its paper specifies.
    contact_forces : ndarray (n_elements, n_samples) or None
        Contact load of each rolling element at each output sample, N (on request).
    element_angles : ndarray (n_elements, n_samples) or None
        Angle of each rolling element from the load line, rad, unwrapped (on request).
    displacement : ndarray (4, n_samples) or (2, n_samples) or None
        Shaft u, v and pedestal u, v displacement (sr5, sr4), or the rotor's x, y
        (rotor2), m (on request); u and x along the load line.
    outer_contact_forces : ndarray (n_elements, n_samples) or None
        Outer-race contact load of each rolling element, N (on request, from models with
        ball dynamics; it also carries the centrifugal load). None otherwise.
    gear : GearTruth or None
        The gear pair's ground truth (mesh force, stiffness, transmission error, tooth
        fault entries) for the ``gearbox`` model; None otherwise.
    """

    label: str
    faults: tuple[Fault, ...]
    frequencies: BearingFrequencies
    shaft_angle: np.ndarray = _OnFirstAccess()
    rpm: np.ndarray = _OnFirstAccess()
    fault_crossings: FaultCrossings
    effective_depth_mm: tuple[float, ...]
    contact_forces: np.ndarray | None = None
    element_angles: np.ndarray | None = None
    displacement: np.ndarray | None = None
    outer_contact_forces: np.ndarray | None = None
    gear: object | None = None

    def outer_fault_load_fraction(self, bearing) -> tuple[float, ...]:
        """How hard the loaded balls strike each outer-race fault: the largest contact
        load any element carries while over the fault, over the steady load of the most
        loaded element (the median over the run of the largest element load, which
        leaves out the impact spikes a fault itself causes), clipped to 1.

        A fault outside the load zone (12 o'clock under a radial load, 3 o'clock at
        zero clearance) is never struck by a loaded element: 0 means the signal carries
        nothing of the fault, whatever the label says. Training sets meant for real
        machines can drop or relabel such runs (``benchmarks/sim2real.py --silent``).

        Parameters
        ----------
        bearing : Bearing
            The scene's bearing (for the fault's angular width on the outer raceway,
            radius (d_p + d) / 2).

        Returns
        -------
        tuple of float
            One value in [0, 1] per fault of :attr:`faults`; NaN for inner-race and ball
            faults (they pass through the load zone every revolution).

        Raises
        ------
        ValueError
            The result was simulated without ``return_forces=True``.

        Examples
        --------
        >>> import ballpass as bp
        >>> def fraction(angle_deg):
        ...     scene = bp.Scene("6205", rpm=1797, duration_s=0.2, fs=12_000,
        ...                      resonance_hz=3_000, fault=bp.Fault("outer", angle_deg=angle_deg))
        ...     res = bp.simulate(scene, model="sr5", return_forces=True)
        ...     return res.truth.outer_fault_load_fraction(scene.bearing)[0]
        >>> fraction(0.0) > 0.8, fraction(180.0)      # 6 o'clock struck, 12 o'clock silent
        (True, 0.0)
        """
        if self.contact_forces is None or self.element_angles is None:
            raise ValueError("outer_fault_load_fraction needs the contact forces: simulate "
                             "with return_forces=True")
        steady = float(np.median(self.contact_forces.max(axis=0)))
        out = []
        for fault in self.faults:
            if fault.kind != "outer":
                out.append(float("nan"))
                continue
            half = fault.width_mm / (bearing.pitch_diameter_mm + bearing.element_diameter_mm)
            offset = np.angle(np.exp(1j * (self.element_angles - np.deg2rad(fault.angle_deg))))
            over = np.abs(offset) <= half
            struck = float(self.contact_forces[over].max()) if over.any() else 0.0
            out.append(min(1.0, struck / steady) if steady > 0.0 else 0.0)
        return tuple(out)

    @classmethod
    def of_scene(cls, scene: Scene, t: np.ndarray | Deferred, crossings: FaultCrossings,
                 effective_depth_mm: tuple[float, ...] | None = None,
                 **outputs) -> GroundTruth:
        """The ground truth every model shares, from the scene (label, faults,
        frequencies, tachometer, speed, effective depths: :func:`effective_depths_mm`
        unless a model gives its own) at sample times ``t`` (s, or a :class:`Deferred`
        of them), plus the model's crossings and optional outputs (``contact_forces``
        ...). The tachometer and the speed are computed on their first read."""
        return cls(
            label=scene.label,
            faults=scene.faults,
            frequencies=scene.frequencies,
            shaft_angle=Deferred(_shaft_angle, scene, t),
            rpm=Deferred(_rpm, scene, t),
            fault_crossings=crossings,
            effective_depth_mm=(effective_depths_mm(scene) if effective_depth_mm is None
                                else effective_depth_mm),
            **outputs,
        )


def effective_depths_mm(scene: Scene) -> tuple[float, ...]:
    """:attr:`GroundTruth.effective_depth_mm` of ``scene``'s faults, mm: a race fault's
    drop against its own race, a ball fault's against the inner race (the deeper of
    its two strikes).

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.simulate.result import effective_depths_mm
    >>> ball = bp.Fault("ball", width_mm=0.53, depth_mm=0.2)
    >>> scene = bp.Scene("6205", fault=ball)
    >>> effective_depths_mm(scene) == (ball.effective_depth_mm(scene.bearing, "inner"),)
    True
    """
    return tuple(f.effective_depth_mm(scene.bearing, "inner" if f.kind == "ball" else None)
                 for f in scene.faults)


@dataclass(frozen=True)
class SimulationResult:
    """Signals of one simulated scene plus its ground truth.

    Attributes
    ----------
    accel : ndarray
        Acceleration at the sensors, m/s^2: shape (n_samples,) for one sensor,
        (n_sensors, n_samples) for several, in the order of ``scene.sensors``.
    fs : float
        Sampling rate, Hz.
    t : ndarray (n_samples,)
        Sample times, s.
    scene : Scene
    sensor_names : tuple of str
    truth : GroundTruth
    info : dict
        ``model``, ``solver``, ``n_steps`` (accepted), ``n_rejected``, ``dt_s`` (fixed
        step) or ``dt_min_s`` (adaptive), ``rtol``, ``internal_fs`` (Hz), ``wall_time_s``,
        ``n_events``. sr5/sr4 also report ``compile_time_s``: the time the first call in a
        process spent compiling (or loading from numba's cache) the integrator, s, 0.0
        afterwards; ``wall_time_s`` and ``integration_time_s`` leave it out. With the EHL
        film (a scene that needs ``"ehl_film"``) they report ``ehl_film_m``, the film
        h_i + h_o added to every contact approach, m.

    Examples
    --------
    >>> import ballpass as bp
    >>> scene = bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.1,
    ...                  fs=48_000, sensors=("loaded", "unloaded"), seed=0)
    >>> res = bp.simulate(scene, model="impulse")
    >>> res.accel.shape, res.fs, res.sensor_names
    ((2, 4800), 48000.0, ('loaded', 'unloaded'))
    >>> res.info["model"]
    'impulse'
    """

    accel: np.ndarray
    fs: float
    t: np.ndarray = _OnFirstAccess()
    scene: Scene
    sensor_names: tuple[str, ...]
    truth: GroundTruth
    info: dict = field(default_factory=dict)

    @classmethod
    def of_scene(cls, scene: Scene, accel: np.ndarray, t: np.ndarray | Deferred,
                 truth: GroundTruth, info: dict) -> SimulationResult:
        """The result every model returns: ``accel`` of shape (n_sensors, n_samples),
        m/s^2, kept 2-D for several sensors and reduced to (n_samples,) for one, with
        the scene's rate and sensor names, sample times ``t`` (s, or a
        :class:`Deferred` of them), the ground truth and the model's ``info``."""
        return cls(accel=accel[0] if len(scene.sensors) == 1 else accel, fs=scene.fs, t=t,
                   scene=scene, sensor_names=tuple(s.name for s in scene.sensors),
                   truth=truth, info=info)

    @property
    def velocity(self) -> np.ndarray:
        """Velocity at the sensors, m/s, shape of ``accel``: what the electrodynamic
        velocity pick-up of a factory's end-of-line bearing test reads (Wrzochal &
        Adamczak).

        The antiderivative of ``accel`` on the record, taken in the frequency domain:
        V(f) = A(f) / (i 2 pi f) for 0 < f < fs/2, with no DC (the sensors are
        AC-coupled: ``accel`` has zero mean, so its integral returns to its start and the
        record holds a whole period of it) and no Nyquist line (whose derivative a
        sampled signal cannot carry). Exact for every line of the record, so unlike a
        cumulative sum it neither drifts nor bends the resonance (a trapezoidal sum
        attenuates 15 kHz at 48 kHz sampling by a third). Noise added by ``snr_db`` or
        ``noise_rms`` is integrated with the signal, as by an integrating accelerometer.

        Examples
        --------
        >>> import numpy as np
        >>> import ballpass as bp
        >>> res = bp.simulate(bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"),
        ...                            duration_s=0.1), model="impulse")
        >>> v = res.velocity
        >>> v.shape == res.accel.shape, bool(abs(v.mean()) < 1e-12)
        (True, True)
        """
        accel = np.asarray(self.accel, dtype=np.float64)
        n = accel.shape[-1]
        spectrum = np.fft.rfft(accel, axis=-1)
        omega = 2.0 * np.pi * np.fft.rfftfreq(n, d=1.0 / self.fs)
        keep = omega > 0.0
        if n % 2 == 0:
            keep[-1] = False  # the Nyquist line
        spectrum[..., ~keep] = 0.0
        spectrum[..., keep] /= 1j * omega[keep]
        return np.fft.irfft(spectrum, n=n, axis=-1)

    def channel(self, name: str) -> np.ndarray:
        """The signal of one sensor by name, (n_samples,), m/s^2.

        Examples
        --------
        >>> import ballpass as bp
        >>> scene = bp.Scene("6205", rpm=1797, duration_s=0.1, sensors=("loaded", "unloaded"))
        >>> res = bp.simulate(scene, model="impulse")
        >>> res.channel("unloaded").shape
        (4800,)
        """
        if name not in self.sensor_names:
            raise ValueError(f"sensor must be one of {self.sensor_names}, got {name!r}")
        data = np.atleast_2d(self.accel)
        return data[self.sensor_names.index(name)]
