"""The envelope diagnoser at the CWRU rig's other speeds: every shared record played slower.

The held-out CWRU records run at motor loads of 1-3 hp, 1772-1730 rpm; the shared ones
at 0 hp (1797 rpm). Playing a record slower by ``f = rpm / 1797`` (resampling it by
1797 / rpm and keeping the sampling rate) turns it into a record of the same machine at
``f`` times the speed: every shaft, fault and cage line moves to ``f`` times its
frequency, and so do the structural resonances. It does not change the load, so it tests
the diagnoser's handling of speed (the demodulation bands of the 1/3-binary tree, the
shaft guard, the slip search, the speed check), not what a heavier load does to the
bearing. Each record is diagnosed whole and in one-second segments with its stated speed
times ``f``; nothing is fitted.

Run::

    PYTHONPATH=. python benchmarks/diagnose_speed.py           # ~4 min on 2 cores

Writes ``docs/diagnosis_speed.md`` and ``docs/diagnosis_speed.csv``.
"""

from __future__ import annotations

import time
from pathlib import Path

import pandas as pd
from diagnose_loro import _md, cwru_records, records_parser, segments
from scipy.signal import resample_poly

from ballpass.diagnose import EnvelopeDiagnoser
from ballpass.signalio import atomic_write

#: The rig's speeds at 0-3 hp, rpm (CWRU data centre); the records are at the first.
SPEEDS = (1797, 1772, 1750, 1730)
#: Rate the 48 kHz healthy recording is brought to first, Hz (the fault files' rate).
FS = 12_000.0


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


def markdown(table: pd.DataFrame, seconds: float) -> str:
    wide = table.pivot_table(index=["group", "record", "truth"], columns="rpm",
                             values="verdict", aggfunc="first", sort=False)
    changed = wide[wide.nunique(axis=1) > 1].reset_index()
    changed.columns = [str(c) if isinstance(c, str) else f"{c} rpm" for c in changed.columns]
    return "\n".join([
        "# The diagnoser at the rig's other speeds",
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
    ])


def main(argv=None) -> None:
    args = records_parser(__doc__).parse_args(argv)
    t0 = time.perf_counter()
    table = diagnose(cwru_records(args.data / "cwru"))
    args.out.mkdir(parents=True, exist_ok=True)
    atomic_write(args.out / "diagnosis_speed.csv", lambda tmp: table.to_csv(tmp, index=False))
    text = markdown(table, time.perf_counter() - t0)
    atomic_write(args.out / "diagnosis_speed.md",
                 lambda tmp: Path(tmp).write_text(text, encoding="utf-8"))
    print(summary(table).to_string(index=False))


if __name__ == "__main__":
    main()
