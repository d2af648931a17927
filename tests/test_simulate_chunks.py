"""The sr4/sr5 integrators run in chunks, so Ctrl-C stops a long simulation between
two of them: the result does not depend on the chunk size, bit for bit (datasets store
a simulator fingerprint and ``regenerate`` promises identical rows), and a long
``ballpass simulate`` receiving SIGINT ends at once with one line and exit code 130.

Planted once each: dopri5 resuming with the initial step instead of the saved one (the
three dopri5 comparisons fail); rk4 resuming with no contact loaded instead of the
saved set (the four rk4 comparisons fail); one call for the whole run (the SIGINT test
times out waiting for the exit).
"""

import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from _processes import cpu_seconds, default_sigint

import ballpass as bp
from ballpass.cli import EXIT_INTERRUPTED
from ballpass.simulate import _integrators as _I

ROOT = Path(__file__).resolve().parents[1]

# short scenes with fault edges, ramps and (inner race, 6000 rpm) contacts opening and
# closing inside steps, so every piece of loop state carried between calls is exercised
SCENES = {
    "outer": bp.Scene("6205", rpm=1797, fault=bp.Fault("outer"), duration_s=0.02),
    "inner": bp.Scene("6205", rpm=6000, fault=bp.Fault("inner", width_mm=2.0),
                      duration_s=0.02),
}
CASES = [("outer", "sr5", "rk4", False), ("inner", "sr5", "rk4", False),
         ("inner", "sr5", "rk4", True), ("outer", "sr5", "dopri5", False),
         ("inner", "sr5", "dopri5", True), ("inner", "sr4", "rk4", False),
         ("inner", "sr4", "dopri5", False)]


def _run(monkeypatch, passes, scene, model, solver, forces):
    monkeypatch.setattr(_I, "CHUNK_PASSES", passes)
    return bp.simulate(SCENES[scene], model=model, solver=solver, return_forces=forces)


@pytest.mark.parametrize("scene, model, solver, forces", CASES)
def test_chunked_run_is_bit_identical_to_one_call(monkeypatch, scene, model, solver,
                                                   forces):
    whole = _run(monkeypatch, 10**12, scene, model, solver, forces)   # a single call
    assert whole.info["n_steps"] > 263            # several chunks at each size below
    for passes in (1, 7, 263):
        part = _run(monkeypatch, passes, scene, model, solver, forces)
        # exact equality, no tolerance: the same floating-point operations in the
        # same order, only interrupted
        assert np.array_equal(part.accel, whole.accel), passes
        assert part.info["n_steps"] == whole.info["n_steps"]
        assert part.info["n_rejected"] == whole.info["n_rejected"]
        if forces:
            assert np.array_equal(part.truth.contact_forces, whole.truth.contact_forces)
            assert np.array_equal(part.truth.displacement, whole.truth.displacement)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ctrl_c_stops_a_long_simulation_within_a_chunk(tmp_path):
    # what a run costs before its integration (imports, loading the kernels, the
    # warm-up run, writing): a tiny simulation's CPU time, once the kernels are
    # compiled (on a fresh clone the first run compiles them; numba caches them)
    import resource

    base = ["simulate", "--fs", "12000", "--resonance", "3000"]
    for _ in range(2):
        start = resource.getrusage(resource.RUSAGE_CHILDREN)
        tiny = subprocess.run([sys.executable, "-m", "ballpass", *base, "--duration",
                               "0.01", "--out", str(tmp_path / "tiny.npz")], cwd=ROOT,
                              capture_output=True, text=True)
        assert tiny.returncode == 0, tiny.stderr
        end = resource.getrusage(resource.RUSAGE_CHILDREN)
        if "compiling" not in tiny.stdout + tiny.stderr:
            break
    before = end.ru_utime + end.ru_stime - start.ru_utime - start.ru_stime + 0.5
    # 50 s at 1/200 of the internal grid: some 5e8 RK4 steps, minutes of work
    dt = 1.0 / (4 * 12000 * 200)
    proc = subprocess.Popen([sys.executable, "-m", "ballpass", *base, "--duration", "50",
                             "--dt", repr(dt), "--out", str(tmp_path / "long.npz")],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, preexec_fn=default_sigint)
    try:
        # inside the integration: the child has used the tiny run's CPU time plus 0.5 s
        # (CPU time, not the clock, which a loaded machine stretches)
        deadline = time.monotonic() + 120
        while cpu_seconds(proc.pid) < before:
            assert proc.poll() is None, proc.stderr.read()
            assert time.monotonic() < deadline
            time.sleep(0.05)
        proc.send_signal(signal.SIGINT)
        # a chunk is some 1e4 steps, ~0.02 s of CPU: 10 s of wall clock leave a loaded
        # 2-core machine a wide margin, and are far below the minutes the run would take
        _, stderr = proc.communicate(timeout=10)
    finally:
        proc.kill()                  # never left running, whatever failed
        proc.wait()
    assert proc.returncode == EXIT_INTERRUPTED
    assert stderr == "ballpass simulate: interrupted\n"
    assert not (tmp_path / "long.npz").exists()
