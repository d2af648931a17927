"""Diagnosis: a physics-based envelope diagnoser, classifier pipelines, honest benchmarks.

Physics-based (no training)
---------------------------
EnvelopeDiagnoser     scikit-learn classifier from the squared-envelope-spectrum evidence
envelope_evidence     evidence of each fault family (BPFO, BPFI +- fr, 2xBSF +- FTF), dB
Explanation           which lines carried a decision, and how far above the background

Importing this package is cheap; scikit-learn loads on first use of a name.
"""

from __future__ import annotations

import importlib

#: public name -> defining submodule
_NAMES = {
    "LABELS": "rules",
    "EnvelopeDiagnoser": "rules",
    "EnvelopeEvidence": "rules",
    "Explanation": "rules",
    "envelope_evidence": "rules",
}

__all__ = sorted(_NAMES)


def __getattr__(name: str):
    if name in _NAMES:
        return getattr(importlib.import_module(f".{_NAMES[name]}", __name__), name)
    raise AttributeError(f"module 'ballpass.diagnose' has no attribute {name!r}")


def __dir__():
    return __all__
