"""The routes to a multibody model at most 50x sr5 and what each can give, measured on
the 6205 reference scene (for benchmarks/multibody_speed.py).

* Cheaper evaluation: the integration's CPU time (0.05 s, default step) with the
  right-hand side changed in a copy of the kernels (the traction law's exponential
  replaced by a division, the law dropped for a constant coefficient, the sensor
  weighting's exponential replaced by a linear expression, the sensor weighting
  dropped), interleaved with the unchanged kernels: each saving is the most that making
  that part cheaper could give (the changed models are not the bearing's; timing only).
* Fewer steps: two RK4 steps per 5.2 us grid interval against the default three, CPU
  time side by side, and why two lose accuracy: a Python RK4 on the model's right-hand
  side (the kernel's arithmetic: equal to the kernel's trajectory to 1e-12) records at
  every step the contact loads of the four stages, so that the loads at the grid point
  (what the model records) can be set against the RK4 quadrature of the loads over the
  step (the force the step applies), and the short-horizon load error split into its
  elastic share (K delta^1.5, from the positions) and Kramer's damping share (from the
  contact's closing speed).
"""

from __future__ import annotations

import contextlib
import csv
import dataclasses
import inspect
import time
import types

import numpy as np
from _paths import RESULTS_DIR

import ballpass.simulate.multibody as mb
from ballpass.simulate.multibody import _kernels as K
from ballpass.simulate.multibody import build, integrate

#: an exponential e^-x (x >= 0) written out in the kernels instead of libm's: x = (128 m
#: + j) ln2 / 128 + r with |r| <= ln2 / 256, e^-x = 2^-m 2^(-j/128) e^-r, e^-r by its
#: Taylor polynomial of degree 5 (the tables built once)
INLINE_EXP = '''

_EXP_T = np.array([2.0 ** (-j / 128.0) for j in range(128)])
_EXP_P2 = np.array([2.0 ** (-m) for m in range(1100)])
_LN2_128_HI = 0.005415212348111709
_LN2_128_LO = math.log(2.0) / 128.0 - _LN2_128_HI


@njit(cache=True, error_model="numpy", inline="always", **_NO_RUNTIME)
def exp_neg(x):
    if x >= 700.0:
        return 0.0
    k = int(x * (128.0 / 0.6931471805599453) + 0.5)
    r = (x - k * _LN2_128_HI) - k * _LN2_128_LO
    p = 1.0 - r * (1.0 - r * (0.5 - r * (1.0 / 6.0 - r * (1.0 / 24.0 - r * (1.0 / 120.0)))))
    return _EXP_P2[k >> 7] * _EXP_T[k & 127] * p


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def mu_slide_roll('''
_MU_DEF = '''

@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def mu_slide_roll('''
INLINE = "traction law: its exponential written out (2^(-j/128) table and polynomial)"

#: changes to the kernels' source, each timed against the unchanged kernels
VARIANTS = {
    "control: the kernels recompiled unchanged": [],
    "traction law: its exponential replaced by a division":
        [("math.exp(-181.46 * s)", "(1.0 / (1.0 + 181.46 * s))")],
    INLINE: [(_MU_DEF, INLINE_EXP), ("math.exp(-181.46 * s)", "exp_neg(181.46 * s)")],
    "traction law dropped (target 0.1 Q: no exponential, no division)":
        [("target = mu_slide_roll(abs(vs) / ur, w_bd, hd) * q", "target = 0.1 * q")],
    "sensor weighting: its exponential replaced by a linear expression":
        [("math.exp(-kappa * (1.0 - cos_rel))", "(1.0 - kappa * (1.0 - cos_rel))")],
    "sensor weighting dropped (outer contacts not added to the sensor)":
        [("                _sensor_share(exc, sensors, nx, ny, q, p[P_MO])\n",
          "                pass\n")],
}


def variant_kernels(replacements):
    """A copy of the multibody kernels module with ``replacements`` (old, new) made in
    its source, compiled without numba's on-disk cache."""
    src = inspect.getsource(K)
    for old, new in replacements:
        if src.count(old) != 1:
            raise RuntimeError(f"the kernels no longer hold {old!r} once: update VARIANTS")
        src = src.replace(old, new)
    mod = types.ModuleType("_multibody_kernels_variant")
    exec(compile(src.replace("cache=True", "cache=False"), "<kernels variant>", "exec"),
         mod.__dict__)
    return mod


@contextlib.contextmanager
def kernels(mod):
    """``integrate`` running ``mod``'s kernels for the time of the block."""
    saved = mb.K
    mb.K = mod
    try:
        yield
    finally:
        mb.K = saved


def inline_exp_error() -> float:
    """Largest relative error of the written-out exponential of :data:`VARIANTS` against
    numpy's over 0 <= x <= 60 (the traction law's argument, 181.46 s, is below 40 where
    its term is not negligible)."""
    mod = variant_kernels(VARIANTS[INLINE])
    x = np.linspace(0.0, 60.0, 200_001)
    got = np.array([mod.exp_neg(v) for v in x])
    return float(np.max(np.abs(got / np.exp(-x) - 1.0)))


def cited_ratio() -> float:
    """The multibody model's cost against sr5 at 48 kHz in docs/results/models_cost.csv
    (benchmarks/models_cost.py: the ratio ``relative_cost`` cites)."""
    with open(RESULTS_DIR / "models_cost.csv", newline="") as f:
        for row in csv.DictReader(f):
            if row["scene"] == "48 kHz" and row["model"] == "multibody":
                return float(row["ratio_median"])
    raise RuntimeError("docs/results/models_cost.csv has no 48 kHz multibody row")


def _cpu(system, h, n_grid, n_sub=None):
    t = time.thread_time()
    integrate(system, h_out=h, n_out=n_grid, stride=4, dt=None if n_sub is None else h / n_sub)
    return time.thread_time() - t


def evaluation_ceilings(sc, h, repeats):
    """CPU time of the integration (``sc``, default step) with each kernel variant and
    with two steps per interval, interleaved with the unchanged kernels. Returns rows
    (name, medians of the ratios to the unchanged kernels' time, min, max)."""
    system = build(sc)
    n_grid = int(round(sc.duration_s / h))
    mods = {name: variant_kernels(rep) for name, rep in VARIANTS.items()}
    for mod in mods.values():  # compile
        with kernels(mod):
            _cpu(system, h, 8)
    _cpu(system, h, 8)
    ratios = {name: [] for name in (*mods, "two RK4 steps per interval (default kernels)")}
    for _ in range(repeats):
        base = _cpu(system, h, n_grid)
        for name, mod in mods.items():
            with kernels(mod):
                ratios[name].append(_cpu(system, h, n_grid) / base)
        ratios["two RK4 steps per interval (default kernels)"].append(
            _cpu(system, h, n_grid, 2) / _cpu(system, h, n_grid))
    return [(name, float(np.median(v)), min(v), max(v)) for name, v in ratios.items()]


def _rk4_loads(system, elastic, h, n_sub, n_grid, n_short):
    """A Python RK4 from the settled state over ``n_grid`` grid intervals: per step the
    loads at its start (inner then outer, (2 Z,)) and their RK4 quadrature over the
    step; over the first ``n_short`` intervals also the elastic share of the inner
    loads (``elastic``: the system without Kramer's damping) at the step's start and its
    quadrature over the step."""
    y = integrate(system, h_out=h, n_out=0, stride=1, dt=h / n_sub)["y_end"]
    dt = h / n_sub
    out = {"start": [], "quad": [], "el_start": [], "el_quad": []}
    w = (1.0, 2.0, 2.0, 1.0)
    for step in range(n_grid * n_sub + 1):
        t = step * dt
        ks, loads, el = [], [], []
        for c in (0.0, 0.5, 0.5, 1.0):
            ys = y if not ks else y + c * dt * ks[-1]
            d, qi, qo = system._eval(t + c * dt, ys)
            ks.append(d)
            loads.append(np.concatenate((qi, qo)))
            if step <= n_short * n_sub:
                el.append(elastic.contact_loads(t + c * dt, ys)[0])
        out["start"].append(loads[0])
        out["quad"].append(sum(wi * q for wi, q in zip(w, loads, strict=True)) / 6.0)
        if el:
            out["el_start"].append(el[0])
            out["el_quad"].append(sum(wi * q for wi, q in zip(w, el, strict=True)) / 6.0)
        y = y + dt / 6.0 * (ks[0] + 2.0 * ks[1] + 2.0 * ks[2] + ks[3])
    return {k: np.array(v) for k, v in out.items()}


def two_steps(scenes, h, n_ref, short_s=0.002, mean_s=0.02):
    """Why two RK4 steps per interval lose against three, on each scene of ``scenes``
    (name -> Scene). Short horizon (``short_s``, the inner loads at every fourth grid
    point, as recorded, against ``n_ref`` steps per interval, relative L2): the error in
    full, of its elastic share and of its damping share, and of the loads with the
    damping share taken as the mean of its RK4 quadratures over the two steps around
    the grid point. Centrifugal balance: the mean outer-minus-inner load of a ball over
    ``mean_s`` (after its first fifth), N, from the loads at the steps' starts (what is
    recorded) and from their quadratures over the steps (the force the steps apply)."""
    rows = []
    for name, sc in scenes.items():
        system = build(sc)
        p0 = system.p.copy()
        p0[K.P_TAU] = 0.0
        elastic = dataclasses.replace(system, p=p0)
        z = sc.bearing.n_elements
        n_short = int(round(short_s / h))
        runs = {}
        for n in (n_ref, 2, 3):
            r = _rk4_loads(system, elastic, h, n, int(round(mean_s / h)), n_short)
            idx = np.arange(0, n_short, 4) * n
            point = r["start"][idx, :z]
            el = r["el_start"][idx]
            damp_quad = r["quad"][:len(r["el_quad"]), :z] - r["el_quad"]
            before = np.maximum(idx - 1, 0)
            two = el + 0.5 * (damp_quad[before] + damp_quad[idx])
            two[idx == 0] = point[idx == 0]
            keep = slice(len(r["start"]) // 5, None)
            runs[n] = dict(point=point, elastic=el, damp=point - el, two=two,
                           mean_point=float(np.mean(r["start"][keep, z:] - r["start"][keep, :z])),
                           mean_quad=float(np.mean(r["quad"][keep, z:] - r["quad"][keep, :z])))
        ref = runs[n_ref]
        norm = np.linalg.norm(ref["point"])
        for n in (2, 3):
            r = runs[n]
            rows.append(dict(
                scene=name, n=n,
                full=float(np.linalg.norm(r["point"] - ref["point"]) / norm),
                elastic=float(np.linalg.norm(r["elastic"] - ref["elastic"]) / norm),
                damping=float(np.linalg.norm(r["damp"] - ref["damp"]) / norm),
                two_step=float(np.linalg.norm(r["two"] - ref["point"]) / norm),
                mean_point=r["mean_point"], mean_quad=r["mean_quad"],
                ref_point=ref["mean_point"], ref_quad=ref["mean_quad"]))
    return rows
