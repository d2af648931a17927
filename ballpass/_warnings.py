"""Warnings that point at the user's line, however deep inside ballpass they are raised."""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

#: the package folder: frames whose file lies below it are ballpass's own
PACKAGE_DIR = str(Path(__file__).resolve().parent)


def warn_user(message: str, category: type[Warning] = UserWarning) -> None:
    """``warnings.warn`` with the stack level of the first caller outside ballpass.

    A fixed ``stacklevel`` is right for one call path only: ``bp.simulate(scene)`` goes
    through the callable module and ``ballpass.simulate.simulate(scene)`` does not, so a
    warning raised inside the solver would point at a ballpass line for one of them.

    Parameters
    ----------
    message : str
        The warning's text.
    category : type of Warning, optional
        Default ``UserWarning``.

    Examples
    --------
    >>> import warnings
    >>> from ballpass._warnings import warn_user
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn_user("look here")
    >>> caught[0].filename.startswith(PACKAGE_DIR)
    False
    """
    frame, level = sys._getframe(1), 2   # stacklevel 2: warn_user's caller
    while frame is not None and str(Path(frame.f_code.co_filename).resolve()).startswith(
            PACKAGE_DIR):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)
