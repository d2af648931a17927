"""Ball faults: simulated (sr5) and every shared CWRU ball record, as the diagnoser reads them.

A ball fault shows in the squared envelope spectrum as the 2xBSF comb with +-FTF
sidebands (the defect passes the load zone once per cage revolution; Smith & Randall,
2015). On the 6205 some of these lines sit on race-family lines (2x2xBSF+FTF = 9.825
orders on 2xBPFI-fr = 9.830), and the evidence leaves such lines out of both families
(``ballpass.diagnose.evidence.shared_lines``). Nothing is fitted: every row is a
held-out result of the default ``EnvelopeDiagnoser``.

* simulated: sr5 ball defects (0.53 mm wide, 0.28 mm deep) on a 6205 and a 6203 under
  500 N, 12 and 48 kHz, 1200 and 1797 rpm, SNR 10 and 0 dB, two seeds, 2 s each;
* simulated race faults (inner and outer race, same scenes, SNR 10 dB, one seed): none
  may be called ball;
* real: every shared CWRU ball record, whole, at its faulty bearing's own sensor (drive
  end: 6205, fan end: 6203) and at the other end (the fault heard from afar).

Each row also reads the ball and the stronger race family from the enhanced envelope
spectrum (band-integrated cyclic coherence, ``ballpass.diagnose.ball.
cyclic_family_evidence``) in the band the diagnoser chose for each family: a second
view, whose dB are not on the squared envelope's scale (compare the two columns with
each other).

Run::

    PYTHONPATH=. python benchmarks/diagnose_ball.py            # ~2 min on 2 cores

Writes ``OUT/diagnosis_ball.md``, ``OUT/results/diagnosis_ball.csv`` and
``OUT/results/diagnosis_ball_reading.csv`` (the expert's reading of the 2xBSF comb:
``expert``).
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import scipy.signal
from _paths import DOCS, ROOT, results_in

import ballpass as bp
from ballpass.datasets.real import load_cwru_mat
from ballpass.diagnose import EnvelopeDiagnoser
from ballpass.diagnose.ball import cyclic_family_evidence
from ballpass.diagnose.ball_spin import cage_modulation_db, smeared_ball_evidence
from ballpass.diagnose.evidence import FAULT_FAMILIES, candidate_bands
from ballpass.features.cyclic import enhanced_envelope_spectrum
from ballpass.features.demodulate import BandDemodulator
from ballpass.signalio import atomic_write

SHARED = ROOT.parent / "shared" / "data"
BEARINGS = ("6205", "6203")
RATES = (12_000.0, 48_000.0)
SPEEDS = (1200.0, 1797.0)
SNRS_DB = (10.0, 0.0)
SEEDS = (0, 1)
SEGMENT_S = 1.0


def _decisive(why) -> str:
    """The band and lines that carried a fault verdict (empty for "healthy")."""
    if why.label == "healthy":
        return ""
    lo, hi = why.band_hz[why.label]
    lines = why.lines[why.lines.decisive & ~why.lines.shared]
    ball = why.lines[(why.lines.fault == "ball") & ~why.lines.shared]
    first = lines.iloc[0]

    def listed(rows) -> str:
        return ", ".join(f"{r.line} {r.found_hz:.1f} Hz {r.level_db:+.1f} dB"
                         for r in rows.itertuples())

    return (f"{why.label} {why.evidence_db[why.label]:.1f} dB in {lo:.0f}-{hi:.0f} Hz: "
            f"{listed(lines)} (1x found at {first.found_hz / first.nominal_hz:.3f} of its "
            f"kinematic frequency); the ball's lines: {listed(ball)}")


def _row(why, x, fs, bearing, **meta) -> dict:
    ev = why.evidence_db
    ees = {f: cyclic_family_evidence(x, fs, bearing, why.rpm, why.band_hz[f], fault=f)
           if np.all(np.isfinite(why.band_hz[f])) else -np.inf
           for f in ("outer", "inner", "ball")}
    return dict(meta, bearing=bearing, verdict=why.label, grade=why.grade,
                **{f"{f}_db": round(float(ev[f]), 1) for f in ("outer", "inner", "ball")},
                ees_ball_db=round(float(ees["ball"]), 1),
                ees_race_db=round(float(max(ees["outer"], ees["inner"])), 1),
                decisive=_decisive(why))


def _simulated_row(kind, bearing, fs, rpm, snr, seed) -> dict:
    scene = bp.Scene(bearing=bearing, rpm=rpm, radial_load_n=500.0,
                     fault=bp.Fault(kind, width_mm=0.53, depth_mm=0.28),
                     duration_s=2.0, fs=fs, snr_db=snr, seed=seed, resonance_hz=3000.0)
    x = np.atleast_2d(bp.simulate(scene).accel)[0]
    (why,) = EnvelopeDiagnoser(bearing=bearing, fs=fs, rpm=rpm).explain(x[None])
    source = "sr5" if kind == "ball" else f"sr5 {kind}"
    return _row(why, x, fs, bearing, source=source,
                record=f"{bearing} {fs / 1e3:g} kHz {rpm:g} rpm {snr:g} dB #{seed}")


def simulated() -> list[dict]:
    return [_simulated_row("ball", bearing, fs, rpm, snr, seed)
            for bearing in BEARINGS for fs in RATES for rpm in SPEEDS
            for snr in SNRS_DB for seed in SEEDS]


def simulated_races() -> list[dict]:
    return [_simulated_row(kind, bearing, 12_000.0, rpm, SNRS_DB[0], SEEDS[0])
            for kind in ("inner", "outer") for bearing in BEARINGS for rpm in SPEEDS]


def real(data: Path) -> list[dict]:
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for path in sorted((data / "cwru").glob("12k_*_B0*.mat")):
            own = "FE" if "_FE_" in path.name else "DE"
            for channel in (own, "DE" if own == "FE" else "FE"):
                rec = load_cwru_mat(path, channel=channel)
                # The faulty bearing's lines, whichever sensor hears them.
                bearing = "6203" if own == "FE" else "6205"
                (why,) = EnvelopeDiagnoser(bearing=bearing, fs=rec.fs,
                                           rpm=rec.rpm).explain(rec.accel[None])
                rows.append(_row(why, rec.accel, rec.fs, bearing, source="CWRU",
                                 record=f"{path.stem} at {channel}"
                                 + ("" if channel == own else " (far end)")))
    return rows


def expert_row(x, fs, bearing, rpm, record) -> dict:
    """What an expert reads of the 2xBSF comb of one whole record: the comb on the
    averaged SES (1 Hz bins, the ball's smeared lines gathered) in the band where it
    reads highest, and how the 2xBSF component swells at FTF against fr there."""
    orders = bp.Bearing.catalog(bearing).frequencies(1.0).as_dict()
    shaft = rpm / 60.0
    top = shaft * (3 * max(orders[c] for c, _, _ in FAULT_FAMILIES.values()) + 1.0)
    bands, ok = candidate_bands(x[None], fs, top)
    smear = smeared_ball_evidence(x[None], fs, bearing, np.array([shaft]), bands, ok,
                                  set_aside_races=False)
    row = dict(record=record, bearing=bearing, smear_db=round(float(smear.evidence_db[0]), 1),
               smear_1x_db=round(float(smear.level_db[0, 0]), 1),
               smear_2x_db=round(float(smear.level_db[0, 1]), 1),
               found_1x_hz=round(float(smear.found_hz[0, 0]), 1),
               kinematic_1x_hz=round(orders["ball_defect"] * shaft, 1),
               band=f"{smear.band_hz[0, 0]:.0f}-{smear.band_hz[0, 1]:.0f}",
               cage_ftf_db=np.nan, cage_fr_db=np.nan, ees_ftf_db=np.nan, ees_bsf_db=np.nan,
               ees_2bsf_db=np.nan)
    if np.isfinite(smear.evidence_db[0]) and np.isfinite(smear.found_hz[0, 0]):
        demodulator = BandDemodulator(x, fs, max_hz=4.0 * top)
        ftf_db, fr_db = cage_modulation_db(demodulator, tuple(smear.band_hz[0]),
                                           smear.found_hz[0, 0],
                                           [orders["ftf"] * shaft, shaft],
                                           cage_hz=orders["ftf"] * shaft)
        row.update(cage_ftf_db=round(float(ftf_db), 1), cage_fr_db=round(float(fr_db), 1))
        alpha, ees = enhanced_envelope_spectrum(x, fs, tuple(smear.band_hz[0]),
                                                max_alpha=orders["ball_defect"] * shaft
                                                + 20.0)
        for name, key in (("ftf", "ftf"), ("bsf", "bsf"), ("2bsf", "ball_defect")):
            row[f"ees_{name}_db"] = round(_line_db(alpha, ees[0], orders[key] * shaft), 1)
    labels = EnvelopeDiagnoser(bearing=bearing, fs=fs, rpm=rpm).predict(
        _segments(x, fs))
    row["segments"] = "/".join(str(int(np.sum(labels == c)))
                               for c in ("ball", "inner", "outer", "healthy"))
    return row


def _segments(x, fs) -> np.ndarray:
    """The record cut into whole one-second segments, (n_segments, SEGMENT_S fs)."""
    n = int(SEGMENT_S * fs)
    return x[: len(x) // n * n].reshape(-1, n)


def _line_db(freqs, spectrum, f, slip: float = 0.02, background_hz: float = 10.0) -> float:
    """Largest bin within the slip search of a line (``f (1 - slip) .. f (1 + slip /
    4)``, +-1 bin) over the median within +-``background_hz`` of that, dB."""
    df = freqs[1]
    near = (freqs >= f * (1 - slip) - df) & (freqs <= f * (1 + slip / 4) + df)
    around = ((freqs >= f * (1 - slip) - background_hz)
              & (freqs <= f * (1 + slip / 4) + background_hz) & (freqs > 0))
    return float(10 * np.log10(spectrum[near].max() / np.median(spectrum[around])))


def expert(data: Path) -> pd.DataFrame:
    """:func:`expert_row` of every shared ball record at both sensors (the faulty
    bearing's lines) and of the healthy baseline at both (the drive end's, 6205)."""
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        paths = sorted((data / "cwru").glob("12k_*_B0*.mat")) + sorted(
            (data / "cwru").glob("Normal_*.mat"))
        for path in paths:
            own = "FE" if "_FE_" in path.name else "DE"
            bearing = "6203" if own == "FE" else "6205"
            for channel in ("DE", "FE"):
                rec = load_cwru_mat(path, channel=channel)
                far = "" if channel == own or path.stem.startswith("Normal") else " (far end)"
                rows.append(expert_row(rec.accel, rec.fs, bearing, rec.rpm,
                                       f"{path.stem} at {channel}{far}"))
                if rec.fs == 4 * RATES[0]:  # the healthy baseline at the faults' rate too
                    x = scipy.signal.decimate(rec.accel, 4, ftype="fir", zero_phase=True)
                    rows.append(expert_row(x, RATES[0], bearing, rec.rpm,
                                           f"{path.stem} at {channel}, decimated to 12 kHz"))
    return pd.DataFrame(rows)


def expert_markdown(table: pd.DataFrame) -> list[str]:
    """The page's section on the expert's reading (:func:`expert`)."""
    healthy = table[table.record.str.startswith("Normal")]
    ball = table[~table.record.str.startswith("Normal") & (table.bearing == "6205")
                 & ~table.record.str.contains("far end")]
    line = healthy[healthy.record.str.contains("at DE")].iloc[0]
    lines = [
        "## The expert's reading of the 2xBSF comb",
        "",
        "A ball's spin is not locked to the shaft or the cage: its axis wanders as it rolls "
        "through the load zone, so its 2xBSF lines are smeared over a few hertz where a race "
        "fault's are one bin wide (Randall & Antoni 2011). Below, each record's 2xBSF comb "
        "read on the squared envelope spectrum averaged over one-second segments (Welch, "
        "1 Hz bins) in the band where it reads highest (`ballpass.diagnose.ball_spin."
        "smeared_ball_evidence`, every harmonic read), and how the 2xBSF component there "
        "swells at the cage rate FTF against the shaft rate fr (`cage_modulation_db`: the "
        "squared envelope band-passed to the line +-1.5 FTF, its own envelope's spectrum). "
        "Set aside what a race line (carrier +-1 FTF +-2 fr) could explain, and nothing is "
        "left to read on either bearing: on the 6205, BPFO + fr (4.585 orders) lies 2.7 % "
        "below 2xBSF (4.7135), within its 2 % slip search and the 1 Hz main lobe, at every "
        "harmonic; on the 6203, 2xBSF (3.987) lies 1 % above BPFI - fr (3.947), 2x2xBSF "
        "1 % above 2xBPFI - 2fr, 3x2xBSF 0.6 % above 2xBPFI + 2fr.",
        "",
        "The drive-end (6205) ball records at their own sensor read a smeared comb of "
        f"{ball.smear_db.min():.1f}-"
        f"{ball.smear_db.max():.1f} dB and an FTF swell of {ball.cage_ftf_db.min():.1f}-"
        f"{ball.cage_ftf_db.max():.1f} dB; the healthy baseline of the same rig reads "
        f"{healthy.smear_db.min():.1f}-{healthy.smear_db.max():.1f} dB and "
        f"{healthy.cage_ftf_db.min():.1f}-{healthy.cage_ftf_db.max():.1f} dB (at 48 kHz and "
        f"decimated to the faults' 12 kHz alike): its drive end carries a line at "
        f"{line.found_1x_hz:.0f} Hz ({line.smear_1x_db:.1f} dB, "
        f"{100 * (1 - line.found_1x_hz / line.kinematic_1x_hz):.1f} % below the kinematic "
        f"{line.kinematic_1x_hz:.1f} Hz), where the drive-end ball records' 1x2xBSF is found "
        f"({ball.found_1x_hz.min():.0f}-{ball.found_1x_hz.max():.0f} Hz). Neither reading "
        "tells these ball records from the "
        "healthy machine, so neither enters the verdict: a ball named by them would be "
        "named on the healthy drive end too.",
        "",
        "The EES columns read the enhanced envelope spectrum (band-integrated cyclic "
        "coherence, Antoni 2007) of the same band at FTF, BSF and 2xBSF, each over its own "
        "background; the last column counts the default diagnoser's verdicts on the "
        "record's one-second segments (ball / inner / outer / healthy).",
        "",
        "| record | bearing | band Hz | comb dB | 1x dB | 2x dB | 1x found Hz | 1x kinematic Hz "
        "| FTF swell dB | fr swell dB | EES FTF dB | EES BSF dB | EES 2xBSF dB | 1 s segments |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    lines += [f"| {r.record} | {r.bearing} | {r.band} | {r.smear_db:.1f} | {r.smear_1x_db:.1f} "
              f"| {r.smear_2x_db:.1f} | {r.found_1x_hz:.1f} | {r.kinematic_1x_hz:.1f} | "
              f"{r.cage_ftf_db:.1f} | {r.cage_fr_db:.1f} | {r.ees_ftf_db:.1f} | "
              f"{r.ees_bsf_db:.1f} | {r.ees_2bsf_db:.1f} | {r.segments} |"
              for r in table.itertuples()]
    return lines + [""]


def markdown(table: pd.DataFrame, before: pd.DataFrame | None = None,
             reading: pd.DataFrame | None = None) -> str:
    sim = table[table.source == "sr5"]
    races = table[table.source.str.startswith("sr5 ")]
    cwru = table[table.source == "CWRU"]
    own = cwru[~cwru.record.str.contains("far end")]
    race_max = own[["outer_db", "inner_db"]].max(axis=1)
    lines = [
        "# Ball faults",
        "",
        "Produced by `PYTHONPATH=. python benchmarks/diagnose_ball.py`; do not edit by hand.",
        "",
        "The default `EnvelopeDiagnoser` (nothing fitted) on simulated ball faults and on "
        "every shared CWRU ball record. A ball fault is read from the 2xBSF comb and its "
        "+-FTF sidebands; a line that collides with a race family's line (within half the "
        "slip search, or 2 bins on short records) counts for neither family. The cage "
        "carries the defect round the load zone, so every 2xBSF carrier must stand within "
        "6 dB of its own +-FTF sidebands (the first cage harmonic of Stribeck's load "
        "distribution is 1.1 dB below the mean for a half-loaded bearing, within 6 dB up "
        "to a load-distribution factor of 1.7); what a carrier stands above that comes off "
        "the ball's evidence, so a 2xBSF comb without cage modulation (a race or shaft "
        "line landing there) makes no ball fault.",
        "",
        f"- simulated (sr5, 6205 and 6203, 12 and 48 kHz, 1200 and 1797 rpm, SNR 10 and "
        f"0 dB, 2 s): **{int((sim.verdict == 'ball').sum())} of {len(sim)} named ball**, "
        f"{int((sim.verdict.isin(['outer', 'inner'])).sum())} called a race fault, "
        f"{int((sim.verdict == 'healthy').sum())} healthy;",
        f"- simulated race faults (inner and outer, same bearings and speeds, 12 kHz, "
        f"10 dB): {int((races.verdict == 'ball').sum())} of {len(races)} called ball, "
        f"{int((races.verdict == races.source.str[4:]).sum())} named their own race;",
        f"- real (CWRU, whole records at the faulty bearing's own sensor): "
        f"**{int((own.verdict == 'ball').sum())} of {len(own)} named ball**; called a race "
        f"fault {int(own.verdict.isin(['outer', 'inner']).sum())} (of which graded N, not "
        f"diagnosable: {int((own.verdict.isin(['outer', 'inner']) & (own.grade == 'N')).sum())}),"
        f" healthy {int((own.verdict == 'healthy').sum())}.",
        "",
        f"At their own sensor the real ball records read {own.ball_db.min():.1f}-"
        f"{own.ball_db.max():.1f} dB of ball evidence (threshold 6 dB), their strongest race "
        f"family {race_max.min():.1f}-{race_max.max():.1f} dB. In the enhanced envelope "
        f"spectrum (band-integrated cyclic coherence, Antoni 2007) the ball reads "
        f"{own.ees_ball_db.min():.1f}-{own.ees_ball_db.max():.1f} dB against "
        f"{own.ees_race_db.min():.1f}-{own.ees_race_db.max():.1f} dB for the stronger race: "
        f"ahead on {int((own.ees_ball_db > own.ees_race_db).sum())} of {len(own)}. The "
        "coherence does not separate these records either: what limits them is the "
        "signal, not the squared envelope. Smith & Randall (2015) grade the drive-end "
        "0.007 in record (118) not diagnosable and the 0.021 in record (222) clearly "
        "diagnosable.",
        "",
    ]
    raced = own[own.verdict.isin(["outer", "inner"])]
    if len(raced):
        lines += ["What carried each race verdict on a ball record, at its own sensor:", ""]
        lines += [f"- {r.record}: {r.decisive}." for r in raced.itertuples()]
        lines += [""]
    if before is not None:
        lines += _before_after(table, before)
    if reading is not None:
        lines += expert_markdown(reading)
    lines += [
        "| source | record | bearing | verdict | grade | outer dB | inner dB | ball dB "
        "| EES ball dB | EES race dB |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in table.itertuples():
        lines.append(f"| {r.source} | {r.record} | {r.bearing} | {r.verdict} | {r.grade} | "
                     f"{r.outer_db:.1f} | {r.inner_db:.1f} | {r.ball_db:.1f} | "
                     f"{r.ees_ball_db:.1f} | {r.ees_race_db:.1f} |")
    return "\n".join(lines) + "\n"


def _before_after(table: pd.DataFrame, before: pd.DataFrame) -> list[str]:
    """Rows whose verdict, grade or ball evidence changed against ``before`` (a table of
    the same rows from the diagnoser without the cage rule, run side by side)."""
    keys = ["source", "record"]
    both = table.merge(before, on=keys, suffixes=("", "_before"))
    changed = both[(both.verdict != both.verdict_before) | (both.grade != both.grade_before)
                   | ((both.ball_db - both.ball_db_before).abs() > 0.05)]
    out = [f"Against the diagnoser without the cage rule ({len(both)} rows compared): "
           f"{len(changed)} changed.", ""]
    if len(changed):
        out += ["| record | before | after | ball dB before | ball dB after |",
                "|---|---|---|---|---|"]
        out += [f"| {r.source} {r.record} | {r.verdict_before} ({r.grade_before}) | "
                f"{r.verdict} ({r.grade}) | {r.ball_db_before:.1f} | {r.ball_db:.1f} |"
                for r in changed.itertuples()]
        out.append("")
    return out


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, default=SHARED)
    parser.add_argument("--out", type=Path, default=DOCS)
    parser.add_argument("--before", type=Path, default=None,
                        help="diagnosis_ball.csv of another version, run side by side: "
                             "the page lists the rows that changed")
    args = parser.parse_args(argv)
    table = pd.DataFrame(simulated() + simulated_races() + real(args.data))
    atomic_write(results_in(args.out) / "diagnosis_ball.csv",
                 lambda tmp: table.to_csv(tmp, index=False))
    reading = expert(args.data)
    atomic_write(results_in(args.out) / "diagnosis_ball_reading.csv",
                 lambda tmp: reading.to_csv(tmp, index=False))
    before = None if args.before is None else pd.read_csv(args.before)
    page = markdown(table, before, reading)
    atomic_write(args.out / "diagnosis_ball.md", lambda tmp: tmp.write_text(page))
    print(page)


if __name__ == "__main__":
    main()
