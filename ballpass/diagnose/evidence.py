"""Fault-family evidence in the squared envelope spectrum, band chosen by that evidence.

A localized fault announces itself in the squared envelope spectrum (SES) as a *family*
of lines whose spacing the bearing's kinematics fix (Randall & Antoni [1]_, section
3.4; Smith & Randall [2]_):

* **outer race**: harmonics of BPFO. The fault sits still; where the load zone or a
  misalignment modulates its impacts at the cage speed, +-FTF sidebands appear (Smith
  & Randall find them 12-16 dB above the background on CWRU outer-race records), but
  the carriers stand clearly above them;
* **inner race**: harmonics of BPFI with sidebands at +-1x the shaft speed;
* **rolling element**: harmonics of the ball-defect frequency 2xBSF with sidebands at
  +-FTF: the cage carries the defect round the load zone, and carriers standing more
  than 6 dB above their sidebands are not a ball comb (:mod:`ballpass.diagnose.ball`).

Three traps make a naive family score fail on real machines, and each has a rule here:

1. **Shared lines.** For a 6205, 2xBPFI (10.830 orders) and 3xBPFO (10.754) fall
   in one slip window, and so do 2x2xBSF+FTF (9.825) and 2xBPFI-fr (9.830). A line
   that another family's lines can explain within the slip search and the frequency
   resolution is left out of *both* families (:func:`shared_lines`): a family is
   judged by the lines only it explains, so a race fault's comb cannot feed the ball
   score nor a ball comb a race's.
2. **Shaft harmonics.** The 6203 has each defect frequency within 2 % of a shaft
   harmonic (2xBSF 3.988, BPFI 4.947, BPFO 3.053 orders) and a healthy machine's SES
   carries shaft harmonics. Where a shaft harmonic stands out in the SES (6 dB above
   its background; where a bin is wider than 0.25 % of the harmonic, judged in the bin
   nearest it, so that a fault line 1.5 bins away cannot raise it:
   :func:`~ballpass.features.shaft.shaft_line_bins`),
   the bins closer to it than the SES can resolve (3 bins: the Hann
   main lobe of +-2 bins plus the +-1 bin line window; at least 0.25 % of its
   frequency) read as background, so a family line that lands on it counts for
   nothing. Long records resolve them: 10 s gives 0.1 Hz bins.
3. **Ball comb vs outer race.** BPFO = Z x FTF, so a ball fault, modulated at FTF,
   fills the FTF comb and puts a line at BPFO too; that line stands no higher than its
   +-FTF neighbours. The outer-race family is marked down only by how far its
   sidebands come within :data:`OUTER_SIDEBAND_MARGIN_DB` of its carriers, so the
   sidebands of real outer-race faults do not refute them.

The evidence is built in stages, each a function that can be read and tested alone:

1. **candidate bands** (:func:`candidate_bands`): the bands of the 1/3-binary tree that
   can carry the lines, hold signal, and end below the anti-aliasing roll-off
   (:data:`ALIAS_FREE_FRACTION`); each is demodulated from its own bins
   (:class:`ballpass.features.demodulate.BandDemodulator`);
2. **line readings** (:func:`line_readings`): each family's lines, carriers and
   sidebands, read over the band's SES background at every common slip scale;
3. **family scores** (:func:`family_scores`): one score per family and scale from its
   readings (the rules below), the scale fitted on the carriers, the best band kept
   (:func:`envelope_evidence`, which also checks the speed);
4. **thresholds and verdict**: :class:`ballpass.diagnose.EnvelopeDiagnoser`.

The demodulation band is chosen *by fault evidence* (the idea of the IESFOgram of
Mauricio et al. [3]_ and of pybearing's harmonic-energy band search): every band of
Antoni's 1/3-binary tree wide enough to carry the family's lines, above the
low-frequency content and with signal in it, is demodulated, and each family keeps the
band where it reads highest.

References
----------
.. [1] R. B. Randall, J. Antoni, "Rolling element bearing diagnostics - A tutorial",
   MSSP 25 (2011) 485-520.
.. [2] W. A. Smith, R. B. Randall, "Rolling element bearing diagnostics using the Case
   Western Reserve University data: A benchmark study", MSSP 64-65 (2015) 100-131.
.. [3] A. Mauricio, W. A. Smith, R. B. Randall, J. Antoni, K. Gryllias, "Improved
   envelope spectrum via feature optimisation-gram (IESFOgram)", MSSP 144 (2020) 106891.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from ..features._validation import (
    check_band,
    check_fs,
    check_nonnegative,
    check_positive_int,
    check_rpm,
    check_signals,
    to_unit_scale,
)
from ..features.bands import _check_reach, as_bearing
from ..features.demodulate import BandDemodulator
from ..features.kurtogram import FLOOR_DB
from ..features.shaft import SHAFT_GUARD_BINS, SHAFT_GUARD_RELATIVE, shaft_line_bins
from .ball import cage_shortfall_db
from .speed import estimate_shaft_speed, fault_comb

__all__ = [
    "ALIAS_FREE_FRACTION",
    "COLLISION_BINS",
    "FAULT_FAMILIES",
    "OUTER_SIDEBAND_MARGIN_DB",
    "EnvelopeEvidence",
    "LineReadings",
    "candidate_bands",
    "envelope_evidence",
    "family_lines",
    "family_scores",
    "line_readings",
    "shaft_resolving_length",
    "shared_lines",
]

#: fault -> (carrier line, sideband spacing, do sidebands support (+1) the fault or
#: only mark it down when they rival the carriers (-1)), as BearingFrequencies names.
FAULT_FAMILIES = {
    "outer": ("bpfo", "ftf", -1),
    "inner": ("bpfi", "shaft", +1),
    "ball": ("ball_defect", "ftf", +1),
}
#: An outer-race carrier stands at least this far above its +-FTF neighbours, dB
#: (a factor 4 in SES power); closer, the line may be a member of a ball fault's FTF
#: comb and the outer-race evidence is marked down by the shortfall.
OUTER_SIDEBAND_MARGIN_DB = 6.0
#: A shaft-harmonic comb must stand this high (median of its ten harmonics above the
#: spectrum's background, dB) to correct the stated speed. Noise alone reads a few dB
#: at the best of the candidate speeds; the whole CWRU records read 22-37 dB, the
#: MFPT records 15 dB.
MIN_COMB_DB = 10.0
#: A speed proposed by the shaft-harmonic comb is used unless the strongest family's
#: evidence falls by at least this much there (dB, a factor 2 in SES power): a
#: correction that loses a fault is a fault's own comb taken for the shaft's (see
#: :mod:`ballpass.diagnose.speed`). Without a fault the strongest evidence of two
#: speeds differs by noise alone: 0.3 dB standard deviation, at most 1.2 dB, over 60
#: noise records of 2 and 10 s; the false combs of the CWRU fan-end outer-race segments
#: lose 4.7-13.8 dB, the right corrections (MFPT) at most 0.1 dB. The rule holds for a
#: correction no fault rate's divisor explains too: an inner-race fault's lines (BPFI
#: harmonics and their shaft sidebands) are dense enough to make a comb of their own (a
#: simulated 6205 at 600 rpm, 30 dB SNR, 2 s: 11-12 dB at 2.3 % below the true speed).
SPEED_KEEP_DB = 3.0
#: Shortest record on which any correction of the speed is checked, s: at coarser than
#: 0.5 Hz resolution a fault's own raw-spectrum harmonics pass for a shaft comb and the
#: evidence cannot tell them (the 6203's BPFO is 1.8 % from 3x: one-second segments of
#: the CWRU fan-end outer-race records lock onto BPFO / 3). Shorter records check only
#: the corrections no fault rate's divisor explains
#: (:func:`ballpass.diagnose.speed.fault_comb`: on a 6205 every one within 4 % at 1797
#: rpm); where one could, diagnose the whole record, or pass its speed to its segments.
SPEED_CHECK_S = 2.0
#: The +-FTF sidebands are resolved from their carrier on records of at least this
#: many cage periods (1 / FTF): 4 SES bins, the Hann main lobe (+-2 bins) plus the
#: +-1 bin line window. Shorter, a carrier's own leakage reads as its sidebands: the
#: ball family (told by its +-FTF sidebands) is not judged, and the outer race, which
#: only needs them to be told from a ball comb, is judged on its carriers alone.
FTF_RESOLVED_CAGE_PERIODS = 4.0
#: Highest frequency a demodulation band may reach, as a fraction of the sampling rate:
#: the alias-free bandwidth of a vibration analyser is fs / 2.56 (51.2 kHz for 20 kHz,
#: the convention of acquisition hardware, whose anti-aliasing filter rolls off between
#: there and fs/2). Above it the signal is the filter's transition band, attenuated and
#: possibly aliased: a band there carries no evidence of the machine.
ALIAS_FREE_FRACTION = 1.0 / 2.56
#: Two lines of different families closer than this many SES bins (where that is more
#: than half the slip search) are not told apart: each is read within +-1 bin, so two windows
#: overlap from 2 bins on (see :func:`shared_lines`).
COLLISION_BINS = 2.0
#: Fewest unshared carriers a family needs to be judged.
MIN_CARRIERS = 2
#: The scale search reaches ``UPWARD * slip`` above the kinematic frequencies: slip only
#: lowers them, the margin absorbs the speed's own uncertainty once it has been checked
#: against the shaft-harmonic comb (about 0.2 %).
UPWARD = 0.25
#: Rows (signals x bands) scored in one vectorised pass; bounds the memory of a batch.
ROWS_PER_BATCH = 256
_SYMBOL = {"bpfo": "BPFO", "bpfi": "BPFI", "ball_defect": "2xBSF", "shaft": "fr", "ftf": "FTF"}


def family_lines(fault: str, harmonics: int) -> list[tuple[str, int, int]]:
    """Lines of a family as ``(name, harmonic, side)``; side -1/0/+1 is the sideband.

    Examples
    --------
    >>> from ballpass.diagnose.evidence import family_lines
    >>> family_lines("inner", 1)
    [('1xBPFI', 1, 0), ('1xBPFI-fr', 1, -1), ('1xBPFI+fr', 1, 1)]
    """
    carrier, modulation, _ = FAULT_FAMILIES[fault]
    lines = []
    for h in range(1, harmonics + 1):
        lines.append((f"{h}x{_SYMBOL[carrier]}", h, 0))
        lines.append((f"{h}x{_SYMBOL[carrier]}-{_SYMBOL[modulation]}", h, -1))
        lines.append((f"{h}x{_SYMBOL[carrier]}+{_SYMBOL[modulation]}", h, +1))
    return lines


def _line_orders(fault: str, harmonics: int, orders: dict) -> np.ndarray:
    """Orders (multiples of the shaft speed) of the lines of :func:`family_lines`."""
    carrier, modulation, _ = FAULT_FAMILIES[fault]
    return np.array([h * orders[carrier] + side * orders[modulation]
                     for _, h, side in family_lines(fault, harmonics)])


def shared_lines(orders: dict, harmonics: int, slip: float,
                 resolution: float = 0.0, ball_judged: bool = True) -> dict:
    """Per family, a bool per line of :func:`family_lines`: True where the line collides
    with another family's, so that one fault could feed both families' scores.

    Two lines ``a`` and ``b`` (orders) collide when ``|a - b| <= max(slip max(a, b) /
    2, resolution)``: within half the slip search (a common slip moves both the same
    way), or, on records too short to resolve that, within the frequency resolution in
    orders (2 bins: the two lines' +-1 bin windows overlap). A
    carrier collides with another family's carriers up to harmonic ``2 harmonics`` (a
    family's higher harmonics are as strong as the ones read) and is left out with its
    sidebands; any line, carrier or sideband, also collides with the lines another
    family reads (harmonics 1..``harmonics``, carriers and sidebands) where one of the
    two families is the ball, and a carrier left out so takes its sidebands with it.
    Between the two races only carriers are compared: their sidebands differ in
    spacing (fr against FTF) and a race fault is named by its carriers. On the 6205,
    2x2xBSF+FTF (9.825 orders) and 2xBPFI-fr (9.830) leave both the ball and the inner
    race: a race-family comb cannot feed the ball score, nor a ball comb the race's.

    Parameters
    ----------
    orders : dict
        ``BearingFrequencies.as_dict()`` at a shaft speed of 1 Hz.
    harmonics : int
        Harmonics read per family.
    slip : float
        Largest relative slip searched.
    resolution : float, optional
        Frequency resolution in orders, ``bins / (T fr)`` (default 0).
    ball_judged : bool, optional
        False on records too short to resolve the +-FTF sidebands, where the ball is
        not judged: there is no ball score to keep clean, and only carriers are
        compared (default True).

    Returns
    -------
    dict of str to ndarray of bool, shape (3 harmonics,)

    Examples
    --------
    >>> import ballpass as bp
    >>> from ballpass.diagnose.evidence import shared_lines, family_lines
    >>> orders = bp.Bearing.catalog("6205").frequencies(1.0).as_dict()
    >>> shared = shared_lines(orders, 3, 0.02)
    >>> [name for (name, _, _), s in zip(family_lines("ball", 3), shared["ball"]) if s]
    ['2x2xBSF+FTF']
    """
    shared = {}
    for fault in FAULT_FAMILIES:
        others = [f for f in FAULT_FAMILIES if f != fault]
        mine = _line_orders(fault, harmonics, orders)
        side = np.array([s for _, _, s in family_lines(fault, harmonics)])
        # Line against line between the ball and a race; race against race, carriers.
        read = np.concatenate([_line_orders(f, harmonics, orders) for f in others
                               if ball_judged and "ball" in (f, fault)] or [np.empty(0)])
        carriers = np.concatenate([orders[FAULT_FAMILIES[f][0]] * np.arange(1, 2 * harmonics + 1)
                                   for f in others])
        hit_line = _collide(mine, read, slip, resolution)
        hit_carrier = _collide(mine[side == 0], carriers, slip, resolution) | hit_line[side == 0]
        shared[fault] = hit_line | np.repeat(hit_carrier, 3)
    return shared


def _collide(mine: np.ndarray, others: np.ndarray, slip: float, resolution: float):
    """True per ``mine`` where some line of ``others`` lies within the collision window."""
    gap = np.abs(mine[:, None] - others[None, :])
    window = np.maximum(0.5 * slip * np.maximum(mine[:, None], others[None, :]), resolution)
    return (gap <= window).any(axis=1)


@dataclass(frozen=True, eq=False)
class EnvelopeEvidence:
    """Fault-family evidence of a batch of signals (see :func:`envelope_evidence`).

    Attributes
    ----------
    evidence_db : dict of str to ndarray, shape (n_signals,)
        For ``"outer"``, ``"inner"``, ``"ball"``: the family's evidence, dB above the
        SES background (``-inf`` where the family cannot be judged).
    levels_db : dict of str to ndarray, shape (n_signals, n_lines)
        Level of each line at the best-fitting scale, dB above the local background;
        NaN for a line left out (shared with another family, on a shaft harmonic, or
        above the SES's highest frequency).
    found_hz, nominal_hz : dict of str to ndarray, shape (n_signals, n_lines)
        Frequency of the SES bin that carried each line, and its kinematic frequency
        at the speed used, Hz.
    shared : dict of str to ndarray of bool, shape (n_lines,)
        Lines left out because another family's lines explain them (:func:`shared_lines`).
    on_shaft : dict of str to ndarray of bool, shape (n_signals, n_lines)
        Lines that fell on a shaft harmonic (or a harmonic of the supply frequency
        ``line_hz``, where given) standing out of the SES and read as background (rule
        2 of the module notes).
    scale : dict of str to ndarray, shape (n_signals,)
        Best-fitting ratio of measured to kinematic frequencies (1 - slip .. 1 + slip/4).
    line_names : dict of str to list of str
        Names of the lines, e.g. ``"2xBPFI-fr"``.
    band_hz : dict of str to ndarray, shape (n_signals, 2)
        Demodulation band where each family read highest, Hz.
    n_bands : ndarray of int, shape (n_signals,)
        Number of candidate bands with signal searched in each row.
    n_readings : ndarray of int, shape (n_signals,)
        Number of family scores the search read in each row (bands with signal x
        judged families x slip scales, both speeds where the speed check searched a
        second one): the size of the search whose maximum the evidence is
        (:func:`ballpass.diagnose.rules.noise_probability`).
    rpm : ndarray, shape (n_signals,)
        Shaft speed used, rev/min.
    rpm_stated : ndarray, shape (n_signals,)
        Speed given by the caller, rev/min.
    speed_corrected : ndarray of bool, shape (n_signals,)
        True where the speed was corrected from the signal's shaft-harmonic comb.
    rpm_comb : ndarray, shape (n_signals,)
        Speed the shaft-harmonic comb proposed instead of the stated one, rev/min
        (used where ``speed_corrected``); NaN where it proposed none.
    duration_s : float
        Record length, s.

    Examples
    --------
    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.diagnose import envelope_evidence
    >>> fs, rpm = 12_000.0, 1797.0
    >>> bpfo = bp.Bearing.catalog("6205").frequencies(rpm / 60).bpfo
    >>> t = np.arange(12_000) / fs
    >>> phase = (t * bpfo) % 1.0 / bpfo                       # time since the last impact, s
    >>> x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    >>> x = x + 0.2 * np.random.default_rng(0).standard_normal(t.size)
    >>> ev = envelope_evidence(x, fs, "6205", rpm)
    >>> max(ev.evidence_db, key=lambda family: ev.evidence_db[family][0])
    'outer'
    >>> ev.line_names["outer"][:3], ev.levels_db["outer"].shape
    (['1xBPFO', '1xBPFO-FTF', '1xBPFO+FTF'], (1, 9))
    """

    evidence_db: dict
    levels_db: dict
    found_hz: dict
    nominal_hz: dict
    shared: dict
    on_shaft: dict
    scale: dict
    line_names: dict
    band_hz: dict
    n_bands: int
    n_readings: np.ndarray
    rpm: np.ndarray
    rpm_stated: np.ndarray
    speed_corrected: np.ndarray
    rpm_comb: np.ndarray
    duration_s: float


def candidate_bands(x: np.ndarray, fs: float, lowest_hz: float, *, max_level: float = 5.0,
                    power=None):
    """Bands of Antoni's 1/3-binary tree fit to demodulate, and which rows hold signal.

    A band qualifies when it is at least ``lowest_hz`` wide (its squared envelope
    holds the fault lines up to that frequency), starts at or above ``lowest_hz``
    (above the fault lines' own low-frequency harmonics and the shaft harmonics, whose
    beats would otherwise write their spacing into the SES: a healthy bearing's
    varying-compliance vibration at BPFO has no high-frequency carrier) and ends at or
    below :data:`ALIAS_FREE_FRACTION` ``fs`` (``fs / 2.56``: above it lies the
    anti-aliasing filter's roll-off, which carries no evidence). It holds signal in a
    row when its mean power density is no more than -:data:`FLOOR_DB` dB below the
    row's average density (the kurtogram's content floor).

    Parameters
    ----------
    x : ndarray, shape (n_signals, n_samples)
    fs : float
        Hz.
    lowest_hz : float
        Highest fault line the SES must carry, Hz.
    max_level : float, optional
        Finest tree level considered (default 5).
    power : ndarray, shape (n_signals, n_samples // 2 + 1), optional
        Power spectrum of the mean-removed ``x`` if already computed.

    Returns
    -------
    bands : ndarray, shape (n_bands, 2)
        ``(lo, hi)`` of each band, Hz; possibly empty.
    has_signal : ndarray of bool, shape (n_signals, n_bands)

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.diagnose.evidence import candidate_bands
    >>> x = np.random.default_rng(0).standard_normal((1, 12_000))
    >>> bands, ok = candidate_bands(x, 12_000.0, 840.0)
    >>> bands[:3].tolist(), bool(ok.all())
    ([[2000.0, 4000.0], [1500.0, 3000.0], [3000.0, 4500.0]], True)
    """
    if power is None:
        power = np.abs(scipy.fft.rfft(x - x.mean(axis=-1, keepdims=True), axis=-1)) ** 2
    df = fs / x.shape[-1]
    mean = power.mean(axis=-1) + 1e-300
    bands, ok = [], []
    levels = [1.0]
    for k in range(2, int(max_level) + 1):
        levels += [k - 2 + math.log2(3), float(k)]
    for level in levels:
        n_bands = round(2**level)
        width = 0.5 * fs / n_bands
        if width < lowest_hz:
            continue
        for j in range(n_bands):
            lo, hi = j * width, (j + 1) * width
            if lo < lowest_hz or hi > ALIAS_FREE_FRACTION * fs:
                continue
            dens = power[:, int(lo / df) : int(hi / df) + 1].mean(axis=-1)
            bands.append((lo, hi))
            ok.append(10 * np.log10(dens / mean + 1e-300) >= FLOOR_DB)
    bands = np.array(bands, dtype=float).reshape(-1, 2)
    has_signal = np.array(ok, dtype=bool).T.reshape(len(x), len(bands))
    return bands, has_signal


@dataclass(frozen=True)
class LineReadings:
    """Stage 2 of the evidence: one family's lines read in one band's SES at every
    common scale of its kinematic frequencies (see :func:`line_readings`).

    Attributes
    ----------
    fault : str
        ``"outer"``, ``"inner"`` or ``"ball"``.
    scales : ndarray, shape (S,)
        Ratios of measured to kinematic frequencies searched.
    level_db : ndarray, shape (n, S, L)
        Largest SES bin within +-1 bin of each line over its background, dB; NaN for
        a line left out (shared, or beyond the spectrum).
    on_bin_db : ndarray, shape (n, S, L)
        The same for the line's nearest bin alone, dB (the scale fit's sharpness).
    found_hz : ndarray, shape (n, S, L)
        Frequency of the bin that carried each line, Hz.
    on_shaft : ndarray of bool, shape (n, S, L)
        Lines that fell on a shaft harmonic standing out of the SES.
    side : ndarray, shape (L,)
        -1, 0, +1: lower sideband, carrier, upper sideband.
    n_carriers : int
        Carriers not shared with another family.
    """

    fault: str
    scales: np.ndarray
    level_db: np.ndarray
    on_bin_db: np.ndarray
    found_hz: np.ndarray
    on_shaft: np.ndarray
    side: np.ndarray
    n_carriers: int


def line_readings(ses, notch, df, shaft_hz, orders, fault, harmonics, slip, background_hz,
                  shared) -> LineReadings:
    """Read one family's lines in SES rows ``ses`` (n, n_bins) at speeds ``shaft_hz`` (Hz).

    For each common scale ``s`` in ``[1 - slip, 1 + UPWARD slip]`` (steps of half a bin
    at the highest harmonic) and each line of :func:`family_lines`: ``10 log10(max SES
    within +-1 bin / background)``, the background the median SES over the line's slip
    search +- ``background_hz``. Bins on a shaft harmonic that stands out (``notch``,
    (n, n_bins) bool) read as background (0 dB); ``shared`` marks the lines another
    family explains (:func:`shared_lines`), left out: (3H,) one per line, or (H,) one
    per carrier, left out with its sidebands.

    Examples
    --------
    A flat SES with one line at 1xBPFO of a 6205 at 30 Hz shaft speed:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.diagnose.evidence import line_readings
    >>> orders = bp.Bearing.catalog("6205").frequencies(1.0).as_dict()
    >>> ses = np.ones((1, 2000)); ses[0, round(30 * orders["bpfo"] / 0.5)] = 100.0
    >>> r = line_readings(ses, np.zeros(ses.shape, bool), 0.5, np.array([30.0]), orders,
    ...                   "outer", 2, 0.02, 10.0, np.zeros(2, bool))
    >>> round(float(np.nanmax(r.level_db[0, :, 0])), 1), r.n_carriers
    (20.0, 2)
    """
    carrier, modulation, _ = FAULT_FAMILIES[fault]
    lines = family_lines(fault, harmonics)
    h = np.array([hh for _, hh, _ in lines], dtype=float)
    side = np.array([ss for _, _, ss in lines], dtype=float)
    shared = np.asarray(shared, dtype=bool)
    # Per carrier (H,): a shared carrier takes its sidebands with it; or per line (3H,).
    excluded = np.repeat(shared, 3) if shared.size == harmonics else shared
    n, n_bins = ses.shape
    f_c = orders[carrier] * shaft_hz
    f_m = orders[modulation] * shaft_hz
    step = 0.5 * df / (harmonics * f_c.max())
    scales = np.arange(1.0 - slip, 1.0 + UPWARD * slip + 0.5 * step, step)
    # Slip slows the cage (FTF) as it slows the defect rates; shaft sidebands stay put.
    f_mod = f_m[:, None, None] * (scales[None, :, None] if modulation == "ftf" else 1.0)
    target = scales[None, :, None] * h * f_c[:, None, None] + side * f_mod  # (n, S, L)
    centre = np.rint(target / df).astype(np.int64)
    usable = (centre >= 1) & (centre + 1 < n_bins) & ~excluded

    # Background: median SES over the slip search of the line +- background_hz.
    nominal = h * f_c[:, None] + side * f_m[:, None]  # (n, L)
    half = max(5, math.ceil(background_hz / df))
    lo = np.rint(nominal * (1 - slip) / df).astype(np.int64) - half
    width = int(np.max(np.rint(nominal * (1 + UPWARD) * slip / df))) + 2 * half + 1
    idx = lo[..., None] + np.arange(width)
    hi = np.rint(nominal * (1 + UPWARD * slip) / df).astype(np.int64) + half
    valid = (idx >= 1) & (idx < n_bins) & (idx <= hi[..., None])
    rows = np.arange(n)[:, None, None]
    background = _masked_median(ses[rows, np.clip(idx, 0, n_bins - 1)], valid)  # (n, L)

    c = np.clip(centre, 1, n_bins - 2)
    tiny = np.finfo(float).tiny
    floor = background[:, None, :] + tiny
    # Bins on a shaft harmonic read as background (level 0 dB): no line there counts.
    window = np.stack([np.where(notch[rows, k], floor, ses[rows, k]) for k in (c - 1, c, c + 1)])
    best = window.argmax(axis=0) - 1
    return LineReadings(
        fault=fault,
        scales=scales,
        level_db=np.where(usable, 10.0 * np.log10((window.max(axis=0) + tiny) / floor), np.nan),
        on_bin_db=np.where(usable, 10.0 * np.log10((window[1] + tiny) / floor), np.nan),
        found_hz=(c + best) * df,
        on_shaft=usable & notch[rows, c],
        side=side,
        n_carriers=int(np.sum(~excluded & (side == 0))),
    )


def family_scores(readings: LineReadings, resolved) -> tuple[np.ndarray, np.ndarray]:
    """Stage 3 of the evidence: a family's score and scale fit at every scale, dB.

    With ``C`` the mean level of the usable carriers and ``S`` the mean over harmonics
    of the stronger sideband (the one read where the other is left out): ``(C + S) /
    2`` for the inner race (+-fr); the same for the ball (+-FTF) less what its carriers
    stand more than 6 dB above their own cage sidebands
    (:func:`ballpass.diagnose.ball.cage_shortfall_db`: a ball comb is cage-modulated);
    ``C - max(0, S - C + OUTER_SIDEBAND_MARGIN_DB)`` for the outer race, whose
    +-FTF neighbours only count against it where ``resolved`` (n,) (records of at
    least :data:`FTF_RESOLVED_CAGE_PERIODS`). The fit is the mean over carriers of the
    window level plus the nearest bin's level. ``-inf`` where the family cannot be
    judged (fewer than :data:`MIN_CARRIERS` unshared carriers; the ball where the FTF
    sidebands are not resolved).

    Returns
    -------
    score, fit : ndarray, shape (n, S)
    """
    _, modulation, support = FAULT_FAMILIES[readings.fault]
    level, side = readings.level_db, readings.side
    is_carrier = side == 0
    resolved = np.asarray(resolved, dtype=bool)
    with np.errstate(all="ignore"), _quiet():
        fit = np.nanmean(np.where(is_carrier, level + readings.on_bin_db, np.nan), axis=-1)
        carriers = np.nanmean(np.where(is_carrier, level, np.nan), axis=-1)
        # The stronger of a pair; where one is left out (shared), the one read: biased
        # low, which keeps a family judged on fewer lines from rising on noise (the
        # stronger of complete pairs alone called 2 of 5 healthy HIT seconds "ball").
        sidebands = np.nanmean(np.fmax(level[..., side == -1], level[..., side == +1]),
                               axis=-1)
    sidebands = np.where(np.isnan(sidebands), 0.0, sidebands)
    if readings.fault == "ball":
        score = 0.5 * (carriers + sidebands) - cage_shortfall_db(level, side,
                                                                 readings.on_shaft)
    elif support > 0:
        score = 0.5 * (carriers + sidebands)
    else:
        shortfall = np.maximum(0.0, sidebands - carriers + OUTER_SIDEBAND_MARGIN_DB)
        score = carriers - np.where(resolved[:, None], shortfall, 0.0)
    judged = (readings.n_carriers >= MIN_CARRIERS) & (resolved[:, None] | (modulation != "ftf")
                                                      | (support < 0))
    score = np.where(judged & np.isfinite(score), score, -np.inf)
    fit = np.where(judged & np.isfinite(fit), fit, -np.inf)
    return score, fit


def _family_scores(ses, notch, df, shaft_hz, orders, fault, harmonics, slip, background_hz,
                   shared, resolved):
    """Stages 2 and 3 in one band, at the best-fitting scale of each row: (evidence
    (n,), level (n, L), found (n, L), scale (n,), on_shaft (n, L), scales judged (n,))."""
    readings = line_readings(ses, notch, df, shaft_hz, orders, fault, harmonics, slip,
                             background_hz, shared)
    score, fit = family_scores(readings, resolved)
    j = fit.argmax(axis=1)
    i = np.arange(len(ses))
    return (score[i, j], readings.level_db[i, j], readings.found_hz[i, j],
            readings.scales[j], readings.on_shaft[i, j], np.isfinite(score).sum(axis=1))


def _masked_median(values: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Median over the last axis of the ``valid`` entries (``inf`` where none):
    ``np.nanmedian`` without its masked-array path, which costs ten times more."""
    ordered = np.sort(np.where(valid, values, np.inf), axis=-1)
    count = valid.sum(axis=-1)
    lower = np.take_along_axis(ordered, np.maximum(count - 1, 0)[..., None] // 2, -1)[..., 0]
    upper = np.take_along_axis(ordered, (count // 2)[..., None], -1)[..., 0]
    with np.errstate(invalid="ignore"):
        return np.where(count > 0, 0.5 * (lower + upper), np.inf)


def shaft_resolving_length(freq_hz, shaft_hz: float):
    """Shortest record whose SES tells a line at ``freq_hz`` from the nearest shaft
    harmonic, s (``inf``: closer than :data:`SHAFT_GUARD_RELATIVE`, never).

    A line reads as its shaft harmonic ``k fr`` when it lies within the shaft guard,
    :data:`SHAFT_GUARD_BINS` SES bins of ``1 / T`` Hz (or the relative guard); it is
    told apart on records of ``T > SHAFT_GUARD_BINS / |f - k fr|``.

    Parameters
    ----------
    freq_hz : float or array_like
        Line frequency, Hz.
    shaft_hz : float
        Shaft speed, Hz.

    Returns
    -------
    ndarray
        Record length, s, shaped like ``freq_hz``.

    Examples
    --------
    The 6203's ball-defect line at 1797 rpm is 0.36 Hz from 4x the shaft speed (3 bins
    of 1 / 8.4 s):

    >>> import ballpass as bp
    >>> from ballpass.diagnose.evidence import shaft_resolving_length
    >>> fr = 1797 / 60
    >>> f = bp.Bearing.catalog("6203").frequencies(fr).ball_defect
    >>> round(float(shaft_resolving_length(f, fr)), 1)
    8.4
    """
    f = np.asarray(freq_hz, dtype=float)
    k = np.maximum(np.rint(f / shaft_hz), 1.0)
    gap = np.abs(f - k * shaft_hz)
    with np.errstate(divide="ignore"):
        length = SHAFT_GUARD_BINS / gap
    return np.where(gap > SHAFT_GUARD_RELATIVE * k * shaft_hz, length, np.inf)


class _quiet:
    """Silence numpy's "mean of empty slice" warnings (all-NaN rows are expected)."""

    def __enter__(self):
        import warnings

        self._ctx = warnings.catch_warnings()
        self._ctx.__enter__()
        warnings.simplefilter("ignore", RuntimeWarning)

    def __exit__(self, *exc):
        return self._ctx.__exit__(*exc)


def envelope_evidence(
    x,
    fs: float,
    bearing,
    rpm,
    *,
    band=None,
    prewhiten: bool = False,
    harmonics: int = 3,
    slip: float = 0.02,
    background_hz: float = 10.0,
    speed_tolerance: float = 0.04,
    line_hz=None,
) -> EnvelopeEvidence:
    """Evidence of each fault family in the squared envelope spectrum, dB.

    For each signal and each candidate band (:func:`candidate_bands`, or ``band``): the
    SES (:func:`ballpass.features.envelope_spectrum`'s, computed from the band's own bins
    by :class:`ballpass.features.demodulate.BandDemodulator`, so a band costs in
    proportion to its width); for each family and each common
    scale ``s`` of its kinematic frequencies in ``[1 - slip, 1 + slip / 2]`` (slip
    slows the cage; steps of half a bin at the highest harmonic) the level of each
    usable line (see the module notes for the lines left out):

    ``L = 10 log10(max SES within +-1 bin / background)``, dB,

    the background being the median SES over the line's slip search +-
    ``background_hz``. With ``C`` the mean level of the usable carriers and ``S`` the
    mean over harmonics of the stronger sideband, the evidence at ``s`` is
    ``(C + S) / 2`` for the inner race (+-fr), the same less the mean over harmonics
    of ``max(0, C_h - S_h - 6 dB)`` for the ball (+-FTF, the cage modulation), and
    ``C - max(0, S - C + 6 dB)`` for the outer race. The scale is fitted on the
    carriers; each family keeps its best band. A family with fewer than two unshared
    carriers cannot be judged (``-inf``).

    The speed is checked first (:func:`ballpass.diagnose.speed.estimate_shaft_speed`):
    where the signal carries a shaft-harmonic comb (median level of its ten harmonics at
    least :data:`MIN_COMB_DB` above the background) that stands at least 3 dB higher
    at another speed within ``+-speed_tolerance`` (and more than 0.2 % away) than at
    the stated one, that speed is used unless the strongest family's evidence is at
    least :data:`SPEED_KEEP_DB` weaker at it than at the stated speed: a fault's own
    raw-spectrum harmonics can make a comb of their own (the 6203's BPFO / 3 is 1.8 %
    above the shaft speed, and on a 2 s record the true shaft lines' main lobes lift its
    first harmonics), and a correction that loses the fault is no correction. Records
    shorter than :data:`SPEED_CHECK_S` keep the stated speed where a divisor of a fault
    rate could be the comb (:func:`ballpass.diagnose.speed.fault_comb`), since their
    evidence cannot tell; other corrections they check as longer records do.

    Parameters
    ----------
    x : array_like, shape (n_signals, n_samples) or (n_samples,)
        Signals, e.g. acceleration in m/s^2.
    fs : float
        Sampling frequency, Hz.
    bearing : str or Bearing
        Catalogue name (``"6205"``) or a :class:`ballpass.Bearing`.
    rpm : float or array_like of shape (n_signals,)
        Stated shaft speed, rev/min.
    band : (float, float) or None, optional
        Demodulation band, Hz; ``None`` (default) searches the candidate bands.
    prewhiten : bool, optional
        Cepstrum pre-whitening before demodulation (default False).
    harmonics : int, optional
        Harmonics 1..H of each family (default 3).
    slip : float, optional
        Largest relative slip searched, in [0, 0.2] (default 0.02).
    background_hz : float, optional
        Half-width of the background median beyond the slip search, Hz (default 10).
    speed_tolerance : float, optional
        Relative half-width of the speed check, in [0, 0.1]; 0 trusts ``rpm``
        (default 0.04: the CWRU rig's speeds at 0-3 hp span 1730-1797 rpm).
    line_hz : float or None, optional
        Supply frequency, Hz (50 or 60), where known: harmonics of it that stand out of
        the SES are set aside as the shaft harmonics are (rule 2 of the module notes;
        an electrical machine modulates its structure at twice the supply frequency,
        and a fault family whose rate falls within the slip search of one of its
        harmonics would read it). Default None: no supply lines set aside.

    Returns
    -------
    EnvelopeEvidence

    Examples
    --------
    Impacts at BPFO of a 6205 at 1796 rpm (0.5 % slip) ringing a 3 kHz resonance:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.diagnose import envelope_evidence
    >>> fs, rpm = 12_000.0, 1796.0
    >>> bpfo = 0.995 * bp.Bearing.catalog("6205").frequencies(rpm / 60).bpfo
    >>> t = np.arange(12_000) / fs
    >>> phase = (t * bpfo) % 1.0 / bpfo                      # time since the last impact, s
    >>> x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    >>> x = x + 0.2 * np.random.default_rng(0).standard_normal(t.size)
    >>> ev = envelope_evidence(x, fs, "6205", rpm)
    >>> {k: bool(v[0] > 10) for k, v in ev.evidence_db.items()}
    {'outer': True, 'inner': False, 'ball': False}
    >>> bool(abs(ev.scale["outer"][0] - 0.995) < 0.005)
    True
    """
    fs = check_fs(fs)
    xv = check_signals(x)
    bearing = as_bearing(bearing)
    harmonics = check_positive_int("harmonics", harmonics, 1)
    slip = check_nonnegative("slip", slip)
    if slip > 0.2:
        raise ValueError(f"slip must be in [0, 0.2], got {slip!r}")
    background_hz = check_nonnegative("background_hz", background_hz)
    speed_tolerance = check_nonnegative("speed_tolerance", speed_tolerance)
    if line_hz is not None and not (isinstance(line_hz, (int, float)) and 0 < line_hz < fs / 2):
        raise ValueError(f"line_hz must be None or a supply frequency in (0, fs/2 = {fs / 2:g}) "
                         f"Hz, got {line_hz!r}")
    if speed_tolerance > 0.1:
        raise ValueError(f"speed_tolerance must be in [0, 0.1], got {speed_tolerance!r}")
    stated = np.array(check_rpm(rpm, (len(xv),)), dtype=float)
    bands = None if band is None else np.array([check_band(band, fs)])
    # before any work: harmonics beyond the envelope spectrum's reach (10**9 exhausted
    # memory); the search window is +-slip
    _check_reach(harmonics, slip, background_hz, bearing, stated, fs / 2.0,
                 xv.shape[-1] // 2 + 1)
    xv = to_unit_scale(xv)[0]     # every output is a ratio (dB) or a frequency: exact

    orders = bearing.frequencies(1.0).as_dict()
    # Resolution in orders at the slowest speed the check may reach: one mask per batch.
    resolution = COLLISION_BINS * fs / xv.shape[-1] / (stated.min() / 60.0
                                                        * (1.0 - speed_tolerance))
    slowest_ftf = orders["ftf"] * stated.min() / 60.0 * (1.0 - speed_tolerance)
    ball_judged = xv.shape[-1] / fs * slowest_ftf >= FTF_RESOLVED_CAGE_PERIODS
    shared = shared_lines(orders, harmonics, slip, resolution, ball_judged)
    settings = dict(fs=fs, orders=orders, harmonics=harmonics, slip=slip,
                    background_hz=background_hz, prewhiten=prewhiten, bands=bands,
                    shared=shared, line_hz=line_hz)
    best, n_bands, n_readings = _best_bands(xv, stated / 60.0, **settings)
    used = stated.copy()
    corrected = np.zeros(len(xv), bool)
    rpm_comb = np.full(len(xv), np.nan)
    if speed_tolerance > 0:
        comb_rpm, comb, at_stated = estimate_shaft_speed(xv, fs, stated,
                                                         tolerance=speed_tolerance)
        carriers = [orders[c] for c, _, _ in FAULT_FAMILIES.values()]
        ambiguous = fault_comb(comb_rpm / stated, carriers, slip, UPWARD * slip,
                               fs / xv.shape[-1], stated / 60.0)
        proposed = np.flatnonzero((comb >= MIN_COMB_DB) & (comb >= at_stated + 3.0)
                                  & (np.abs(comb_rpm / stated - 1) > 0.002)
                                  & ((xv.shape[-1] / fs >= SPEED_CHECK_S) | ~ambiguous))
        rpm_comb[proposed] = comb_rpm[proposed]
        if proposed.size:
            alt, alt_bands, alt_readings = _best_bands(xv[proposed], comb_rpm[proposed] / 60.0,
                                                       **settings)
            n_readings[proposed] += alt_readings
            take = _strongest(best)[proposed] - _strongest(alt) < SPEED_KEEP_DB
            rows = proposed[take]
            for fault, rec in best.items():
                for key, value in rec.items():
                    value[rows] = alt[fault][key][take]
            n_bands[rows] = alt_bands[take]
            corrected[rows] = True
            used[rows] = comb_rpm[rows]
    shaft_hz = used / 60.0
    names = {f: [name for name, _, _ in family_lines(f, harmonics)] for f in FAULT_FAMILIES}
    nominal = {}
    for fault, (carrier, modulation, _) in FAULT_FAMILIES.items():
        lines = family_lines(fault, harmonics)
        h = np.array([hh for _, hh, _ in lines], dtype=float)
        side = np.array([ss for _, _, ss in lines], dtype=float)
        nominal[fault] = (h * orders[carrier] + side * orders[modulation]) * shaft_hz[:, None]
    return EnvelopeEvidence(
        evidence_db={f: best[f]["evidence"] for f in FAULT_FAMILIES},
        levels_db={f: best[f]["level"] for f in FAULT_FAMILIES},
        found_hz={f: best[f]["found"] for f in FAULT_FAMILIES},
        nominal_hz=nominal,
        shared=shared,
        on_shaft={f: best[f]["on_shaft"] for f in FAULT_FAMILIES},
        scale={f: best[f]["scale"] for f in FAULT_FAMILIES},
        line_names=names,
        band_hz={f: best[f]["band"] for f in FAULT_FAMILIES},
        n_bands=n_bands,
        n_readings=n_readings,
        rpm=used,
        rpm_stated=stated,
        speed_corrected=corrected,
        rpm_comb=rpm_comb,
        duration_s=xv.shape[-1] / fs,
    )


def _strongest(best: dict) -> np.ndarray:
    """Per row, the largest evidence of any family, dB."""
    return np.max([rec["evidence"] for rec in best.values()], axis=0)


def _best_bands(xv, shaft_hz, *, fs, orders, harmonics, slip, background_hz, prewhiten,
                bands, shared, line_hz=None):
    """Each family's evidence in its best band at the shaft speeds ``shaft_hz`` (Hz, one
    per row): ``({fault: {evidence, level, found, on_shaft, scale, band}}, bands with
    signal, family scores read)``; ``shared`` is :func:`shared_lines`'s mask."""
    top = float(np.max(shaft_hz)) * (harmonics * max(orders[c] for c, _, _ in
                                                     FAULT_FAMILIES.values()) + 1.0)
    # The SES is needed up to the highest line's slip search and background, and one
    # shaft harmonic beyond (the shaft guard's nearest harmonic).
    reach = (top * (1.0 + slip) + float(np.max(shaft_hz)) + background_hz
             + 10.0 * fs / xv.shape[-1])
    demodulator = BandDemodulator(xv, fs, max_hz=reach, prewhiten=prewhiten)
    if bands is None:
        bands, has_signal = candidate_bands(xv, fs, top, power=demodulator.power)
    else:
        has_signal = np.ones((len(xv), 1), bool)
    n = len(xv)
    resolved = xv.shape[-1] / fs * orders["ftf"] * shaft_hz >= FTF_RESOLVED_CAGE_PERIODS
    n_lines = 3 * harmonics
    best = {
        f: dict(
            evidence=np.full(n, -np.inf),
            level=np.full((n, n_lines), np.nan),
            found=np.full((n, n_lines), np.nan),
            on_shaft=np.zeros((n, n_lines), bool),
            scale=np.ones(n),
            band=np.full((n, 2), np.nan),
        )
        for f in FAULT_FAMILIES
    }
    searched = np.flatnonzero(has_signal.any(axis=0))
    n_readings = np.zeros(n, np.int64)
    # Bands are scored together, stacked as extra rows (the line layout is the same in
    # every band), a few at a time so that a batch of many signals stays small.
    per_batch = max(1, ROWS_PER_BATCH // n)
    for start in range(0, searched.size, per_batch):
        chunk = searched[start : start + per_batch]
        spectra = [demodulator.ses(tuple(bands[k])) for k in chunk]
        df = spectra[0][0][1]
        ses = np.concatenate([s for _, s in spectra])  # (len(chunk) * n, n_bins)
        speeds = np.tile(shaft_hz, len(chunk))
        notch = shaft_line_bins(spectra[0][0], ses, speeds, background_hz)
        if line_hz is not None:  # the supply's harmonics, set aside like the shaft's
            notch |= shaft_line_bins(spectra[0][0], ses, np.full(speeds.shape, float(line_hz)),
                                     background_hz)
        for fault in FAULT_FAMILIES:
            scored = _family_scores(ses, notch, df, speeds, orders, fault, harmonics, slip,
                                    background_hz, shared[fault], np.tile(resolved, len(chunk)))
            rec = best[fault]
            for i, k in enumerate(chunk):
                ev, level, found, scale, on_shaft, judged = (v[i * n : (i + 1) * n]
                                                             for v in scored)
                n_readings += np.where(has_signal[:, k], judged, 0)
                better = has_signal[:, k] & (ev > rec["evidence"])
                rec["evidence"] = np.where(better, ev, rec["evidence"])
                rec["level"] = np.where(better[:, None], level, rec["level"])
                rec["found"] = np.where(better[:, None], found, rec["found"])
                rec["on_shaft"] = np.where(better[:, None], on_shaft, rec["on_shaft"])
                rec["scale"] = np.where(better, scale, rec["scale"])
                rec["band"] = np.where(better[:, None], bands[k], rec["band"])
    return best, has_signal.sum(axis=1), n_readings
