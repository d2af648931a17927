"""Pre-processing before the envelope, measured leave-one-record-out on every shared record.

Randall & Antoni's procedure (MSSP 25, 2011, section 4) removes the discrete
(deterministic) part of a signal before the spectral-kurtosis band choice and the
envelope: cepstrum pre-whitening, linear prediction or discrete/random separation
(DRS). :class:`ballpass.diagnose.EnvelopeDiagnoser` offers each (``prewhiten=True``,
``separate="lp"``, ``separate="drs"``) and runs without by default. This script runs
the diagnoser with each option, unchanged otherwise, on every real record of
``../shared/data`` (whole records and one-second segments, as
``benchmarks/diagnose_loro.py``). The options are fixed settings, nothing is fitted to
the records, so each result is a held-out result.

It also measures what one second can show: for each record, the evidence of its true
family in each one-second segment (median and largest) against the largest evidence
any family reaches in the healthy segments of the same sensor's healthy recording.

Run::

    PYTHONPATH=. python benchmarks/diagnose_preprocessing.py        # ~5 min on 2 cores

Writes ``docs/diagnosis_preprocessing.md`` and ``docs/results/diagnosis_preprocessing.csv``.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pandas as pd
from _paths import results_in
from diagnose_loro import _md, real_records, records_parser, segments

from ballpass.diagnose import EnvelopeDiagnoser, envelope_evidence
from ballpass.signalio import atomic_write

#: name -> (EnvelopeDiagnoser keyword arguments, description)
VARIANTS = {
    "none (default)": ({}, "no pre-processing"),
    "cepstrum": ({"prewhiten": True}, "cepstrum pre-whitening (`prewhiten=True`)"),
    "lp": ({"separate": "lp"}, "linear-prediction residual (`separate=\"lp\"`)"),
    "drs": ({"separate": "drs"}, "discrete/random separation (`separate=\"drs\"`)"),
}
FAMILIES = ("outer", "inner", "ball")


def run(records, variant: str) -> list[dict]:
    """Diagnose each record whole and in one-second segments with one variant."""
    kwargs = VARIANTS[variant][0]
    rows = []
    for rec in records:
        diag = EnvelopeDiagnoser(bearing=rec.bearing, fs=rec.fs, rpm=rec.rpm, **kwargs)
        (exp,) = diag.explain(rec.x[None])
        seg = segments(rec.x, rec.fs)
        pred = diag.predict(seg, rpm=exp.rpm)
        rows.append({"variant": variant, "group": rec.group, "record": rec.name,
                     "truth": rec.label, "prediction": exp.label, "grade": exp.grade,
                     "segments": len(seg), "segments_right": int(np.sum(pred == rec.label)),
                     "segments_flagged": int(np.sum(pred != "healthy")),
                     "segment_labels": "".join(p[0] for p in pred)})
        print(f"{variant:15s} {rec.name:30s} {rec.label:7s} -> {exp.label:7s} "
              f"{rows[-1]['segment_labels']}", flush=True)
    return rows


def per_class(table: pd.DataFrame) -> pd.DataFrame:
    """Records and segments named, per group and class, one column pair per variant."""
    out = []
    for (group, truth), part in table.groupby(["group", "truth"], sort=False):
        row = {"group": group, "class": truth, "records": part["record"].nunique()}
        for variant, v in part.groupby("variant", sort=False):
            row[variant] = (f"{int((v['prediction'] == truth).sum())} "
                            f"({v['segments_right'].sum()}/{v['segments'].sum()})")
        out.append(row)
    return pd.DataFrame(out)


def totals(table: pd.DataFrame) -> pd.DataFrame:
    """The issue's goal quantities per variant."""
    out = []
    for variant, v in table.groupby("variant", sort=False):
        g, t = v["group"], v["truth"]
        race = t.isin(["inner", "outer"])
        right = v["prediction"] == t
        healthy = t == "healthy"
        out.append({
            "pre-processing": variant,
            "DE inner+outer": f"{right[(g == 'DE') & race].mean():.0%}",
            "DE all faulty": f"{right[(g == 'DE') & ~healthy].mean():.0%}",
            "FE inner+outer": f"{right[(g == 'FE') & race].mean():.0%}",
            "FE>DE inner+outer": f"{right[(g == 'FE>DE') & race].mean():.0%}",
            "DE>FE inner+outer": f"{right[(g == 'DE>FE') & race].mean():.0%}",
            "healthy segments flagged": f"{v.loc[healthy, 'segments_flagged'].sum()}"
                                        f"/{v.loc[healthy, 'segments'].sum()}",
            "MFPT": f"{int(right[g == 'MFPT'].sum())}/{int((g == 'MFPT').sum())}",
            "records right": f"{int(right.sum())}/{len(v)}",
            "segments right": f"{v['segments_right'].sum()}/{v['segments'].sum()}",
        })
    return pd.DataFrame(out)


def one_second(records) -> pd.DataFrame:
    """Evidence of each record's true family (the strongest family for a healthy
    record), whole and per one-second segment, against the largest evidence any family
    reaches in a one-second segment of the healthy recording at the same sensor."""
    healthy_max = {}
    for rec in records:
        if rec.label == "healthy":
            ev = envelope_evidence(segments(rec.x, rec.fs), rec.fs, rec.bearing, rec.rpm)
            healthy_max[rec.group] = float(np.max([ev.evidence_db[f] for f in FAMILIES]))
    def family(label, evidence):
        return label if label != "healthy" else max(FAMILIES, key=evidence.get)

    rows = []
    for rec in records:
        if rec.group == "MFPT":
            continue
        diag = EnvelopeDiagnoser(bearing=rec.bearing, fs=rec.fs, rpm=rec.rpm)
        (whole,) = diag.explain(rec.x[None])
        seg = segments(rec.x, rec.fs)
        # Segments use the record's checked speed, as benchmarks/diagnose_loro.py does.
        ev = envelope_evidence(seg, rec.fs, rec.bearing, whole.rpm).evidence_db

        seg_ev = (ev[rec.label] if rec.label != "healthy"
                  else np.max([ev[f] for f in FAMILIES], axis=0))
        reference = healthy_max[rec.group.split(">")[-1]]  # the sensor's healthy channel
        rows.append({
            "group": rec.group, "record": rec.name, "truth": rec.label,
            "whole (dB)": round(whole.evidence_db[family(rec.label, whole.evidence_db)], 1),
            "whole": whole.label,
            "1 s median (dB)": round(float(np.median(seg_ev)), 1),
            "1 s largest (dB)": round(float(np.max(seg_ev)), 1),
            "healthy 1 s largest (dB)": round(reference, 1),
            "1 s above healthy": f"{int(np.sum(seg_ev > reference))}/{len(seg)}",
        })
    return pd.DataFrame(rows)


def verdict(table: pd.DataFrame) -> list[str]:
    """Which option names the most records and segments (computed, not written)."""
    right = table.assign(r=table["prediction"] == table["truth"]).groupby(
        "variant", sort=False).agg(records=("r", "sum"), segments=("segments_right", "sum"))
    best_rec = right.index[right["records"] == right["records"].max()].tolist()
    best_seg = right.index[right["segments"] == right["segments"].max()].tolist()
    return [
        f"Most whole records named: {', '.join(best_rec)} "
        f"({int(right['records'].max())} of {table['record'].nunique()}); most one-second "
        f"segments named: {', '.join(best_seg)} ({int(right['segments'].max())}). "
        "Removing the discrete part takes the shaft harmonics out of the SES; on these "
        "records the diagnoser's own rules (shaft-harmonic bins read as background, "
        "families judged by the lines only they explain) already do that, and every "
        "option loses the fan-end 12 o'clock outer-race record at its own sensor "
        "(linear prediction and DRS to a false inner call, the cepstrum to healthy; the "
        "cepstrum also most of the fan-end segments). Hence no pre-processing by "
        "default; `separate=` remains the tool for gear-mesh lines (docs/seed004.md), "
        "where the discrete part dominates.",
    ]


def markdown(table, ceiling, seconds) -> str:
    return "\n".join([
        "# Pre-processing before the envelope, on held-out recordings",
        "",
        "Produced by `PYTHONPATH=. python benchmarks/diagnose_preprocessing.py` "
        f"({seconds:.0f} s); do not edit by hand.",
        "",
        "`EnvelopeDiagnoser` with each pre-processing option of Randall & Antoni's "
        "procedure (MSSP 25, 2011, section 4), everything else at its defaults, on every "
        "real CWRU and MFPT record we test on (groups as in [diagnosis.md](diagnosis.md)). The "
        "options are fixed settings; nothing is fitted, so every number is held out.",
        "",
        *[f"- **{k}**: {d}" for k, (_, d) in VARIANTS.items()],
        "",
        "## The goal quantities",
        "",
        _md(totals(table)),
        "",
        *verdict(table),
        "",
        "## Per group and class",
        "",
        "Whole records named (one-second segments named in brackets).",
        "",
        _md(per_class(table)),
        "",
        "## What one second can show",
        "",
        "Evidence of each record's true family (for the healthy records: the strongest "
        "family; default settings) from the whole record and from each one-second "
        "segment, against the largest evidence *any* family reaches in a one-second "
        "segment of the healthy recording at the same sensor (`FE>DE` records against "
        "the healthy drive-end channel, `DE>FE` against the fan-end one). A segment "
        "whose evidence lies below that level cannot be named by any threshold that "
        "keeps every healthy segment healthy.",
        "",
        _md(ceiling),
        "",
        "## Averaging one-second captures: tried, not shipped",
        "",
        "A record-level verdict from its one-second segments by averaging their SES per "
        "band before the families are judged (the averaged envelope spectrum) was "
        "prototyped and measured once (not produced by this script). On white noise it "
        "behaves as theory says: the largest family evidence over K averaged captures "
        "follows 0.41 + 3.86 / sqrt(K) dB (Monte Carlo, 6205 and 6203, 100 records per "
        "K: 4.27, 3.14, 2.12, 1.61 dB for K = 1, 2, 5, 10), so the threshold could drop "
        "by 3.86 (1 - 1/sqrt(K)) dB at the same false-alarm margin, and a simulated "
        "inner-race fault that one capture names once in ten is named from ten averaged "
        "captures. On the real records it fails where it matters: the healthy drive-end "
        "recording, averaged over its five segments, reads outer-race evidence 6.3 dB, "
        "above both the lowered threshold (3.9 dB) and the single-capture one (6 dB), "
        "while the whole record reads 1.2 dB; the deterministic content of a healthy "
        "machine near the fault lines (probably shaft-harmonic leakage at one-second "
        "resolution; not verified) stands out once the background's scatter averages "
        "away. The faint fan-end "
        "outer-race records gain nothing (12 o'clock: 1.0 dB averaged against 7.4 dB "
        "whole) and the ball records turn into false inner or outer calls. A contiguous "
        "record is diagnosed whole (finer resolution, which separates the fault lines "
        "from the shaft harmonics); separate captures are diagnosed one by one.",
        "",
    ])


def main(argv=None) -> None:
    args = records_parser(__doc__).parse_args(argv)
    t0 = time.perf_counter()
    records = real_records(args.data)
    table = pd.DataFrame([row for v in VARIANTS for row in run(records, v)])
    ceiling = one_second(records)
    seconds = time.perf_counter() - t0
    atomic_write(results_in(args.out) / "diagnosis_preprocessing.csv",
                 lambda tmp: table.to_csv(tmp, index=False))
    text = markdown(table, ceiling, seconds)
    atomic_write(args.out / "diagnosis_preprocessing.md",
                 lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    print(totals(table).to_string(index=False))
    print(ceiling.to_string(index=False))


if __name__ == "__main__":
    main()
