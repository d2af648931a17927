"""Randomized grid axes: a distribution instead of a list of values.

A ``[grid]`` axis may be a table naming one distribution::

    resonance_hz = { uniform = [2000, 6000] }        # Hz, flat between the bounds
    radial_load_n = { log_uniform = [100, 2000] }    # N, flat in log(load)
    slip = { normal = [0.01, 0.002] }                # mean, standard deviation
    fault_angle_deg = { choice = [0, 90, 180] }      # one of the values, equally likely

The axis then adds no points to the grid's product: each run draws its own value
(``[dataset] draws`` runs per grid point, each from its own seed; see
:func:`ballpass.datasets.read_grid`). A drawn grid is a way to say "the machine's
value is unknown somewhere in this range" (domain randomization, Tobin et al. 2017).

Every distribution is checked against its field's allowed range before any work:
``uniform`` and ``log_uniform`` need ``lo < hi`` inside the range (``log_uniform``
also ``lo > 0``); ``choice`` values are checked one by one; a ``normal`` is
**refused** unless ``mean +- 4 sigma`` lies inside the range, and the rare draw
beyond (6e-5 of them) is drawn again, so that no clipped value piles up on a bound.

Examples
--------
>>> import numpy as np
>>> from ballpass.datasets.distributions import parse_distribution
>>> d = parse_distribution("resonance_hz", {"uniform": [2000, 5000]}, fs=12_000)
>>> d
Distribution(kind='uniform', params=(2000.0, 5000.0))
>>> 2000 <= d.draw(np.random.default_rng(0)) < 5000
True
>>> parse_distribution("slip", {"normal": [0.01, 0.01]}, fs=12_000)  # doctest: +ELLIPSIS
Traceback (most recent call last):
    ...
ValueError: grid.slip = { normal = [0.01, 0.01] }: mean +- 4 sigma = [-0.03, 0.05] leaves ...
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["DISTRIBUTIONS", "Distribution", "field_range", "is_distribution",
           "parse_distribution"]

#: distribution names a grid axis may use
DISTRIBUTIONS = ("uniform", "log_uniform", "normal", "choice")
#: a normal is accepted when its mean +- this many standard deviations lies in range
NORMAL_SIGMAS = 4.0

#: axis -> (lo, hi, lo_open, hi_open, unit): the values :class:`~ballpass.Scene`,
#: :class:`~ballpass.Fault` and :class:`~ballpass.Sensor` accept. ``resonance*_hz``
#: also stay below 0.45 fs (see :func:`field_range`).
FIELD_RANGES = {
    "fault_width_mm": (0.0, 50.0, True, False, "mm"),
    "fault_depth_mm": (0.0, 50.0, True, False, "mm"),
    "fault_angle_deg": (-1e6, 1e6, False, False, "deg"),
    "fault_engagement": (0.0, 1.0, True, False, ""),
    "fault_spin_drift_deg": (0.0, 90.0, False, False, "deg"),
    "rpm": (0.0, 1e5, True, False, "rpm"),
    "radial_load_n": (0.0, 1e6, False, False, "N"),
    "clearance_um": (-50.0, 200.0, True, True, "um"),
    "slip": (0.0, 0.1, False, False, ""),
    "snr_db": (-60.0, 200.0, False, False, "dB"),
    "level_db": (-60.0, 60.0, False, False, "dB"),
    "impact_spread": (0.0, 3.0, False, False, ""),
    "impact_edges": (0.0, 1.0, False, False, ""),
    "impact_correlation": (0.0, 1.0, False, True, ""),
    "noise_rms": (0.0, 1e6, False, False, "m/s^2"),
    "noise_slope_db_oct": (-12.0, 12.0, False, False, "dB/octave"),
    "resonance_hz": (100.0, math.inf, False, False, "Hz"),
    "resonance_damping": (0.0, 1.0, True, True, ""),
    "sensor_angle_deg": (-1e6, 1e6, False, False, "deg"),
    **{f"resonance{k}_hz": (0.0, math.inf, True, False, "Hz") for k in (2, 3)},
    **{f"resonance{k}_damping": (0.0, 1.0, True, True, "") for k in (2, 3)},
    **{f"resonance{k}_gain": (0.0, 100.0, True, False, "") for k in (2, 3)},
    **{f"shaft_harmonic_{k}x": (0.0, 1e4, False, False, "m/s^2") for k in (1, 2, 3, 4)},
}


def is_distribution(raw) -> bool:
    """True for a table naming one of :data:`DISTRIBUTIONS` (``{uniform = [lo, hi]}``)."""
    return isinstance(raw, dict) and len(raw) == 1 and next(iter(raw)) in DISTRIBUTIONS


def field_range(key: str, fs: float) -> tuple[float, float, bool, bool, str]:
    """Allowed ``(lo, hi, lo_open, hi_open, unit)`` of axis ``key`` at sampling rate ``fs``
    (Hz): resonances must sit below 0.45 fs, inside the output band."""
    lo, hi, lo_open, hi_open, unit = FIELD_RANGES[key]
    if key.startswith("resonance") and key.endswith("_hz"):
        hi = 0.45 * fs
    return lo, hi, lo_open, hi_open, unit


def _inside(value: float, lo: float, hi: float, lo_open: bool, hi_open: bool) -> bool:
    return (value > lo if lo_open else value >= lo) and (value < hi if hi_open else value <= hi)


def _interval(lo, hi, lo_open, hi_open) -> str:
    return f"{'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"


@dataclass(frozen=True)
class Distribution:
    """A validated distribution of one grid axis (build it with :func:`parse_distribution`).

    Attributes
    ----------
    kind : str
        One of :data:`DISTRIBUTIONS`.
    params : tuple of float
        ``(lo, hi)`` for ``uniform`` and ``log_uniform``, ``(mean, sigma)`` for
        ``normal``, the values for ``choice``; in the axis's unit.
    bounds : tuple, optional
        ``(lo, hi, lo_open, hi_open)`` of the field: a ``normal`` draw outside them is
        drawn again.
    """

    kind: str
    params: tuple
    bounds: tuple = (-math.inf, math.inf, False, False)

    def __repr__(self) -> str:
        return f"Distribution(kind={self.kind!r}, params={self.params!r})"

    def draw(self, rng: np.random.Generator) -> float:
        """One value drawn with ``rng``.

        Examples
        --------
        >>> import numpy as np
        >>> from ballpass.datasets.distributions import Distribution
        >>> angle = Distribution("choice", (0.0, 90.0, 180.0))
        >>> angle.draw(np.random.default_rng(1)) in (0, 90, 180)
        True
        """
        if self.kind == "uniform":
            return float(rng.uniform(*self.params))
        if self.kind == "log_uniform":
            lo, hi = self.params
            return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))
        if self.kind == "normal":
            while True:  # refused unless mean +- 4 sigma is in range: one try in 16000 repeats
                value = float(rng.normal(*self.params))
                if _inside(value, *self.bounds):
                    return value
        return float(self.params[int(rng.integers(len(self.params)))])

    @property
    def representative(self) -> float:
        """A typical value (the middle, the geometric middle, the mean, the first choice),
        used to validate the grid point's scene."""
        if self.kind == "uniform":
            return 0.5 * (self.params[0] + self.params[1])
        if self.kind == "log_uniform":
            return math.sqrt(self.params[0] * self.params[1])
        return self.params[0]

    @property
    def extremes(self) -> tuple[float, ...]:
        """Values at the edges of what can be drawn (the normal's at 4 sigma)."""
        if self.kind == "normal":
            mu, sigma = self.params
            return (max(mu - NORMAL_SIGMAS * sigma, self.bounds[0]),
                    min(mu + NORMAL_SIGMAS * sigma, self.bounds[1]))
        return self.params

    def describe(self) -> str:
        """The distribution as text, e.g. ``uniform 2000 - 6000``."""
        if self.kind in ("uniform", "log_uniform"):
            return f"{self.kind} {self.params[0]:g} - {self.params[1]:g}"
        if self.kind == "normal":
            return f"normal mean {self.params[0]:g}, sigma {self.params[1]:g}"
        return "choice of " + ", ".join(f"{v:g}" for v in self.params)

    def as_dict(self) -> dict:
        """The TOML/JSON form, ``{"uniform": [lo, hi]}``."""
        return {self.kind: list(self.params)}


def parse_distribution(key: str, raw: dict, fs: float) -> Distribution:
    """Validate the distribution of grid axis ``key`` against the field's allowed range.

    Parameters
    ----------
    key : str
        Axis name (a key of :data:`FIELD_RANGES`).
    raw : dict
        ``{"uniform": [lo, hi]}``, ``{"log_uniform": [lo, hi]}``, ``{"normal": [mean,
        sigma]}`` or ``{"choice": [v1, v2, ...]}``.
    fs : float
        Sampling rate of the dataset, Hz (resonances must sit below 0.45 fs).

    Returns
    -------
    Distribution

    Raises
    ------
    ValueError
        An axis that cannot be drawn, an unknown distribution, parameters that are not
        finite numbers, ``lo >= hi``, ``lo <= 0`` for ``log_uniform``, ``sigma <= 0``, a
        normal whose mean +- 4 sigma leaves the range, or any bound or choice outside it.
    """
    where = f"grid.{key} = {_toml(raw)}"
    if key not in FIELD_RANGES:
        raise ValueError(f"{where}: grid.{key} cannot be drawn; distributions are allowed on "
                         f"{sorted(FIELD_RANGES)}")
    if not is_distribution(raw):
        raise ValueError(f"{where}: a distribution is a table with one key of "
                         f"{list(DISTRIBUTIONS)}")
    kind, params = next(iter(raw.items()))
    if not isinstance(params, list) or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
            for v in params):
        raise ValueError(f"{where}: the parameters must be a list of finite numbers")
    params = tuple(float(v) for v in params)
    lo, hi, lo_open, hi_open, unit = field_range(key, fs)
    allowed = f"the allowed range {_interval(lo, hi, lo_open, hi_open)} {unit}".rstrip()
    if kind == "choice":
        if not params:
            raise ValueError(f"{where}: give at least one value")
        if len(set(params)) != len(params):
            raise ValueError(f"{where}: duplicate values")
        check = params
    else:
        if len(params) != 2:
            names = "[mean, sigma]" if kind == "normal" else "[lo, hi]"
            raise ValueError(f"{where}: {kind} takes two numbers {names}, got {len(params)}")
        a, b = params
        if kind == "normal":
            if b <= 0:
                raise ValueError(f"{where}: sigma must be > 0, got {b:g}")
            check = (a - NORMAL_SIGMAS * b, a + NORMAL_SIGMAS * b)
            if not all(_inside(v, lo, hi, lo_open, hi_open) for v in check):
                raise ValueError(
                    f"{where}: mean +- 4 sigma = [{check[0]:g}, {check[1]:g}] leaves {allowed}; "
                    "a normal is refused rather than clipped: use a smaller sigma or a "
                    "uniform")
        else:
            if not a < b:
                raise ValueError(f"{where}: lo must be below hi, got lo = {a:g}, hi = {b:g}")
            if kind == "log_uniform" and a <= 0:
                raise ValueError(f"{where}: log_uniform needs lo > 0, got {a:g}")
            check = params
    bad = [v for v in check if not _inside(v, lo, hi, lo_open, hi_open)]
    if bad:
        raise ValueError(f"{where}: {bad[0]:g} is outside {allowed}")
    return Distribution(kind, params, (lo, hi, lo_open, hi_open))


def _toml(raw) -> str:
    if is_distribution(raw):
        kind, params = next(iter(raw.items()))
        return f"{{ {kind} = {params} }}"
    return repr(raw)
