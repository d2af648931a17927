"""Fault-band features: squared-envelope-spectrum lines at the bearing's fault frequencies.

For a bearing and shaft speed, the level of the squared envelope spectrum (SES) at
harmonics 1..H of BPFO, BPFI, BSF, the ball-defect frequency 2xBSF and FTF, and at the
shaft sidebands of each BPFI harmonic (an inner-race fault turns with the shaft, so
the load zone modulates its impacts at the shaft speed). Each level is the largest
SES value within a slip tolerance of the nominal line, relative to the local SES
background, in dB. These are the quantities a vibration analyst reads off an
envelope spectrum (Randall & Antoni 2011, section 3.4; Smith & Randall 2015).
"""

from __future__ import annotations

import math

import numpy as np

from ..bearing import Bearing
from ._validation import (
    check_flag,
    check_fs,
    check_nonnegative,
    check_positive_int,
    check_rpm,
    check_signal,
    to_unit_scale,
)
from .envelope import envelope_spectrum
from .shaft import without_shaft_lines

__all__ = [
    "FAULT_LINES",
    "as_bearing",
    "fault_band_names",
    "fault_band_levels",
    "fault_band_features",
]

#: Fault lines, in the order of the features: attribute names of BearingFrequencies.
FAULT_LINES = ("bpfo", "bpfi", "bsf", "ball_defect", "ftf")
#: Bins on each side of the search window left out of the background (the main lobe
#: of the Hann window is +-2 bins).
_GUARD_BINS = 2
#: Fewest background bins on each side of a line.
_MIN_BACKGROUND_BINS = 3


def fault_band_names(harmonics: int = 3) -> list[str]:
    """Names of the fault-band features, in the order they are returned.

    ``"<line>_<h>"`` for each line of :data:`FAULT_LINES` and harmonic ``h``, then
    ``"bpfi_<h>_lsb"`` / ``"bpfi_<h>_usb"`` for the lower and upper shaft sidebands
    (``h * BPFI -/+ shaft``).

    Examples
    --------
    >>> from ballpass.features import fault_band_names
    >>> fault_band_names(1)
    ['bpfo_1', 'bpfi_1', 'bsf_1', 'ball_defect_1', 'ftf_1', 'bpfi_1_lsb', 'bpfi_1_usb']
    """
    harmonics = check_positive_int("harmonics", harmonics, 1)
    names = [f"{line}_{h}" for line in FAULT_LINES for h in range(1, harmonics + 1)]
    names += [f"bpfi_{h}_{side}" for h in range(1, harmonics + 1) for side in ("lsb", "usb")]
    return names


def as_bearing(bearing) -> Bearing:
    """A :class:`ballpass.Bearing` from a catalogue name or a Bearing (returned as is)."""
    if isinstance(bearing, Bearing):
        return bearing
    if isinstance(bearing, str):
        return Bearing.catalog(bearing)
    raise TypeError(
        f"bearing must be a catalogue name (str) or a Bearing, got {type(bearing).__name__}"
    )


def _target_orders(bearing: Bearing, harmonics: int) -> np.ndarray:
    """Feature frequencies per unit shaft speed (orders), in feature-name order."""
    orders = bearing.frequencies(1.0)
    h = np.arange(1, harmonics + 1, dtype=float)
    lines = [getattr(orders, line) * h for line in FAULT_LINES]
    sidebands = np.stack([h * orders.bpfi - 1.0, h * orders.bpfi + 1.0], axis=-1).ravel()
    return np.concatenate(lines + [sidebands])


def _check_reach(harmonics: int, tolerance: float, background_hz: float | None,
                 bearing: Bearing, rpm, top_hz: float, n_bins: int) -> None:
    """Refuse, before any work, a tolerance of 1 or more (the search window would reach
    0 Hz), more harmonics than both the spectrum's ``n_bins`` bins and those whose
    lowest line's search window starts below its top ``top_hz`` (every line above is
    NaN: ``harmonics=10**9`` would allocate gigabytes) and, unless None, a background
    window wider than the spectrum."""
    if not tolerance < 1.0:
        raise ValueError(f"tolerance must be in [0, 1) (relative half-width of the search "
                         f"window; real slip is 0.01-0.02), got {tolerance!r}")
    if background_hz is not None and background_hz > top_hz:
        raise ValueError(f"background_hz must be at most the spectrum's top frequency, "
                         f"{top_hz:g} Hz, got {background_hz:g}")
    try:
        speeds = np.asarray(rpm, dtype=float)
    except (TypeError, ValueError):
        return  # check_rpm says what is wrong
    if speeds.size == 0 or not (np.isfinite(speeds).all() and (speeds > 0).all()):
        return  # check_rpm says what is wrong
    orders = bearing.frequencies(1.0)
    lowest = min(getattr(orders, line) for line in FAULT_LINES) * speeds.min() / 60.0
    fit = math.floor(top_hz / (lowest * (1.0 - tolerance)))
    most = max(1, fit, n_bins)
    if harmonics > most:
        raise ValueError(f"harmonics must be at most {most:,} here, the spectrum's bins: "
                         f"the search window of every line beyond harmonic {fit:,} of the "
                         f"lowest fault line ({lowest:.4g} Hz at {speeds.min():g} rpm) lies "
                         f"above the spectrum's top, {top_hz:g} Hz; got {harmonics:,}")


def fault_band_levels(
    freqs,
    ses,
    bearing,
    rpm,
    *,
    harmonics: int = 3,
    tolerance: float = 0.01,
    background_hz: float = 10.0,
    shaft_guard: bool = True,
) -> dict[str, np.ndarray]:
    """Levels of the fault lines in a given squared envelope spectrum, dB.

    For each target frequency ``f`` (see :func:`fault_band_names`):

    * line = the largest SES value in ``[f (1 - tolerance), f (1 + tolerance)]``
      (at least the bin nearest ``f``): rolling elements slip, so real fault lines
      sit up to 1-2 % away from the kinematic value;
    * background = the median SES value within ``background_hz`` on either side of
      that window (at least 3 bins each side), leaving out the window and 2 guard
      bins on each side (the Hann main lobe);
    * level = ``10 log10(line / background)``, dB (the SES is a power quantity);
    * with ``shaft_guard`` (default), the bins of shaft harmonics that stand 6 dB above
      their surroundings read as background first
      (:func:`ballpass.features.shaft.without_shaft_lines`, the envelope diagnoser's
      rule): a fault line within the slip window of a shaft harmonic (the 6203's 2xBSF
      is 0.3 % below 4x) would otherwise read the machine's shaft line as a fault.
      Without it, learned pipelines trained on simulations (which have no shaft lines)
      call real healthy machines faulty, and their transfer swings with the training
      SNR (docs/sim2real.md).

    Lines whose window lies above the highest frequency give NaN; a spectrum too short
    to hold any background bin gives 0 dB.

    Parameters
    ----------
    freqs : array_like, shape (n_bins,)
        Uniform frequency grid from 0 Hz, as returned by :func:`envelope_spectrum`.
    ses : array_like, shape (..., n_bins)
        Squared envelope spectrum (any unit^2).
    bearing : str or Bearing
        Catalogue name (``"6205"``) or a :class:`ballpass.Bearing`.
    rpm : float or array_like of shape (...)
        Shaft speed, rev/min: one for all spectra or one per spectrum.
    harmonics : int, optional
        Harmonics 1..H of each line (default 3); at most the spectrum's bins, or more
        if the lowest line's search window still starts below the top at H.
    tolerance : float, optional
        Relative half-width of the search window, in [0, 1) (default 0.01, i.e. 1 %
        slip).
    background_hz : float, optional
        Width of the background window on each side, Hz (default 10).
    shaft_guard : bool, optional
        Read shaft-harmonic lines as background (default True).

    Returns
    -------
    dict of str to ndarray of shape (...)
        Level of each feature, dB; NumPy scalars for a single spectrum.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import fault_band_levels
    >>> f = np.arange(2001) * 0.5                      # 0..1000 Hz, 0.5 Hz bins
    >>> ses = np.ones_like(f)
    >>> ses[np.argmin(abs(f - 107.5))] = 100.0         # a line at BPFO (6205, 1796 rpm)
    >>> levels = fault_band_levels(f, ses, "6205", 1796)
    >>> round(float(levels["bpfo_1"]), 1), round(float(levels["bpfi_1"]), 1)
    (20.0, 0.0)
    """
    freqs = np.asarray(freqs, dtype=float)
    ses = np.asarray(ses, dtype=float)
    if freqs.ndim != 1 or freqs.size < 2 or freqs[0] != 0.0 or ses.shape[-1:] != freqs.shape:
        raise ValueError(
            "freqs must be the 1-D uniform grid from 0 Hz of the spectrum (length of ses's "
            f"last axis), got freqs shape {freqs.shape} and ses shape {ses.shape}"
        )
    bearing = as_bearing(bearing)
    harmonics = check_positive_int("harmonics", harmonics, 1)
    tolerance = check_nonnegative("tolerance", tolerance)
    background_hz = check_nonnegative("background_hz", background_hz)
    shaft_guard = check_flag("shaft_guard", shaft_guard)
    rpm = check_rpm(rpm, ses.shape[:-1])
    # a background wider than a given spectrum is all of it (no bomb: the windows are
    # cut at its ends), as a spectrum cut below its Nyquist frequency may need
    _check_reach(harmonics, tolerance, None, bearing, rpm, freqs[-1], freqs.size)

    df = freqs[1]
    n_bins = freqs.size
    margin = max(math.ceil(background_hz / df), _MIN_BACKGROUND_BINS)
    targets = (rpm[..., None] / 60.0) * _target_orders(bearing, harmonics)
    flat_ses = np.ascontiguousarray(ses).reshape(-1, n_bins)
    if shaft_guard:
        shaft_hz = np.broadcast_to(rpm, ses.shape[:-1]).reshape(-1) / 60.0
        # Only the bins the line search reads need the guard, with every harmonic whose
        # guard or background window reaches them: one shaft spacing and one background
        # window beyond the highest line's window and background.
        reach = (targets.max() * (1.0 + tolerance) + (margin + _GUARD_BINS + 2) * df
                 + shaft_hz.max() + background_hz)
        top = min(n_bins, math.ceil(reach / df) + 1)
        flat_ses = np.concatenate([
            without_shaft_lines(freqs[:top], flat_ses[:, :top], shaft_hz, background_hz),
            flat_ses[:, top:]], axis=1)
    f = targets.reshape(-1, targets.shape[-1])
    # Search window [lo, hi] (bins): the slip tolerance, at least the nearest bin.
    in_range = f * (1.0 - tolerance) <= freqs[-1]
    f = np.where(in_range, f, 0.0)
    centre = np.round(f / df)
    lo = np.maximum(1, np.minimum(centre, np.ceil(f * (1.0 - tolerance) / df)))
    top = np.maximum(centre, np.floor(f * (1.0 + tolerance) / df))
    hi = np.maximum(lo, np.minimum(n_bins - 1, top))
    lo, hi = lo.astype(np.intp), hi.astype(np.intp)
    levels = np.full(f.shape, np.nan)
    tiny = np.finfo(float).tiny
    # Lines with a full background (margin bins on each side of the window, beyond the
    # guard bins), all at once; those cut by 0 Hz or the top of the spectrum below.
    start = lo - _GUARD_BINS - margin
    full = in_range & (start >= 1) & (hi + _GUARD_BINS + 1 + margin <= n_bins)
    if full.any():
        row = np.nonzero(full)[0] * n_bins
        a, b, start = row + lo[full], row + hi[full], row + start[full]
        each = np.arange(margin)
        background = flat_ses.ravel()[
            np.concatenate([start[:, None] + each, b[:, None] + _GUARD_BINS + 1 + each], axis=-1)
        ]
        line = np.maximum.reduceat(flat_ses.ravel(), np.stack([a, b + 1], axis=-1).ravel())[::2]
        floor = np.median(background, axis=-1)
        levels[full] = 10.0 * np.log10((line + tiny) / (floor + tiny))
    for row, j in zip(*np.nonzero(in_range & ~full), strict=True):
        spectrum, a, b = flat_ses[row], lo[row, j], hi[row, j]
        line = spectrum[a : b + 1].max()
        left = spectrum[max(1, a - _GUARD_BINS - margin) : max(1, a - _GUARD_BINS)]
        right = spectrum[b + _GUARD_BINS + 1 : b + _GUARD_BINS + 1 + margin]
        background = np.concatenate([left, right])
        floor = np.median(background) if background.size else line
        levels[row, j] = 10.0 * np.log10((line + tiny) / (floor + tiny))
    levels = levels.reshape(targets.shape)
    return {name: levels[..., j][()] for j, name in enumerate(fault_band_names(harmonics))}


def highest_fault_line(bearing, rpm, fs: float, harmonics: int = 3) -> np.ndarray:
    """Highest line the fault-band levels read, Hz: the envelope must carry it.

    ``harmonics`` times the highest defect frequency (BPFO, BPFI, 2xBSF) plus one shaft
    order (the sideband of a modulated line), capped just below ``fs / 2``. A
    demodulation band chosen by the kurtogram must lie above it (``fault_hz`` of
    :func:`ballpass.features.fast_kurtogram`).

    Parameters
    ----------
    bearing : Bearing
        The bearing.
    rpm : float or ndarray
        Shaft speed(s), rev/min.
    fs : float
        Sampling frequency, Hz.
    harmonics : int, optional
        Harmonics read (default 3, as :func:`fault_band_levels`).

    Returns
    -------
    ndarray, shape of ``rpm``
        Frequency, Hz.

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.features.bands import highest_fault_line
    >>> round(float(highest_fault_line(bp.Bearing.catalog("6205"), 1797.0, 12_000.0)))
    517
    """
    orders = _highest_fault_order(bearing, harmonics)
    shaft_hz = np.asarray(rpm, dtype=float) / 60.0
    return np.minimum(orders * shaft_hz, np.nextafter(fs / 2, 0))


def _highest_fault_order(bearing, harmonics: int) -> float:
    """Order (multiple of the shaft speed) of :func:`highest_fault_line`, uncapped:
    ``harmonics`` times the highest defect order (BPFO, BPFI, 2xBSF) plus one."""
    per_order = bearing.frequencies(1.0)  # every defect frequency scales with the speed
    return harmonics * max(per_order.bpfo, per_order.bpfi, per_order.ball_defect) + 1.0


def fault_band_features(
    x,
    fs: float,
    bearing,
    rpm,
    *,
    band=None,
    prewhiten: bool = False,
    harmonics: int = 3,
    tolerance: float = 0.01,
    background_hz: float = 10.0,
    shaft_guard: bool = True,
    axis: int = -1,
) -> dict[str, np.ndarray]:
    """Fault-band features of signals: SES levels at the bearing's fault lines, dB.

    :func:`envelope_spectrum` (squared, Hann window) followed by
    :func:`fault_band_levels`.

    Parameters
    ----------
    x : array_like, shape (..., n_samples)
        Signal(s), e.g. acceleration in m/s^2. The resolution ``fs / n_samples``
        sets how well lines are separated: 1 Hz (1 s records) resolves the BPFO,
        BPFI and sideband lines of a 6205 at 1800 rpm.
    fs : float
        Sampling frequency, Hz.
    bearing : str or Bearing
        Catalogue name or a :class:`ballpass.Bearing`.
    rpm : float or array_like of shape (...)
        Shaft speed, rev/min, one per signal or one for all.
    band : (float, float) or None, optional
        Demodulation band, Hz; ``None`` (default) chooses it per signal with the
        kurtogram, among bands above the highest line read (:func:`highest_fault_line`).
    prewhiten : bool, optional
        Cepstrum pre-whitening before demodulation (default False).
    harmonics, tolerance, background_hz, shaft_guard
        See :func:`fault_band_levels`; ``background_hz`` at most ``fs / 2``.
    axis : int, optional
        Sample axis (default -1).

    Returns
    -------
    dict of str to ndarray of shape (...)
        Level of each feature of :func:`fault_band_names`, dB.

    Examples
    --------
    Impacts at BPFO of a 6205 at 1796 rpm ringing a 3 kHz resonance:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.features import fault_band_features
    >>> fs, rpm = 12_000.0, 1796.0
    >>> bpfo = bp.Bearing.catalog("6205").frequencies(rpm / 60).bpfo
    >>> t = np.arange(24_000) / fs
    >>> phase = (t * bpfo) % 1.0 / bpfo                  # time since the last impact, s
    >>> x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    >>> x += 0.2 * np.random.default_rng(0).standard_normal(t.size)
    >>> feats = fault_band_features(x, fs, "6205", rpm)
    >>> bool(feats["bpfo_1"] > 10 > feats["bpfi_1"])
    True
    """
    xv = check_signal(x, axis)
    bearing = as_bearing(bearing)
    _check_reach(check_positive_int("harmonics", harmonics, 1),
                 check_nonnegative("tolerance", tolerance),
                 check_nonnegative("background_hz", background_hz), bearing, rpm,
                 check_fs(fs) / 2.0, xv.shape[-1] // 2 + 1)   # the SES's bins
    fault_hz = None
    if band is None:  # the kurtogram's band must carry the lines read
        fault_hz = highest_fault_line(bearing, check_rpm(rpm, xv.shape[:-1]), check_fs(fs),
                                      harmonics)
    # the levels are ratios: computed on a copy scaled exactly to unit peak, whose SES
    # neither overflows (1e200 m/s^2) nor underflows (1e-300)
    freqs, ses = envelope_spectrum(to_unit_scale(xv)[0], fs, band, squared=True,
                                   prewhiten=prewhiten, fault_hz=fault_hz)
    return fault_band_levels(
        freqs,
        ses,
        bearing,
        rpm,
        harmonics=harmonics,
        tolerance=tolerance,
        background_hz=background_hz,
        shaft_guard=shaft_guard,
    )
