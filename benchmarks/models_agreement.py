"""Cross-model agreement: the impulse model against sr5 on the same scenes.

For every fault kind (outer, inner, ball), shaft speed and output configuration (48 kHz
with the default 15 kHz resonance; a CWRU-like 12 kHz with 3.5 kHz) one scene runs
through both models with the same seed, hence the same slip and the same impact times.
Measured on the loaded-zone sensor, in the scene's demodulation band:

* the SES line of the fault (largest bin within +-1.5 % of the kinematic frequency):
  its frequency in each model and its prominence (line / median SES up to 5 x BPFI);
* the correlation of the two squared-envelope spectra over 1 Hz - 5 x BPFI (linear
  amplitude, and in dB, which weighs the background as much as the lines);
* as a yardstick, the correlation of sr5 with itself under another seed (other slip):
  two runs of one model that differ only in the random slip;
* the RMS ratio impulse / sr5 of the raw signals.

Writes ``docs/models_agreement.csv``, ``docs/models_agreement.md`` and
``docs/models_agreement.png``.

    python benchmarks/models_agreement.py
    python benchmarks/models_agreement.py --duration 0.5    # quicker
"""

from __future__ import annotations

import argparse
from pathlib import Path

import _machine  # benchmarks/_machine.py (scripts run from their folder)
import numpy as np

import ballpass as bp
from ballpass import __version__
from ballpass.features import envelope_spectrum

DOCS = Path(__file__).resolve().parent.parent / "docs"
KINDS = {"outer": "bpfo", "inner": "bpfi", "ball": "ball_defect"}
RPMS = [600.0, 1200.0, 1797.0, 3000.0]
CONFIGS = {"48 kHz / 15 kHz": (48_000.0, 15_000.0), "12 kHz / 3.5 kHz": (12_000.0, 3_500.0)}


def _ses(res):
    return envelope_spectrum(res.accel, res.fs, band=res.scene.demodulation_band)


def _corr(a, b):
    return float(np.corrcoef(a, b)[0, 1])


def compare(kind: str, rpm: float, config: str, duration: float) -> tuple[dict, tuple]:
    fs, res_hz = CONFIGS[config]
    scene = bp.Scene("6205", rpm=rpm, fault=bp.Fault(kind), duration_s=duration, fs=fs,
                     resonance_hz=res_hz)
    r5 = bp.simulate(scene, model="sr5")
    ri = bp.simulate(scene, model="impulse")
    r5b = bp.simulate(scene.replace(seed=1), model="sr5")
    f, a5 = _ses(r5)
    _, ai = _ses(ri)
    _, a5b = _ses(r5b)
    fr = scene.frequencies
    freq = getattr(fr, KINDS[kind])
    band = (f >= 1.0) & (f <= 5.0 * fr.bpfi)
    near = np.abs(f - freq) <= max(1.5 * f[1], 0.015 * freq)

    def line(a):
        k = np.flatnonzero(near)[np.argmax(a[near])]
        return f[k], a[k] / np.median(a[band])

    f5, p5 = line(a5)
    fi, pi = line(ai)
    db = [10 * np.log10(a[band] + 1e-12 * a[band].max()) for a in (a5, ai, a5b)]
    row = dict(kind=kind, rpm=rpm, config=config, defect_hz=freq,
               line_hz_sr5=f5, line_hz_impulse=fi, line_diff_hz=fi - f5, bin_hz=f[1],
               prominence_sr5=p5, prominence_impulse=pi,
               corr=_corr(a5[band], ai[band]), corr_db=_corr(db[0], db[1]),
               corr_sr5_other_seed=_corr(a5[band], a5b[band]),
               corr_db_sr5_other_seed=_corr(db[0], db[2]),
               rms_ratio=float(np.std(ri.accel) / np.std(r5.accel)))
    return row, (f[band], a5[band], ai[band])


def write(rows: list[dict], spectra: dict, duration: float) -> None:
    import matplotlib
    import pandas as pd

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    df = pd.DataFrame(rows)
    DOCS.mkdir(exist_ok=True)
    df.to_csv(DOCS / "models_agreement.csv", index=False, float_format="%.5g")
    lines = [
        "# impulse against sr5 (benchmarks/models_agreement.py)",
        "",
        f"6205, 500 N, default 0.5 x 0.1 mm faults, {duration:g} s, seed 0 (sr5 yardstick: "
        f"seed 1), loaded-zone sensor, SES in the scene's demodulation band, correlation "
        f"over 1 Hz - 5 x BPFI. ballpass {__version__}; {_machine.machine()}.",
        "",
        "| config | fault | rpm | defect Hz | line sr5 / impulse Hz | prominence sr5 / "
        "impulse | corr | corr dB | sr5 vs sr5 (seed 1) corr / dB | RMS impulse / sr5 |",
        "|---|---|---:|---:|---|---|---:|---:|---|---:|",
    ]
    for r in df.itertuples():
        lines.append(
            f"| {r.config} | {r.kind} | {r.rpm:g} | {r.defect_hz:.1f} | "
            f"{r.line_hz_sr5:.1f} / {r.line_hz_impulse:.1f} | {r.prominence_sr5:.0f} / "
            f"{r.prominence_impulse:.0f} | {r.corr:.3f} | {r.corr_db:.3f} | "
            f"{r.corr_sr5_other_seed:.3f} / {r.corr_db_sr5_other_seed:.3f} | "
            f"{r.rms_ratio:.2f} |")
    lines += ["", "Summary by fault kind (median and range over speeds and configs):", "",
              "| fault | corr median | corr min | corr dB median | same line bin |",
              "|---|---:|---:|---:|---:|"]
    for kind, g in df.groupby("kind", sort=False):
        same = int((np.abs(g["line_diff_hz"]) <= g["bin_hz"] + 1e-9).sum())
        lines.append(f"| {kind} | {g['corr'].median():.3f} | {g['corr'].min():.3f} | "
                     f"{g['corr_db'].median():.3f} | {same}/{len(g)} |")
    (DOCS / "models_agreement.md").write_text("\n".join(lines) + "\n")

    fig, axes = plt.subplots(2, 3, figsize=(11, 5.5))
    for ax, kind in zip(axes[0], KINDS, strict=True):
        f, a5, ai = spectra[kind]
        ax.plot(f, a5 / a5.max(), lw=0.8, label="sr5")
        ax.plot(f, -ai / ai.max(), lw=0.8, label="impulse (mirrored)")
        ax.set_title(f"{kind}, 1797 rpm, 48 kHz", fontsize=9)
        ax.set_xlabel("Hz")
        ax.legend(fontsize=7)
    axes[0, 0].set_ylabel("SES / max")
    for ax, (config, g) in zip(axes[1, :2], df.groupby("config", sort=False), strict=True):
        for kind, gk in g.groupby("kind", sort=False):
            ax.plot(gk["rpm"], gk["corr"], "o-", label=f"{kind} impulse vs sr5")
            ax.plot(gk["rpm"], gk["corr_sr5_other_seed"], "x:", color="grey")
        ax.set_title(f"SES correlation, {config}\n(grey x: sr5 seed 0 vs seed 1)", fontsize=9)
        ax.set_xlabel("rpm")
        ax.set_ylim(0, 1.02)
        ax.legend(fontsize=7)
    ax = axes[1, 2]
    for kind, g in df.groupby("kind", sort=False):
        ax.plot(g["rpm"], g["rms_ratio"], "o", label=kind)
    ax.set_title("RMS impulse / sr5", fontsize=9)
    ax.set_xlabel("rpm")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(DOCS / "models_agreement.png", dpi=110)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=1.0, help="simulated s per scene")
    args = parser.parse_args()
    rows, spectra = [], {}
    for config in CONFIGS:
        for kind in KINDS:
            for rpm in RPMS:
                row, spec = compare(kind, rpm, config, args.duration)
                rows.append(row)
                if rpm == 1797.0 and config.startswith("48"):
                    spectra[kind] = spec
    write(rows, spectra, args.duration)
    print((DOCS / "models_agreement.md").read_text())


if __name__ == "__main__":
    main()
