"""Ready-made scikit-learn pipelines: signal features + a classifier.

Each pipeline takes raw signals ``X`` of shape ``(n_signals, n_samples)`` and has four
steps: ``"features"`` (a stateless :class:`~sklearn.pipeline.FeatureUnion` of
:class:`~ballpass.features.IndicatorTransformer` and
:class:`~ballpass.features.FaultBandTransformer`), ``"impute"`` (the median of the
training rows for undefined features: a fault line above the Nyquist frequency, the
kurtosis of a constant signal), ``"scale"`` (:class:`~sklearn.preprocessing.StandardScaler`)
and ``"classifier"``.

The feature step holds no fitted state: each row's features depend only on that row
(and its speed). ``pipe[:1].transform(X)`` can therefore be computed once and the
remaining steps ``pipe[1:]`` cross-validated on it, with exactly the result of
cross-validating the whole pipeline; :func:`ballpass.diagnose.run_benchmark` does this.

Speeds
------
The fault-band features need each row's shaft speed. With one speed for all rows, pass
``rpm=`` to :func:`make_pipeline`. With one speed per row, route it with scikit-learn
metadata routing; the pipeline already requests it::

    import sklearn
    with sklearn.config_context(enable_metadata_routing=True):
        pipe.fit(X_train, y_train, rpm=rpm_train)
        y_pred = pipe.predict(X_test, rpm=rpm_test)
"""

from __future__ import annotations

import sklearn
from sklearn.ensemble import HistGradientBoostingClassifier, RandomForestClassifier
from sklearn.impute import SimpleImputer
from sklearn.linear_model import LogisticRegression
from sklearn.neighbors import KNeighborsClassifier
from sklearn.pipeline import FeatureUnion, Pipeline
from sklearn.preprocessing import StandardScaler
from sklearn.svm import SVC

from ..features import INDICATORS
from ..features.transformers import FaultBandTransformer, IndicatorTransformer
from . import _names
from ._names import CLASSIFIERS, FEATURE_SETS
from .invariant import EvidenceTransformer

__all__ = ["CLASSIFIERS", "FEATURE_SETS", "make_classifier", "make_features", "make_pipeline"]

#: Indicators without a unit: they do not change with sensor sensitivity or gain.
_DIMENSIONLESS = tuple(n for n in INDICATORS if n not in ("rms", "peak", "peak_to_peak"))

#: Feature set name -> (indicators, or None for none; fault bands?; diagnoser evidence?)
_CONTENT = {
    "dimensionless": (_DIMENSIONLESS, True, False),
    "all": (INDICATORS, True, False),
    "bands": (None, True, False),
    "indicators": (INDICATORS, False, False),
    "evidence": (None, False, True),  # the EvidenceTransformer alone
    "combined": (_DIMENSIONLESS, True, True),  # "dimensionless" and "evidence"
}


def make_classifier(name: str, *, random_state=0):
    """The bare classifier of a pipeline (no feature or scaling step).

    Parameters
    ----------
    name : str
        One of :data:`CLASSIFIERS`.
    random_state : int or None, optional
        Seed of the randomised classifiers (default 0).

    Returns
    -------
    sklearn classifier

    Examples
    --------
    >>> from ballpass.diagnose import make_classifier
    >>> make_classifier("random_forest").get_params()["n_estimators"]
    100
    >>> make_classifier("tree")                             # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    ValueError: classifier must be one of ['gradient_boosting', 'knn', ...], got 'tree'
    """
    # Grids give one healthy run per operating point against one per fault size and
    # kind: the classes are weighted to count equally (kNN has no weights).
    if name == "random_forest":
        # trees are fitted on every core (threads: the trees' fitting releases the GIL)
        return RandomForestClassifier(n_estimators=_names.FOREST_TREES,
                                      class_weight="balanced", n_jobs=-1,
                                      random_state=random_state)
    if name == "gradient_boosting":
        return HistGradientBoostingClassifier(class_weight="balanced",
                                              random_state=random_state)
    if name == "svm":
        return SVC(C=10.0, gamma="scale", class_weight="balanced", random_state=random_state)
    if name == "knn":
        return KNeighborsClassifier(n_neighbors=5)
    if name == "logistic":
        return LogisticRegression(C=1.0, class_weight="balanced", max_iter=2000)
    raise ValueError(f"classifier must be one of {sorted(CLASSIFIERS)}, got {name!r}")


def make_features(
    features: str = "dimensionless",
    *,
    bearing="6205",
    fs: float = 12_000.0,
    rpm: float = 1797.0,
    band=None,
    harmonics: int = 3,
    separate=False,
    other_shafts=(),
):
    """The stateless feature step: ``(n_signals, n_samples) -> (n_signals, n_features)``.

    Parameters
    ----------
    features : str, optional
        Feature set, one of :data:`FEATURE_SETS`:

        * ``"dimensionless"`` (default): crest, kurtosis, skewness, shape, impulse and
          clearance factors and the fault-band SES levels (dB). Nothing in it scales
          with the sensor's sensitivity or the machine's vibration level, so it
          transfers between machines and from simulation to measurement;
        * ``"all"``: also RMS, peak and peak-to-peak (m/s^2);
        * ``"bands"``: the fault-band levels only;
        * ``"indicators"``: the statistical indicators only;
        * ``"evidence"``: what the envelope diagnoser reads, as features
          (:class:`~ballpass.diagnose.EvidenceTransformer`): each fault family's
          evidence and line levels in dB over their local background, in the band its
          own evidence picks, and the squared envelope spectrum on an order axis in dB
          over its median. No value has a unit of the machine; ``band`` and
          ``separate`` do not apply;
        * ``"combined"``: the ``"evidence"`` features followed by the
          ``"dimensionless"`` ones (``band`` and ``separate`` apply to the latter).
    bearing : str or Bearing, optional
        For the fault bands (default ``"6205"``).
    fs : float, optional
        Sampling frequency, Hz (default 12000).
    rpm : float, optional
        Shaft speed, rev/min, when not routed per row (default 1797).
    band : (float, float) or None, optional
        Demodulation band, Hz; ``None`` (default) chooses it per row (kurtogram).
    harmonics : int, optional
        Harmonics of each fault line (default 3).
    separate, other_shafts : optional
        Discrete/random separation before the fault bands (gear-mesh lines in a
        gearbox); see :class:`~ballpass.features.FaultBandTransformer`. Default off.

    Returns
    -------
    sklearn.pipeline.FeatureUnion
        Fault bands request ``rpm`` in ``transform`` (metadata routing).

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.diagnose import make_features
    >>> X = np.random.default_rng(0).standard_normal((2, 12_000))
    >>> step = make_features("dimensionless", fs=12_000, rpm=1797)
    >>> step.fit_transform(X).shape                 # 6 shape indicators + 21 fault bands
    (2, 27)
    """
    if features not in FEATURE_SETS:
        raise ValueError(f"features must be one of {sorted(FEATURE_SETS)}, got {features!r}")
    indicators, bands, evidence = _CONTENT[features]
    parts = []
    if evidence:
        ev = EvidenceTransformer(bearing, fs=fs, rpm=rpm, harmonics=harmonics)
        with sklearn.config_context(enable_metadata_routing=True):
            ev.set_transform_request(rpm=True)
        parts.append(("evidence", ev))
    if indicators is not None:
        parts.append(("indicators", IndicatorTransformer(indicators=list(indicators))))
    if bands:
        fb = FaultBandTransformer(bearing, fs=fs, rpm=rpm, band=band, harmonics=harmonics,
                                  separate=separate, other_shafts=other_shafts)
        with sklearn.config_context(enable_metadata_routing=True):
            fb.set_transform_request(rpm=True)
        parts.append(("bands", fb))
    return FeatureUnion(parts)


def make_pipeline(
    classifier: str = "random_forest",
    *,
    features: str = "dimensionless",
    bearing="6205",
    fs: float = 12_000.0,
    rpm: float = 1797.0,
    band=None,
    harmonics: int = 3,
    separate=False,
    other_shafts=(),
    random_state=0,
) -> Pipeline:
    """A ready-made pipeline: signal features, standard scaling, a classifier.

    Parameters
    ----------
    classifier : str, optional
        One of :data:`CLASSIFIERS` (default ``"random_forest"``).
    features : str, optional
        Feature set, one of :data:`FEATURE_SETS` (default ``"dimensionless"``); see
        :func:`make_features`.
    bearing, fs, rpm, band, harmonics, separate, other_shafts
        Of the feature step; see :func:`make_features`.
    random_state : int or None, optional
        Seed of the randomised classifiers (default 0).

    Returns
    -------
    sklearn.pipeline.Pipeline
        Steps ``"features"``, ``"impute"``, ``"scale"``, ``"classifier"``.

    Examples
    --------
    >>> import numpy as np
    >>> from ballpass.diagnose import make_pipeline
    >>> rng = np.random.default_rng(0)
    >>> X = rng.standard_normal((20, 12_000))
    >>> X[10:] += 3 * (rng.random((10, 12_000)) < 0.002)   # impulsive rows
    >>> y = np.repeat(["healthy", "outer"], 10)
    >>> pipe = make_pipeline("logistic", fs=12_000, rpm=1797).fit(X, y)
    >>> (pipe.predict(X) == y).mean()
    np.float64(1.0)
    """
    return Pipeline([
        ("features", make_features(features, bearing=bearing, fs=fs, rpm=rpm, band=band,
                                   harmonics=harmonics, separate=separate,
                                   other_shafts=other_shafts)),
        ("impute", SimpleImputer(strategy="median")),
        ("scale", StandardScaler()),
        ("classifier", make_classifier(classifier, random_state=random_state)),
    ])
