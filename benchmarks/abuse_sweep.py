"""Adversarial sweep: bad arguments, tampered datasets, corrupted files, interrupts and
bombs thrown at the public API and the CLI, each case classified clean or not.

Eight kinds, generated programmatically (every bad value of every checked argument of
the public functions and CLI options; every tampering of a dataset manifest; byte flips
at many offsets of every signal format; Ctrl-C and SIGTERM at many moments of every
long command; ...):

* **security** - a manifest naming files outside its folder (``..``, absolute paths,
  symlinks): a canary file beside the folder must stay untouched and nothing outside
  the folder may change;
* **manifest** - duplicated, missing, altered entries, unknown versions, truncated or
  non-JSON manifests, stray and missing shards: refused naming the manifest or shard,
  or read exactly as the untampered dataset;
* **corrupted** - signal files and shards with flipped bytes, truncated, NaN, too short:
  refused naming the file, or read exactly as the original;
* **interrupt** - SIGINT or SIGTERM during a command: exit 130, one line, no traceback,
  nothing half-written;
* **bomb** - sizes that would ask for gigabytes or hours: refused (or done) within the
  time budget, never a MemoryError;
* **substitution** - a model that cannot represent the scene, options it would ignore:
  refused naming what is missing;
* **scale** - signals scaled by 1e-300 .. 1e300: scale-free results unchanged, scaled
  ones finite where the float range allows;
* **message** - bad values of every argument and CLI option: a ValueError/TypeError
  (CLI: exit 2) with one line naming the argument as the user typed it.

Clean means: a ValueError or TypeError (CLI: exit code 2, or 130 when interrupted) whose
message is one line naming the argument or file, within the case's time budget, no
traceback on a CLI path, nothing outside the case's folder touched -- or, where the
input is harmless after all (a flipped byte in padding), a result identical to the
untampered one. Most cases call the API or ``ballpass.cli.main`` in this process; a few
interrupt cases run ``python -m ballpass`` where the signal to a separate process is the
point.

    PYTHONPATH=$PWD nice -n 10 python benchmarks/abuse_sweep.py     # ~10 min on 2 cores

Run it in the foreground: a shell starts a background job (``cmd &`` without job
control) with SIGINT ignored, the interrupt cases' children inherit that, and they then
count as not clean (31 of them did so in one such run).

Writes ``docs/results/abuse_sweep.md`` (table per kind and the failures) and
``docs/results/abuse_sweep.png``.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import warnings
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from _paths import RESULTS_DIR

ROOT = Path(__file__).resolve().parent.parent
KINDS = ("security", "manifest", "corrupted", "interrupt", "bomb", "substitution", "scale",
         "message")
FS = 12_000.0
X = np.random.default_rng(0).standard_normal(24_000)
#: a run that refuses should do so before any work: well under a second; 3 s leaves a
#: loaded machine room (the bombs this sweep found took minutes)
BUDGET_S = 3.0


@dataclass
class Case:
    kind: str
    name: str
    run: Callable[[], str | None]   # None when clean, else what went wrong


class Hang(BaseException):
    """Raised by the alarm when a case exceeds its budget."""


@contextlib.contextmanager
def budget(seconds: float):
    def fire(signum, frame):
        raise Hang(f"still running after {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, fire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def _one_line(text: str) -> bool:
    return "\n" not in text.strip() and "Traceback" not in text


def refuses(call, names, seconds: float = BUDGET_S, errors=(ValueError, TypeError)):
    """A check: ``call()`` raises one of ``errors`` within ``seconds`` with a one-line
    message naming one of ``names``."""
    names = (names,) if isinstance(names, str) else tuple(names)

    def check():
        try:
            with budget(seconds), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                call()
        except errors as exc:
            msg = str(exc)
            if not _one_line(msg):
                return f"message on several lines: {msg[:120]!r}"
            if not any(n.lower() in msg.lower() for n in names):
                return f"message does not name {names[0]!r}: {msg[:160]!r}"
            return None
        except Hang as exc:
            return f"hang: {exc}"
        except MemoryError:
            return "MemoryError"
        except Exception as exc:  # noqa: BLE001 - what the sweep is looking for
            return f"{type(exc).__name__}: {str(exc)[:160]!r}"
        return "accepted"
    return check


def completes(call, ok=lambda r: True, seconds: float = BUDGET_S):
    """A check: ``call()`` either refuses cleanly (ValueError/TypeError, one line) or
    returns a result ``ok`` accepts, within ``seconds``; never a MemoryError or hang."""
    def check():
        try:
            with budget(seconds), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                result = call()
        except (ValueError, TypeError) as exc:
            return None if _one_line(str(exc)) else f"message on several lines: {exc!s:.120}"
        except Hang as exc:
            return f"hang: {exc}"
        except MemoryError:
            return "MemoryError"
        except Exception as exc:  # noqa: BLE001
            return f"{type(exc).__name__}: {str(exc)[:160]!r}"
        return None if ok(result) else "wrong result"
    return check


def cli(argv, cwd: Path, seconds: float = 20.0):
    """``ballpass.cli.main(argv)`` in ``cwd``: (exit code or exception text, stdout,
    stderr)."""
    from ballpass.cli import main

    out, err = io.StringIO(), io.StringIO()
    old = Path.cwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), \
                budget(seconds), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                code = main([str(a) for a in argv])
            except SystemExit as exc:               # argparse
                code = exc.code
    except Hang as exc:
        code = f"hang: {exc}"
    except BaseException as exc:  # noqa: BLE001 - a traceback on a CLI path
        code = f"traceback: {type(exc).__name__}: {str(exc)[:120]}"
    finally:
        os.chdir(old)
    return code, out.getvalue(), err.getvalue()


def cli_refuses(argv, names, cwd: Path, seconds: float = 20.0, value: str | None = None):
    """A check: the CLI exits 2 with one error line naming one of ``names`` (or quoting
    the ``value`` typed)."""
    names = (names,) if isinstance(names, str) else tuple(names)

    def check():
        code, _, err = cli(argv, cwd, seconds)
        lines = [ln for ln in err.strip().splitlines() if "warning:" not in ln]
        if code != 2:
            return f"exit {code!r}: {err.strip()[-160:]!r}"
        if lines and lines[0].startswith("usage:") and all(
                ln.startswith(" ") for ln in lines[1:-1]):
            lines = lines[-1:]                       # argparse's usage, then its one error
        if len(lines) != 1 or "Traceback" in err:
            return f"{len(lines)} error lines: {err[-160:]!r}"
        # the option as typed, its name as a word ("fs must be ..."), or the value typed
        # in quotes ("unknown bearing 'nope'")
        words = [re.escape(n) for n in names] + [
            r"\b" + re.escape(n.lstrip("-")) + r"\b(?!_)" for n in names]
        if value is not None:
            words.append(re.escape(repr(value)))
            if Path(value).suffix in (".npz", ".csv", ".parquet", ".mat", ".toml"):
                words.append(re.escape(value))      # a file named as typed
        if not any(re.search(w, lines[0], re.I) for w in words):
            return f"does not name {names[0]!r}: {lines[0][:160]!r}"
        return None
    return check


def snapshot(folder: Path) -> dict:
    """Every file under ``folder`` (symlinks not followed) with its size and mtime."""
    out = {}
    for p in folder.rglob("*"):
        with contextlib.suppress(OSError):
            st = p.lstat()
            out[str(p)] = (st.st_size, st.st_mtime_ns)
    return out


# ----------------------------------------------------------------------------- fixtures
GRID = {"dataset": {"duration_s": 0.05, "fs": 12000, "seed": 3, "shard_size": 1,
                    "model": "impulse"},
        "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"],
                 "rpm": [1797], "resonance_hz": [3000]}}

GRID_TOML = ('[dataset]\nduration_s = 0.05\nfs = 12000\nseed = 3\nshard_size = 1\n'
             'model = "impulse"\n[grid]\nbearing = ["6205"]\n'
             'fault = ["healthy", "outer", "inner"]\nrpm = [1797]\nresonance_hz = [3000]\n')


class World:
    """Shared inputs: a reference dataset, signal files of each format, a scratch area."""

    def __init__(self, base: Path):
        import ballpass as bp
        from ballpass.signalio import write_signal

        self.base = base
        self.ref_ds = base / "ref" / "ds"
        bp.datasets.generate(GRID, self.ref_ds, progress=False)
        self.ref_rows = bp.datasets.load(self.ref_ds)
        self.sigs = {}
        for ext in ("npz", "parquet", "csv"):
            path = base / "ref" / f"sig.{ext}"
            write_signal(path, X[:6000], FS, meta={"bearing": "6205", "rpm": 1797.0})
            self.sigs[ext] = path
        mat = ROOT / "tests" / "data" / "cwru_mat"
        self.mat = next(iter(sorted(mat.glob("*.mat"))), None)
        self.n = 0

    def scratch(self) -> Path:
        self.n += 1
        d = self.base / f"case{self.n:05d}"
        d.mkdir()
        return d

    def dataset_copy(self) -> tuple[Path, Path, Path]:
        """A fresh copy of the reference dataset in a scratch folder with a canary file
        beside it: (folder, dataset, canary)."""
        d = self.scratch()
        ds = d / "ds"
        shutil.copytree(self.ref_ds, ds)
        canary = d / "canary.parquet"
        canary.write_bytes(b"canary: must survive\n")
        return d, ds, canary


def same_rows(a, b) -> bool:
    (sa, ma), (sb, mb) = a, b
    return sa.shape == sb.shape and np.array_equal(sa, sb) and len(ma) == len(mb)


# ----------------------------------------------------------------- datasets: tampering
def _edit_manifest(ds: Path, change) -> None:
    path = ds / "_manifest.json"
    manifest = json.loads(path.read_text())
    result = change(manifest, ds)
    if isinstance(result, (bytes, str)):               # a replacement text
        path.write_bytes(result if isinstance(result, bytes) else result.encode())
    else:
        path.write_text(json.dumps(manifest))


def _dataset_op(world: World, op: str, ds: Path, cwd: Path, partial: bool) -> str | None:
    """Run ``op`` on the tampered ``ds``: None when it refused cleanly or its result is
    that of the untampered dataset."""
    import ballpass as bp

    if op.startswith("cli "):
        argv = {"cli info": ["info", ds],
                "cli generate": ["generate", ds.parent / "grid.toml", "--out", ds,
                                 "--quiet"]}[op]
        if op == "cli generate":
            (ds.parent / "grid.toml").write_text(GRID_TOML)
        code, _, err = cli(argv, cwd)
        if code == 0:
            return None if op == "cli info" or same_rows(bp.datasets.load(ds),
                                                         world.ref_rows) else "wrong rows"
        lines = err.strip().splitlines()
        if code == 2 and len(lines) == 1 and "Traceback" not in err:
            return None
        return f"exit {code!r}: {err.strip()[-160:]!r}"
    calls = {
        "load": lambda: bp.datasets.load(ds),
        "info": lambda: bp.datasets.info(ds),
        "dry_run": lambda: bp.datasets.dry_run(GRID, out_dir=ds),
        "generate": lambda: bp.datasets.generate(GRID, ds, progress=False),
    }
    oks = {
        "load": lambda r: same_rows(r, world.ref_rows) or (partial and len(r[1]) < 3),
        "info": lambda r: (r["n_rows"] == 3 and r["shards_complete"] == 3) or (
            partial and r["shards_complete"] < 3),
        "dry_run": lambda r: True,
        "generate": lambda r: same_rows(bp.datasets.load(ds), world.ref_rows),
    }
    return completes(calls[op], oks[op], seconds=30.0)()


def dataset_case(world: World, kind: str, name: str, tamper, op: str,
                 partial: bool = False) -> Case:
    """A case: ``tamper(ds, folder, canary)`` on a fresh copy of the reference dataset,
    then ``op``; ``partial``: the tampering legitimately hides rows (a shard marked
    incomplete is one an interrupted run may have left), so fewer rows are fine."""
    def run():
        folder, ds, canary = world.dataset_copy()
        tamper(ds, folder, canary)
        inside = (str(ds), str(ds.resolve()))     # the folder (or a symlink's target)

        def outside():
            return {k: v for k, v in snapshot(folder).items()
                    if not any(k == d or k.startswith(d + os.sep) for d in inside)}
        before = outside()
        problem = _dataset_op(world, op, ds, folder, partial)
        after = outside()
        if canary.read_bytes() != b"canary: must survive\n":
            return "canary outside the folder changed"
        changed = {k for k in before.keys() | after.keys()
                   if before.get(k) != after.get(k)} - {str(folder / "grid.toml")}
        if changed:
            return f"outside the folder changed: {sorted(changed)[:2]}"
        return problem
    return Case(kind, f"{name} / {op}", run)


def security_cases(world: World) -> list[Case]:
    def entry(value):
        def tamper(ds, folder, canary):
            def change(m, ds):
                m["shards"][0]["file"] = value(canary) if callable(value) else value
                m["shards"][0]["complete"] = True
            _edit_manifest(ds, change)
        return tamper

    def symlink(ds, folder, canary):
        (ds / "part-00000.parquet").unlink()
        (ds / "part-00000.parquet").symlink_to(canary)

    def symlink_dir(ds, folder, canary):
        shutil.rmtree(ds)
        shutil.copytree(world.ref_ds, folder / "real")
        ds.symlink_to(folder / "real")

    def manifest_symlink(ds, folder, canary):
        (ds / "_manifest.json").unlink()
        (ds / "_manifest.json").symlink_to(canary)

    variants = {
        "file ../canary": entry("../canary.parquet"),
        "file ../../canary": entry(lambda c: "../" + os.path.relpath(c, c.parent.parent)),
        "file absolute canary": entry(lambda c: str(c)),
        "file sub/../../canary": entry("x/../../canary.parquet"),
        "file shard/../../canary": entry("part-00000.parquet/../../canary.parquet"),
        "file ~/canary": entry("~/canary.parquet"),
        "file empty": entry(""),
        "file .": entry("."),
        "file ..": entry(".."),
        "file NUL": entry("part-00000.parquet\x00../canary"),
        "file URL": entry(lambda c: "file://" + str(c)),
        "file backslashes": entry("..\\canary.parquet"),
        "file number": entry(7),
        "file list": entry(["../canary.parquet"]),
        "file other shard": entry("part-00001.parquet"),
        "file manifest": entry("_manifest.json"),
        "shard symlink to canary": symlink,
        "manifest symlink to canary": manifest_symlink,
        "dataset folder a symlink": symlink_dir,
    }
    ops = ("load", "info", "dry_run", "generate", "cli info", "cli generate")
    return [dataset_case(world, "security", n, t, op) for n, t in variants.items()
            for op in ops]


def manifest_cases(world: World) -> list[Case]:
    def change(fn):
        return lambda ds, folder, canary: _edit_manifest(ds, fn)

    def setter(path, value):
        def fn(m, ds):
            node = m
            for key in path[:-1]:
                node = node[key]
            node[path[-1]] = value
        return change(fn)

    def deleter(key):
        return change(lambda m, ds: m.pop(key))

    def text(t):
        return lambda ds, folder, canary: (ds / "_manifest.json").write_bytes(
            t if isinstance(t, bytes) else t.encode())

    def truncated(fraction):
        def tamper(ds, folder, canary):
            b = (ds / "_manifest.json").read_bytes()
            (ds / "_manifest.json").write_bytes(b[:int(len(b) * fraction)])
        return tamper

    def stray(ds, folder, canary):
        shutil.copy(ds / "part-00000.parquet", ds / "part-00003.parquet")

    def missing(ds, folder, canary):
        (ds / "part-00001.parquet").unlink()

    def renamed(ds, folder, canary):
        (ds / "part-00001.parquet").rename(ds / "part-00009.parquet")

    def swapped(ds, folder, canary):
        a, b = ds / "part-00000.parquet", ds / "part-00001.parquet"
        tmp = ds / "swap"
        a.rename(tmp)
        b.rename(a)
        tmp.rename(b)

    variants = {
        "shard listed twice": change(lambda m, ds: m["shards"].append(dict(m["shards"][0]))),
        "shards empty": setter(("shards",), []),
        "shards not a list": setter(("shards",), {"a": 1}),
        "shards null": setter(("shards",), None),
        "shard entry a string": change(lambda m, ds: m["shards"].__setitem__(0, "x")),
        "shard index repeated": setter(("shards", 1, "index"), 0),
        "shard index negative": setter(("shards", 1, "index"), -1),
        "shard index huge": setter(("shards", 1, "index"), 10**18),
        "shard n_rows +1": setter(("shards", 0, "n_rows"), 2),
        "shard n_rows 0": setter(("shards", 0, "n_rows"), 0),
        "shard n_rows -5": setter(("shards", 0, "n_rows"), -5),
        "shard n_rows text": setter(("shards", 0, "n_rows"), "1"),
        "shard sha256 altered": setter(("shards", 0, "sha256"), "0" * 64),
        "shard bytes altered": setter(("shards", 0, "bytes"), 1),
        "shard runs altered": setter(("shards", 0, "runs"), [5, 9]),
        "shard complete false": setter(("shards", 0, "complete"), False),
        "n_rows 9": setter(("n_rows",), 9),
        "n_rows -1": setter(("n_rows",), -1),
        "n_rows text": setter(("n_rows",), "3"),
        "n_rows 1e300": setter(("n_rows",), 1e300),
        "n_runs 99": setter(("n_runs",), 99),
        "format_version 99": setter(("format_version",), 99),
        "format_version 0": setter(("format_version",), 0),
        "format_version text": setter(("format_version",), "2"),
        "format_version null": setter(("format_version",), None),
        "format other": setter(("format",), "something-else"),
        "fs 0": setter(("fs",), 0),
        "fs negative": setter(("fs",), -12000.0),
        "fs text": setter(("fs",), "fast"),
        "signal_length 5": setter(("signal_length",), 5),
        "signal_length huge": setter(("signal_length",), 10**15),
        "status garbage": setter(("status",), "weird"),
        "root_seed text": setter(("root_seed",), "seed"),
        "grid altered": setter(("grid", "grid", "rpm"), [900.0]),
        "grid garbage": setter(("grid",), "x"),
        "fingerprint altered": setter(("fingerprint", "simulator_sources"), "0" * 64),
        **{f"key {k} deleted": deleter(k) for k in
           ("format", "format_version", "shards", "n_rows", "fs", "signal_length", "grid",
            "status", "n_runs", "root_seed", "fingerprint")},
        "empty file": text(b""),
        "not JSON": text("this is not json"),
        "binary": text(bytes(range(256))),
        "JSON list": text("[1, 2, 3]"),
        "JSON null": text("null"),
        "deep nesting": text("[" * 100_000 + "]" * 100_000),
        "number 1e999": text('{"format": "ballpass-dataset", "format_version": 1e999}'),
        **{f"truncated at {f:.0%}": truncated(f) for f in (0.1, 0.3, 0.5, 0.7, 0.9, 0.99)},
        "stray extra shard": stray,
        "shard file missing": missing,
        "shard file renamed": renamed,
        "shard files swapped": swapped,
    }
    ops = ("load", "info", "generate", "cli info")
    return [dataset_case(world, "manifest", n, t, op, partial=n == "shard complete false")
            for n, t in variants.items() for op in ops]


# ------------------------------------------------------------------- corrupted files
def _features_of(path: Path, cwd: Path):
    return cli(["features", path, "--quiet"], cwd)


def corrupted_cases(world: World) -> list[Case]:
    from ballpass.signalio import read_signal

    cases = []

    def file_case(name, src: Path, mutate):
        def run():
            d = world.scratch()
            path = d / src.name
            data = bytearray(src.read_bytes())
            result = mutate(data)
            path.write_bytes(bytes(result if result is not None else data))
            code, out, err = _features_of(path, d)
            if code == 0:
                # accepted: only if the data read is the original's
                try:
                    a, b = read_signal(path), read_signal(src)
                except Exception as exc:  # noqa: BLE001
                    return f"features ran, read_signal fails: {exc!s:.100}"
                if a.accel.shape == b.accel.shape and np.array_equal(a.accel, b.accel) \
                        and a.fs == b.fs:
                    return None
                return "garbage accepted: the data read differs from the file's"
            lines = err.strip().splitlines()
            if code != 2 or len(lines) != 1 or "Traceback" in err:
                return f"exit {code!r}: {err.strip()[-160:]!r}"
            if path.name not in lines[0]:
                return f"does not name the file: {lines[0][:160]!r}"
            return None
        cases.append(Case("corrupted", name, run))

    sources = dict(world.sigs)
    if world.mat is not None:
        sources["mat"] = world.mat
    for ext, src in sources.items():
        size = src.stat().st_size
        for k in range(40):
            offset = int(size * (k + 0.5) / 40)

            def flip(data, offset=offset):
                data[offset] ^= 0x5A
            file_case(f"{ext}: byte {offset} of {size} flipped", src, flip)
        for f in (0.0, 0.05, 0.5, 0.95):
            file_case(f"{ext}: truncated at {f:.0%}", src,
                      lambda data, f=f: data[:int(len(data) * f)])
        file_case(f"{ext}: text instead", src, lambda data: b"hello, world\n" * 10)
    from ballpass.signalio import write_signal

    def written(name, accel, ext):
        def run():
            d = world.scratch()
            path = d / f"sig.{ext}"
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    write_signal(path, accel, FS, meta={"bearing": "6205", "rpm": 1797.0})
                except (ValueError, TypeError):
                    return None                      # refused when written: clean
            for command in ("features", "plot", "diagnose"):
                code, _, err = cli([command, path, "--quiet", *(
                    ["--out", d / "figs"] if command == "plot" else [])], d)
                lines = err.strip().splitlines()
                if code != 2 or len(lines) != 1 or path.name not in lines[0]:
                    return f"{command}: exit {code!r}: {err.strip()[-160:]!r}"
            return None
        cases.append(Case("corrupted", f"{ext}: {name}", run))

    bad = X[:6000].copy()
    bad[100] = np.nan
    inf = X[:6000].copy()
    inf[2000] = np.inf
    for label, accel in {"a NaN": bad, "an inf": inf, "5 samples": X[:5],
                         "1 sample": X[:1]}.items():
        for ext in ("npz", "parquet", "csv"):
            written(f"signal with {label}", accel, ext)
    # dataset shards with flipped bytes
    shard = world.ref_ds / "part-00001.parquet"
    size = shard.stat().st_size
    for k in range(30):
        offset = int(size * (k + 0.5) / 30)

        def flip_shard(ds, folder, canary, offset=offset):
            p = ds / "part-00001.parquet"
            data = bytearray(p.read_bytes())
            data[offset] ^= 0x5A
            p.write_bytes(bytes(data))
        cases.append(dataset_case(world, "corrupted", f"shard byte {offset} flipped",
                                  flip_shard, "load"))
    return cases


# ------------------------------------------------------------------------- interrupts
def _interrupt_commands(world: World, d: Path) -> dict:
    from ballpass.signalio import write_signal

    sig = d / "sig.npz"
    write_signal(sig, np.tile(X, 4), FS, meta={"bearing": "6205", "rpm": 1797.0})
    (d / "grid.toml").write_text(GRID_TOML.replace('fault = ["healthy", "outer", "inner"]',
                                                   'fault = ["healthy", "outer", "inner"]\n'
                                                   'radial_load_n = [100, 200, 300, 400]'))
    return {
        "simulate sr5": ["simulate", "--duration", "2", "--out", "x.npz"],
        "simulate dopri5": ["simulate", "--duration", "1", "--solver", "dopri5",
                            "--out", "x.parquet"],
        "simulate impulse": ["simulate", "--duration", "5", "--model", "impulse",
                             "--out", "x.csv"],
        "generate": ["generate", "grid.toml", "--out", "ds", "--quiet"],
        "features": ["features", sig, "--out", "f.csv", "--plot", "figs"],
        "diagnose": ["diagnose", sig, "--out", "d.csv"],
        "plot": ["plot", sig, "--out", "p"],
        "bifurcation": ["bifurcation", "--parameter", "rpm", "--range", "500", "3000", "6",
                        "--duration", "0.3", "--fs", "12000", "--out", "b.csv"],
        "work-precision": ["work-precision", "--duration", "0.1", "--no-scipy",
                           "--csv", "w.csv"],
        "info": ["info", world.ref_ds],
    }


def interrupt_cases(world: World) -> list[Case]:
    cases = []
    names = list(_interrupt_commands(world, world.scratch()))
    for command in names:
        for sig in (signal.SIGINT, signal.SIGTERM):
            for delay in (0.02, 0.1, 0.3, 0.6, 1.0, 2.0):
                def run(command=command, sig=sig, delay=delay):
                    d = world.scratch()
                    argv = _interrupt_commands(world, d)[command]
                    timer = threading.Timer(delay, os.kill, (os.getpid(), sig))
                    timer.start()
                    try:
                        code, _, err = cli(argv, d, seconds=120.0)
                    finally:
                        timer.cancel()
                    time.sleep(0.05)  # a signal that fired late lands here, not in the next
                    left = [p.name for p in d.rglob("*") if ".tmp" in p.name]
                    if left:
                        return f"half-written files left: {left[:3]}"
                    if code == 0:
                        return None                          # finished first
                    lines = err.strip().splitlines()
                    if code == 130 and len(lines) == 1 and "interrupted" in lines[0]:
                        return None
                    return f"exit {code!r}: {err.strip()[-200:]!r}"
                cases.append(Case("interrupt", f"{command}: {sig.name} after {delay} s", run))

    # the API: a KeyboardInterrupt inside bp.simulate leaves the process able to simulate
    import ballpass as bp

    scene = bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.05)

    for model in ("sr5", "sr4", "impulse", "rotor2"):
        for delay in (0.05, 0.3):
            def run(model=model, delay=delay):
                ref = bp.simulate(scene, model=model).accel
                timer = threading.Timer(delay, os.kill, (os.getpid(), signal.SIGINT))
                timer.start()
                try:
                    bp.simulate(scene.replace(duration_s=4.0), model=model)
                except KeyboardInterrupt:
                    pass
                finally:
                    timer.cancel()
                again = bp.simulate(scene, model=model).accel
                return None if np.array_equal(ref, again) else "differs after an interrupt"
            cases.append(Case("interrupt", f"bp.simulate {model}: Ctrl-C after {delay} s, "
                                           "then again", run))

    # separate processes, as a terminal or `kill` sends them
    for command, argv, group in (
            ("simulate", ["simulate", "--duration", "60", "--out", "x.npz"], False),
            ("generate --jobs 2", ["generate", "grid.toml", "--out", "ds", "--jobs", "2",
                                   "--quiet"], True)):
        for sig in (signal.SIGINT, signal.SIGTERM):
            def run(argv=argv, sig=sig, group=group, command=command):
                d = world.scratch()
                _interrupt_commands(world, d)
                proc = subprocess.Popen(
                    [sys.executable, "-m", "ballpass", *map(str, argv)], cwd=d,
                    stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                    env={**os.environ, "PYTHONPATH": str(ROOT)}, start_new_session=True,
                    preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
                try:
                    time.sleep(4.0)
                    if group and sig == signal.SIGINT:
                        os.killpg(proc.pid, sig)
                    else:
                        proc.send_signal(sig)
                    t0 = time.monotonic()
                    _, err = proc.communicate(timeout=30)
                    waited = time.monotonic() - t0
                except subprocess.TimeoutExpired:
                    return "still running 30 s after the signal"
                finally:
                    with contextlib.suppress(ProcessLookupError):
                        os.killpg(proc.pid, signal.SIGKILL)
                    proc.wait()
                lines = err.strip().splitlines()
                if proc.returncode == 0:
                    return None
                if proc.returncode == 130 and len(lines) == 1 and "interrupted" in lines[0]:
                    return None if waited < 10 else f"took {waited:.1f} s to stop"
                return f"exit {proc.returncode}: {err.strip()[-200:]!r}"
            cases.append(Case("interrupt", f"process {command}: {sig.name}", run))
    return cases


# ------------------------------------------------------------------------------ bombs
def bomb_cases(world: World) -> list[Case]:
    import ballpass as bp
    from ballpass import features as F
    from ballpass import plot as P

    x = X[:6000]
    calls = {}
    for fs in (1e9, 1e12, 1e15, 1e300):
        calls[f"fault_band_features fs={fs:g}"] = lambda fs=fs: F.fault_band_features(
            x, fs, "6205", 1797)
        calls[f"envelope_spectrum fs={fs:g}"] = lambda fs=fs: F.envelope_spectrum(x, fs)
    for h in (10**4, 10**6, 10**9, 10**12, 2**62):
        calls[f"fault_band_features harmonics={h}"] = lambda h=h: F.fault_band_features(
            x, FS, "6205", 1797, harmonics=h)
        calls[f"envelope_evidence harmonics={h}"] = lambda h=h: bp.diagnose.envelope_evidence(
            x, FS, "6205", 1797, harmonics=h)
    for b in (1e6, 1e9, 1e300):
        calls[f"fault_band_features background_hz={b:g}"] = lambda b=b: (
            F.fault_band_features(x, FS, "6205", 1797, background_hz=b))
    for n in (10**6, 10**8, 10**9, 10**12):
        calls[f"order_track samples_per_rev={n}"] = lambda n=n: F.order_track(
            x, FS, rpm=1797, samples_per_rev=n)
        calls[f"order_envelope_spectrum samples_per_rev={n}"] = lambda n=n: (
            F.order_envelope_spectrum(x, FS, rpm=1797, samples_per_rev=n))
    for n in (10**6, 10**9, 10**12):
        calls[f"spectral_kurtosis nperseg={n}"] = lambda n=n: F.spectral_kurtosis(
            x, FS, nperseg=n)
        calls[f"separate_discrete order={n}"] = lambda n=n: F.separate_discrete(
            x, FS, 1797, order=n)
        calls[f"separate_discrete nperseg={n}"] = lambda n=n: F.separate_discrete(
            x, FS, 1797, nperseg=n)
        calls[f"psd nperseg={n}"] = lambda n=n: P.psd(x, FS, nperseg=n)
        calls[f"spectrogram nperseg={n}"] = lambda n=n: P.spectrogram(x, FS, nperseg=n)
        calls[f"bandpass order={n}"] = lambda n=n: F.bandpass(x, FS, (1000, 3000), order=n)
        calls[f"pulses_per_rev={n}"] = lambda n=n: F.order_track(
            x, FS, tacho=np.sin(np.arange(6000) / 7.0), pulses_per_rev=n)
    for n in (30, 100, 10**6):
        calls[f"fast_kurtogram nlevel={n}"] = lambda n=n: F.fast_kurtogram(x, FS, nlevel=n)
    scene = bp.Scene("6205", duration_s=0.05, fs=12000.0, resonance_hz=3000.0)
    for key, values in {"duration_s": (1e5, 1e9, 1e300), "fs": (1e9, 1e12, 1e300)}.items():
        for v in values:
            calls[f"Scene {key}={v:g} simulate"] = lambda key=key, v=v: bp.simulate(
                scene.replace(**{key: v}))
            calls[f"Scene {key}={v:g} impulse"] = lambda key=key, v=v: bp.simulate(
                scene.replace(**{key: v}), model="impulse")
    for dt in (1e-12, 1e-15, 1e-300):
        calls[f"simulate dt={dt:g}"] = lambda dt=dt: bp.simulate(scene, solver="rk4", dt=dt)
    for rtol in (1e-14, 1e-16, 1e-300):
        calls[f"simulate rtol={rtol:g}"] = lambda rtol=rtol: bp.simulate(
            scene, solver="dopri5", rtol=rtol)
    for o in (10**4, 10**6, 10**9):
        calls[f"simulate oversample={o}"] = lambda o=o: bp.simulate(scene, oversample=o)
    calls["simulate 10000 sensors"] = lambda: bp.simulate(scene.replace(
        sensors=tuple(bp.Sensor(angle_deg=float(a)) for a in range(10_000))))
    many = tuple(bp.Fault("outer", angle_deg=float(a % 360)) for a in range(10**5))
    calls["Scene 10^5 faults"] = lambda: bp.simulate(scene.replace(fault=many))
    for key, value in {"repeats": 10**9, "shard_size": 10**12}.items():
        calls[f"grid {key}={value}"] = lambda key=key, value=value: bp.datasets.dry_run(
            {"dataset": {**GRID["dataset"], key: value}, "grid": GRID["grid"]})
    for n in (10**6, 10**7, 10**9):
        calls[f"grid rpm range of {n} points"] = lambda n=n: bp.datasets.read_grid(
            {"dataset": GRID["dataset"], "grid": {**GRID["grid"], "rpm": {
                "start": 600, "stop": 3000, "num": n}}})
    calls["grid 10^12 combinations"] = lambda: bp.datasets.dry_run(
        {"dataset": GRID["dataset"], "grid": {**GRID["grid"], **{
            k: {"start": 1, "stop": 2, "num": 10**4} for k in ("rpm", "radial_load_n",
                                                                "fault_width_mm")}}})
    for seg in (1e-9, 1e-6):
        calls[f"load_cwru segment_s={seg:g}"] = lambda seg=seg: bp.datasets.load_cwru(
            [world.mat], segment_s=seg)
    cases = [Case("bomb", name, completes(call)) for name, call in calls.items()]
    for argv, name in (
            (["bifurcation", "--parameter", "rpm", "--range", "500", "600", "1000000",
              "--out", "b.csv"], "bifurcation --range 500 600 1000000"),
            (["bifurcation", "--parameter", "rpm", "--range", "500", "600", "1e18",
              "--out", "b.csv"], "bifurcation --range 500 600 1e18"),
            (["bifurcation", "--parameter", "rpm", "--values",
              *map(str, range(500, 20_500)), "--out", "b.csv"],
             "bifurcation --values x20000"),
            (["simulate", "--duration", "1e7", "--out", "x.npz"], "simulate --duration 1e7"),
            (["simulate", "--fs", "1e12", "--out", "x.npz"], "simulate --fs 1e12"),
            (["simulate", "--dt", "1e-15", "--out", "x.npz"], "simulate --dt 1e-15"),
            (["simulate", "--sensors", *map(str, range(5000)), "--out", "x.npz"],
             "simulate 5000 sensors"),
            (["generate", "big.toml", "--out", "ds", "--dry-run"], "generate 10^12 rows"),
            (["features", "sig.npz", "--segment", "1e-9"], "features --segment 1e-9"),
            (["work-precision", "--repeats", "1000000000", "--csv", "w.csv"],
             "work-precision --repeats 1e9")):
        def run(argv=argv):
            d = world.scratch()
            from ballpass.signalio import write_signal

            write_signal(d / "sig.npz", X, FS, meta={"bearing": "6205", "rpm": 1797.0})
            (d / "big.toml").write_text(GRID_TOML.replace(
                    "rpm = [1797]", "rpm = {start = 600, stop = 3000, num = 1000000}\n"
                    "radial_load_n = {start = 100, stop = 900, num = 1000000}"))
            code, _, err = cli(argv, d, seconds=BUDGET_S + 2.0)
            lines = err.strip().splitlines()
            if code == 0 or (code == 2 and len(lines) == 1):    # refused, or cheap after all
                return None
            return f"exit {code!r}: {err.strip()[-160:]!r}"
        cases.append(Case("bomb", name, run))
    return cases


# ---------------------------------------------------------------------- substitutions
def substitution_cases(world: World) -> list[Case]:
    import ballpass as bp
    from ballpass import features as F

    base = bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.02)
    options = {
        "gears": dict(gears="tran-furch-cu"),
        "needs envelope": dict(needs=("envelope",)),
        "needs ball_dynamics": dict(needs=("ball_dynamics",)),
        "needs contact_forces": dict(needs=("contact_forces",)),
        "clearance": dict(clearance_um=20.0),
        "preload": dict(clearance_um=-5.0),
        "extra modes": dict(resonances=((9000.0, 0.03, 0.5),)),
        "waviness": dict(waviness=(bp.Waviness("outer", 10, 0.5),)),
        "needs ehl_film": dict(needs=("ehl_film",)),
        "speed ramp": dict(rpm=(600.0, 1800.0)),
        "pit fault": dict(fault=bp.Fault("outer", geometry="pit")),
        "intermittent ball": dict(fault=bp.Fault("ball", engagement=0.5)),
    }
    cases = []
    for model in ("impulse", "sr4", "sr5", "rotor2", "multibody", "gearbox"):
        for label, change in options.items():
            def run(model=model, change=change):
                try:
                    scene = base.replace(**change)
                except (ValueError, TypeError):
                    return None
                missing = bp.simulate.unrepresented(scene, model)
                check = refuses(lambda: bp.simulate(scene, model=model),
                                ["does not represent", "not represent", "cannot", "only"],
                                seconds=60.0)
                if missing:
                    return check()
                return completes(lambda: bp.simulate(scene, model=model), seconds=60.0)()
            cases.append(Case("substitution", f"{model} with {label}", run))
    scene = base
    bad = {
        "return_forces='yes'": (dict(return_forces="yes"), "return_forces"),
        "return_forces=1": (dict(return_forces=1), "return_forces"),
        "return_forces=None": (dict(return_forces=None), "return_forces"),
        "allow_unrepresented='no'": (dict(allow_unrepresented="no"), "allow_unrepresented"),
        "model='foo'": (dict(model="foo"), "model"),
        "model='SR5'": (dict(model="SR5"), "model"),
        "model=5": (dict(model=5), "model"),
        "solver='foo'": (dict(solver="foo"), "solver"),
        "solver='rk4' for impulse": (dict(model="impulse", solver="rk4"), "solver"),
        "dt with dopri5": (dict(solver="dopri5", dt=1e-6), "dt"),
        "rtol with rk4": (dict(solver="rk4", rtol=1e-6), "rtol"),
        "atol without rtol on rk4": (dict(solver="rk4", atol=1e-3), "atol"),
        "dt with impulse": (dict(model="impulse", dt=1e-6), "dt"),
        "params of another model": (dict(model="sr5", params=bp.simulate.Rotor2Parameters()),
                                    "params"),
        "params a dict": (dict(model="sr5", params={"contact_damping": 1.0}), "params"),
        "oversample=0": (dict(oversample=0), "oversample"),
        "oversample=2.5": (dict(oversample=2.5), "oversample"),
    }
    for label, (kw, name) in bad.items():
        cases.append(Case("substitution", f"simulate {label}",
                          refuses(lambda kw=kw: bp.simulate(scene, **kw), name, 60.0)))
    scenes = {
        "duration below one sample": (lambda: bp.Scene("6205", duration_s=1e-6), "duration_s"),
        "fault kind 'outter'": (lambda: bp.Fault("outter"), "kind"),
        "fault engagement 2": (lambda: bp.Fault("ball", engagement=2.0), "engagement"),
        "fault ramp_fraction 0.9": (lambda: bp.Fault("outer", ramp_fraction=0.9),
                                    "ramp_fraction"),
        "fault element 99": (lambda: bp.Scene("6205", fault=bp.Fault("outer", element=99)),
                             "element"),
        "fault edge 'soft'": (lambda: bp.Fault("outer", edge="soft"), "edge"),
        "fault geometry 'hole'": (lambda: bp.Fault("outer", geometry="hole"), "geometry"),
        "needs 'envelop'": (lambda: bp.Scene("6205", needs=("envelop",)), "envelop"),
        "sensor name clash": (lambda: bp.Scene("6205", sensors=(bp.Sensor(0, "a"),
                                                                bp.Sensor(90, "a"))),
                              "sensor"),
        "gears 'nope'": (lambda: bp.Scene("6205", gears="nope"), "gear"),
        "waviness on 'cage'": (lambda: bp.Waviness("cage", 10, 0.5), "cage"),
        "tolerance=2": (lambda: F.fault_band_features(X, FS, "6205", 1797, tolerance=2),
                        "tolerance"),
        "tolerance=-0.1": (lambda: F.fault_band_features(X, FS, "6205", 1797,
                                                         tolerance=-0.1), "tolerance"),
        "prewhiten='no'": (lambda: F.envelope(X, FS, prewhiten="no"), "prewhiten"),
        "squared='no'": (lambda: F.envelope_spectrum(X, FS, squared="no"), "squared"),
        "shaft_guard='no'": (lambda: F.fault_band_features(X, FS, "6205", 1797,
                                                           shaft_guard="no"), "shaft_guard"),
        "separate method 'foo'": (lambda: F.separate_discrete(X, FS, 1797, method="foo"),
                                  "method"),
        "window 'foo'": (lambda: F.envelope_spectrum(X, FS, window="foo"), "window"),
        "classifier 'foo'": (lambda: bp.diagnose.make_classifier("foo"), "foo"),
        "features 'foo'": (lambda: bp.diagnose.make_features("foo"), "foo"),
    }
    for label, (call, name) in scenes.items():
        cases.append(Case("substitution", label, refuses(call, name)))
    grids = {
        "model 'foo'": ({"model": "foo"}, {}, "foo"),
        "solver 'foo'": ({"solver": "foo"}, {}, "foo"),
        "dataset key 'duraton_s'": ({"duraton_s": 0.05}, {}, "duraton_s"),
        "grid key 'rmp'": ({}, {"rmp": [1797]}, "rmp"),
        "fault 'outter'": ({}, {"fault": ["outter"]}, "outter"),
        "bearing 'nope'": ({}, {"bearing": ["nope"]}, "nope"),
        "sensor 'nowhere'": ({}, {"sensor": ["nowhere"]}, "nowhere"),
        "rpm 'fast'": ({}, {"rpm": ["fast"]}, "rpm"),
        "rpm empty": ({}, {"rpm": []}, "rpm"),
        "repeats 0": ({"repeats": 0}, {}, "repeats"),
        "repeats 2.5": ({"repeats": 2.5}, {}, "repeats"),
        "shard_size 0": ({"shard_size": 0}, {}, "shard_size"),
        "duration_s -1": ({"duration_s": -1}, {}, "duration_s"),
        "fs 'fast'": ({"fs": "fast"}, {}, "fs"),
        "seed -1": ({"seed": -1}, {}, "seed"),
    }
    for label, (ds_change, grid_change, name) in grids.items():
        def call(ds_change=ds_change, grid_change=grid_change):
            grid = {"dataset": {**GRID["dataset"], **ds_change},
                    "grid": {**GRID["grid"], **grid_change}}
            return bp.datasets.read_grid(grid)
        cases.append(Case("substitution", f"grid {label}", refuses(call, name)))
    return cases


# ------------------------------------------------------------------------------ scale
def _numeric(result) -> dict:
    """The numeric arrays of a result (tuple, dict, dataclass), by name."""
    import dataclasses

    if isinstance(result, dict):
        items = result.items()
    elif dataclasses.is_dataclass(result):
        items = ((f.name, getattr(result, f.name)) for f in dataclasses.fields(result))
    elif isinstance(result, tuple):
        items = enumerate(result)
    else:
        items = [("", result)]
    out = {}
    for k, v in items:
        if isinstance(v, (dict, tuple)) or dataclasses.is_dataclass(v):
            out.update({f"{k}.{kk}": vv for kk, vv in _numeric(v).items()})
            continue
        with contextlib.suppress(TypeError, ValueError):
            a = np.asarray(v, dtype=float)
            out[str(k)] = a
    return out


def scale_cases(world: World) -> list[Case]:
    from ballpass import features as F

    rng = np.random.default_rng(5)
    t = np.arange(12_000) / FS
    sig = rng.standard_normal(12_000) + 3 * np.sin(2 * np.pi * 3000 * t) * (
        np.sin(2 * np.pi * 107 * t) > 0.95)
    healthy = rng.standard_normal(12_000)
    # name -> (call, {output: power of the scale it carries}; unlisted outputs: 0)
    funcs = {
        "indicators": (lambda x: F.indicators(x), {"rms": 1, "peak": 1, "peak_to_peak": 1,
                                                   "mean": 1, "std": 1}),
        "envelope_spectrum": (lambda x: F.envelope_spectrum(x, FS, (2000, 4000)),
                              {"1": 2}),
        "envelope": (lambda x: F.envelope(x, FS, (2000, 4000)), {"": 1}),
        "bandpass": (lambda x: F.bandpass(x, FS, (2000, 4000)), {"": 1}),
        "fast_kurtogram": (lambda x: F.fast_kurtogram(x, FS), None),
        "envelope_analysis": (lambda x: F.envelope_analysis(x, FS, rpm=1797,
                                                            bearing="6205"),
                              {"ses": 2, "indicators.rms": 1, "indicators.peak": 1,
                               "indicators.peak_to_peak": 1}),
        "fault_band_features": (lambda x: F.fault_band_features(x, FS, "6205", 1797), {}),
        "spectral_kurtosis": (lambda x: F.spectral_kurtosis(x, FS), {}),
        "order_envelope_spectrum": (lambda x: F.order_envelope_spectrum(
            x, FS, rpm=1797, band=(2000, 4000)), {"1": 2}),
        "indicator_ratios": (lambda x: F.indicator_ratios(x, healthy * np.abs(x).max()), {}),
        "cepstrum_prewhiten": (lambda x: F.cepstrum_prewhiten(x), {}),
        "envelope_evidence": (lambda x: __import__("ballpass").diagnose.envelope_evidence(
            x, FS, "6205", 1797), None),
    }
    cases = []
    for name, (call, powers) in funcs.items():
        for s in (1e-300, 1e-200, 1e-100, 1e-10, 1e10, 1e100, 1e200, 1e300):
            def run(call=call, powers=powers, s=s):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    ref = _numeric(call(sig))
                    try:
                        with budget(30.0):
                            got = _numeric(call(sig * s))
                    except (ValueError, TypeError) as exc:
                        return f"refused a scaled signal: {exc!s:.120}"
                for key, r in ref.items():
                    g = got.get(key)
                    if g is None or g.shape != r.shape:
                        return f"{key}: shape changed"
                    p = 0 if powers is None else powers.get(key, 0)
                    finite = np.isfinite(r)
                    if powers is None and p == 0 and not np.isfinite(g[finite]).all():
                        return f"{key}: not finite"
                    with np.errstate(all="ignore"):
                        top = np.abs(r[finite]).max(initial=0.0)
                        mag = math.log10(top) + p * math.log10(s) if top > 0 else 0.0
                    if p and not -290 < mag < 300:
                        continue                     # beyond the float range: exempt
                    if not np.isfinite(g[finite]).all():
                        return f"{key}: not finite at scale {s:g}"
                    if powers is None:
                        continue                     # structure only: finite suffices
                    with np.errstate(all="ignore"):
                        back = g[finite] / float(s) ** p if p else g[finite]
                    if not np.allclose(back, r[finite], rtol=1e-6, atol=1e-9 * top):
                        return f"{key}: differs by scale (power {p})"
                return None
            cases.append(Case("scale", f"{name} x {s:g}", run))
    return cases


# --------------------------------------------------------------------------- messages
BAD = {
    "positive": [0, -1.0, float("nan"), float("inf"), -float("inf"), "abc", [1.0, 2.0]],
    "real": [float("nan"), float("inf"), "abc", [1.0, 2.0]],
    "speed": [float("nan"), float("inf"), "abc", 0, -1.0],   # (start, end): a ramp
    "count": [0, -1, 2.5, float("nan"), "abc"],
    "signal": [np.array([]), "abc", np.full(6000, np.nan), X[:6000].astype(complex),
               np.array([[1.0, 2.0], [3.0]], dtype=object)],
    "band": [(3000.0, 1000.0), (-100.0, 1000.0), (float("nan"), 1000.0), "ab",
             (1.0, 2.0, 3.0), (1000.0, 1000.0), (1000.0, 1e9)],
    "bearing": ["nope", 42, ""],
    "flag": ["yes", 2],
    "axis": [5, -9, 1.5],
    "fraction": [-0.1, 1.5, float("nan"), "abc"],
}


def message_cases(world: World) -> list[Case]:
    import ballpass as bp
    from ballpass import features as F
    from ballpass.signalio import write_signal

    x = X[:6000]
    # function -> (call taking keyword overrides, {argument: kind})
    api = {
        "bandpass": (lambda **k: F.bandpass(**{"x": x, "fs": FS, "band": (1000, 3000), **k}),
                     {"x": "signal", "fs": "positive", "band": "band", "order": "count",
                      "axis": "axis"}),
        "envelope": (lambda **k: F.envelope(**{"x": x, "fs": FS, **k}),
                     {"x": "signal", "fs": "positive", "band": "band", "order": "count",
                      "squared": "flag", "prewhiten": "flag", "fault_hz": "positive"}),
        "envelope_spectrum": (lambda **k: F.envelope_spectrum(**{"x": x, "fs": FS, **k}),
                              {"x": "signal", "fs": "positive", "band": "band",
                               "order": "count", "axis": "axis"}),
        "fast_kurtogram": (lambda **k: F.fast_kurtogram(**{"x": x, "fs": FS, **k}),
                           {"x": "signal", "fs": "positive", "nlevel": "count",
                            "min_bandwidth": "positive", "floor_db": "real"}),
        "fault_band_features": (
            lambda **k: F.fault_band_features(**{"x": x, "fs": FS, "bearing": "6205",
                                                 "rpm": 1797, **k}),
            {"x": "signal", "fs": "positive", "bearing": "bearing", "rpm": "positive",
             "band": "band", "harmonics": "count", "tolerance": "fraction",
             "background_hz": "positive", "axis": "axis"}),
        "indicators": (lambda **k: F.indicators(**{"x": x, **k}),
                       {"x": "signal", "axis": "axis"}),
        "spectral_kurtosis": (lambda **k: F.spectral_kurtosis(**{"x": x, "fs": FS, **k}),
                              {"x": "signal", "fs": "positive", "nperseg": "count",
                               "noverlap": "count"}),
        "order_track": (lambda **k: F.order_track(**{"x": x, "fs": FS, "rpm": 1797, **k}),
                        {"x": "signal", "fs": "positive", "rpm": "positive",
                         "samples_per_rev": "count", "pulses_per_rev": "count"}),
        "separate_discrete": (
            lambda **k: F.separate_discrete(**{"x": x, "fs": FS, "rpm": 1797, **k}),
            {"x": "signal", "fs": "positive", "rpm": "positive", "order": "count",
             "nperseg": "count", "delay": "count"}),
        "envelope_analysis": (
            lambda **k: F.envelope_analysis(**{"x": x, "fs": FS, "rpm": 1797,
                                               "bearing": "6205", **k}),
            {"x": "signal", "fs": "positive", "rpm": "positive", "bearing": "bearing"}),
        "cepstrum_prewhiten": (lambda **k: F.cepstrum_prewhiten(**{"x": x, **k}),
                               {"x": "signal", "axis": "axis"}),
        "envelope_evidence": (
            lambda **k: bp.diagnose.envelope_evidence(**{"x": x, "fs": FS, "bearing": "6205",
                                                         "rpm": 1797, **k}),
            {"x": "signal", "fs": "positive", "bearing": "bearing", "rpm": "positive",
             "harmonics": "count", "slip": "fraction", "background_hz": "positive",
             "speed_tolerance": "fraction", "band": "band"}),
        "Scene": (lambda **k: bp.Scene(**{"bearing": "6205", **k}),
                  {"bearing": "bearing", "rpm": "speed", "radial_load_n": "positive",
                   "duration_s": "positive", "fs": "positive", "seed": "count",
                   "slip": "fraction", "resonance_hz": "positive",
                   "resonance_damping": "fraction", "snr_db": "real",
                   "noise_rms": "positive", "clearance_um": "real",
                   "noise_slope_db_oct": "real"}),
        "Fault": (lambda **k: bp.Fault(**{"kind": "outer", **k}),
                  {"width_mm": "positive", "depth_mm": "positive", "angle_deg": "real",
                   "element": "count", "ramp_fraction": "fraction",
                   "engagement": "fraction"}),
        "Sensor": (lambda **k: bp.Sensor(**k), {"angle_deg": "real"}),
        "simulate": (lambda **k: bp.simulate(bp.Scene("6205", duration_s=0.01), **k),
                     {"dt": "positive", "rtol": "positive", "atol": "positive",
                      "oversample": "count"}),
        "write_signal": (lambda **k: write_signal(**{"path": world.scratch() / "s.npz",
                                                     "accel": x, "fs": FS, **k}),
                         {"fs": "positive"}),    # any samples (read_signal checks them)
        "Bearing.frequencies": (
            lambda **k: bp.Bearing.catalog("6205").frequencies(**{"shaft_hz": 30.0, **k}),
            {"shaft_hz": "positive"}),
    }
    # values that are legitimate for an argument although bad for its kind
    valid = {("Scene", "seed", 0), ("Fault", "element", 0), ("Fault", "depth_mm", 0),
             ("Scene", "noise_rms", 0), ("spectral_kurtosis", "noverlap", 0),
             ("separate_discrete", "delay", 0), ("Scene", "radial_load_n", 0),
             # documented: level 0 is the full band, no bandwidth minimum, no fault
             # line to stay above, no background window
             ("fast_kurtogram", "nlevel", 0), ("fast_kurtogram", "min_bandwidth", 0),
             ("envelope", "fault_hz", 0), ("fault_band_features", "background_hz", 0),
             ("envelope_evidence", "background_hz", 0)}
    cases = []
    for fname, (call, args) in api.items():
        for arg, kind in args.items():
            for value in BAD[kind]:
                if isinstance(value, (int, float)) and (fname, arg, value) in valid:
                    continue
                label = f"{fname}({arg}={_short(value)})"
                if kind == "signal" and arg in ("x", "accel"):
                    names = [arg, "signal", "sample", "empty", "finite", "complex", "NaN"]
                else:
                    names = [arg]
                cases.append(Case("message", label,
                                  refuses(lambda call=call, arg=arg, value=value:
                                          call(**{arg: value}), names, seconds=30.0)))
    # CLI options: the message names the option as typed
    positive = ["-1", "0", "nan", "inf", "abc", "1e400", ""]
    real = ["nan", "inf", "abc", ""]
    count = ["-1", "0", "2.5", "abc", ""]
    commands = {
        "simulate": (["simulate", "--duration", "0.01", "--out", "x.npz"], {
            "--rpm": positive, "--load": positive[:1] + positive[2:], "--width": positive,
            "--depth": positive,
            "--angle": real, "--duration": positive, "--fs": positive,
            "--resonance": positive, "--damping": positive,
            "--slip": ["-1", "nan", "inf", "abc", "2"],
            "--snr": real, "--seed": ["-1", "2.5", "abc", ""], "--torque": real,
            "--dt": positive, "--rtol": positive, "--bearing": ["nope", ""],
            "--model": ["foo", ""], "--solver": ["foo", ""], "--sensors": ["nowhere"],
            "--needs": ["nothing"]}),
        "features": (["features", "sig.npz"], {
            "--fs": positive, "--rpm": positive, "--band": [["3000", "1000"], ["-1", "100"],
                                                            ["nan", "100"], ["a", "b"]],
            "--segment": positive, "--bearing": ["nope", ""]}),
        "diagnose": (["diagnose", "sig.npz"], {
            "--fs": positive, "--rpm": positive, "--segment": positive,
            "--bearing": ["nope", ""], "--baseline": ["missing.npz", "text.npz"]}),
        "plot": (["plot", "sig.npz", "--out", "p"], {
            "--fs": positive, "--rpm": positive, "--segment": positive,
            "--max-figures": count}),
        "generate": (["generate", "grid.toml", "--out", "ds", "--quiet"], {
            "--jobs": count[1:]}),                  # -1: every core
        "bifurcation": (["bifurcation", "--parameter", "rpm", "--values", "900", "1800",
                         "--duration", "0.2", "--fs", "12000", "--out", "b.csv"], {
            "--duration": positive, "--discard": ["-1", "nan", "abc", "2"],
            "--fs": positive, "--jobs": count[1:], "--clearance": real,
            "--load": positive[:1] + positive[2:],
            "--parameter": ["nope"], "--model": ["foo"]}),
        "work-precision": (["work-precision", "--duration", "0.05", "--no-scipy",
                            "--csv", "w.csv"], {
            "--repeats": count, "--duration": positive,
            "--scipy-time-limit": positive[:3] + positive[4:5]}),   # inf: no limit
        "bearings": (["bearings"], {"--rpm": positive, "--bearing": ["nope"]}),
        "models": (["models"], {"--needs": ["nothing"], "--bearing": ["nope"]}),
    }

    def prepare(d: Path) -> None:
        write_signal(d / "sig.npz", X, FS, meta={"bearing": "6205", "rpm": 1797.0})
        (d / "text.npz").write_text("not an archive")
        (d / "grid.toml").write_text(GRID_TOML)

    for command, (base, options) in commands.items():
        for option, values in options.items():
            for value in values:
                value = value if isinstance(value, list) else [value]
                argv = [a for a in base]
                if option in argv:                 # replace the base's own value
                    i = argv.index(option)
                    del argv[i:i + 2]
                argv += [option, *value]

                def run(argv=argv, option=option, value=value):
                    d = world.scratch()
                    prepare(d)
                    return cli_refuses(argv, [option], d, seconds=60.0,
                                       value=" ".join(value))()
                cases.append(Case("message", f"{command} {option} {' '.join(value)!r}", run))
    return cases


def _short(value) -> str:
    if isinstance(value, np.ndarray):
        return f"array{value.shape} {value.dtype}"
    return repr(value)[:30]


# ------------------------------------------------------------------------------ main
GENERATORS = {"security": security_cases, "manifest": manifest_cases,
              "corrupted": corrupted_cases, "interrupt": interrupt_cases, "bomb": bomb_cases,
              "substitution": substitution_cases, "scale": scale_cases,
              "message": message_cases}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--kinds", nargs="+", choices=KINDS, default=list(KINDS))
    parser.add_argument("--match", default=None, help="only cases whose name contains this")
    parser.add_argument("--out", default=str(RESULTS_DIR))
    args = parser.parse_args(argv)
    # a real memory bomb becomes a MemoryError here, not a machine swapping
    limit = 8 * 2**30
    resource.setrlimit(resource.RLIMIT_AS, (limit, resource.getrlimit(resource.RLIMIT_AS)[1]))
    import ballpass as bp

    bp.simulate(bp.Scene("6205", duration_s=0.01))     # compile outside every budget
    results = []
    with tempfile.TemporaryDirectory(prefix="abuse-") as tmp:
        world = World(Path(tmp))
        for kind in args.kinds:
            cases = [c for c in GENERATORS[kind](world)
                     if args.match is None or args.match in c.name]
            t0 = time.perf_counter()
            for case in cases:
                try:
                    problem = case.run()
                except BaseException as exc:  # noqa: BLE001 - the sweep must go on
                    problem = f"sweep: {type(exc).__name__}: {str(exc)[:120]}"
                results.append((case.kind, case.name, problem))
            bad = sum(1 for r in results if r[0] == kind and r[2])
            print(f"{kind}: {len(cases)} cases, {bad} not clean, "
                  f"{time.perf_counter() - t0:.0f} s", flush=True)
    write_report(results, Path(args.out))
    return 0


def write_report(results, out: Path) -> None:
    total = Counter(k for k, _, _ in results)
    clean = Counter(k for k, _, p in results if not p)
    lines = ["# Adversarial sweep", "",
             "Bad arguments, tampered datasets, corrupted files, interrupts and bombs thrown "
             "at the API and the CLI; clean = refused with one line naming the argument or "
             "file (CLI: exit 2, or 130 when interrupted) within the time budget, no "
             "traceback, nothing outside the folder touched, or a result identical to the "
             "untampered input's. Written by `benchmarks/abuse_sweep.py`.", "",
             "| kind | cases | clean | % |", "|---|---|---|---|"]
    for kind in KINDS:
        if total[kind]:
            lines.append(f"| {kind} | {total[kind]} | {clean[kind]} | "
                         f"{100 * clean[kind] / total[kind]:.1f} |")
    n, c = sum(total.values()), sum(clean.values())
    lines += [f"| **all** | {n} | {c} | {100 * c / max(n, 1):.1f} |", "", "## Not clean", ""]
    lines += [f"- {kind}: `{name}`: {problem}" for kind, name, problem in results if problem]
    if c == n:
        lines.append("None.")
    out.mkdir(parents=True, exist_ok=True)
    (out / "abuse_sweep.md").write_text("\n".join(lines) + "\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    kinds = [k for k in KINDS if total[k]]
    fig, ax = plt.subplots(figsize=(7, 3.2))
    pct = [100 * clean[k] / total[k] for k in kinds]
    ax.bar(range(len(kinds)), pct, color=["C2" if p >= 98 else "C3" for p in pct])
    for i, k in enumerate(kinds):
        ax.text(i, 1, f"{clean[k]}/{total[k]}", ha="center", fontsize=7, rotation=90)
    ax.axhline(98, color="grey", ls="--", lw=0.8, label="goal 98 %")
    ax.set_xticks(range(len(kinds)), kinds, fontsize=8, rotation=20)
    ax.set_ylabel("clean, %")
    ax.set_ylim(0, 100)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(out / "abuse_sweep.png", dpi=120)
    print("\n".join(lines[:len(kinds) + 9]))


if __name__ == "__main__":
    raise SystemExit(main())
