"""Waviness: distributed form errors of a race or of the rolling elements.

A wavy surface departs from its nominal circle by r(phi) = sum_q A_q cos(q phi + phase_q)
(q lobes round the circumference, amplitude A_q). In a bearing model it enters the
contact deflection of every element, delta_j = ... + r (Wrzochal & Adamczak's review section 4.4,
Liu &
Shao 2015 eq. 19; Sopanen & Mikkola 2003). Its known signature on a radially loaded
bearing with Z elements, shaft frequency f_s and cage frequency f_c (Wardle 1988,
Yhland 1992):

* outer race, order q = kZ +- 1: radial vibration at kZ f_c (k x BPFO);
* inner race, order q = kZ +- 1: radial vibration at kZ (f_s - f_c) +- f_s;
* ball, even order q: vibration at q f_b +- f_c (f_b the ball spin frequency).

Housing ovality is outer-race waviness of order 2: it pinches the ring, so elements
out of the load zone carry load too.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from ._validation import check_number

__all__ = ["Waviness", "WAVY_SURFACES"]

WAVY_SURFACES = ("outer", "inner", "ball")


def _as_tuple(name: str, values) -> tuple:
    if isinstance(values, (str, bytes)) or not isinstance(values, (Sequence, int, float)):
        raise TypeError(f"{name} must be a number or a sequence of numbers, got {values!r}")
    return tuple(values) if isinstance(values, Sequence) else (values,)


@dataclass(frozen=True)
class Waviness:
    """Waviness of one surface: a sum of cosine lobes, for ``Scene(waviness=...)``.

    Parameters
    ----------
    race : {"outer", "inner", "ball"}
        The wavy surface: the outer race (fixed), the inner race (turns with the shaft)
        or every rolling element (each ball with its own random phases, drawn from the
        scene's seed: balls are made one by one).
    orders : int or sequence of int
        Number of lobes q of each component round the circumference, >= 1 (q = 2 is an
        oval).
    amplitudes_um : float or sequence of float
        Amplitude A_q of each component, micrometres, in (0, 100]; one per order.
    phases_deg : float or sequence of float, optional
        Phase of each component, degrees (angle convention of :mod:`ballpass.scene`:
        on the outer race a lobe crest at 0 deg sits in the load zone). Default 0.

    Examples
    --------
    >>> import ballpass as bp
    >>> w = bp.Waviness("outer", orders=10, amplitudes_um=0.5)   # 6205: q = Z + 1
    >>> w.orders, w.amplitudes_um, w.phases_deg
    ((10,), (0.5,), (0.0,))
    """

    race: str
    orders: tuple
    amplitudes_um: tuple
    phases_deg: tuple | None = None

    def __post_init__(self) -> None:
        if self.race not in WAVY_SURFACES:
            raise ValueError(f"waviness race must be one of {WAVY_SURFACES}, got {self.race!r}")
        orders = _as_tuple("orders", self.orders)
        for q in orders:
            if isinstance(q, bool) or not isinstance(q, int) or not 1 <= q <= 1000:
                raise ValueError(f"waviness orders must be ints in [1, 1000], got {q!r}")
        amps = tuple(check_number("amplitudes_um", a, 0.0, 100.0, lo_open=True)
                     for a in _as_tuple("amplitudes_um", self.amplitudes_um))
        phases = ((0.0,) * len(orders) if self.phases_deg is None else
                  tuple(check_number("phases_deg", a, -1e6, 1e6)
                        for a in _as_tuple("phases_deg", self.phases_deg)))
        if not orders or len(amps) != len(orders) or len(phases) != len(orders):
            raise ValueError(
                f"waviness needs one amplitude (and phase) per order: orders={orders}, "
                f"amplitudes_um={amps}, phases_deg={phases}")
        object.__setattr__(self, "orders", orders)
        object.__setattr__(self, "amplitudes_um", amps)
        object.__setattr__(self, "phases_deg", phases)
