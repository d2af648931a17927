"""Features a machine cannot shift: the diagnoser's evidence, as a feature set.

A learned model trained on simulations meets a real machine as a stranger when its
features carry the units of one machine: an RMS, a peak, a level at a frequency in Hz.
The envelope diagnoser reads what no gain, resonance or speed of a machine can move:
each fault family's lines in dB over their local background, at the kinematic orders
of the bearing, in the band where the family's own evidence reads highest
(:func:`~ballpass.diagnose.envelope_evidence`, after Randall & Antoni 2011 and Smith &
Randall 2015). :class:`EvidenceTransformer` turns that into a feature vector:

* ``<family>_evidence_db``: the family's evidence, dB above the SES background (three);
* ``<family>_<line>_db``: the level of each line of the family (carrier harmonics and
  their sidebands: ``outer_1xBPFO``, ``inner_2xBPFI+fr``, ``ball_1x2xBSF-FTF``, ...),
  dB above the local background at the best-fitting slip scale (``9 x 3`` at three
  harmonics);
* ``ses_order_<o>``: the squared envelope spectrum in the band of the strongest
  family, on an **order** axis (frequency / shaft frequency, so that a speed shift
  does not move it), in dB over its own median, the highest value in each order bin
  ``[o, o + order_step)`` from ``order_step`` to ``max_order``.

Every value is a ratio of two levels of the same signal, or an order: multiplying a
recording by a constant (another amplifier gain or unit) changes none of them.
A line another family's carrier explains counts for neither family and reads 0 dB;
lines on a shaft harmonic or beyond the spectrum and families that cannot be judged
are NaN: impute them in a pipeline (:func:`~ballpass.diagnose.make_pipeline` does).

Examples
--------
>>> import numpy as np
>>> import ballpass as bp
>>> from ballpass.diagnose import EvidenceTransformer
>>> scene = bp.Scene("6205", rpm=1797, fs=12_000, duration_s=1.0, resonance_hz=3_000,
...                  fault=bp.Fault("outer"), noise_rms=0.05)
>>> x = bp.simulate(scene, model="impulse").accel[None]
>>> tr = EvidenceTransformer("6205", fs=12_000, rpm=1797).set_output(transform="pandas")
>>> f = tr.fit_transform(x)
>>> f.shape
(1, 78)
>>> bool(f["outer_evidence_db"].iloc[0] > f["inner_evidence_db"].iloc[0] + 6)
True
"""

from __future__ import annotations

import math

import numpy as np
from sklearn.base import BaseEstimator, TransformerMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from .._params import StatelessMixin, keep_params
from ..features import envelope_spectrum
from ..features._validation import check_fs, check_positive_int, check_rpm
from .evidence import FAULT_FAMILIES, envelope_evidence, family_lines

__all__ = ["EvidenceTransformer", "evidence_feature_names"]

#: Fewest samples a row needs for evidence: one SES line resolved from its neighbours
#: needs several shaft revolutions; below this every feature is NaN.
MIN_SAMPLES = 256


def evidence_feature_names(harmonics: int = 3, max_order: float = 12.0,
                           order_step: float = 0.25) -> list[str]:
    """Names of the :class:`EvidenceTransformer` features, in output order.

    Examples
    --------
    >>> from ballpass.diagnose.invariant import evidence_feature_names
    >>> names = evidence_feature_names(harmonics=1, max_order=1.0, order_step=0.5)
    >>> names[:4], names[-2:]
    (['outer_evidence_db', 'inner_evidence_db', 'ball_evidence_db', 'outer_1xBPFO_db'], \
['ses_order_0.5', 'ses_order_1'])
    """
    names = [f"{family}_evidence_db" for family in FAULT_FAMILIES]
    for family in FAULT_FAMILIES:
        names += [f"{family}_{line}_db" for line, _, _ in family_lines(family, harmonics)]
    return names + [f"ses_order_{o:g}" for o in _order_edges(max_order, order_step)[:-1]]


def _order_edges(max_order: float, order_step: float) -> np.ndarray:
    n = int(math.floor(max_order / order_step + 1e-9))
    return order_step * np.arange(1, n + 2)


class EvidenceTransformer(StatelessMixin, TransformerMixin, BaseEstimator):
    """Fault-family evidence and order-normalized SES of each signal (no absolute units).

    ``(n_signals, n_samples) -> (n_signals, n_features)``; see the module notes for the
    features and :func:`evidence_feature_names` for their names.

    Parameters
    ----------
    bearing : str or Bearing, optional
        Catalogue name or :class:`ballpass.Bearing` (default ``"6205"``).
    fs : float, optional
        Sampling frequency of the rows, Hz (default 12000).
    rpm : float, optional
        Shaft speed, rev/min (default 1797). ``transform(X, rpm=...)`` overrides it per
        row; in a pipeline route it with ``set_transform_request(rpm=True)``.
    harmonics : int, optional
        Harmonics 1..H of each family (default 3).
    max_order : float, optional
        Highest shaft order of the order-normalized SES (default 12: it holds two
        harmonics of each family of a 6205 with their sidebands, BPFI 5.4 and 10.8 +- 1,
        BPFO 3.6 and 7.2, 2xBSF 4.7 and 9.4; the line levels cover the third).
    order_step : float, optional
        Width of the SES order bins (default 0.25 orders: wider than the slip search at
        the fifth order, 2 % of 5 = 0.1, narrower than the gap between a 6205's BPFI and
        2xBSF, 0.70).

    See Also
    --------
    ballpass.diagnose.envelope_evidence : the evidence this wraps.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.diagnose import EvidenceTransformer
    >>> X = np.random.default_rng(0).standard_normal((2, 12_000))
    >>> tr = EvidenceTransformer("6205", fs=12_000, rpm=1797, harmonics=1, max_order=6)
    >>> tr.fit_transform(X, rpm=[1750.0, 1797.0]).shape     # 3 + 3 x 3 lines + 24 orders
    (2, 36)
    """

    def __init__(self, bearing="6205", fs=12_000.0, rpm=1797.0, *, harmonics=3,
                 max_order=12.0, order_step=0.25):
        keep_params(self, locals())

    def _check_params(self) -> None:
        check_fs(self.fs)
        check_positive_int("harmonics", self.harmonics, 1)
        for name in ("max_order", "order_step"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value) or value <= 0:
                raise ValueError(f"{name} must be a positive number, got {value!r}")
        if self.order_step > self.max_order:
            raise ValueError(f"order_step = {self.order_step:g} exceeds max_order = "
                             f"{self.max_order:g}")

    def fit(self, X, y=None):
        """Validate ``X`` (n_signals, n_samples) and the parameters; returns self."""
        self._check_params()
        validate_data(self, X, reset=True, dtype=[np.float64, np.float32])
        return self

    def transform(self, X, rpm=None):
        """Features of each row of ``X``.

        Parameters
        ----------
        X : array_like, shape (n_signals, n_samples)
            Signals sampled at ``fs`` (any unit: only ratios are kept).
        rpm : float or array_like of shape (n_signals,), optional
            Shaft speed per row, rev/min; default ``self.rpm``.

        Returns
        -------
        ndarray, shape (n_signals, n_features)
            NaN where a line or family cannot be judged, and everywhere in rows shorter
            than :data:`MIN_SAMPLES`; 0 dB everywhere in rows where no band holds signal.
        """
        check_is_fitted(self)
        self._check_params()
        X = validate_data(self, X, reset=False, dtype=[np.float64, np.float32])
        speed = check_rpm(self.rpm if rpm is None else np.reshape(rpm, -1), (len(X),))
        out = np.full((len(X), len(self._names())), np.nan)
        if X.shape[1] < MIN_SAMPLES:
            return out
        ev = envelope_evidence(X, float(self.fs), self.bearing, speed,
                               harmonics=int(self.harmonics))
        families = list(FAULT_FAMILIES)
        evidence = np.column_stack([ev.evidence_db[f] for f in families])
        out[:, :3] = np.where(np.isfinite(evidence), evidence, np.nan)
        col = 3
        for f in families:
            # a line another family's carrier explains counts for neither: 0 dB, not a gap
            levels = np.where(ev.shared[f], 0.0, ev.levels_db[f])
            out[:, col:col + levels.shape[1]] = levels
            col += levels.shape[1]
        out[:, col:] = self._ses_orders(X, ev, evidence)
        # no band holds signal (a quiet healthy record): nothing stands above the
        # background, 0 dB everywhere, rather than a gap to impute
        out[ev.n_bands == 0] = 0.0
        return out

    def _ses_orders(self, X, ev, evidence) -> np.ndarray:
        """The SES in the strongest family's band, dB over its median, max per order bin."""
        edges = _order_edges(self.max_order, self.order_step)
        out = np.full((len(X), len(edges) - 1), np.nan)
        strongest = np.argmax(np.where(np.isfinite(evidence), evidence, -np.inf), axis=1)
        families = list(FAULT_FAMILIES)
        for i, x in enumerate(X):
            band = ev.band_hz[families[strongest[i]]][i]
            if not np.all(np.isfinite(band)):
                continue
            freqs, ses = envelope_spectrum(x, float(self.fs), band=tuple(band))
            floor = np.median(ses[1:])
            if not floor > 0:
                continue
            orders = freqs / (ev.rpm[i] / 60.0)
            db = 10.0 * np.log10(np.maximum(ses, 1e-300) / floor)
            which = np.digitize(orders, edges) - 1
            inside = (which >= 0) & (which < len(edges) - 1)
            row = np.full(len(edges) - 1, -np.inf)
            np.maximum.at(row, which[inside], db[inside])
            out[i] = np.where(np.isfinite(row), row, np.nan)
        return out

    def fit_transform(self, X, y=None, rpm=None):
        """``fit(X).transform(X, rpm=rpm)``."""
        return self.fit(X, y).transform(X, rpm=rpm)

    def _names(self) -> list[str]:
        return evidence_feature_names(int(self.harmonics), float(self.max_order),
                                      float(self.order_step))

    def get_feature_names_out(self, input_features=None):
        """Feature names (:func:`evidence_feature_names`), ndarray of str."""
        return np.asarray(self._names(), dtype=object)

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.input_tags.allow_nan = False
        return tags
