"""Thresholds from a healthy baseline of the machine: what its own seconds read.

The diagnoser's default threshold (6 dB) comes from white noise. A real machine's
healthy spectrum can read higher in places: the CWRU rig's healthy drive end carries a
comb 0.85 % above the 6205's BPFO that one-second records cannot tell from it, and 2 of
its 33 one-second windows read "outer" above 6 dB (docs/diagnosis_length.md). An analyst
compares with a baseline; :func:`baseline_thresholds` does so: it cuts healthy
recordings into windows as long as the signals to be diagnosed, started every
:data:`WINDOW_STEP` of their length (a user's seconds start anywhere), and fits an
:class:`~ballpass.diagnose.EnvelopeDiagnoser` on them (each family's threshold becomes
the 99th percentile of its healthy evidence plus 1 dB, never below the default).
"""

from __future__ import annotations

import numpy as np

from ..features._validation import check_fs, check_rpm, check_signal

__all__ = ["WINDOW_STEP", "sliding_windows", "baseline_thresholds"]

#: Windows start every this fraction of their length (1/8 s for one-second windows).
WINDOW_STEP = 0.125


def sliding_windows(x, n: int, step: float = WINDOW_STEP) -> np.ndarray:
    """Windows of ``n`` samples of ``x``, started every ``step * n`` samples.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
    n : int
        Window length, samples; at most ``len(x)``.
    step : float, optional
        Start-to-start distance as a fraction of ``n``, in (0, 1] (default 1/8).

    Returns
    -------
    ndarray, shape (n_windows, n)
        Copies; the last window ends at most ``step * n`` samples before the end.

    Examples
    --------
    >>> from ballpass.diagnose.baseline import sliding_windows
    >>> sliding_windows(range(10), 4, step=0.5)[:, 0].tolist()
    [0, 2, 4, 6]
    """
    x = np.asarray(x)
    if x.ndim != 1:
        raise ValueError(f"x must be 1-D, got shape {x.shape}")
    if not 1 <= n <= len(x):
        raise ValueError(f"n must be in [1, len(x) = {len(x)}], got {n}")
    if not 0.0 < step <= 1.0:
        raise ValueError(f"step must be in (0, 1], got {step!r}")
    hop = max(1, round(step * n))
    starts = np.arange(0, len(x) - n + 1, hop)
    return np.stack([x[i:i + n] for i in starts])


def baseline_thresholds(records, bearing, seconds: float, **diagnoser_params) -> dict:
    """Each fault family's threshold, dB, from healthy recordings of the machine.

    Each record is cut by :func:`sliding_windows` into windows of ``seconds`` (or the
    whole record, if shorter) and an :class:`~ballpass.diagnose.EnvelopeDiagnoser` is
    fitted on them at the record's own rate and speed; a family's threshold is the
    largest over the records. Pass the result as ``threshold_db`` to diagnose signals of
    the same machine, at any rate.

    Parameters
    ----------
    records : sequence of (x, fs, rpm)
        Healthy signals (m/s^2), their sampling frequencies (Hz) and shaft speeds
        (rev/min).
    bearing : str or Bearing
        The bearing whose fault lines are diagnosed.
    seconds : float
        Length of the signals to be diagnosed, s (> 0).
    **diagnoser_params
        Further :class:`~ballpass.diagnose.EnvelopeDiagnoser` parameters (``band``,
        ``quantile``, ``margin_db``, ...).

    Returns
    -------
    dict of str to float
        ``{"outer": dB, "inner": dB, "ball": dB}``.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.diagnose import EnvelopeDiagnoser
    >>> from ballpass.diagnose.baseline import baseline_thresholds
    >>> healthy = np.random.default_rng(0).standard_normal(36_000)      # 3 s at 12 kHz
    >>> thresholds = baseline_thresholds([(healthy, 12_000.0, 1797.0)], "6205", 1.0)
    >>> sorted(thresholds), min(thresholds.values()) >= 6.0
    (['ball', 'inner', 'outer'], True)
    >>> diag = EnvelopeDiagnoser("6205", fs=48_000.0, rpm=1797.0, threshold_db=thresholds)
    """
    from .rules import EnvelopeDiagnoser

    if isinstance(seconds, bool) or not np.isfinite(seconds) or seconds <= 0:
        raise ValueError(f"seconds must be finite and > 0, got {seconds!r}")
    if not len(records):
        raise ValueError("records must hold at least one healthy (x, fs, rpm)")
    checked = []
    for i, (x, fs, rpm) in enumerate(records):
        x = check_signal(x, name=f"records[{i}] signal")
        if x.ndim != 1:
            raise ValueError(f"records[{i}] signal must be 1-D, got shape {x.shape}")
        checked.append((x, check_fs(fs), float(check_rpm(rpm, ()))))
    thresholds: dict = {}
    for x, fs, rpm in checked:
        windows = sliding_windows(x, min(len(x), round(seconds * fs)))
        diag = EnvelopeDiagnoser(bearing, fs=fs, rpm=rpm, **diagnoser_params).fit(windows)
        for fault, value in diag.thresholds_.items():
            thresholds[fault] = max(value, thresholds.get(fault, -np.inf))
    return thresholds
