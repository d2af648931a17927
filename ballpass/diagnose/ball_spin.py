"""The ball's smeared comb: 2xBSF read at the resolution the ball's own spin allows.

A race defect strikes at a rate the shaft and cage fix (BPFO = Z FTF, BPFI = Z (fr -
FTF)); on a 10 s record its squared envelope spectrum (SES) lines are one 0.1 Hz bin
wide. A defect on a ball strikes at twice the ball spin frequency, and the ball's spin
is not locked to anything: its axis wanders in three dimensions as it rolls in and out
of the load zone, and its spin speed with it (Randall & Antoni 2011, section 2.2, on
the rolling elements' random slip and why ball faults are the hardest to see). On the
CWRU drive-end 0.021 in ball record the SES bins round 2xBSF stand 5-7 dB above the
background over 137.9-141.0 Hz (0.1-2.3 % below the kinematic 141.1 Hz), while the
inner-race comb beside it (BPFI 161.9 Hz, +-fr) is one bin wide. Read at one bin, such
a line loses to noise; read on an SES averaged over one-second segments (Welch; 1 Hz
bins) it gathers its power into a bin or two and the background's scatter shrinks
with the number of segments.

:func:`smeared_ball_evidence` reads the 2xBSF harmonics so, in each candidate band of
:func:`ballpass.diagnose.evidence.candidate_bands`, leaving out every harmonic a race
family's line (carriers up to twice the harmonics read, with their +-1 FTF and +-2 fr
sidebands, :data:`RACE_SIDEBANDS`) or a standing-out shaft harmonic could explain
within its slip search and two bins (the Hann main lobe).

:func:`cage_modulation_db` asks the second question an expert asks of a 2xBSF line:
is it carried round the load zone by the cage? It band-passes the squared envelope
round the line (+-1.5 FTF, the line and its first cage sidebands), takes that
component's own squared envelope, and reads its spectrum at the cage rate FTF (and, for
comparison, at the shaft rate fr): a ball defect's impacts swell once per cage
revolution, a shaft-locked line once per shaft revolution.

Neither reading enters the verdict: on the shared CWRU records both read as high on
the healthy baseline as on the ball records (``benchmarks/diagnose_ball.py``, the
page's "expert's reading" table), so naming a ball by them would name the healthy
drive end too.

References
----------
R. B. Randall, J. Antoni, "Rolling element bearing diagnostics - A tutorial", MSSP 25
(2011) 485-520. P. D. Welch, IEEE Trans. Audio Electroacoust. 15 (1967) 70-73.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.signal

from ..features._validation import check_fs, check_nonnegative, check_signal
from ..features.bands import as_bearing
from ..features.demodulate import BandDemodulator
from ..features.shaft import shaft_line_bins

__all__ = ["RACE_SIDEBANDS", "SEGMENT_S", "SmearedBall", "averaged_ses", "cage_modulation_db",
           "smeared_ball_evidence"]

#: Welch segment of the averaged SES, s: 1 Hz bins, about the width of a ball line
#: smeared by 1 % of random slip at 100-300 Hz (the 2xBSF of a 6205 at 1797 rpm is
#: 141 Hz). Records shorter than three half-overlapping segments (2 s) are not read.
SEGMENT_S = 1.0
#: Sidebands of every race carrier a ball harmonic must keep clear of: ``(FTF, fr)``
#: orders, each ``-k..k``. +-1 FTF (load zone, cage) and +-2 fr: the CWRU inner-race
#: records carry +-2 fr, and the drive-end outer-race ones BPFO + fr in 2xBSF's
#: window (137.2 Hz against 141.1 Hz at 1796 rpm, 2.7 % below).
RACE_SIDEBANDS = (1, 2)


@dataclass(frozen=True)
class SmearedBall:
    """The ball's smeared-comb reading of a batch (:func:`smeared_ball_evidence`).

    Attributes
    ----------
    evidence_db : ndarray, shape (n,)
        Mean level of the readable 2xBSF harmonics in the best band, dB over the
        averaged SES's background; ``-inf`` where not judged (record shorter than
        three segments, or fewer than two harmonics clear of the races' lines).
    level_db : ndarray, shape (n, H)
        Level of each harmonic in that band, dB; NaN where left out.
    found_hz : ndarray, shape (n, H)
        Frequency of the bin that carried each harmonic, Hz.
    band_hz : ndarray, shape (n, 2)
        Band where the comb read highest, Hz.
    n_bands : ndarray of int, shape (n,)
        Bands with signal searched per row.
    """

    evidence_db: np.ndarray
    level_db: np.ndarray
    found_hz: np.ndarray
    band_hz: np.ndarray
    n_bands: np.ndarray


def _race_lines(orders: dict, harmonics: int) -> np.ndarray:
    """Orders of the race lines a ball harmonic must keep clear of."""
    k_ftf, k_fr = RACE_SIDEBANDS
    side = (np.arange(-k_ftf, k_ftf + 1)[:, None] * orders["ftf"]
            + np.arange(-k_fr, k_fr + 1)[None, :]).ravel()
    h = np.arange(1, 2 * harmonics + 1)
    return np.concatenate([(h[:, None] * orders[c] + side[None, :]).ravel()
                           for c in ("bpfo", "bpfi")])


def averaged_ses(demodulator: BandDemodulator, band, segment_s: float = SEGMENT_S):
    """Welch-averaged spectrum of the squared envelope of ``band``: ``(freqs, psd)``,
    Hann segments of ``segment_s`` overlapping by half, shapes (n_bins,) and (n, n_bins)."""
    rate, e = demodulator.squared_envelope(band)
    nper = max(8, round(segment_s * rate))
    return scipy.signal.welch(e, fs=rate, nperseg=nper, noverlap=nper // 2,
                              detrend="constant", axis=-1)


def smeared_ball_evidence(x, fs: float, bearing, shaft_hz, bands, has_signal, *,
                          harmonics: int = 3, slip: float = 0.02,
                          background_hz: float = 10.0, segment_s: float = SEGMENT_S,
                          set_aside_races: bool = True) -> SmearedBall:
    """The 2xBSF comb read on the averaged SES of each band (module notes).

    Per harmonic ``h`` of 2xBSF: ``10 log10(max over [h f (1 - slip) - 1 bin, h f (1 +
    slip / 4) + 1 bin] / median over that window +- background_hz)``; bins on a shaft
    harmonic standing out of the averaged SES read as background; a harmonic whose
    window, widened by two bins, holds a race line (:data:`RACE_SIDEBANDS`) is left
    out. The evidence is the mean of the readable harmonics' levels, the best band kept.

    Parameters
    ----------
    x : ndarray, shape (n, n_samples)
        Signals (already validated, e.g. by
        :func:`~ballpass.diagnose.evidence.envelope_evidence`).
    fs : float
        Sampling frequency, Hz.
    bearing : str or Bearing
    shaft_hz : ndarray, shape (n,)
        Shaft speed of each row, Hz (the speed the evidence used).
    bands : ndarray, shape (n_bands, 2)
        Candidate bands, Hz; ``has_signal`` (n, n_bands) marks those read per row.
    harmonics, slip, background_hz : optional
        As :func:`~ballpass.diagnose.evidence.envelope_evidence`.
    segment_s : float, optional
        Welch segment, s (default :data:`SEGMENT_S`).
    set_aside_races : bool, optional
        Leave out the harmonics a race line could explain (default True); False reads
        every harmonic, to see what stands there whatever explains it (on the 6205 the
        race rule leaves none: BPFO + fr, 4.585 orders, lies 2.7 % below 2xBSF, within
        its 2 % slip search and the 1 Hz bins' main lobe).

    Returns
    -------
    SmearedBall
    """
    fs = check_fs(fs)
    x = check_signal(x)
    if x.ndim != 2:
        raise ValueError(f"x must be (n_signals, n_samples), got shape {x.shape}")
    n, n_samples = x.shape
    shaft_hz = np.broadcast_to(np.asarray(shaft_hz, dtype=float), (n,))
    if not np.all(shaft_hz > 0):
        raise ValueError(f"shaft_hz must be > 0 (shaft speed per row, Hz), got {shaft_hz!r}")
    if not check_nonnegative("segment_s", segment_s) > 0:
        raise ValueError("segment_s must be > 0 (Welch segment, s), got 0")
    bands = np.asarray(bands, dtype=float).reshape(-1, 2)
    has_signal = np.asarray(has_signal, dtype=bool)
    if has_signal.shape != (n, len(bands)):
        raise ValueError(f"has_signal must be (n_signals, n_bands) = {(n, len(bands))}, "
                         f"got {has_signal.shape}")
    evidence = np.full(n, -np.inf)
    level_best = np.full((n, harmonics), np.nan)
    found_best = np.full((n, harmonics), np.nan)
    band_best = np.full((n, 2), np.nan)
    n_bands = has_signal.sum(axis=1)
    if n_samples / fs < 2.0 * segment_s or len(bands) == 0:
        return SmearedBall(evidence, level_best, found_best, band_best, n_bands)
    orders = as_bearing(bearing).frequencies(1.0).as_dict()
    h = np.arange(1, harmonics + 1, dtype=float)
    races = _race_lines(orders, harmonics)
    reach = float(np.max(shaft_hz)) * (harmonics * orders["ball_defect"] * (1 + slip) + 1.0)
    demodulator = BandDemodulator(x, fs, max_hz=reach + background_hz + 2.0 / segment_s)
    for k in np.flatnonzero(has_signal.any(axis=0)):
        freqs, psd = averaged_ses(demodulator, tuple(bands[k]), segment_s)
        df = freqs[1]
        half = math.ceil(background_hz / df)
        notch = shaft_line_bins(freqs, psd, shaft_hz, background_hz)
        for i in np.flatnonzero(has_signal[:, k]):
            f_b = h * orders["ball_defect"] * shaft_hz[i]
            lo = np.floor(f_b * (1 - slip) / df).astype(int) - 1
            hi = np.ceil(f_b * (1 + 0.25 * slip) / df).astype(int) + 1
            guard_lo, guard_hi = (lo - 2) * df / shaft_hz[i], (hi + 2) * df / shaft_hz[i]
            clear = ~((races[None, :] >= guard_lo[:, None])
                      & (races[None, :] <= guard_hi[:, None])).any(axis=1) | (
                          not set_aside_races)
            level = np.full(harmonics, np.nan)
            found = np.full(harmonics, np.nan)
            row = np.where(notch[i], np.nan, psd[i])  # shaft lines read as background
            for j in np.flatnonzero(clear & (hi + half < freqs.size)):
                background = np.nanmedian(row[max(1, lo[j] - half): hi[j] + half + 1])
                window = np.nan_to_num(row[lo[j]: hi[j] + 1], nan=background)
                level[j] = 10 * np.log10(window.max() / background)
                found[j] = (lo[j] + window.argmax()) * df
            if np.sum(np.isfinite(level)) < 2:
                continue
            ev = float(np.nanmean(level))
            if ev > evidence[i]:
                evidence[i], level_best[i], found_best[i] = ev, level, found
                band_best[i] = bands[k]
    return SmearedBall(evidence, level_best, found_best, band_best, n_bands)


def cage_modulation_db(demodulator: BandDemodulator, band, centre_hz, rates_hz, *,
                       cage_hz):
    """How strongly the component of the squared envelope at ``centre_hz`` swells at
    each rate of ``rates_hz``, dB over its background (module notes).

    The squared envelope of ``band`` (:meth:`BandDemodulator.squared_envelope`) is
    band-passed to ``centre_hz +- 1.5 cage_hz`` (rectangular in frequency: the line and
    its first cage sidebands), its squared magnitude taken, and that spectrum (Hann)
    read at each rate: the largest bin within +-2 % of the rate (or +-2 bins) over the
    median of the bins within 5 Hz outside that window.

    Parameters
    ----------
    demodulator : BandDemodulator
        Of one signal.
    band : (float, float)
        Demodulation band, Hz.
    centre_hz : float
        Line whose modulation is read, Hz (e.g. a 2xBSF harmonic found by
        :func:`smeared_ball_evidence`).
    rates_hz : sequence of float
        Modulation rates read, Hz (e.g. FTF and fr).
    cage_hz : float
        Cage rate FTF, Hz: half-width of the component is 1.5 times it.

    Returns
    -------
    ndarray, shape (len(rates_hz),)
        Level at each rate, dB.

    Examples
    --------
    Impacts at 2xBSF of a 6205 at 1797 rpm, swelling at FTF: the envelope of the
    2xBSF component reads its FTF line far above its shaft line:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.features.demodulate import BandDemodulator
    >>> from ballpass.diagnose.ball_spin import cage_modulation_db
    >>> fs, f = 12_000.0, bp.Bearing.catalog("6205").frequencies(1797 / 60)
    >>> t = np.arange(120_000) / fs
    >>> phase = (t * f.ball_defect) % 1.0 / f.ball_defect
    >>> x = (1 + np.cos(2 * np.pi * f.ftf * t)) * np.exp(-800 * phase) * np.sin(
    ...     2 * np.pi * 3000 * phase)
    >>> x = x + 0.5 * np.random.default_rng(0).standard_normal(t.size)
    >>> ftf_db, fr_db = cage_modulation_db(BandDemodulator(x, fs, max_hz=600.0),
    ...                                    (2000, 4000), f.ball_defect,
    ...                                    [f.ftf, f.shaft], cage_hz=f.ftf)
    >>> bool(ftf_db > 20.0 and ftf_db > fr_db + 6.0)
    True
    """
    for name, value in (("centre_hz", centre_hz), ("cage_hz", cage_hz)):
        if not check_nonnegative(name, value) > 0:
            raise ValueError(f"{name} must be > 0 Hz, got {value!r}")
    rates = np.atleast_1d(np.asarray(rates_hz, dtype=float))
    if rates.ndim != 1 or rates.size == 0 or not np.all(rates > 0):
        raise ValueError(f"rates_hz must be one or more rates > 0 Hz, got {rates_hz!r}")
    rate, e = demodulator.squared_envelope(band)
    if e.shape[0] != 1:
        raise ValueError(f"demodulator must hold one signal, got {e.shape[0]}")
    e = e[0] - e[0].mean()
    spectrum = np.fft.rfft(e)
    f = np.fft.rfftfreq(e.size, 1.0 / rate)
    keep = np.abs(f - float(centre_hz)) <= 1.5 * float(cage_hz)
    z = np.fft.ifft(np.where(keep, 2.0 * spectrum, 0.0), n=e.size)
    a = np.abs(z) ** 2
    power = np.abs(np.fft.rfft((a - a.mean()) * np.hanning(a.size))) ** 2
    out = []
    for r in rates:
        near = np.abs(f - r) <= max(0.02 * r, 2.0 * f[1])
        around = (np.abs(f - r) <= 5.0 + max(0.02 * r, 2.0 * f[1])) & ~near
        out.append(10.0 * np.log10(power[near].max() / np.median(power[around])))
    return np.array(out)
