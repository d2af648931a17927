"""``ballpass diagnose INPUT...``: the envelope diagnoser's verdict and why, per signal."""

from __future__ import annotations

import argparse
from pathlib import Path

EXAMPLE = """\
examples:
  ballpass simulate --fault inner --out inner.npz && ballpass diagnose inner.npz
  ballpass diagnose 12k_DE_IR007_0.mat 12k_DE_OR007@6_0.mat
  ballpass diagnose 12k_FE_OR007@12_0.mat --channel FE  # the fan-end 6203 at its sensor
  ballpass diagnose cwru/ --out verdicts.csv            # every .mat file of a folder
  ballpass diagnose rec.csv --fs 12000 --rpm 1797 --bearing 6205   # also .npy, .wav
  ballpass diagnose recordings.csv    # a manifest: path, fs, rpm, bearing[, label] per row
  ballpass diagnose OuterRaceFault_vload_1.mat --segment 1
  ballpass diagnose 12k_DE_OR007@6_0.mat --plot figures/   # the SES behind each verdict
  ballpass diagnose cwru/ --segment 1 --baseline Normal_0.mat  # thresholds from healthy

Inputs are those of `ballpass features` (see `ballpass features --help` for the CWRU
pitfalls: values in g, the normal baseline sampled at 48 kHz). Each signal gets a
verdict (healthy, outer, inner, ball), a grade in the spirit of Smith & Randall (Y clearly
diagnosed, P partly, N not diagnosable), the evidence of each fault family against its
threshold (dB), the lines that carried the decision, and what was corrected (a stated
speed that the shaft harmonics contradict). Diagnose whole records: a 10 s record
resolves fault lines that one-second segments cannot (docs/diagnosis.md); with --segment
each record is also diagnosed whole, next to the tally of its segments' verdicts.
With --baseline, the thresholds come from healthy recordings of the machine instead of
from noise statistics alone: a healthy machine's own lines (the CWRU drive end carries
one 0.85 % above BPFO) then no longer pass for a fault (docs/diagnosis_length.md)."""


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register ``diagnose`` on the ``ballpass`` command."""
    from .features import add_input_arguments, add_quiet_argument

    p = subparsers.add_parser(
        "diagnose",
        help="the envelope diagnoser's verdict, grade and evidence for each signal",
        description="Diagnose every signal of the inputs with the physics-based envelope "
        "diagnoser (no training): print its verdict, grade, fault-family evidence and the "
        "lines behind it, and optionally write them as a table.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_input_arguments(p, band_default="each fault family's band, chosen by its own "
                        "evidence")
    p.add_argument(
        "--baseline",
        nargs="+",
        default=None,
        metavar="HEALTHY",
        help="healthy recording(s) of the same machine and sensor (inputs as INPUT, read "
        "with the same --fs/--channel/--rpm/--bearing): each fault family's threshold "
        "becomes what their windows of the diagnosed length read (started every 1/8 of "
        "it; 99th percentile + 1 dB, never below 6 dB)",
    )
    p.add_argument(
        "--line-hz",
        type=float,
        default=None,
        metavar="HZ",
        help="supply frequency of the machine (50 or 60), where known: harmonics of it "
        "standing out of the squared envelope spectrum are set aside like the shaft's, so "
        "an electrical line at a fault rate is not read as the fault",
    )
    p.add_argument(
        "--out",
        "-o",
        default=None,
        metavar="TABLE",
        help="also write one row per signal to TABLE.csv or TABLE.parquet",
    )
    p.add_argument(
        "--plot",
        default=None,
        metavar="DIR",
        help="also draw each verdict's squared envelope spectrum with the lines the "
        "diagnoser read, one DIR/<signal>.png per signal",
    )
    add_quiet_argument(p)
    p.set_defaults(func=run)
    return p


def verdict_rows(signals, band=None, progress: bool = True, segmented: bool = False,
                 thresholds=None, line_hz=None):
    """``(explanation, row)`` per signal: the diagnoser's :class:`Explanation` and a
    table row (source, truth when known, the bearing whose lines were read, verdict,
    grade, evidence and threshold per family in dB, the verdict's band, the speeds
    stated and used, notes). ``segmented``: the signals are ``--segment`` cuts (a
    signal too short is then the option's fault, not the record's). ``thresholds``:
    a :class:`BaselineThresholds` (``--baseline``), or None for the default. ``line_hz``:
    the supply frequency (``--line-hz``), or None."""
    import sys

    import numpy as np
    from tqdm import tqdm

    from ..diagnose import EnvelopeDiagnoser
    from ..diagnose.rules import MIN_CAGE_PERIODS
    from ..features.bands import as_bearing
    from .features import is_known

    for sig in signals:  # every signal checked before any is diagnosed
        missing = [f"{what} ({opt})" for what, opt, value in (
            ("bearing", "--bearing", sig.bearing), ("shaft speed", "--rpm", sig.rpm))
            if not is_known(value)]
        if missing:
            raise ValueError(f"{sig.name}: the input does not give the {' or '.join(missing)};"
                             " pass it on the command line (the fault lines need both)")
        shortest = MIN_CAGE_PERIODS / as_bearing(sig.bearing).frequencies(
            float(sig.rpm) / 60.0).ftf
        seconds = len(sig.x) / sig.fs
        if seconds < shortest:
            remedy = ("give a --segment of at least that, or diagnose the whole record"
                      if segmented else "the diagnoser needs at least that much of the "
                      "record (a ball fault's +-FTF sidebands are resolved over it)")
            raise ValueError(
                f"{sig.name} lasts {seconds:.3g} s, shorter than {MIN_CAGE_PERIODS:g} cage "
                f"periods ({shortest:.3g} s at {float(sig.rpm):g} rpm): {remedy}")
    out = []
    for sig in tqdm(signals, desc="diagnose", unit="signal", disable=not progress,
                    leave=False, file=sys.stderr):
        own = {} if thresholds is None else {"threshold_db": thresholds(sig)}
        diag = EnvelopeDiagnoser(bearing=sig.bearing, fs=sig.fs, rpm=float(sig.rpm), band=band,
                                 line_hz=line_hz, **own)
        why = diag.explain(np.asarray(sig.x, dtype=np.float64)[None])[0]
        lo, hi = why.band_hz.get(why.label, (np.nan, np.nan))
        row = {"source": sig.name, **sig.columns, "bearing": str(sig.bearing),
               "prediction": why.label, "grade": why.grade}
        for family, value in why.evidence_db.items():
            row[f"{family}_db"] = value
            row[f"{family}_threshold_db"] = why.threshold_db[family]
        row |= {"band_lo_hz": lo, "band_hi_hz": hi, "rpm_stated": why.rpm_stated,
                "rpm_used": why.rpm, "false_alarm_probability": why.false_alarm_probability,
                "notes": " / ".join(why.notes)}
        out.append((why, row))
    return out


def run(args) -> int:
    """Diagnose the inputs; print the verdicts (and write the table); returns the exit code."""
    import pandas as pd

    from ._output import TABLE_SUFFIXES, check_output_path, show_progress, write_table
    from .features import load_records, segment_signals

    out = None if args.out is None else check_output_path(
        args.out, option="--out", suffixes=TABLE_SUFFIXES)
    plots = None if args.plot is None else check_output_path(args.plot, option="--plot",
                                                              folder=True)
    records = load_records(args)
    segmented = args.segment is not None
    signals = segment_signals(records, args.segment) if segmented else records
    band = tuple(args.band) if args.band is not None else None
    thresholds = None
    if args.baseline is not None:
        try:
            healthy = load_records(argparse.Namespace(**{**vars(args),
                                                         "inputs": args.baseline}))
        except (ValueError, TypeError, FileNotFoundError) as exc:  # say which input it was
            raise type(exc)(f"--baseline: {exc}") from None
        thresholds = BaselineThresholds(healthy, band, line_hz=args.line_hz)
        thresholds.check(records)
    results = verdict_rows(signals, band, progress=show_progress(args), segmented=segmented,
                           thresholds=thresholds, line_hz=args.line_hz)
    for why, row in results:
        truth = row.get("label")
        known = f" (label: {truth})" if isinstance(truth, str) and truth else ""
        print(f"{row['source']}{known}: {why}")
    rows = [row | {"scope": "segment" if segmented else "record"} for _, row in results]
    if segmented:
        rows += record_verdicts(records, results, args.segment, band,
                                progress=show_progress(args), thresholds=thresholds,
                                line_hz=args.line_hz)
    if out is not None:
        frame = pd.DataFrame(rows)
        write_table(frame, Path(out))
        print(f"{len(frame)} verdict(s) -> {out}")
    if plots is not None:
        written = write_plots(signals, [why for why, _ in results], plots,
                              progress=show_progress(args))
        print(f"{len(written)} figure(s) -> {plots}")
    return 0


def record_verdicts(records, segment_results, seconds: float, band,
                    progress: bool = True, thresholds=None, line_hz=None) -> list[dict]:
    """Each whole record diagnosed too, printed with the tally of its segments' verdicts
    (``segment_results`` in record order, as :func:`segment_signals` cuts them into
    ``seconds``): a 10 s record resolves lines that its one-second segments cannot
    (docs/diagnosis_length.md). Returns its table rows (``scope`` = ``"record"``)."""
    from collections import Counter

    from .._validation import check_segment

    rows = []
    verdicts = iter(row["prediction"] for _, row in segment_results)
    whole = verdict_rows(records, band, progress, thresholds=thresholds, line_hz=line_hz)
    for rec, (why, row) in zip(records, whole, strict=True):
        n = len(rec.x) // check_segment(seconds, rec.fs, "--segment")
        mine = [next(verdicts) for _ in range(n)]
        tally = ", ".join(f"{n} {label}" for label, n in Counter(mine).most_common())
        print(f"{rec.name}, whole record ({len(rec.x) / rec.fs:.3g} s): {why.label} "
              f"(grade {why.grade}); its {len(mine)} segment{'s' * (len(mine) != 1)}: "
              f"{tally}")
        rows.append(row | {"scope": "record"})
    return rows


class BaselineThresholds:
    """``--baseline``: per bearing and signal length, the thresholds that
    :func:`ballpass.diagnose.baseline_thresholds` fits on the healthy ``baseline``
    signals of that bearing (windows as long as the signal diagnosed, or the whole
    baseline if shorter), fitted once and printed. Call it with a signal to get its
    ``threshold_db``. ``line_hz`` (``--line-hz``): the supply frequency, whose
    harmonics the fit sets aside as the diagnosis does."""

    def __init__(self, baseline, band=None, line_hz=None):
        self.baseline = baseline
        self.band = band
        self.line_hz = line_hz
        self._fitted = {}

    def check(self, signals) -> None:
        """A ValueError, before any work, if a baseline lacks its bearing or speed or a
        signal's bearing has no baseline (the signals' own gaps are
        :func:`verdict_rows`' to report)."""
        from .features import is_known

        for sig in self.baseline:
            if not (is_known(sig.bearing) and is_known(sig.rpm)):
                raise ValueError(f"--baseline {sig.name}: the input does not give the "
                                 "bearing or the shaft speed; pass --bearing and --rpm")
        have = {str(b.bearing) for b in self.baseline}
        missing = sorted({str(s.bearing) for s in signals if is_known(s.bearing)} - have)
        if missing:
            raise ValueError(f"--baseline holds no healthy recording of bearing "
                             f"{', '.join(missing)} (it has {', '.join(sorted(have))}): "
                             "give one of the same machine and sensor")

    def __call__(self, sig) -> dict:
        from ..diagnose import baseline_thresholds

        mine = [b for b in self.baseline if str(b.bearing) == str(sig.bearing)]
        # windows as long as the signal, at most as long as the longest baseline
        seconds = min(len(sig.x) / sig.fs, max(len(b.x) / b.fs for b in mine))
        key = (str(sig.bearing), round(seconds, 3))
        if key not in self._fitted:
            found = baseline_thresholds([(b.x, b.fs, float(b.rpm)) for b in mine],
                                        sig.bearing, seconds, band=self.band,
                                        line_hz=self.line_hz)
            self._fitted[key] = found
            print(f"baseline ({', '.join(b.name for b in mine)}), {key[0]} on {seconds:.3g} s "
                  "windows: thresholds "
                  + ", ".join(f"{f} {v:.1f}" for f, v in found.items()) + " dB")
        return self._fitted[key]


def write_plots(signals, explanations, folder: Path, progress: bool = True) -> list[Path]:
    """One PNG per signal in ``folder`` (created), named after it as ``plot`` and
    ``features --plot`` name theirs: its SES with the lines the diagnoser read."""
    import sys

    import numpy as np
    from tqdm import tqdm

    from ..diagnose import plot_explanation
    from ..signalio import atomic_write
    from ._output import figure_writer

    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for sig, why in tqdm(list(zip(signals, explanations, strict=True)), desc="plot",
                         unit="figure", disable=not progress, leave=False, file=sys.stderr):
        path = folder / f"{sig.name}.png"
        ax = plot_explanation(np.asarray(sig.x, dtype=np.float64), sig.fs, why)
        atomic_write(path, figure_writer(ax.figure, path))
        written.append(path)
    return written
