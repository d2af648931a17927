"""Compiled loops of the fast kurtogram (numba, ``cache=True``).

The two passes over each row of the tree that surround its inverse FFT: weighting the
spectrum bins each band gathers, and the moments of ``|c|^2`` of the band signals. In
NumPy each is several passes with temporaries (gather, product, square, sum, dot);
fused here they read and write each value once, which halves the time of the
kurtogram outside its FFTs (``benchmarks/features_speed.py``). Imported on the first
kurtogram of a process, not with :mod:`ballpass.features`: numba compiles them once
(about 2 s, then cached on disk next to this file).
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["gather_bands", "band_moments"]


@njit(cache=True)
def gather_bands(spectrum, starts, weights, which, out):
    """``out[j, i] = spectrum[starts[j] + i] * weights[which[j], i]``, 0 outside the
    spectrum, for one signal.

    ``spectrum`` (n_bins,) complex, contiguous; ``starts`` (n_bands,) int, first bin of
    each band (may be < 0 or run past the last bin); ``weights`` (n_distinct, n_taps),
    ``which`` (n_bands,) int: the row of ``weights`` of each band; ``out`` (n_bands,
    n_taps) complex, C-contiguous, overwritten. Real and imaginary parts are scaled apart
    (float64 views: real, imaginary, real, ...): the loop vectorises, 3x faster than on
    complex numbers, and the products are those of a complex times a real number.
    """
    n_bins = spectrum.shape[0]
    n_taps = weights.shape[1]
    spectrum = spectrum.view(np.float64)
    out = out.view(np.float64)
    for j in range(starts.shape[0]):
        start = starts[j]
        lo = min(max(0, -start), n_taps)  # bins [lo, hi) of the band lie in the spectrum
        hi = max(min(n_taps, n_bins - start), lo)
        dst = out[j]
        src = spectrum[2 * (start + lo) : 2 * (start + hi)]
        w = weights[which[j], lo:hi]
        for i in range(2 * lo):
            dst[i] = 0.0
        band = dst[2 * lo : 2 * hi]
        for i in range(hi - lo):
            band[2 * i] = src[2 * i] * w[i]
            band[2 * i + 1] = src[2 * i + 1] * w[i]
        for i in range(2 * hi, 2 * n_taps):
            dst[i] = 0.0


@njit(cache=True, inline="always")
def _add_moments(v, sum2, sum4):
    """``sum2 + |v|^2, sum4 + |v|^4``."""
    p = v.real * v.real + v.imag * v.imag
    return sum2 + p, sum4 + p * p


@njit(cache=True)
def band_moments(c, m2, m4):
    """Means of ``|c|^2`` and ``|c|^4`` of each band signal of one signal: ``c``
    (n_bands, n_taps) complex, its rows in any order of their samples (the means do
    not depend on it); ``m2``, ``m4`` (n_bands,), overwritten.

    Four interleaved partial sums: independent additions (faster than one running sum,
    which waits on each addition) and a smaller rounding error.
    """
    n_bands, n_taps = c.shape
    for j in range(n_bands):
        a0 = a1 = a2 = a3 = 0.0
        b0 = b1 = b2 = b3 = 0.0
        i = 0
        while i + 4 <= n_taps:
            a0, b0 = _add_moments(c[j, i], a0, b0)
            a1, b1 = _add_moments(c[j, i + 1], a1, b1)
            a2, b2 = _add_moments(c[j, i + 2], a2, b2)
            a3, b3 = _add_moments(c[j, i + 3], a3, b3)
            i += 4
        for k in range(i, n_taps):
            a0, b0 = _add_moments(c[j, k], a0, b0)
        m2[j] = ((a0 + a1) + (a2 + a3)) / n_taps
        m4[j] = ((b0 + b1) + (b2 + b3)) / n_taps
