"""Elastohydrodynamic (EHL) lubricant film of a ball-raceway contact.

Liu & Shao (2015), as Wrzochal & Adamczak's review reports their model (its eq. 19),
add the lubricant film thicknesses at the inner and outer contacts to the contact
approach of every element:

    delta_j = x cos(theta_j) + y sin(theta_j) - C_r + Pi_j + h_ij + h_oj,

so a film acts as a loss of clearance: the rolling element meets the races h_i + h_o
earlier, and a loaded shaft sits that much higher. The film thickness here is Hamrock
& Dowson's (1977) regression for isothermal, fully flooded elliptical (point)
contacts, with the ellipticity of Hamrock & Brewe (1983):

    H = h / R_x,  U = eta_0 u / (E' R_x),  G = alpha E',  W = Q / (E' R_x^2),
    k = 1.0339 (R_y / R_x)^0.636,
    central: H_c = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k)),
    minimum: H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k)),

with R_x, R_y the effective radii along and across the rolling direction, E' =
E / (1 - nu^2) for two steel bodies (Hamrock's reduced modulus, twice Harris's), u the
mean entrainment speed of pure rolling, u = (d_p / 4)(1 - gamma^2)|omega_i - omega_o|
(gamma = d cos(alpha) / d_p; Harris & Kotzalas 2006, ch. 4 and 23). Liu & Shao use the
central film; the minimum film (at the exit constriction) is offered for comparison.
Point contacts only: a roller's line contact has other regressions (Pan & Hamrock
1989), not implemented.

Examples
--------
>>> import ballpass as bp
>>> from ballpass.lubrication import film_thickness_m
>>> h = film_thickness_m(bp.Bearing.catalog("6205"), "inner", load_n=200.0, rpm=1797)
>>> round(h * 1e6, 3)                                   # um, ISO VG 68 oil at 40 C
0.375
"""

from __future__ import annotations

import math

from ._validation import check_number
from .bearing import Bearing

__all__ = ["VISCOSITY_PA_S", "PRESSURE_VISCOSITY_PER_PA", "FILM_KINDS",
           "entrainment_speed", "film_thickness_m"]

#: dynamic viscosity at atmospheric pressure, Pa s: an ISO VG 68 mineral oil at 40 C
#: (68 mm^2/s by ISO 3448, density about 880 kg/m^3)
VISCOSITY_PA_S = 0.060
#: pressure-viscosity coefficient alpha of the Barus law, 1/Pa: a typical mineral oil
#: (2.2e-8 1/Pa; Hamrock, Schmid & Jacobson, Fundamentals of Machine Elements, 2004)
PRESSURE_VISCOSITY_PER_PA = 2.2e-8

#: film kind -> (coefficient, exponents of U, G, W, ellipticity factor (a, b) in
#: 1 - a exp(-b k)); Hamrock & Dowson 1977
FILM_KINDS = {
    "central": (2.69, 0.67, 0.53, -0.067, 0.61, 0.73),
    "minimum": (3.63, 0.68, 0.49, -0.073, 1.0, 0.68),
}


def entrainment_speed(bearing: Bearing, rpm: float) -> float:
    """Mean surface (entrainment) speed of pure rolling at either contact, m/s.

    u = (d_p / 4)(1 - gamma^2) omega for the inner ring turning at omega and the outer
    ring fixed, gamma = d cos(alpha) / d_p (Harris & Kotzalas 2006, ch. 4): the same
    at the inner and the outer contact.

    Parameters
    ----------
    bearing : Bearing
    rpm : float
        Shaft speed, rpm, >= 0.

    Returns
    -------
    float

    Examples
    --------
    >>> import ballpass as bp
    >>> round(entrainment_speed(bp.Bearing.catalog("6205"), 1797), 3)     # m/s
    1.761
    """
    rpm = check_number("rpm", rpm, 0.0)
    gamma = bearing.element_diameter_m * math.cos(bearing.contact_angle_rad) / (
        bearing.pitch_diameter_m)
    return 0.25 * bearing.pitch_diameter_m * (1.0 - gamma**2) * rpm * math.pi / 30.0


def film_thickness_m(bearing: Bearing, race: str, load_n: float, rpm: float, *,
                     viscosity_pa_s: float = VISCOSITY_PA_S,
                     pressure_viscosity_per_pa: float = PRESSURE_VISCOSITY_PER_PA,
                     kind: str = "central") -> float:
    """Hamrock-Dowson EHL film thickness of one ball-raceway contact, m.

    Parameters
    ----------
    bearing : Bearing
        A ball bearing (point contacts).
    race : {"inner", "outer"}
        Which contact.
    load_n : float
        Contact load Q, N, > 0 (the film thins only weakly with it, as Q^-0.067).
    rpm : float
        Shaft speed, rpm, >= 0 (inner ring turning, outer fixed); 0 gives no film.
    viscosity_pa_s : float, optional
        Lubricant dynamic viscosity at atmospheric pressure and the bearing's
        temperature, Pa s, > 0. Default :data:`VISCOSITY_PA_S` (ISO VG 68 at 40 C).
    pressure_viscosity_per_pa : float, optional
        Barus pressure-viscosity coefficient, 1/Pa, > 0. Default
        :data:`PRESSURE_VISCOSITY_PER_PA` (mineral oil).
    kind : {"central", "minimum"}, optional
        Central film (default; the one Liu & Shao 2015 add to the approach) or the
        minimum film at the exit constriction.

    Returns
    -------
    float

    Raises
    ------
    ValueError
        A roller bearing (line contact), an unknown ``race`` or ``kind``, or an
        argument out of range.

    Examples
    --------
    A 6205 at 1797 rpm, 200 N on the inner contact, ISO VG 68 at 40 C: a film of a
    third of a micrometre, thinner at its exit constriction:

    >>> import ballpass as bp
    >>> b = bp.Bearing.catalog("6205")
    >>> round(film_thickness_m(b, "inner", 200.0, 1797) * 1e6, 3)
    0.375
    >>> round(film_thickness_m(b, "inner", 200.0, 1797, kind="minimum") * 1e6, 3)
    0.303
    """
    if kind not in FILM_KINDS:
        raise ValueError(f"kind must be one of {sorted(FILM_KINDS)}, got {kind!r}")
    load_n = check_number("load_n", load_n, 0.0, lo_open=True, unit="N")
    eta = check_number("viscosity_pa_s", viscosity_pa_s, 0.0, lo_open=True, unit="Pa s")
    alpha = check_number("pressure_viscosity_per_pa", pressure_viscosity_per_pa, 0.0,
                         lo_open=True, unit="1/Pa")
    total, diff = bearing.contact_curvature(race)  # refuses rollers and unknown races
    r_x = 2.0 / (total * (1.0 + diff))   # 1/R_x = sum_rho (1 + F) / 2, rolling direction
    r_y = 2.0 / (total * (1.0 - diff))   # 1/R_y = sum_rho (1 - F) / 2, across the track
    e_red = bearing.youngs_modulus_pa / (1.0 - bearing.poisson_ratio**2)
    u = entrainment_speed(bearing, rpm)
    if u == 0.0:
        return 0.0
    coef, eu, eg, ew, a, b = FILM_KINDS[kind]
    ellipticity = 1.0339 * (r_y / r_x) ** 0.636
    h_dimensionless = (coef * (eta * u / (e_red * r_x)) ** eu * (alpha * e_red) ** eg
                       * (load_n / (e_red * r_x**2)) ** ew * (1.0 - a * math.exp(-b * ellipticity)))
    return h_dimensionless * r_x
