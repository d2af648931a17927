"""Bearing geometry, a catalogue of real bearings and their characteristic frequencies.

Everything here is plain kinematics and quasi-static contact mechanics; nothing is
compiled. The dataclass stores the dimensions engineers quote (mm, degrees) and
exposes SI properties (``*_m``, ``*_rad``) that the simulator uses.

References
----------
.. [1] T. A. Harris, M. N. Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed.,
   CRC Press, 2006 (kinematics, Hertz contact, Stribeck load distribution).
.. [2] N. Sawalhi, R. B. Randall, "Simulating gear and bearing interactions in the
   presence of faults: Part I", MSSP 22 (2008) 1924-1951, eqs. (17)-(20) as printed in
   seed 004 (defect frequencies).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

__all__ = ["Bearing", "BearingFrequencies"]


@dataclass(frozen=True)
class BearingFrequencies:
    """Characteristic defect frequencies of a bearing at one shaft speed, in Hz.

    Attributes
    ----------
    shaft : float
        Shaft (inner-ring) rotation frequency, Hz.
    ftf : float
        Fundamental train (cage) frequency, Hz.
    bsf : float
        Ball spin frequency: rotations of a rolling element about its own axis, Hz.
    ball_defect : float
        Ball-defect frequency ``2 * bsf``: a defect on a rolling element strikes the
        inner and the outer race once each per ball revolution (the "ball fault
        frequency" f_BF of Nakhaeinejad & Bryant 2011, eq. 28), Hz.
    bpfo : float
        Ball pass frequency, outer race, Hz.
    bpfi : float
        Ball pass frequency, inner race, Hz.
    """

    shaft: float
    ftf: float
    bsf: float
    ball_defect: float
    bpfo: float
    bpfi: float

    def as_dict(self) -> dict[str, float]:
        """Return the frequencies as ``{name: Hz}``."""
        return {
            "shaft": self.shaft,
            "ftf": self.ftf,
            "bsf": self.bsf,
            "ball_defect": self.ball_defect,
            "bpfo": self.bpfo,
            "bpfi": self.bpfi,
        }


def _require_positive(name: str, value: float) -> None:
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        raise TypeError(f"{name} must be a number, got {type(value).__name__}")
    if not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")


@dataclass(frozen=True)
class Bearing:
    """A rolling-element bearing: geometry, material and internal clearance.

    Parameters
    ----------
    name : str
        Designation, e.g. ``"6205"``.
    n_elements : int
        Number of rolling elements Z (balls or rollers), >= 3.
    element_diameter_mm : float
        Ball (or roller) diameter d, mm.
    pitch_diameter_mm : float
        Pitch diameter d_p, mm; must exceed ``element_diameter_mm``.
    contact_angle_deg : float, optional
        Nominal contact angle, degrees in [0, 60). Default 0 (radial bearing).
    inner_conformity, outer_conformity : float, optional
        Groove radius divided by ball diameter, f_i and f_o, each in (0.5, 0.6].
        Defaults 0.515 and 0.525. Ignored for rollers.
    radial_clearance_mm : float, optional
        **Radial** internal clearance c_r, mm: the free radial travel of the inner ring
        from the concentric position until one element touches both races (half of the
        diametral clearance P_d quoted in catalogues). Negative values are a preload.
        Default 0.
    element : {"ball", "roller"}, optional
        Point contact (Hertz exponent 3/2) or line contact (10/9). Default ``"ball"``.
    roller_length_mm : float, optional
        Effective roller length l, mm; required for rollers.
    youngs_modulus_pa, poisson_ratio : float, optional
        Elastic constants of elements and races (bearing steel: 2.075e11 Pa, 0.3).
    source : str, optional
        Where the dimensions come from (shown by ``ballpass bearings``).

    Examples
    --------
    >>> import ballpass as bp
    >>> b = bp.Bearing.catalog("6205")
    >>> f = b.frequencies(shaft_hz=29.95)
    >>> round(f.bpfo / 29.95, 4), round(f.bpfi / 29.95, 4)
    (3.5848, 5.4152)
    """

    name: str
    n_elements: int
    element_diameter_mm: float
    pitch_diameter_mm: float
    contact_angle_deg: float = 0.0
    inner_conformity: float = 0.515
    outer_conformity: float = 0.525
    radial_clearance_mm: float = 0.0
    element: str = "ball"
    roller_length_mm: float | None = None
    youngs_modulus_pa: float = 2.075e11
    poisson_ratio: float = 0.3
    source: str = field(default="user", compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.n_elements, int) or isinstance(self.n_elements, bool):
            raise TypeError(f"n_elements must be an int, got {type(self.n_elements).__name__}")
        if self.n_elements < 3:
            raise ValueError(f"n_elements must be >= 3, got {self.n_elements}")
        _require_positive("element_diameter_mm", self.element_diameter_mm)
        _require_positive("pitch_diameter_mm", self.pitch_diameter_mm)
        if self.element_diameter_mm >= self.pitch_diameter_mm:
            raise ValueError(
                "element_diameter_mm must be < pitch_diameter_mm (got "
                f"{self.element_diameter_mm} >= {self.pitch_diameter_mm}): impossible geometry"
            )
        spacing = math.pi * self.pitch_diameter_mm / self.n_elements
        if self.element_diameter_mm >= spacing:
            raise ValueError(
                f"{self.n_elements} elements of diameter {self.element_diameter_mm} mm do not fit "
                f"on a pitch circle of {self.pitch_diameter_mm} mm: element_diameter_mm must be "
                f"< pi*pitch_diameter_mm/n_elements = {spacing:.3f} mm"
            )
        if not (0.0 <= self.contact_angle_deg < 60.0):
            raise ValueError(
                f"contact_angle_deg must be in [0, 60), got {self.contact_angle_deg!r}"
            )
        for name in ("inner_conformity", "outer_conformity"):
            value = getattr(self, name)
            if not (0.5 < value <= 0.6):
                raise ValueError(f"{name} must be in (0.5, 0.6], got {value!r}")
        if not math.isfinite(self.radial_clearance_mm) or abs(self.radial_clearance_mm) >= (
            0.1 * self.element_diameter_mm
        ):
            raise ValueError(
                "radial_clearance_mm must be finite and smaller in magnitude than "
                f"0.1*element_diameter_mm = {0.1 * self.element_diameter_mm:.3f} mm, "
                f"got {self.radial_clearance_mm!r}"
            )
        if self.element not in ("ball", "roller"):
            raise ValueError(f"element must be 'ball' or 'roller', got {self.element!r}")
        if self.element == "roller":
            if self.roller_length_mm is None:
                raise ValueError("roller_length_mm is required when element='roller'")
            _require_positive("roller_length_mm", self.roller_length_mm)
        _require_positive("youngs_modulus_pa", self.youngs_modulus_pa)
        if not (0.0 <= self.poisson_ratio < 0.5):
            raise ValueError(f"poisson_ratio must be in [0, 0.5), got {self.poisson_ratio!r}")

    # ------------------------------------------------------------------ catalogue
    @classmethod
    def catalog(cls, name: str) -> Bearing:
        """Return a catalogue bearing by designation.

        Parameters
        ----------
        name : str
            One of :meth:`catalog_names` (case-insensitive).

        Raises
        ------
        ValueError
            If the designation is unknown; the message lists the known ones.
        """
        if not isinstance(name, str):
            raise TypeError(f"bearing name must be a str, got {type(name).__name__}")
        key = name.strip().upper()
        for entry_name, kwargs in _CATALOG.items():
            if entry_name.upper() == key:
                return cls(name=entry_name, **kwargs)
        raise ValueError(
            f"unknown bearing {name!r}; the catalogue has: {', '.join(cls.catalog_names())}"
        )

    @staticmethod
    def catalog_names() -> list[str]:
        """Designations available through :meth:`catalog`."""
        return list(_CATALOG)

    def with_clearance(self, radial_clearance_mm: float) -> Bearing:
        """Return a copy with another radial clearance (mm; negative = preload)."""
        return replace(self, radial_clearance_mm=float(radial_clearance_mm))

    # ------------------------------------------------------------------ SI geometry
    @property
    def element_diameter_m(self) -> float:
        """Rolling-element diameter d, m."""
        return self.element_diameter_mm * 1e-3

    @property
    def pitch_diameter_m(self) -> float:
        """Pitch diameter d_p, m."""
        return self.pitch_diameter_mm * 1e-3

    @property
    def radial_clearance_m(self) -> float:
        """Radial clearance c_r, m (negative = preload)."""
        return self.radial_clearance_mm * 1e-3

    @property
    def contact_angle_rad(self) -> float:
        """Contact angle, rad."""
        return math.radians(self.contact_angle_deg)

    @property
    def diameter_ratio(self) -> float:
        """r = (d / d_p) cos(alpha), the ratio in every defect-frequency formula."""
        return self.element_diameter_mm / self.pitch_diameter_mm * math.cos(self.contact_angle_rad)

    @property
    def inner_race_radius_m(self) -> float:
        """Radius of the inner raceway at the contact, (d_p - d)/2, m."""
        return 0.5 * (self.pitch_diameter_m - self.element_diameter_m)

    @property
    def outer_race_radius_m(self) -> float:
        """Radius of the outer raceway at the contact, (d_p + d)/2, m."""
        return 0.5 * (self.pitch_diameter_m + self.element_diameter_m)

    @property
    def load_exponent(self) -> float:
        """Hertz load-deflection exponent n: 3/2 for balls, 10/9 for rollers."""
        return 1.5 if self.element == "ball" else 10.0 / 9.0

    # ------------------------------------------------------------------ kinematics
    def frequencies(self, shaft_hz: float) -> BearingFrequencies:
        """Characteristic frequencies for a rotating inner ring and a fixed outer ring.

        Sawalhi & Randall (2008), eqs. (17)-(20) (seed 004), with r = (d/d_p) cos(alpha):
        FTF = f_r/2 (1 - r); BPFO = Z FTF; BPFI = Z f_r/2 (1 + r);
        BSF = d_p/(2d) f_r (1 - r^2); ball-defect frequency = 2 BSF.

        Parameters
        ----------
        shaft_hz : float
            Shaft rotation frequency f_r, Hz (rpm / 60), > 0.

        Returns
        -------
        BearingFrequencies
            ``.ftf .bsf .ball_defect .bpfo .bpfi`` in Hz.
        """
        _require_positive("shaft_hz", shaft_hz)
        r = self.diameter_ratio
        z = self.n_elements
        ftf = 0.5 * shaft_hz * (1.0 - r)
        bsf = self.pitch_diameter_mm / (2.0 * self.element_diameter_mm) * shaft_hz * (1.0 - r * r)
        return BearingFrequencies(
            shaft=float(shaft_hz),
            ftf=ftf,
            bsf=bsf,
            ball_defect=2.0 * bsf,
            bpfo=z * ftf,
            bpfi=0.5 * z * shaft_hz * (1.0 + r),
        )


#: Catalogue: designation -> constructor keywords. Dimensions in mm.
_CATALOG: dict[str, dict] = {
    "6205": dict(
        n_elements=9, element_diameter_mm=7.94, pitch_diameter_mm=39.04,
        source="SKF 6205-2RS JEM, CWRU drive end (Smith & Randall 2015)",
    ),
    "6203": dict(
        n_elements=8, element_diameter_mm=6.746, pitch_diameter_mm=28.5,
        source="SKF 6203-2RS JEM, CWRU fan end",
    ),
    "6004": dict(
        n_elements=9, element_diameter_mm=6.35, pitch_diameter_mm=31.0,
        source="SKF 6004, seed 001 Table 1",
    ),
    "ER-16K": dict(
        n_elements=9, element_diameter_mm=7.94, pitch_diameter_mm=39.32,
        source="MB ER-16K, seed 000 Table 1 (pitch 39.32 mm from the race diameters)",
    ),
    "6208": dict(
        n_elements=9, element_diameter_mm=11.8872, pitch_diameter_mm=59.9948,
        source="SKF 6208, seed 004 Table 2",
    ),
    "6305": dict(
        n_elements=7, element_diameter_mm=11.0998, pitch_diameter_mm=43.4848,
        source="SKF 6305, seed 004 Table 2",
    ),
    "6306": dict(
        n_elements=8, element_diameter_mm=11.8872, pitch_diameter_mm=51.9938,
        source="SKF 6306, seed 004 Table 2",
    ),
    "6307": dict(
        n_elements=8, element_diameter_mm=13.4874, pitch_diameter_mm=57.4802,
        source="SKF 6307, seed 004 Table 2",
    ),
    "NU2204": dict(
        n_elements=11, element_diameter_mm=6.477, pitch_diameter_mm=33.4772,
        element="roller", roller_length_mm=8.0,
        source="SKF NU 2204, seed 004 Table 2 (roller length 8 mm assumed)",
    ),
    "NJ305": dict(
        n_elements=11, element_diameter_mm=9.25, pitch_diameter_mm=43.5,
        element="roller", roller_length_mm=11.0, radial_clearance_mm=0.125,
        source="NJ 305, seed 003 section 2.1 (P_d = 0.25 mm diametral)",
    ),
}
