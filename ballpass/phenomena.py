"""The vocabulary of physical phenomena a scene can ask for and a model can represent.

"Model only what a scene needs": every simulation model declares the phenomena it
represents (``ballpass.simulate.MODELS[name].represents``), every scene the phenomena
it needs (:func:`ballpass.simulate.scene_needs`), and ``model="auto"`` runs the cheapest
model whose phenomena cover the needs. This module holds the one vocabulary both sides
use; it imports nothing heavy so that :class:`~ballpass.Scene` can validate
``needs=`` at construction.

Examples
--------
>>> from ballpass.phenomena import PHENOMENA, check_needs
>>> sorted(check_needs(("envelope",)))
['envelope']
>>> "gear_mesh" in PHENOMENA
True
"""

from __future__ import annotations

from collections.abc import Iterable

__all__ = ["PHENOMENA", "DEFAULT_NEEDS", "check_needs"]

#: phenomenon name -> what a model that represents it reproduces
PHENOMENA: dict[str, str] = {
    "envelope": "fault impacts at the kinematic rates with random slip, load-zone "
                "modulation, structural resonances and the transmission path to each "
                "sensor: the envelope-level signature a diagnosis reads",
    "contact_dynamics": "Hertz (or line) contacts, clearance non-linearity, varying "
                        "compliance at the element-pass rate, entry into and exit from "
                        "defects as changes of the contact geometry",
    "contact_forces": "per-element contact forces as an output (ground truth)",
    "varying_speed": "a shaft speed that changes during the scene (run-up, run-down)",
    "waviness": "race and element waviness (distributed form errors)",
    "ball_dynamics": "every rolling element a body: cage speed, slip, traction, "
                     "centrifugal and gyroscopic loads from the physics, not prescribed",
    "gear_mesh": "a gear pair on the shaft: time-varying mesh stiffness, transmission "
                 "error, gear faults",
    "rotor_dynamics": "the rotor's own non-linear response: unbalance, clearance-driven "
                      "periodic, quasi-periodic and chaotic motion",
    "mounted_clearance": "a mounted clearance or preload that replaces the catalogue "
                         "bearing's (Scene(clearance_um=...)): the load zone it shapes",
    "structural_modes": "several structural modes in the transmission path beside the "
                        "main resonance (Scene(resonances=...))",
    "pit_faults": "round EDM pits narrower than the contact ellipse, which unload the "
                  "contact only partly (Fault(geometry='pit'))",
    "ehl_film": "the elastohydrodynamic lubricant film of Liu & Shao (2015): its "
                "thickness at the inner and outer contacts adds to every contact "
                "approach (Scene(needs=(..., 'ehl_film')))",
    "ball_race_sprung_mass": "Nabhan & Rashed (2020)'s lumped degrees of freedom: inner "
                             "race, a ball coordinate between the races and outer race "
                             "on their own springs, and a 2.1 kHz sprung mass, with the "
                             "paper's parameter table",
    "axial_load": "an axial (thrust) load on a ball bearing (Scene(axial_load_n=...)): "
                  "contact angles that grow with it and a load zone that widens to the "
                  "whole ring",
    "intermittent_faults": "ball defects that meet the races on some revolutions only, "
                           "as a ball's spin axis wanders (Fault(engagement<1) or "
                           "Fault(spin_drift_deg>0))",
}

#: what a scene that states no needs asks for: the envelope signature (with its
#: resonance) and the contact dynamics that produce it
DEFAULT_NEEDS = frozenset({"envelope", "contact_dynamics"})


def check_needs(needs: Iterable[str] | str, name: str = "needs") -> frozenset[str]:
    """Validate phenomenon names and return them as a frozenset.

    Parameters
    ----------
    needs : str or iterable of str
        Names from :data:`PHENOMENA`.
    name : str, optional
        Argument name used in error messages.

    Returns
    -------
    frozenset of str

    Raises
    ------
    TypeError
        ``needs`` is not a string or an iterable of strings.
    ValueError
        A name is not in the vocabulary; the message lists the allowed ones.

    Examples
    --------
    >>> from ballpass.phenomena import check_needs
    >>> sorted(check_needs(["envelope", "contact_forces"]))
    ['contact_forces', 'envelope']
    >>> check_needs("envelop")                              # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    ValueError: needs names an unknown phenomenon 'envelop'; allowed: axial_load, ...
    """
    if isinstance(needs, str):
        needs = (needs,)
    try:
        items = tuple(needs)
    except TypeError:
        raise TypeError(f"{name} must be a phenomenon name or a sequence of them, "
                        f"got {needs!r}") from None
    for item in items:
        if not isinstance(item, str):
            raise TypeError(f"{name} must hold phenomenon names (str), got {item!r}")
        if item not in PHENOMENA:
            raise ValueError(f"{name} names an unknown phenomenon {item!r}; allowed: "
                             f"{', '.join(sorted(PHENOMENA))}")
    return frozenset(items)
