"""Cost of running the sr4/sr5 integrators in chunks (so that Ctrl-C stops a long
simulation): integration time with the default chunk size against one call for the
whole run, side by side.

Each case runs three ways, interleaved round by round (the order rotating) so that the
machine's load hits all alike: default chunks, one call, and chunks 64 times smaller
(which magnify the cost of a call). The table gives the median integration time over
the rounds with its spread (min-max), the median over rounds of the ratio
chunked / one call within a round (paired, so a load spike hitting one round cancels),
and the time of one chunk (integration time over the number of calls), the longest a
Ctrl-C waits. On a machine shared with other jobs these ratios scatter by several per
cent either way, more than chunking can cost, so the cost of a call itself is also
measured directly: a call that returns at once (no pass allowed), timed over
thousands of calls; times the number of calls, over the integration time, it bounds
the overhead.

    PYTHONPATH=$PWD python benchmarks/sr5_chunking.py        # ~2 min on 2 cores

Writes ``docs/results/sr5_chunking.md`` and ``docs/results/sr5_chunking.png``.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from _machine import machine
from _paths import RESULTS_DIR

import ballpass as bp
from ballpass.simulate import _integrators as _I

OUTER = bp.Scene("6205", rpm=1797.0, fs=48_000.0, duration_s=2.0,
                 fault=bp.Fault("outer", width_mm=0.5, depth_mm=0.1))
INNER = OUTER.replace(fault=bp.Fault("inner", width_mm=0.5, depth_mm=0.1), duration_s=1.0)
#: case -> (scene, model, solver)
CASES = {
    "sr5 rk4, outer, 2 s": (OUTER, "sr5", "rk4"),
    "sr5 rk4, inner, 1 s": (INNER, "sr5", "rk4"),
    "sr5 dopri5, outer, 1 s": (OUTER.replace(duration_s=1.0), "sr5", "dopri5"),
    "sr4 rk4, outer, 1 s": (OUTER.replace(duration_s=1.0), "sr4", "rk4"),
}
ONE_CALL = 1 << 62


def _time(scene, model, solver, passes) -> tuple[float, int]:
    """Integration time (s) and passes of the main loop (upper bound: steps plus
    rejections) of one run with ``passes`` per call."""
    _I.CHUNK_PASSES = passes
    res = bp.simulate(scene, model=model, solver=solver)
    return res.info["integration_time_s"], res.info["n_steps"] + res.info["n_rejected"]


def _call_cost() -> float:
    """Seconds per :func:`rk4` call that returns at once (``max_passes`` = 0): the
    dispatch and argument-unboxing cost every chunk pays; median of 9 batches."""
    from ballpass.simulate._sr5_driver import _split_times
    from ballpass.simulate.sr5 import build_model

    bm = build_model(OUTER, None, resonator=True)
    h_out, n_out = 1.0 / (4 * OUTER.fs), 4 * OUTER.n_samples
    before, after = _split_times(bm, (n_out - 1) * h_out)
    out, states = np.empty((n_out, 1)), np.empty((0, bm.n_state))
    work = _I.rk4_start(bm.y0, *bm.model, bm.n_res, h_out, 6, 1, n_out, before, out, states)
    args = (*bm.model, bm.n_res, h_out, 6, 1, n_out, before, after, math.inf, math.inf,
            np.full(bm.n_state, np.inf), out, states, *work, 0)
    batches = []
    for _ in range(9):
        t0 = time.perf_counter()
        for _ in range(2000):
            _I.rk4(*args)
        batches.append((time.perf_counter() - t0) / 2000)
    return float(np.median(batches))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=15)
    args = parser.parse_args(argv)
    chunk = _I.CHUNK_PASSES
    for scene, model, solver in CASES.values():  # compile and warm up
        bp.simulate(scene.replace(duration_s=0.01), model=model, solver=solver)
    modes = [("chunked", chunk), ("one call", ONE_CALL), ("chunks / 64", chunk // 64)]
    times = {(name, mode): [] for name in CASES for mode, _ in modes}
    passes = {}
    for r in range(args.rounds):
        for name, (scene, model, solver) in CASES.items():
            for mode, size in modes[r % 3:] + modes[:r % 3]:
                t, passes[name] = _time(scene, model, solver, size)
                times[name, mode].append(t)
    _I.CHUNK_PASSES = chunk
    call_s = _call_cost()
    rows = []
    for name in CASES:
        a, b = np.array(times[name, "chunked"]), np.array(times[name, "one call"])
        c = np.array(times[name, "chunks / 64"])
        calls = math.ceil(passes[name] / chunk)
        rows.append((name, np.median(a), a.min(), a.max(), np.median(b), b.min(), b.max(),
                     np.median(a / b), np.median(c / b), calls, np.median(a) / calls,
                     calls * call_s / np.median(b)))
    out = RESULTS_DIR
    lines = [
        "# Chunked integration: what interruptibility costs",
        "",
        f"Integration time of sr4/sr5 with {chunk} loop passes per kernel call (the "
        "default) against one call for the whole run; median (min-max) of "
        f"{args.rounds} interleaved rounds. Machine: {machine()}, shared with other jobs.",
        "Written by `benchmarks/sr5_chunking.py`.",
        "",
        "| case | chunked, s | one call, s | chunked / one call | chunks / 64: ratio "
        "| calls | one chunk, ms | calls x call cost / time |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, ma, lo_a, hi_a, mb, lo_b, hi_b, ratio, ratio64, calls, per, bound in rows:
        lines.append(f"| {name} | {ma:.3f} ({lo_a:.3f}-{hi_a:.3f}) | {mb:.3f} "
                     f"({lo_b:.3f}-{hi_b:.3f}) | {ratio:.3f} | {ratio64:.3f} | {calls} "
                     f"| {1e3 * per:.0f} | {100 * bound:.3f} % |")
    lines += ["", f"Cost of one call that returns at once: {1e6 * call_s:.1f} us (median "
              "of 9 batches of 2000 calls)."]
    (out / "sr5_chunking.md").write_text("\n".join(lines) + "\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 3.2))
    for i, name in enumerate(CASES):
        a, b = np.array(times[name, "chunked"]), np.array(times[name, "one call"])
        ax.plot(np.full(a.size, i - 0.1), a / np.median(b), "o", color="C0", ms=4,
                label="chunked" if i == 0 else None)
        ax.plot(np.full(b.size, i + 0.1), b / np.median(b), "s", color="C1", ms=4,
                label="one call" if i == 0 else None)
    ax.axhline(1.02, color="grey", ls="--", lw=0.8, label="+2 %")
    ax.set_xticks(range(len(CASES)), list(CASES), fontsize=7)
    ax.set_ylabel("integration time / median of one call")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "sr5_chunking.png", dpi=120)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
