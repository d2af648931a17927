"""What the envelope diagnoser costs per one-second signal, at 12 kHz and at 48 kHz.

The same second is diagnosed at its own rate and brought down by ``resample_poly`` to a
quarter of it (four times fewer samples, two fewer levels of the 1/3-binary band tree):

* real: seconds of the CWRU healthy drive-end recording (48 kHz) and of the HIT-SM
  healthy and faulty recordings (51.2 kHz, brought to 12.8 kHz);
* synthetic: impacts at BPFO of a 6205 at 1797 rpm ringing a 3 kHz resonance in noise,
  generated at 48 kHz.

Each signal is timed ``--repeats`` times, the two rates alternating, after one untimed
call (numba/scipy warm-up); the table gives medians with the 10-90 % spread and the
ratio of the medians of each pair. Timings on a shared machine are noisy: compare the
ratios, measured side by side.

Run::

    PYTHONPATH=. python benchmarks/diagnose_cost.py            # ~1 min on 2 cores
    PYTHONPATH=. python benchmarks/diagnose_cost.py --data ../shared/data --out docs

Writes ``docs/diagnosis_cost.md``, ``docs/results/diagnosis_cost.csv`` and
``docs/results/diagnosis_cost.png``.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import pandas as pd
import scipy.io
from _paths import DOCS, results_in
from scipy.signal import resample_poly

import ballpass as bp
from ballpass.datasets.real import load_cwru_mat
from ballpass.diagnose import EnvelopeDiagnoser
from ballpass.signalio import atomic_write


def hit_second(path: Path, start_s: float) -> np.ndarray:
    """One second of a HIT-SM recording (51.2 kHz; the file's only variable)."""
    mat = scipy.io.loadmat(path)
    name = next(k for k in mat if not k.startswith("__"))
    x = np.asarray(mat[name], dtype=float).ravel()
    i = int(start_s * 51_200)
    return x[i : i + 51_200]


def synthetic_second(fs: float, seed: int) -> np.ndarray:
    """Impacts at BPFO of a 6205 at 1797 rpm ringing 3 kHz, in white noise."""
    bpfo = 0.995 * bp.Bearing.catalog("6205").frequencies(1797 / 60).bpfo
    t = np.arange(int(fs)) / fs
    phase = (t * bpfo) % 1.0 / bpfo
    x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    return x + 0.5 * np.random.default_rng(seed).standard_normal(t.size)


def cases(data: Path):
    """``(name, x_high, fs_high, rpm)`` of every second timed."""
    out = []
    cwru = data / "cwru" / "Normal_0_48k.mat"
    if cwru.exists():
        rec = load_cwru_mat(cwru, channel="DE")
        for start in (0, 2, 4):
            x = rec.accel[start * 48_000 : (start + 1) * 48_000]
            out.append((f"CWRU healthy DE, s {start}-{start + 1}", x, 48_000.0, rec.rpm))
    for stem in ("Normal_1200", "OR5_900", "IR2_600"):
        path = data / "hit" / f"{stem}.mat"
        if path.exists():
            out.append((f"HIT {stem}, s 1-2", hit_second(path, 1.0), 51_200.0,
                        float(stem.split("_")[1])))
    for seed in (0, 1):
        out.append((f"synthetic outer race, seed {seed}", synthetic_second(48_000.0, seed),
                    48_000.0, 1797.0))
    return out


def timed(diagnoser, x, repeats: int) -> list[float]:
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        diagnoser.predict(x[None])
        out.append(time.perf_counter() - t0)
    return out


def measure(data: Path, repeats: int) -> pd.DataFrame:
    rows = []
    for name, x_high, fs_high, rpm in cases(data):
        versions = {"high": (x_high, fs_high), "low": (resample_poly(x_high, 1, 4), fs_high / 4)}
        diag = {k: EnvelopeDiagnoser("6205", fs=fs, rpm=rpm) for k, (_, fs) in versions.items()}
        times = {k: [] for k in versions}
        for k, (x, _) in versions.items():
            diag[k].predict(x[None])  # warm-up
        for _ in range(repeats):  # alternate, so that both see the same machine load
            for k, (x, _) in versions.items():
                times[k] += timed(diag[k], x, 1)
        row = {"signal": name, "fs_high_hz": fs_high}
        for k in versions:
            t = np.array(times[k]) * 1e3
            row[f"{k}_ms"] = float(np.median(t))
            row[f"{k}_p10_ms"], row[f"{k}_p90_ms"] = (float(v) for v in np.percentile(t, [10, 90]))
            row[f"{k}_label"] = str(diag[k].predict(versions[k][0][None])[0])
        row["ratio"] = row["high_ms"] / row["low_ms"]
        rows.append(row)
        print(f"{name}: {row['high_ms']:.0f} ms against {row['low_ms']:.0f} ms, "
              f"ratio {row['ratio']:.2f}", flush=True)
    return pd.DataFrame(rows)


def markdown(table: pd.DataFrame) -> str:
    lines = ["| signal | at fs (ms, p10-p90) | at fs/4 (ms, p10-p90) | ratio | labels |",
             "|---|---|---|---|---|"]
    for r in table.itertuples():
        lines.append(
            f"| {r.signal} ({r.fs_high_hz / 1000:g} kHz) | {r.high_ms:.0f} "
            f"({r.high_p10_ms:.0f}-{r.high_p90_ms:.0f}) | {r.low_ms:.0f} "
            f"({r.low_p10_ms:.0f}-{r.low_p90_ms:.0f}) | {r.ratio:.2f} | "
            f"{r.high_label} / {r.low_label} |")
    return "\n".join(lines)


def figure(table: pd.DataFrame, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 3.5))
    y = np.arange(len(table))
    for k, colour, label in (("high", "C0", "at fs (48/51.2 kHz)"),
                             ("low", "C1", "same second at fs/4")):
        ax.barh(y + (0.2 if k == "low" else -0.2), table[f"{k}_ms"], height=0.4,
                color=colour, label=label,
                xerr=[table[f"{k}_ms"] - table[f"{k}_p10_ms"],
                      table[f"{k}_p90_ms"] - table[f"{k}_ms"]])
    ax.set_yticks(y, table["signal"])
    ax.set_xlabel("EnvelopeDiagnoser.predict, one 1 s signal (ms, median, p10-p90)")
    ax.legend(loc="lower right")
    fig.tight_layout()
    atomic_write(path, lambda tmp: fig.savefig(tmp, dpi=120, format="png"))
    plt.close(fig)


PAGE = """# What the envelope diagnoser costs at 48 kHz

Generated by `benchmarks/diagnose_cost.py` (median of {repeats} calls of
`EnvelopeDiagnoser.predict` on one 1 s signal, the two rates alternating; 10-90 %
spread in brackets; a shared 2-core machine, so compare the ratios). Each second is
diagnosed at its own rate and brought to a quarter of it by `resample_poly`.

{table}

![cost per second at both rates](results/diagnosis_cost.png)

Why the cost grows with the samples and not faster: each candidate band of the
1/3-binary tree is demodulated from its own bins of one spectrum of the record
(`ballpass.features.demodulate.BandDemodulator`), so a band costs in proportion to its
width and the whole tree a few transforms of the full length; the bands are then scored
together, stacked as rows. What still grows faster than the samples is the number of
bands wide enough to hold the fault lines (71 at 48 kHz, 11 at 12 kHz for a 6205 at
1797 rpm, with signal in every band, as white noise has): each is scored at the same
cost, which is why
the synthetic signal (white noise up to 24 kHz) costs more than the real recordings,
whose high bands hold little.
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, default=Path("../shared/data"))
    parser.add_argument("--out", type=Path, default=DOCS)
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    table = measure(args.data, args.repeats)
    results = results_in(args.out)
    atomic_write(results / "diagnosis_cost.csv", lambda tmp: table.to_csv(tmp, index=False))
    figure(table, results / "diagnosis_cost.png")
    page = PAGE.format(table=markdown(table), repeats=args.repeats)
    atomic_write(args.out / "diagnosis_cost.md", lambda tmp: tmp.write_text(page))
    print(page)


if __name__ == "__main__":
    main()
