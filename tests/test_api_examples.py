"""Every public function and class has a runnable Examples section and a page in the API
reference.

"Public" is what the public modules list in ``__all__`` (the names a user imports).
The examples themselves run as doctests (``--doctest-modules`` in the pytest
configuration), so this module only checks that none is missing: a new public name
without an example, or one left out of ``docs/api.rst``, fails here.
"""

from __future__ import annotations

import importlib
import inspect
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

PUBLIC_MODULES = (
    "ballpass", "ballpass.simulate", "ballpass.features", "ballpass.diagnose",
    "ballpass.datasets", "ballpass.plot", "ballpass.dynamics", "ballpass.gears",
    "ballpass.bearing", "ballpass.scene", "ballpass.signalio", "ballpass.phenomena",
    "ballpass.waviness",
)

#: scikit-learn's estimator protocol: documented once by scikit-learn and shown in each
#: estimator's class example, like scikit-learn's own estimators do
ESTIMATOR_METHODS = frozenset({"fit", "transform", "fit_transform", "predict",
                               "predict_proba", "decision_function", "score",
                               "get_feature_names_out"})


def _public_objects() -> dict[str, object]:
    """Qualified public name -> function or class, each object once."""
    found: dict[int, tuple[str, object]] = {}
    for module_name in PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.isfunction(obj) or inspect.isclass(obj):
                found.setdefault(id(obj), (f"{module_name}.{name}", obj))
    return dict(found.values())


def _public_methods(cls) -> dict[str, object]:
    return {name: member for name, member in vars(cls).items()
            if not name.startswith("_") and name not in ESTIMATOR_METHODS
            and inspect.isfunction(member)}


def _has_examples(obj) -> bool:
    return re.search(r"^Examples\n-{8}\n", inspect.getdoc(obj) or "", re.M) is not None


OBJECTS = _public_objects()


def test_the_public_api_is_found():
    # guards the walk itself: an empty or tiny set would make the checks below vacuous
    assert len(OBJECTS) > 80
    assert "ballpass.simulate.simulate" in OBJECTS and "ballpass.Scene" in OBJECTS


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_public_name_has_an_examples_section(name):
    obj = OBJECTS[name]
    assert _has_examples(obj), f"{name} has no 'Examples' section in its docstring"
    if inspect.isclass(obj):
        missing = [m for m, member in _public_methods(obj).items() if not _has_examples(member)]
        assert not missing, f"methods of {name} without an 'Examples' section: {missing}"


def _documented_names() -> set[str]:
    """Fully qualified names the API reference lists (autosummary entries under their
    ``currentmodule``, and ``auto*`` directives)."""
    names, current = set(), None
    for line in (ROOT / "docs" / "api.rst").read_text().splitlines():
        if m := re.match(r"\.\. currentmodule:: (\S+)", line):
            current = m.group(1)
        elif m := re.match(r"\.\. auto\w+:: (\S+)", line):
            names.add(m.group(1))
        elif (m := re.match(r"   ([A-Za-z_][\w.]*)$", line)) and current:
            names.add(f"{current}.{m.group(1)}")
    return names


def _resolve(dotted: str):
    module_name, _, attr = dotted.rpartition(".")
    while module_name:
        try:
            module = importlib.import_module(module_name)
        except ImportError:
            module_name, _, head = module_name.rpartition(".")
            attr = f"{head}.{attr}"
            continue
        obj = module
        for part in attr.split("."):
            obj = getattr(obj, part, None)
        return obj
    return None


def test_every_public_function_and_class_is_in_the_api_reference():
    listed = {id(obj) for obj in map(_resolve, _documented_names()) if obj is not None}
    missing = sorted(name for name, obj in OBJECTS.items() if id(obj) not in listed)
    assert not missing, f"add to docs/api.rst: {missing}"
