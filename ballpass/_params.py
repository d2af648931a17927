"""scikit-learn conventions the estimators share: constructor arguments kept as given,
and the tags of an estimator that learns nothing."""

from __future__ import annotations


def keep_params(estimator, arguments: dict) -> None:
    """Store each constructor argument as the attribute of its name, unchanged.

    scikit-learn's convention: ``__init__`` validates nothing and keeps every argument
    under its own name, where ``get_params`` reads it back. Call it first thing in
    ``__init__`` as ``keep_params(self, locals())``.

    Parameters
    ----------
    estimator : object
        The estimator being constructed.
    arguments : dict
        ``locals()`` of its ``__init__``: the arguments by name (``self`` is skipped).

    Examples
    --------
    >>> from ballpass._params import keep_params
    >>> class Scaler:
    ...     def __init__(self, factor=2.0, *, offset=0.0):
    ...         keep_params(self, locals())
    >>> vars(Scaler(offset=1.0))
    {'factor': 2.0, 'offset': 1.0}
    """
    for name, value in arguments.items():
        if name != "self":
            setattr(estimator, name, value)


class StatelessMixin:
    """Tags of an estimator that learns nothing from ``fit``: it needs no fit and no
    target (``requires_fit`` and ``target_tags.required`` False).

    Put it first among the bases, left of scikit-learn's mixins and ``BaseEstimator``,
    whose tags it amends.

    Examples
    --------
    >>> from sklearn.base import BaseEstimator, TransformerMixin
    >>> from sklearn.utils import get_tags
    >>> from ballpass._params import StatelessMixin
    >>> class Identity(StatelessMixin, TransformerMixin, BaseEstimator):
    ...     def transform(self, X):
    ...         return X
    >>> tags = get_tags(Identity())
    >>> tags.requires_fit, tags.target_tags.required
    (False, False)
    """

    def __sklearn_tags__(self):
        tags = super().__sklearn_tags__()
        tags.requires_fit = False
        tags.target_tags.required = False
        return tags
