"""Simulate bearing vibration with exact ground truth: "model only what a scene needs".

:func:`simulate` runs a :class:`~ballpass.Scene` through one of the models in
:data:`MODELS` and returns a :class:`SimulationResult`. Each model declares the
phenomena it represents (vocabulary: :data:`ballpass.phenomena.PHENOMENA`) and its cost
relative to ``sr5``; :func:`scene_needs` says what a scene asks for, and
``model="auto"`` (:func:`resolve_model`) runs the cheapest model that can take the
scene and covers its needs, recording why in ``res.info["model_reason"]``.

Models (the table behind ``auto``: ``python -m ballpass bearings`` lists bearings,
:func:`model_table` the models):

``sr5``
    Sawalhi & Randall (2008) bearing-pedestal model with a high-frequency resonator per
    sensor: shaft x/y, pedestal x/y, resonator(s) (see :mod:`.sr5`,
    :mod:`._sr5_driver`). What a plain scene runs.
``impulse``
    Phenomenological impulse trains (McFadden & Smith 1984, Ho & Randall 2000) with
    sr5's kinematics and slip, the Stribeck load zone and the resonance (see
    :mod:`.impulse`): the envelope signature only, at a tenth of sr5's cost.
``sr4``
    The same without the resonator: the sensors read the housing acceleration.
``rotor2``
    The NJ 305 rotor paper's rigid rotor on a cylindrical roller bearing (Palmgren line contacts,
    clearance, unbalance, defects), Newmark-beta by default (see :mod:`.rotor2`): the
    non-linear rotor dynamics for Poincare sections and bifurcation diagrams
    (:mod:`ballpass.dynamics`).
``multibody``
    Nakhaeinejad & Bryant (2011, Nakhaeinejad & Bryant (2011)): every ball a body with traction,
    slip and
    centrifugal load (see :mod:`.multibody`). What scenes that need ``ball_dynamics``
    run.
``gearbox``
    A gear pair (Tran, Furch & Cu) whose pinion sits on the bearing's shaft, coupled to the sr5
    bearing-pedestal model (see :mod:`.gearbox`); what a scene with ``gears`` runs.
``nabhan2020``
    Nabhan & Rashed (2020)'s lumped model with its parameter table: inner race, ball
    coordinate, outer race, 2.1 kHz sprung mass, sharp notch, no slip (see
    :mod:`.nabhan2020`); runs only when asked for (``model="nabhan2020"`` or a scene
    that needs ``ball_race_sprung_mass``).

A new model is one file that builds a :class:`Model` and one line in :data:`MODELS`.
"""

from __future__ import annotations

import logging
import sys
import time
import types

import numpy as np

from ._cache import clear_stale_cache, has_compiled_kernels, source_fingerprint

# before any kernel module is imported: numba must not load kernels compiled from
# other sources (see ._cache)
clear_stale_cache()

from ..phenomena import DEFAULT_NEEDS, PHENOMENA  # noqa: E402
from ..scene import Scene  # noqa: E402
from ._registry import Model  # noqa: E402
from ._shared import OVERSAMPLE, SimulationUnstableError, check_solver_args  # noqa: E402
from ._sr5_driver import SOLVERS, SR4, SR5, build, integrate  # noqa: E402
from .gearbox import GEARBOX  # noqa: E402
from .impulse import IMPULSE, ImpulseParameters  # noqa: E402
from .multibody import MULTIBODY, MultibodyParameters  # noqa: E402
from .nabhan2020 import NABHAN2020, Nabhan2020Parameters  # noqa: E402
from .result import SimulationResult  # noqa: E402
from .rotor2 import ROTOR2, Rotor2Parameters  # noqa: E402
from .sr5 import BearingModel, SR5Parameters  # noqa: E402

__all__ = [
    "simulate",
    "integrate",
    "scene_needs",
    "unrepresented",
    "resolve_model",
    "model_table",
    "build",
    "Model",
    "MODELS",
    "PHENOMENA",
    "SOLVERS",
    "SimulationResult",
    "SimulationUnstableError",
    "SR5Parameters",
    "ImpulseParameters",
    "Rotor2Parameters",
    "MultibodyParameters",
    "Nabhan2020Parameters",
    "BearingModel",
    "source_fingerprint",
    "work_precision",
    "speedup",
    "plot_work_precision",
]

#: model name -> :class:`Model`, cheapest first
MODELS: dict[str, Model] = {
    m.name: m for m in sorted((IMPULSE, SR5, SR4, ROTOR2, MULTIBODY, GEARBOX,
                                NABHAN2020),
                              key=lambda m: m.relative_cost)}


def scene_needs(scene: Scene, *, return_forces: bool = False) -> frozenset:
    """The phenomena a scene asks a model to represent.

    Derived from the scene's fields (a speed ramp needs ``varying_speed``, waviness
    ``waviness``, gears ``gear_mesh``, ``clearance_um`` ``mounted_clearance``, extra
    ``resonances`` ``structural_modes``, a pit fault ``pit_faults``, a fault with
    ``engagement < 1`` or ``spin_drift_deg > 0`` ``intermittent_faults``,
    ``axial_load_n > 0`` ``axial_load``: a model that ignores a field the scene sets
    would silently drop it) plus
    ``Scene(needs=...)`` for what the fields cannot say; a scene that states no needs
    asks for ``envelope`` and ``contact_dynamics``. ``return_forces=True`` adds ``contact_forces``.

    Parameters
    ----------
    scene : Scene
    return_forces : bool, optional
        Whether per-element contact forces are requested as output.

    Returns
    -------
    frozenset of str

    Examples
    --------
    >>> import ballpass as bp
    >>> sorted(bp.simulate.scene_needs(bp.Scene(bearing="6205")))
    ['contact_dynamics', 'envelope']
    >>> sorted(bp.simulate.scene_needs(bp.Scene(bearing="6205", rpm=(600, 1800),
    ...                                         needs=("envelope",))))
    ['envelope', 'varying_speed']
    >>> sorted(bp.simulate.scene_needs(bp.Scene(bearing="6205", clearance_um=-3.0,
    ...                                         needs=("envelope",))))
    ['envelope', 'mounted_clearance']
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a ballpass.Scene, got {type(scene).__name__}")
    needs = set(scene.needs) if scene.needs else set(DEFAULT_NEEDS)
    if not scene.speed.is_constant:
        needs.add("varying_speed")
    if getattr(scene, "waviness", ()):
        needs.add("waviness")
    if getattr(scene, "gears", None) is not None:
        needs.add("gear_mesh")
    if scene.clearance_um is not None:
        needs.add("mounted_clearance")
    if scene.resonances:
        needs.add("structural_modes")
    if any(f.geometry == "pit" for f in scene.faults):
        needs.add("pit_faults")
    if any(f.engagement < 1.0 or f.spin_drift_deg > 0.0 for f in scene.faults):
        needs.add("intermittent_faults")
    if scene.axial_load_n > 0:
        needs.add("axial_load")
    if return_forces:
        needs.add("contact_forces")
    return frozenset(needs)


def unrepresented(scene: Scene, model: str, *, return_forces: bool = False) -> frozenset:
    """What the scene states that ``model`` does not represent.

    The stated needs are those of the scene's fields (gears, a clearance, a speed
    ramp, ...), of ``Scene(needs=...)`` and of ``return_forces``; not the default
    needs of a scene that states none, which only guide ``model="auto"``. A model
    asked for by name that leaves one out would give a signal without what its
    scene says it has.

    Examples
    --------
    >>> import ballpass as bp
    >>> sorted(bp.simulate.unrepresented(bp.Scene(bearing="6205", clearance_um=5.0),
    ...                                  "impulse"))
    ['mounted_clearance']
    >>> sorted(bp.simulate.unrepresented(bp.Scene(bearing="6205"), "impulse"))
    []
    """
    stated = scene_needs(scene, return_forces=return_forces)
    if not scene.needs:   # the defaults are no statement of the scene's
        stated -= DEFAULT_NEEDS
    return stated - MODELS[model].represents


def _choose(scene: Scene, model: str, return_forces: bool,
            allow_unrepresented: bool = False) -> tuple[Model, str]:
    """The model to run and the reason (for ``res.info["model_reason"]``)."""
    if not isinstance(model, str):
        raise TypeError(f"model must be a str, got {type(model).__name__}")
    for name, flag in (("return_forces", return_forces),
                       ("allow_unrepresented", allow_unrepresented)):
        if not isinstance(flag, bool | np.bool_):
            raise TypeError(f"{name} must be True or False, got {flag!r}")
    needs = scene_needs(scene, return_forces=return_forces)
    if model != "auto":
        if model not in MODELS:
            raise ValueError(f"model must be 'auto' or one of {list(MODELS)}, got {model!r}")
        chosen = MODELS[model]
        refusal = chosen.accepts(scene)
        if refusal:
            raise ValueError(f"model {model!r} cannot take this scene: {refusal}")
        stated = unrepresented(scene, model, return_forces=return_forces)
        if stated and not allow_unrepresented:
            able = [m.name for m in MODELS.values() if stated <= m.represents]
            raise ValueError(
                f"model {model!r} does not represent {', '.join(sorted(stated))}, which the "
                f"scene asks for: its signal would lack it. Models that do: "
                f"{', '.join(able) or 'none'}. Use model='auto' or one of those, or pass "
                "allow_unrepresented=True to simulate without it.")
        missing = needs - chosen.represents
        note = (f"; it does not represent {', '.join(sorted(missing))}, which the scene "
                "asks for" if missing else "")
        return chosen, f"requested by the caller{note}"
    passed = []
    for candidate in MODELS.values():  # cheapest first
        refusal = candidate.accepts(scene)
        missing = needs - candidate.represents
        if refusal is None and not missing:
            why = f"cheapest model that represents {', '.join(sorted(needs))}"
            if passed:
                why += "; cheaper ones: " + "; ".join(passed)
            return candidate, why
        passed.append(f"{candidate.name} " + (refusal if refusal else
                                              "lacks " + ", ".join(sorted(missing))))
    raise ValueError(
        f"no model represents everything this scene needs ({', '.join(sorted(needs))}): "
        + "; ".join(passed))


def resolve_model(scene: Scene, model: str = "auto", *, return_forces: bool = False,
                  allow_unrepresented: bool = False) -> str:
    """Name of the model :func:`simulate` will run for ``scene``.

    Parameters
    ----------
    scene : Scene
    model : str, optional
        ``"auto"`` (the cheapest model that can take the scene and represents
        :func:`scene_needs`) or a name in :data:`MODELS`.
    return_forces : bool, optional
        Whether contact forces will be requested (they are a need of their own).
    allow_unrepresented : bool, optional
        Let a model named by the caller leave out what the scene states and it does
        not represent (:func:`unrepresented`; default False: refused).

    Returns
    -------
    str

    Raises
    ------
    ValueError
        Unknown model name, a model that cannot take the scene or (unless
        ``allow_unrepresented``) leaves out what it states, or (``auto``) no model that
        covers the needs; the message says what each model lacks and which has it.

    Examples
    --------
    >>> import ballpass as bp
    >>> bp.simulate.resolve_model(bp.Scene(bearing="6205"))
    'sr5'
    """
    return _choose(scene, model, return_forces, allow_unrepresented)[0].name


def model_table():
    """The registry as a table: one row per model, cheapest first.

    Returns
    -------
    pandas.DataFrame
        Columns ``model``, ``relative_cost``, ``solvers``, one boolean column per
        phenomenon, ``description``, ``reference``.

    Examples
    --------
    >>> import ballpass as bp
    >>> table = bp.simulate.model_table()
    >>> bool(table.set_index("model").loc["sr5", "envelope"])
    True
    """
    import pandas as pd

    rows = []
    for m in MODELS.values():
        row = {"model": m.name, "relative_cost": m.relative_cost,
               "solvers": ", ".join(m.solvers)}
        row.update({p: p in m.represents for p in PHENOMENA})
        row.update(description=m.description, reference=m.reference)
        rows.append(row)
    return pd.DataFrame(rows)


def simulate(scene: Scene, model: str = "auto", solver: str = "auto", *, dt: float | None = None,
             rtol: float | None = None, atol: float | None = None, params=None,
             return_forces: bool = False, oversample: int = OVERSAMPLE,
             allow_unrepresented: bool = False) -> SimulationResult:
    """Simulate the vibration of a scene.

    Parameters
    ----------
    scene : Scene
        What to simulate (validated on construction).
    model : str, optional
        ``"auto"`` (default): the cheapest model in :data:`MODELS` that can take the
        scene and represents :func:`scene_needs`; or a model name.
    solver : str, optional
        ``"auto"`` (the model's default) or one of the model's ``solvers``
        (``"rk4"``, ``"dopri5"`` for sr5).
    dt : float, optional
        Step of a fixed-step solver, s (refused with an adaptive one). sr5's RK4 rounds
        it down to a multiple of the internal output spacing (or, below it, to a
        divisor), with a warning; default 0.3 / omega_c with omega_c the linearised
        contact natural frequency (rad/s), rounded down: 31 us for a 6205 at 500 N and
        48 kHz, a relative L2 error below 1e-3 (see docs/solvers.md); steps in which a
        contact opens or closes are redone on the internal grid.
    rtol : float, optional
        Relative tolerance of an adaptive solver (default 1e-6); refused with a
        fixed-step one.
    atol : float, optional
        Absolute tolerance of an adaptive solver as a multiple of ``rtol`` times each
        state component's characteristic scale (default 1).
    params : object, optional
        The model's structural parameters (:class:`SR5Parameters` for sr5/sr4).
    return_forces : bool, optional
        Also return every element's contact load at the output samples
        (``res.truth.contact_forces``); asks for a model that represents
        ``contact_forces``.
    oversample : int, optional
        Internal output rate as a multiple of ``scene.fs`` before the anti-alias
        decimation (default 4).
    allow_unrepresented : bool, optional
        Run a ``model`` named by the caller even if it leaves out what the scene
        states (gears with ``"impulse"``, ``needs=("ball_dynamics",)`` with ``"sr5"``):
        :func:`unrepresented` is then dropped from the signal, and
        ``info["model_reason"]`` says so. Default False: refused, naming what is
        missing and which models have it.

    Returns
    -------
    SimulationResult
        ``accel`` in m/s^2, shape (n_samples,) or (n_sensors, n_samples);
        ``info["model"]`` and ``info["model_reason"]`` say which model ran and why.

    Notes
    -----
    The kernels are numba code, compiled on first use and cached on disk. When the cache
    holds none of them (the first simulation after installing or updating ballpass) the
    ``"ballpass"`` logger says so at WARNING level before the 15-60 s of compilation,
    and at INFO level how long that first simulation took.

    Raises
    ------
    ValueError
        Bad arguments (before any work), a named model that leaves out what the scene
        states, or no model covers the scene's needs.
    SimulationUnstableError
        The integration diverged; the message names the scene and the step size.

    Examples
    --------
    >>> import ballpass as bp
    >>> scene = bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault("outer"),
    ...                  duration_s=0.1, fs=48_000)
    >>> res = bp.simulate(scene)
    >>> res.accel.shape, res.info["model"]
    ((4800,), 'sr5')
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a ballpass.Scene, got {type(scene).__name__}")
    chosen, reason = _choose(scene, model, return_forces, allow_unrepresented)
    check_solver_args(chosen.name, solver, chosen.solvers, chosen.fixed_step_solvers,
                      dt, rtol, atol, oversample)
    solver = chosen.default_solver if solver == "auto" else solver
    compiling = _announce_compilation()
    start = time.perf_counter()
    res = chosen.run(scene, solver, dt=dt, rtol=rtol, atol=atol, params=params,
                     return_forces=return_forces, oversample=oversample)
    if compiling:
        _log.info("first simulation with compilation took %.1f s", time.perf_counter() - start)
    res.info["model"] = chosen.name
    res.info["model_reason"] = reason
    res.info.setdefault("solver", solver)
    return res


_log = logging.getLogger("ballpass")
#: whether this process has looked for compiled kernels yet (once per process)
_compile_checked = False


def _announce_compilation() -> bool:
    """Say, once per process, that the kernels are being compiled when numba's cache
    holds none of them (fresh install, update, empty ``NUMBA_CACHE_DIR``).

    The record goes to the ``"ballpass"`` logger at WARNING level, so Python's default
    handler prints it on stderr without any logging set-up; silence it with
    ``logging.getLogger("ballpass").setLevel(logging.ERROR)``. Returns whether it was
    said.
    """
    global _compile_checked
    if _compile_checked:
        return False
    _compile_checked = True
    if has_compiled_kernels():
        return False
    _log.warning(
        "ballpass: compiling the simulator's numba kernels; the first simulation after "
        "installing or updating ballpass takes 15-60 s, later ones reuse the compiled code"
    )
    return True


from .work_precision import plot_work_precision, speedup, work_precision  # noqa: E402


class _CallableModule(types.ModuleType):
    """``ballpass.simulate`` is both this namespace and the :func:`simulate` function."""

    def __call__(self, *args, **kwargs) -> SimulationResult:
        return simulate(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
