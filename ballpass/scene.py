"""What to simulate: a bearing, an operating point, faults, sensors. Validated and frozen.

All classes are frozen dataclasses. They take the units engineers quote where the
argument name says so (``rpm``, ``*_mm``, ``*_deg``, ``*_hz``) and are validated on
construction: bad input raises ``ValueError``/``TypeError`` naming the argument, the
value and the allowed range, before any simulation work starts.

Angle convention (everywhere in ballpass): degrees in the bearing plane, measured from
the load line (0 deg = centre of the load zone), positive in the direction of shaft
rotation. An outer-race fault at 0 deg sits where the load is; a sensor at 180 deg is in
the unloaded zone. Angles are wrapped to [0, 360) on construction, so 359.9 and -0.1
are the same angle.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

from ._validation import check_number as _number
from .bearing import Bearing, BearingFrequencies
from .phenomena import check_needs

__all__ = ["Fault", "Sensor", "SpeedProfile", "Scene", "wrap_deg"]

FAULT_KINDS = ("outer", "inner", "ball")
EDGE_PROFILES = ("ramped", "sharp")
STANDARD_GRAVITY = 9.80665  # m/s^2
#: Lowest structural resonance accepted, Hz. The resonances that bearing impacts excite
#: and envelope analysis demodulates lie at kHz (Randall & Antoni, MSSP 25 (2011)
#: 485-520, sec. 3); below 100 Hz a "resonance" sits among the shaft harmonics and the
#: fault frequencies themselves, and carries no envelope.
MIN_RESONANCE_HZ = 100.0


def wrap_deg(angle: float) -> float:
    """Wrap an angle in degrees to [0, 360)."""
    wrapped = math.fmod(angle, 360.0)
    if wrapped < 0.0:
        wrapped += 360.0
    return 0.0 if wrapped == 360.0 else wrapped


@dataclass(frozen=True)
class Fault:
    """A localized defect (spall, EDM notch) on one of the bearing's surfaces.

    Parameters
    ----------
    kind : {"outer", "inner", "ball"}
        Outer race (fixed), inner race (rotates with the shaft) or one rolling element
        (spins at BSF and strikes the inner and outer race alternately).
    width_mm : float, optional
        Extent of the defect in the rolling direction, mm (default 0.5). Must be smaller
        than the element spacing on the pitch circle (races) or the element diameter
        (ball); checked by :class:`Scene`, which knows the bearing.
    depth_mm : float, optional
        Depth of the defect, mm, > 0 (default 0.1). A rolling element cannot reach the
        bottom of a defect narrower than itself: the simulator uses
        ``min(depth, d/2 (1 - sqrt(1 - (w/d)^2)))`` for ``w < d`` (seed 001 eq. 26 with the
        ball diameter d, not the printed pitch diameter).
    angle_deg : float, optional
        Outer race: position of the defect centre. Inner race: position of the defect
        centre at t = 0 (it then turns with the shaft). Ball: spin phase of the defect at
        t = 0 (0 = facing the outer race). Degrees, wrapped to [0, 360). Default 0.
    element : int, optional
        Index of the rolling element that carries a ball defect (0-based). Default 0.
    edge : {"ramped", "sharp"}, optional
        Depth profile across the defect. ``"ramped"`` (default) lets the depth rise and
        fall as half-cosine ramps over ``ramp_fraction`` of the defect's angular extent at
        entry and exit, the shape of public Sawalhi-Randall implementations; ``"sharp"``
        is the rectangular notch of seed 004 eq. (15).
    ramp_fraction : float, optional
        Fraction lambda of the angular extent taken by each ramp, in (0, 0.5]. Default 0.2.

    Examples
    --------
    >>> from ballpass import Fault
    >>> Fault("outer", width_mm=0.53, depth_mm=0.1, angle_deg=-0.1).angle_deg
    359.9
    """

    kind: str
    width_mm: float = 0.5
    depth_mm: float = 0.1
    angle_deg: float = 0.0
    element: int = 0
    edge: str = "ramped"
    ramp_fraction: float = 0.2

    def __post_init__(self) -> None:
        if self.kind not in FAULT_KINDS:
            raise ValueError(f"fault kind must be one of {FAULT_KINDS}, got {self.kind!r}")
        object.__setattr__(self, "width_mm", _number("width_mm", self.width_mm, 0.0, 50.0,
                                                     lo_open=True))
        object.__setattr__(self, "depth_mm", _number("depth_mm", self.depth_mm, 0.0, 50.0,
                                                     lo_open=True))
        angle = _number("angle_deg", self.angle_deg, -1e6, 1e6)
        object.__setattr__(self, "angle_deg", wrap_deg(angle))
        if isinstance(self.element, bool) or not isinstance(self.element, int):
            raise TypeError(f"element must be an int, got {type(self.element).__name__}")
        if self.element < 0:
            raise ValueError(f"element must be >= 0, got {self.element}")
        if self.edge not in EDGE_PROFILES:
            raise ValueError(f"edge must be one of {EDGE_PROFILES}, got {self.edge!r}")
        object.__setattr__(self, "ramp_fraction",
                           _number("ramp_fraction", self.ramp_fraction, 0.0, 0.5, lo_open=True))

    def check_fits(self, bearing: Bearing) -> None:
        """Raise ``ValueError`` if the defect does not fit on ``bearing``."""
        if self.kind == "ball":
            limit = bearing.element_diameter_mm
            if self.width_mm >= limit:
                raise ValueError(
                    f"ball fault width_mm must be < the element diameter {limit:g} mm, "
                    f"got {self.width_mm!r}"
                )
            if self.element >= bearing.n_elements:
                raise ValueError(
                    f"fault element must be in [0, {bearing.n_elements - 1}] for a bearing "
                    f"with {bearing.n_elements} elements, got {self.element}"
                )
        else:
            spacing = math.pi * bearing.pitch_diameter_mm / bearing.n_elements
            if self.width_mm >= spacing:
                raise ValueError(
                    f"{self.kind}-race fault width_mm must be < the element spacing on the "
                    f"pitch circle, pi*d_p/Z = {spacing:.3f} mm, got {self.width_mm!r}"
                )
        if self.depth_mm >= bearing.element_diameter_mm:
            raise ValueError(
                f"depth_mm must be < the element diameter {bearing.element_diameter_mm:g} mm, "
                f"got {self.depth_mm!r}"
            )

    def effective_depth_mm(self, bearing: Bearing) -> float:
        """Depth the rolling element can actually drop into the defect, mm.

        ``min(h, d/2 (1 - sqrt(1 - (w/d)^2)))`` for a defect narrower than the element
        diameter d; a defect at least as wide as the element lets it reach depth h
        (seed 001 eq. 26, with d_b in place of the printed d_p).
        """
        d = bearing.element_diameter_mm
        w = self.width_mm
        if w >= d:
            return self.depth_mm
        drop = 0.5 * d * (1.0 - math.sqrt(1.0 - (w / d) ** 2))
        return min(self.depth_mm, drop)


_SENSOR_NAMES = {"loaded": 0.0, "unloaded": 180.0}


@dataclass(frozen=True)
class Sensor:
    """An accelerometer on the bearing housing, measuring radially.

    Each sensor sees the contact forces through its own transfer path: the force of a
    contact at angle phi is attenuated by the transmission factor
    ``exp(-attenuation * (1 - cos(phi - angle)))`` — 1 at the sensor, decaying smoothly
    with the angular distance round the ring to ``exp(-2 attenuation)`` opposite it
    (after McFadden & Smith's transmission factor) — and then filtered by the
    structure's resonance (``Scene.resonance_hz``).

    Parameters
    ----------
    angle_deg : float, optional
        Position on the housing, degrees from the load line (0 = loaded zone, 180 =
        unloaded zone). Default 0.
    name : str, optional
        Channel name; defaults to ``"loaded"`` at 0 deg, ``"unloaded"`` at 180 deg, else
        ``"sensor_<angle>deg"``.
    attenuation : float, optional
        kappa of the transmission factor, dimensionless, in [0, 10]. Default 0.8: a
        contact 90 deg away reaches the sensor at 45 % amplitude, one opposite it at
        exp(-1.6) = 20 % (-13.9 dB). 0 makes every sensor see the pedestal motion.

    Examples
    --------
    >>> from ballpass import Sensor
    >>> Sensor.named("unloaded").angle_deg
    180.0
    """

    angle_deg: float = 0.0
    name: str | None = None
    attenuation: float = 0.8

    def __post_init__(self) -> None:
        angle = _number("sensor angle_deg", self.angle_deg, -1e6, 1e6)
        object.__setattr__(self, "angle_deg", wrap_deg(angle))
        object.__setattr__(self, "attenuation",
                           _number("attenuation", self.attenuation, 0.0, 10.0))
        if self.name is None:
            default = {0.0: "loaded", 180.0: "unloaded"}.get(self.angle_deg)
            object.__setattr__(self, "name", default or f"sensor_{self.angle_deg:g}deg")
        elif not isinstance(self.name, str) or not self.name:
            raise TypeError(f"sensor name must be a non-empty str, got {self.name!r}")

    @classmethod
    def named(cls, name: str) -> Sensor:
        """``"loaded"`` (0 deg) or ``"unloaded"`` (180 deg)."""
        if name not in _SENSOR_NAMES:
            raise ValueError(f"sensor name must be one of {sorted(_SENSOR_NAMES)}, got {name!r}")
        return cls(angle_deg=_SENSOR_NAMES[name], name=name)


@dataclass(frozen=True)
class SpeedProfile:
    """Shaft speed over time: constant, or a linear run-up / run-down.

    Parameters
    ----------
    rpm_start : float
        Speed at t = 0, rpm, in (0, 100000].
    rpm_end : float, optional
        Speed at t = ``duration_s`` of the scene, rpm; equal to ``rpm_start`` (default)
        for constant speed.

    Examples
    --------
    >>> from ballpass import SpeedProfile
    >>> p = SpeedProfile(600.0, 1200.0)
    >>> p.rpm_at(0.5, duration_s=1.0)
    900.0
    """

    rpm_start: float
    rpm_end: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "rpm_start",
                           _number("rpm", self.rpm_start, 0.0, 1e5, lo_open=True))
        end = self.rpm_start if self.rpm_end is None else self.rpm_end
        object.__setattr__(self, "rpm_end", _number("rpm_end", end, 0.0, 1e5, lo_open=True))

    @property
    def is_constant(self) -> bool:
        """True when the speed does not change."""
        return self.rpm_start == self.rpm_end

    @property
    def mean_rpm(self) -> float:
        """Time-averaged speed, rpm."""
        return 0.5 * (self.rpm_start + self.rpm_end)

    def rpm_at(self, t, duration_s: float):
        """Speed at time(s) ``t`` (s) of a scene lasting ``duration_s``, rpm."""
        return self.rpm_start + (self.rpm_end - self.rpm_start) * (t / duration_s)

    def shaft_angle(self, t, duration_s: float):
        """Shaft angle turned since t = 0, rad: the integral of 2 pi rpm/60 dt."""
        w0 = self.rpm_start * math.pi / 30.0
        w1 = self.rpm_end * math.pi / 30.0
        return w0 * t + 0.5 * (w1 - w0) * t * t / duration_s


@dataclass(frozen=True)
class Scene:
    """One simulation request: bearing, operating point, faults, sensors, output.

    Parameters
    ----------
    bearing : Bearing or str
        A :class:`~ballpass.Bearing` or a catalogue designation such as ``"6205"``.
    rpm : float or SpeedProfile or (float, float)
        Shaft speed, rpm: a constant, a :class:`SpeedProfile`, or ``(start, end)`` for a
        linear ramp over the scene. In (0, 100000].
    radial_load_n : float, optional
        Radial load on the shaft along the load line, N, in [0, 1e6]. Default 500.
    fault : Fault or sequence of Fault or None, optional
        The defect(s); ``None`` (default) is a healthy bearing.
    duration_s : float, optional
        Length of the output signal, s, in (0, 3600]. Default 1.
    fs : float, optional
        Output sampling rate, Hz, in [1000, 1e6]. Default 48000.
    seed : int, optional
        Seed of every random choice in the scene (slip, noise). Default 0.
    slip : float, optional
        Standard deviation of the inter-impact period as a fraction of the nominal
        period, from random rolling-element slip (Randall & Antoni 2011), in [0, 0.1].
        The cage keeps its mean speed. Default 0.01.
    resonance_hz : float, optional
        Frequency of the structure's high-frequency resonance seen by the sensors, Hz.
        In [100, 0.45 * fs] (see :data:`MIN_RESONANCE_HZ`). Default 15000 (Sawalhi &
        Randall).
    resonance_damping : float, optional
        Damping ratio of that resonance, in (0, 1). Default 0.05.
    sensors : sequence of Sensor or str, optional
        Housing accelerometers; strings ``"loaded"``/``"unloaded"`` are accepted.
        Default: one sensor in the loaded zone.
    snr_db : float, optional
        Add white Gaussian measurement noise at this signal-to-noise ratio, dB, relative
        to the RMS of the noise-free signal at each sensor. Exclusive with ``noise_rms``.
    noise_rms : float, optional
        Add white Gaussian noise of this absolute RMS, m/s^2 (the same for a healthy and a
        faulty run). Exclusive with ``snr_db``.
    gravity : bool, optional
        Add the weight of shaft and pedestal along the load line (g = 9.80665 m/s^2).
        Default True.
    needs : sequence of str, optional
        Phenomena the simulation must represent, beyond what the other fields already
        say (names in :data:`ballpass.phenomena.PHENOMENA`); ``model="auto"`` runs the
        cheapest model that covers them. Empty (default) asks for ``envelope`` and
        ``contact_dynamics``; ``("envelope",)`` asks for the envelope-level signature
        only (the cheap ``impulse`` model). See :func:`ballpass.simulate.scene_needs`.

    Examples
    --------
    >>> import ballpass as bp
    >>> s = bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault("inner"), fs=48_000)
    >>> round(s.frequencies.bpfi, 2)
    162.19
    """

    bearing: Bearing | str
    rpm: float | SpeedProfile | tuple = 1797.0
    radial_load_n: float = 500.0
    fault: Fault | Sequence[Fault] | None = None
    duration_s: float = 1.0
    fs: float = 48_000.0
    seed: int = 0
    slip: float = 0.01
    resonance_hz: float = 15_000.0
    resonance_damping: float = 0.05
    sensors: tuple = field(default=(Sensor(),))
    snr_db: float | None = None
    noise_rms: float | None = None
    gravity: bool = True
    needs: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        bearing = self.bearing
        if isinstance(bearing, str):
            bearing = Bearing.catalog(bearing)
        elif not isinstance(bearing, Bearing):
            raise TypeError(f"bearing must be a Bearing or a catalogue name, got {bearing!r}")
        object.__setattr__(self, "bearing", bearing)

        rpm = self.rpm
        if isinstance(rpm, SpeedProfile):
            pass
        elif isinstance(rpm, (tuple, list)):
            if len(rpm) != 2:
                raise ValueError(f"rpm as a ramp must be (start, end), got {rpm!r}")
            rpm = SpeedProfile(rpm[0], rpm[1])
        else:
            rpm = _number("rpm", rpm, 0.0, 1e5, lo_open=True)
        object.__setattr__(self, "rpm", rpm)

        object.__setattr__(self, "radial_load_n",
                           _number("radial_load_n", self.radial_load_n, 0.0, 1e6))
        object.__setattr__(self, "duration_s",
                           _number("duration_s", self.duration_s, 0.0, 3600.0, lo_open=True))
        object.__setattr__(self, "fs", _number("fs", self.fs, 1000.0, 1e6))
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise ValueError(f"seed must be an int >= 0, got {self.seed!r}")
        object.__setattr__(self, "slip", _number("slip", self.slip, 0.0, 0.1))
        object.__setattr__(self, "resonance_hz", _number("resonance_hz", self.resonance_hz,
                                                         MIN_RESONANCE_HZ, 1e6))
        if self.resonance_hz > 0.45 * self.fs:
            raise ValueError(
                f"resonance_hz={self.resonance_hz:g} lies above 0.45*fs = {0.45 * self.fs:g} Hz: "
                "the fault impacts would vanish from the sampled signal. Lower resonance_hz "
                f"(the CWRU drive-end rig rings at about 2.5-4 kHz) or raise fs to at least "
                f"{self.resonance_hz / 0.45:.0f} Hz."
            )
        object.__setattr__(self, "resonance_damping",
                           _number("resonance_damping", self.resonance_damping, 0.0, 1.0,
                                   lo_open=True, hi_open=True))

        faults = self.fault
        if faults is None:
            faults_t: tuple[Fault, ...] = ()
        elif isinstance(faults, Fault):
            faults_t = (faults,)
        elif isinstance(faults, Sequence) and not isinstance(faults, str):
            faults_t = tuple(faults)
            for f in faults_t:
                if not isinstance(f, Fault):
                    raise TypeError(
                        f"fault must be a Fault, a sequence of Faults or None, got {f!r}")
        else:
            raise TypeError(f"fault must be a Fault, a sequence of Faults or None, got {faults!r}")
        for f in faults_t:
            f.check_fits(bearing)
        object.__setattr__(self, "fault", faults_t[0] if len(faults_t) == 1 else
                           (None if not faults_t else faults_t))

        sensors = self.sensors
        if isinstance(sensors, (Sensor, str)):
            sensors = (sensors,)
        sensors_t = tuple(Sensor.named(s) if isinstance(s, str) else s for s in sensors)
        if not sensors_t:
            raise ValueError("sensors must name at least one sensor")
        for s in sensors_t:
            if not isinstance(s, Sensor):
                raise TypeError(f"sensors must be Sensor objects or names, got {s!r}")
        names = [s.name for s in sensors_t]
        if len(set(names)) != len(names):
            raise ValueError(f"sensor names must be unique, got {names}")
        object.__setattr__(self, "sensors", sensors_t)

        if self.snr_db is not None and self.noise_rms is not None:
            raise ValueError("give snr_db or noise_rms, not both")
        if self.snr_db is not None:
            object.__setattr__(self, "snr_db", _number("snr_db", self.snr_db, -60.0, 200.0))
        if self.noise_rms is not None:
            object.__setattr__(self, "noise_rms",
                               _number("noise_rms", self.noise_rms, 0.0, 1e6))
        if not isinstance(self.gravity, bool):
            raise TypeError(f"gravity must be a bool, got {self.gravity!r}")
        if self.radial_load_n == 0 and not self.gravity:
            raise ValueError("radial_load_n=0 with gravity=False leaves the bearing without "
                             "any load: no load zone and no static equilibrium. Give a "
                             "radial_load_n > 0 N or keep gravity=True")
        object.__setattr__(self, "needs", tuple(sorted(check_needs(self.needs))))

    # ------------------------------------------------------------------ derived
    @property
    def faults(self) -> tuple[Fault, ...]:
        """The faults as a tuple (empty for a healthy bearing)."""
        if self.fault is None:
            return ()
        if isinstance(self.fault, Fault):
            return (self.fault,)
        return tuple(self.fault)

    @property
    def speed(self) -> SpeedProfile:
        """The speed as a :class:`SpeedProfile` (constant when ``rpm`` is a number)."""
        return self.rpm if isinstance(self.rpm, SpeedProfile) else SpeedProfile(self.rpm)

    @property
    def shaft_hz(self) -> float:
        """Mean shaft frequency, Hz."""
        return self.speed.mean_rpm / 60.0

    @property
    def frequencies(self) -> BearingFrequencies:
        """Defect frequencies at the mean shaft speed, Hz."""
        return self.bearing.frequencies(self.shaft_hz)

    @property
    def demodulation_band(self) -> tuple[float, float]:
        """Band around the structural resonance for envelope analysis, Hz:
        ``resonance_hz`` +- max(20 %, 500 Hz), kept inside (1 Hz, 0.49 fs)."""
        half = max(0.2 * self.resonance_hz, 500.0)
        return (max(self.resonance_hz - half, 1.0), min(self.resonance_hz + half, 0.49 * self.fs))

    @property
    def label(self) -> str:
        """``"healthy"``, a fault kind, or kinds joined by ``"+"`` for several faults."""
        kinds = [f.kind for f in self.faults]
        return "+".join(dict.fromkeys(kinds)) if kinds else "healthy"

    @property
    def n_samples(self) -> int:
        """Number of output samples, ``round(duration_s * fs)``."""
        return max(1, int(round(self.duration_s * self.fs)))

    def replace(self, **changes) -> Scene:
        """Return a validated copy with some fields changed."""
        return replace(self, **changes)
