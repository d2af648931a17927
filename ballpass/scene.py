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

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

from . import _resources
from ._validation import check_number as _number
from .bearing import Bearing, BearingFrequencies
from .gears import GearPair
from .phenomena import check_needs
from .waviness import Waviness

__all__ = ["Fault", "Sensor", "SpeedProfile", "Scene", "wrap_deg"]

FAULT_KINDS = ("outer", "inner", "ball")
EDGE_PROFILES = ("ramped", "sharp", "blunt")
FAULT_GEOMETRIES = ("groove", "pit")
STANDARD_GRAVITY = 9.80665  # m/s^2
#: scenes needing less memory than this (bytes) skip the free-memory check
_MEMORY_CHECK_BYTES = 256 * 2**20
#: Lowest structural resonance accepted, Hz. The resonances that bearing impacts excite
#: and envelope analysis demodulates lie at kHz (Randall & Antoni, MSSP 25 (2011)
#: 485-520, sec. 3); below 100 Hz a "resonance" sits among the shaft harmonics and the
#: fault frequencies themselves, and carries no envelope.
MIN_RESONANCE_HZ = 100.0
#: most localized faults one scene may hold: the simulators test every element against
#: every fault at every step, so the cost grows with their number (1000 faults cost
#: about as much as the rest of a 12 kHz scene); damage spread over a race is waviness
MAX_FAULTS = 1000


def _sagitta(radius: float, half_chord: float) -> float:
    """Sagitta of a circle of ``radius`` over a chord of half length ``half_chord``
    (same unit, ``half_chord < radius``), computed without cancellation:
    R - sqrt(R^2 - a^2) = a^2 / (R + sqrt(R^2 - a^2))."""
    return half_chord**2 / (radius + math.sqrt(radius**2 - half_chord**2))


def wrap_deg(angle: float) -> float:
    """Wrap an angle in degrees to [0, 360).

    Examples
    --------
    >>> from ballpass.scene import wrap_deg
    >>> wrap_deg(-90.0), wrap_deg(725.0)
    (270.0, 5.0)
    """
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
        bottom of a defect narrower than itself: the simulators use the drop of the
        mating surfaces over the width, set by their relative curvature
        (:meth:`effective_depth_mm`; a ball defect strikes the inner race deeper than
        the outer), at most this depth.
    angle_deg : float, optional
        Outer race: position of the defect centre. Inner race: position of the defect
        centre at t = 0 (it then turns with the shaft). Ball: spin phase of the defect at
        t = 0 (0 = facing the outer race). Degrees, wrapped to [0, 360). Default 0.
    element : int, optional
        Index of the rolling element that carries a ball defect (0-based). Default 0.
    edge : {"ramped", "sharp", "blunt"}, optional
        Depth profile across the defect. ``"ramped"`` (default) lets the depth rise and
        fall as half-cosine ramps over ``ramp_fraction`` of the defect's angular extent at
        entry and exit, the shape of public Sawalhi-Randall implementations; ``"sharp"``
        is the rectangular notch of Tran, Furch & Cu eq. (15); ``"blunt"`` is a notch whose edges
        repeated impacts have cut flat (Liu & Shao 2014, Wrzochal & Adamczak's review section 4.2):
        the ball
        rolls on the flat cut, so its centre drops *linearly* over ``ramp_fraction`` of
        the extent and meets the far edge's cut at the angle atan(depth / cut length)
        instead of a vertical wall. (Liu & Shao's explicit forms H_1-H_4 were not at
        hand; this is their ball-on-plane segment, with the depth limited by
        the drop of the mating surfaces, :meth:`effective_depth_mm`, as for every
        profile.)
    ramp_fraction : float, optional
        Fraction lambda of the angular extent taken by each ramp (or flat cut), in
        (0, 0.5]. Default 0.2.
    geometry : {"groove", "pit"}, optional
        ``"groove"`` (default, Sawalhi & Randall): the defect spans the whole contact
        across the track, so an element inside it drops by the effective depth and
        unloads completely. ``"pit"``: a round pit of diameter ``width_mm``, like the
        EDM faults of the CWRU rig, which removes only the strip of the Hertz contact
        ellipse it spans across the track; see :meth:`pit_unloading`.
    engagement : float, optional
        Ball defects only: probability, in (0, 1], that the defect lies on the rolling
        band during one spin revolution of the ball. A real ball's spin axis wanders,
        so a defect on it meets the races only intermittently (the reason Smith &
        Randall 2015 find few CWRU ball faults diagnosable); revolutions are drawn
        independently from the scene's seed. Default 1 (every revolution, as in
        Sawalhi & Randall).
    spin_drift_deg : float, optional
        Ball defects only: how far the ball's spin axis wanders, D in [0, 90] degrees.
        A ball turns in three dimensions, so the defect strikes the races with a size
        that changes from one revolution to the next, and on some not at all
        (Nakhaeinejad & Bryant 2011 on why ball-fault harmonics are clear in simulation
        but not in measurement; Smith & Randall 2015 on the CWRU ball faults). Per spin
        revolution the defect's latitude lambda off the rolling band is drawn with
        sin(lambda) uniform on [-sin D, sin D]; a round pit of diameter ``width_mm``
        then unloads the strip of the Hertz contact it covers, and it strikes on a
        share min(1, (w/2 + a) / (R sin D)) of the revolutions (R the ball radius, a
        the semi-axis across the track of the contact ellipse on the race it meets,
        the inner race's the wider; one latitude per revolution for both races).
        Default 0: the axis is
        fixed and the defect strikes on every revolution it is engaged. 90 is a ball
        turning every way.

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
    geometry: str = "groove"
    engagement: float = 1.0
    spin_drift_deg: float = 0.0

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
        if self.geometry not in FAULT_GEOMETRIES:
            raise ValueError(f"geometry must be one of {FAULT_GEOMETRIES}, got {self.geometry!r}")
        object.__setattr__(self, "engagement",
                           _number("engagement", self.engagement, 0.0, 1.0, lo_open=True))
        if self.engagement < 1.0 and self.kind != "ball":
            raise ValueError(f"engagement < 1 applies to ball defects only, got "
                             f"engagement={self.engagement!r} for a {self.kind}-race fault")
        object.__setattr__(self, "spin_drift_deg",
                           _number("spin_drift_deg", self.spin_drift_deg, 0.0, 90.0))
        if self.spin_drift_deg > 0.0 and self.kind != "ball":
            raise ValueError(f"spin_drift_deg > 0 applies to ball defects only, got "
                             f"spin_drift_deg={self.spin_drift_deg!r} for a {self.kind}-race "
                             f"fault")

    def check_fits(self, bearing: Bearing) -> None:
        """Raise ``ValueError`` if the defect does not fit on ``bearing``.

        Examples
        --------
        >>> import ballpass as bp
        >>> b = bp.Bearing.catalog("6205")
        >>> bp.Fault("outer", width_mm=1.0).check_fits(b)          # fits: returns None
        >>> bp.Fault("outer", width_mm=50.0).check_fits(b)   # doctest: +ELLIPSIS
        Traceback (most recent call last):
            ...
        ValueError: outer-race fault width_mm must be < the element spacing ... got 50.0
        """
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
            if self.element != 0:
                raise ValueError(
                    f"fault element={self.element} picks the rolling element of a ball "
                    f"fault; a {self.kind}-race fault has none (leave element at 0)")
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

    def effective_depth_mm(self, bearing: Bearing, race: str | None = None) -> float:
        """Depth the mating surfaces drop into the defect, mm.

        A notch of width w across the track (rolling direction w, half width a = w/2)
        is bridged by the two surfaces in contact: the intact one rests on the notch's
        corners and approaches the defective one by the sagittas of both circles over
        the chord 2a in the rolling plane,

            drop = s(R_b) + s(R_i)  (ball on the convex inner race),
            drop = s(R_b) - s(R_o)  (ball in the concave outer race),

        s(R) = R - sqrt(R^2 - a^2), with R_b = d/2 and the raceway radii
        R_i = (d_p - d)/2, R_o = (d_p + d)/2; the depth used is min(h, drop), and h
        itself for a notch at least as wide as the element (w >= d). To first order
        drop = a^2 / (2 r) with the relative radius r = 1 / (1/R_b +- 1/R_race) of the
        pair (r - sqrt(r^2 - a^2) differs by less than 0.1 % for w < 0.6 mm on a
        6205), the geometry of the multibody model (Nakhaeinejad & Bryant (2011)).
        The notch is the same whether it is cut in the race or in the ball, so a
        race fault drops against its own race and a ball fault by the race it
        strikes: on a 6205 the inner race takes 1.26x the ball's own sagitta, the outer
        race 0.83x, and a ball defect strikes the inner race 1.5x deeper than the outer.

        Assumptions: a notch across the whole track (``geometry="groove"``), rigid
        surfaces, curvature in the rolling plane only (the curvature across the track
        does not enter a notch that spans it). A round ``geometry="pit"`` keeps its
        own, shallower equivalent depth (:meth:`pit_unloading`), of which this is the
        upper bound. Nabhan & Rashed (2020) eq. 26 (the ball's sagitta alone) is what
        their model specifies: ``ballpass.simulate.nabhan2020`` keeps it.

        Parameters
        ----------
        bearing : Bearing
        race : {"inner", "outer"} or None
            The race the defect's drop is taken against. A race fault drops against
            its own race: None or its own kind. A ball fault strikes both races, each
            to its own depth: required.

        Returns
        -------
        float
            min(h, drop), mm.

        Examples
        --------
        >>> import ballpass as bp
        >>> b = bp.Bearing.catalog("6205")                # d = 7.94 mm, d_p = 39.04 mm
        >>> round(bp.Fault("inner", width_mm=0.53, depth_mm=0.2).effective_depth_mm(b), 5)
        0.01111
        >>> round(bp.Fault("outer", width_mm=0.53, depth_mm=0.2).effective_depth_mm(b), 5)
        0.00736
        >>> ball = bp.Fault("ball", width_mm=0.53, depth_mm=0.2)
        >>> round(ball.effective_depth_mm(b, race="inner") / ball.effective_depth_mm(b, "outer"), 3)
        1.51
        >>> bp.Fault("outer", width_mm=10.0, depth_mm=0.2).effective_depth_mm(b)
        0.2
        """
        if self.kind == "ball":
            if race not in ("inner", "outer"):
                raise ValueError(f"race must be 'inner' or 'outer' for a ball fault (it strikes "
                                 f"both races, each to its own depth), got {race!r}")
        elif race not in (None, self.kind):
            raise ValueError(f"race must be None or {self.kind!r} for an {self.kind}-race "
                             f"fault (it drops against its own race), got {race!r}")
        race = race or self.kind
        a = 0.5 * self.width_mm
        r_ball = 0.5 * bearing.element_diameter_mm
        if a >= r_ball:
            return self.depth_mm
        if race == "inner":
            drop = _sagitta(r_ball, a) + _sagitta(bearing.inner_race_radius_m * 1e3, a)
        else:
            drop = _sagitta(r_ball, a) - _sagitta(bearing.outer_race_radius_m * 1e3, a)
        return min(self.depth_mm, drop)

    def pit_unloading(self, ellipse_half_width_mm: float) -> float:
        """Share of a contact's load that a round pit removes when the contact sits on it.

        A pit of diameter w centred under a Hertz contact ellipse of semi-axis a across
        the track removes the strip ``abs(x) < w/2`` of the patch (it covers the short axis of
        the ellipse, 2b ~ 0.2-0.5 mm, from w ~ 2b on). The Hertz pressure
        p0 sqrt(1 - x^2/a^2 - y^2/b^2) integrated over y gives a load density
        proportional to 1 - x^2/a^2 across the track (Johnson, *Contact Mechanics*,
        1985, sec. 4.2), so the strip carries the share (3 s - s^3) / 2 of the load,
        s = min(1, w / 2a). A pit as wide as the ellipse unloads the contact fully.

        Parameters
        ----------
        ellipse_half_width_mm : float
            Semi-axis a of the contact ellipse across the track, mm, > 0.

        Returns
        -------
        float
            Load share in [0, 1].

        Examples
        --------
        >>> from ballpass import Fault
        >>> round(Fault("outer", width_mm=0.5, geometry="pit").pit_unloading(1.0), 4)
        0.3672
        """
        a = _number("ellipse_half_width_mm", ellipse_half_width_mm, 0.0, lo_open=True)
        s = min(1.0, self.width_mm / (2.0 * a))
        return 0.5 * (3.0 * s - s**3)


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
        """Speed at time(s) ``t`` (s) of a scene lasting ``duration_s``, rpm.

        Examples
        --------
        >>> from ballpass import SpeedProfile
        >>> SpeedProfile(600.0, 1200.0).rpm_at(0.25, duration_s=1.0)
        750.0
        """
        return self.rpm_start + (self.rpm_end - self.rpm_start) * (t / duration_s)

    def shaft_angle(self, t, duration_s: float):
        """Shaft angle turned since t = 0, rad: the integral of 2 pi rpm/60 dt.

        Examples
        --------
        >>> import math
        >>> from ballpass import SpeedProfile
        >>> turned = SpeedProfile(600.0, 1200.0).shaft_angle(1.0, duration_s=1.0)   # rad
        >>> round(turned / (2 * math.pi), 6)                  # revolutions at a mean 15 rev/s
        15.0
        """
        w0 = self.rpm_start * math.pi / 30.0
        if self.is_constant:  # the same numbers without the vanishing quadratic term
            return w0 * t
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
    waviness : Waviness or sequence of Waviness, optional
        Distributed form errors of the races or balls (:class:`~ballpass.Waviness`); a
        scene with waviness needs a model that represents ``"waviness"``. Default none.
    clearance_um : float, optional
        Mounted radial clearance, micrometres, in (-50, 200); negative is a radial
        preload (an interference fit or a tight housing), which loads every element,
        also those opposite the load zone. Default None: the bearing's own
        ``radial_clearance_mm``.
    resonances : sequence of (hz, damping, gain), optional
        Further structural modes of the transfer path beside ``resonance_hz``: each a
        frequency (Hz, below 0.45 fs), a damping ratio in (0, 1) and a gain relative
        to the main resonance (> 0). A real housing has several modes in the
        measured band (the CWRU drive end shows energy from 2.5 to 5 kHz). Default none.
    noise_slope_db_oct : float, optional
        Spectral slope of the background noise of ``snr_db``/``noise_rms``, dB per
        octave, in [-12, 12]: 0 (default) is white, -3 pink, -6 brown (a machine's
        background falls with frequency). The RMS stays as set.
    shaft_harmonics : sequence of float, optional
        Amplitudes of the shaft-rate lines 1x, 2x, ... the rest of the machine adds
        (unbalance, misalignment, looseness), m/s^2 each, >= 0; phases drawn from the
        seed. Default none.
    gears : GearPair or str or None, optional
        A gear pair whose pinion sits on the bearing's shaft and turns at ``rpm`` (a
        :class:`~ballpass.GearPair` or a preset name such as ``"seed004"``); the scene
        then needs ``gear_mesh`` (the ``gearbox`` model). Default None.
    axial_load_n : float, optional
        Axial (thrust) load on the inner ring, N, in [0, 1e6]; ball bearings only. A
        positive value makes the scene need ``axial_load``: the balls' contact angle
        grows and the load zone widens (:meth:`Bearing.combined_load_distribution`).
        Default 0.

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
    waviness: tuple = ()
    clearance_um: float | None = None
    resonances: tuple = ()
    noise_slope_db_oct: float = 0.0
    shaft_harmonics: tuple = ()
    gears: GearPair | str | None = None
    axial_load_n: float = 0.0

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
        object.__setattr__(self, "axial_load_n",
                           _number("axial_load_n", self.axial_load_n, 0.0, 1e6))
        if self.axial_load_n > 0 and bearing.element != "ball":
            raise ValueError(f"axial_load_n={self.axial_load_n!r} needs a ball bearing: the "
                             f"{bearing.name} has rollers, whose line contacts carry no axial "
                             "load in ballpass; use axial_load_n=0")
        object.__setattr__(self, "duration_s",
                           _number("duration_s", self.duration_s, 0.0, 3600.0, lo_open=True))
        object.__setattr__(self, "fs", _number("fs", self.fs, 1000.0, 1e6))
        if round(self.duration_s * self.fs) < 1:   # would silently become one sample
            raise ValueError(f"duration_s={self.duration_s:g} s is shorter than one sample "
                             f"at fs={self.fs:g} Hz; give at least {1 / self.fs:.3g} s")
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
            if len(faults) > MAX_FAULTS:
                raise ValueError(
                    f"fault holds {len(faults)} faults; at most {MAX_FAULTS} localized faults "
                    f"per scene (for damage spread over a race use Scene(waviness=...))")
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
        self._check_fits_in_memory()

        if self.snr_db is not None and self.noise_rms is not None:
            raise ValueError("give snr_db or noise_rms, not both")
        if self.snr_db is not None:
            object.__setattr__(self, "snr_db", _number("snr_db", self.snr_db, -60.0, 200.0))
        if self.noise_rms is not None:
            object.__setattr__(self, "noise_rms",
                               _number("noise_rms", self.noise_rms, 0.0, 1e6))
        if not isinstance(self.gravity, bool):
            raise TypeError(f"gravity must be a bool, got {self.gravity!r}")
        object.__setattr__(self, "needs", tuple(sorted(check_needs(self.needs))))
        self._check_realism()
        clearance_mm = (bearing.radial_clearance_mm if self.clearance_um is None
                        else self.clearance_um * 1e-3)
        if (self.radial_load_n == 0 and self.axial_load_n == 0 and not self.gravity
                and clearance_mm >= 0.0):
            # a preload (negative clearance) loads every element by itself
            raise ValueError("radial_load_n=0 with gravity=False leaves the bearing without "
                             "any load: no load zone and no static equilibrium. Give a "
                             "radial_load_n > 0 N, keep gravity=True or preload the bearing "
                             "(clearance_um < 0)")

        if isinstance(self.gears, str):
            object.__setattr__(self, "gears", GearPair.preset(self.gears))
        elif self.gears is not None and not isinstance(self.gears, GearPair):
            raise TypeError(f"gears must be a GearPair, a preset name or None, got {self.gears!r}")

    def _check_realism(self) -> None:
        """Validate and normalise waviness, clearance, extra resonances and background."""
        wav = self.waviness
        wav = (wav,) if isinstance(wav, Waviness) else wav
        if not isinstance(wav, (tuple, list)) or not all(isinstance(w, Waviness) for w in wav):
            raise TypeError(f"waviness must be a Waviness or a sequence of them, got {wav!r}")
        object.__setattr__(self, "waviness", tuple(wav))
        if self.clearance_um is not None:
            object.__setattr__(self, "clearance_um", _number(
                "clearance_um", self.clearance_um, -50.0, 200.0, lo_open=True, hi_open=True))
        modes = []
        for mode in self.resonances:
            if not isinstance(mode, (tuple, list)) or len(mode) != 3:
                raise ValueError(f"resonances must hold (hz, damping, gain) triples, got "
                                 f"{mode!r}")
            hz = _number("resonances hz", mode[0], 0.0, 0.45 * self.fs, lo_open=True)
            zeta = _number("resonances damping", mode[1], 0.0, 1.0, lo_open=True,
                           hi_open=True)
            modes.append((hz, zeta, _number("resonances gain", mode[2], 0.0, 100.0,
                                            lo_open=True)))
        object.__setattr__(self, "resonances", tuple(modes))
        object.__setattr__(self, "noise_slope_db_oct", _number(
            "noise_slope_db_oct", self.noise_slope_db_oct, -12.0, 12.0))
        object.__setattr__(self, "shaft_harmonics", tuple(
            _number("shaft_harmonics", a, 0.0, 1e4) for a in self.shaft_harmonics))

    def _check_fits_in_memory(self) -> None:
        """Refuse a scene whose simulation would not fit in this machine's free memory."""
        need = _resources.simulation_bytes(self.n_samples, len(self.sensors))
        if need < _MEMORY_CHECK_BYTES:  # reading /proc/meminfo costs more than a small scene
            return
        free = _resources.available_memory()
        if need > free:
            raise ValueError(
                f"duration_s={self.duration_s:g} s at fs={self.fs:g} Hz with "
                f"{len(self.sensors)} sensor(s) is {self.n_samples} samples per sensor; "
                f"simulating it needs about {_resources.human_bytes(need)} of memory and "
                f"{_resources.human_bytes(free)} is available. Shorten duration_s or lower fs "
                "(simulate a long record as several scenes).")

    # ------------------------------------------------------------------ derived
    @property
    def faults(self) -> tuple[Fault, ...]:
        """The faults as a tuple (empty for a healthy bearing)."""
        if self.fault is None:
            return ()
        if isinstance(self.fault, Fault):
            return (self.fault,)
        return tuple(self.fault)

    @functools.cached_property
    def speed(self) -> SpeedProfile:
        """The speed as a :class:`SpeedProfile` (constant when ``rpm`` is a number;
        built once per scene)."""
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
        """Return a validated copy with some fields changed.

        Examples
        --------
        >>> import ballpass as bp
        >>> scene = bp.Scene(bp.Bearing.catalog("6205"), rpm=1797)
        >>> scene.replace(rpm=1200).rpm
        1200.0
        """
        return replace(self, **changes)
