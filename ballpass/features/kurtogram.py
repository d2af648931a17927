"""Spectral kurtosis and the fast kurtogram.

The spectral kurtosis (SK) of a signal is the kurtosis of its complex envelope in a
frequency band: about 0 for stationary Gaussian noise, large where repetitive
transients (bearing impacts ringing a structural resonance) dominate. The fast
kurtogram maps SK over centre frequency and bandwidth on Antoni's 1/3-binary tree and
picks the band that maximises it: the classic way to choose the demodulation band of
envelope analysis.

References
----------
.. [1] J. Antoni, "The spectral kurtosis: a useful tool for characterising
   non-stationary signals", MSSP 20 (2006) 282-307 (definition, eq. 8; estimator
   variance 4/K for K independent segments of Gaussian noise, section 4).
.. [2] J. Antoni, "Fast computation of the kurtogram for the detection of transient
   faults", MSSP 21 (2007) 108-124 (the 1/3-binary tree, levels k and k + log2(3) - 1,
   kurtosis of complex band signals E|c|^4 / (E|c|^2)^2 - 2).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import scipy.fft
import scipy.signal

from ._validation import (
    check_fs,
    check_nonnegative,
    check_positive_int,
    check_signal,
    to_unit_scale,
)

__all__ = ["KurtogramResult", "fast_kurtogram", "spectral_kurtosis"]

#: Bands whose mean power density lies more than this many dB below the signal's
#: average density carry no content (anti-aliasing roll-off, dead bands near Nyquist).
FLOOR_DB = -20.0
#: Narrowest band the automatic choice accepts, Hz: an envelope band must pass the
#: modulation sidebands of the fault frequencies (BPFI of a 6205 at 1800 rpm is 162 Hz).
MIN_BANDWIDTH_HZ = 300.0


@dataclass(frozen=True, eq=False)
class KurtogramResult:
    """Fast-kurtogram grid and the band it selects.

    Attributes
    ----------
    kurtosis : ndarray, shape (..., n_rows, n_cols)
        Spectral kurtosis of each band, each band's value repeated over the grid
        columns it spans (the layout of Antoni's figures). 0 for Gaussian noise.
    density_db : ndarray, shape (..., n_rows, n_cols)
        Mean power spectral density of each band relative to the signal's average
        density, dB.
    levels : ndarray, shape (n_rows,)
        Tree level of each row: 0, 1, 1.585, 2, 2.585, ..., nlevel. A row at level
        ``l`` splits ``[0, fs/2]`` into ``2**l`` bands.
    bandwidths : ndarray, shape (n_rows,)
        Bandwidth of the bands of each row, Hz.
    freqs : ndarray, shape (n_cols,)
        Centre frequency of each grid column, Hz.
    fs : float
        Sampling frequency, Hz.
    best_band : tuple of float or ndarray of shape (..., 2)
        ``(lo, hi)`` in Hz of the band with the largest kurtosis among the admissible
        ones (see :func:`fast_kurtogram`); an array for batched input.
    best_level, best_kurtosis : float or ndarray, shape (...)
        Level and kurtosis of that band.
    admissible : ndarray of bool, shape (..., n_rows, n_cols)
        Bands among which ``best_band`` was chosen (see :func:`fast_kurtogram`).
    floor_db : float
        Content threshold: bands with ``density_db < floor_db`` hold no content.

    Examples
    --------
    Impacts ringing at 3 kHz, 100 per second, in white noise:

    >>> import numpy as np
    >>> from ballpass.features import fast_kurtogram
    >>> fs = 12_000.0
    >>> t = np.arange(240) / fs
    >>> ring = np.exp(-600 * t) * np.sin(2 * np.pi * 3000 * t)
    >>> x = np.convolve(np.tile(np.r_[1.0, np.zeros(119)], 100), ring)[:12_000]
    >>> x += 0.1 * np.random.default_rng(0).standard_normal(x.size)
    >>> res = fast_kurtogram(x, fs)
    >>> res.kurtosis.shape == res.admissible.shape == (res.levels.size, res.freqs.size)
    True
    >>> bool(res.best_kurtosis == res.kurtosis[res.admissible].max())
    True
    """

    kurtosis: np.ndarray
    density_db: np.ndarray
    levels: np.ndarray
    bandwidths: np.ndarray
    freqs: np.ndarray
    fs: float
    best_band: tuple[float, float] | np.ndarray
    best_level: float | np.ndarray
    best_kurtosis: float | np.ndarray
    admissible: np.ndarray
    floor_db: float

    def plot(self, ax=None):
        """Draw the kurtogram heat map; see :func:`ballpass.plot.kurtogram`.

        Returns
        -------
        matplotlib.axes.Axes

        Examples
        --------
        >>> import numpy as np
        >>> from ballpass.features import fast_kurtogram
        >>> x = np.random.default_rng(0).standard_normal(4096)
        >>> ax = fast_kurtogram(x, fs=12_000.0).plot()
        >>> ax.get_xlabel()
        'Frequency (Hz)'
        """
        from ..plot import kurtogram

        return kurtogram(self, ax=ax)


#: Inverse FFTs of at least this many points run as two passes of short batched FFTs
#: (Bailey's four-step algorithm, see :func:`_band_signals`). Measured on the 2-core
#: machine of ``benchmarks/features_speed.py`` (1 MB of L2 cache per core): the
#: 36 015-point transform of the full band of 1 s at 48 kHz takes 0.6 ms, its
#: four-step form 0.3 ms; at 18 144 points and below the direct transform is as fast
#: or faster.
_FOUR_STEP_MIN = 32_768


class _Row(NamedTuple):
    """Frequency-domain plan of one row of the tree (see :func:`_tree`)."""

    starts: np.ndarray  # (n_bands,) first FFT bin each band gathers (< 0 below 0 Hz)
    w: np.ndarray  # (n_distinct, n_taps) weights of the n_taps bins from there ...
    which: np.ndarray  # (n_bands,) ... row of w of each band
    split: tuple[int, int, np.ndarray] | None  # four-step factors and twiddles, or None


class _Plan(NamedTuple):
    """Plan of the 1/3-binary tree for one signal length and rate (see :func:`_tree`)."""

    levels: np.ndarray  # (n_rows,) tree level of each row
    n_bands: np.ndarray  # (n_rows,) bands per row
    rows: list  # of _Row
    taps: np.ndarray  # (n_all,) n_taps of every band of every row, row after row
    w2: np.ndarray  # (n_all,) sum of w^2 of every band (Parseval)
    grid: np.ndarray  # (n_rows, n_cols) index into the n_all bands of each grid cell


def _four_step(n: int) -> tuple[int, int, np.ndarray]:
    """Factors ``n = n1 * n2`` (``n1`` the divisor nearest ``sqrt(n)`` from below) and
    the twiddles ``exp(2 pi i k1 n2 / n)``, shape ``(n1, n2)``, of :func:`_band_signals`."""
    n1 = max(d for d in range(1, math.isqrt(n) + 1) if n % d == 0)
    n2 = n // n1
    return n1, n2, np.exp((2j * np.pi / n) * np.outer(np.arange(n1), np.arange(n2)))


@functools.lru_cache(maxsize=16)
def _tree(n: int, fs: float, nlevel: int) -> _Plan:
    """Frequency-domain plan of the 1/3-binary tree for ``n`` samples at ``fs``.

    Per row, the first FFT bin each band gathers and the weights of its bins
    (raised-cosine edges; 0 outside ``[0, fs/2]``); per band, the number of taps and the
    sum of the squared weights; per grid cell, its band. Cached: the plan depends only
    on the signal length and rate.
    """
    n_bins = n // 2 + 1
    df = fs / n
    levels, n_bands = [0.0], [1]
    for k in range(1, nlevel + 1):
        if k > 1:
            levels.append(k - 2 + math.log2(3))
            n_bands.append(3 * 2 ** (k - 2))
        levels.append(float(k))
        n_bands.append(2**k)
    n_cols = math.lcm(*n_bands)
    rows, taps, w2, grid = [], [], [], []
    for nb in n_bands:
        width = 0.5 * fs / nb
        centres = (np.arange(nb) + 0.5) * width
        n_taps = scipy.fft.next_fast_len(math.ceil(1.5 * width / df) + 1)
        first = np.round((centres - 0.75 * width) / df).astype(np.int64)
        idx = first[:, None] + np.arange(n_taps)
        f = idx * df
        u = np.abs(f - centres[:, None]) / width
        # Raised-cosine edges, -6 dB at the band edges, so neighbouring bands sum to one.
        taper = 0.5 + 0.5 * np.cos(2 * np.pi * (u - 0.25))
        w = np.where(u <= 0.25, 1.0, np.where(u >= 0.75, 0.0, taper))
        w[0, f[0] < centres[0]] = 1.0  # no neighbour below 0 Hz ...
        w[-1, f[-1] > centres[-1]] = 1.0  # ... nor above fs/2
        w[(idx < 0) | (idx >= n_bins)] = 0.0
        split = _four_step(n_taps) if n_taps >= _FOUR_STEP_MIN else None
        # Bands whose centres sit alike on the bin grid share their weights (at 48 kHz
        # and 48 000 samples, 3 distinct rows of weights of 128 bands): less to store
        # and to read.
        distinct, which = np.unique(w, axis=0, return_inverse=True)
        rows.append(_Row(first, distinct, which.ravel(), split))
        grid.append(len(taps) + np.arange(n_cols) // (n_cols // nb))
        taps += [n_taps] * nb
        w2.append(np.sum(w**2, axis=-1))
    return _Plan(np.array(levels), np.array(n_bands), rows, np.array(taps, dtype=float),
                 np.concatenate(w2), np.array(grid))


def _band_signals(bands: np.ndarray, split) -> np.ndarray:
    """Inverse FFT of ``bands`` (``(..., n_taps)``, complex, contiguous; overwritten)
    along the last axis, each transform's output in an order of its own when ``split``
    is given.

    With ``split = (n1, n2, twiddles)`` the transform runs as Bailey's four-step
    algorithm: ``b[n2' + n2 n1']`` viewed as ``(n1, n2)``, inverse FFTs along ``n1``,
    a product with ``exp(2 pi i k1 n2' / n_taps)``, inverse FFTs along ``n2``, which
    leaves ``c[k1 + n1 k2]`` at ``[k1, k2]``: two passes of short batched transforms,
    faster than one long transform that outgrows the cache. The order does not matter
    to the moments of ``|c|^2``.
    """
    if split is None:
        return scipy.fft.ifft(bands, axis=-1, overwrite_x=True)
    n1, n2, twiddles = split
    a = scipy.fft.ifft(bands.reshape(bands.shape[:-1] + (n1, n2)), axis=-2, overwrite_x=True)
    a *= twiddles
    return scipy.fft.ifft(a, axis=-1, overwrite_x=True).reshape(bands.shape)


def _default_nlevel(n: int) -> int:
    """Levels such that the finest band keeps about 64 samples of complex envelope."""
    return int(min(7, max(0, math.floor(math.log2(n)) - 7)))


def fast_kurtogram(
    x,
    fs: float,
    *,
    nlevel: int | None = None,
    min_bandwidth: float = MIN_BANDWIDTH_HZ,
    floor_db: float = FLOOR_DB,
    fault_hz=None,
    axis: int = -1,
) -> KurtogramResult:
    """Fast kurtogram: spectral kurtosis on Antoni's 1/3-binary band tree.

    Row ``k`` splits ``[0, fs/2]`` into ``2**k`` equal bands and row
    ``k + log2(3) - 1`` into ``3 * 2**(k-1)`` bands ([2]_). For each band the complex
    envelope ``c`` is formed and its kurtosis ``E|c|^4 / (E|c|^2)^2 - 2`` (0 for Gaussian
    noise) is computed. The tree is evaluated in the frequency domain: one real FFT of
    the signal, then per row one batched inverse FFT of the bins each band gathers
    (raised-cosine band edges, -6 dB at the nominal edges, so the bands of a row sum
    to the analytic signal). Each band signal comes out sampled at the rate of its
    support (1.5 times its bandwidth), like the decimated outputs of Antoni's FIR tree,
    at a cost of one FFT-length of work per row (1 s at 48 kHz, 7 levels: about 4 ms on
    one core, ``benchmarks/features_speed.py``; the first call of a process loads two
    small compiled loops, 0.7 s, which numba compiles once per install, 2 s).

    The band returned as ``best_band`` maximises the kurtosis among *admissible*
    bands, those where the signal has content:

    * at least ``min_bandwidth`` wide: narrower bands cannot carry the fault
      modulation sidebands;
    * a mean power density no more than ``-floor_db`` dB below the signal's average
      density: this excludes the dead bands above an anti-aliasing filter, where a
      few spikes give enormous kurtosis (on the CWRU 12 kHz recordings the
      5.6-6 kHz band reaches kurtosis > 100);
    * not reaching ``fs/2``: the band hugging Nyquist holds the transition band of
      the recorder's (or a simulator's) anti-aliasing filter. On simulated signals its
      sharp broadband clicks reach high kurtosis while the resonance band gives a
      squared envelope spectrum with a fault line 9 dB stronger;
    * above the fault lines it must carry: envelope analysis demodulates a carrier
      (a structural resonance) that the impacts excite, so a band holding the fault
      frequencies themselves returns them, and the shaft harmonics beside them, as
      raw content, not as modulation. With ``fault_hz`` (the highest fault line the
      envelope spectrum is read at, e.g. three times the highest defect frequency)
      a band's lower edge must lie at or above it, so its centre lies at least half
      a bandwidth above the fault lines. Without ``fault_hz`` only the bands starting
      at 0 Hz are excluded (they have no carrier at all; on a CWRU inner-race record
      the band 0-375 Hz won, below the fault's own lines).

    The full band (level 0) is always admissible without ``fault_hz``; with it, only
    when no band above the fault lines is. Pass ``band`` explicitly to the envelope
    functions to demodulate anywhere else.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s), any unit. The mean is removed.
    fs : float
        Sampling frequency, Hz.
    nlevel : int, optional
        Number of binary levels (>= 0; ``2**nlevel <= n_samples / 2``). Default
        ``min(7, floor(log2(n_samples)) - 7)``, so the finest bands keep about 64
        samples of envelope.
    min_bandwidth : float, optional
        Narrowest admissible band for ``best_band``, Hz (default 300).
    floor_db : float, optional
        Content threshold for ``best_band``, dB relative to the average power
        density (default -20).
    fault_hz : float or array_like of shape (...), optional
        Highest fault-line frequency the envelope must carry, Hz (one value, or one
        per signal): bands whose lower edge lies below it are not admissible for
        ``best_band``. :func:`envelope_analysis` sets it from ``rpm`` and
        ``bearing``. Default: only bands starting at 0 Hz are excluded.
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    KurtogramResult
        ``.kurtosis`` grid, ``.levels``, ``.freqs``, ``.best_band``, ``.plot()``.

    See Also
    --------
    spectral_kurtosis : SK from the short-time Fourier transform.
    ballpass.features.envelope_spectrum : uses ``best_band`` when ``band=None``.

    References
    ----------
    .. [1] J. Antoni, MSSP 20 (2006) 282-307.
    .. [2] J. Antoni, MSSP 21 (2007) 108-124.

    Examples
    --------
    An impulse every 10 ms ringing a 3 kHz resonance, in white noise:

    >>> import numpy as np
    >>> from ballpass.features import fast_kurtogram
    >>> fs = 12_000.0
    >>> t = np.arange(12_000) / fs
    >>> ring = np.exp(-600 * t[:240]) * np.sin(2 * np.pi * 3000 * t[:240])
    >>> x = np.convolve(np.tile(np.r_[1.0, np.zeros(119)], 100), ring)[:12_000]
    >>> x += 0.1 * np.random.default_rng(0).standard_normal(x.size)
    >>> res = fast_kurtogram(x, fs)
    >>> lo, hi = res.best_band
    >>> bool(lo <= 3000 <= hi), res.kurtosis.shape
    (True, (12, 192))
    """
    fs = check_fs(fs)
    x = check_signal(x, axis, nonempty=True)
    n = x.shape[-1]
    if nlevel is None:
        nlevel = _default_nlevel(n)
    nlevel = check_positive_int("nlevel", nlevel, 0)
    if 2**nlevel > n / 2:
        raise ValueError(f"nlevel must satisfy 2**nlevel <= n_samples/2 = {n / 2:g}, got {nlevel}")
    min_bandwidth = check_nonnegative("min_bandwidth", min_bandwidth)
    if isinstance(floor_db, bool) or not isinstance(floor_db, (int, float, np.floating)):
        raise TypeError(f"floor_db must be a number of dB, got {floor_db!r}")
    if not math.isfinite(floor_db):
        raise ValueError(f"floor_db must be a finite number of dB, got {floor_db!r}")
    fault_hz = check_fault_hz(fault_hz, x.shape[:-1], fs)

    # scale-free: computed on a copy scaled exactly to unit peak (1e200 would overflow)
    return _kurtogram(to_unit_scale(x)[0], fs, nlevel, min_bandwidth, float(floor_db),
                      fault_hz)[0]


def check_fault_hz(fault_hz, batch_shape: tuple, fs: float):
    """Validate ``fault_hz`` of :func:`fast_kurtogram`: None, or finite values in
    ``[0, fs/2)`` broadcastable to the signals' batch shape; returned as an array of
    that shape (or None)."""
    if fault_hz is None:
        return None
    try:
        values = np.asarray(fault_hz, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"fault_hz must be a frequency (Hz) or an array of them, got "
                        f"{fault_hz!r}") from None
    if not np.all(np.isfinite(values)) or np.any(values < 0) or np.any(values >= fs / 2):
        raise ValueError(
            f"fault_hz must be finite frequencies in [0, fs/2 = {fs / 2:g}) Hz, got {fault_hz!r}"
        )
    try:
        return np.broadcast_to(values, batch_shape)
    except ValueError:
        raise ValueError(
            f"fault_hz must be one value or one per signal (shape {batch_shape}), "
            f"got shape {values.shape}"
        ) from None


def _kurtogram(
    x: np.ndarray, fs: float, nlevel: int, min_bandwidth: float, floor_db: float,
    fault_hz: np.ndarray | None = None,
) -> tuple[KurtogramResult, np.ndarray]:
    """Fast kurtogram of validated ``x`` (samples last), and the one-sided spectrum of
    ``x`` minus its mean (``scipy.fft.rfft``) it was computed from, for reuse.
    ``fault_hz``: validated, of the batch shape of ``x``, or None."""
    from ._kernels import band_moments, gather_bands  # numba, compiled on first use

    n = x.shape[-1]
    levels, n_bands, rows, taps, w2, grid = _tree(n, fs, nlevel)
    spectrum = scipy.fft.rfft(x - x.mean(axis=-1, keepdims=True), axis=-1)
    spec = spectrum.reshape(-1, spectrum.shape[-1])
    n_signals = spec.shape[0]
    mean_power = np.mean(spec.real**2 + spec.imag**2, axis=-1)[:, None]
    # Signal by signal (a batch row by row would stream every row's band signals of all
    # signals through memory), with one work buffer for all rows: the weighted bins of
    # the bands, transformed in place.
    work = np.empty(max(row.starts.size * row.w.shape[1] for row in rows), dtype=complex)
    m2, m4 = np.empty((n_signals, taps.size)), np.empty((n_signals, taps.size))
    for one, m2_one, m4_one in zip(spec, m2, m4, strict=True):
        first = 0
        for row in rows:
            bands = work[: row.starts.size * row.w.shape[1]].reshape(row.starts.size, -1)
            gather_bands(one, row.starts, row.w, row.which, bands)
            last = first + row.starts.size
            band_moments(np.ascontiguousarray(_band_signals(bands, row.split)),
                         m2_one[first:last], m4_one[first:last])
            first = last
    # Parseval: sum |bands|^2 = n_taps * sum |c|^2 = n_taps^2 * m2
    band_power = m2 * taps**2 / w2
    k = np.divide(m4, m2**2, out=np.full_like(m2, 2.0), where=m2 > 0) - 2.0
    ratio = np.divide(band_power, mean_power, out=np.zeros_like(m2), where=mean_power > 0)
    db = 10 * np.log10(np.maximum(ratio, 1e-300))
    kurt = k[:, grid].reshape(x.shape[:-1] + grid.shape)
    dens = db[:, grid].reshape(kurt.shape)
    n_cols = grid.shape[-1]

    bandwidths = 0.5 * fs / n_bands
    # Grid columns of each row's last band, the one that reaches fs/2.
    nyquist_band = np.arange(n_cols) >= n_cols - n_cols // n_bands[:, None]
    # lower edge of the band each grid cell belongs to, Hz
    low_edge = (np.arange(n_cols) // (n_cols // n_bands[:, None])) * bandwidths[:, None]
    if fault_hz is None:
        above_faults = low_edge > 0
    else:
        above_faults = low_edge >= fault_hz[..., None, None]
    ok = (dens >= floor_db) & ((bandwidths >= min_bandwidth)[:, None] & ~nyquist_band)
    ok = ok & above_faults
    if fault_hz is None:
        ok[..., 0, :] = True
    else:  # the full band holds the fault lines: only when no band above them has content
        ok[..., 0, :] |= ~ok.any(axis=(-2, -1))[..., None]
    flat = np.where(ok, kurt, -np.inf).reshape(x.shape[:-1] + (-1,))
    best = np.argmax(flat, axis=-1)
    row, col = np.divmod(best, n_cols)
    width = bandwidths[row]
    lo = (col // (n_cols // n_bands[row])) * width
    best_band = np.stack([lo, lo + width], axis=-1)
    best_k = np.take_along_axis(flat, best[..., None], axis=-1)[..., 0]
    if x.ndim == 1:
        best_band = (float(best_band[0]), float(best_band[1]))
        best_level, best_k = float(levels[row]), float(best_k)
    else:
        best_level = levels[row]
    return KurtogramResult(
        kurtosis=kurt,
        density_db=dens,
        levels=levels,
        bandwidths=bandwidths,
        freqs=(np.arange(n_cols) + 0.5) * (0.5 * fs / n_cols),
        fs=fs,
        best_band=best_band,
        best_level=best_level,
        best_kurtosis=best_k,
        admissible=ok,
        floor_db=float(floor_db),
    ), spectrum


def spectral_kurtosis(
    x,
    fs: float,
    *,
    nperseg: int = 256,
    noverlap: int | None = None,
    window="hann",
    axis: int = -1,
) -> tuple[np.ndarray, np.ndarray]:
    """Spectral kurtosis from the short-time Fourier transform.

    ``SK(f) = <|S(t, f)|^4> / <|S(t, f)|^2>^2 - 2`` averaged over the STFT segments
    that lie fully inside the signal ([1]_, eq. 8). For stationary Gaussian noise
    ``SK = 0``; with ``K`` non-overlapping segments its standard deviation is about
    ``2 / sqrt(K)`` ([1]_, section 4), so ``|SK| > 3 * 2 / sqrt(K)`` flags
    non-Gaussian (impulsive) content at roughly 99.7 % confidence. The 0 Hz and Nyquist
    bins of a real signal are real-valued; their reference is 3, not 2, so they too
    read 0 for Gaussian noise.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s), any unit.
    fs : float
        Sampling frequency, Hz.
    nperseg : int, optional
        Segment length, samples (default 256; frequency resolution ``fs / nperseg``).
    noverlap : int, optional
        Overlap between segments, samples (default ``nperseg // 2``). Overlap
        correlates the segments and widens the confidence bound above.
    window : str or tuple or array_like, optional
        Window, as accepted by :func:`scipy.signal.get_window` (default ``"hann"``).
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    freqs : ndarray, shape (nperseg // 2 + 1,)
        Frequencies, Hz.
    sk : ndarray, shape (..., nperseg // 2 + 1)
        Spectral kurtosis (dimensionless).

    References
    ----------
    .. [1] J. Antoni, MSSP 20 (2006) 282-307.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import spectral_kurtosis
    >>> x = np.random.default_rng(0).standard_normal(256 * 400)
    >>> f, sk = spectral_kurtosis(x, fs=1000.0, noverlap=0)
    >>> bool(np.all(np.abs(sk) < 5 * 2 / np.sqrt(400)))
    True
    """
    fs = check_fs(fs)
    x = to_unit_scale(check_signal(x, axis))[0]   # scale-free: |X|^4 neither overflows
    nperseg = check_positive_int("nperseg", nperseg, 2)
    noverlap = nperseg // 2 if noverlap is None else check_positive_int("noverlap", noverlap, 0)
    if noverlap >= nperseg:
        raise ValueError(f"noverlap must be < nperseg = {nperseg}, got {noverlap}")
    n = x.shape[-1]
    too_short = (f"x must span at least two full segments of nperseg = {nperseg} samples "
                 f"(hop {nperseg - noverlap}), got {n} samples")
    if nperseg > n:  # before the window is built: nperseg = 10**9 would allocate 8 GB
        raise ValueError(too_short)
    if isinstance(window, (str, tuple)):
        win = scipy.signal.get_window(window, nperseg)
    else:
        win = np.asarray(window, dtype=float)
    if win.shape != (nperseg,):
        raise ValueError(f"window must have nperseg = {nperseg} samples, got shape {win.shape}")
    stft = scipy.signal.ShortTimeFFT(win, hop=nperseg - noverlap, fs=fs, fft_mode="onesided")
    if stft.upper_border_begin(n)[1] - stft.lower_border_end[1] < 2:
        raise ValueError(too_short)
    p0, p1 = stft.lower_border_end[1], stft.upper_border_begin(n)[1]
    s = stft.stft(x, p0=p0, p1=p1, axis=-1)  # (..., n_freqs, n_segments)
    p = s.real**2 + s.imag**2
    m2 = p.mean(axis=-1)
    m4 = np.mean(p * p, axis=-1)
    reference = np.full(stft.f.shape, 2.0)
    reference[0] = 3.0
    if nperseg % 2 == 0:
        reference[-1] = 3.0
    out = np.broadcast_to(reference, m2.shape).copy()  # a silent bin reads 0
    sk = np.divide(m4, m2**2, out=out, where=m2 > 0) - reference
    return stft.f, sk
