"""Can a healthy machine's own line at a fault rate be told from a localized fault?

Four statistics a vibration analyst would use to tell a healthy bearing's distributed
line at BPFO (varying compliance: a direct low-frequency line, no impacts) from a
localized fault (impacts ringing a resonance), measured on every shared recording in
the band where the diagnoser's strongest family read highest, at that family's first
carrier ``a`` as found:

* ``raw_db``: the line at ``a`` in the raw (Hann-windowed) spectrum above the median of
  the bins within +-10 Hz, dB. A distributed line is a direct line.
* ``sk``: the spectral kurtosis of the band, ``E|c|^4 / (E|c|^2)^2 - 2`` of its analytic
  signal ``c`` (0 for Gaussian noise, standard deviation ``2 / sqrt(B T)`` for a band
  ``B`` wide over ``T`` s). Impacts make it positive.
* ``coherence_k``: the cyclic coherence of the band at ``k a`` (k = 1, 2, 3),
  ``|sum X(f) X*(f + k a)| / sqrt(sum |X(f)|^2 sum |X(f + k a)|^2)`` over the band,
  the best of +-1 bin: the share of the band's power that is modulated at ``k a``
  (``m / 2`` for a carrier whose power is modulated ``1 + m cos``, about ``1 /
  sqrt(B T)`` for noise). Impacts keep it high at every harmonic; a smooth modulation
  falls off after the first.
* ``cyclic_power``: ``2 sum_k |P(k a)|^2 / P(0)^2`` over k = 1..3, ``P`` the spectrum of
  the band's squared envelope: the modulation power of the family's first lines. A
  Gaussian carrier modulated without impacts has ``sk = cyclic_power`` (all its
  kurtosis is its modulation); impacts add kurtosis beyond it.
* ``in_phase_k``: the band cut in four equal sub-bands, the complex squared-envelope
  spectrum ``c_j`` of each at ``k a`` (k = 1, 2), and ``|sum c_j| / sum |c_j|``: 1 where
  every sub-band is modulated in phase. An impact excites every frequency of the band
  at once (in phase, near 1); a varying stiffness that moves the resonance (frequency
  modulation) lifts one side of it as it lowers the other (antiphase, near 0); noise
  reads about 0.5 (four random phasors).

Every statistic is reported, none is used by the diagnoser: the table says whether any
of them puts the healthy false alarms on one side and the faults on the other.

Run::

    PYTHONPATH=. python benchmarks/diagnose_healthy_lines.py            # ~1 min
    PYTHONPATH=. python benchmarks/diagnose_healthy_lines.py --out docs

Writes ``OUT/diagnosis_healthy_lines.md`` and ``OUT/results/diagnosis_healthy_lines.csv``.
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import scipy.fft
from _paths import DOCS, ROOT, results_in

from ballpass.datasets.mfpt import load_mfpt_mat
from ballpass.datasets.real import load_cwru_mat
from ballpass.diagnose import envelope_evidence
from ballpass.diagnose.evidence import FTF_RESOLVED_CAGE_PERIODS
from ballpass.diagnose.noise_law import noise_threshold
from ballpass.diagnose.rules import DEFAULT_FALSE_ALARM, DEFAULT_THRESHOLD_DB
from ballpass.features.bands import as_bearing
from ballpass.signalio import atomic_write

SHARED = ROOT.parent / "shared" / "data"
STATISTICS = ("raw_db", "sk", "coherence_1", "coherence_2", "coherence_3", "cyclic_power",
              "in_phase_1", "in_phase_2")
SUB_BANDS = 4


def load_hit(path: Path) -> np.ndarray:
    """The one signal of a HIT-SM ``.mat`` file (its only non-``__`` variable)."""
    import scipy.io

    mat = scipy.io.loadmat(path)
    (name,) = [k for k in mat if not k.startswith("__")]
    return np.asarray(mat[name], dtype=float).ravel()


def records(data: Path):
    """``(name, truth, signal, fs, rpm, bearing)`` of every shared recording, and the
    one-second segments of the healthy ones."""
    label = {"Normal": "healthy", "IR": "inner", "OR": "outer"}
    for path in sorted((data / "hit").glob("*.mat")):
        state, rpm = path.stem.split("_")
        truth = label[state.rstrip("0123456789")]
        x = load_hit(path)
        yield path.stem, truth, x, 51_200.0, float(rpm), "6205"
        if truth == "healthy":
            for i in range(len(x) // 51_200):
                yield f"{path.stem}[{i}]", truth, x[i * 51_200 : (i + 1) * 51_200], \
                    51_200.0, float(rpm), "6205"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for path in sorted((data / "cwru").glob("*.mat")):
            channel = "FE" if "_FE_" in path.name else "DE"
            rec = load_cwru_mat(path, channel=channel)
            yield path.stem, rec.label, rec.accel, rec.fs, rec.rpm, rec.bearing
            if rec.label == "healthy":
                n = int(rec.fs)
                for i in range(min(10, len(rec.accel) // n)):
                    yield f"{path.stem}[{i}]", rec.label, rec.accel[i * n : (i + 1) * n], \
                        rec.fs, rec.rpm, rec.bearing
    for path in sorted((data / "mfpt").glob("*.mat")):
        rec = load_mfpt_mat(path)
        yield path.stem, rec.label, rec.accel, rec.fs, rec.rpm, rec.bearing


def band_statistics(x, fs, band, alpha) -> dict:
    """The statistics of the module notes in ``band`` (Hz) at the line ``alpha`` (Hz)."""
    lo, hi = band
    spectrum = scipy.fft.fft(x - x.mean())
    f = scipy.fft.fftfreq(x.size, 1.0 / fs)
    spectrum[(f < lo) | (f > hi)] = 0.0
    power = np.abs(scipy.fft.ifft(spectrum)) ** 2  # squared envelope of the band
    out = {"sk": float(np.mean(power**2) / np.mean(power) ** 2 - 2.0)}
    ses = np.abs(scipy.fft.rfft(power)) / power.size
    df = fs / x.size
    at = lambda freq: ses[int(round(freq / df)) - 1 : int(round(freq / df)) + 2].max()  # noqa: E731
    out["cyclic_power"] = float(sum(2 * (at(k * alpha) / ses[0]) ** 2 for k in (1, 2, 3)))
    half = scipy.fft.rfft(x - x.mean())
    fr = scipy.fft.rfftfreq(x.size, 1.0 / fs)
    for k in (1, 2, 3):
        best = 0.0
        centre = k * alpha / df
        for shift in range(int(np.floor(centre)) - 1, int(np.ceil(centre)) + 2):
            sel = np.flatnonzero((fr >= lo) & (fr + shift * df <= hi))
            a, b = half[sel], half[sel + shift]
            value = abs(np.sum(a * np.conj(b))) / np.sqrt(np.sum(abs(a) ** 2) * np.sum(abs(b) ** 2))
            best = max(best, float(value))
        out[f"coherence_{k}"] = best
    out.update(in_phase(spectrum, f, fs, band, alpha))
    raw = np.abs(scipy.fft.rfft((x - x.mean()) * np.hanning(x.size))) ** 2
    i = int(np.argmin(np.abs(fr - alpha)))
    out["raw_db"] = float(10 * np.log10(raw[i - 2 : i + 3].max()
                                        / np.median(raw[np.abs(fr - alpha) <= 10.0])))
    return out


def in_phase(spectrum, f, fs, band, alpha) -> dict:
    """``in_phase_1``, ``in_phase_2`` of the module notes from the band's two-sided
    spectrum ``spectrum`` (zero outside the band) at bin frequencies ``f``, Hz."""
    lo, hi = band
    edges = np.linspace(lo, hi, SUB_BANDS + 1)
    n = spectrum.size
    t = np.arange(n) / fs
    coeffs = []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        part = np.where((f >= a) & (f < b), spectrum, 0.0)
        power = np.abs(scipy.fft.ifft(part)) ** 2
        power = power - power.mean()
        coeffs.append([np.sum(power * np.exp(-2j * np.pi * k * alpha * t)) for k in (1, 2)])
    c = np.array(coeffs)
    return {f"in_phase_{k + 1}": float(abs(c[:, k].sum()) / (np.abs(c[:, k]).sum() + 1e-300))
            for k in range(2)}


def measure(data: Path) -> pd.DataFrame:
    rows = []
    for name, truth, x, fs, rpm, bearing in records(data):
        ev = envelope_evidence(x, fs, bearing, rpm)
        family = max(ev.evidence_db, key=lambda f: ev.evidence_db[f][0])
        band = tuple(float(v) for v in ev.band_hz[family][0])
        alpha = float(ev.found_hz[family][0][0])
        ftf = as_bearing(bearing).frequencies(ev.rpm[0] / 60.0).ftf
        resolved = ev.duration_s * ftf >= FTF_RESOLVED_CAGE_PERIODS
        threshold = max(DEFAULT_THRESHOLD_DB, noise_threshold(
            DEFAULT_FALSE_ALARM, ev.n_readings[0], ev.duration_s, resolved))
        row = {"record": name, "truth": truth, "strongest": family,
               "evidence_db": round(float(ev.evidence_db[family][0]), 1),
               "threshold_db": round(float(threshold), 2),
               "band_hz": f"{band[0]:.0f}-{band[1]:.0f}",
               "sk_noise_sd": round(2.0 / np.sqrt((band[1] - band[0]) * len(x) / fs), 3)}
        row.update({k: round(v, 3) for k, v in band_statistics(x, fs, band, alpha).items()})
        rows.append(row)
        print(row, flush=True)
    return pd.DataFrame(rows)


def markdown(table: pd.DataFrame) -> str:
    alarms = table[(table.truth == "healthy") & (table.evidence_db > table.threshold_db)]
    named = table[(table.truth != "healthy") & (table.truth == table.strongest)
                  & (table.evidence_db > table.threshold_db)]
    lines = [
        "# A healthy machine's own lines against a localized fault's",
        "",
        "Generated by `benchmarks/diagnose_healthy_lines.py` on every shared recording "
        "(HIT-SM self-built rig, CWRU, MFPT; the healthy ones also in one-second segments); "
        "do not edit by hand. Each row is read in the band where the strongest family read "
        "highest, at that family's first carrier as found (definitions in the script).",
        "",
        "A row is called faulty where its evidence exceeds its threshold (`threshold_db`: 6 "
        "dB, raised to the noise law's 0.1 % over the row's own search). "
        f"Healthy records and segments the default diagnoser calls faulty: {len(alarms)}; "
        f"fault records it names: {len(named)}. For each statistic, the range over the "
        "false alarms and over the named faults, and how many named faults fall inside "
        "the false alarms' range (0 would mean a threshold exists that separates them "
        "on these records):",
        "",
        "| statistic | false alarms | named faults | faults inside the alarms' range |",
        "|---|---|---|---|",
    ]
    for stat in STATISTICS:
        lo, hi = alarms[stat].min(), alarms[stat].max()
        inside = int(named[stat].between(lo, hi).sum()) if len(alarms) else 0
        lines.append(f"| {stat} | {lo:.2f} to {hi:.2f} | {named[stat].min():.2f} to "
                     f"{named[stat].max():.2f} | {inside} of {len(named)} |")
    lines += _hit_1200(table)
    lines += ["", "Every row:", "", "| " + " | ".join(table.columns) + " |",
              "|" + "---|" * len(table.columns)]
    lines += ["| " + " | ".join(str(v) for v in row) + " |"
              for row in table.itertuples(index=False)]
    return "\n".join(lines) + "\n"


def _hit_1200(table: pd.DataFrame) -> list[str]:
    """What the HIT-SM healthy recording at 1200 rpm carries, from its row."""
    rows = table[table.record == "Normal_1200"]
    if rows.empty:
        return []
    r = rows.iloc[0]
    noise = r.sk_noise_sd  # also about 1 / sqrt(B T), the coherence of noise
    return [
        "",
        f"The HIT-SM healthy recording at 1200 rpm (called {r.strongest}, "
        f"{r.evidence_db} dB, band {r.band_hz} Hz) is not a direct line imprinted on the "
        f"band: its band is non-Gaussian (spectral kurtosis {r.sk:.2f}, "
        f"{r.sk / noise:.0f} noise standard deviations) and modulated at the first "
        f"three harmonics alike (cyclic coherence {r.coherence_1:.2f}, "
        f"{r.coherence_2:.2f}, {r.coherence_3:.2f}; noise reads about {noise / 2:.3f}): a "
        "second-order cyclostationary comb with slowly decaying harmonics, the "
        "signature of impacts, shallower than the faults' in most rows but not in all. "
        f"Its kurtosis is {r.sk / max(r.cyclic_power, 1e-9):.1f} times what its "
        "modulation explains (a Gaussian carrier modulated without impacts has "
        "`sk = cyclic_power`), and its modulation is in phase across the band's "
        f"quarters ({r.in_phase_1:.2f} at 1x, {r.in_phase_2:.2f} at 2x; noise about "
        "0.5, a resonance moved by a varying stiffness near 0): broadband impacts, "
        "not a frequency-modulated resonance. By every test here it is a shallow "
        "localized defect's signature, and the diagnoser names it so. "
        "A rule on two of these statistics at once could be drawn between the rows "
        "above, but both of its constants would be read off these very records, with "
        "the nearest fault a few hundredths from the cut: it is not used.",
    ]


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, default=SHARED,
                        help="folder holding hit/, cwru/ and mfpt/")
    parser.add_argument("--out", type=Path, default=DOCS)
    args = parser.parse_args(argv)
    table = measure(args.data)
    args.out.mkdir(parents=True, exist_ok=True)
    atomic_write(results_in(args.out) / "diagnosis_healthy_lines.csv",
                 lambda tmp: table.to_csv(tmp, index=False))
    page = markdown(table)
    atomic_write(args.out / "diagnosis_healthy_lines.md", lambda tmp: tmp.write_text(page))


if __name__ == "__main__":
    main()
