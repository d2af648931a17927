"""Physics-based diagnosis from the squared envelope spectrum: no training data needed.

A localized fault announces itself in the squared envelope spectrum (SES) as a *family*
of lines whose spacing the bearing's kinematics fix (Randall & Antoni [1]_, section
3.4; the diagnostic grades of Smith & Randall [2]_):

* **outer race** — harmonics of BPFO, *without* sidebands at +-FTF: the fault sits
  still in the load zone, so its impacts are of equal strength and unmodulated;
* **inner race** — harmonics of BPFI with sidebands at +-1x the shaft speed (the fault
  turns with the shaft and passes through the load zone once per revolution);
* **rolling element** — harmonics of the ball-defect frequency 2xBSF with sidebands at
  +-FTF (the faulty element is carried through the load zone at the cage speed).

The outer-race sidebands count *against* the family because BPFO = Z x FTF: a ball
fault, modulated at FTF, fills the whole FTF comb, BPFO and its neighbours alike,
while an outer-race line stands above its +-FTF neighbours.

For each family, :func:`envelope_evidence` measures each line against the local SES
background and combines the levels into one number, the family's *evidence* in dB.
Rolling elements slip, so the whole family is searched over a common scale factor
``1 - slip .. 1 + slip/2`` of its kinematic frequencies (slip lowers the cage speed;
the small upward margin absorbs an imprecise tachometer) and the best-fitting scale is
kept. :class:`EnvelopeDiagnoser` names the family with the strongest evidence when it
exceeds a threshold, and "healthy" otherwise.

References
----------
.. [1] R. B. Randall, J. Antoni, "Rolling element bearing diagnostics - A tutorial",
   MSSP 25 (2011) 485-520.
.. [2] W. A. Smith, R. B. Randall, "Rolling element bearing diagnostics using the Case
   Western Reserve University data: A benchmark study", MSSP 64-65 (2015) 100-131.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.ndimage
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.utils.validation import check_array

from ..features import envelope_spectrum, fast_kurtogram
from ..features._validation import (
    check_band,
    check_fs,
    check_nonnegative,
    check_positive_int,
    check_rpm,
    check_signal,
)
from ..features.bands import as_bearing
from ._names import LABELS

__all__ = [
    "LABELS",
    "FAULT_FAMILIES",
    "EnvelopeEvidence",
    "Explanation",
    "envelope_evidence",
    "EnvelopeDiagnoser",
]

#: fault -> (carrier line, sideband spacing, do sidebands support (+1) or refute (-1)
#: the fault), as BearingFrequencies attributes.
FAULT_FAMILIES = {
    "outer": ("bpfo", "ftf", -1),
    "inner": ("bpfi", "shaft", +1),
    "ball": ("ball_defect", "ftf", +1),
}
_SYMBOL = {"bpfo": "BPFO", "bpfi": "BPFI", "ball_defect": "2xBSF", "shaft": "fr", "ftf": "FTF"}
#: Fewest SES bins on each side of a line in its background median.
_MIN_BACKGROUND_BINS = 5


def _family_lines(fault: str, harmonics: int) -> list[tuple[str, int, int]]:
    """Lines of a family as ``(name, harmonic, side)``; side -1/0/+1 is the sideband."""
    carrier, modulation, _ = FAULT_FAMILIES[fault]
    lines = []
    for h in range(1, harmonics + 1):
        lines.append((f"{h}x{_SYMBOL[carrier]}", h, 0))
        lines.append((f"{h}x{_SYMBOL[carrier]}-{_SYMBOL[modulation]}", h, -1))
        lines.append((f"{h}x{_SYMBOL[carrier]}+{_SYMBOL[modulation]}", h, +1))
    return lines


def _role(fault: str, side: int) -> str:
    """``"carrier"``, ``"sideband"`` or ``"refuting sideband"`` (outer race, +-FTF)."""
    if side == 0:
        return "carrier"
    return "sideband" if FAULT_FAMILIES[fault][2] > 0 else "refuting sideband"


@dataclass(frozen=True, eq=False)
class EnvelopeEvidence:
    """Fault-family evidence of a batch of signals (see :func:`envelope_evidence`).

    Attributes
    ----------
    evidence_db : dict of str to ndarray, shape (n_signals,)
        For ``"outer"``, ``"inner"``, ``"ball"``: the family's evidence, dB above the
        SES background.
    levels_db : dict of str to ndarray, shape (n_signals, n_lines)
        Level of each line of the family at the best-fitting scale, dB above the local
        background (NaN above the SES's highest frequency).
    found_hz : dict of str to ndarray, shape (n_signals, n_lines)
        Frequency of the SES bin that carried each line, Hz.
    nominal_hz : dict of str to ndarray, shape (n_signals, n_lines)
        Kinematic frequency of each line at the given speed, Hz.
    scale : dict of str to ndarray, shape (n_signals,)
        Best-fitting ratio of measured to kinematic frequencies (1 - slip .. 1 + slip/2),
        known to about one SES bin at the highest harmonic (the +-1 bin line window).
    line_names : dict of str to list of str
        Names of the lines, e.g. ``"2xBPFI-fr"`` (lower shaft sideband of 2xBPFI).
    band_hz : ndarray, shape (n_signals, 2)
        Demodulation band of each signal, Hz.
    """

    evidence_db: dict
    levels_db: dict
    found_hz: dict
    nominal_hz: dict
    scale: dict
    line_names: dict
    band_hz: np.ndarray


def _ses_per_band(x: np.ndarray, fs: float, band, prewhiten: bool):
    """SES of each row of ``x`` (n, n_samples) and the band used, (n, 2) Hz."""
    if band is None:
        bands = np.reshape(fast_kurtogram(x, fs).best_band, (-1, 2))
    else:
        bands = np.tile(check_band(band, fs), (len(x), 1))
    ses = np.empty((len(x), x.shape[-1] // 2 + 1))
    unique, inverse = np.unique(bands, axis=0, return_inverse=True)
    for k, b in enumerate(unique):
        rows = np.flatnonzero(inverse.ravel() == k)
        freqs, ses[rows] = envelope_spectrum(x[rows], fs, tuple(b), prewhiten=prewhiten)
    return freqs, ses, bands


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
) -> EnvelopeEvidence:
    """Evidence of each fault family in the squared envelope spectrum, dB.

    For each signal: the SES (:func:`ballpass.features.envelope_spectrum`) in the
    demodulation band; a background, the running median of the SES over
    ``+-background_hz`` (at least 5 bins each side); and for each family and each
    candidate scale ``s`` in ``[1 - slip, 1 + slip / 2]`` (steps of half a bin at the
    highest harmonic) the level of each line at ``s`` times its kinematic frequency:

    ``L = 10 log10(max SES within +-1 bin / background)``, dB.

    With ``C`` the mean level of the carriers ``h x f_c``, ``h = 1..harmonics``, and
    ``S`` the mean over ``h`` of the stronger sideband ``h x f_c -/+ f_m``, the
    family's evidence at ``s`` is ``(C + S) / 2`` for the modulated families (inner
    race: ``f_m`` = shaft speed; ball: ``f_m`` = FTF) and ``C - S / 2`` for the outer
    race (``f_m`` = FTF; see the module notes). The evidence is the largest value over
    ``s``. Noise alone reads about 1-4 dB (the largest of three exponentially
    distributed SES bins over their median, maximised over the scales); a clear fault
    8 dB and more.

    Parameters
    ----------
    x : array_like, shape (n_signals, n_samples) or (n_samples,)
        Signals, e.g. acceleration in m/s^2. At least 1 s gives 1 Hz resolution,
        enough to separate the shaft sidebands of a 6205 at 1800 rpm.
    fs : float
        Sampling frequency, Hz.
    bearing : str or Bearing
        Catalogue name (``"6205"``) or a :class:`ballpass.Bearing`.
    rpm : float or array_like of shape (n_signals,)
        Shaft speed, rev/min.
    band : (float, float) or None, optional
        Demodulation band, Hz; ``None`` (default) chooses it per signal with
        :func:`ballpass.features.fast_kurtogram`.
    prewhiten : bool, optional
        Cepstrum pre-whitening before demodulation (default False).
    harmonics : int, optional
        Harmonics 1..H of each family (default 3).
    slip : float, optional
        Largest relative slip searched, dimensionless in [0, 0.2] (default 0.02).
    background_hz : float, optional
        Half-width of the background median, Hz (default 10).

    Returns
    -------
    EnvelopeEvidence

    Examples
    --------
    Impacts at BPFO of a 6205 at 1796 rpm ringing a 3 kHz resonance:

    >>> import numpy as np
    >>> import ballpass as bp
    >>> from ballpass.diagnose import envelope_evidence
    >>> fs, rpm = 12_000.0, 1796.0
    >>> bpfo = 0.995 * bp.Bearing.catalog("6205").frequencies(rpm / 60).bpfo  # 0.5 % slip
    >>> t = np.arange(12_000) / fs
    >>> phase = (t * bpfo) % 1.0 / bpfo                      # time since the last impact, s
    >>> x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    >>> x = x + 0.2 * np.random.default_rng(0).standard_normal(t.size)
    >>> ev = envelope_evidence(x, fs, "6205", rpm)
    >>> {k: bool(v[0] > 8) for k, v in ev.evidence_db.items()}
    {'outer': True, 'inner': False, 'ball': False}
    >>> bool(abs(ev.scale["outer"][0] - 0.995) < 0.005)     # to about a bin at 3xBPFO
    True
    """
    fs = check_fs(fs)
    xv = check_signal(x)
    if xv.ndim > 2:
        raise ValueError(f"x must be (n_signals, n_samples) or (n_samples,), got {xv.shape}")
    xv = np.atleast_2d(xv)
    bearing = as_bearing(bearing)
    harmonics = check_positive_int("harmonics", harmonics, 1)
    slip = check_nonnegative("slip", slip)
    if slip > 0.2:
        raise ValueError(f"slip must be in [0, 0.2], got {slip!r}")
    background_hz = check_nonnegative("background_hz", background_hz)
    shaft_hz = check_rpm(rpm, (len(xv),)) / 60.0
    prewhiten = bool(prewhiten)

    freqs, ses, bands = _ses_per_band(xv, fs, band, prewhiten)
    df = freqs[1]
    n_bins = freqs.size
    half = max(math.ceil(background_hz / df), _MIN_BACKGROUND_BINS)
    background = scipy.ndimage.median_filter(ses, size=(1, 2 * half + 1), mode="reflect")
    tiny = np.finfo(float).tiny
    orders = bearing.frequencies(1.0).as_dict()
    rows = np.arange(len(xv))[:, None, None]

    out = {key: {} for key in ("evidence_db", "levels_db", "found_hz", "nominal_hz", "scale")}
    names = {}
    for fault, (carrier, modulation, support) in FAULT_FAMILIES.items():
        lines = _family_lines(fault, harmonics)
        names[fault] = [name for name, _, _ in lines]
        h = np.array([hh for _, hh, _ in lines], dtype=float)
        side = np.array([ss for _, _, ss in lines], dtype=float)
        f_c = orders[carrier] * shaft_hz  # (n,)
        f_m = orders[modulation] * shaft_hz
        # Common scale grid: half a bin at the highest harmonic of the fastest signal.
        step = 0.5 * df / (harmonics * f_c.max())
        scales = np.arange(1.0 - slip, 1.0 + 0.5 * slip + 0.5 * step, step)
        # The modulation is scaled too: slip slows the cage (FTF) as it slows BPFI
        # relative to the shaft; the shaft sidebands are kept at the shaft speed.
        f_mod = f_m[:, None, None] * (scales[None, :, None] if modulation == "ftf" else 1.0)
        target = (scales[None, :, None] * h * f_c[:, None, None]) + side * f_mod  # (n, S, L)
        centre = np.rint(target / df).astype(np.int64)
        valid = (centre >= 1) & (centre + 1 < n_bins)
        c = np.clip(centre, 1, n_bins - 2)
        window = np.stack([ses[rows, c - 1], ses[rows, c], ses[rows, c + 1]])
        best = window.argmax(axis=0) - 1
        floor = background[rows, c] + tiny
        level = np.where(valid, 10.0 * np.log10((window.max(axis=0) + tiny) / floor), np.nan)
        on_bin = np.where(valid, 10.0 * np.log10((window[1] + tiny) / floor), np.nan)
        is_carrier = side == 0
        # The scale is fitted on the carriers: the +-1 bin window makes their level
        # flat over about a bin, the level of the nearest bin alone centres the fit.
        fit = np.nanmean(np.where(is_carrier, level + on_bin, np.nan), axis=-1)
        j = np.where(np.isnan(fit), -np.inf, fit).argmax(axis=1)  # best scale per signal
        carriers = np.nanmean(np.where(is_carrier, level, np.nan), axis=-1)
        sidebands = np.nanmean(np.fmax(level[..., side == -1], level[..., side == +1]), axis=-1)
        if support > 0:
            score = 0.5 * (carriers + sidebands)
        else:
            score = carriers - 0.5 * sidebands
        i = np.arange(len(xv))
        out["evidence_db"][fault] = score[i, j]
        out["levels_db"][fault] = level[i, j]
        out["found_hz"][fault] = (c[i, j] + best[i, j]) * df
        out["nominal_hz"][fault] = h * f_c[:, None] + side * f_m[:, None]
        out["scale"][fault] = scales[j]
    return EnvelopeEvidence(**out, line_names=names, band_hz=bands)


@dataclass(frozen=True)
class Explanation:
    """Why :class:`EnvelopeDiagnoser` gave a signal its label.

    Attributes
    ----------
    label : str
        Predicted label.
    evidence_db : dict of str to float
        Evidence of each fault family, dB above the SES background.
    threshold_db : dict of str to float
        Threshold each family's evidence had to exceed, dB.
    band_hz : (float, float)
        Demodulation band, Hz.
    rpm : float
        Shaft speed used, rev/min.
    lines : pandas.DataFrame
        One row per line of every family: ``fault``, ``line`` (e.g. ``"1xBPFI+fr"``),
        ``harmonic``, ``role`` (``"carrier"``, ``"sideband"``, or ``"refuting
        sideband"`` for the +-FTF neighbours of the BPFO lines, which count against an
        outer-race fault), ``nominal_hz`` (kinematic), ``found_hz`` (bin that carried
        it), ``level_db`` (above background) and ``decisive`` (True for the lines of
        the predicted family).
    """

    label: str
    evidence_db: dict
    threshold_db: dict
    band_hz: tuple
    rpm: float
    lines: object

    def __str__(self) -> str:
        head = (
            f"{self.label} at {self.rpm:g} rpm, band {self.band_hz[0]:g}-{self.band_hz[1]:g} Hz; "
            "evidence (threshold): "
            + ", ".join(
                f"{f} {self.evidence_db[f]:.1f} dB ({self.threshold_db[f]:.1f})"
                for f in FAULT_FAMILIES
            )
        )
        if self.label == "healthy":
            return head + "; no family above its threshold"
        decisive = self.lines[self.lines["decisive"]]
        body = "; ".join(
            f"{r.line} {r.found_hz:.1f} Hz {r.level_db:+.1f} dB"
            + (" (against)" if r.role == "refuting sideband" else "")
            for r in decisive.itertuples()
        )
        return f"{head}\n  {body}"


class EnvelopeDiagnoser(ClassifierMixin, BaseEstimator):
    """Physics-based bearing diagnosis from the squared envelope spectrum.

    Predicts ``"healthy"``, ``"outer"``, ``"inner"`` or ``"ball"`` from the evidence of
    each fault family (:func:`envelope_evidence`): the family with the largest evidence
    above its threshold, else healthy. Needs no training data; it declares itself
    fitted. :meth:`fit` only calibrates the thresholds on healthy signals of the
    machine, which makes the diagnoser more sensitive on quiet machines and less
    trigger-happy on noisy ones.

    Parameters
    ----------
    bearing : str or Bearing, optional
        Catalogue name or :class:`ballpass.Bearing` (default ``"6205"``, CWRU drive end).
    fs : float, optional
        Sampling frequency of the signals, Hz (default 12000).
    rpm : float, optional
        Shaft speed, rev/min (default 1797); ``predict(X, rpm=...)`` overrides it per row.
    band : (float, float) or None, optional
        Demodulation band, Hz; ``None`` (default) picks it per signal (fast kurtogram).
    prewhiten : bool, optional
        Cepstrum pre-whitening before demodulation (default False).
    harmonics : int, optional
        Harmonics of each family (default 3).
    slip : float, optional
        Largest relative slip searched (default 0.02).
    background_hz : float, optional
        Half-width of the SES background median, Hz (default 10).
    threshold_db : float, optional
        Evidence a family needs to be named, dB (default 5.0), until :meth:`fit`
        calibrates per-family thresholds. Noise reads 2-4 dB: on white noise the
        default is exceeded by fewer than 1 in 1000 one-second signals.
    quantile : float, optional
        :meth:`fit`: quantile of the healthy evidence a threshold sits on, in (0, 1]
        (default 0.99).
    margin_db : float, optional
        :meth:`fit`: added to that quantile, dB (default 1.0).
    softness_db : float, optional
        Temperature of :meth:`predict_proba`, dB (default 2.0).

    Attributes
    ----------
    classes_ : ndarray of str
        ``["ball", "healthy", "inner", "outer"]`` (sorted, as scikit-learn orders classes).
    thresholds_ : dict of str to float
        Per-family thresholds, dB, after :meth:`fit`.

    See Also
    --------
    envelope_evidence : the evidence this estimator thresholds.

    Examples
    --------
    >>> import numpy as np
    >>> import ballpass as bp
    >>> fs, rpm = 12_000.0, 1797.0
    >>> bpfi = bp.Bearing.catalog("6205").frequencies(rpm / 60).bpfi
    >>> t = np.arange(12_000) / fs
    >>> phase = (t * bpfi) % 1.0 / bpfi                       # time since the last impact, s
    >>> zone = 1 + np.cos(2 * np.pi * rpm / 60 * t)           # load-zone modulation
    >>> x = zone * np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    >>> x = x + 0.2 * np.random.default_rng(0).standard_normal(t.size)
    >>> diag = bp.diagnose.EnvelopeDiagnoser(bearing="6205", fs=fs, rpm=rpm)
    >>> diag.predict(np.stack([x, np.random.default_rng(1).standard_normal(t.size)]))
    array(['inner', 'healthy'], dtype=object)
    """

    def __init__(
        self,
        bearing="6205",
        fs=12_000.0,
        rpm=1797.0,
        *,
        band=None,
        prewhiten=False,
        harmonics=3,
        slip=0.02,
        background_hz=10.0,
        threshold_db=5.0,
        quantile=0.99,
        margin_db=1.0,
        softness_db=2.0,
    ):
        self.bearing = bearing
        self.fs = fs
        self.rpm = rpm
        self.band = band
        self.prewhiten = prewhiten
        self.harmonics = harmonics
        self.slip = slip
        self.background_hz = background_hz
        self.threshold_db = threshold_db
        self.quantile = quantile
        self.margin_db = margin_db
        self.softness_db = softness_db

    classes_ = np.array(sorted(LABELS), dtype=object)

    def __sklearn_is_fitted__(self) -> bool:
        return True

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.requires_fit = False
        tags.target_tags.required = False
        return tags

    # ------------------------------------------------------------ evidence
    def _evidence(self, X, rpm) -> EnvelopeEvidence:
        X = check_array(X, dtype=[np.float64, np.float32], ensure_min_features=2)
        return envelope_evidence(
            X,
            self.fs,
            self.bearing,
            self.rpm if rpm is None else rpm,
            band=self.band,
            prewhiten=self.prewhiten,
            harmonics=self.harmonics,
            slip=self.slip,
            background_hz=self.background_hz,
        )

    def _thresholds(self) -> dict:
        fitted = getattr(self, "thresholds_", None)
        if fitted is not None:
            return dict(fitted)
        return dict.fromkeys(FAULT_FAMILIES, float(check_nonnegative("threshold_db",
                                                                     self.threshold_db)))

    def _decision(self, ev: EnvelopeEvidence) -> np.ndarray:
        thresholds = self._thresholds()
        margin = {f: ev.evidence_db[f] - thresholds[f] for f in FAULT_FAMILIES}
        margin["healthy"] = -np.max(np.stack([margin[f] for f in FAULT_FAMILIES]), axis=0)
        return np.column_stack([margin[c] for c in self.classes_])

    # ------------------------------------------------------------ estimator API
    def fit(self, X, y=None, rpm=None):
        """Calibrate the per-family thresholds on healthy signals.

        Each threshold becomes the ``quantile`` of that family's evidence over the
        healthy rows plus ``margin_db``.

        Parameters
        ----------
        X : array_like, shape (n_signals, n_samples)
            Signals sampled at ``fs``.
        y : array_like of str, shape (n_signals,), optional
            Labels; only the ``"healthy"`` rows are used. ``None``: all rows are healthy.
        rpm : float or array_like of shape (n_signals,), optional
            Shaft speed per row, rev/min; default ``self.rpm``.

        Returns
        -------
        self
        """
        X = check_array(X, dtype=[np.float64, np.float32], ensure_min_features=2)
        q = float(self.quantile)
        if not 0.0 < q <= 1.0:
            raise ValueError(f"quantile must be in (0, 1], got {self.quantile!r}")
        healthy = np.ones(len(X), bool) if y is None else np.asarray(y) == "healthy"
        if not healthy.any():
            raise ValueError("fit needs at least one healthy signal (y == 'healthy') to "
                             "calibrate the thresholds; without fit the defaults apply")
        rpm = None if rpm is None else check_rpm(rpm, (len(X),))[healthy]
        ev = self._evidence(X[healthy], rpm)
        margin = float(check_nonnegative("margin_db", self.margin_db))
        self.thresholds_ = {
            f: float(np.quantile(ev.evidence_db[f], q)) + margin for f in FAULT_FAMILIES
        }
        return self

    def decision_function(self, X, rpm=None):
        """Margin of each class, dB, columns in the order of ``classes_``.

        A fault class scores its evidence minus its threshold; ``"healthy"`` scores
        minus the largest of those. The predicted class has the largest score.

        Parameters
        ----------
        X : array_like, shape (n_signals, n_samples)
        rpm : float or array_like of shape (n_signals,), optional
            Shaft speed per row, rev/min; default ``self.rpm``.

        Returns
        -------
        ndarray, shape (n_signals, 4)
        """
        return self._decision(self._evidence(X, rpm))

    def predict_proba(self, X, rpm=None):
        """Softmax of :meth:`decision_function` / ``softness_db``, columns as ``classes_``.

        A monotone squashing of the dB margins into scores that sum to one, not a
        calibrated probability.

        Returns
        -------
        ndarray, shape (n_signals, 4)
        """
        z = self.decision_function(X, rpm) / float(self.softness_db)
        z -= z.max(axis=1, keepdims=True)
        p = np.exp(z)
        return p / p.sum(axis=1, keepdims=True)

    def predict(self, X, rpm=None):
        """Label of each signal: ``"healthy"``, ``"outer"``, ``"inner"`` or ``"ball"``.

        Parameters
        ----------
        X : array_like, shape (n_signals, n_samples)
            Signals sampled at ``fs``, e.g. acceleration in m/s^2.
        rpm : float or array_like of shape (n_signals,), optional
            Shaft speed per row, rev/min; default ``self.rpm``.

        Returns
        -------
        ndarray of str (object), shape (n_signals,)
        """
        return self.classes_[self.decision_function(X, rpm).argmax(axis=1)]

    def explain(self, X, rpm=None) -> list[Explanation]:
        """Which lines carried each decision, and how far above the background.

        Parameters
        ----------
        X : array_like, shape (n_signals, n_samples)
        rpm : float or array_like of shape (n_signals,), optional
            Shaft speed per row, rev/min; default ``self.rpm``.

        Returns
        -------
        list of Explanation
            One per signal; ``print`` one for a summary.
        """
        import pandas as pd

        ev = self._evidence(X, rpm)
        labels = self.classes_[self._decision(ev).argmax(axis=1)]
        speeds = check_rpm(self.rpm if rpm is None else rpm, (len(labels),))
        thresholds = self._thresholds()
        layout = {f: _family_lines(f, self.harmonics) for f in FAULT_FAMILIES}
        out = []
        for i, label in enumerate(labels):
            frames = [
                pd.DataFrame({
                    "fault": fault,
                    "line": ev.line_names[fault],
                    "harmonic": [h for _, h, _ in layout[fault]],
                    "role": [_role(fault, side) for _, _, side in layout[fault]],
                    "nominal_hz": ev.nominal_hz[fault][i],
                    "found_hz": ev.found_hz[fault][i],
                    "level_db": ev.levels_db[fault][i],
                    "decisive": fault == label,
                })
                for fault in FAULT_FAMILIES
            ]
            out.append(Explanation(
                label=str(label),
                evidence_db={f: float(ev.evidence_db[f][i]) for f in FAULT_FAMILIES},
                threshold_db=thresholds,
                band_hz=(float(ev.band_hz[i, 0]), float(ev.band_hz[i, 1])),
                rpm=float(speeds[i]),
                lines=pd.concat(frames, ignore_index=True),
            ))
        return out
