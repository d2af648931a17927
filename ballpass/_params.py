"""Storing a scikit-learn estimator's constructor arguments."""

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
