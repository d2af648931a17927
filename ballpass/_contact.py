"""Hertz contact stiffness and the quasi-static (Stribeck) load distribution of a
rolling-element bearing; :mod:`ballpass.bearing` re-exports the public names.

Plain quasi-static contact mechanics; scipy is imported only inside the functions
that need it, so ``import ballpass`` stays cheap.

References
----------
.. [1] T. A. Harris, M. N. Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed.,
   CRC Press, 2006 (ch. 6 Hertz contact: curvature sum and difference, the
   dimensionless factors a*, b*, delta*; ch. 7 Stribeck load distribution, J_r(eps)).
.. [2] M. Nakhaeinejad, M. D. Bryant, "Dynamic modeling of rolling element bearings with
   surface contact defects using bond graphs", J. Tribology 133 (2011) 011102,
   eqs. (6)-(8): Harris point-contact stiffness, curvature sum and difference. Its
   printed "2E2" is 2*sqrt(2)*E, and its delta* polynomial is a chart fit good to 3 %
   only for F(rho) in [0.9, 0.99]; here delta* comes from the elliptic integrals instead.
.. [3] Nabhan & Rashed (2020) (MSC-ADAMS inner-race paper), eq. (2) series combination of
   the inner and outer contacts, eq. (3) Harris stiffness, eqs. (4)-(10) Stribeck
   distribution (eq. 10: Q_max = 4.37 F_r / (Z cos alpha)).
.. [4] A. Palmgren, *Ball and Roller Bearing Engineering*, 1959: line contact
   delta = 3.84e-5 Q^0.9 / l^0.8 (mm, N, mm), as used by the NJ 305 rotor paper, eq. (1).
.. [5] K. L. Johnson, *Contact Mechanics*, CUP 1985, sec. 4.2 (elliptical contact in
   Carlson's form), and DLMF 19.25.1 (K - E and E - k'^2 K through R_D).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from ._validation import check_number

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np

__all__ = [
    "HertzFactors",
    "LoadDistribution",
    "hertz_factors",
    "point_contact_stiffness",
    "line_contact_stiffness",
    "series_stiffness",
    "stribeck_integral",
    "stribeck_qmax",
]

def _monotone_root(func, scale: float) -> float:
    """Root of a continuous non-decreasing ``func`` by bracketing and Brent's method.

    The bracket starts at [-scale, scale] and doubles outward until it straddles zero.
    """
    from scipy.optimize import brentq

    scale = scale if scale > 0.0 else 1e-9
    lo, hi = -scale, scale
    f_hi = func(hi)
    for _ in range(200):
        if f_hi >= 0.0:
            break
        lo, hi = hi, 2.0 * hi
        f_hi = func(hi)
    else:  # pragma: no cover - the contact force grows without bound
        raise RuntimeError("could not bracket the equilibrium from above")
    f_lo = func(lo)
    for _ in range(200):
        if f_lo <= 0.0:
            break
        hi, lo = lo, 2.0 * lo if lo < 0.0 else -scale
        f_lo = func(lo)
    else:  # pragma: no cover
        raise RuntimeError("could not bracket the equilibrium from below")
    if f_hi == 0.0:
        return hi
    if f_lo == 0.0:
        return lo
    return float(brentq(func, lo, hi, xtol=1e-18 * scale, rtol=1e-15, maxiter=500))


# ---------------------------------------------------------------------- Hertz contact
@dataclass(frozen=True)
class HertzFactors:
    """Dimensionless Hertz point-contact factors (the exact "Harris chart").

    Attributes
    ----------
    curvature_difference : float
        F(rho), the input, in [0, 1).
    kappa : float
        Ellipticity a/b of the contact ellipse, >= 1.
    a_star, b_star : float
        Semi-axis factors: a = a* (3 Q / (2 sum_rho E'))^(1/3), likewise b.
    delta_star : float
        Deflection factor: delta = delta* (3 Q / (2 sum_rho E'))^(2/3) sum_rho / 2,
        with 1/E' = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2. Equal to 1 for a circular
        contact (F(rho) = 0).

    Examples
    --------
    >>> from ballpass.bearing import hertz_factors
    >>> h = hertz_factors(0.9)                   # a conforming ball-race contact
    >>> h.kappa > 1.0, round(h.a_star * h.b_star, 3)
    (True, 1.425)
    """

    curvature_difference: float
    kappa: float
    a_star: float
    b_star: float
    delta_star: float


def hertz_factors(curvature_difference: float) -> HertzFactors:
    """Exact Hertz factors kappa, a*, b*, delta* from the curvature difference F(rho).

    Harris & Kotzalas (module reference 1) ch. 6: with e^2 = m = 1 - 1/kappa^2, K and E the complete
    elliptic integrals of the first and second kind,
    F(rho) = [(kappa^2 + 1) E - 2 K] / [(kappa^2 - 1) E],
    delta* = (2 K / pi) (pi / (2 kappa^2 E))^(1/3), a* = (2 kappa^2 E / pi)^(1/3),
    b* = (2 E / (pi kappa))^(1/3). The first relation cancels to second order near the
    circular contact, so it is solved in Carlson's form (Johnson, module reference 6, DLMF 19.25.1):
    (1 + F)/(1 - F) = R_D(0, 1, p) / R_D(0, p, 1) with p = 1/kappa^2, for ln p by
    :func:`scipy.optimize.brentq`. This replaces Nakhaeinejad & Bryant's delta* polynomial, which
    follows the chart within 3 % only for F(rho) in [0.9, 0.99] (it is 7 % off at 0.88,
    23 % at 0.85, 5 % at 0.995, and meaningless outside).

    Parameters
    ----------
    curvature_difference : float
        F(rho), dimensionless, in [0, 1). 0 is a circular contact; F -> 1 tends to a
        line contact.

    Returns
    -------
    HertzFactors

    Examples
    --------
    >>> from ballpass.bearing import hertz_factors
    >>> hertz_factors(0.0).delta_star
    1.0
    >>> h = hertz_factors(0.9)
    >>> round(h.kappa, 3), round(h.delta_star, 4)
    (6.713, 0.6799)
    """
    from scipy.optimize import brentq
    from scipy.special import ellipe, ellipkm1, elliprd

    f = check_number("curvature_difference", curvature_difference, 0.0)
    if f >= 1.0:
        raise ValueError(
            f"curvature_difference must be in [0, 1) (1 is a line contact), got {f!r}"
        )
    if f == 0.0:
        p = 1.0
    else:
        target = math.log1p(f) - math.log1p(-f)

        def residual(log_p: float) -> float:
            pp = math.exp(log_p)
            return math.log(elliprd(0.0, 1.0, pp)) - math.log(elliprd(0.0, pp, 1.0)) - target

        log_p_min = math.log(1e-200)
        if residual(log_p_min) < 0.0:
            raise ValueError(
                f"curvature_difference={f!r} is too close to 1 (contact ellipse longer than "
                "1e100 times its width); treat it as a line contact"
            )
        p = math.exp(brentq(residual, log_p_min, 0.0, xtol=1e-15, rtol=1e-15, maxiter=500))
    k_int = float(ellipkm1(p))
    e_int = float(ellipe(1.0 - p))
    kappa = 1.0 / math.sqrt(p)
    return HertzFactors(
        curvature_difference=f,
        kappa=kappa,
        a_star=(2.0 * e_int / (math.pi * p)) ** (1.0 / 3.0),
        b_star=(2.0 * e_int / (math.pi * kappa)) ** (1.0 / 3.0),
        delta_star=(2.0 * k_int / math.pi) * (math.pi * p / (2.0 * e_int)) ** (1.0 / 3.0),
    )


def point_contact_stiffness(
    curvature_sum_per_m: float,
    curvature_difference: float,
    youngs_modulus_pa: float = 2.075e11,
    poisson_ratio: float = 0.3,
) -> float:
    """Hertz load-deflection constant of one point contact between like materials.

    Harris & Kotzalas (module reference 1) ch. 6, Nakhaeinejad & Bryant (2011) eq. 6 (printed
    "2E2", read 2 sqrt(2) E),
    Nabhan & Rashed (2020) eq. 3: K = 2 sqrt(2) E / (3 (1 - nu^2)) sum_rho^(-1/2) delta*^(-3/2), so
    that Q = K delta^1.5. With E = 2.075e5 MPa and nu = 0.3 the prefactor is Harris's
    2.15e5 (N/mm^1.5 with sum_rho in 1/mm). delta* comes from :func:`hertz_factors`.

    Parameters
    ----------
    curvature_sum_per_m : float
        Sum_rho, 1/m, > 0.
    curvature_difference : float
        F(rho), in [0, 1).
    youngs_modulus_pa : float, optional
        E of both bodies, Pa. Default 2.075e11 (bearing steel).
    poisson_ratio : float, optional
        nu of both bodies, in [0, 0.5). Default 0.3.

    Returns
    -------
    float
        K, N/m^1.5.

    Examples
    --------
    A 10 mm steel ball on a flat (sum_rho = 4/d, F(rho) = 0) gives the textbook
    (4/3) E* sqrt(R) with E* = E / (2 (1 - nu^2)):

    >>> from ballpass.bearing import point_contact_stiffness
    >>> k = point_contact_stiffness(4 / 0.010, 0.0)
    >>> e_star = 2.075e11 / (2 * (1 - 0.3**2))
    >>> round(k / (4 / 3 * e_star * 0.005**0.5), 12)
    1.0
    """
    s = check_number("curvature_sum_per_m", curvature_sum_per_m, 0.0, lo_open=True, unit="1/m")
    e = check_number("youngs_modulus_pa", youngs_modulus_pa, 0.0, lo_open=True, unit="Pa")
    nu = check_number("poisson_ratio", poisson_ratio, 0.0)
    if nu >= 0.5:
        raise ValueError(f"poisson_ratio must be in [0, 0.5), got {nu!r}")
    delta_star = hertz_factors(curvature_difference).delta_star
    return 2.0 * math.sqrt(2.0) * e / (3.0 * (1.0 - nu * nu)) / math.sqrt(s) / delta_star**1.5


#: Palmgren's line-contact coefficient, mm N^-0.9 mm^0.8 (delta = C Q^0.9 / l^0.8).
PALMGREN_COEFFICIENT = 3.84e-5


def line_contact_stiffness(length_m: float) -> float:
    """Palmgren's load-deflection constant of one roller-raceway line contact.

    Palmgren (module reference 5; the NJ 305 rotor paper eq. 1): delta = 3.84e-5 Q^0.9 / l^0.8 with
    delta and l in
    mm and Q in N, for bearing steel. Inverted: Q = K delta^(10/9) with
    K = (l^0.8 / 3.84e-5)^(10/9) N/mm^(10/9), returned in SI (times 1000^(10/9)).

    Parameters
    ----------
    length_m : float
        Effective roller length l, m, > 0.

    Returns
    -------
    float
        K, N/m^(10/9).

    Examples
    --------
    >>> from ballpass.bearing import line_contact_stiffness
    >>> f"{line_contact_stiffness(0.011):.3e}"
    '1.463e+09'
    """
    length_mm = check_number("length_m", length_m, 0.0, lo_open=True, unit="m") * 1e3
    n = 10.0 / 9.0
    k_mm = (length_mm**0.8 / PALMGREN_COEFFICIENT) ** n
    return k_mm * 1e3**n


def series_stiffness(k_inner: float, k_outer: float, load_exponent: float) -> float:
    """Two power-law contacts Q = K delta^n in series (Nabhan & Rashed (2020) eq. 2).

    Both carry the same load Q and their approaches add, so
    K = [1 / ((1/K_i)^(1/n) + (1/K_o)^(1/n))]^n.

    Parameters
    ----------
    k_inner, k_outer : float
        Constants of the two contacts, N/m^n, > 0.
    load_exponent : float
        n (1.5 for point, 10/9 for line contact), > 0.

    Returns
    -------
    float
        Combined constant, N/m^n.

    Examples
    --------
    >>> from ballpass.bearing import series_stiffness
    >>> series_stiffness(1.0, 1.0, 1.5) == 2.0 ** -1.5
    True
    """
    ki = check_number("k_inner", k_inner, 0.0, lo_open=True, unit="N/m^n")
    ko = check_number("k_outer", k_outer, 0.0, lo_open=True, unit="N/m^n")
    n = check_number("load_exponent", load_exponent, 0.0, lo_open=True)
    return (1.0 / (ki ** (-1.0 / n) + ko ** (-1.0 / n))) ** n


# ---------------------------------------------------------------------- Stribeck
def stribeck_integral(epsilon: float, load_exponent: float = 1.5) -> float:
    """Harris's radial load integral J_r(epsilon) of the continuous Stribeck distribution.

    Harris & Kotzalas (module reference 1) ch. 7; Nabhan & Rashed (2020) eqs. 5, 8, 9: for
    infinitely many
    elements,
    Q(psi) = Q_max [1 - (1 - cos psi)/(2 eps)]^n inside the zone ``|psi| <= psi_l`` with
    psi_l = arccos(1 - 2 eps) (pi when eps >= 1), and F_r = Z Q_max J_r cos(alpha) with

    J_r(eps) = 1/(2 pi) int_{-psi_l}^{psi_l} [1 - (1 - cos psi)/(2 eps)]^n cos psi dpsi.

    Parameters
    ----------
    epsilon : float
        Load-distribution factor eps = (1 - c / delta_r) / 2, > 0 (0.5 at zero clearance,
        > 0.5 with preload, >= 1 for a full ring).
    load_exponent : float, optional
        n, 1.5 for balls, 10/9 for rollers. Default 1.5.

    Returns
    -------
    float
        J_r, dimensionless.

    Examples
    --------
    >>> from ballpass.bearing import stribeck_integral
    >>> round(1 / stribeck_integral(0.5), 2)      # Stribeck's 4.37
    4.37
    """
    return _load_zone_integral(epsilon, load_exponent, _radial_integrand)


def _radial_integrand(psi: float, eps: float, n: float) -> float:
    drop = math.sin(0.5 * psi) ** 2 / eps  # (1 - cos psi) / (2 eps), without cancellation
    if eps >= 1.0:
        # full ring: the integral of cos over [0, pi] vanishes, so integrate
        # (g^n - 1) cos psi, which keeps its accuracy as eps -> inf (J_r ~ n / (4 eps))
        return math.expm1(n * math.log1p(-drop)) * math.cos(psi) if drop < 1.0 else (
            -math.cos(psi)
        )
    return max(1.0 - drop, 0.0) ** n * math.cos(psi)


def _load_zone_integral(epsilon: float, load_exponent: float, integrand) -> float:
    """Harris's load integrals: ``(1/pi) int_0^psi_l integrand(psi, eps, n) dpsi``.

    The radial (:func:`stribeck_integral`) and axial (:func:`axial_integral`) integrals
    share the checks of their arguments, the load zone ``psi_l = arccos(1 - 2 eps)``
    (pi when eps >= 1) and the quadrature (relative tolerance 1e-12); the integrand,
    even in psi, is integrated over half the zone.

    Parameters
    ----------
    epsilon : float
        Load-distribution factor eps, > 0.
    load_exponent : float
        n, > 0 (1.5 for balls, 10/9 for rollers).
    integrand : callable
        ``integrand(psi, eps, n) -> float``, psi in rad.

    Returns
    -------
    float
        The integral, dimensionless.
    """
    from scipy.integrate import quad

    eps = check_number("epsilon", epsilon, 0.0, lo_open=True)
    n = check_number("load_exponent", load_exponent, 0.0, lo_open=True)
    limit = math.pi if eps >= 1.0 else math.acos(1.0 - 2.0 * eps)
    value, _ = quad(integrand, 0.0, limit, args=(eps, n), epsabs=0.0, epsrel=1e-12,
                    limit=200)
    return value / math.pi


def stribeck_qmax(
    radial_load_n: float,
    n_elements: int,
    *,
    epsilon: float = 0.5,
    load_exponent: float = 1.5,
    contact_angle_deg: float = 0.0,
) -> float:
    """Closed-form Stribeck maximum element load Q_max = F_r / (Z J_r(eps) cos alpha), N.

    At zero clearance (eps = 0.5) and n = 1.5 this is Nabhan & Rashed (2020) eq. 10,
    Q_max = 4.37 F_r / (Z cos alpha); for rollers (n = 10/9) the constant is about
    4.08. It is the many-element limit: a finite bearing's exact value
    (:meth:`Bearing.load_distribution`) differs by the discreteness of the sum (0.4 %
    for 9 balls with one on the load line). Stribeck's design rule 5 F_r / Z adds an
    allowance for clearance.

    Parameters
    ----------
    radial_load_n : float
        F_r, N, >= 0.
    n_elements : int
        Z, >= 1.
    epsilon : float, optional
        Load-distribution factor (see :func:`stribeck_integral`). Default 0.5.
    load_exponent : float, optional
        n. Default 1.5.
    contact_angle_deg : float, optional
        alpha, degrees in [0, 90). Default 0.

    Returns
    -------
    float
        Q_max, N.

    Examples
    --------
    >>> from ballpass.bearing import stribeck_qmax
    >>> round(stribeck_qmax(1000.0, 9), 1)       # 4.37 * 1000 / 9
    485.6
    """
    f_r = check_number("radial_load_n", radial_load_n, 0.0, unit="N")
    if isinstance(n_elements, bool) or not isinstance(n_elements, int) or n_elements < 1:
        raise ValueError(f"n_elements must be an int >= 1, got {n_elements!r}")
    alpha = check_number("contact_angle_deg", contact_angle_deg, 0.0, unit="deg")
    if alpha >= 90.0:
        raise ValueError(f"contact_angle_deg must be in [0, 90), got {alpha!r}")
    j_r = stribeck_integral(epsilon, load_exponent)
    return f_r / (n_elements * j_r * math.cos(math.radians(alpha)))


@dataclass(frozen=True, eq=False)
class LoadDistribution:
    """Quasi-static load distribution of a radially loaded bearing (from
    :meth:`Bearing.load_distribution`).

    Attributes
    ----------
    element_angles_deg : numpy.ndarray, shape (Z,)
        Angular position of each element, degrees from the load line, in [0, 360).
    element_loads_n : numpy.ndarray, shape (Z,)
        Normal contact load Q_j of each element, N (exactly 0.0 where separated).
    deflection_m : float
        Inner-ring displacement along the load line, m.
    lateral_deflection_m : float
        Inner-ring displacement perpendicular to the load line (+90 deg), m; 0 when the
        element layout is symmetric about the load line.
    load_zone_half_angle_deg : float
        Continuous Stribeck extent psi_l = arccos(c / delta_r), delta_r the total radial
        displacement, clipped to [0, 180] deg (180 = full ring). The zone is centred on
        the load line, or at atan2(lateral, deflection) when the ring also moved sideways.
    n_loaded : int
        Number of elements with Q_j > 0.
    epsilon : float
        Stribeck load-distribution factor eps = (1 - c/delta_r)/2 (0.5 at zero
        clearance; 0 when nothing is loaded; inf for a preloaded ring at zero load).
    q_max_n : float
        Largest element load, N.
    radial_load_n, clearance_m, stiffness, load_exponent : float
        The inputs: F_r (N), c (m), K (N/m^n), n.

    Examples
    --------
    >>> import ballpass as bp
    >>> ld = bp.Bearing.catalog("6205").load_distribution(1000.0)
    >>> ld.element_loads_n.shape, ld.n_loaded
    ((9,), 5)
    >>> round(float(ld.element_loads_n.sum()), 1) > 1000.0  # the loads' projections balance F_r
    True
    """

    element_angles_deg: np.ndarray
    element_loads_n: np.ndarray
    deflection_m: float
    lateral_deflection_m: float
    load_zone_half_angle_deg: float
    n_loaded: int
    epsilon: float
    q_max_n: float
    radial_load_n: float
    clearance_m: float
    stiffness: float
    load_exponent: float
