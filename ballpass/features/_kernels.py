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

from numba import njit

__all__ = ["gather_bands", "band_moments"]


@njit(cache=True)
def gather_bands(spectrum, starts, weights, out):
    """``out[s, j, i] = spectrum[s, starts[j] + i] * weights[j, i]``, 0 outside the
    spectrum.

    ``spectrum`` (n_signals, n_bins) complex; ``starts`` (n_bands,) int, first bin of
    each band (may be < 0 or run past the last bin); ``weights`` (n_bands, n_taps);
    ``out`` (n_signals, n_bands, n_taps) complex, overwritten.
    """
    n_signals, n_bins = spectrum.shape
    n_bands, n_taps = weights.shape
    for s in range(n_signals):
        for j in range(n_bands):
            start = starts[j]
            lo = min(max(0, -start), n_taps)
            hi = max(min(n_taps, n_bins - start), lo)
            for i in range(lo):
                out[s, j, i] = 0.0
            for i in range(lo, hi):
                out[s, j, i] = spectrum[s, start + i] * weights[j, i]
            for i in range(hi, n_taps):
                out[s, j, i] = 0.0


@njit(cache=True)
def band_moments(c, m2, m4, first):
    """Means of ``|c|^2`` and ``|c|^4`` over the last axis of ``c`` (n_signals,
    n_bands, n_taps) into ``m2[:, first:first + n_bands]`` and ``m4[...]`` (in order
    within each band signal or not: the means do not depend on it).

    Four interleaved partial sums: independent additions (faster than one running sum,
    which waits on each addition) and a smaller rounding error.
    """
    n_signals, n_bands, n_taps = c.shape
    for s in range(n_signals):
        for j in range(n_bands):
            a0 = a1 = a2 = a3 = 0.0
            b0 = b1 = b2 = b3 = 0.0
            i = 0
            while i + 4 <= n_taps:
                v = c[s, j, i]
                p = v.real * v.real + v.imag * v.imag
                a0 += p
                b0 += p * p
                v = c[s, j, i + 1]
                p = v.real * v.real + v.imag * v.imag
                a1 += p
                b1 += p * p
                v = c[s, j, i + 2]
                p = v.real * v.real + v.imag * v.imag
                a2 += p
                b2 += p * p
                v = c[s, j, i + 3]
                p = v.real * v.real + v.imag * v.imag
                a3 += p
                b3 += p * p
                i += 4
            while i < n_taps:
                v = c[s, j, i]
                p = v.real * v.real + v.imag * v.imag
                a0 += p
                b0 += p * p
                i += 1
            m2[s, first + j] = ((a0 + a1) + (a2 + a3)) / n_taps
            m4[s, first + j] = ((b0 + b1) + (b2 + b3)) / n_taps
