"""How high noise alone reads: the law of a record's strongest family evidence.

The diagnoser's evidence of a record is a maximum over every reading its search makes
(candidate bands x judged families x slip scales, and a second speed where the speed
check searched one; :attr:`EnvelopeEvidence.n_readings`). If one reading of noise
exceeds ``e`` with a probability whose tail is exponential, ``P(E > e) ~ exp(-(e - a) /
s)``, the largest of ``N`` independent readings follows a Gumbel law of scale ``s`` and
location ``a + s ln N``: the location grows with the log of the search size. Readings
of neighbouring scales and of nested bands are correlated, so the search counts as an
effective ``N_eff = N^k`` readings (``k < 1``), and the location is
``a + b ln N`` with ``b = k s`` free. The scale of one reading shrinks with the record
length (a longer record averages more bins in each line's background), and both grow
where the +-FTF sidebands are not resolved (records shorter than
:data:`~ballpass.diagnose.evidence.FTF_RESOLVED_CAGE_PERIODS` cage periods: the outer
race is judged on its carriers alone, an average of fewer lines):

``loc = a + b ln N + c u``,   ``scale = exp(d + e ln T + f u)``,

``T`` the record length in seconds and ``u`` 1 where the sidebands are not resolved.
The six coefficients (:data:`NOISE_EVIDENCE_LAW`) are a maximum-likelihood fit on
Monte Carlo records of white and pink Gaussian noise (12, 48 and 51.2 kHz; 1, 2, 5 and
10 s; a 6205 and a 6203 at 580-1800 rpm; ``benchmarks/diagnose_noise.py --fit``), and
checked on other seeds (docs/diagnosis_noise.md): the fraction of fresh noise records
above the law's 10 % and 1 % quantiles is stated per rate, length and speed there.

With the law, a threshold that gives one false-alarm probability whatever the rate,
length and speed is its quantile (:func:`noise_threshold`), and a record's evidence has
a p-value that counts the whole search once (:func:`noise_probability`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["NOISE_EVIDENCE_LAW", "noise_evidence_law", "noise_probability", "noise_threshold"]

#: Coefficients ``(a, b, c, d, e, f)`` of the noise law of the module notes (dB, dB per
#: e-fold of readings, dB; log-dB, per e-fold of seconds, log-dB). Maximum likelihood
#: on 432 noise records (``benchmarks/diagnose_noise.py --fit``, seed 11, six per rate x
#: length x speed x bearing cell): ``b`` = 0.156 dB per e-fold of the readings (the
#: search counts as about ``N^0.5`` independent readings), scale 0.29 dB at 1 s and
#: 0.20 dB at 10 s, 1.45 times wider and 0.44 dB higher where the +-FTF sidebands are
#: not resolved.
NOISE_EVIDENCE_LAW = (2.109, 0.1562, 0.4446, -1.2491, -0.1599, 0.3749)


def noise_evidence_law(n_readings, duration_s: float, ftf_resolved=True):
    """Gumbel location and scale, dB, of a noise record's strongest evidence.

    Parameters
    ----------
    n_readings : int or array_like
        Readings searched (:attr:`EnvelopeEvidence.n_readings`), at least 1.
    duration_s : float
        Record length, s.
    ftf_resolved : bool or array_like of bool, optional
        Whether the +-FTF sidebands are resolved (default True).

    Returns
    -------
    loc, scale : ndarray
        dB, broadcast over the arguments.

    Examples
    --------
    >>> from ballpass.diagnose.noise_law import noise_evidence_law
    >>> loc, scale = noise_evidence_law(4000, 1.0)
    >>> round(float(loc), 2), round(float(scale), 3)
    (3.4, 0.287)
    """
    a, b, c, d, e, f = NOISE_EVIDENCE_LAW
    n = np.maximum(np.asarray(n_readings, dtype=float), 1.0)
    if not duration_s > 0:
        raise ValueError(f"duration_s must be > 0 (record length, s), got {duration_s!r}")
    u = 1.0 - np.asarray(ftf_resolved, dtype=float)
    return a + b * np.log(n) + c * u, np.exp(d + e * math.log(duration_s) + f * u)


def noise_probability(evidence_db, n_readings, duration_s: float, ftf_resolved=True):
    """Probability that a record of noise alone, searched as widely (``n_readings``
    readings, ``duration_s`` s), reads a strongest evidence of at least ``evidence_db``.

    Per record, not per reading: the law is that of the maximum over the whole search.
    A statement about the search, not about the machine: a healthy machine's own lines
    are not noise, and a low probability does not rule them out.

    Returns
    -------
    float or ndarray
        Shaped like the broadcast arguments; 1 at ``-inf``, 0 at ``+inf``.

    Examples
    --------
    >>> from ballpass.diagnose.noise_law import noise_probability
    >>> f"{noise_probability(6.0, 4000, 1.0):.0e}", float(noise_probability(-float("inf"), 10, 1.0))
    ('1e-04', 1.0)
    """
    loc, scale = noise_evidence_law(n_readings, duration_s, ftf_resolved)
    with np.errstate(over="ignore"):
        z = (np.asarray(evidence_db, dtype=float) - loc) / scale
        p = -np.expm1(-np.exp(-z))
    return float(p) if np.ndim(p) == 0 else p


def noise_threshold(probability: float, n_readings, duration_s: float, ftf_resolved=True):
    """Evidence, dB, that noise alone reaches with ``probability`` per record: the
    threshold whose false-alarm probability on noise is ``probability`` whatever the
    rate, length and speed (the inverse of :func:`noise_probability`).

    Examples
    --------
    >>> from ballpass.diagnose.noise_law import noise_probability, noise_threshold
    >>> t = noise_threshold(1e-3, 4000, 1.0)
    >>> round(float(t), 2), f"{noise_probability(t, 4000, 1.0):.3g}"
    (5.39, '0.001')
    """
    if not 0.0 < probability < 1.0:
        raise ValueError(f"probability must be in (0, 1), got {probability!r}")
    loc, scale = noise_evidence_law(n_readings, duration_s, ftf_resolved)
    return loc - scale * math.log(-math.log1p(-probability))
