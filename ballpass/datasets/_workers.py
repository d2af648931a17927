"""The worker processes of :func:`ballpass.datasets.generate`: how many, forked after the
kernels are compiled, dying with their parent, stopped at once on Ctrl-C; the shards
dispatched to them (or to any :class:`concurrent.futures.Executor`).
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os
import signal
import sys
import threading
import time
import warnings
from concurrent.futures.process import BrokenProcessPool

from ._shard import ShardSpec, run_shard


def _die_with_parent(parent_pid: int) -> None:
    """Worker initializer: end this worker as soon as the process that started it dies.

    On Linux the kernel sends SIGKILL on the parent's death (``PR_SET_PDEATHSIG``);
    elsewhere a daemon thread polls the parent id. Either way a killed ``generate``
    leaves no worker behind still writing shards.
    """
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        if libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL) != 0:
            raise OSError(ctypes.get_errno(), "prctl failed")
    except (OSError, AttributeError):  # not Linux: poll instead

        def watch() -> None:
            while os.getppid() == parent_pid:
                time.sleep(0.5)
            os._exit(1)

        threading.Thread(target=watch, daemon=True).start()
    if os.getppid() != parent_pid:  # the parent died before the signal was armed
        os._exit(1)
    # Ctrl-C reaches the whole process group: the parent alone handles it (and stops
    # the workers with SIGTERM, whose handler the fork copied from the CLI: default here)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


_PR_SET_PDEATHSIG = 1  # from <linux/prctl.h>


def available_cores() -> int:
    """Cores this process may run on (its CPU affinity where the OS tells)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def _n_workers(n_jobs: int, n_tasks: int) -> int:
    """Workers for ``n_tasks`` shards: ``n_jobs`` capped at the shards and the cores;
    a request above the cores warns."""
    cores = available_cores()
    if n_jobs > cores:
        warnings.warn(f"n_jobs={n_jobs} is more than the {cores} cores available; using "
                      f"{min(cores, n_tasks)} worker(s)", stacklevel=3)
    return max(1, min(n_jobs, cores, n_tasks))


def _pool(n_workers: int) -> cf.ProcessPoolExecutor:
    """Worker processes that die with this one. On Linux they are forked after the
    kernels are compiled in the parent, so they start at once with the kernels loaded
    (no import, no cache load); elsewhere they start the platform's default way."""
    context = multiprocessing.get_context("fork" if sys.platform == "linux" else None)
    return cf.ProcessPoolExecutor(n_workers, mp_context=context,
                                  initializer=_die_with_parent, initargs=(os.getpid(),))


def _stop_workers(executor: cf.ProcessPoolExecutor) -> None:
    """End the pool's worker processes at once (SIGTERM, then wait for them): their
    unfinished shards are only temporary files, removed by the caller."""
    processes = list((getattr(executor, "_processes", None) or {}).values())
    for process in processes:
        process.terminate()
    for process in processes:
        process.join(timeout=10)


def _dispatch(specs: list[ShardSpec], n_workers: int, executor):
    """Run the shards; yield their reports as they complete."""
    if executor is None and n_workers == 1:
        yield from map(run_shard, specs)
        return
    own = executor is None
    if own:
        executor = _pool(n_workers)
    futures = [executor.submit(run_shard, s) for s in specs]
    finished = False
    try:
        for fut in cf.as_completed(futures):
            yield fut.result()
        finished = True
    except BrokenProcessPool:
        raise RuntimeError("a worker process died (killed, or out of memory?); complete "
                           "shards are kept, run generate again to resume") from None
    finally:
        if own and not finished:   # an error, Ctrl-C or SIGTERM: stop the workers now;
            _stop_workers(executor)  # the pool then fails the futures left (cancelling
            executor.shutdown(wait=True)  # them too would race it)
        else:
            for fut in futures:
                fut.cancel()
            if own:
                executor.shutdown(wait=True, cancel_futures=True)
