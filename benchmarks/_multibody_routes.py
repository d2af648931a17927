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
* Two steps with the overdamped radial mode integrated exactly: a copy of the kernels
  whose RK4 step is the exponential RK4 of Cox & Matthews (2002) on the fast root of
  every overdamped loaded contact block (:data:`ETD`), its CPU time at two steps per
  interval against the default, its errors in the work-precision table.
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


#: The exponential RK4 step (ETDRK4, Cox & Matthews 2002) in a copy of the kernels:
#: the fast root of every overdamped loaded contact block (each ball's centre and the
#: outer race, frozen at the step's start) integrated exactly inside the RK4 stages, the
#: rest of the state by classical RK4 (the same ODE; only its integration). Compiled in
#: place of the kernels' RK4 step for dynamic balls (:data:`ETD`).
ETD_SOURCE = '''
#: 1 / k! for k = 0..19 (the phi functions' Taylor coefficients)
INV_FACT = np.array([1.0 / math.factorial(k) for k in range(20)])
#: per body in ``prop`` of :func:`etd_blocks`: the first eigenvector of K (cos, sin),
#: then per direction its fast root s1 (0: not in L), its slow root s2, and of s1
#: exp(z / 2), h / 2 phi_1(z / 2) and the three weights of Cox & Matthews (2002)
ETD_COLS = 2 + 2 * 7
#: a direction's fast root is in L only when the block's roots are real and apart:
#: c^2 / 4 - w0 >= ETD_SPLIT (c / 2)^2 (root ratio >= 3, the modal projection's
#: condition number below 3); nearer critical damping its fastest root is at most
#: 1.5 c / 2 and RK4 takes the block explicitly
ETD_SPLIT = 0.25


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _phi123(z, em):
    """phi_1, phi_2, phi_3 of a real z <= 0 (phi_k(z) = sum_i z^i / (i + k)!), ``em``
    = expm1(z): by their Taylor series for |z| <= 0.5 (16 terms: remainder below
    1e-19), by the recursion phi_(k+1) = (phi_k - 1 / k!) / z beyond (rounding below
    1e-14)."""
    if abs(z) <= 0.5:
        p1 = INV_FACT[16]
        p2 = INV_FACT[17]
        p3 = INV_FACT[18]
        for i in range(14, -1, -1):
            p1 = p1 * z + INV_FACT[i + 1]
            p2 = p2 * z + INV_FACT[i + 2]
            p3 = p3 * z + INV_FACT[i + 3]
        return p1, p2, p3
    p1 = em / z
    p2 = (p1 - 1.0) / z
    p3 = (p2 - 0.5) / z
    return p1, p2, p3


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _root_coefs(s, h, out, o):
    """For a root s (1/s) of a block and the step h: exp(h s / 2), h / 2 phi_1(h s / 2)
    and Cox & Matthews' weights h (phi1 - 3 phi2 + 4 phi3), h (2 phi2 - 4 phi3),
    h (4 phi3 - phi2) of z = h s into out[o:o + 5]."""
    z = h * s
    em2 = math.expm1(0.5 * z)
    q1, _, _ = _phi123(0.5 * z, em2)
    p1, p2, p3 = _phi123(z, em2 * (em2 + 2.0))
    out[o] = em2 + 1.0
    out[o + 1] = 0.5 * h * q1
    out[o + 2] = h * (p1 - 3.0 * p2 + 4.0 * p3)
    out[o + 3] = h * (2.0 * p2 - 4.0 * p3)
    out[o + 4] = h * (4.0 * p3 - p2)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def etd_blocks(kb, p, h, prop):
    """The linear part L of the exponential RK4 step, frozen over a step: per body
    (every ball's centre, the outer race) the contact block [[0, I], [-K/m, -tau K/m]]
    (K from :func:`ball_stiffness`) is split along the two eigenvectors of the symmetric
    K into two scalar blocks [[0, 1], [-w0, -c]] (w0 = k/m, c = tau w0) with roots
    s1 < s2 < 0 (s1 s2 = w0); where they are real and apart (:data:`ETD_SPLIT`: an
    overdamped loaded contact) L holds the fast one, s1 times the projection onto its
    mode (x, v) = m1 (1, s1), m1 = (s2 x - v) / (s2 - s1); every other part of the
    state is outside L (classical RK4). Writes ``prop`` (Z + 1, ETD_COLS)."""
    z = int(p[P_Z])
    tau = p[P_TAU]
    for j in range(z + 1):
        inv_m = 1.0 / (p[P_MB] if j < z else p[P_MO])
        a, b, d = kb[j, 0], kb[j, 1], kb[j, 2]
        mean = 0.5 * (a + d)
        r = math.sqrt(0.25 * (a - d) * (a - d) + b * b)
        if r <= 0.0:
            ex, ey = 1.0, 0.0
        else:
            if a >= d:
                ex, ey = mean + r - d, b
            else:
                ex, ey = b, mean + r - a
            nrm = math.sqrt(ex * ex + ey * ey)
            ex /= nrm
            ey /= nrm
        prop[j, 0] = ex
        prop[j, 1] = ey
        for k in range(2):
            o = 2 + 7 * k
            w0 = (mean + r if k == 0 else mean - r) * inv_m
            c = tau * w0
            disc = 0.25 * c * c - w0
            if w0 <= 0.0 or disc < ETD_SPLIT * 0.25 * c * c:
                prop[j, o] = 0.0
                continue
            s1 = -0.5 * c - math.sqrt(disc)
            prop[j, o] = s1
            prop[j, o + 1] = w0 / s1  # the slow root, without cancellation
            _root_coefs(s1, h, prop[j], o + 2)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _fast_add(out, v, prop, p, col, rk4):
    """out += c m1(v) (1, s1) on every body's centre along each direction whose fast
    root s1 is in L (:func:`etd_blocks`), m1(v) the fast mode's coordinate of v there:
    c = g / rk4 - 1, g the coefficient in column ``col`` (0: exp(z/2), 1: h/2
    phi_1(z/2), 2-4: the weights), or with ``col`` -1 c = -s1 (out -= L v)."""
    z = int(p[P_Z])
    nd = 6 + 3 * z
    for j in range(z + 1):
        b = 6 + 3 * j if j < z else 3
        m = prop[j]
        for k in range(2):
            o = 2 + 7 * k
            s1 = m[o]
            if s1 == 0.0:
                continue
            if k == 0:
                dx, dy = m[0], m[1]
            else:
                dx, dy = -m[1], m[0]
            s2 = m[o + 1]
            xv = dx * v[b] + dy * v[b + 1]
            vv = dx * v[nd + b] + dy * v[nd + b + 1]
            if col < 0:
                m1 = -(s1 * (s2 * xv - vv) / (s2 - s1))
            else:
                m1 = (s2 * xv - vv) / (s2 - s1) * (m[o + 2 + col] / rk4 - 1.0)
            out[b] += dx * m1
            out[b + 1] += dy * m1
            out[nd + b] += dx * s1 * m1
            out[nd + b + 1] += dy * s1 * m1


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _etd_apply(v, prop, p, col, rk4):
    """v <- g(h L) v: on the fast mode of every block in L g's coefficient in column
    ``col`` (0: exp(z/2), 1: h/2 phi_1(z/2), 2-4: the weights; :func:`etd_blocks`),
    everywhere else the scalar ``rk4`` (g at z = 0)."""
    _fast_add(v, v, prop, p, col, rk4)
    for k in range(v.shape[0]):
        v[k] *= rk4


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _minus_lw(k, w, prop, p):
    """k <- k - L w on every body's centre (L as in :func:`etd_blocks`)."""
    _fast_add(k, w, prop, p, -1, 1.0)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _half_stage(t, y, h, src, w, tmp, out, prop, p, faults, sensors, qi, qo, flags, e):
    """A mid-step stage of :func:`_etd_stages`: w = h/2 phi_1(h L / 2) ``src``, ``out``
    = N(w) = f(t + h/2, y + w) - L w."""
    for k in range(y.shape[0]):
        w[k] = src[k]
    _etd_apply(w, prop, p, 1, 0.5 * h)
    for k in range(y.shape[0]):
        tmp[k] = y[k] + w[k]
    rhs(t + 0.5 * h, tmp, out, p, faults, sensors, qi, qo, flags, e, True)
    _minus_lw(out, w, prop, p)


@njit(cache=True, error_model="numpy", **_NO_RUNTIME)
def _etd_stages(t, y, h, k1, k2, k3, k4, tmp, w, kb, prop, p, faults, sensors, qi, qo,
                flags, e2, e3, e4):
    """One exponential RK4 step (ETDRK4, Cox & Matthews 2002) of y (in place),
    k1 = f(t, y) given: the deviation w = y(t) - y_n solves w' = L w + N(w),
    N(w) = f(y_n + w) - L w, L the overdamped contact blocks frozen at y_n (``prop``:
    :func:`etd_blocks`), exactly for constant N; where L is zero the step is classical
    RK4. Overwrites k1."""
    n = y.shape[0]
    # a = h/2 phi1 N(0), then b = h/2 phi1 N_a
    _half_stage(t, y, h, k1, w, tmp, k2, prop, p, faults, sensors, qi, qo, flags, e2)
    _half_stage(t, y, h, k2, w, tmp, k3, prop, p, faults, sensors, qi, qo, flags, e3)
    # c = E2 a + h/2 phi1 (2 N_b - N_0)
    for k in range(n):
        w[k] = k1[k]
    _etd_apply(w, prop, p, 1, 0.5 * h)
    _etd_apply(w, prop, p, 0, 1.0)
    for k in range(n):
        k4[k] = 2.0 * k3[k] - k1[k]
    _etd_apply(k4, prop, p, 1, 0.5 * h)
    for k in range(n):
        w[k] += k4[k]
        tmp[k] = y[k] + w[k]
    rhs(t + h, tmp, k4, p, faults, sensors, qi, qo, flags, e4, True)
    _minus_lw(k4, w, prop, p)  # N_c
    # y += f1 N_0 + f2 (N_a + N_b) + f3 N_c
    for k in range(n):
        w[k] = k2[k] + k3[k]
    _etd_apply(k1, prop, p, 2, h / 6.0)
    _etd_apply(w, prop, p, 3, h / 3.0)
    _etd_apply(k4, prop, p, 4, h / 6.0)
    for k in range(n):
        y[k] += k1[k] + w[k] + k4[k]
'''
_RK4_BRANCH = """        if method == METHOD_RK4:
            if qs:"""
_ETD_BRANCH = """        if method == METHOD_RK4 and not qs:
            ball_stiffness(y, p, qi, qo, kb)
            etd_blocks(kb, p, h, prop)
            _etd_stages(t, y, h, k1, k2, k3, k4, tmp, gsum, kb, prop, p, faults, sensors,
                        qi, qo, flags, e2, e3, e4)
            if step >= n_pre:
                for s in range(ns):
                    acc[s] += dt / 6.0 * (e1[s] + 2.0 * e2[s] + 2.0 * e3[s] + e4[s])
        elif method == METHOD_RK4:
            if qs:"""
_KB = "    kb = np.zeros((z + 1, 3))\n"
ETD_NAME = "exponential RK4 (ETDRK4 on the overdamped contact modes), two steps per interval"
#: the replacements that make a copy of the kernels step by ETDRK4 (``solver="rk4"``)
ETD = [(_KB, _KB + "    prop = np.zeros((z + 1, ETD_COLS))\n"), (_RK4_BRANCH, _ETD_BRANCH),
       ("\n\n@njit(cache=True, error_model=\"numpy\", **_NO_RUNTIME)\ndef _log_crossings(",
        ETD_SOURCE + "\n\n@njit(cache=True, error_model=\"numpy\", **_NO_RUNTIME)\n"
        "def _log_crossings(")]


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
    """CPU time of the integration (``sc``, default step) with each kernel variant, with
    two steps per interval and with two exponential RK4 steps per interval (:data:`ETD`),
    interleaved with the unchanged kernels. Returns rows
    (name, medians of the ratios to the unchanged kernels' time, min, max)."""
    system = build(sc)
    n_grid = int(round(sc.duration_s / h))
    mods = {name: variant_kernels(rep) for name, rep in VARIANTS.items()}
    for mod in mods.values():  # compile
        with kernels(mod):
            _cpu(system, h, 8)
    _cpu(system, h, 8)
    etd = variant_kernels(ETD)
    with kernels(etd):
        _cpu(system, h, 8)
    ratios = {name: [] for name in (*mods, "two RK4 steps per interval (default kernels)",
                                    ETD_NAME)}
    for _ in range(repeats):
        base = _cpu(system, h, n_grid)
        for name, mod in mods.items():
            with kernels(mod):
                ratios[name].append(_cpu(system, h, n_grid) / base)
        ratios["two RK4 steps per interval (default kernels)"].append(
            _cpu(system, h, n_grid, 2) / _cpu(system, h, n_grid))
        base = _cpu(system, h, n_grid)
        with kernels(etd):
            ratios[ETD_NAME].append(_cpu(system, h, n_grid, 2) / base)
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
