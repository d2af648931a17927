"""scikit-learn transformers over the feature functions.

Each row of ``X`` is one signal (``(n_signals, n_samples)``); each output column one
feature. The transformers are stateless: ``fit`` only validates and records the input
width; ``transform`` calls :func:`~ballpass.features.indicators` or
:func:`~ballpass.features.fault_band_features`. Column names come from
``get_feature_names_out``, so ``set_output(transform="pandas")`` gives labelled
DataFrames.
"""

from __future__ import annotations

import numpy as np
from sklearn.base import BaseEstimator, TransformerMixin
from sklearn.utils.validation import check_is_fitted, validate_data

from .._params import StatelessMixin, keep_params
from ._validation import check_fs, check_rpm
from .bands import fault_band_features, fault_band_names
from .indicators import INDICATORS, indicators
from .separation import check_separate, separated_rows

__all__ = ["IndicatorTransformer", "FaultBandTransformer"]


def _signals(estimator, X, *, reset: bool) -> np.ndarray:
    """Validate ``X`` as (n_signals, n_samples) with at least 2 samples per signal."""
    X = validate_data(estimator, X, reset=reset, dtype=[np.float64, np.float32])
    if X.shape[1] < 2:
        raise ValueError(
            f"X has {X.shape[1]} feature(s) (samples per signal); a signal needs at least 2"
        )
    return X


class IndicatorTransformer(StatelessMixin, TransformerMixin, BaseEstimator):
    """Statistical indicators of each signal: ``(n_signals, n_samples) -> (n_signals, k)``.

    Parameters
    ----------
    indicators : sequence of str or None, optional
        Names from :data:`ballpass.features.INDICATORS`, in output order; ``None``
        (default) for all of them.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import IndicatorTransformer
    >>> X = np.random.default_rng(0).standard_normal((4, 1000))
    >>> tr = IndicatorTransformer(indicators=["rms", "kurtosis"]).set_output(transform="pandas")
    >>> tr.fit_transform(X).columns.tolist()
    ['rms', 'kurtosis']
    """

    def __init__(self, indicators=None):
        self.indicators = indicators

    def _names(self) -> list[str]:
        if self.indicators is None:
            return list(INDICATORS)
        names = list(self.indicators)
        unknown = [n for n in names if n not in INDICATORS]
        if unknown or not names:
            raise ValueError(
                f"indicators must be a non-empty subset of {INDICATORS}, got {self.indicators!r}"
            )
        return names

    def fit(self, X, y=None):
        """Validate ``X`` (n_signals, n_samples) and the parameters; returns self."""
        self._names()
        _signals(self, X, reset=True)
        return self

    def transform(self, X):
        """Indicators of each row of ``X``; returns ndarray (n_signals, n_indicators)."""
        check_is_fitted(self)
        X = _signals(self, X, reset=False)
        values = indicators(X)
        return np.column_stack([values[name] for name in self._names()])

    def get_feature_names_out(self, input_features=None):
        """Indicator names, ndarray of str."""
        return np.asarray(self._names(), dtype=object)


class FaultBandTransformer(StatelessMixin, TransformerMixin, BaseEstimator):
    """Fault-band SES levels of each signal, dB: ``(n_signals, n_samples) -> (n_signals, k)``.

    Parameters
    ----------
    bearing : str or Bearing, optional
        Catalogue name or :class:`ballpass.Bearing` (default ``"6205"``, the CWRU
        drive-end bearing).
    fs : float, optional
        Sampling frequency of the rows, Hz (default 12000).
    rpm : float, optional
        Shaft speed, rev/min (default 1797). ``transform(X, rpm=...)`` overrides it
        per row; in a pipeline route it with ``set_transform_request(rpm=True)``
        (sklearn metadata routing).
    band : (float, float) or None, optional
        Demodulation band, Hz; ``None`` (default) chooses it per row (kurtogram).
    prewhiten : bool, optional
        Cepstrum pre-whitening (default False).
    harmonics : int, optional
        Harmonics 1..H of each line (default 3).
    tolerance : float, optional
        Relative slip tolerance of the line search (default 0.01).
    background_hz : float, optional
        Background window on each side of a line, Hz (default 10).
    separate : bool or {"tsa", "lp", "drs"}, optional
        Remove the discrete part (gear-mesh lines) before the SES
        (:func:`ballpass.features.separate_discrete`); ``True`` = ``"tsa"`` at each
        row's rpm. Default False.
    other_shafts : sequence of float, optional
        Further shafts' speeds as multiples of ``rpm`` for ``"tsa"`` (a gear pair's
        second shaft: teeth[0] / teeth[1]). Default ().

    See Also
    --------
    ballpass.features.fault_band_features : the function this wraps.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.features import FaultBandTransformer
    >>> X = np.random.default_rng(0).standard_normal((3, 12_000))
    >>> tr = FaultBandTransformer("6205", fs=12_000.0, rpm=1797.0, harmonics=1)
    >>> tr.fit_transform(X, rpm=[1730.0, 1750.0, 1797.0]).shape
    (3, 7)
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
        tolerance=0.01,
        background_hz=10.0,
        separate=False,
        other_shafts=(),
    ):
        keep_params(self, locals())

    def fit(self, X, y=None):
        """Validate ``X`` (n_signals, n_samples) and the parameters; returns self."""
        X = _signals(self, X, reset=True)
        self._features(X[:1], None)  # validates every parameter where it is used (one row)
        return self

    def _features(self, X: np.ndarray, rpm) -> np.ndarray:
        speed = self.rpm if rpm is None else np.asarray(rpm, dtype=float).reshape(-1)
        check_separate(self.separate, self.other_shafts)
        if self.separate is not False:
            X = separated_rows(X, check_fs(self.fs), check_rpm(speed, (len(X),)),
                               self.separate, self.other_shafts)
        values = fault_band_features(
            X,
            self.fs,
            self.bearing,
            speed,
            band=self.band,
            prewhiten=self.prewhiten,
            harmonics=self.harmonics,
            tolerance=self.tolerance,
            background_hz=self.background_hz,
        )
        return np.column_stack([values[name] for name in fault_band_names(self.harmonics)])

    def transform(self, X, rpm=None):
        """Fault-band levels of each row of ``X``, dB.

        Parameters
        ----------
        X : array_like, shape (n_signals, n_samples)
            Signals sampled at ``fs``.
        rpm : float or array_like of shape (n_signals,), optional
            Shaft speed per row, rev/min; default ``self.rpm``.

        Returns
        -------
        ndarray, shape (n_signals, n_features)
        """
        check_is_fitted(self)
        return self._features(_signals(self, X, reset=False), rpm)

    def fit_transform(self, X, y=None, rpm=None):
        """``fit(X).transform(X, rpm=rpm)``."""
        return self.fit(X, y).transform(X, rpm=rpm)

    def get_feature_names_out(self, input_features=None):
        """Feature names (:func:`ballpass.features.fault_band_names`), ndarray of str."""
        return np.asarray(fault_band_names(self.harmonics), dtype=object)
