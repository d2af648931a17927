"""Non-linear dynamics of a simulated rotor: Poincare sections and bifurcation diagrams.

A rotor on a bearing with clearance answers a periodic excitation (unbalance at the
shaft speed, varying compliance at the roller-pass rate, a defect) periodically,
quasi-periodically or chaotically depending on speed, load and clearance (the NJ 305 rotor paper's
conclusions). The standard views:

* :func:`poincare_section`: the rotor's displacement (x along the load line, y
  perpendicular, m) strobed once per shaft (or cage) revolution after the transient. A
  period-1 response gives one point, period-n n points, quasi-periodic motion a closed
  curve and chaos a scattered cloud.
* :func:`bifurcation_diagram`: the section's x coordinate against a swept parameter
  (``rpm``, ``radial_load_n``, any numeric :class:`~ballpass.Scene` field, or the
  bearing's ``radial_clearance_mm``).
* :func:`zero_one_test`: Gottwald and Melbourne's 0-1 test for chaos on the section
  (K near 0: regular, near 1: chaotic), a chaos indicator that needs no phase-space
  reconstruction.
* :func:`largest_lyapunov_exponent`: the mean exponential rate at which two nearby
  trajectories of any ODE separate (Benettin et al. 1980): positive for chaos, zero for
  periodic or quasi-periodic motion (a torus), negative for a stable equilibrium.

Any model that returns the rotor displacement with ``return_forces=True`` works
(``rotor2``; ``sr5``/``sr4`` give the shaft in rows 0-1 of theirs).

Examples
--------
>>> import ballpass as bp
>>> scene = bp.Scene(bearing="NJ305", rpm=1500, radial_load_n=200, duration_s=0.4,
...                  fs=10_000, resonance_hz=4000)
>>> res = bp.simulate(scene, model="rotor2", return_forces=True)
>>> bp.dynamics.poincare_section(res, discard_s=0.2).shape    # 25 rev/s for 0.2 s
(5, 2)
"""

from __future__ import annotations

import math
import numbers

import numpy as np

__all__ = ["poincare_section", "bifurcation_diagram", "zero_one_test",
           "largest_lyapunov_exponent", "plot_poincare",
           "plot_bifurcation", "STROBES", "sweepable_parameters", "MAX_VALUES"]

#: strobe name -> what it samples once per period of
STROBES = {
    "shaft": "the shaft rotation (unbalance, inner-race defect period)",
    "cage": "the cage rotation (fundamental train frequency; varying compliance and "
            "roller-defect period)",
}

#: fewest points :func:`zero_one_test` accepts
MIN_POINTS_01 = 300

#: the bearing parameter a bifurcation diagram can sweep besides the Scene's own fields
BEARING_PARAMETERS = ("radial_clearance_mm",)
#: Most values a bifurcation diagram takes: each is one simulation, and a diagram is read
#: by eye -- 10,000 columns are more than a 7-inch figure has pixels at 300 dpi (2,100).
MAX_VALUES = 10_000


def _strobe_angle(res, strobe: str) -> np.ndarray:
    """Angle (rad) whose multiples of 2 pi are the strobe instants, per output sample."""
    if strobe not in STROBES:
        raise ValueError(f"strobe must be one of {list(STROBES)}, got {strobe!r}")
    angle = np.asarray(res.truth.shaft_angle, dtype=float)
    if strobe == "cage":
        angle = angle * 0.5 * (1.0 - res.scene.bearing.diameter_ratio)
    return angle


def poincare_section(res, strobe: str = "shaft", discard_s: float | None = None) -> np.ndarray:
    """Rotor displacement strobed once per shaft or cage revolution.

    Parameters
    ----------
    res : SimulationResult
        From :func:`ballpass.simulate` with ``return_forces=True`` (which returns
        ``res.truth.displacement``; rows 0 and 1 are the rotor's x and y, m).
    strobe : {"shaft", "cage"}, optional
        Sample when the shaft (default) or the cage has turned a whole number of
        revolutions since t = 0 (from the tachometer channel ``res.truth.shaft_angle``,
        so speed ramps strobe correctly).
    discard_s : float, optional
        Transient to drop, s, in [0, duration). Default: the first half of the record.

    Returns
    -------
    ndarray (n, 2)
        x (along the load line) and y (perpendicular) displacement at each strobe
        instant, m; the displacement is interpolated between output samples with a
        cubic spline.

    Raises
    ------
    TypeError
        ``res`` is not a simulation result (e.g. an array of samples).
    ValueError
        No displacement in ``res``, an unknown ``strobe``, a ``discard_s`` outside the
        record.

    Examples
    --------
    >>> import ballpass as bp
    >>> scene = bp.Scene(bearing="NJ305", rpm=1200, radial_load_n=300, duration_s=0.3,
    ...                  fs=10_000, resonance_hz=4000)
    >>> res = bp.simulate(scene, model="rotor2", return_forces=True)
    >>> pts = bp.dynamics.poincare_section(res, discard_s=0.1)
    >>> pts.shape
    (4, 2)
    """
    from scipy.interpolate import make_interp_spline

    if not hasattr(res, "truth"):
        raise TypeError(f"res must be the SimulationResult of bp.simulate, got "
                        f"{type(res).__name__}")
    disp = getattr(res.truth, "displacement", None)
    if disp is None:
        raise ValueError("res has no displacement: simulate with return_forces=True "
                         "(e.g. bp.simulate(scene, model='rotor2', return_forces=True))")
    angle = _strobe_angle(res, strobe)
    t = np.asarray(res.t, dtype=float)
    duration = t[-1] + 1.0 / res.fs
    if discard_s is None:
        discard_s = 0.5 * duration
    if isinstance(discard_s, bool) or not isinstance(discard_s, numbers.Real) or not (
            0.0 <= discard_s < duration):
        raise ValueError(f"discard_s must be in [0, {duration:g}) s, got {discard_s!r}")
    start = float(np.interp(discard_s, t, angle))
    k = np.arange(math.ceil(start / (2.0 * math.pi) - 1e-12),
                  math.floor(angle[-1] / (2.0 * math.pi) + 1e-12) + 1)
    if k.size == 0:
        return np.empty((0, 2))
    t_k = np.interp(2.0 * math.pi * k, angle, t)
    spline = make_interp_spline(t, np.asarray(disp[:2], dtype=float).T, k=3)
    return spline(t_k)


def sweepable_parameters(scene) -> list[str]:
    """Names :func:`bifurcation_diagram` can sweep for ``scene``: its numeric fields
    (``rpm`` only at constant speed) and the bearing's ``radial_clearance_mm``.

    Examples
    --------
    >>> import ballpass as bp
    >>> names = bp.dynamics.sweepable_parameters(bp.Scene("6205", rpm=1797))
    >>> names[:3], names[-1]
    (['rpm', 'radial_load_n', 'duration_s'], 'radial_clearance_mm')
    """
    from dataclasses import fields

    names = [f.name for f in fields(scene)
             if isinstance(getattr(scene, f.name), numbers.Real)
             and not isinstance(getattr(scene, f.name), bool)]
    return names + list(BEARING_PARAMETERS)


def _with(scene, parameter: str, value: float):
    """``scene`` with one parameter changed (validated by the Scene/Bearing)."""
    if parameter == "radial_clearance_mm":
        return scene.replace(bearing=scene.bearing.with_clearance(value))
    current = getattr(scene, parameter)
    if isinstance(current, int) and value != int(value):
        raise ValueError(f"{parameter} takes whole numbers, got {value:g}")
    return scene.replace(**{parameter: type(current)(value) if isinstance(current, int)
                            else float(value)})


def _section_of(scene, model, strobe, discard_s, simulate_kwargs) -> np.ndarray:
    from . import simulate

    res = simulate(scene, model=model, return_forces=True, **simulate_kwargs)
    return poincare_section(res, strobe=strobe, discard_s=discard_s)


def bifurcation_diagram(scene, parameter: str, values, *, model: str = "rotor2",
                        strobe: str = "shaft", discard_s: float | None = None,
                        n_jobs: int = 1, progress: bool = True, **simulate_kwargs):
    """Poincare sections of a scene over the values of one parameter.

    Parameters
    ----------
    scene : Scene
        The base scene.
    parameter : str
        A numeric field of ``scene`` (``"rpm"`` at constant speed, ``"radial_load_n"``,
        ``"duration_s"``, ...) or ``"radial_clearance_mm"`` of its bearing
        (:func:`sweepable_parameters` lists them).
    values : sequence of float
        Values of the parameter, in its unit (rpm, N, mm, ...); at most
        :data:`MAX_VALUES`.
    model : str, optional
        Model to run (default ``"rotor2"``); any model that returns a displacement.
    strobe : {"shaft", "cage"}, optional
        See :func:`poincare_section`.
    discard_s : float, optional
        Transient to drop from every run, s (default: half of ``scene.duration_s``).
    n_jobs : int, optional
        Parallel processes (joblib; -1 = all cores). Default 1.
    progress : bool, optional
        Show a progress bar (tqdm). Default True.
    **simulate_kwargs
        Passed to :func:`ballpass.simulate` (``solver``, ``dt``, ``rtol``, ``params``).

    Returns
    -------
    pandas.DataFrame
        One row per section point: ``parameter`` (the value), ``point`` (index within
        its section), ``x_m``, ``y_m`` (displacement, m); ``df.attrs["parameter"]``
        holds the parameter's name.

    Raises
    ------
    ValueError
        Unknown parameter, bad values, or a value the scene or model refuses: every
        scene is built and checked before the first simulation.

    Examples
    --------
    >>> import ballpass as bp
    >>> scene = bp.Scene(bearing="NJ305", rpm=1200, radial_load_n=300, duration_s=0.3,
    ...                  fs=10_000, resonance_hz=4000)
    >>> df = bp.dynamics.bifurcation_diagram(scene, "rpm", [900, 1200], discard_s=0.15,
    ...                                      progress=False)
    >>> [float(v) for v in sorted(df["parameter"].unique())]
    [900.0, 1200.0]
    """
    import pandas as pd

    from .scene import Scene
    from .simulate import resolve_model

    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a ballpass.Scene, got {type(scene).__name__}")
    allowed = sweepable_parameters(scene)
    if not isinstance(parameter, str) or parameter not in allowed:
        raise ValueError(f"parameter must be one of {allowed} for this scene, got "
                         f"{parameter!r}")
    try:
        vals = np.asarray(values, dtype=float).ravel()
    except (TypeError, ValueError):
        raise TypeError(f"values must be a sequence of numbers, got {values!r}") from None
    if vals.size == 0 or not np.all(np.isfinite(vals)):
        raise ValueError("values must be a non-empty sequence of finite numbers, got "
                         f"{vals.tolist()}")
    if vals.size > MAX_VALUES:
        raise ValueError(f"values: {vals.size:,} values, one simulation each; a diagram "
                         f"takes at most {MAX_VALUES:,}")
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, int) or n_jobs == 0:
        raise ValueError(f"n_jobs must be a non-zero int (-1 = all cores), got {n_jobs!r}")
    if strobe not in STROBES:
        raise ValueError(f"strobe must be one of {list(STROBES)}, got {strobe!r}")
    if discard_s is not None and not (isinstance(discard_s, numbers.Real)
                                      and 0.0 <= discard_s < scene.duration_s):
        raise ValueError(f"discard_s must be in [0, {scene.duration_s:g}) s, got {discard_s!r}")
    scenes = []
    for v in vals:  # every value validated before any simulation
        try:
            s = _with(scene, parameter, v)
        except (ValueError, TypeError) as exc:
            raise ValueError(f"{parameter}={v:g}: {exc}") from None
        resolve_model(s, model, return_forces=True)
        scenes.append(s)

    from joblib import Parallel, delayed
    from tqdm.auto import tqdm

    jobs = (delayed(_section_of)(s, model, strobe, discard_s, simulate_kwargs) for s in scenes)
    sections = list(tqdm(Parallel(n_jobs=n_jobs, return_as="generator")(jobs),
                         total=len(scenes), desc=f"bifurcation over {parameter}",
                         unit="run", disable=not progress, leave=False))
    frames = [pd.DataFrame({"parameter": v, "point": np.arange(len(pts)),
                            "x_m": pts[:, 0], "y_m": pts[:, 1]})
              for v, pts in zip(vals, sections, strict=True)]
    df = pd.concat(frames, ignore_index=True)
    df.attrs["parameter"] = parameter
    return df


def zero_one_test(series, *, n_c: int = 100, seed: int = 0) -> float:
    """Gottwald and Melbourne's 0-1 test for chaos (correlation method).

    For each of ``n_c`` random frequencies c in (pi/5, 4 pi/5) the series phi_j drives
    the translation p_n = sum_j phi_j cos(j c), q_n = sum_j phi_j sin(j c) of the
    centred series; the mean square displacement M_c(n) grows linearly in n for chaotic
    data and stays bounded for regular data. K_c is the correlation of M_c(n)
    (n <= N/10) with n, and the result is the median of K_c (Gottwald & Melbourne,
    SIAM J. Appl. Dyn. Syst. 8 (2009) 129-145).

    Parameters
    ----------
    series : array_like (N,)
        An observable sampled once per forcing period (e.g. a Poincare coordinate),
        N >= 300. Shorter series are refused: at N = 100 a quasi-periodic series
        (cos 2.2 n + 0.3 cos 0.7 n) scores K = 0.92; at N = 300 it scores 0.07 and
        the chaotic logistic map 0.998 (tests/test_dynamics.py checks N = 2000).
    n_c : int, optional
        Number of random frequencies. Default 100.
    seed : int, optional
        Seed of the frequencies. Default 0.

    Returns
    -------
    float
        K: near 0 for periodic or quasi-periodic data, near 1 for chaotic data.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.dynamics import zero_one_test
    >>> x = np.empty(1000); x[0] = 0.3
    >>> for i in range(999):
    ...     x[i + 1] = 3.97 * x[i] * (1 - x[i])      # logistic map, chaotic
    >>> zero_one_test(x) > 0.9
    True
    >>> zero_one_test(np.cos(0.9 * np.arange(1000))) < 0.1
    True
    """
    phi = np.asarray(series, dtype=float).ravel()
    if phi.size < MIN_POINTS_01 or not np.all(np.isfinite(phi)):
        raise ValueError(f"series must hold >= {MIN_POINTS_01} finite values (shorter ones "
                         f"mistake quasi-periodic motion for chaos), got {phi.size}")
    if isinstance(n_c, bool) or not isinstance(n_c, int) or n_c < 1:
        raise ValueError(f"n_c must be an int >= 1, got {n_c!r}")
    phi = phi - phi.mean()
    n_total = phi.size
    n_cut = n_total // 10
    rng = np.random.default_rng(seed)
    j = np.arange(1, n_total + 1)
    n = np.arange(1, n_cut + 1)
    ks = []
    for c in rng.uniform(math.pi / 5, 4 * math.pi / 5, n_c):
        p = np.cumsum(phi * np.cos(j * c))
        q = np.cumsum(phi * np.sin(j * c))
        # mean square displacement; its oscillatory correction (E phi)^2 (1 - cos nc) /
        # (1 - cos c) vanishes for the centred series
        d = np.array([np.mean((p[k:] - p[:-k]) ** 2 + (q[k:] - q[:-k]) ** 2) for k in n])
        if np.std(d) == 0.0:
            ks.append(0.0)
            continue
        ks.append(float(np.corrcoef(n, d)[0, 1]))
    return float(np.median(ks))


def largest_lyapunov_exponent(rhs, y0, duration: float, *, renormalize_s: float,
                              transient_s: float = 0.0, d0: float = 1e-8, scale=None,
                              method: str = "DOP853", rtol: float = 1e-10,
                              atol: float = 1e-12) -> tuple[float, np.ndarray]:
    """Largest Lyapunov exponent of an ODE from two nearby trajectories.

    The reference trajectory y and a companion y + d0 u (u a unit vector in the scaled
    norm) are integrated together with :func:`scipy.integrate.solve_ivp` (the same steps
    for both); every ``renormalize_s`` the separation d (in the norm
    ``||(y2 - y1) / scale||``) is recorded and the companion pulled back to distance d0
    along the same direction (Benettin, Galgani, Giorgilli & Strelcyn 1980). The exponent
    is the mean of ln(d / d0) per unit time.

    Parameters
    ----------
    rhs : callable
        ``rhs(t, y) -> dy/dt`` for a state ``y`` of shape (n,).
    y0 : array_like (n,)
        Initial state.
    duration : float
        Time over which the exponent is averaged (after the transient), in the units of
        ``t``, > 0 and at least one ``renormalize_s``.
    renormalize_s : float
        Time between renormalizations, > 0: short enough that d stays small (linear)
        between them.
    transient_s : float, optional
        Time integrated before the companion starts, >= 0. Default 0.
    d0 : float, optional
        Scaled initial separation, in (0, 1e-3]. Default 1e-8: far above the integration
        error at rtol 1e-10, far below the attractor's size.
    scale : array_like (n,), optional
        Scale of each state component (its units), > 0. Default ones.
    method, rtol, atol
        Passed to :func:`scipy.integrate.solve_ivp` (``atol`` in the units of y).

    Returns
    -------
    exponent : float
        Largest Lyapunov exponent, 1 / (unit of t).
    running : ndarray (k,)
        The running estimate after each of the k renormalizations (its settling shows
        whether ``duration`` suffices).

    Raises
    ------
    ValueError
        A non-positive ``duration`` or ``renormalize_s``, ``duration`` shorter than one
        ``renormalize_s``, a negative ``transient_s``, ``d0`` outside (0, 1e-3], a
        ``scale`` of the wrong shape or not positive.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.dynamics import largest_lyapunov_exponent
    >>> # x'' + 0.2 x' + x = 0: both trajectories decay like exp(-0.1 t)
    >>> lam, _ = largest_lyapunov_exponent(lambda t, y: [y[1], -y[0] - 0.2 * y[1]],
    ...                                    [1.0, 0.0], 200.0, renormalize_s=1.0)
    >>> round(lam, 2)
    -0.1
    """
    from scipy.integrate import solve_ivp

    for name, v in (("duration", duration), ("renormalize_s", renormalize_s)):
        if isinstance(v, bool) or not isinstance(v, numbers.Real) or not v > 0:
            raise ValueError(f"{name} must be > 0, got {v!r}")
    if duration < renormalize_s:
        raise ValueError(f"duration must be >= renormalize_s={renormalize_s:g}, got "
                         f"{duration!r}")
    if isinstance(transient_s, bool) or not isinstance(transient_s, numbers.Real) or not (
            transient_s >= 0):
        raise ValueError(f"transient_s must be >= 0, got {transient_s!r}")
    if isinstance(d0, bool) or not isinstance(d0, numbers.Real) or not 0 < d0 <= 1e-3:
        raise ValueError(f"d0 must be in (0, 1e-3], got {d0!r}")
    y = np.asarray(y0, dtype=float).ravel()
    n = y.size
    s = np.ones(n) if scale is None else np.asarray(scale, dtype=float).ravel()
    if s.shape != (n,) or not np.all(s > 0):
        raise ValueError(f"scale must hold {n} positive values (one per state), got {scale!r}")

    def pair(t, yy):
        return np.concatenate((np.asarray(rhs(t, yy[:n]), dtype=float),
                               np.asarray(rhs(t, yy[n:]), dtype=float)))

    t = 0.0
    if transient_s > 0:
        y = solve_ivp(rhs, (0.0, transient_s), y, method=method, rtol=rtol,
                      atol=atol).y[:, -1]
        t = transient_s
    u = np.ones(n) / math.sqrt(n)  # any direction: the largest exponent attracts it
    y2 = y + d0 * u * s
    k = max(1, round(duration / renormalize_s))
    logs = np.empty(k)
    for i in range(k):
        sol = solve_ivp(pair, (t, t + renormalize_s), np.concatenate((y, y2)),
                        method=method, rtol=rtol, atol=atol)
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed at t = {t:g}: {sol.message}")
        y, y2 = sol.y[:n, -1], sol.y[n:, -1]
        sep = (y2 - y) / s
        d = float(np.linalg.norm(sep))
        logs[i] = math.log(d / d0)
        y2 = y + sep * (d0 / d) * s
        t += renormalize_s
    running = np.cumsum(logs) / (renormalize_s * np.arange(1, k + 1))
    return float(running[-1]), running


def plot_poincare(points, *, ax=None, unit: str = "um", **scatter_kwargs):
    """Scatter a Poincare section.

    Parameters
    ----------
    points : ndarray (n, 2) or SimulationResult
        From :func:`poincare_section` (a result is sectioned with its defaults).
    ax : matplotlib Axes, optional
        Draw here (default: a new figure).
    unit : {"um", "m"}, optional
        Axis unit. Default micrometres.
    **scatter_kwargs
        Passed to ``ax.scatter``.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.dynamics import plot_poincare
    >>> ax = plot_poincare(np.array([[1e-4, 0.0], [1.1e-4, 1e-6]]))
    >>> ax.get_xlabel()
    'x, along the load line (um)'
    """
    from .plot import _axes

    if hasattr(points, "truth"):
        points = poincare_section(points)
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise ValueError(f"points must have shape (n, 2), got {pts.shape}")
    scale = _unit_scale(unit)
    ax = _axes(ax)
    scatter_kwargs.setdefault("s", 6)
    ax.scatter(pts[:, 0] * scale, pts[:, 1] * scale, **scatter_kwargs)
    ax.set_xlabel(f"x, along the load line ({unit})")
    ax.set_ylabel(f"y, perpendicular ({unit})")
    ax.set_title("Poincare section")
    return ax


def _unit_scale(unit: str) -> float:
    scales = {"um": 1e6, "m": 1.0}
    if unit not in scales:
        raise ValueError(f"unit must be one of {list(scales)}, got {unit!r}")
    return scales[unit]


def plot_bifurcation(df, *, coordinate: str = "x_m", ax=None, unit: str = "um",
                     **scatter_kwargs):
    """Plot a bifurcation diagram: section coordinate against the swept parameter.

    Parameters
    ----------
    df : pandas.DataFrame
        From :func:`bifurcation_diagram`.
    coordinate : {"x_m", "y_m"}, optional
        Section coordinate on the vertical axis. Default ``"x_m"``.
    ax : matplotlib Axes, optional
    unit : {"um", "m"}, optional
        Unit of the vertical axis. Default micrometres.
    **scatter_kwargs
        Passed to ``ax.scatter``.

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> import pandas as pd
    >>> from ballpass.dynamics import plot_bifurcation
    >>> df = pd.DataFrame({"parameter": [1.0, 2.0], "point": [0, 0],
    ...                    "x_m": [1e-4, 2e-4], "y_m": [0.0, 0.0]})
    >>> df.attrs["parameter"] = "rpm"
    >>> plot_bifurcation(df).get_xlabel()
    'rpm'
    """
    from .plot import _axes

    if coordinate not in ("x_m", "y_m"):
        raise ValueError(f"coordinate must be 'x_m' or 'y_m', got {coordinate!r}")
    for col in ("parameter", coordinate):
        if col not in df:
            raise ValueError(f"df must have a {col!r} column (from bifurcation_diagram)")
    scale = _unit_scale(unit)
    ax = _axes(ax)
    scatter_kwargs.setdefault("s", 2)
    scatter_kwargs.setdefault("color", "k")
    ax.scatter(df["parameter"], df[coordinate] * scale, **scatter_kwargs)
    ax.set_xlabel(df.attrs.get("parameter", "parameter"))
    ax.set_ylabel(f"{'x' if coordinate == 'x_m' else 'y'} at the section ({unit})")
    ax.set_title("Bifurcation diagram")
    return ax
