"""Ball loads under a combined radial and axial load (rigid rings; Harris & Kotzalas ch. 7).

A ball bearing carries an axial load through its contact angle, and the angle grows
with the load: the rings' groove curvature centres, A = (f_i + f_o - 1) d apart when
unloaded (A cos(alpha_0) = A - c with c the radial clearance), move apart by the
axial displacement delta_a and the radial displacement delta_r of the inner ring.
Ball j at psi_j from the load line is then compressed by

    a_j = A sin(alpha_0) + delta_a,   r_j = A cos(alpha_0) + delta_r cos(psi_j),
    s_j = hypot(a_j, r_j),   delta_j = s_j - A,   alpha_j = atan2(a_j, r_j),

carries Q_j = K max(delta_j, 0)^1.5 (K both contacts in series,
:meth:`ballpass.Bearing.hertz_stiffness`, taken at the nominal contact angle) and the
rings balance sum_j Q_j sin(alpha_j) = F_a, sum_j Q_j cos(alpha_j) cos(psi_j) = F_r
(Jones's rigid-ring equilibrium; the elements are symmetric about the load line: an
element on it, so the lateral balance holds by symmetry).

Under a pure axial load every ball carries Q = F_a / (Z sin(alpha)) at the angle alpha
of Harris's eq. F_a / (Z K A^1.5) = sin(alpha) (cos(alpha_0) / cos(alpha) - 1)^1.5; a
radial load on top shifts the load zone: Harris's load-distribution factor epsilon
exceeds 0.5 and reaches the whole ring (epsilon >= 1) when the axial share dominates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._contact import _load_zone_integral, _monotone_root
from ._validation import check_number

__all__ = ["CombinedLoadDistribution", "combined_load_distribution", "axial_integral"]


@dataclass(frozen=True, eq=False)
class CombinedLoadDistribution:
    """Ball loads and contact angles under a combined load.

    Attributes
    ----------
    element_angles_deg : numpy.ndarray, shape (Z,)
        Element positions, degrees from the load line.
    element_loads_n : numpy.ndarray, shape (Z,)
        Normal contact load Q_j, N (0.0 where separated).
    contact_angles_deg : numpy.ndarray, shape (Z,)
        Loaded contact angle alpha_j of every element, degrees.
    axial_deflection_m, radial_deflection_m : float
        delta_a and delta_r of the inner ring, m.
    epsilon : float
        Harris's load-distribution factor from the ball approaches fitted as
        delta_0 + delta_1 cos(psi): (delta_0 + delta_1) / (2 delta_1) (0.5 under a pure
        radial load at zero clearance, > 0.5 with axial load, inf under pure axial).
    q_max_n : float
        Largest element load, N.

    Examples
    --------
    >>> import ballpass as bp
    >>> ld = bp.Bearing.catalog("6205").combined_load_distribution(1000.0, 500.0)
    >>> bool(ld.epsilon > 0.5)             # the axial load spreads the load zone
    True
    >>> ld.element_loads_n.shape
    (9,)
    """

    element_angles_deg: np.ndarray
    element_loads_n: np.ndarray
    contact_angles_deg: np.ndarray
    axial_deflection_m: float
    radial_deflection_m: float
    epsilon: float
    q_max_n: float


def axial_integral(epsilon: float, load_exponent: float = 1.5) -> float:
    """Harris's axial load integral J_a(epsilon) of the continuous distribution.

    J_a = 1/(2 pi) int_{-psi_l}^{psi_l} [1 - (1 - cos psi)/(2 eps)]^n dpsi, with
    F_a = Z Q_max J_a sin(alpha) (Harris & Kotzalas ch. 7); psi_l = arccos(1 - 2 eps)
    (pi from eps = 1 on).

    Parameters
    ----------
    epsilon : float
        Load-distribution factor, > 0.
    load_exponent : float, optional
        n, 1.5 for balls. Default 1.5.

    Returns
    -------
    float

    Examples
    --------
    >>> from ballpass.bearing import axial_integral
    >>> round(axial_integral(0.5), 4)     # (1/pi) int_0^(pi/2) cos^1.5
    0.2782
    >>> round(axial_integral(1e9), 6)     # all balls alike
    1.0
    """
    return _load_zone_integral(epsilon, load_exponent, _axial_integrand)


def _axial_integrand(psi: float, eps: float, n: float) -> float:
    return max(1.0 - math.sin(0.5 * psi) ** 2 / eps, 0.0) ** n


def combined_load_distribution(bearing, radial_load_n: float, axial_load_n: float
                               ) -> CombinedLoadDistribution:
    """Rigid-ring equilibrium of a ball bearing under radial and axial load.

    Parameters
    ----------
    bearing : Bearing
        A ball bearing.
    radial_load_n : float
        F_r along the load line, N, >= 0.
    axial_load_n : float
        F_a, N, >= 0.

    Returns
    -------
    CombinedLoadDistribution

    Raises
    ------
    ValueError
        A roller bearing (its line contacts take no axial load here), a load not finite
        or negative, or a preloaded bearing (negative clearance).

    Examples
    --------
    >>> import ballpass as bp
    >>> ld = bp.Bearing.catalog("6205").combined_load_distribution(0.0, 900.0)
    >>> bool(abs(ld.element_loads_n.std()) < 1e-9 * ld.q_max_n)      # all balls alike
    True
    """
    f_r = check_number("radial_load_n", radial_load_n, 0.0, unit="N")
    f_a = check_number("axial_load_n", axial_load_n, 0.0, unit="N")
    if bearing.element != "ball":
        raise ValueError("axial_load_n needs a ball bearing: the line contacts of a roller "
                         "bearing carry no axial load in this model")
    c = bearing.radial_clearance_m
    if c < 0.0:
        raise ValueError(f"radial_clearance_mm must be >= 0 for a combined load, got "
                         f"{bearing.radial_clearance_mm!r}")
    d = bearing.element_diameter_m
    big_a = (bearing.inner_conformity + bearing.outer_conformity - 1.0) * d
    if bearing.contact_angle_deg > 0.0:   # angular contact: the nominal angle is given
        alpha_0 = bearing.contact_angle_rad
    else:                                 # deep groove: the clearance sets it (Harris)
        alpha_0 = math.acos(1.0 - c / big_a)
    a_sin0, a_cos0 = big_a * math.sin(alpha_0), big_a * math.cos(alpha_0)
    k = bearing.hertz_stiffness()
    z = bearing.n_elements
    psi = 2.0 * math.pi * np.arange(z) / z
    cpsi = np.cos(psi)

    def state(da: float, dr: float):
        ax = a_sin0 + da
        rad = a_cos0 + dr * cpsi
        s = np.hypot(ax, rad)
        q = k * np.maximum(s - big_a, 0.0) ** 1.5
        return q, np.arctan2(ax, rad)

    def axial_residual(da: float, dr: float) -> float:
        q, alpha = state(da, dr)
        return float(np.dot(q, np.sin(alpha))) - f_a

    scale = (max(f_r, f_a, 1e-9) / (k * z / 4)) ** (2.0 / 3.0) + c

    def da_of(dr: float) -> float:
        if f_a == 0.0 and a_sin0 == 0.0:
            return 0.0        # symmetric grooves: no axial reaction at delta_a = 0
        return _monotone_root(lambda da: axial_residual(da, dr), scale)

    dr = 0.0
    if f_r > 0.0:
        def radial_residual(r: float) -> float:
            q, alpha = state(da_of(r), r)
            return float(np.dot(q * np.cos(alpha), cpsi)) - f_r
        dr = _monotone_root(radial_residual, scale)
    da = da_of(dr)
    q, alpha = state(da, dr)
    # Harris's epsilon from the approach delta(psi) = delta_0 + delta_1 cos(psi) (least
    # squares over every ball, separated ones included: geometric, not loads):
    # delta_max [1 - (1 - cos psi) / (2 eps)] gives eps = (delta_0 + delta_1) / (2 delta_1)
    approach = np.hypot(a_sin0 + da, a_cos0 + dr * cpsi) - big_a
    (d0, d1), *_ = np.linalg.lstsq(np.column_stack([np.ones(z), cpsi]), approach, rcond=None)
    eps = math.inf if dr == 0.0 or d1 <= 0.0 else float((d0 + d1) / (2.0 * d1))
    return CombinedLoadDistribution(
        element_angles_deg=np.degrees(psi), element_loads_n=q,
        contact_angles_deg=np.degrees(alpha), axial_deflection_m=float(da),
        radial_deflection_m=float(dr), epsilon=eps, q_max_n=float(q.max()))
