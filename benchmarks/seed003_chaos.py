"""Why the NJ 305 rotor (``rotor2``) is non-periodic at every speed: checks outside the model.

1. ``agreement``: the rotor's equations written again here in NumPy (:func:`rotor_rhs`,
   healthy bearing) and integrated with :func:`scipy.integrate.solve_ivp` (DOP853, rtol
   1e-10) against rotor2's rk4, strobed once per roller pass: the two agree until their
   difference, amplified at the Lyapunov rate, reaches the attractor's size.
2. ``lyapunov``: the largest Lyapunov exponent of those equations
   (:func:`ballpass.dynamics.largest_lyapunov_exponent`) at four speeds, at the paper's
   set-up (0.125 mm) and at 0.01 mm.
3. ``sweep``: rotor2 over the paper's unstated parameters (unbalance m_u e, contact
   damping, clearance) at three speeds, each run classed from its Poincare section; and a
   bifurcation diagram over speed for two settings.

    PYTHONPATH=$PWD nice -n 10 python benchmarks/seed003_chaos.py   # ~25 min, busy 2 cores
    # (the Lyapunov exponents take two thirds; --only STEP reruns one step)

Writes ``docs/results/seed003_chaos_*.csv`` and ``docs/results/seed003_chaos.png``;
benchmarks/seed003.py quotes them on docs/seed003.md.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
import pandas as pd
from _paths import RESULTS_DIR as RESULTS
from scipy.integrate import solve_ivp
from scipy.interpolate import make_interp_spline

import ballpass as bp
from ballpass.simulate import Rotor2Parameters

#: the paper's section 3.6 set-up: 0.125 mm radial clearance, gravity only
CLEARANCE_MM = 0.125
#: speeds of the Lyapunov exponents, rpm (the paper's four and its 2000)
SPEEDS = (500.0, 900.0, 1500.0, 2000.0)


def scene(clearance_mm: float, rpm: float, duration: float, fs: float = 20_000.0) -> bp.Scene:
    """The paper's healthy NJ 305 under gravity alone (rotor2 ignores the resonance)."""
    b = bp.Bearing.catalog("NJ305").with_clearance(clearance_mm)
    return bp.Scene(bearing=b, rpm=rpm, radial_load_n=0.0, duration_s=duration, fs=fs,
                    resonance_hz=0.4 * fs)


def rotor_rhs(s: bp.Scene, params: Rotor2Parameters):
    """The rigid rotor's equations (rotor2's module docstring), healthy and aligned,
    from the bearing's data alone: state (x, y, x', y') in m and m/s, x along gravity.

    m x'' + c x' + sum Q_j cos(phi_j) = m g + m_u e w^2 cos(w t + u),
    m y'' + c y' + sum Q_j sin(phi_j) =       m_u e w^2 sin(w t + u),
    Q_j = K max(0, x cos(phi_j) + y sin(phi_j) - c_r)^n (+ c_d along the loaded contact),
    phi_j = phi_0 + 2 pi j / Z + r_c w t.
    """
    b = s.bearing
    k, n, cr, z = b.hertz_stiffness(), b.load_exponent, b.radial_clearance_m, b.n_elements
    cage = b.frequencies(1.0).ftf
    w = s.rpm * math.pi / 30.0
    m, c, cd = params.rotor_mass_kg, params.bearing_damping_ns_m, params.contact_damping_ns_m
    fu = params.unbalance_mass_kg * params.unbalance_eccentricity_m * w * w
    u = math.radians(params.unbalance_phase_deg)
    phi0 = math.radians(params.cage_angle_deg) + 2.0 * math.pi * np.arange(z) / z
    g = bp.scene.STANDARD_GRAVITY if s.gravity else 0.0

    def rhs(t, y):
        phi = phi0 + cage * w * t
        cs, sn = np.cos(phi), np.sin(phi)
        delta = y[0] * cs + y[1] * sn - cr
        q = np.where(delta > 0.0, k * np.maximum(delta, 0.0) ** n
                     + cd * (y[2] * cs + y[3] * sn), 0.0)
        q = np.maximum(q, 0.0)
        fx = m * g + fu * math.cos(w * t + u) - c * y[2] - q @ cs
        fy = fu * math.sin(w * t + u) - c * y[3] - q @ sn
        return np.array([y[2], y[3], fx / m, fy / m])

    return rhs


def roller_pass_hz(s: bp.Scene) -> float:
    """Rate at which rollers pass a point of the outer ring (BPFO), Hz."""
    return s.frequencies.bpfo


def strobe(t: np.ndarray, xy: np.ndarray, rate_hz: float, t0: float) -> np.ndarray:
    """(x, y) at t = k / rate_hz >= t0 (cubic spline of ``xy`` (n, 2) over ``t``)."""
    tk = np.arange(math.ceil(t0 * rate_hz), math.floor(t[-1] * rate_hz) + 1) / rate_hz
    return make_interp_spline(t, xy, k=3)(tk)


#: instants at which the solvers' differences are tabulated, ms
AGREEMENT_MS = (1, 2, 5, 10, 20, 40, 60, 100)


def agreement(quick: bool) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Four integrations of the same equations from the same state against solve_ivp's
    DOP853 at rtol 1e-10: rotor2's rk4 (default step) and dopri5 (rtol 1e-10), DOP853 at
    rtol 1e-8 and Radau at rtol 1e-10 on :func:`rotor_rhs`.

    Returns the largest x-y difference up to each of ``AGREEMENT_MS`` per pair, and the
    roller-pass sections of rk4 and of the reference after a 50 ms transient (point by
    point they differ; as clouds they should not)."""
    duration = 0.1 if quick else 0.3
    rows, clouds = [], []
    for rpm in (900.0, 2000.0):
        s = scene(CLEARANCE_MM, rpm, duration)
        params = Rotor2Parameters()
        runs = {name: bp.simulate(s, model="rotor2", return_forces=True, params=params,
                                  **kw).truth.displacement
                for name, kw in (("rotor2 rk4 (default step)", {}),
                                 ("rotor2 dopri5, rtol 1e-10",
                                  dict(solver="dopri5", rtol=1e-10)))}
        t = np.arange(s.n_samples) / s.fs
        y0 = np.concatenate((runs["rotor2 rk4 (default step)"][:, 0], [0.0, 0.0]))
        f = rotor_rhs(s, params)
        ivp = {}
        for name, method, rtol in (("reference", "DOP853", 1e-10),
                                   ("solve_ivp DOP853, rtol 1e-8", "DOP853", 1e-8),
                                   ("solve_ivp Radau, rtol 1e-10", "Radau", 1e-10)):
            t0 = time.perf_counter()
            ivp[name] = solve_ivp(f, (0.0, t[-1]), y0, method=method, rtol=rtol,
                                  atol=rtol * 1e-6, t_eval=t).y[:2]
            print(f"{rpm:.0f} rpm {name}: {time.perf_counter() - t0:.0f} s", flush=True)
        ref = ivp.pop("reference")
        runs.update(ivp)
        orbit = float(np.ptp(ref[0, t >= 0.05]))
        for name, xy in runs.items():
            diff = np.linalg.norm(xy - ref, axis=0)
            for ms in AGREEMENT_MS:
                n = int(ms * 1e-3 * s.fs)
                if n <= t.size:
                    rows.append(dict(rpm=rpm, solver=name, t_ms=ms,
                                     max_diff_um=float(diff[:n].max()) * 1e6,
                                     orbit_um=orbit * 1e6))
        fp = roller_pass_hz(s)
        for name, xy in (("rk4", runs["rotor2 rk4 (default step)"]), ("reference", ref)):
            sec = strobe(t, xy.T, fp, 0.05)
            clouds.append(pd.DataFrame(dict(rpm=rpm, solver=name, x_um=sec[:, 0] * 1e6,
                                            y_um=sec[:, 1] * 1e6)))
    return pd.DataFrame(rows), pd.concat(clouds, ignore_index=True)


#: the exponents' cases: (clearance mm, contact damping N s/m) -> speeds (rpm); at zero
#: clearance the rotor never leaves its rollers (the reference case of a forced, damped
#: response); c_d = 2000 N s/m at 800 and 1500 rpm checks the second diagram's regimes
LYAPUNOV_CASES = {(CLEARANCE_MM, 0.0): SPEEDS, (0.01, 0.0): SPEEDS,
                  (0.0, 0.0): (900.0, 2000.0), (CLEARANCE_MM, 2000.0): (800.0, 1500.0)}


def lyapunov(quick: bool, cases: dict | None = None) -> pd.DataFrame:
    """Largest Lyapunov exponent for ``cases`` (default ``LYAPUNOV_CASES``), renormalized
    once per roller pass, after a 0.1 s transient."""
    duration = 0.1 if quick else 0.5
    rows = []
    for (clearance, cd), speeds in (cases or LYAPUNOV_CASES).items():
        for rpm in speeds:
            s = scene(clearance, rpm, 0.01)
            params = Rotor2Parameters(contact_damping_ns_m=cd)
            x0 = bp.simulate(s, model="rotor2", return_forces=True,
                             params=params).truth.displacement[:, 0]
            fp = roller_pass_hz(s)
            omega = bp.simulate.rotor2.contact_omega(s, params)
            # displacement in units of 1 um, velocity in 1 um times the contact rate
            sc = np.array([1e-6, 1e-6, 1e-6 * omega, 1e-6 * omega])
            t0 = time.perf_counter()
            lam, run = bp.dynamics.largest_lyapunov_exponent(
                rotor_rhs(s, params), np.concatenate((x0, [0.0, 0.0])), duration,
                renormalize_s=1.0 / fp, transient_s=0.1, d0=1e-6, scale=sc,
                rtol=1e-10, atol=1e-16)
            half = run[len(run) // 2]
            rows.append(dict(clearance_mm=clearance, contact_damping_ns_m=cd, rpm=rpm,
                             lyapunov_1_s=lam,
                             at_half_1_s=half, per_roller_pass=lam / fp,
                             per_revolution=lam / s.shaft_hz,
                             doubling_ms=(math.log(2) / lam * 1e3 if lam > 0 else np.nan),
                             roller_pass_hz=fp, wall_s=time.perf_counter() - t0))
            print(rows[-1], flush=True)
    return pd.DataFrame(rows)


def classify(ts: np.ndarray, xy: np.ndarray, rate_hz: float, t0: float, orbit: float,
             max_period: int = 8) -> tuple[str, int, float]:
    """Period of the section of ``xy`` strobed at ``rate_hz`` after ``t0``.

    Period p when every point returns within 1e-2 of the orbit's peak-to-peak size
    ``orbit`` (m) after p strobes (a numerical floor: rk4's relative error is ~3e-3 at
    its default step, so tighter would call a period-1 orbit non-periodic);
    otherwise "non-periodic". Returns the class, the period (0: none) and the section's
    spread (largest peak-to-peak of x and y), m."""
    sec = strobe(ts, xy, rate_hz, t0)
    tol = 1e-2 * orbit
    for p in range(1, max_period + 1):
        if len(sec) > 2 * p and np.max(np.linalg.norm(sec[p:] - sec[:-p], axis=1)) < tol:
            return f"period {p}", p, float(np.ptp(sec, axis=0).max())
    return "non-periodic", 0, float(np.ptp(sec, axis=0).max())


def _run(clearance, rpm, params, revs, skip):
    s = scene(clearance, rpm, revs * 60.0 / rpm, fs=max(4000.0, 40.0 * rpm / 60.0 * 4.33))
    res = bp.simulate(s, model="rotor2", return_forces=True, params=params)
    xy = res.truth.displacement.T
    t0 = skip * 60.0 / rpm
    orbit = float(np.ptp(xy[res.t >= t0], axis=0).max())
    return s, res, xy, t0, orbit


#: the sweep's settings: unbalance m_u e (kg m), contact damping (N s/m), clearance (mm)
UNBALANCE = (0.0, 1e-6, 2e-5, 2e-4)
CONTACT_DAMPING = (0.0, 200.0, 2000.0)
CLEARANCES = (0.0, 0.01, 0.05, 0.125)


def sweep(quick: bool) -> pd.DataFrame:
    """rotor2 over unbalance x contact damping x clearance at three speeds."""
    revs, skip = (40, 20) if quick else (100, 50)
    rows = []
    for mue in UNBALANCE:
        for cd in CONTACT_DAMPING:
            params = Rotor2Parameters(unbalance_mass_kg=0.05 if mue else 0.0,
                                      unbalance_eccentricity_m=mue / 0.05,
                                      contact_damping_ns_m=cd)
            for clearance in CLEARANCES:
                for rpm in (500.0, 1000.0, 2000.0):
                    s, res, xy, t0, orbit = _run(clearance, rpm, params, revs, skip)
                    shaft = classify(res.t, xy, s.shaft_hz, t0, orbit)
                    rp = classify(res.t, xy, roller_pass_hz(s), t0, orbit)
                    rows.append(dict(unbalance_kg_m=mue, contact_damping_ns_m=cd,
                                     clearance_mm=clearance, rpm=rpm, orbit_um=orbit * 1e6,
                                     shaft_strobe=shaft[0], shaft_spread_um=shaft[2] * 1e6,
                                     shaft_spread_rel=shaft[2] / orbit,
                                     roller_strobe=rp[0], roller_spread_um=rp[2] * 1e6,
                                     roller_spread_rel=rp[2] / orbit))
        print(f"unbalance {mue:g} done", flush=True)
    return pd.DataFrame(rows)


#: the bifurcation diagrams' settings: label -> (clearance mm, Rotor2Parameters)
DIAGRAMS = {
    "paper's set-up (0.125 mm, m_u e = 1e-6 kg m)": (CLEARANCE_MM, Rotor2Parameters()),
    "paper's set-up with contact damping c_d = 2000 N s/m": (
        CLEARANCE_MM, Rotor2Parameters(contact_damping_ns_m=2000.0)),
}


def diagrams(quick: bool) -> pd.DataFrame:
    """Sections once per roller pass over speed for the DIAGRAMS settings."""
    revs, skip = (30, 20) if quick else (80, 50)
    speeds = np.linspace(500.0, 2000.0, 8 if quick else 31)
    frames = []
    for label, (clearance, params) in DIAGRAMS.items():
        for rpm in speeds:
            s, res, xy, t0, orbit = _run(clearance, rpm, params, revs, skip)
            sec = strobe(res.t, xy, roller_pass_hz(s), t0)
            kind, _, spread = classify(res.t, xy, roller_pass_hz(s), t0, orbit)
            frames.append(pd.DataFrame(dict(setting=label, rpm=rpm, x_um=sec[:, 0] * 1e6,
                                            y_um=sec[:, 1] * 1e6, orbit_um=orbit * 1e6,
                                            section=kind, spread_rel=spread / orbit)))
    return pd.concat(frames, ignore_index=True)


def plot(d: dict) -> None:
    """The figure: solvers against the reference, the exponents, rk4's and the
    reference's sections, the two diagrams."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 2, figsize=(11, 11), layout="constrained")
    ax = axes[0, 0]
    for (rpm, name), g in d["agreement"].groupby(["rpm", "solver"], sort=False):
        ax.loglog(g.t_ms, g.max_diff_um, "o-" if rpm < 1000 else "s--", ms=3, lw=0.8,
                  label=f"{name}, {rpm:.0f} rpm")
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("largest |difference| so far (µm)")
    ax.set_title("against solve_ivp DOP853 rtol 1e-10, same equations and state",
                 fontsize=9)
    ax.legend(fontsize=6)
    ax = axes[0, 1]
    for (c, cd), g in d["lyapunov"].groupby(["clearance_mm", "contact_damping_ns_m"]):
        ax.plot(g.rpm, g.lyapunov_1_s, "o-", label=f"clearance {c:g} mm, c_d {cd:g} N s/m")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("rpm")
    ax.set_ylabel("largest Lyapunov exponent (1/s)")
    ax.legend(fontsize=7)
    for ax, (rpm, g) in zip(axes[1], d["clouds"].groupby("rpm"), strict=True):
        for name, h in g.groupby("solver"):
            ax.plot(h.y_um, h.x_um, ".", ms=3, label=name, alpha=0.7)
        ax.set_xlabel("y at each roller pass (µm)")
        ax.set_ylabel("x (µm)")
        ax.set_title(f"Poincaré sections per roller pass, {rpm:.0f} rpm", fontsize=9)
        ax.legend(fontsize=7)
    for ax, (label, g) in zip(axes[2], d["diagrams"].groupby("setting", sort=False),
                              strict=True):
        # y: the rotor rolls sideways over the rollers, x moves 10x less
        ax.plot(g.rpm, g.y_um, ".", ms=1, color="k")
        ax.set_xlabel("rpm")
        ax.set_ylabel("y at each roller pass (µm)")
        ax.set_title(label, fontsize=9)
    fig.savefig(RESULTS / "seed003_chaos.png", dpi=110)


#: CSVs in docs/results/
CSVS = {"agreement": "seed003_chaos_agreement.csv", "clouds": "seed003_chaos_clouds.csv",
        "lyapunov": "seed003_chaos_lyapunov.csv", "sweep": "seed003_chaos_sweep.csv",
        "diagrams": "seed003_chaos_diagrams.csv"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="shorter records, fewer values")
    ap.add_argument("--only", choices=["agreement", "lyapunov", "sweep", "diagrams"],
                    help="recompute one step only")
    args = ap.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    RESULTS.mkdir(parents=True, exist_ok=True)
    steps = {"agreement": agreement, "lyapunov": lyapunov, "sweep": sweep,
             "diagrams": diagrams}
    for key, fn in steps.items():
        if args.only in (None, key):
            t0 = time.perf_counter()
            out = fn(args.quick)
            if key == "agreement":
                out, clouds = out
                clouds.to_csv(RESULTS / CSVS["clouds"], index=False)
            out.to_csv(RESULTS / CSVS[key], index=False)
            print(f"{key}: {time.perf_counter() - t0:.0f} s", flush=True)
    d = {k: pd.read_csv(RESULTS / f) for k, f in CSVS.items() if (RESULTS / f).exists()}
    if len(d) == len(CSVS):
        plot(d)


if __name__ == "__main__":
    main()
