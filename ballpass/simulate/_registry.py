"""The model registry: what each simulation model represents, costs and accepts.

A model plugs in with one file that builds a :class:`Model` and one line in
:mod:`ballpass.simulate` that lists it; ``model="auto"`` then considers it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..phenomena import PHENOMENA
from ..scene import Scene

__all__ = ["Model"]


@dataclass(frozen=True)
class Model:
    """One simulation model of the hierarchy.

    Attributes
    ----------
    name : str
        Registry key, e.g. ``"sr5"``.
    description : str
        One line: what the model is.
    represents : frozenset of str
        Phenomena (names in :data:`ballpass.phenomena.PHENOMENA`) the model reproduces.
    relative_cost : float
        Wall time per simulated second relative to ``sr5`` (= 1) on the reference
        scene of ``benchmarks/models_cost.py``, which measures it.
    solvers : tuple of str
        Solvers the model supports; the first is its default.
    fixed_step_solvers : tuple of str
        Those of ``solvers`` that take a step ``dt`` (the others take ``rtol``).
    reference : str
        The paper(s) the model follows.
    accepts : callable
        ``accepts(scene) -> str | None``: ``None`` when the model can take the scene,
        otherwise the reason it cannot (bearing type, sensors, speed profile ...).
    run : callable
        ``run(scene, solver, *, dt, rtol, atol, params, return_forces, oversample)``
        -> :class:`~ballpass.simulate.SimulationResult`; ``solver`` is resolved (never
        ``"auto"``) and every argument has been validated.

    Examples
    --------
    >>> from ballpass.simulate import MODELS
    >>> m = MODELS["impulse"]
    >>> m.name, m.default_solver, sorted(m.represents)
    ('impulse', 'analytic', ['envelope', 'intermittent_faults', 'varying_speed'])
    """

    name: str
    description: str
    represents: frozenset
    relative_cost: float
    solvers: tuple[str, ...]
    fixed_step_solvers: tuple[str, ...]
    reference: str
    accepts: Callable[[Scene], str | None]
    run: Callable

    def __post_init__(self) -> None:
        unknown = set(self.represents) - set(PHENOMENA)
        if unknown:
            raise ValueError(f"model {self.name!r} represents unknown phenomena {sorted(unknown)}")
        if not self.solvers or not set(self.fixed_step_solvers) <= set(self.solvers):
            raise ValueError(f"model {self.name!r}: fixed_step_solvers must be among solvers")
        if not self.relative_cost > 0:
            raise ValueError(f"model {self.name!r}: relative_cost must be > 0")

    @property
    def default_solver(self) -> str:
        """The solver ``solver="auto"`` runs."""
        return self.solvers[0]

    def covers(self, needs: frozenset) -> bool:
        """Whether the model represents every phenomenon in ``needs``.

        Examples
        --------
        >>> from ballpass.simulate import MODELS
        >>> MODELS["sr5"].covers(frozenset({"envelope"}))
        True
        >>> MODELS["impulse"].covers(frozenset({"contact_forces"}))
        False
        """
        return needs <= self.represents

    def __repr__(self) -> str:
        return (f"Model({self.name!r}, cost={self.relative_cost:g}, "
                f"represents={sorted(self.represents)})")
