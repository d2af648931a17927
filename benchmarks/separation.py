"""Discrete/random separation against exact removal of the periodic part.

A synthetic gearbox signal whose periodic part is known exactly: a 15-tooth mesh (one
ring of a 3.1 kHz resonance, 5 % damping, per tooth; tooth-to-tooth amplitudes fixed per
revolution, so the gear part is periodic in the shaft angle), inner-race impacts at BPFI
of a 6205 with 1 % random jitter of each period ringing a 2.9 kHz resonance, and white
noise. The gear part, eight times the bearing's ring amplitude, masks the fault: the
BPFI line of the squared envelope spectrum (SES, band 2-4 kHz) stands about 2-3 times
above its background (the median SES 3-30 Hz from it). Removing the gear part exactly
(subtracting the known signal) is the reference; ``separate_discrete`` with ``tsa``
(the shaft speed known), ``lp`` (linear prediction) and ``drs`` (discrete/random
separation, no speed) are measured against it, in dB of prominence, on 2000 rpm (a
whole number of samples per revolution at 48 kHz) and 1987 rpm, over seeds, for the
defaults, the gain DRS would apply with the spectra known exactly (its resolution ceiling),
and a scan of DRS's Welch segment and of LP's order.

Writes ``docs/results/separation.csv``, ``docs/separation.md`` (tables between markers of the
page) and ``docs/results/separation.png``.

    python benchmarks/separation.py              # 10 seeds, a few minutes
    python benchmarks/separation.py --seeds 2    # a quick look
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import pandas as pd
from _paths import DOCS, RESULTS_DIR
from scipy.signal import welch

import ballpass as bp
from ballpass.diagnose.report import markdown_table
from ballpass.features import envelope_spectrum, separate_discrete
from ballpass.features.separation import _apply_gain, _drs_nperseg

BAND = (2000.0, 4000.0)
GEAR_AMPLITUDE = 8.0   # ring amplitude of a tooth over a bearing impact's
NOISE_RMS = 0.3        # white noise, in bearing ring amplitudes
BPFI_ORDER = bp.Bearing.catalog("6205").frequencies(1.0).bpfi
#: (fs Hz, duration s): the issue's 1 s at 48 kHz, longer records (DRS's averages grow
#: with the record), and 2 s at 20 kHz
RECORDS = ((48_000.0, 1.0), (48_000.0, 2.0), (48_000.0, 4.0), (48_000.0, 8.0),
           (20_000.0, 2.0))
RPMS = (2000.0, 1987.0)
#: DRS's Welch segment around its default (the delay one segment, as by default)
DRS_SCAN = (8192, 16384, 32768, 65536)
LP_SCAN = (30, 100, 300)


def rings(times: np.ndarray, amplitudes: np.ndarray, f_n: float, fs: float, n: int,
          zeta: float = 0.05) -> np.ndarray:
    """Sum of unit-impulse responses of one resonance (Hz) started at ``times`` (s),
    exact at every sample (sub-sample start times), over 10 ms each."""
    x = np.zeros(n)
    w = 2 * np.pi * f_n
    wd = w * math.sqrt(1 - zeta**2)
    first = np.ceil(times * fs).astype(int)
    idx = first[:, None] + np.arange(int(0.01 * fs))[None, :]
    tau = idx / fs - times[:, None]
    inside = idx < n
    ring = amplitudes[:, None] * np.exp(-zeta * w * tau) * np.sin(wd * tau)
    np.add.at(x, idx[inside], ring[inside])
    return x


def gearbox_signal(rpm: float, fs: float, duration: float, seed: int):
    """(gear part, bearing part + noise, BPFI Hz) of one synthetic record."""
    rng = np.random.default_rng(seed)
    n = int(round(fs * duration))
    f_shaft = rpm / 60.0
    teeth = 1.0 + 0.3 * rng.standard_normal(15)
    k = np.arange(int(duration * f_shaft * 15) + 1)
    gear = GEAR_AMPLITUDE * rings(k / (15 * f_shaft), teeth[k % 15], 3100.0, fs, n)
    bpfi = BPFI_ORDER * f_shaft
    periods = (1.0 + 0.01 * rng.standard_normal(int(duration * bpfi) + 2)) / bpfi
    hits = np.cumsum(periods)
    hits = hits[hits < duration]
    bearing = rings(hits, np.ones(hits.size), 2900.0, fs, n)
    return gear, bearing + NOISE_RMS * rng.standard_normal(n), bpfi


def prominence(x: np.ndarray, fs: float, bpfi: float) -> float:
    """SES at BPFI (largest bin within 1 Hz) over the median SES 3-30 Hz from it."""
    f, a = envelope_spectrum(x, fs, band=BAND)
    near = (np.abs(f - bpfi) < 30) & (np.abs(f - bpfi) > 3)
    return float(a[np.abs(f - bpfi) <= 1.0].max() / np.median(a[near]))


def exact_spectra_gain(gear: np.ndarray, rest: np.ndarray, fs: float, rpm: float) -> np.ndarray:
    """The discrete part DRS would find with the spectra known exactly: the gain
    P_gear / (P_gear + P_rest) at DRS's default resolution (the gear's Welch spectrum from
    the record, the random part's from a 16 s record of it) applied to the signal as
    DRS applies its gain. What is left short of exact removal is the resolution's cost,
    not the estimate's."""
    nper = _drs_nperseg(fs, gear.size)
    kw = dict(nperseg=nper, noverlap=3 * nper // 4, window="hann")
    _f, p_gear = welch(gear, fs, **kw)
    _g, long_rest, _b = gearbox_signal(rpm, fs, 16.0, 10_000)
    _f, p_rest = welch(long_rest, fs, **kw)
    return _apply_gain(gear + rest, p_gear / (p_gear + p_rest), nper)


def methods(fs: float) -> dict:
    """Name -> residual(x, rpm) of every separation measured."""
    out = {"tsa": lambda x, rpm: separate_discrete(x, fs, rpm=rpm)[1],
           "drs (default)": lambda x, rpm: separate_discrete(x, fs, method="drs")[1],
           "lp (default, order 100)": lambda x, rpm: separate_discrete(x, fs, method="lp")[1]}
    for nper in DRS_SCAN:
        out[f"drs nperseg={nper}"] = (
            lambda x, rpm, a=nper: separate_discrete(x, fs, method="drs", nperseg=a)[1])
    for order in LP_SCAN:
        out[f"lp order={order}"] = (
            lambda x, rpm, o=order: separate_discrete(x, fs, method="lp", order=o)[1])
    return out


def measure(seeds: int) -> pd.DataFrame:
    rows = []
    for fs, duration in RECORDS:
        for rpm in RPMS:
            for seed in range(seeds):
                gear, rest, bpfi = gearbox_signal(rpm, fs, duration, seed)
                x = gear + rest
                exact = prominence(rest, fs, bpfi)
                base = {"fs_hz": fs, "duration_s": duration, "rpm": rpm, "seed": seed,
                        "exact": exact}
                rows.append({**base, "method": "raw", "prominence": prominence(x, fs, bpfi)})
                rows.append({**base, "method": "exact removal", "prominence": exact})
                ceiling = x - exact_spectra_gain(gear, rest, fs, rpm)
                rows.append({**base, "method": "drs gain from the exact spectra",
                             "prominence": prominence(ceiling, fs, bpfi)})
                for name, residual in methods(fs).items():
                    if "nperseg" in name and 2.75 * int(name.split("=")[1]) > x.size:
                        continue  # fewer than 4 Welch segments after the delay
                    rows.append({**base, "method": name,
                                 "prominence": prominence(residual(x, rpm), fs, bpfi)})
    table = pd.DataFrame(rows)
    table["db_vs_exact"] = 10 * np.log10(table["prominence"] / table["exact"])
    return table


def summary(table: pd.DataFrame) -> pd.DataFrame:
    """Per method (rows) and record (columns): the median and range over speeds and
    seeds of the BPFI prominence in dB against exact removal; the first row gives exact
    removal's own prominence (median)."""
    table = table.assign(record=[f"{fs / 1000:g} kHz, {d:g} s" for fs, d in
                                 zip(table.fs_hz, table.duration_s, strict=True)])
    records = list(dict.fromkeys(table.record))
    rows = [{"method": "exact removal: prominence",
             **{r: f"{table[(table.record == r) & (table.method == 'raw')].exact.median():.0f}"
                for r in records}}]
    for method, part in table.groupby("method", sort=False):
        cells = {}
        for r in records:
            db = part[part.record == r].db_vs_exact
            cells[r] = f"{db.median():+.1f} ({db.min():+.1f}..{db.max():+.1f})" if len(db) else "–"
        rows.append({"method": method, **cells})
    return pd.DataFrame(rows)


def figure(table: pd.DataFrame, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    keep = ["raw", "tsa", "drs gain from the exact spectra", "drs (default)",
            "lp (default, order 100)"]
    fig, ax = plt.subplots(figsize=(10, 4))
    records = list(dict.fromkeys(zip(table.fs_hz, table.duration_s, strict=True)))
    width = 0.8 / len(keep)
    for i, name in enumerate(keep):
        part = table[table.method == name]
        med = [part[(part.fs_hz == fs) & (part.duration_s == d)]["db_vs_exact"].median()
               for fs, d in records]
        ax.bar(np.arange(len(records)) + i * width, med, width, label=name)
    ax.axhline(-3.0, color="k", ls="--", lw=1, label="3 dB short of exact removal")
    ax.set_xticks(np.arange(len(records)) + 0.4 - width / 2,
                  [f"{fs / 1000:g} kHz, {d:g} s" for fs, d in records])
    ax.set_ylabel("BPFI prominence, dB vs exact removal")
    ax.set_title("Separation of a 15-tooth mesh from an inner-race fault (median over seeds "
                 "and speeds)")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--replot", action="store_true",
                        help="rewrite the page and figure from docs/results/separation.csv")
    args = parser.parse_args()
    if args.replot:
        table = pd.read_csv(RESULTS_DIR / "separation.csv")
    else:
        table = measure(args.seeds)
        table.to_csv(RESULTS_DIR / "separation.csv", index=False)
    figure(table, RESULTS_DIR / "separation.png")
    text = markdown_table(summary(table))
    page = DOCS / "separation.md"
    begin, end = "<!-- separation-table: begin -->", "<!-- separation-table: end -->"
    old = page.read_text()
    page.write_text(old[:old.index(begin) + len(begin)] + "\n" + text + "\n" +
                    old[old.index(end):])
    print(text)


if __name__ == "__main__":
    main()
