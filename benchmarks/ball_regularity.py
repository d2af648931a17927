"""Real CWRU ball faults against the simulated ball rows of the shipped grid.

Nakhaeinejad & Bryant (2011) find the harmonics of a ball fault clear in simulation
but not in measurement and blame the ball's three-dimensional rotation; Smith & Randall
(2015) grade most CWRU ball records partly or not diagnosable. This script puts numbers
on the difference, one-second segment by segment:

* the squared envelope spectrum (band from the fast kurtogram) at BSF, 2xBSF, its
  +-FTF sidebands (the cage carries the defect round the load zone) and 4xBSF, each
  line in dB above the median of the spectrum within +-20 Hz;
* the kurtosis of the raw segment and of the demodulation band;
* how regular the impacts are: the squared envelope's largest value in each 1/(2 BSF)
  period, and the coefficient of variation (std / mean) of those maxima: a comb of
  equal strikes gives a small one, strikes of random size or missing ones a large one.

Sources: every shared CWRU ball record at its faulty bearing's own sensor (drive-end
6205 at DE, fan-end 6203 at FE), and the ball runs of the shipped grid
``sim2real_cwru`` (6205, drawn loads, resonances, noise) simulated three ways: a fixed
spin axis (every revolution strikes alike), the grid's engagement draw (0.2-0.7 of the
revolutions, each strike full) and a wandering spin axis (``Fault(spin_drift_deg=D)``,
D uniform in 0-90 deg, engagement 1).

Run::

    PYTHONPATH=. python benchmarks/ball_regularity.py --cwru ../shared/data/cwru   # ~1 min

Writes ``docs/ball_regularity.md``, ``docs/results/ball_regularity.csv`` and
``docs/results/ball_regularity.png``.
"""

from __future__ import annotations

import argparse
import dataclasses
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
from _paths import DOCS, results_in
from _report import spread, table, write_csv, write_page
from scipy import signal, stats

import ballpass as bp
from ballpass.datasets import example_grid, read_grid
from ballpass.datasets.real import load_cwru_mat
from ballpass.features import fast_kurtogram

#: record -> (channel of the faulty bearing, its bearing)
RECORDS = {"12k_DE_B007_0.mat": ("DE", "6205"), "12k_DE_B021_0.mat": ("DE", "6205"),
           "12k_FE_B007_0.mat": ("FE", "6203"), "12k_FE_B014_0.mat": ("FE", "6203"),
           "12k_FE_B021_0.mat": ("FE", "6203")}
#: simulated variant -> fault fields given the run's own generator
VARIANTS = {
    "sim: fixed axis": lambda rng: {"engagement": 1.0, "spin_drift_deg": 0.0},
    "sim: engagement 0.2-0.7": lambda rng: {"engagement": rng.uniform(0.2, 0.7),
                                            "spin_drift_deg": 0.0},
    "sim: spin drift 0-90 deg": lambda rng: {"engagement": 1.0,
                                             "spin_drift_deg": rng.uniform(0.0, 90.0)},
}
#: envelope lines, as multiples of (BSF, FTF)
LINES = {"bsf": (1, 0), "2bsf": (2, 0), "2bsf-ftf": (2, -1), "2bsf+ftf": (2, 1),
         "4bsf": (4, 0)}
METRICS = ["2bsf_db", "bsf_db", "sideband_db", "4bsf_db", "kurtosis", "band_kurtosis",
           "strike_cv"]


def _line_db(freqs, ses, f) -> float:
    """Peak of the spectrum ``ses`` within +-1 % (at least 2 bins) of ``f``, in dB above
    its median within +-20 Hz."""
    df = freqs[1] - freqs[0]
    near = np.abs(freqs - f) <= max(2 * df, 0.01 * f)
    local = np.abs(freqs - f) <= 20.0
    return float(10 * np.log10(ses[near].max() / np.median(ses[local])))


def metrics(x, fs, bearing, rpm) -> dict:
    """The envelope lines, kurtoses and strike regularity of one segment (see above)."""
    fr = bp.Bearing.catalog(bearing).frequencies(rpm / 60.0)
    band = fast_kurtogram(x, fs).best_band
    sos = signal.butter(4, band, "bandpass", fs=fs, output="sos")
    y = signal.sosfiltfilt(sos, x)
    se = np.abs(signal.hilbert(y)) ** 2
    ses = np.abs(np.fft.rfft(se - se.mean())) / se.size
    freqs = np.fft.rfftfreq(se.size, 1.0 / fs)
    lines = {k: _line_db(freqs, ses, a * fr.bsf + b * fr.ftf) for k, (a, b) in LINES.items()}
    period = int(fs / (2.0 * fr.bsf))
    peaks = se[:se.size // period * period].reshape(-1, period).max(axis=1)
    return {"band_lo_hz": band[0], "band_hi_hz": band[1], "2bsf_db": lines["2bsf"],
            "bsf_db": lines["bsf"], "4bsf_db": lines["4bsf"],
            "sideband_db": max(lines["2bsf-ftf"], lines["2bsf+ftf"]),
            "kurtosis": float(stats.kurtosis(x)), "band_kurtosis": float(stats.kurtosis(y)),
            "strike_cv": float(peaks.std() / peaks.mean())}


def real_rows(folder: Path) -> list[dict]:
    rows = []
    for name, (channel, bearing) in RECORDS.items():
        path = folder / name
        if not path.exists():
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            rec = load_cwru_mat(path, channel=channel)
        n = int(rec.fs)
        for k in range(rec.accel.size // n):
            rows.append({"source": f"real {channel} ({bearing})", "record": name,
                         "segment": k, **metrics(rec.accel[k * n:(k + 1) * n], rec.fs,
                                                 bearing, rec.rpm)})
    return rows


def sim_rows(n_runs: int) -> list[dict]:
    runs = [r for r in read_grid(example_grid("sim2real_cwru")).runs
            if (r.scene.get("fault") or {}).get("kind") == "ball"][:n_runs]
    rows = []
    for variant, fields in VARIANTS.items():
        for run in runs:
            scene = run.build_scene()
            rng = np.random.default_rng(scene.seed)
            fault = dataclasses.replace(scene.fault, **fields(rng))
            scene = scene.replace(fault=fault)
            x = bp.simulate(scene).accel
            rows.append({"source": variant, "record": f"run {run.run_id}", "segment": 0,
                         "engagement": fault.engagement, "spin_drift_deg": fault.spin_drift_deg,
                         **metrics(x, scene.fs, "6205", scene.speed.rpm_start)})
    return rows


def figure(frame: pd.DataFrame, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for source, part in frame.groupby("source", sort=False):
        ax.scatter(part["2bsf_db"], part["strike_cv"], s=14, label=source, alpha=0.7)
    ax.set_xlabel("2xBSF line above its neighbourhood [dB]")
    ax.set_ylabel("strike-size variation (CV of per-period maxima)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def page(frame: pd.DataFrame, seconds: float, n_runs: int) -> list[str]:
    rows = []
    for source, part in frame.groupby("source", sort=False):
        rows.append([source, len(part), *[spread(part[m], ".1f") if m != "strike_cv"
                                          else spread(part[m]) for m in METRICS]])
    return [
        "# Real ball faults against simulated ones",
        "",
        f"Produced by `PYTHONPATH=. python benchmarks/ball_regularity.py --cwru DIR` "
        f"({seconds:.0f} s); do not edit by hand.",
        "",
        "One-second segments: every shared CWRU ball record at its faulty bearing's own "
        "sensor, and the first "
        f"{n_runs} ball runs of the shipped grid `sim2real_cwru` simulated with a fixed "
        "spin axis, with the grid's engagement draw (0.2-0.7 of the revolutions strike, "
        "each fully) and with a wandering spin axis (`Fault(spin_drift_deg=D)`, D "
        "uniform in 0-90 deg). Squared envelope spectrum in the fast kurtogram's band; "
        "each line in dB above the median of the spectrum within +-20 Hz (sideband: the "
        "stronger of 2xBSF+-FTF); kurtosis (Fisher, 0 for Gaussian) of the raw segment "
        "and of the band; strike CV: the coefficient of variation of the squared "
        "envelope's maxima over consecutive 1/(2 BSF) periods. Median (range).",
        "",
        *table(["source", "segments", "2xBSF dB", "BSF dB", "sideband dB", "4xBSF dB",
                "kurtosis", "band kurtosis", "strike CV"], rows, "lrrrrrrrr"),
        "",
        "![2xBSF line against strike-size variation](results/ball_regularity.png)",
        "",
        "Every segment is in `results/ball_regularity.csv`.",
    ]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cwru", type=Path, required=True, help="folder of CWRU .mat files")
    parser.add_argument("--runs", type=int, default=20, help="ball runs of the grid per variant")
    parser.add_argument("--out", type=Path, default=DOCS)
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    frame = pd.DataFrame(real_rows(args.cwru) + sim_rows(args.runs))
    results = results_in(args.out)
    write_csv(frame.round(4), results / "ball_regularity.csv")
    figure(frame, results / "ball_regularity.png")
    write_page(args.out / "ball_regularity.md", page(frame, time.perf_counter() - t0, args.runs))
    print(frame.groupby("source", sort=False)[METRICS].median().round(2).to_string())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
