"""Bearing geometry, a catalogue of real bearings, their characteristic frequencies,
Hertz contact stiffness and the quasi-static (Stribeck) load distribution.

Everything here is plain kinematics and quasi-static contact mechanics; nothing is
compiled, and numpy/scipy are imported only inside the functions that need them, so
``import ballpass`` stays cheap. The dataclass stores the dimensions engineers quote
(mm, degrees) and exposes SI properties (``*_m``, ``*_rad``) that the simulator uses.
The contact mechanics (Hertz factors and stiffness, the Stribeck distribution) live in
:mod:`ballpass._contact` and are re-exported here.

References
----------
.. [1] T. A. Harris, M. N. Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed.,
   CRC Press, 2006 (kinematics; ch. 6 Hertz contact: curvature sum and difference,
   the dimensionless factors a*, b*, delta*; ch. 7 Stribeck load distribution, J_r(eps)).
.. [2] N. Sawalhi, R. B. Randall, "Simulating gear and bearing interactions in the
   presence of faults: Part I", MSSP 22 (2008) 1924-1951, eqs. (17)-(20) as printed in
   Tran, Furch & Cu (defect frequencies).
.. [3] M. Nakhaeinejad, M. D. Bryant, "Dynamic modeling of rolling element bearings with
   surface contact defects using bond graphs", J. Tribology 133 (2011) 011102 (Nakhaeinejad &
   Bryant 2011),
   eqs. (6)-(8): Harris point-contact stiffness, curvature sum and difference. Its
   printed "2E2" is 2*sqrt(2)*E, and its delta* polynomial is a chart fit good to 3 %
   only for F(rho) in [0.9, 0.99]; here delta* comes from the elliptic integrals instead.
.. [4] Nabhan & Rashed (2020) (MSC-ADAMS inner-race paper), eq. (2) series combination of the inner
   and outer contacts, eq. (3) Harris stiffness, eqs. (4)-(10) Stribeck distribution
   (eq. 10: Q_max = 4.37 F_r / (Z cos alpha)).
.. [5] A. Palmgren, *Ball and Roller Bearing Engineering*, 1959: line contact
   delta = 3.84e-5 Q^0.9 / l^0.8 (mm, N, mm), as used by the NJ 305 rotor paper, eq. (1).
.. [6] K. L. Johnson, *Contact Mechanics*, CUP 1985, sec. 4.2 (elliptical contact in
   Carlson's form), and DLMF 19.25.1 (K - E and E - k'^2 K through R_D).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

from ._combined_load import CombinedLoadDistribution, axial_integral, combined_load_distribution
from ._contact import (
    HertzFactors,
    LoadDistribution,
    _monotone_root,
    hertz_factors,
    line_contact_stiffness,
    point_contact_stiffness,
    series_stiffness,
    stribeck_integral,
    stribeck_qmax,
)
from ._validation import check_number

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np

__all__ = [
    "Bearing",
    "BearingFrequencies",
    "HertzFactors",
    "LoadDistribution",
    "hertz_factors",
    "point_contact_stiffness",
    "line_contact_stiffness",
    "series_stiffness",
    "stribeck_integral",
    "stribeck_qmax",
    "axial_integral",
    "CombinedLoadDistribution",
]


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

    Examples
    --------
    >>> import ballpass as bp
    >>> f = bp.Bearing.catalog("6205").frequencies(29.95)
    >>> round(f.bpfo, 2), round(f.bpfi, 2), round(f.ftf, 3)     # Hz
    (107.36, 162.19, 11.929)
    >>> round(f.ball_defect / f.bsf, 6)
    2.0
    """

    shaft: float
    ftf: float
    bsf: float
    ball_defect: float
    bpfo: float
    bpfi: float

    def as_dict(self) -> dict[str, float]:
        """Return the frequencies as ``{name: Hz}``.

        Examples
        --------
        >>> import ballpass as bp
        >>> f = bp.Bearing.catalog("6205").frequencies(29.95)
        >>> {k: round(hz, 1) for k, hz in f.as_dict().items()}  # doctest: +NORMALIZE_WHITESPACE
        {'shaft': 29.9, 'ftf': 11.9, 'bsf': 70.6, 'ball_defect': 141.2,
         'bpfo': 107.4, 'bpfi': 162.2}
        """
        return {
            "shaft": self.shaft,
            "ftf": self.ftf,
            "bsf": self.bsf,
            "ball_defect": self.ball_defect,
            "bpfo": self.bpfo,
            "bpfi": self.bpfi,
        }


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
        if not isinstance(self.n_elements, numbers.Integral) or isinstance(self.n_elements,
                                                                           bool):
            raise TypeError(f"n_elements must be an int, got "
                            f"{type(self.n_elements).__name__} ({self.n_elements!r})")
        if self.n_elements < 3:
            raise ValueError(f"n_elements must be >= 3, got {self.n_elements}")
        object.__setattr__(self, "n_elements", int(self.n_elements))
        if not isinstance(self.name, str) or not self.name:
            raise TypeError(f"name must be a non-empty str, got {self.name!r}")
        # numbers first (a string '10' is a TypeError naming the argument, not a failed
        # comparison), stored as floats
        for arg in ("element_diameter_mm", "pitch_diameter_mm", "contact_angle_deg",
                    "inner_conformity", "outer_conformity", "radial_clearance_mm",
                    "youngs_modulus_pa", "poisson_ratio"):
            object.__setattr__(self, arg, check_number(arg, getattr(self, arg)))
        if self.roller_length_mm is not None:
            object.__setattr__(self, "roller_length_mm",
                               check_number("roller_length_mm", self.roller_length_mm))
        check_number("element_diameter_mm", self.element_diameter_mm, 0.0, lo_open=True)
        check_number("pitch_diameter_mm", self.pitch_diameter_mm, 0.0, lo_open=True)
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
            check_number("roller_length_mm", self.roller_length_mm, 0.0, lo_open=True)
        check_number("youngs_modulus_pa", self.youngs_modulus_pa, 0.0, lo_open=True)
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
        key = name.replace(" ", "").upper()  # "NU 2204" as printed is "NU2204"
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
        """Return a copy with another radial clearance (mm; negative = preload).

        Examples
        --------
        >>> import ballpass as bp
        >>> loose = bp.Bearing.catalog("6205").with_clearance(0.02)
        >>> loose.radial_clearance_mm, loose.radial_clearance_m
        (0.02, 2e-05)
        """
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

        Sawalhi & Randall (2008), eqs. (17)-(20) (Tran, Furch & Cu), with r = (d/d_p) cos(alpha):
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

        Examples
        --------
        >>> import ballpass as bp
        >>> f = bp.Bearing.catalog("6205").frequencies(shaft_hz=1797 / 60)
        >>> round(f.bpfi, 1), round(f.bpfo, 1)                    # Hz
        (162.2, 107.4)
        """
        check_number("shaft_hz", shaft_hz, 0.0, lo_open=True, unit="Hz")
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

    # ------------------------------------------------------------------ Hertz contact
    def contact_curvature(self, race: str) -> tuple[float, float]:
        """Curvature sum and curvature difference of one ball-raceway contact.

        Harris & Kotzalas [1] ch. 6 (Nakhaeinejad & Bryant (2011) eqs. 7-8). With gamma = d
        cos(alpha)/d_p
        and f the groove conformity (groove radius / d), the principal curvatures are
        ball 2/d, 2/d; inner race 2/d * gamma/(1 - gamma) (rolling direction) and
        -1/(f d) (groove); outer race -2/d * gamma/(1 + gamma) and -1/(f d). Concave
        surfaces count negative. Then

        * inner: sum_rho = (4 - 1/f_i + 2 gamma/(1 - gamma)) / d,
          F(rho) = (1/f_i + 2 gamma/(1 - gamma)) / (d sum_rho);
        * outer: sum_rho = (4 - 1/f_o - 2 gamma/(1 + gamma)) / d,
          F(rho) = (1/f_o - 2 gamma/(1 + gamma)) / (d sum_rho).

        Parameters
        ----------
        race : {"inner", "outer"}
            Which contact.

        Returns
        -------
        curvature_sum_per_m : float
            Sum_rho, 1/m.
        curvature_difference : float
            F(rho), dimensionless, in [0, 1).

        Raises
        ------
        ValueError
            For a roller bearing (line contact has no F(rho)) or an unknown ``race``.

        Examples
        --------
        >>> import ballpass as bp
        >>> s, f = bp.Bearing.catalog("6205").contact_curvature("inner")
        >>> round(s * 1e-3, 4), round(f, 4)          # 1/mm, dimensionless
        (0.3235, 0.9546)
        """
        if self.element != "ball":
            raise ValueError(
                f"contact_curvature is defined for ball bearings; {self.name!r} has "
                f"element={self.element!r} (line contact)"
            )
        if race not in ("inner", "outer"):
            raise ValueError(f"race must be 'inner' or 'outer', got {race!r}")
        d = self.element_diameter_m
        gamma = self.element_diameter_mm * math.cos(self.contact_angle_rad) / self.pitch_diameter_mm
        if race == "inner":
            groove = 1.0 / self.inner_conformity
            rolling = 2.0 * gamma / (1.0 - gamma)
        else:
            groove = 1.0 / self.outer_conformity
            rolling = -2.0 * gamma / (1.0 + gamma)
        total = 4.0 - groove + rolling
        return total / d, (groove + rolling) / total

    def contact_ellipse(self, race: str, load_n: float) -> tuple[float, float]:
        """Semi-axes of the Hertz contact ellipse of one ball-raceway contact, m.

        Harris & Kotzalas [1] ch. 6: ``a = a* (3 Q / (2 sum_rho E'))^(1/3)`` across the
        track and likewise ``b`` with ``b*`` along it, ``E' = E / (2 (1 - nu^2))`` for
        like materials, ``a*, b*`` from :func:`hertz_factors` of the curvature
        difference (:meth:`contact_curvature`).

        Parameters
        ----------
        race : {"inner", "outer"}
            Which contact.
        load_n : float
            Contact load Q, N (>= 0).

        Returns
        -------
        a_m, b_m : float
            Semi-axis across the track and along it (rolling direction), m.

        Raises
        ------
        ValueError
            For a roller bearing, an unknown ``race`` or a negative load.

        Examples
        --------
        The most loaded inner contact of a 6205 under 1 kN radial load (Stribeck:
        Q = 4.37 F_r / Z = 486 N) and its peak pressure 3 Q / (2 pi a b):

        >>> import math
        >>> import ballpass as bp
        >>> a, b = bp.Bearing.catalog("6205").contact_ellipse("inner", 486.0)
        >>> round(a * 1e3, 3), round(b * 1e3, 3)              # mm
        (1.159, 0.105)
        >>> round(1.5 * 486.0 / (math.pi * a * b) * 1e-6)     # MPa
        1909
        """
        if not load_n >= 0.0:
            raise ValueError(f"load_n must be >= 0 N, got {load_n!r}")
        total, diff = self.contact_curvature(race)
        factors = hertz_factors(diff)
        e_prime = self.youngs_modulus_pa / (2.0 * (1.0 - self.poisson_ratio**2))
        scale = (3.0 * load_n / (2.0 * total * e_prime)) ** (1.0 / 3.0)
        return factors.a_star * scale, factors.b_star * scale

    def contact_stiffnesses(self) -> tuple[float, float]:
        """Load-deflection constants of the inner and the outer contact, N/m^n.

        Balls: Harris's point contact, :func:`point_contact_stiffness` with the
        curvatures of :meth:`contact_curvature`, scaled with ``youngs_modulus_pa`` and
        ``poisson_ratio`` (Nakhaeinejad & Bryant (2011) eq. 6, Nabhan & Rashed (2020) eq. 3).
        Rollers: Palmgren's line
        contact, :func:`line_contact_stiffness`, the same for both races (it has no
        curvature dependence) and not scaled with E: the law is an empirical fit for
        bearing steel.

        Returns
        -------
        k_inner, k_outer : float
            Q = k delta^n for one contact, Q in N, delta in m, n = :attr:`load_exponent`;
            units N/m^1.5 (balls) or N/m^(10/9) (rollers).

        Examples
        --------
        >>> import ballpass as bp
        >>> k_i, k_o = bp.Bearing.catalog("6205").contact_stiffnesses()
        >>> f"{k_i:.3e} {k_o:.3e}"
        '2.825e+10 2.507e+10'
        """
        if self.element == "roller":
            k = line_contact_stiffness(self.roller_length_mm * 1e-3)
            return k, k
        out = []
        for race in ("inner", "outer"):
            s, f = self.contact_curvature(race)
            out.append(point_contact_stiffness(s, f, self.youngs_modulus_pa, self.poisson_ratio))
        return out[0], out[1]

    def hertz_stiffness(self) -> float:
        """Combined load-deflection constant K of one element between both races, N/m^n.

        The inner and outer contacts act in series (Nabhan & Rashed (2020) eq. 2):
        K = [1 / ((1/K_i)^(1/n) + (1/K_o)^(1/n))]^n, with K_i, K_o from
        :meth:`contact_stiffnesses` and n = :attr:`load_exponent`, so that the load on
        an element is Q = K delta^n with delta the total elastic approach of the two
        races along the contact normal.

        Returns
        -------
        float
            K in N/m^1.5 for balls, N/m^(10/9) for rollers.

        Notes
        -----
        For the 6205 (conformities 0.515/0.525, E = 2.075e11 Pa, nu = 0.3) this gives
        K = 9.40e9 N/m^1.5 (exact elliptic-integral delta*; the value 9.5e9 quoted for
        Nakhaeinejad & Bryant (2011) comes from its approximate delta* polynomial). For NJ305 (l =
        11 mm)
        Palmgren's law gives 6.77e8 N/m^(10/9) (1.46e9 per contact).

        Examples
        --------
        >>> import ballpass as bp
        >>> f"{bp.Bearing.catalog('6205').hertz_stiffness():.3e}"
        '9.398e+09'
        """
        k_i, k_o = self.contact_stiffnesses()
        return series_stiffness(k_i, k_o, self.load_exponent)

    # ------------------------------------------------------------------ load distribution
    def load_distribution(
        self,
        radial_load_n: float,
        *,
        stiffness: float | None = None,
        clearance_m: float | None = None,
        cage_angle_deg: float = 0.0,
    ) -> LoadDistribution:
        """Quasi-static equilibrium of the inner ring under a radial load (Stribeck).

        The outer ring is fixed; the inner ring moves by (x, y), x along the load line
        (angle 0, the centre of the load zone) and y at +90 deg. Element j sits at
        psi_j = cage_angle + 360 j / Z and is compressed along its contact normal by
        delta_j = (x cos psi_j + y sin psi_j - c) cos(alpha), carrying
        Q_j = K max(delta_j, 0)^n (Nabhan & Rashed (2020) eqs. 1, 11 with sin for the y term, 13-14;
        Harris & Kotzalas [1] ch. 7). The equilibrium
        sum_j Q_j cos(alpha) (cos psi_j, sin psi_j) = (F_r, 0) is solved to machine
        precision with :func:`scipy.optimize.brentq`: the radial balance is monotone in
        x. When the layout is symmetric about the load line (an element on it, or two
        straddling it: cage_angle a multiple of 180/Z deg) the lateral balance holds by
        symmetry and y = 0. Otherwise the loads are not symmetric, the ring also shifts
        sideways, and y is found by an outer brentq on the lateral balance, which is
        monotone in y because the contact potential is convex.

        With a contact angle alpha the axial displacement is held at zero (the axial
        reaction sum Q sin(alpha) is taken by the shaft), so only Q cos(alpha) balances
        F_r; this reproduces Stribeck's Q_max = 4.37 F_r / (Z cos alpha).

        Parameters
        ----------
        radial_load_n : float
            Radial load F_r on the inner ring along the load line, N, finite and >= 0.
        stiffness : float, optional
            Load-deflection constant K of one element (both contacts in series),
            N/m^n, > 0. Default :meth:`hertz_stiffness`.
        clearance_m : float, optional
            Radial clearance c, m (negative = preload), finite. Default
            :attr:`radial_clearance_m`.
        cage_angle_deg : float, optional
            Position of element 0, degrees from the load line, finite. Default 0 (an
            element on the load line).

        Returns
        -------
        LoadDistribution
            Element angles (deg) and loads (N), shaft deflection (m), load-zone extent.

        Raises
        ------
        ValueError
            If an argument is not finite or out of range; the message names it.

        Notes
        -----
        Zero load with c >= 0 leaves the ring concentric and every load exactly zero.
        A preload (c < 0) at zero load loads every element with K (-c cos alpha)^n
        (full ring). Loads of separated elements are exactly 0.0.

        Examples
        --------
        >>> import ballpass as bp
        >>> ld = bp.Bearing.catalog("6205").load_distribution(1000.0)
        >>> ld.load_zone_half_angle_deg, ld.n_loaded
        (90.0, 5)
        >>> round(ld.q_max_n * 9 / 1000.0, 2)        # Stribeck: about 4.37 for many balls
        4.39
        """
        import numpy as np

        f_r = check_number("radial_load_n", radial_load_n, 0.0, unit="N")
        k = self.hertz_stiffness() if stiffness is None else check_number(
            "stiffness", stiffness, 0.0, lo_open=True, unit="N/m^n"
        )
        c = self.radial_clearance_m if clearance_m is None else check_number(
            "clearance_m", clearance_m, unit="m"
        )
        cage = check_number("cage_angle_deg", cage_angle_deg, unit="deg")
        n = self.load_exponent
        z = self.n_elements
        cos_a = math.cos(self.contact_angle_rad)

        angles_deg = np.mod(cage + 360.0 * np.arange(z) / z, 360.0)
        psi = np.radians(angles_deg)  # the reported angles are the ones used
        cpsi, spsi = np.cos(psi), np.sin(psi)

        def loads(x: float, y: float) -> np.ndarray:
            approach = (x * cpsi + y * spsi - c) * cos_a
            return k * np.maximum(approach, 0.0) ** n

        x = y = 0.0
        if f_r > 0.0:
            def fx(xx: float, yy: float) -> float:
                return cos_a * float(np.dot(loads(xx, yy), cpsi)) - f_r

            # deflection scale: the clearance plus the approach at which one element
            # would carry the whole load
            scale = abs(c) + (f_r / (k * cos_a ** (n + 1))) ** (1.0 / n)

            def x_of(yy: float) -> float:
                return _monotone_root(lambda xx: fx(xx, yy), scale + abs(yy))

            spacing = 360.0 / z
            offset = math.fmod(math.fmod(cage, spacing) + spacing, spacing)
            symmetric = any(
                abs(offset - s) <= 1e-9 * spacing for s in (0.0, 0.5 * spacing, spacing)
            )
            if symmetric:
                x = x_of(0.0)
            else:
                y = _monotone_root(
                    lambda yy: cos_a * float(np.dot(loads(x_of(yy), yy), spsi)), scale
                )
                x = x_of(y)

        q = loads(x, y)
        q.setflags(write=False)
        angles_deg.setflags(write=False)
        radial = math.hypot(x, y)
        if radial == 0.0:
            epsilon = math.inf if c < 0.0 else 0.0
            half_angle = 180.0 if c < 0.0 else 0.0
        else:
            epsilon = 0.5 * (1.0 - c / radial)
            half_angle = math.degrees(math.acos(min(1.0, max(-1.0, c / radial))))
        return LoadDistribution(
            element_angles_deg=angles_deg,
            element_loads_n=q,
            deflection_m=float(x),
            lateral_deflection_m=float(y),
            load_zone_half_angle_deg=half_angle,
            n_loaded=int(np.count_nonzero(q > 0.0)),
            epsilon=epsilon,
            q_max_n=float(q.max()),
            radial_load_n=f_r,
            clearance_m=float(c),
            stiffness=float(k),
            load_exponent=n,
        )

    def combined_load_distribution(self, radial_load_n: float,
                                   axial_load_n: float) -> CombinedLoadDistribution:
        """Ball loads and contact angles under a radial and an axial load (rigid rings).

        See :func:`ballpass._combined_load.combined_load_distribution` (Harris & Kotzalas
        ch. 7, Jones): under a pure axial load every ball carries F_a / (Z sin alpha),
        the contact angle alpha growing with the load; a radial load on top shifts the
        load zone (epsilon > 0.5, the whole ring from epsilon = 1).

        Parameters
        ----------
        radial_load_n, axial_load_n : float
            F_r and F_a, N, >= 0.

        Returns
        -------
        CombinedLoadDistribution

        Examples
        --------
        >>> import ballpass as bp
        >>> ld = bp.Bearing.catalog("6205").combined_load_distribution(500.0, 500.0)
        >>> bool(ld.epsilon > 1.0), int((ld.element_loads_n > 0).sum())   # whole ring
        (True, 9)
        """
        return combined_load_distribution(self, radial_load_n, axial_load_n)


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
        source="SKF 6004, Nabhan & Rashed (2020) Table 1",
    ),
    "ER-16K": dict(
        n_elements=9, element_diameter_mm=7.94, pitch_diameter_mm=39.32,
        source="MB ER-16K, Nakhaeinejad & Bryant (2011) Table 1 (pitch 39.32 mm from the "
               "race diameters)",
    ),
    "6208": dict(
        n_elements=9, element_diameter_mm=11.8872, pitch_diameter_mm=59.9948,
        source="SKF 6208, Tran, Furch & Cu Table 2",
    ),
    "6305": dict(
        n_elements=7, element_diameter_mm=11.0998, pitch_diameter_mm=43.4848,
        source="SKF 6305, Tran, Furch & Cu Table 2",
    ),
    "6306": dict(
        n_elements=8, element_diameter_mm=11.8872, pitch_diameter_mm=51.9938,
        source="SKF 6306, Tran, Furch & Cu Table 2",
    ),
    "6307": dict(
        n_elements=8, element_diameter_mm=13.4874, pitch_diameter_mm=57.4802,
        source="SKF 6307, Tran, Furch & Cu Table 2",
    ),
    "NU2204": dict(
        n_elements=11, element_diameter_mm=6.477, pitch_diameter_mm=33.4772,
        element="roller", roller_length_mm=8.0,
        source="SKF NU 2204, Tran, Furch & Cu Table 2 (roller length 8 mm assumed)",
    ),
    "3207": dict(
        n_elements=14, element_diameter_mm=10.3124, pitch_diameter_mm=53.4924,
        contact_angle_deg=30.0,
        source="SKF 3207 BN double-row angular contact, Tran, Furch & Cu Table 2 (14 balls over "
               "both rows, alpha = 30 deg; the planar models treat them as one row)",
    ),
    "NJ305": dict(
        n_elements=11, element_diameter_mm=9.25, pitch_diameter_mm=43.5,
        element="roller", roller_length_mm=11.0, radial_clearance_mm=0.125,
        source="NJ 305, the NJ 305 rotor paper section 2.1 (P_d = 0.25 mm diametral)",
    ),
    # The MFPT data set's test bearing (Bechhoefer, MFPT fault database, 2013): 8 elements
    # of 0.235 in on a 1.245 in pitch circle, contact angle 0. Its geometry gives FTF
    # 10.14 Hz at 25 Hz; the 14.8375 Hz stored in the data files contradicts their BPFO.
    "MFPT-NICE": dict(
        n_elements=8, element_diameter_mm=0.235 * 25.4, pitch_diameter_mm=1.245 * 25.4,
        source="NICE bearing of the MFPT fault data set (0.235 in elements, 1.245 in pitch)",
    ),
    # The XJTU-SY run-to-failure data set's test bearing (Wang, Lei, Li, Yan, IEEE Trans.
    # Reliability 69 (2020) 401-412, Table 2): 8 balls of 7.92 mm on a 34.55 mm pitch
    # circle, contact angle 0; its stated BPFO 107.91 Hz and BPFI 172.09 Hz at 35 Hz follow.
    "UER204": dict(
        n_elements=8, element_diameter_mm=7.92, pitch_diameter_mm=34.55,
        source="LDK UER204, XJTU-SY bearing data set (Wang et al. 2020, Table 2)",
    ),
    # The IMS (University of Cincinnati / NASA) run-to-failure rig's bearings (Qiu, Lee,
    # Lin, J. Sound Vib. 289 (2006) 1066-1090): Rexnord ZA-2115, two rows of 16 rollers
    # of 0.331 in on a 2.815 in pitch circle, contact angle 15.17 deg; BPFO 236.4 Hz at
    # 2000 rpm follows. The roller length is not published: point contact is assumed, so
    # its frequencies are exact and a simulation of it is indicative only.
    "ZA-2115": dict(
        n_elements=16, element_diameter_mm=0.331 * 25.4, pitch_diameter_mm=2.815 * 25.4,
        contact_angle_deg=15.17,
        source="Rexnord ZA-2115, IMS run-to-failure rig (Qiu et al. 2006; 16 rollers per "
               "row, the planar models treat one row; point contact assumed)",
    ),
}
