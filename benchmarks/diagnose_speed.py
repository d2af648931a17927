"""The envelope diagnoser at the CWRU rig's other speeds and at 48 kHz.

The held-out CWRU records run at motor loads of 1-3 hp, 1772-1730 rpm; the shared ones
at 0 hp (1797 rpm). Playing a record slower by ``f = rpm / 1797`` (resampling it by
1797 / rpm and keeping the sampling rate) turns it into a record of the same machine at
``f`` times the speed: every shaft, fault and cage line moves to ``f`` times its
frequency, and so do the structural resonances. It does not change the load, so it tests
the diagnoser's handling of speed (the demodulation bands of the 1/3-binary tree, the
shaft guard, the slip search, the speed check), not what a heavier load does to the
bearing. Each record is diagnosed whole and in one-second segments with its stated speed
times ``f``; nothing is fitted.

The rig's held-out records also come at 48 kHz. Each 12 kHz fault record is brought to
48 kHz and its empty band above 6 kHz filled with what the 48 kHz healthy recording holds
there at the same sensor; the first 5 s (the healthy recording's length) are diagnosed at
both rates. This tests the rate's effect on the band search (the 1/3-binary tree spans
0-24 kHz in bands four times as wide, with real sensor noise above 6 kHz), not real
48 kHz fault records.

Run::

    PYTHONPATH=. python benchmarks/diagnose_speed.py           # ~4 min on 2 cores

Writes ``docs/diagnosis_speed.md``, ``docs/results/diagnosis_speed.csv`` and
``docs/results/diagnosis_rate.csv``.
"""

from __future__ import annotations

import time
from pathlib import Path

import pandas as pd
from _paths import results_in
from diagnose_loro import _md, cwru_records, records_parser, segments
from scipy.signal import butter, resample_poly, sosfiltfilt

from ballpass.diagnose import EnvelopeDiagnoser
from ballpass.signalio import atomic_write

#: The rig's speeds at 0-3 hp, rpm (CWRU data centre); the records are at the first.
SPEEDS = (1797, 1772, 1750, 1730)
#: Rate the 48 kHz healthy recording is brought to first, Hz (the fault files' rate).
FS = 12_000.0
#: The rate of the rig's other records, Hz.
FS_HIGH = 48_000.0
#: Lower edge of the healthy recording's content added above a 12 kHz record's Nyquist
#: frequency, Hz: 6 kHz plus a guard for the 8th-order Butterworth high-pass's skirt.
FILL_FROM_HZ = 6_500.0


def played_at(x, fs: float, rpm: int):
    """``x`` (at ``fs``) brought to 12 kHz and played at ``rpm / 1797`` of its speed."""
    if fs != FS:
        x = resample_poly(x, round(FS), round(fs))
    return x if rpm == SPEEDS[0] else resample_poly(x, SPEEDS[0], rpm)


def diagnose(records) -> pd.DataFrame:
    """One row per record and speed: the whole record's verdict, its strongest family
    evidence, and the one-second segments named right."""
    rows = []
    for rec in records:
        for rpm in SPEEDS:
            x = played_at(rec.x, rec.fs, rpm)
            diag = EnvelopeDiagnoser(bearing=rec.bearing, fs=FS, rpm=rec.rpm * rpm / SPEEDS[0])
            whole = diag.explain(x[None])[0]
            parts = diag.predict(segments(x, FS, 1.0))
            rows.append({"group": rec.group, "record": rec.name, "truth": rec.label,
                         "rpm": rpm, "verdict": whole.label,
                         "evidence_db": max(whole.evidence_db.values()),
                         "segments_right": int((parts == rec.label).sum()),
                         "segments": len(parts)})
    return pd.DataFrame(rows)


def at_48k(records) -> pd.DataFrame:
    """One row per fault record: verdict and one-second segments named on its first 5 s
    at 12 kHz and the same 5 s at 48 kHz (high band from the healthy recording)."""
    healthy = {rec.name.split()[-1]: rec for rec in records if rec.label == "healthy"}
    sos = butter(8, FILL_FROM_HZ, "highpass", fs=FS_HIGH, output="sos")
    high = {ch: sosfiltfilt(sos, rec.x) for ch, rec in healthy.items() if rec.fs == FS_HIGH}
    rows = []
    for rec in records:
        channel = rec.name.split()[-1]
        if rec.label == "healthy" or rec.fs != FS or channel not in high:
            continue
        n = len(high[channel])
        x48 = resample_poly(rec.x, round(FS_HIGH / FS), 1)[:n]
        versions = {"12 kHz": (rec.x[: len(x48) // 4], FS),
                    "48 kHz": (x48 + high[channel][: len(x48)], FS_HIGH)}
        row = {"group": rec.group, "record": rec.name, "truth": rec.label}
        for name, (x, fs) in versions.items():
            diag = EnvelopeDiagnoser(bearing=rec.bearing, fs=fs, rpm=rec.rpm)
            parts = diag.predict(segments(x, fs, 1.0))
            row[f"verdict {name}"] = diag.predict(x[None])[0]
            row[f"segments named {name}"] = int((parts == rec.label).sum())
            row["segments"] = len(parts)
        rows.append(row)
    return pd.DataFrame(rows)


def rate_summary(table: pd.DataFrame) -> pd.DataFrame:
    """Records and segments named at each rate, and verdicts that agree."""
    same = (table["verdict 12 kHz"] == table["verdict 48 kHz"]).sum()
    return pd.DataFrame([{
        "rate": name,
        "records named": f"{(table[f'verdict {name}'] == table.truth).sum()} of {len(table)}",
        "verdict as at 12 kHz": f"{same} of {len(table)}",
        "1 s segments named": f"{table[f'segments named {name}'].sum()} of "
                              f"{table.segments.sum()}"}
        for name in ("12 kHz", "48 kHz")])


def summary(table: pd.DataFrame) -> pd.DataFrame:
    """Per speed: records named, records whose verdict is the one at 1797 rpm, segments
    named."""
    base = table[table.rpm == SPEEDS[0]].set_index("record").verdict
    rows = []
    for rpm, part in table.groupby("rpm", sort=False):
        part = part.set_index("record")
        rows.append({"speed (rpm)": rpm,
                     "records named": f"{(part.verdict == part.truth).sum()} of {len(part)}",
                     "verdict as at 1797 rpm": f"{(part.verdict == base).sum()} of {len(part)}",
                     "1 s segments named": f"{part.segments_right.sum()} of "
                                           f"{part.segments.sum()}"})
    return pd.DataFrame(rows)


def markdown(table: pd.DataFrame, rates: pd.DataFrame, seconds: float) -> str:
    wide = table.pivot_table(index=["group", "record", "truth"], columns="rpm",
                             values="verdict", aggfunc="first", sort=False)
    changed = wide[wide.nunique(axis=1) > 1].reset_index()
    changed.columns = [str(c) if isinstance(c, str) else f"{c} rpm" for c in changed.columns]
    return "\n".join([
        "# The diagnoser at the rig's other speeds and at 48 kHz",
        "",
        "Produced by `PYTHONPATH=. python benchmarks/diagnose_speed.py` "
        f"({seconds / 60:.0f} min); do not edit by hand.",
        "",
        "Every shared CWRU record (each fault file at both sensors with its faulty "
        "bearing's lines, the healthy recording at both) played slower by rpm / 1797, "
        "so that it runs at the speeds of the rig's 1-3 hp records, and diagnosed whole "
        "and in one-second segments with the stated speed scaled alike. Playing a "
        "record slower moves the resonances with the fault lines and keeps the load: "
        "this tests how the diagnoser handles speed, not what a heavier load does.",
        "",
        _md(summary(table)),
        "",
        "Records whose whole-record verdict changes with the speed:",
        "",
        _md(changed) if len(changed) else "none.",
        "",
        "## At 48 kHz",
        "",
        "The rig's held-out records also come at 48 kHz, and the diagnoser's "
        "1/3-binary band tree then spans 0-24 kHz in bands four times as wide. Each "
        "12 kHz fault "
        "record is brought to 48 kHz, its empty band above 6 kHz filled with the 48 kHz "
        "healthy recording's own content above "
        f"{FILL_FROM_HZ / 1000:g} kHz at the same sensor (real sensor noise where the "
        "tree now looks), and its first 5 s (the healthy recording's length) are "
        "diagnosed at both rates. This tests the rate, not real 48 kHz fault records.",
        "",
        _md(rate_summary(rates)),
        "",
        "Records whose verdict changes with the rate:",
        "",
        _md(rates.loc[rates["verdict 12 kHz"] != rates["verdict 48 kHz"],
                      ["group", "record", "truth", "verdict 12 kHz", "verdict 48 kHz"]]),
        "",
    ])


def main(argv=None) -> None:
    args = records_parser(__doc__).parse_args(argv)
    t0 = time.perf_counter()
    records = cwru_records(args.data / "cwru")
    table = diagnose(records)
    rates = at_48k(records)
    results = results_in(args.out)
    atomic_write(results / "diagnosis_speed.csv", lambda tmp: table.to_csv(tmp, index=False))
    atomic_write(results / "diagnosis_rate.csv", lambda tmp: rates.to_csv(tmp, index=False))
    text = markdown(table, rates, time.perf_counter() - t0)
    atomic_write(args.out / "diagnosis_speed.md",
                 lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    print(summary(table).to_string(index=False))
    print(rate_summary(rates).to_string(index=False))


if __name__ == "__main__":
    main()
