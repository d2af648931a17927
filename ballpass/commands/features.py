"""``ballpass features INPUT...``: a feature table for signal files, CWRU .mat files or datasets."""

from __future__ import annotations

import argparse
import math
import numbers
import os
from dataclasses import dataclass, field
from pathlib import Path

EXAMPLE = """\
examples:
  ballpass simulate --fault outer --out outer.npz && ballpass features outer.npz
  ballpass features 12k_DE_IR007_0.mat 12k_DE_OR007@6_0.mat --segment 1 --out cwru.csv
  ballpass features Normal_0_48k.mat --plot figs/      # fs 48 kHz from the file name
  ballpass features out/quick --out quick_features.parquet
  ballpass features recordings.csv --out table.csv      # a manifest of recordings
  ballpass features rec.wav --rpm 1797 --bearing 6205   # a plain recording

inputs:
  .npz/.csv/.parquet  signal files written by `ballpass simulate` (one row per channel;
                      --bearing/--rpm default to the file's metadata)
  .csv/.npy/.wav      a recording in a plain format: a CSV column of numbers (with or
                      without header; --column NAME when there are several), a NumPy
                      array (n_samples,) or (n_channels, n_samples), a WAV file (its own
                      rate; integer PCM in fractions of full scale). Give --fs (not for
                      .wav), --rpm and --bearing.
  .mat                CWRU Bearing Data Center or MFPT files (told apart by content).
                      Values are stored in g and are converted to m/s^2 (x 9.80665).
                      CWRU: fs comes from the file name or record number: 12k_* files
                      are 12 kHz, 48k_* files AND the normal baseline (Normal_*, records
                      97-100) are 48 kHz -- not 12 kHz; pass --fs when neither tells. rpm
                      comes from the file, else from the motor load (rpm_source says
                      which); the bearing defaults to the rig's (DE: 6205, FE: 6203).
                      MFPT: fs, rpm and load from the file's `bearing` struct; bearing
                      MFPT-NICE. Any other .mat file: --fs, and --variable NAME
                      unless the file holds one variable.
  MANIFEST            a .csv/.parquet table listing recordings of any rig, one row each:
                      path (relative to the table's folder), fs, rpm, bearing; optional
                      label, variable, column, channel, group, load (docs/datasets.md).
                      Rows whose file cannot be read are skipped with a warning.
  DIR                 a dataset folder with _manifest.json (`ballpass generate`), or a
                      folder of .mat recordings, each read as alone (a logger's with --fs;
                      unreadable ones skipped with a warning)

columns: source, channel, segment, start_s, fs, bearing, rpm, label (when known), the
demodulation band chosen by the kurtogram (band_lo_hz, band_hi_hz, kurtogram_sk), the
statistical indicators, and the fault-band SES levels in dB (bpfo_1 ... bpfi_3_usb)."""

#: Columns copied from a dataset's metadata when present.
_DATASET_COLUMNS = (
    "label",
    "group",
    "run_id",
    "sensor",
    "segment",
    "start_s",
    "fault_width_mm",
    "radial_load_n",
    "snr_db",
)


@dataclass
class Signal:
    """One signal to analyse: samples (m/s^2), its rate and what is known about it."""

    name: str
    x: object  # ndarray (n_samples,)
    fs: float
    bearing: object = None  # catalogue name or Bearing
    rpm: float | None = None
    columns: dict = field(default_factory=dict)


def add_input_arguments(p: argparse.ArgumentParser,
                        band_default: str = "chosen by the fast kurtogram") -> None:
    """Options shared by ``features``, ``plot`` and ``diagnose``: inputs and what they
    lack (``band_default`` says what ``--band`` defaults to)."""
    p.add_argument(
        "inputs",
        nargs="+",
        metavar="INPUT",
        help="recording (.csv/.npy/.wav/.mat, or .npz/.parquet from `ballpass simulate`), "
        "manifest table (.csv/.parquet with a path column) listing recordings, folder of "
        ".mat recordings (CWRU/MFPT; any other with --fs), or dataset folder",
    )
    p.add_argument(
        "--fs",
        type=float,
        default=None,
        help="sampling rate, Hz, of files that do not state it (plain .csv, .npy, a .mat "
        "--variable; CWRU .mat files whose name does not); must agree with a rate the file "
        "states (.wav, ballpass files, MFPT)",
    )
    p.add_argument(
        "--column",
        default=None,
        metavar="NAME",
        help="the signal's column in a plain .csv file with several numeric columns (a "
        "header name, or an index from 0 when the file has no header)",
    )
    p.add_argument(
        "--variable",
        default=None,
        metavar="NAME",
        help="the signal's variable in a .mat file that is not a CWRU or MFPT recording "
        "(default: its only variable)",
    )
    p.add_argument(
        "--bearing", default=None, help="bearing for the fault frequencies (default: from the file)"
    )
    p.add_argument(
        "--rpm", type=float, default=None, help="shaft speed, rpm (default: from the file)"
    )
    p.add_argument(
        "--channel",
        default="DE",
        choices=["DE", "FE", "BA"],
        help="accelerometer of .mat files (default DE)",
    )
    p.add_argument(
        "--band",
        type=float,
        nargs=2,
        default=None,
        metavar=("LO", "HI"),
        help=f"demodulation band, Hz (default: {band_default})",
    )
    p.add_argument(
        "--segment",
        type=float,
        default=None,
        metavar="SECONDS",
        help="cut each signal into segments of this length, one row each",
    )


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register ``features`` on the ``ballpass`` command."""
    p = subparsers.add_parser(
        "features",
        help="feature table (indicators, kurtogram band, fault-band levels) of signals",
        description="Compute statistical indicators, the kurtogram demodulation band and "
        "the squared-envelope-spectrum levels at the bearing's fault frequencies for every "
        "signal of the inputs, and write them as a table.",
        epilog=EXAMPLE,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    add_input_arguments(p)
    p.add_argument(
        "--out",
        "-o",
        default=None,
        metavar="TABLE",
        help="write the table to TABLE.csv or TABLE.parquet (default: CSV on stdout)",
    )
    p.add_argument(
        "--plot",
        default=None,
        metavar="DIR",
        help="also draw one overview figure (PNG) per signal into DIR",
    )
    add_quiet_argument(p)
    p.set_defaults(func=run)
    return p


def is_known(value) -> bool:
    """True unless ``value`` is missing: None or NaN (a bearing or speed an input lacks)."""
    return value is not None and not (isinstance(value, float) and math.isnan(value))


#: Columns of a recording's metadata copied into the feature table (when it has them).
_RECORDING_COLUMNS = ("channel", "label", "group", "manifest_row", "load", "fault_width_mm",
                      "fault_angle_deg", "load_hp", "load_lbs", "rpm_source", "rpm_mismatch")


def _from_recordings(path: Path, args) -> list[Signal]:
    """The signals of a recording file, a folder of .mat recordings or a manifest."""
    from collections import Counter

    from ..datasets.manifest import read_recordings

    found = read_recordings(path, fs=args.fs, column=getattr(args, "column", None),
                            variable=getattr(args, "variable", None), channel=args.channel)
    per_file = Counter(str(p) for p, _ in found)
    names = []
    for file, rec in found:  # CWRU/MFPT and multi-channel files name their channel
        named = rec.info.get("dataset") in ("cwru", "mfpt") or per_file[str(file)] > 1
        names.append(f"{rec.name}_{rec.channel}" if named else rec.name)
    repeated = Counter(names)
    signals = []
    for name, (file, rec) in zip(names, found, strict=True):
        meta = rec.columns()
        if repeated[name] > 1 and "manifest_row" in meta:  # one file on several rows
            name = f"{name}_row{meta['manifest_row']}"
        columns = {k: meta[k] for k in _RECORDING_COLUMNS
                   if k in meta and not (k == "label" and meta[k] == "unknown")}
        # the recording's file, not the manifest's or the folder's name: as the manifest's
        # path column gives it (rig1/a.wav and rig2/a.wav are two), else its name
        columns["file"] = (os.path.relpath(file, path.parent) if "manifest_row" in meta
                           else Path(file).name)
        rpm = args.rpm if args.rpm is not None else rec.rpm
        signals.append(Signal(name, rec.accel, rec.fs, args.bearing or rec.bearing, rpm,
                              columns))
    return signals


def _from_dataset(folder: Path, args) -> list[Signal]:
    import importlib

    load = getattr(importlib.import_module("ballpass.datasets"), "load", None)
    if load is None:
        raise ValueError(
            f"{folder} is a dataset folder, but this build of ballpass has no "
            "ballpass.datasets.load to read it"
        )
    X, meta = load(folder)
    if "fs" not in meta.columns:
        raise ValueError(f"{folder}: the dataset metadata has no 'fs' column")
    signals = []
    for i, row in enumerate(meta.to_dict("records")):
        columns = {k: row[k] for k in _DATASET_COLUMNS if k in row}
        rpm = args.rpm if args.rpm is not None else row.get("rpm")
        signals.append(
            Signal(
                f"{folder.name}_{i:06d}",
                X[i],
                float(row["fs"]),
                args.bearing or row.get("bearing"),
                rpm,
                columns,
            )
        )
    return signals


def load_inputs(args) -> list[Signal]:
    """Every signal of ``args.inputs`` (segmented with ``--segment``), in input order."""
    signals = load_records(args)
    return signals if args.segment is None else segment_signals(signals, args.segment)


def load_records(args) -> list[Signal]:
    """Every signal of ``args.inputs``, whole, in input order."""
    if args.rpm is not None and not (math.isfinite(args.rpm) and args.rpm > 0):
        raise ValueError(f"--rpm must be a finite speed > 0 rev/min, got {args.rpm:g}")
    if args.fs is not None and not (math.isfinite(args.fs) and args.fs > 0):
        raise ValueError(f"--fs must be a finite sampling rate > 0 Hz, got {args.fs:g}")
    if args.bearing is not None:        # named as typed, and "" is not "from the file"
        from ballpass import Bearing

        try:
            Bearing.catalog(args.bearing)
        except (KeyError, ValueError) as exc:
            raise ValueError(f"--bearing: {str(exc).strip(chr(34))}") from None
    signals: list[Signal] = []
    for raw in args.inputs:
        path = Path(raw)
        before = len(signals)
        if path.is_dir() and any((path / name).is_file()
                                 for name in ("_manifest.json", "manifest.json")):
            signals += _from_dataset(path, args)
        elif not path.exists():
            raise FileNotFoundError(f"no such file or folder: {path}")
        else:
            signals += _from_recordings(path, args)
        check_analysable(signals[before:], path)
        for sig in signals[before:]:  # which file, and which record (split by it)
            sig.columns.setdefault("file", path.name)
            sig.columns.setdefault("group", sig.name)
    return signals


#: Fewest samples a signal needs for ``features``, ``plot`` and ``diagnose``: the fast
#: kurtogram estimates each band's kurtosis from at least about 64 samples of its
#: complex envelope (:func:`~ballpass.features.kurtogram._default_nlevel`); a shorter
#: signal has fewer even in its one, whole band.
MIN_SAMPLES = 64


def check_analysable(signals: list[Signal], source) -> None:
    """Refuse, naming ``source`` (the input file or folder), a signal with NaN or inf
    samples, fewer than :data:`MIN_SAMPLES` samples or a stated speed that is not > 0."""
    import numpy as np

    for sig in signals:
        where = f"{source}" + (f" ({sig.name})" if len(signals) > 1 else "")
        x = np.asarray(sig.x)
        if len(x) < MIN_SAMPLES:
            raise ValueError(f"{where}: {len(x)} samples, too short to analyse: features, "
                             f"plot and diagnose need at least {MIN_SAMPLES} samples "
                             f"({MIN_SAMPLES / sig.fs:.3g} s at {sig.fs:g} Hz)")
        if (isinstance(sig.rpm, numbers.Real) and is_known(sig.rpm)
                and not (math.isfinite(sig.rpm) and sig.rpm > 0)):
            raise ValueError(f"{where}: its rpm, {sig.rpm!r}, is not a speed > 0 rev/min; "
                             "give the right one with --rpm")
        bad = np.flatnonzero(~np.isfinite(x))
        if bad.size:
            raise ValueError(f"{where}: {bad.size} NaN or inf sample(s), the first at sample "
                             f"{bad[0]} ({bad[0] / sig.fs:.6g} s); clean or interpolate the "
                             "signal first")


def segment_signals(signals: list[Signal], seconds: float) -> list[Signal]:
    """Each signal cut into consecutive segments of ``seconds`` (``--segment``), named
    ``<name>_seg000`` ..., in order; a trailing part shorter than a segment is dropped."""
    import numpy as np

    from .._validation import check_segment

    out = []
    for sig in signals:
        length = check_segment(seconds, sig.fs, "--segment")
        n = len(sig.x) // length
        if n == 0:
            raise ValueError(f"{sig.name}: shorter than one --segment of {seconds} s")
        if length < MIN_SAMPLES:
            raise ValueError(f"--segment {seconds} s is {length} samples at {sig.fs:g} Hz; "
                             f"features, plot and diagnose need at least {MIN_SAMPLES}")
        for k, piece in enumerate(np.reshape(sig.x[: n * length], (n, length))):
            columns = sig.columns | {"segment": k, "start_s": k * length / sig.fs}
            out.append(
                Signal(f"{sig.name}_seg{k:03d}", piece, sig.fs, sig.bearing, sig.rpm, columns)
            )
    return out


def feature_rows(signals: list[Signal], band=None, progress: bool = True) -> list[dict]:
    """One dict of columns per signal: identity, kurtogram band, indicators, fault bands."""
    import sys

    import numpy as np
    from tqdm import tqdm

    from .. import features as F
    from ..features._validation import check_band

    rows = []
    for sig in tqdm(signals, desc="features", unit="signal", disable=not progress,
                    leave=False, file=sys.stderr):
        x = np.asarray(sig.x, dtype=np.float64)
        known = is_known(sig.bearing) and is_known(sig.rpm)
        analysis = None
        if band is None:  # kurtogram, band, SES and indicators in one pass
            analysis = F.envelope_analysis(x, sig.fs, rpm=float(sig.rpm) if known else None,
                                           bearing=sig.bearing if known else None)
            kg = analysis.kurtogram
        else:
            kg = F.fast_kurtogram(x, sig.fs)
        lo, hi = check_band(band, sig.fs) if band is not None else kg.best_band
        row = {
            "source": sig.name,
            **sig.columns,
            "fs": sig.fs,
            "n_samples": x.size,
            "bearing": getattr(sig.bearing, "name", sig.bearing),
            "rpm": sig.rpm,
            "band_lo_hz": lo,
            "band_hi_hz": hi,
            "kurtogram_sk": kg.best_kurtosis,
        }
        ind = analysis.indicators if analysis is not None else F.indicators(x)
        row.update({k: float(v) for k, v in ind.items()})
        if known:
            levels = (analysis.fault_bands if analysis is not None else
                      F.fault_band_features(x, sig.fs, sig.bearing, float(sig.rpm), band=(lo, hi)))
            row.update({k: float(v) for k, v in levels.items()})
        else:
            row.update(dict.fromkeys(F.fault_band_names(), np.nan))
        rows.append(row)
    return rows


def add_quiet_argument(p: argparse.ArgumentParser) -> None:
    """``--quiet``: no progress bar (it is shown on stderr only when that is a terminal)."""
    p.add_argument("--quiet", "-q", "--no-progress", dest="quiet", action="store_true",
                   help="hide the progress bar (shown on stderr when it is a terminal)")


def plot_signals(signals: list[Signal], folder: Path, band=None, names=None,
                 suffix: str = ".png", progress: bool = False) -> list[Path]:
    """One overview figure per signal in ``folder`` (each written atomically); the paths.

    ``names`` are the file stems (default: the signals' names); ``suffix`` the figure
    format (one of ``FIGURE_SUFFIXES``); ``progress`` shows a bar on stderr.
    """
    import sys

    from tqdm import tqdm

    from ..features.bands import as_bearing
    from ..plot import signal_overview
    from ..signalio import atomic_write
    from ._output import figure_writer

    paths = []
    stems = names or [s.name for s in signals]
    for sig, stem in tqdm(list(zip(signals, stems, strict=True)), desc="plot", unit="figure",
                          disable=not progress, leave=False, file=sys.stderr):
        known = is_known(sig.bearing) and is_known(sig.rpm)
        bearing = as_bearing(sig.bearing) if known else None
        shaft_hz = float(sig.rpm) / 60.0 if known else None
        label = sig.columns.get("label")
        title = " · ".join(
            str(p) for p in (sig.name, label, f"{sig.rpm:g} rpm" if known else None) if p
        )
        path = folder / f"{stem}{suffix}"
        fig = signal_overview(
            sig.x, sig.fs, bearing=bearing, shaft_hz=shaft_hz, band=band, title=title
        )
        atomic_write(path, figure_writer(fig, path))
        fig.clear()
        paths.append(path)
    return paths


def run(args) -> int:
    """Compute the feature table; write it (and figures); returns the exit code."""
    import sys

    import pandas as pd

    from ._output import TABLE_SUFFIXES, check_output_path, show_progress, write_table

    out = None if args.out is None else check_output_path(
        args.out, option="--out", suffixes=TABLE_SUFFIXES)
    plots = None if args.plot is None else check_output_path(
        args.plot, option="--plot", folder=True)
    signals = load_inputs(args)
    band = tuple(args.band) if args.band is not None else None
    frame = pd.DataFrame(feature_rows(signals, band, progress=show_progress(args)))
    if plots is not None:  # figures first: the table appears only once they all exist
        paths = plot_signals(signals, plots, band, progress=show_progress(args))
        print(f"{len(paths)} figure(s) -> {plots}", file=sys.stderr if out is None else None)
    if out is None:
        frame.to_csv(sys.stdout, index=False)
    else:
        write_table(frame, out)
        print(f"{len(frame)} signal(s) x {frame.shape[1]} columns -> {out}")
    return 0
