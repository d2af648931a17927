"""Gear pairs: involute geometry, contact ratios, mesh stiffness, transmission error and
tooth faults, for the ``gearbox`` simulation model (Tran, Furch & Cu).

A :class:`GearPair` is a pinion (``teeth[0]``) on the shaft of the scene's bearing and
a gear (``teeth[1]``) on a second shaft; ``Scene(gears=GearPair(...))`` simulates both
(see :mod:`ballpass.simulate.gearbox`). The pinion turns at ``Scene.rpm``; the gear at
``rpm * teeth[0] / teeth[1]``; teeth meet at the mesh frequency
``f_m = teeth[0] * f_pinion = teeth[1] * f_gear``.

Geometry (standard full-depth involute teeth without profile shift, addendum = module):

* transverse module m_t = m_n / cos(beta), transverse pressure angle
  alpha_t = atan(tan(alpha_n) / cos(beta)); pitch radius r = m_t z / 2; base radius
  r_b = r cos(alpha_t); tip radius r_a = r + m_n; centre distance a = r_1 + r_2;
* transverse contact ratio
  eps_alpha = (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin(alpha_t)) / p_bt
  with the transverse base pitch p_bt = pi m_t cos(alpha_t); overlap (face) ratio
  eps_beta = b sin(beta) / (pi m_n) (ISO 21771, ISO 6336-1 sections 6-7).

Mesh stiffness k(t) = k_mean n(u) / eps_alpha, with u the mesh phase (teeth passed) and
n(u) the number of tooth pairs in contact averaged over the face width: a spur pair
alternates between floor(eps_alpha) + 1 pairs (double contact, a fraction
frac(eps_alpha) of each mesh period) and floor(eps_alpha) pairs (single contact); a
helical pair is a stack of spur slices staggered by eps_beta mesh periods across the
face, so the rectangular wave is averaged over a window of eps_beta periods. Its
ripple vanishes when eps_beta is an integer (the 15/32 pair of Tran, Furch & Cu has
eps_beta = 1.02: an almost constant stiffness, a quiet helical mesh). k_mean defaults to
the ISO 6336-1 mesh stiffness c_gamma = 20 N/(mm um) per unit face width.

Assumptions: every tooth pair in contact is equally stiff along the whole path of
contact (no parabolic single-tooth stiffness), the axial force of a helical mesh is
ignored (a planar model in the transverse plane), there is no backlash travel (a tooth
separation simply unloads the mesh) and no tooth friction.

Examples
--------
>>> import ballpass as bp
>>> g = bp.GearPair.preset("tran-furch-cu")
>>> g.teeth, round(g.mesh_frequency(2000 / 60), 2)
((15, 32), 500.0)
>>> round(g.contact_ratio, 3), round(g.overlap_ratio, 3)
(1.326, 1.024)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from ._validation import check_number

__all__ = ["GearPair", "GearFault", "GEAR_PRESETS", "PRESET_ALIASES", "STEEL_DENSITY"]

#: density of gear steel, kg/m^3 (the masses and inertias of the default solid discs)
STEEL_DENSITY = 7850.0
#: ISO 6336-1 (2019) eq. 6: mean mesh stiffness per unit face width c_gamma, N/(mm um),
#: for solid steel spur and helical gears: 20 N/(mm um) = 2e10 N/m^2
ISO_MESH_STIFFNESS_PER_WIDTH = 2.0e10

GEAR_FAULT_KINDS = ("crack", "spall")


@dataclass(frozen=True)
class GearFault:
    """A local tooth fault: a cracked or spalled tooth stiffens the mesh less while it
    is in contact.

    Parameters
    ----------
    kind : {"crack", "spall"}
        A root crack (the tooth bends more: Chaari, Fakhfakh & Haddar 2009 compute
        10-50 % loss of single-tooth stiffness for cracks of 10-50 % of the tooth
        thickness) or a spall (part of the flank carries no load).
    gear : {"pinion", "gear"}, optional
        Which wheel carries the faulty tooth. Default ``"pinion"``.
    tooth : int, optional
        Index of the faulty tooth (0 enters mesh at t = 0). Default 0.
    stiffness_loss : float, optional
        Fraction of that tooth's mesh stiffness lost, in (0, 1]. Default 0.3.

    Examples
    --------
    >>> from ballpass import GearFault
    >>> GearFault("crack", stiffness_loss=0.5).gear
    'pinion'
    """

    kind: str
    gear: str = "pinion"
    tooth: int = 0
    stiffness_loss: float = 0.3

    def __post_init__(self) -> None:
        if self.kind not in GEAR_FAULT_KINDS:
            raise ValueError(f"kind must be one of {GEAR_FAULT_KINDS}, got {self.kind!r}")
        if self.gear not in ("pinion", "gear"):
            raise ValueError(f"gear must be 'pinion' or 'gear', got {self.gear!r}")
        if isinstance(self.tooth, bool) or not isinstance(self.tooth, int) or self.tooth < 0:
            raise ValueError(f"tooth must be an int >= 0, got {self.tooth!r}")
        object.__setattr__(self, "stiffness_loss",
                           check_number("stiffness_loss", self.stiffness_loss, 0.0, 1.0,
                                        lo_open=True))


def _pair(name: str, value, kind=float, lo: float = 0.0) -> tuple:
    """A (pinion, gear) pair of positive numbers."""
    try:
        a, b = value
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a pair (pinion, gear), got {value!r}") from None
    if kind is int:
        for v in (a, b):
            if isinstance(v, bool) or not isinstance(v, int):
                raise TypeError(f"{name} must hold ints, got {value!r}")
        return int(a), int(b)
    return (check_number(f"{name}[0]", a, lo, lo_open=lo == 0.0),
            check_number(f"{name}[1]", b, lo, lo_open=lo == 0.0))


@dataclass(frozen=True)
class GearPair:
    """A pinion-gear pair: geometry, inertia, mesh stiffness and damping, errors, load.

    Parameters
    ----------
    teeth : (int, int)
        Teeth of the pinion (on the bearing's shaft) and of the gear, each >= 6.
    module_mm : float, optional
        Normal module m_n, mm, in (0, 50]. Default 3 (Tran, Furch & Cu Table 1).
    face_width_mm : float, optional
        Face width b, mm, > 0. Default 20 (Tran, Furch & Cu Table 1).
    helix_angle_deg : float, optional
        Helix angle beta, degrees in [0, 45); 0 = spur. Default 0.
    pressure_angle_deg : float, optional
        Normal pressure angle alpha_n, degrees in [10, 35]. Default 20 (ISO 53 basic rack).
    masses_kg, inertias_kgm2 : (float, float) or None, optional
        Masses (kg) and polar moments of inertia (kg m^2) of pinion and gear. None
        (default): solid steel discs of the pitch diameter and the face width
        (density 7850 kg/m^3).
    mesh_stiffness_n_per_m : float or None, optional
        Mean mesh stiffness k_mean along the line of action, N/m. None (default):
        ISO 6336-1 c_gamma = 20 N/(mm um) times the face width (4e8 N/m for 20 mm).
    mesh_damping_ratio : float, optional
        Damping ratio of the mesh mode, c_m = 2 zeta sqrt(k_mean m_e) with the
        equivalent mass m_e = 1 / (r_b1^2 / I_1 + r_b2^2 / I_2); in [0, 1). Default 0.07
        (the 0.03-0.17 range of Kasuba & Evans 1981, reviewed by Özgüven & Houser 1988,
        Tran, Furch & Cu ref. [9]).
    transmission_error_um : sequence of float, optional
        Static transmission error (profile and pitch deviations) at the mesh frequency
        and its harmonics: peak amplitudes of harmonics 1, 2, ..., um along the line of
        action. Default (2.0, 0.5): the order of the profile-form deviation of an
        ISO 1328-1 grade 6-7 gear of module 3.
    eccentricity_um : (float, float), optional
        Runout of pinion and gear, um (>= 0): a transmission error once per revolution
        of each wheel, which modulates the mesh into sidebands at both shaft
        frequencies. Default (0, 0).
    torque_nm : float, optional
        Input torque on the pinion shaft, N m, > 0. The gear's shaft carries the load
        torque torque_nm * teeth[1] / teeth[0], so that the mean mesh force is
        torque_nm / r_b1 along the line of action. Default 50.
    support_stiffness_n_per_m, support_damping_ns_per_m : float, optional
        Lateral stiffness (N/m) and damping (N s/m) of the gear's shaft and bearings.
        Defaults 1e8 and 2000.
    drive_stiffness_nm_per_rad, output_stiffness_nm_per_rad : float, optional
        Torsional stiffness of the input shaft (drive to pinion) and of the output
        shaft (gear to the load, which turns at the nominal speed), N m/rad. Defaults
        1e5 (a 40 mm steel shaft 200 mm long: G J / L = 8e10 * pi * 0.04^4 / 32 / 0.2).
    drive_inertia_kgm2 : float, optional
        Inertia of the drive (motor rotor, clutch) that applies ``torque_nm``, kg m^2.
        Default 0.02 (the rotor of a 5-10 kW four-pole induction motor).
    fault : GearFault or None, optional
        A cracked or spalled tooth. Default None (healthy).
    name : str, optional
        Label (presets set it).

    Examples
    --------
    >>> import ballpass as bp
    >>> g = bp.GearPair((20, 40), module_mm=2.0, face_width_mm=15.0)
    >>> round(g.contact_ratio, 3), g.overlap_ratio, round(g.base_radius_m[0] * 1e3, 3)
    (1.635, 0.0, 18.794)
    """

    teeth: tuple[int, int]
    module_mm: float = 3.0
    face_width_mm: float = 20.0
    helix_angle_deg: float = 0.0
    pressure_angle_deg: float = 20.0
    masses_kg: tuple[float, float] | None = None
    inertias_kgm2: tuple[float, float] | None = None
    mesh_stiffness_n_per_m: float | None = None
    mesh_damping_ratio: float = 0.07
    transmission_error_um: tuple[float, ...] = (2.0, 0.5)
    eccentricity_um: tuple[float, float] = (0.0, 0.0)
    torque_nm: float = 50.0
    support_stiffness_n_per_m: float = 1e8
    support_damping_ns_per_m: float = 2000.0
    drive_stiffness_nm_per_rad: float = 1e5
    output_stiffness_nm_per_rad: float = 1e5
    drive_inertia_kgm2: float = 0.02
    fault: GearFault | None = None
    name: str = field(default="user", compare=False)

    def __post_init__(self) -> None:
        teeth = _pair("teeth", self.teeth, int)
        if min(teeth) < 6:
            raise ValueError(f"teeth must be >= 6 on both wheels, got {teeth}")
        object.__setattr__(self, "teeth", teeth)
        check_number("module_mm", self.module_mm, 0.0, 50.0, lo_open=True)
        check_number("face_width_mm", self.face_width_mm, 0.0, 1000.0, lo_open=True)
        check_number("helix_angle_deg", self.helix_angle_deg, 0.0, 45.0, hi_open=True)
        check_number("pressure_angle_deg", self.pressure_angle_deg, 10.0, 35.0)
        for name in ("masses_kg", "inertias_kgm2"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, _pair(name, getattr(self, name)))
        if self.mesh_stiffness_n_per_m is not None:
            check_number("mesh_stiffness_n_per_m", self.mesh_stiffness_n_per_m, 0.0, 1e12,
                         lo_open=True)
        check_number("mesh_damping_ratio", self.mesh_damping_ratio, 0.0, 1.0, hi_open=True)
        te = self.transmission_error_um
        if isinstance(te, (int, float)):
            te = (te,)
        try:
            te = tuple(check_number(f"transmission_error_um[{i}]", v, 0.0, 1000.0)
                       for i, v in enumerate(te))
        except TypeError:
            raise TypeError("transmission_error_um must be a sequence of amplitudes (um), "
                            f"got {self.transmission_error_um!r}") from None
        object.__setattr__(self, "transmission_error_um", te)
        ecc = _pair("eccentricity_um", self.eccentricity_um, lo=-math.inf)
        for v in ecc:
            check_number("eccentricity_um", v, 0.0, 1000.0)
        object.__setattr__(self, "eccentricity_um", ecc)
        check_number("torque_nm", self.torque_nm, 0.0, 1e6, lo_open=True)
        check_number("support_stiffness_n_per_m", self.support_stiffness_n_per_m, 0.0,
                     lo_open=True)
        check_number("support_damping_ns_per_m", self.support_damping_ns_per_m, 0.0)
        for name in ("drive_stiffness_nm_per_rad", "output_stiffness_nm_per_rad",
                     "drive_inertia_kgm2"):
            check_number(name, getattr(self, name), 0.0, lo_open=True)
        if self.fault is not None:
            if not isinstance(self.fault, GearFault):
                raise TypeError(f"fault must be a GearFault or None, got {self.fault!r}")
            n = teeth[0] if self.fault.gear == "pinion" else teeth[1]
            if self.fault.tooth >= n:
                raise ValueError(f"fault.tooth must be < {n} (teeth of the {self.fault.gear}), "
                                 f"got {self.fault.tooth}")
        if self.contact_ratio < 1.0:
            raise ValueError(f"transverse contact ratio {self.contact_ratio:.3f} < 1: the "
                             f"teeth {teeth} do not mesh continuously")

    # ------------------------------------------------------------------ presets
    @classmethod
    def preset(cls, name: str, **changes) -> GearPair:
        """A gear pair of the catalogue :data:`GEAR_PRESETS`, optionally changed.

        Parameters
        ----------
        name : str
            ``"tran-furch-cu"`` (the constant mesh of Tran, Furch & Cu Table 1) or
            ``"tran-furch-cu-1st"``, ``"-2nd"``, ``"-3rd"``, ``"-reverse"`` (the other pairs of
            that table); the former names ``"seed004"``, ``"seed004-1st"``, ... still work.
        **changes
            Fields to override (e.g. ``torque_nm=100``).

        Examples
        --------
        >>> from ballpass import GearPair
        >>> GearPair.preset("tran-furch-cu-1st").teeth
        (15, 29)
        """
        key = name.lower() if isinstance(name, str) else None
        key = PRESET_ALIASES.get(key, key)
        if key not in GEAR_PRESETS:
            raise ValueError(f"unknown gear preset {name!r}; presets: {', '.join(GEAR_PRESETS)}")
        return cls(name=key, **{**GEAR_PRESETS[key], **changes})

    def replace(self, **changes) -> GearPair:
        """A validated copy with some fields changed.

        Examples
        --------
        >>> import ballpass as bp
        >>> g = bp.GearPair.preset("tran-furch-cu").replace(teeth=(16, 32))
        >>> g.teeth, g.ratio
        ((16, 32), 2.0)
        """
        return replace(self, **changes)

    # ------------------------------------------------------------------ geometry
    @property
    def transverse_pressure_angle_rad(self) -> float:
        """alpha_t = atan(tan(alpha_n) / cos(beta)), rad."""
        return math.atan(math.tan(math.radians(self.pressure_angle_deg))
                         / math.cos(math.radians(self.helix_angle_deg)))

    @property
    def transverse_module_m(self) -> float:
        """m_t = m_n / cos(beta), m."""
        return self.module_mm * 1e-3 / math.cos(math.radians(self.helix_angle_deg))

    @property
    def pitch_radius_m(self) -> tuple[float, float]:
        """Pitch radii m_t z / 2 of pinion and gear, m."""
        return tuple(0.5 * self.transverse_module_m * z for z in self.teeth)

    @property
    def base_radius_m(self) -> tuple[float, float]:
        """Base radii r cos(alpha_t) of pinion and gear, m: the lever arms of the mesh
        force about each axis."""
        c = math.cos(self.transverse_pressure_angle_rad)
        return tuple(r * c for r in self.pitch_radius_m)

    @property
    def centre_distance_m(self) -> float:
        """Centre distance r_1 + r_2, m."""
        return sum(self.pitch_radius_m)

    @property
    def ratio(self) -> float:
        """Speed reduction teeth[1] / teeth[0]."""
        return self.teeth[1] / self.teeth[0]

    @property
    def contact_ratio(self) -> float:
        """Transverse contact ratio eps_alpha (ISO 21771 eq. 68, zero profile shift)."""
        a_t = self.transverse_pressure_angle_rad
        m_n = self.module_mm * 1e-3
        path = sum(math.sqrt((r + m_n) ** 2 - rb**2)
                   for r, rb in zip(self.pitch_radius_m, self.base_radius_m, strict=True))
        path -= self.centre_distance_m * math.sin(a_t)
        return path / (math.pi * self.transverse_module_m * math.cos(a_t))

    @property
    def overlap_ratio(self) -> float:
        """Overlap (face) contact ratio eps_beta = b sin(beta) / (pi m_n); 0 for spur."""
        return (self.face_width_mm * math.sin(math.radians(self.helix_angle_deg))
                / (math.pi * self.module_mm))

    @property
    def masses(self) -> tuple[float, float]:
        """Masses of pinion and gear, kg (given, or solid steel discs)."""
        if self.masses_kg is not None:
            return self.masses_kg
        b = self.face_width_mm * 1e-3
        return tuple(STEEL_DENSITY * math.pi * r * r * b for r in self.pitch_radius_m)

    @property
    def inertias(self) -> tuple[float, float]:
        """Polar moments of inertia of pinion and gear, kg m^2 (given, or solid discs
        m r^2 / 2)."""
        if self.inertias_kgm2 is not None:
            return self.inertias_kgm2
        return tuple(0.5 * m * r * r for m, r in zip(self.masses, self.pitch_radius_m, strict=True))

    @property
    def mesh_stiffness(self) -> float:
        """Mean mesh stiffness k_mean, N/m."""
        if self.mesh_stiffness_n_per_m is not None:
            return self.mesh_stiffness_n_per_m
        return ISO_MESH_STIFFNESS_PER_WIDTH * self.face_width_mm * 1e-3

    @property
    def equivalent_mass(self) -> float:
        """m_e = 1 / (r_b1^2 / I_1 + r_b2^2 / I_2), kg: the torsional mesh mode's mass."""
        (rb1, rb2), (i1, i2) = self.base_radius_m, self.inertias
        return 1.0 / (rb1 * rb1 / i1 + rb2 * rb2 / i2)

    @property
    def mesh_damping(self) -> float:
        """c_m = 2 zeta sqrt(k_mean m_e), N s/m."""
        return 2.0 * self.mesh_damping_ratio * math.sqrt(self.mesh_stiffness * self.equivalent_mass)

    @property
    def mean_mesh_force(self) -> float:
        """Mean force along the line of action in steady state, torque / r_b1, N."""
        return self.torque_nm / self.base_radius_m[0]

    def mesh_frequency(self, shaft_hz: float) -> float:
        """Mesh frequency teeth[0] * shaft_hz (pinion shaft at ``shaft_hz``), Hz.

        Examples
        --------
        >>> import ballpass as bp
        >>> bp.GearPair.preset("tran-furch-cu").mesh_frequency(shaft_hz=25.0)     # 15 teeth x 25 Hz
        375.0
        """
        return self.teeth[0] * shaft_hz

    def gear_shaft_hz(self, shaft_hz: float) -> float:
        """Speed of the gear's shaft when the pinion turns at ``shaft_hz``, Hz.

        Examples
        --------
        >>> import ballpass as bp
        >>> bp.GearPair.preset("tran-furch-cu").gear_shaft_hz(32.0)               # 32 Hz x 15/32
        15.0
        """
        return shaft_hz * self.teeth[0] / self.teeth[1]


def _tran_furch_cu(teeth, module, face, helix) -> dict:
    return dict(teeth=teeth, module_mm=module, face_width_mm=face, helix_angle_deg=helix)


#: Tran, Furch & Cu Table 1: the gear pairs of the vehicle gearbox; pressure
#: angle not printed, the ISO 53 basic rack's 20 deg assumed
GEAR_PRESETS: dict[str, dict] = {
    "tran-furch-cu": _tran_furch_cu((15, 32), 3.0, 20.0, 28.85),        # constant mesh
    "tran-furch-cu-1st": _tran_furch_cu((15, 29), 3.5, 20.0, 0.0),
    "tran-furch-cu-2nd": _tran_furch_cu((21, 26), 3.0, 20.0, 28.85),
    "tran-furch-cu-3rd": _tran_furch_cu((27, 20), 3.0, 20.0, 28.85),
    "tran-furch-cu-reverse": _tran_furch_cu((15, 19), 3.5, 15.0, 0.0),
}
#: Former names of the presets, still accepted: ``"seed004"`` is ``"tran-furch-cu"``.
PRESET_ALIASES = {name.replace("tran-furch-cu", "seed004"): name for name in GEAR_PRESETS}
