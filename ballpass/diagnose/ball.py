"""Cage modulation: what tells a ball defect from the race families its lines collide with.

A defect on a rolling element strikes the races at 2xBSF (once per ball revolution on
each race), and the ball carries it round the load zone with the cage: the impacts are
modulated at the cage rate FTF, so the squared envelope spectrum (SES) shows the 2xBSF
comb flanked by sidebands at +-FTF (Randall & Antoni 2011, section 2.2; Smith &
Randall 2015 read CWRU ball faults by them). No race fault makes a 2xBSF comb with
+-FTF sidebands. Yet the comb alone says little: on a 6205, 2x2xBSF+FTF (9.825
orders) lies on 2xBPFI-fr (9.830), and a slip of 1-2 % moves 3x2xBSF (14.14 orders)
onto the 14th shaft harmonic; on a 6203, 2xBSF (3.987) is 0.3 % from the 4th. A line
at 2xBSF with no sidebands is not a ball fault: the ball family is judged by its
carriers *and* their cage modulation (:func:`cage_shortfall_db`).

How strong the sidebands are follows from the load distribution (Harris's, after
Stribeck): a ball at cage angle ``psi`` carries ``q(psi) = q_max [1 - (1 - cos psi) /
(2 epsilon)]^1.5`` (zero outside the loaded arc), its impacts' squared envelope scales
with ``q^2``, and the SES line at ``h 2xBSF + k FTF`` has the power of the ``k``-th
Fourier coefficient of ``q^2`` over one cage revolution
(:func:`load_zone_sideband_db`). A radial load zone (``epsilon`` = 0.5, half the
bearing loaded) puts the first sidebands 1.1 dB below the carrier; they stay within
:data:`CAGE_SIDEBAND_MARGIN_DB` (6 dB) up to ``epsilon`` = 1.7, a bearing loaded all
round whose far side still carries a tenth of the peak load. Closer to uniform
loading the cage leaves no mark and the ball cannot be told from the lines it collides
with: its score falls, and the verdict goes to the family that can be read, or to
"healthy".

The same lines read from the enhanced envelope spectrum (the band-integrated cyclic
coherence, :func:`ballpass.features.cyclic.enhanced_envelope_spectrum`; Antoni 2007)
give a second view that weights every carrier frequency of the band alike
(:func:`cyclic_family_evidence`).

References
----------
R. B. Randall, J. Antoni, "Rolling element bearing diagnostics - A tutorial", MSSP 25
(2011) 485-520. W. A. Smith, R. B. Randall, MSSP 64-65 (2015) 100-131. T. A. Harris,
M. N. Kotzalas, "Rolling Bearing Analysis", 5th ed. (2007), ch. 7 (load distribution).
J. Antoni, JSV 304 (2007) 497-529.
"""

from __future__ import annotations

import numpy as np

from ..features._validation import check_fs, check_nonnegative, check_signal
from ..features.bands import as_bearing
from ..features.cyclic import enhanced_envelope_spectrum
from ..features.shaft import shaft_line_bins

__all__ = [
    "CAGE_SIDEBAND_MARGIN_DB",
    "cage_note",
    "cage_shortfall_db",
    "cyclic_family_evidence",
    "load_zone_sideband_db",
    "unmodulated_comb_db",
]

#: The +-FTF sidebands of a ball fault's 2xBSF comb stand at most this far below its
#: carriers, dB (a factor 4 in SES power): the load distribution's first cage harmonic
#: (:func:`load_zone_sideband_db`) is within 6 dB of its mean for every load zone from
#: a point load up to ``epsilon`` = 1.7. Carriers standing further above their
#: sidebands are not a cage-modulated ball comb; the ball's score is marked down by the
#: excess (the mirror of the outer race's rule in :mod:`ballpass.diagnose.evidence`).
CAGE_SIDEBAND_MARGIN_DB = 6.0


def load_zone_sideband_db(epsilon: float, order: int = 1) -> float:
    """Level of the ``order``-th +-FTF sideband of a ball fault's SES line relative to
    its carrier, dB, for the load-distribution factor ``epsilon`` (module notes).

    Parameters
    ----------
    epsilon : float
        Load-distribution factor, > 0: 0.5 for a radial load on a bearing without
        clearance (half loaded), larger for preload (all balls loaded).
    order : int, optional
        Sideband order ``k`` (default 1).

    Returns
    -------
    float
        ``20 log10(|c_k| / c_0)`` of the Fourier coefficients of ``q(psi)^2``, dB (<= 0).

    Examples
    --------
    >>> from ballpass.diagnose.ball import load_zone_sideband_db
    >>> round(load_zone_sideband_db(0.5), 1), round(load_zone_sideband_db(1.7), 1)
    (-1.1, -5.7)
    """
    epsilon = check_nonnegative("epsilon", epsilon)
    if epsilon == 0:
        raise ValueError("epsilon must be > 0 (the load-distribution factor), got 0")
    psi = np.linspace(-np.pi, np.pi, 20_001)[:-1]
    q = np.clip(1.0 - (1.0 - np.cos(psi)) / (2.0 * epsilon), 0.0, None) ** 1.5
    e = q**2
    return float(20.0 * np.log10(abs(np.mean(e * np.exp(1j * order * psi))) / np.mean(e)))


def cage_shortfall_db(level_db, side, on_shaft):
    """How far a ball comb's carriers stand above their cage sidebands beyond what any
    load zone explains, dB: the mean over harmonics of ``max(0, C_h - S_h - 6 dB)``,
    ``C_h`` the carrier's level, ``S_h`` its stronger readable +-FTF sideband's and 6 dB
    :data:`CAGE_SIDEBAND_MARGIN_DB`.

    Each carrier is compared with its own sidebands: the load zone modulates every
    harmonic alike. A line left out (NaN: shared with another family) or on a shaft
    harmonic (read as background) cannot be read; a harmonic is compared where its
    carrier and at least one of its sidebands can. The ball's score is ``(C + S) / 2``
    less this shortfall (:func:`ballpass.diagnose.evidence.family_scores`): a
    cage-modulated comb keeps its score, and a comb at 2xBSF without sidebands (a race
    or shaft line landing there) loses what its carriers stand above them.

    Parameters
    ----------
    level_db : ndarray, shape (..., 3 H)
        Line levels in :func:`~ballpass.diagnose.evidence.family_lines` order, dB.
    side : ndarray, shape (3 H,)
        -1, 0, +1 per line.
    on_shaft : ndarray of bool, shape (..., 3 H)
        Lines read on a shaft harmonic.

    Returns
    -------
    ndarray, shape (...)
        Shortfall, dB (>= 0; 0 where no carrier can be compared).

    Examples
    --------
    Carriers at 20 dB: sidebands at 18 dB are a cage-modulated comb, at 2 dB they fall
    12 dB short:

    >>> import numpy as np
    >>> from ballpass.diagnose.ball import cage_shortfall_db
    >>> side = np.array([0, -1, 1, 0, -1, 1])
    >>> levels = np.array([[20.0, 18.0, 17.0, 20.0, 16.0, 18.0],
    ...                    [20.0, 2.0, 1.0, 20.0, 2.0, 0.0]])
    >>> cage_shortfall_db(levels, side, np.zeros(levels.shape, bool)).tolist()
    [0.0, 12.0]
    """
    side = np.asarray(side)
    readable = np.where(np.asarray(on_shaft, dtype=bool), np.nan,
                        np.asarray(level_db, dtype=float))
    carrier = readable[..., side == 0]
    with np.errstate(all="ignore"):
        sideband = np.fmax(readable[..., side == -1], readable[..., side == +1])
        excess = np.maximum(0.0, carrier - sideband - CAGE_SIDEBAND_MARGIN_DB)
    compared = np.isfinite(carrier) & np.isfinite(sideband)
    count = compared.sum(axis=-1)
    total = np.where(compared, excess, 0.0).sum(axis=-1)
    return np.where(count > 0, total / np.maximum(count, 1), 0.0)


def unmodulated_comb_db(ev, i: int) -> float:
    """The ball's evidence in row ``i`` of
    :class:`~ballpass.diagnose.evidence.EnvelopeEvidence` ``ev`` before the cage rule
    marked it down, dB: the evidence plus :func:`cage_shortfall_db` of the lines read
    (in the band and at the scale the ball kept); ``-inf`` where nothing was marked
    down (a cage-modulated comb, or none)."""
    from .evidence import family_lines

    evidence = float(ev.evidence_db["ball"][i])
    if not np.isfinite(evidence):
        return -np.inf
    side = np.array([s for _, _, s in family_lines("ball", len(ev.line_names["ball"]) // 3)])
    short = float(cage_shortfall_db(ev.levels_db["ball"][i], side, ev.on_shaft["ball"][i]))
    return evidence + short if short > 0 else -np.inf


def cage_note(ev, i: int) -> list[str]:
    """:meth:`~ballpass.diagnose.EnvelopeDiagnoser.explain`'s note on row ``i`` where
    the cage rule decided (the 2xBSF comb would have rivalled the verdict,
    :func:`unmodulated_comb_db`, but its carriers stand too far above their +-FTF
    sidebands). Empty where nothing was marked down."""
    raw = unmodulated_comb_db(ev, i)
    if not np.isfinite(raw):
        return []
    evidence = float(ev.evidence_db["ball"][i])
    return [f"ball: the 2xBSF carriers stand {raw - evidence:.1f} dB further above their "
            f"+-FTF sidebands than a load zone explains ({CAGE_SIDEBAND_MARGIN_DB:g} dB): no "
            f"cage modulation, so no ball comb; its evidence lowered from {raw:.1f} to "
            f"{evidence:.1f} dB. What stands at 2xBSF is not told from a race or shaft line"]


def cyclic_family_evidence(x, fs: float, bearing, rpm: float, band, *, fault: str = "ball",
                           harmonics: int = 3, slip: float = 0.02,
                           background_hz: float = 10.0) -> float:
    """A family's evidence read from the enhanced envelope spectrum of one band, dB.

    The lines, the shared-line and shaft-harmonic rules and the family score are those
    of :func:`ballpass.diagnose.evidence.envelope_evidence`; the spectrum is the band's
    squared cyclic coherence averaged over its carriers
    (:func:`~ballpass.features.cyclic.enhanced_envelope_spectrum`) instead of its SES.
    Its background is flatter than the SES's (an average over carrier bins, not one
    periodogram bin), so its dB do not share the SES thresholds: compare families with
    each other, not with :data:`~ballpass.diagnose.rules.DEFAULT_THRESHOLD_DB`.

    Parameters
    ----------
    x : array_like, shape (n_samples,)
        One signal.
    fs : float
        Sampling frequency, Hz.
    bearing : str or Bearing
        Catalogue name or :class:`ballpass.Bearing`.
    rpm : float
        Shaft speed, rev/min.
    band : (float, float)
        Carrier band, Hz (e.g. the band ``explain()`` reports for the family).
    fault : {"outer", "inner", "ball"}, optional
        Family read (default ``"ball"``).
    harmonics, slip, background_hz : optional
        As :func:`~ballpass.diagnose.evidence.envelope_evidence`.

    Returns
    -------
    float
        Evidence, dB over the EES background (``-inf``: not judged).
    """
    from .evidence import FAULT_FAMILIES, family_scores, line_readings, shared_lines

    if fault not in FAULT_FAMILIES:
        raise ValueError(f"fault must be one of {list(FAULT_FAMILIES)}, got {fault!r}")
    fs = check_fs(fs)
    xv = check_signal(x)
    if xv.ndim != 1:
        raise ValueError(f"x must be one signal (n_samples,), got shape {xv.shape}")
    shaft = float(check_nonnegative("rpm", rpm)) / 60.0
    if shaft == 0:
        raise ValueError("rpm must be > 0 (shaft speed, rev/min), got 0")
    orders = as_bearing(bearing).frequencies(1.0).as_dict()
    top = shaft * (harmonics * max(orders["bpfo"], orders["bpfi"], orders["ball_defect"]) + 1)
    reach = top * (1 + slip) + background_hz + shaft
    alpha, ees = enhanced_envelope_spectrum(xv, fs, band, max_alpha=min(reach,
                                                                         band[1] - band[0]))
    resolution = 2.0 * alpha[1] / shaft
    shared = shared_lines(orders, harmonics, slip, resolution)[fault]
    speeds = np.array([shaft])
    notch = shaft_line_bins(alpha, ees, speeds, background_hz)
    readings = line_readings(ees, notch, alpha[1], speeds, orders, fault, harmonics, slip,
                             background_hz, shared)
    score, fit = family_scores(readings, np.array([True]))
    return float(score[0, fit[0].argmax()])
