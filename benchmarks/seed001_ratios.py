"""Nabhan & Rashed (2020) reproduced: faulty/healthy indicator ratios of an inner-race fault
over speed.

Nabhan & Rashed (2020) (an MSC-ADAMS study of an SKF 6004 with an inner-race notch; DIGEST sections
1.2 and 2.4) plots the ratio faulty/healthy of RMS, crest factor, kurtosis and skewness
of the housing acceleration over 500-3000 rpm, for notch widths 0.25, 0.50 and 0.75 mm,
with accelerometers in the loaded zone (its Fig. 11) and the unloaded zone (Fig. 12).
This script simulates the same sweep with ballpass and draws the same figure.

Set-up (stated in docs/seed001.md): 6004, 500 N radial load, notch depth 0.5 mm (the
ball drops 2.5 / 9.9 / 22 um, Nabhan & Rashed (2020) eq. 26 with the ball diameter), notch at the
load line at t = 0, the Sawalhi-Randall 15 kHz / 5 % housing resonance at 48 kHz (as
the shipped grid speed_sweep_6004), sensors at 0 deg (loaded) and 180 deg (unloaded),
and **white measurement noise of a fixed 0.5 m/s^2 RMS**, the same for healthy and
faulty runs, so that a ratio compares machines, not signal-to-noise settings. Each
ratio divides the mean of an indicator over ``--repeats`` faulty runs (own seeds) by its
mean over as many healthy runs at the same speed.

    python benchmarks/seed001_ratios.py              # 11 speeds x 3 repeats, ~2 min on 2 cores
    python benchmarks/seed001_ratios.py --repeats 1 --step 500   # quick look

Writes ``docs/results/seed001_ratios.csv`` and ``docs/results/seed001_ratios.png``.
"""

from __future__ import annotations

import argparse
import itertools
from pathlib import Path

import numpy as np
import pandas as pd
from _paths import RESULTS_DIR
from joblib import Parallel, delayed

import ballpass as bp
from ballpass.features import indicators

WIDTHS_MM = (0.25, 0.5, 0.75)
DEPTH_MM = 0.5
FS = 48_000.0
RESONANCE_HZ, DAMPING = 15_000.0, 0.05
LOAD_N = 500.0
NOISE_RMS = 0.5  # m/s^2, white, the same for every run
SENSORS = ("loaded", "unloaded")
INDICATORS = ("rms", "crest_factor", "kurtosis", "skewness")
#: The simulator's decimation rings at both record ends (reported upstream): simulate
#: this much more on each side and cut it off, s.
PAD_S = 0.1


def simulate_run(width_mm: float | None, rpm: float, seed: int, duration_s: float) -> np.ndarray:
    """Acceleration (2, n) at the loaded and unloaded sensors, m/s^2; ``None`` = healthy."""
    fault = None if width_mm is None else bp.Fault("inner", width_mm=width_mm,
                                                   depth_mm=DEPTH_MM, angle_deg=0.0)
    scene = bp.Scene(bearing="6004", rpm=rpm, radial_load_n=LOAD_N, fault=fault,
                     duration_s=duration_s + 2 * PAD_S, fs=FS, seed=seed,
                     resonance_hz=RESONANCE_HZ, resonance_damping=DAMPING,
                     sensors=SENSORS, noise_rms=NOISE_RMS)
    pad = round(PAD_S * FS)
    return bp.simulate(scene).accel[:, pad:-pad]


def ratios(speeds, repeats: int = 3, duration_s: float = 1.0, n_jobs: int = 2) -> pd.DataFrame:
    """Faulty/healthy ratio of each indicator per width, speed and sensor.

    Returns
    -------
    pandas.DataFrame
        Columns ``width_mm``, ``rpm``, ``sensor``, ``indicator``, ``faulty``,
        ``healthy`` (means over the repeats) and ``ratio``.
    """
    cases = list(itertools.product((None, *WIDTHS_MM), speeds, range(repeats)))
    signals = Parallel(n_jobs=n_jobs)(
        delayed(simulate_run)(w, rpm, 1000 * i + k, duration_s)
        for i, (w, rpm, k) in enumerate(cases))
    rows = []
    for (w, rpm, k), x in zip(cases, signals, strict=True):
        values = indicators(x)
        for s, sensor in enumerate(SENSORS):
            rows += [{"width_mm": w, "rpm": rpm, "repeat": k, "sensor": sensor,
                      "indicator": name, "value": float(values[name][s])}
                     for name in INDICATORS]
    runs = pd.DataFrame(rows)
    mean = runs.groupby(["width_mm", "rpm", "sensor", "indicator"], dropna=False)["value"].mean()
    is_healthy = mean.index.get_level_values("width_mm").isna()
    healthy = mean[is_healthy].droplevel("width_mm").rename("healthy")
    faulty = mean[~is_healthy].rename("faulty").reset_index()
    out = faulty.join(healthy, on=["rpm", "sensor", "indicator"])
    out["ratio"] = out["faulty"] / out["healthy"]
    return out


def plot(table: pd.DataFrame, path: Path) -> None:
    """Figure like Nabhan & Rashed's Figs. 11-12: rows = sensor zone, columns = indicator."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import FormatStrFormatter, NullFormatter

    titles = {"rms": "RMS", "crest_factor": "crest factor", "kurtosis": "kurtosis",
              "skewness": "skewness"}
    fig = Figure(figsize=(13, 6.2), layout="constrained")
    axes = fig.subplots(len(SENSORS), len(INDICATORS), sharex=True)
    for (r, sensor), (c, name) in itertools.product(enumerate(SENSORS), enumerate(INDICATORS)):
        ax = axes[r, c]
        for w in WIDTHS_MM:
            part = table[(table.sensor == sensor) & (table.indicator == name)
                         & (table.width_mm == w)].sort_values("rpm")
            ax.plot(part.rpm, part.ratio, "o-", ms=3, label=f"{w:g} mm")
        ax.axhline(1.0, color="0.4", lw=0.8, ls="--")
        if name == "skewness":
            ax.set_yscale("symlog", linthresh=1.0)
            ax.text(0.02, 0.02, "healthy skewness ~ 0: the ratio is unstable",
                    transform=ax.transAxes, fontsize=7, color="0.3")
        elif name in ("rms", "kurtosis"):
            ax.set_yscale("log")
            ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))
            ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_title(f"{titles[name]} ratio, {sensor} zone", fontsize=9)
        ax.grid(alpha=0.3)
        if r == len(SENSORS) - 1:
            ax.set_xlabel("shaft speed (rpm)")
    axes[0, 0].legend(title="notch width", fontsize=8)
    fig.suptitle("SKF 6004 inner-race notch: faulty / healthy indicator ratios "
                 f"(noise {NOISE_RMS:g} m/s² RMS, {RESONANCE_HZ / 1000:g} kHz resonance)",
                 fontsize=10)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--step", type=float, default=250.0, help="speed step, rpm")
    parser.add_argument("--repeats", type=int, default=3, help="runs per point")
    parser.add_argument("--duration", type=float, default=1.0, help="s per run")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    speeds = np.arange(500.0, 3000.0 + 1e-9, args.step)
    table = ratios(speeds, repeats=args.repeats, duration_s=args.duration, n_jobs=args.jobs)
    csv = RESULTS_DIR / "seed001_ratios.csv"
    table.round(4).to_csv(csv, index=False)
    plot(table, RESULTS_DIR / "seed001_ratios.png")
    wide = table.pivot_table(index=["sensor", "indicator", "width_mm"], columns="rpm",
                             values="ratio")
    with pd.option_context("display.width", 200, "display.max_columns", 20):
        print(wide.round(2).to_string())
    print(f"wrote {csv} and {RESULTS_DIR / 'seed001_ratios.png'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
