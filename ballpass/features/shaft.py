"""Shaft harmonics in a squared envelope spectrum: the bins they occupy.

A machine's shaft harmonics (unbalance, misalignment, the motor's electromagnetic lines
at multiples of its synchronous speed) stand in the envelope spectrum of most real
recordings. Bearing fault lines can lie within a bin or two of them: the 6203's 2xBSF is
0.3 % below 4x the shaft speed, its BPFI 1.1 % below 5x. A line on a shaft harmonic
that stands out is no evidence of a fault, so the envelope diagnoser
(:mod:`ballpass.diagnose.evidence`) and the fault-band features
(:func:`ballpass.features.fault_band_levels`) read those bins as background.
"""

from __future__ import annotations

import math

import numpy as np

#: A shaft harmonic standing this far above the SES background (dB) is a line in its
#: own right; a fault line on it would be no evidence (the diagnoser's decision
#: threshold: a shaft line strong enough to count as evidence does not count) ...
SHAFT_LINE_DB = 6.0
#: ... and its SES bins closer than this many bins read as background: the Hann
#: window's main lobe (+-2 bins) plus the +-1 bin line window ...
SHAFT_GUARD_BINS = 3.0
#: ... or closer than this fraction of the harmonic's frequency: an induction motor's
#: synchronous speed, whose multiples carry electromagnetic lines, lies 0.17-0.25 %
#: above the shaft speed at no load (CWRU: 1796-1797 rpm against 1800 rpm; the healthy
#: fan-end channel carries lines at 360.0 and 450.0 Hz). Where one bin is wider than
#: this fraction, a harmonic is looked for in its nearest bin only.
SHAFT_GUARD_RELATIVE = 0.0025


def _harmonic_bins(freqs: np.ndarray, ses: np.ndarray, shaft_hz: np.ndarray,
                   background_hz: float):
    """Shared work of :func:`shaft_line_bins` and :func:`without_shaft_lines`: the
    mask (n, n_bins) and, per bin, the background median of its nearest harmonic."""
    n, n_bins = ses.shape
    df = freqs[1]
    fine = SHAFT_GUARD_BINS * df <= 0.25 * shaft_hz  # (n,)
    # only rows fine enough are guarded: their harmonics are >= 12 bins apart, so K is
    # at most n_bins / 12 (a coarse row, e.g. fs = 1e12 Hz, would ask for billions)
    k = np.arange(1, int(freqs[-1] / shaft_hz[fine].min()) + 1) if fine.any() else []
    if len(k) == 0:  # the spectrum ends below the first harmonic, or no row is guarded
        return np.zeros(ses.shape, dtype=bool), np.zeros(ses.shape)
    exact = k[None, :] * shaft_hz[:, None] / df  # harmonic frequencies in bins, (n, K)
    centre = np.rint(exact).astype(np.int64)
    half = min(n_bins, max(5, math.ceil(background_hz / df)))  # the whole spectrum at most
    rows = np.arange(n)[:, None, None]
    around = np.clip(centre[..., None] + np.arange(-half, half + 1), 1, n_bins - 1)
    background = np.median(ses[rows, around], axis=-1)  # (n, K)
    # The harmonic's line is looked for within the +-1 bin line window, or in its nearest
    # bin alone where one bin exceeds the synchronous-speed offset at that harmonic: no
    # shaft or motor line sits a bin away there, but a fault line can (coarse bins).
    wide = SHAFT_GUARD_RELATIVE * exact >= 1.0  # the +-1 bin window applies, (n, K)
    steps = np.arange(-1, 2)
    near = np.clip(centre[..., None] + steps, 1, n_bins - 1)
    looked = (steps == 0) | wide[..., None]  # (n, K, 3)
    peak = np.where(looked, ses[rows, near], 0.0).max(axis=-1)
    present = (centre < n_bins - 1) & (peak >= background * 10 ** (SHAFT_LINE_DB / 10))
    m = np.maximum(np.rint(freqs[None, :] / shaft_hz[:, None]), 1.0)  # nearest harmonic
    guard = np.maximum(SHAFT_GUARD_BINS * df, SHAFT_GUARD_RELATIVE * m * shaft_hz[:, None])
    close = np.abs(freqs[None, :] - m * shaft_hz[:, None]) < guard
    idx = np.clip(m.astype(np.int64) - 1, 0, k.size - 1)
    mask = close & np.take_along_axis(present, idx, axis=1) & fine[:, None]
    return mask, np.take_along_axis(background, idx, axis=1)


def shaft_line_bins(freqs: np.ndarray, ses: np.ndarray, shaft_hz: np.ndarray,
                    background_hz: float) -> np.ndarray:
    """Bins of each SES row on a shaft harmonic that stands out, (n, n_bins) bool.

    A harmonic ``k fr`` stands out when the largest SES bin within +-1 bin of it is at
    least :data:`SHAFT_LINE_DB` above the median SES over +-``background_hz``; its bins
    within the guard (:data:`SHAFT_GUARD_BINS`, :data:`SHAFT_GUARD_RELATIVE`) are marked.
    Where one bin is wider than the synchronous-speed offset at the harmonic
    (``SHAFT_GUARD_RELATIVE k fr``: low harmonics on short records) only the bin nearest
    ``k fr`` counts: no shaft or motor line can sit a bin away, but a fault line can (the
    6203's BPFO, 3.05 orders, 1.5 bins above 3x on 1 s records, leaks into the nearest
    bin some 13 dB below its own peak, so it cannot raise the guard that would blank it).
    Only where the guard spans at most a quarter of the shaft speed: at coarser
    resolution (records shorter than 12 shaft revolutions) a fault line and the shaft
    harmonic beside it share the same bins, and marking them would blank a fault line
    as often as a shaft line.

    Parameters
    ----------
    freqs : ndarray, shape (n_bins,)
        Uniform frequency grid from 0 Hz, Hz.
    ses : ndarray, shape (n, n_bins)
        Squared envelope spectra.
    shaft_hz : ndarray, shape (n,)
        Shaft speed of each row, Hz.
    background_hz : float
        Half-width of the background window around each harmonic, Hz.

    Returns
    -------
    ndarray of bool, shape (n, n_bins)

    Examples
    --------
    A 4x line 20 dB above a flat SES (4 s, 0.25 Hz bins) at 30 Hz shaft speed marks the
    bins closer than 3 bins (0.75 Hz) to 120 Hz:

    >>> import numpy as np
    >>> from ballpass.features.shaft import shaft_line_bins
    >>> freqs = np.arange(2001) * 0.25
    >>> ses = np.ones((1, freqs.size)); ses[0, 480] = 100.0
    >>> freqs[shaft_line_bins(freqs, ses, np.array([30.0]), 10.0)[0]].tolist()
    [119.5, 119.75, 120.0, 120.25, 120.5]
    """
    return _harmonic_bins(freqs, ses, shaft_hz, background_hz)[0]


def without_shaft_lines(freqs: np.ndarray, ses: np.ndarray, shaft_hz: np.ndarray,
                        background_hz: float) -> np.ndarray:
    """SES rows with the bins of :func:`shaft_line_bins` replaced by the background
    median around their harmonic: what is left for the fault lines.

    Parameters and shapes as :func:`shaft_line_bins`; returns a new array like ``ses``.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features.shaft import without_shaft_lines
    >>> freqs = np.arange(2001) * 0.25
    >>> ses = np.ones((1, freqs.size)); ses[0, 480] = 100.0
    >>> float(without_shaft_lines(freqs, ses, np.array([30.0]), 10.0).max())
    1.0
    """
    mask, background = _harmonic_bins(freqs, ses, shaft_hz, background_hz)
    return np.where(mask, background, ses)
