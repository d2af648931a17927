"""Classifier benchmarks without leakage between training and test data.

Segments cut from one simulation run (or one recording) share its fault, its speed,
its random slip and noise: a classifier that saw some of them in training recognises
the others by those shared details, not by the fault. Every split here therefore keeps
the rows of a ``group`` (a run, or a recording) on one side. What each split measures:

``run``
    Stratified group k-fold over runs: new runs of conditions seen in training.
``speed``, ``load``, ``fault_size``
    Leave one shaft speed / load / fault size out: generalisation to an unseen operating
    point or defect size. For ``fault_size`` the healthy runs, which have no size, are
    spread over the folds by group. On an axis drawn from a distribution (every run its
    own value) each of :data:`QUANTILE_BINS` quantile bins is left out in turn instead;
    :attr:`BenchmarkResult.info` ``["fold_rules"]`` and the report say which rule made
    the folds.
``sensor``
    Train on the loaded-zone sensor of some runs, test on the unloaded-zone sensor of
    the other runs: a change of transfer path.
``random``
    **Optimistic**: k-fold over rows, ignoring groups, so segments of one run sit on both
    sides. Reported only next to the honest splits, to show how much leakage inflates
    a score.
``sim2real``
    Train on every simulated row, test on real recordings.

The feature step of the pipelines is stateless (each row's features depend on that row
alone), so it is computed once per dataset and only the classifier is refitted per fold;
the physics-based :class:`~ballpass.diagnose.EnvelopeDiagnoser` is calibrated on the
healthy training rows of each fold (:meth:`~ballpass.diagnose.EnvelopeDiagnoser.fit`).
"""

from __future__ import annotations

import hashlib
import sys
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
import sklearn
from sklearn.base import clone
from sklearn.metrics import accuracy_score, confusion_matrix, f1_score, recall_score
from sklearn.model_selection import StratifiedGroupKFold, StratifiedKFold
from threadpoolctl import threadpool_limits
from tqdm.auto import tqdm

from ..signalio import atomic_write
from ._names import CLASSIFIERS, FEATURE_SETS, LABELS, MODELS, QUANTILE_BINS, RECOMMENDED, SPLITS
from .evidence import FAULT_FAMILIES
from .pipelines import make_features, make_pipeline
from .rules import EnvelopeDiagnoser

__all__ = ["SPLITS", "MODELS", "BenchmarkResult", "split_indices", "run_benchmark"]

_OPTIMISTIC = {"random"}
#: the classes of the three-class (normal, inner, outer) score
THREE_CLASSES = ("healthy", "outer", "inner")


@dataclass
class BenchmarkResult:
    """Scores of every model on every split.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per (split, model): ``split``, ``model``, ``optimistic``, ``folds``,
        ``n_test``, ``accuracy``, ``macro_f1`` (over the classes present in the test
        rows), ``accuracy_fold_min`` and ``accuracy_fold_max`` (the spread over the
        folds) and ``recall_<label>`` for each of :data:`~ballpass.diagnose.LABELS`
        (NaN when the class is absent from the test rows). Scores pool the
        out-of-fold predictions of all folds.
        Also ``balanced_accuracy`` (the mean recall over the classes present: four
        classes where all are), ``accuracy_3class`` (over the normal, outer- and
        inner-race rows; a "ball" answer on them is an error) and
        ``balanced_accuracy_3class`` (the mean recall of those three).
    confusion : dict of (str, str) to ndarray of int, shape (4, 4)
        Confusion matrix per (split, model); rows true, columns predicted, in the order
        of :data:`~ballpass.diagnose.LABELS`.
    predictions : pandas.DataFrame
        Every out-of-fold prediction: ``split``, ``model``, ``fold``, ``row`` (index in
        the test dataset: the real one for ``sim2real``), ``group``, ``y_true``,
        ``y_pred``, and ``file`` where the test rows have one (real recordings). One
        row per test row and model: for ``sim2real``, the predictions of the first
        training seed.
    spread : pandas.DataFrame
        ``sim2real`` only: the scores of every model for each training seed
        (``seed`` = the classifiers' ``random_state``; the envelope diagnoser has no
        seed and appears once), columns as ``table``.
    skipped : dict of str to str
        Splits that could not be formed on this dataset, with the reason.
    info : dict
        Dataset and settings: rows, groups, features, bearing, fs, ...;
        ``fold_rules``: split -> the rule that made its folds, in words (leave one
        value out, or one quantile bin of a drawn axis).

    Examples
    --------
    :func:`run_benchmark` returns one; its examples show the table and a confusion
    matrix.
    """

    table: pd.DataFrame
    confusion: dict
    predictions: pd.DataFrame
    skipped: dict = field(default_factory=dict)
    info: dict = field(default_factory=dict)
    spread: pd.DataFrame = field(default_factory=pd.DataFrame)


def _check_meta(meta: pd.DataFrame, n: int, name: str) -> None:
    if not isinstance(meta, pd.DataFrame):
        raise TypeError(f"{name} must be a pandas DataFrame, got {type(meta).__name__}")
    if len(meta) != n:
        raise ValueError(f"{name} has {len(meta)} rows but X has {n}")
    missing = {"label", "group", "rpm"} - set(meta.columns)
    if missing:
        raise ValueError(f"{name} lacks column(s) {sorted(missing)}")
    unknown = set(meta["label"]) - set(LABELS)
    if unknown:
        raise ValueError(f"{name}.label holds {sorted(unknown)}; allowed: {LABELS}")


def _load_column(meta: pd.DataFrame) -> str | None:
    for col in ("radial_load_n", "load_hp"):
        if col in meta.columns and meta[col].nunique() > 1:
            return col
    return None


def _stratified_group_folds(y, groups, n_splits: int, random_state) -> list:
    """Group k-fold, stratified on the label; fewer folds when groups are few."""
    counts = pd.Series(groups).groupby(np.asarray(y)).nunique()
    k = int(min(n_splits, counts.max()))
    if k < 2:
        return []
    cv = StratifiedGroupKFold(n_splits=k, shuffle=True, random_state=random_state)
    return list(cv.split(np.zeros(len(y)), y, groups))


#: An axis not known to be drawn (no ``drawn`` given) with more distinct values than this
#: is treated as drawn: leaving each value out would cost a fit per value.
MAX_VALUE_FOLDS = 12


def _leave_one_value_out(values: np.ndarray) -> list:
    out = []
    for v in np.unique(values):
        test = np.flatnonzero(values == v)
        out.append((np.flatnonzero(values != v), test))
    return out


def _quantile_bins(values: np.ndarray, groups: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Bin index of each row (-1 where the value is NaN) and the bin edges.

    The edges are quantiles of the values over the groups (one value per run), so the
    bins hold about equal numbers of runs; every row of a group falls in its group's bin.
    """
    finite = np.isfinite(values)
    per_group = pd.Series(values[finite]).groupby(groups[finite]).first().to_numpy()
    edges = np.unique(np.quantile(per_group, np.linspace(0.0, 1.0, QUANTILE_BINS + 1)))
    bins = np.full(len(values), -1)
    # interior edges only: bin k holds edges[k] <= v < edges[k + 1], the last one closed
    bins[finite] = np.searchsorted(edges[1:-1], values[finite], side="right")
    return bins, edges


def _levels(values: np.ndarray, groups: np.ndarray, name: str, drawn) -> tuple[np.ndarray, str]:
    """The level of each row that a leave-one-level-out split leaves out, and the rule.

    A listed axis leaves out each of its values; a drawn one (named in ``drawn``, or, when
    ``drawn`` is None, one with more than :data:`MAX_VALUE_FOLDS` distinct values) each of
    :data:`QUANTILE_BINS` quantile bins. NaN (no value: healthy rows of a size axis) is
    level -1.
    """
    finite = values[np.isfinite(values)]
    n_values = np.unique(finite).size
    is_drawn = n_values > MAX_VALUE_FOLDS if drawn is None else name in drawn
    if not is_drawn or n_values <= QUANTILE_BINS:
        levels = np.where(np.isfinite(values), values, -1.0)
        return levels, f"leave one value of `{name}` out ({n_values} values)"
    bins, edges = _quantile_bins(values, groups)
    why = "drawn axis" if drawn is not None else f"more than {MAX_VALUE_FOLDS} values"
    ranges = ", ".join(f"[{lo:.4g}, {hi:.4g}{']' if k == len(edges) - 2 else ')'}"
                       for k, (lo, hi) in enumerate(zip(edges[:-1], edges[1:], strict=True)))
    return bins, (f"leave one of {len(edges) - 1} quantile bins of `{name}` out ({why}, "
                  f"{n_values} values): {ranges}")


def split_indices(meta: pd.DataFrame, split: str, *, n_splits: int = 5,
                  random_state=0, drawn=None) -> list[tuple[np.ndarray, np.ndarray]]:
    """Train/test row indices of one split of a dataset.

    Parameters
    ----------
    meta : pandas.DataFrame
        Row metadata as :func:`ballpass.datasets.load` returns it: at least ``label``,
        ``group`` and ``rpm``; ``radial_load_n`` or ``load_hp`` for ``load``,
        ``fault_width_mm`` for ``fault_size``, ``sensor`` for ``sensor``.
    split : str
        One of :data:`SPLITS` except ``"sim2real"`` (which needs two datasets).
    n_splits : int, optional
        Folds of the k-fold splits (``run``, ``sensor``, ``random``; default 5), fewer
        when the classes have fewer groups.
    random_state : int or None, optional
        Shuffling seed of the k-fold splits (default 0).
    drawn : collection of str, optional
        Columns drawn from a distribution (a grid's drawn axes, e.g.
        ``ballpass.datasets.info(folder)["drawn"]``): ``speed``, ``load`` and
        ``fault_size`` leave out each of :data:`QUANTILE_BINS` quantile bins of such a
        column instead of each distinct value. Default None: a column with more than
        :data:`MAX_VALUE_FOLDS` distinct values counts as drawn.

    Returns
    -------
    list of (ndarray, ndarray)
        ``(train, test)`` positional indices per fold; empty when the dataset cannot
        form the split (one speed only, no unloaded sensor, ...). Except for
        ``random``, no ``group`` has rows on both sides of any fold.

    Examples
    --------
    >>> import pandas as pd
    >>> from ballpass.diagnose import split_indices
    >>> meta = pd.DataFrame({"label": ["healthy", "outer"] * 4, "group": [0, 1, 2, 3] * 2,
    ...                      "rpm": [1730, 1730, 1797, 1797] * 2})
    >>> [(tr.tolist(), te.tolist()) for tr, te in split_indices(meta, "speed")]
    [([2, 3, 6, 7], [0, 1, 4, 5]), ([0, 1, 4, 5], [2, 3, 6, 7])]
    """
    return _split(meta, split, n_splits, random_state, drawn)[0]


def _split(meta: pd.DataFrame, split: str, n_splits: int, random_state, drawn
           ) -> tuple[list, str]:
    """:func:`split_indices` and, in words, the rule that made its folds."""
    _check_meta(meta, len(meta), "meta")
    y = meta["label"].to_numpy()
    groups = meta["group"].to_numpy()
    rule = SPLITS.get(split, "")
    if split == "run":
        return _stratified_group_folds(y, groups, n_splits, random_state), rule
    if split == "speed":
        levels, rule = _levels(np.round(meta["rpm"].to_numpy(float)), groups, "rpm", drawn)
        folds = _leave_one_value_out(levels)
    elif split == "load":
        col = _load_column(meta)
        if col is None:
            return [], rule
        levels, rule = _levels(meta[col].to_numpy(float), groups, col, drawn)
        folds = _leave_one_value_out(levels)
    elif split == "fault_size":
        width = meta["fault_width_mm"].to_numpy(float) if "fault_width_mm" in meta else None
        if width is None or np.unique(width[np.isfinite(width)]).size < 2:
            return [], rule
        levels, rule = _levels(width, groups, "fault_width_mm", drawn)
        sizes = np.unique(levels[levels != -1])
        # Healthy runs have no size: deal their groups round-robin over the folds.
        healthy = y == "healthy"
        order = np.random.default_rng(random_state).permutation(np.unique(groups[healthy]))
        fold_of = {g: k % len(sizes) for k, g in enumerate(order)}
        healthy_fold = np.array([fold_of.get(g, -1) for g in groups])
        folds = []
        for k, size in enumerate(sizes):
            test = np.flatnonzero(((levels == size) & ~healthy)
                                  | (healthy & (healthy_fold == k)))
            folds.append((np.setdiff1d(np.arange(len(y)), test), test))
        rule += "; healthy runs dealt over the folds by group"
    elif split == "sensor":
        sensor = meta["sensor"].to_numpy() if "sensor" in meta else np.array([])
        loaded, unloaded = sensor == "loaded", sensor == "unloaded"
        if not (loaded.any() and unloaded.any()):
            return [], rule
        rows = np.flatnonzero(loaded)
        folds = []
        for tr, te in _stratified_group_folds(y[rows], groups[rows], n_splits, random_state):
            test_groups = set(groups[rows[te]])
            folds.append((rows[tr], np.flatnonzero(unloaded & np.isin(groups,
                                                                       list(test_groups)))))
    elif split == "random":
        k = int(min(n_splits, pd.Series(y).value_counts().min()))
        if k < 2:
            return [], rule
        cv = StratifiedKFold(n_splits=k, shuffle=True, random_state=random_state)
        return list(cv.split(np.zeros(len(y)), y)), rule
    else:
        raise ValueError(f"split must be one of {sorted(set(SPLITS) - {'sim2real'})}, "
                         f"got {split!r}")
    # A split of one value only (one speed, ...) is no split.
    folds = [(tr, te) for tr, te in folds if len(tr) and len(te)] if len(folds) > 1 else []
    return folds, rule


def _disjoint(groups: np.ndarray, train: np.ndarray, test: np.ndarray) -> bool:
    return not set(groups[train]) & set(groups[test])


def _scores(y_true, y_pred) -> dict:
    present = [c for c in LABELS if c in set(y_true)]
    recall = recall_score(y_true, y_pred, labels=list(LABELS), average=None,
                          zero_division=np.nan)
    row = {
        "n_test": len(y_true),
        "accuracy": accuracy_score(y_true, y_pred),
        "macro_f1": f1_score(y_true, y_pred, labels=present, average="macro",
                             zero_division=0.0),
    }
    row.update({f"recall_{c}": (r if c in present else np.nan)
                for c, r in zip(LABELS, recall, strict=True)})
    row["balanced_accuracy"] = float(np.mean([row[f"recall_{c}"] for c in present]))
    three = np.isin(y_true, THREE_CLASSES)
    row["accuracy_3class"] = (accuracy_score(np.asarray(y_true)[three],
                                             np.asarray(y_pred)[three])
                              if three.any() else np.nan)
    present3 = [c for c in THREE_CLASSES if c in present]
    row["balanced_accuracy_3class"] = (float(np.mean([row[f"recall_{c}"] for c in present3]))
                                       if present3 else np.nan)
    return row


#: Fewer independent groups (runs or recordings) than this in a class make its recall a
#: matter of a handful of cases: the report warns.
MIN_GROUPS_PER_CLASS = 5


def _few_groups(meta: pd.DataFrame) -> dict:
    """``{label: groups}`` of the classes with fewer than :data:`MIN_GROUPS_PER_CLASS`
    groups, with a warning naming them."""
    counts = meta.groupby("label")["group"].nunique()
    few = {str(k): int(v) for k, v in counts.items() if v < MIN_GROUPS_PER_CLASS}
    if few:
        warnings.warn(f"classes with fewer than {MIN_GROUPS_PER_CLASS} groups (runs or "
                      f"recordings): {few}; their recall rests on a handful of cases",
                      stacklevel=3)
    return few


def _fold_spread(pred: pd.DataFrame) -> dict:
    """Lowest and highest accuracy over the folds of one (split, model)."""
    per_fold = (pred["y_true"] == pred["y_pred"]).groupby(pred["fold"]).mean()
    return {"accuracy_fold_min": float(per_fold.min()),
            "accuracy_fold_max": float(per_fold.max())}


def _single(meta: pd.DataFrame, column: str, name: str):
    values = meta[column].dropna().unique() if column in meta else []
    if len(values) != 1:
        raise ValueError(f"{name}.{column} must hold one value for the whole dataset, "
                         f"got {list(values)}")
    return values[0]


def _row_batches(rpm: np.ndarray, size: int = 8):
    """Row indices in batches of one speed each, at most ``size`` rows: a row's features
    and diagnoser evidence are then computed among rows of its own speed only, i.e. as
    for the row alone (the candidate bands start above the fastest row's fault lines),
    whichever fold later holds it."""
    for value in np.unique(rpm):
        rows = np.flatnonzero(rpm == value)
        for i in range(0, rows.size, size):
            yield rows[i:i + size]


def _union_rows(union):
    """Per-row features of the pipelines' stateless feature step."""
    def compute(x, rpm):
        with sklearn.config_context(enable_metadata_routing=True):
            return np.asarray(union.transform(x, rpm=rpm), dtype=float)
    return compute


def _evidence_rows(diagnoser: EnvelopeDiagnoser):
    """Per-row evidence of each fault family, dB, columns in ``FAULT_FAMILIES`` order."""
    def compute(x, rpm):
        ev = diagnoser._evidence(x, rpm)[0].evidence_db
        return np.column_stack([ev[f] for f in FAULT_FAMILIES])
    return compute


def _pipeline_of(model: str, features: str, recommended=RECOMMENDED) -> tuple[str, str]:
    """(classifier, feature set) of a learned model: ``"recommended"`` is
    ``recommended`` whatever ``features`` is."""
    return tuple(recommended) if model == "recommended" else (model, features)


def _fit_predict(model, train, test, test_set, meta, rows_of, diagnoser, features,
                 random_state, recommended=RECOMMENDED):
    """Fit ``model`` on the simulated ``train`` rows and predict the ``test`` rows of
    ``test_set`` from the per-row work (features, diagnoser evidence) done once."""
    y_tr = meta["label"].to_numpy()[train]
    if model == "envelope":
        evidence = rows_of["evidence", "sim"]
        est = clone(diagnoser)
        healthy = train[y_tr == "healthy"]
        if healthy.size:  # calibrated on the fold's healthy training rows, as fit does
            est._fit_evidence({f: evidence[healthy, i] for i, f in enumerate(FAULT_FAMILIES)})
        test_ev = rows_of["evidence", test_set][test]
        margins = est._decision({f: test_ev[:, i] for i, f in enumerate(FAULT_FAMILIES)})
        return est.classes_[margins.argmax(axis=1)]
    name, feature_set = _pipeline_of(model, features, recommended)
    est = clone(make_pipeline(name, features=feature_set, random_state=random_state)[1:])
    classifier = est.steps[-1][1]
    if hasattr(classifier, "n_neighbors"):  # kNN: no more neighbours than training rows
        classifier.set_params(n_neighbors=min(classifier.n_neighbors, len(train)))
    rows = f"features_{feature_set}"
    return est.fit(rows_of[rows, "sim"][train], y_tr).predict(rows_of[rows, test_set][test])


def _save_npz(path: Path, values: np.ndarray, finished: np.ndarray) -> None:
    with path.open("wb") as fh:  # a file object: np.savez would append ".npz" to a name
        np.savez(fh, values=values, finished=finished)


class _Checkpoint:
    """A benchmark's finished work in a folder, so that an interrupted run resumes.

    Holds the per-row work of each dataset (``<name>_<dataset>.npz``: values and a mask
    of finished rows, rewritten atomically after every batch) and the out-of-fold
    predictions of every finished (split, model) pair
    (``pairs/<split>__<model>.parquet``).
    ``key.txt`` fingerprints the data (a BLAKE2 hash of the signals, labels, groups and
    speeds) and the settings; a folder holding another key is emptied of these files
    first. ``folder=None`` keeps nothing.
    """

    def __init__(self, folder, datasets: dict, settings: dict):
        self.folder = None if folder is None else Path(folder)
        if self.folder is None:
            return
        digest = hashlib.blake2b(repr(sorted(settings.items())).encode(), digest_size=16)
        for name, (x, m) in sorted(datasets.items()):
            digest.update(name.encode())
            digest.update(np.ascontiguousarray(x).tobytes())
            digest.update(m[["label", "group", "rpm"]].to_csv(index=False).encode())
        self.key = digest.hexdigest()
        stamp = self.folder / "key.txt"
        if stamp.exists() and stamp.read_text().strip() != self.key:
            for old in [*self.folder.glob("*.npz"), *self.folder.glob("pairs/*.parquet")]:
                old.unlink()
            stamp.unlink()
        self.stamped = stamp.exists()

    def _stamp(self) -> None:
        """Create the folder and its key with the first work saved (a run that saves
        nothing, e.g. one whose splits cannot be formed, writes nothing)."""
        if not self.stamped:
            self.folder.mkdir(parents=True, exist_ok=True)
            atomic_write(self.folder / "key.txt", lambda tmp: tmp.write_text(self.key + "\n"))
            self.stamped = True

    def per_row(self, name: str, key: str, x, rpm, compute, advance) -> np.ndarray:
        """``compute(x[rows], rpm[rows])`` for every row batch not finished before;
        ``advance(n)`` after each batch. Returns (n_rows, n_values)."""
        path = None if self.folder is None else self.folder / f"{name}_{key}.npz"
        values, finished = None, np.zeros(len(x), bool)
        if path is not None and path.exists():
            with np.load(path) as saved:
                values, finished = saved["values"], saved["finished"]
            advance(int(finished.sum()))
        for rows in _row_batches(rpm):
            if finished[rows].all():
                continue
            out = compute(x[rows], rpm[rows])
            if values is None:
                values = np.full((len(x), out.shape[1]), np.nan)
            values[rows], finished[rows] = out, True
            if path is not None:
                self._stamp()
                atomic_write(path, lambda tmp, v=values, f=finished: _save_npz(tmp, v, f))
            advance(len(rows))
        return values

    def predictions(self, split: str, model: str) -> pd.DataFrame | None:
        """The saved predictions of a finished (split, model) pair, or None."""
        path = None if self.folder is None else self.folder / "pairs" / f"{split}__{model}.parquet"
        if path is None or not path.exists():
            return None
        return pd.read_parquet(path)

    def save_predictions(self, split: str, model: str, pred: pd.DataFrame) -> None:
        if self.folder is not None:
            self._stamp()
            atomic_write(self.folder / "pairs" / f"{split}__{model}.parquet",
                         lambda tmp: pred.to_parquet(tmp, index=False))


def run_benchmark(
    X,
    meta: pd.DataFrame,
    *,
    real=None,
    splits=None,
    models=None,
    features: str = "dimensionless",
    n_splits: int = 5,
    band=None,
    harmonics: int = 3,
    random_state=0,
    seeds: int = 5,
    progress: bool = False,
    checkpoint=None,
    drawn=None,
    recommended=None,
) -> BenchmarkResult:
    """Cross-validate the envelope diagnoser and the classifier pipelines.

    Parameters
    ----------
    X : array_like, shape (n_rows, n_samples)
        Signals, e.g. from :func:`ballpass.datasets.load`, m/s^2.
    meta : pandas.DataFrame
        Their metadata (``label``, ``group``, ``rpm``, ``bearing``, ``fs``, and the
        columns the splits use; see :func:`split_indices`).
    real : (array_like, pandas.DataFrame), optional
        Real recordings in the same form (e.g. :func:`ballpass.datasets.load_cwru`,
        same bearing and fs): adds the ``sim2real`` split, trained on all of ``X``.
    splits : sequence of str, optional
        Names from :data:`SPLITS`; default all that the data can form.
    models : sequence of str, optional
        Names from :data:`MODELS`; default all. ``"recommended"`` is the pipeline
        :data:`~ballpass.diagnose._names.RECOMMENDED` (its own feature set, whatever
        ``features`` is).
    features : str, optional
        Feature set of the pipelines (default ``"dimensionless"``; see
        :func:`ballpass.diagnose.make_features`).
    n_splits : int, optional
        Folds of the k-fold splits (default 5).
    band : (float, float) or None, optional
        Demodulation band, Hz, for the fault bands and the diagnoser; ``None`` (default)
        picks it per row with the kurtogram.
    harmonics : int, optional
        Harmonics of each fault line (default 3).
    random_state : int or None, optional
        Seed of the fold shuffling and the randomised classifiers (default 0).
    seeds : int, optional
        Training seeds of the ``sim2real`` split (default 5): each learned model is
        trained with ``random_state``, ``random_state + 1``, ... and every seed's scores
        go to :attr:`BenchmarkResult.spread`; the table and the predictions are the
        first seed's. A new simulated dataset (another root seed of the grid) moves the
        scores more: benchmark several for that.
    progress : bool, optional
        Say on stderr what work lies ahead, and show a progress bar over the rows'
        features and diagnoser evidence, then over the folds (default False).
    checkpoint : str or os.PathLike, optional
        Folder that keeps the finished work (each row's features and evidence, each
        finished split and model), so that an interrupted call resumes where it stopped
        when called again with the same data and settings; work of other data or
        settings found there is discarded. Default None: nothing kept.
    drawn : collection of str, optional
        The dataset's drawn (continuous) columns, e.g. ``radial_load_n``: the
        ``speed``, ``load`` and ``fault_size`` splits leave out quantile bins of them
        instead of each value (see :func:`split_indices`; default None: a column with
        many distinct values counts as drawn). ``info["fold_rules"]`` says which rule
        made each split's folds.
    recommended : (str, str), optional
        (classifier, feature set) reported as model ``"recommended"``: default
        :data:`~ballpass.diagnose._names.RECOMMENDED`; ``ballpass benchmark`` passes
        :data:`~ballpass.diagnose._names.RECOMMENDED_TWIN` for a twin's dataset.
        ``info["recommended"]`` holds the one used.

    Returns
    -------
    BenchmarkResult
        Write it out with :func:`ballpass.diagnose.write_report`. Interrupted
        (``KeyboardInterrupt``, Ctrl-C), the finished (split, model) pairs only, with
        ``info["interrupted"]`` True.

    Notes
    -----
    Each row's features and diagnoser evidence depend on that row alone (and its
    speed), so they are computed once per row, in batches of rows of one speed, and
    every fold reuses them; the diagnoser's thresholds are still calibrated per fold on
    its healthy training rows.

    Raises
    ------
    ValueError
        Unknown split or model names, a dataset mixing bearings or sampling rates, or
        real recordings of another bearing or rate.

    Examples
    --------
    >>> import numpy as np, pandas as pd
    >>> import ballpass as bp
    >>> from ballpass.diagnose import run_benchmark
    >>> faults = ["outer", "inner"] * 3 + [None] * 3
    >>> scenes = [bp.Scene("6205", rpm=1797, fs=12_000, duration_s=1.0, resonance_hz=3_000,
    ...                    fault=bp.Fault(f) if f else None, noise_rms=0.5, seed=i)
    ...           for i, f in enumerate(faults)]
    >>> X = np.stack([bp.simulate(s, model="impulse").accel for s in scenes])
    >>> meta = pd.DataFrame({"label": [f or "healthy" for f in faults], "group": range(9),
    ...                      "rpm": 1797.0, "bearing": "6205", "fs": 12_000.0})
    >>> result = run_benchmark(X, meta, splits=["run"], models=["envelope", "logistic"],
    ...                        n_splits=3)
    >>> result.table[["split", "model", "n_test", "accuracy"]]
      split     model  n_test  accuracy
    0   run  envelope       9       1.0
    1   run  logistic       9       1.0
    >>> result.confusion[("run", "envelope")].diagonal().tolist()   # healthy, outer, inner, ball
    [3, 3, 3, 0]
    >>> sorted(result.predictions.columns)
    ['fold', 'group', 'model', 'row', 'split', 'y_pred', 'y_true']
    """
    if isinstance(n_splits, bool) or not isinstance(n_splits, (int, np.integer)) \
            or n_splits < 2:
        raise ValueError(f"n_splits (--folds) must be an int >= 2: k-fold cross-validation "
                         f"needs two folds at least, got {n_splits!r}")
    if isinstance(seeds, bool) or not isinstance(seeds, (int, np.integer)) or seeds < 1:
        raise ValueError(f"seeds (--train-seeds) must be an int >= 1, got {seeds!r}")
    X = np.asarray(X)
    _check_meta(meta, len(X), "meta")
    meta = meta.reset_index(drop=True)
    bearing = str(_single(meta, "bearing", "meta"))
    fs = float(_single(meta, "fs", "meta"))
    splits = [s for s in SPLITS if s != "sim2real" or real is not None] if splits is None \
        else list(splits)
    models = list(MODELS) if models is None else list(models)
    for name, allowed, given in (("splits", SPLITS, splits), ("models", MODELS, models)):
        unknown = set(given) - set(allowed)
        if unknown or not given:
            raise ValueError(f"{name} must be a non-empty subset of {list(allowed)}, "
                             f"got {given!r}")
    if "sim2real" in splits and real is None:
        raise ValueError("the sim2real split needs real recordings (real=(X_real, meta_real))")
    recommended = RECOMMENDED if recommended is None else tuple(recommended)
    if len(recommended) != 2 or recommended[0] not in CLASSIFIERS \
            or recommended[1] not in FEATURE_SETS:
        raise ValueError(f"recommended must be (classifier, feature set) with a classifier "
                         f"of {list(CLASSIFIERS)} and a feature set of {list(FEATURE_SETS)}, "
                         f"got {recommended!r}")

    datasets = {"sim": (X, meta)}
    if real is not None:
        Xr, meta_r = np.asarray(real[0]), real[1].reset_index(drop=True)
        _check_meta(meta_r, len(Xr), "real meta")
        for column, value in (("bearing", bearing), ("fs", fs)):
            other = _single(meta_r, column, "real meta")
            if (float(other) != value) if column == "fs" else (str(other) != value):
                raise ValueError(f"real recordings have {column}={other!r}, the simulated "
                                 f"dataset {value!r}")
        datasets["real"] = (Xr, meta_r)

    plan = []  # (split, folds, test set)
    skipped, fold_rules = {}, {"sim2real": SPLITS["sim2real"]}
    for split in splits:
        if split == "sim2real":
            plan.append((split, [(np.arange(len(X)), np.arange(len(datasets["real"][0])))],
                         "real"))
            continue
        folds, fold_rules[split] = _split(meta, split, n_splits, random_state, drawn)
        if not folds:
            skipped[split] = "the dataset has a single value of this factor"
            continue
        if split not in _OPTIMISTIC and not all(_disjoint(meta["group"].to_numpy(), tr, te)
                                                for tr, te in folds):
            raise RuntimeError(f"split {split!r} put one group on both sides")
        plan.append((split, folds, "sim"))

    settings = {"features": features, "recommended": list(recommended), "band": band,
                "harmonics": harmonics,
                "n_splits": n_splits, "random_state": random_state, "seeds": seeds}
    state = _Checkpoint(checkpoint, datasets, settings)
    learned = [m for m in models if m != "envelope"]
    diagnoser = EnvelopeDiagnoser(bearing, fs=fs, band=band, harmonics=harmonics)
    per_row = []  # (name, dataset, function of (x, rpm) -> per-row values)
    for feature_set in dict.fromkeys(_pipeline_of(m, features, recommended)[1]
                                     for m in learned):
        union = make_features(feature_set, bearing=bearing, fs=fs, band=band,
                              harmonics=harmonics)
        per_row += [(f"features_{feature_set}", k, _union_rows(union)) for k in datasets]
    if "envelope" in models:
        per_row += [("evidence", k, _evidence_rows(diagnoser)) for k in datasets]
    if not plan:  # no split can be formed: no work, nothing kept
        per_row = []
    done = {(split, model): state.predictions(split, model)
            for split, _folds, _t in plan for model in models}
    n_rows = sum(len(datasets[k][0]) for _n, k, _f in per_row)
    n_fits = sum(len(folds) for _s, folds, _t in plan) * len(models)
    n_done = sum(len(folds) for split, folds, _t in plan for model in models
                 if done[split, model] is not None)
    bar = tqdm(total=n_rows + n_fits, desc="benchmark", unit="step", file=sys.stderr,
               disable=not progress, leave=False)
    if progress:
        tqdm.write(f"benchmark: per-row features and diagnoser evidence for {n_rows} rows "
                   f"({', '.join(sorted({n for n, _k, _f in per_row}))}), then {n_fits} fits "
                   f"({len(models)} models over {sum(len(f) for _s, f, _t in plan)} folds of "
                   f"{len(plan)} splits)"
                   + (f"; {n_done} fits resumed from {checkpoint}" if n_done else ""),
                   file=sys.stderr)
    interrupted, rows_of, predictions_of, spread = False, {}, {}, []
    fitted = {}  # (pipeline, split, fold, seed) -> predictions

    def fit_predict(model, split, k, train, test, test_set, seed):
        """``_fit_predict`` once per pipeline: ``recommended`` is one of the others
        when ``features`` is its feature set, and is then not fitted again."""
        key = (_pipeline_of(model, features, recommended) if model != "envelope" else model,
               split, k, seed)
        if key not in fitted:
            # one thread: a fit on a few hundred rows gains nothing from OpenMP's
            # threads, which cost gradient boosting 60x its time on a busy machine
            with threadpool_limits(1):
                fitted[key] = _fit_predict(model, train, test, test_set, meta, rows_of,
                                           diagnoser, features, seed, recommended)
        return fitted[key]

    try:
        for name, key, compute in per_row:
            x, m = datasets[key]
            bar.set_description(f"{name} ({key})")
            rows_of[name, key] = state.per_row(name, key, x, m["rpm"].to_numpy(float),
                                               compute, bar.update)
        for split, folds, test_set in plan:
            test_meta = datasets[test_set][1]
            for model in models:
                bar.set_description(f"{split} / {model}")
                pred = done[split, model]
                if pred is not None:
                    bar.update(len(folds))
                    predictions_of[split, model] = pred
                    continue
                parts = []
                for k, (train, test) in enumerate(folds):
                    y_pred = fit_predict(model, split, k, train, test, test_set,
                                         random_state)
                    parts.append(pd.DataFrame({
                        "split": split, "model": model, "fold": k, "row": test,
                        "group": test_meta["group"].to_numpy()[test],
                        "y_true": test_meta["label"].to_numpy()[test], "y_pred": y_pred,
                        **({"file": test_meta["file"].to_numpy()[test]}
                           if "file" in test_meta else {})}))
                    bar.update()
                predictions_of[split, model] = pd.concat(parts, ignore_index=True)
                state.save_predictions(split, model, predictions_of[split, model])
        for split, folds, test_set in plan:  # sim2real: the spread over training seeds
            if split != "sim2real":
                continue
            (train, test), = folds
            for model in models:
                pred = predictions_of[split, model]
                spread.append({"split": split, "model": model, "seed": random_state,
                               **_scores(pred["y_true"], pred["y_pred"])})
                for k in range(1, seeds) if model != "envelope" else ():
                    seed = None if random_state is None else random_state + k
                    y = fit_predict(model, split, 0, train, test, test_set, seed)
                    spread.append({"split": split, "model": model, "seed": seed,
                                   **_scores(pred["y_true"], y)})
    except KeyboardInterrupt:  # keep what is finished: a partial report that says so
        interrupted = True
        for pair, pred in done.items():
            if pred is not None:
                predictions_of.setdefault(pair, pred)
    finally:
        bar.close()
    rows, confusion, predictions = [], {}, []
    for split, folds, _t in plan:
        for model in models:
            pred = predictions_of.get((split, model))
            if pred is None:
                continue
            predictions.append(pred)
            confusion[split, model] = confusion_matrix(pred["y_true"], pred["y_pred"],
                                                       labels=list(LABELS))
            rows.append({"split": split, "model": model, "optimistic": split in _OPTIMISTIC,
                         "folds": len(folds), **_scores(pred["y_true"], pred["y_pred"]),
                         **_fold_spread(pred)})
    few = _few_groups(meta)
    info = {
        "rows": len(X), "groups": int(meta["group"].nunique()), "bearing": bearing, "fs": fs,
        "few_groups": few,
        "fold_rules": {split: fold_rules[split] for split, _f, _t in plan},
        "samples_per_row": int(X.shape[1]), "features": features,
        "recommended": recommended, "n_splits": n_splits,
        "seeds": seeds if "sim2real" in splits else 1,
        "labels": meta["label"].value_counts().to_dict(),
    }
    if interrupted:
        info["interrupted"] = True
        info["pairs_done"] = len(rows)
        info["pairs_planned"] = len(plan) * len(models)
    if real is not None:
        info["real_rows"] = len(datasets["real"][0])
        info["real_groups"] = int(datasets["real"][1]["group"].nunique())
    return BenchmarkResult(
        table=pd.DataFrame(rows),
        confusion=confusion,
        predictions=pd.concat(predictions, ignore_index=True) if predictions else pd.DataFrame(),
        skipped=skipped,
        info=info,
        spread=pd.DataFrame(spread),
    )
