"""Diagnosis: a physics-based envelope diagnoser, classifier pipelines, honest benchmarks.

Physics-based (no training)
---------------------------
EnvelopeDiagnoser     scikit-learn classifier from the squared-envelope-spectrum evidence
envelope_evidence     evidence of each fault family (BPFO, BPFI +- fr, 2xBSF +- FTF), dB
Explanation           which lines carried a decision, and how far above the background
noise_probability     how often noise, searched as widely as a record, reads its evidence
noise_threshold       the evidence noise reaches with a given probability per record
plot_explanation      the squared envelope spectrum behind a decision, its lines marked
baseline_thresholds   each family's threshold from healthy recordings of the machine
EvidenceTransformer   the diagnoser's evidence as features for learned models (no absolute units)

Learned
-------
make_pipeline         signal features + scaling + a classifier, ready for scikit-learn
make_features         the (stateless) feature step alone
make_classifier       the bare classifier of a pipeline
CLASSIFIERS           names of the ready-made classifiers
FEATURE_SETS          names of the feature sets

Benchmarks
----------
run_benchmark         cross-validate models over leakage-free splits -> BenchmarkResult
split_indices         the train/test row indices of one split (groups never straddle)
write_report          Markdown/CSV table and confusion-matrix figures of a BenchmarkResult
SPLITS, MODELS        the splits (what each measures) and the models

Importing this package is cheap; scikit-learn loads on first use of a name.
"""

from __future__ import annotations

import importlib

#: public name -> defining submodule
_NAMES = {
    "LABELS": "_names",
    "EnvelopeDiagnoser": "rules",
    "EnvelopeEvidence": "evidence",
    "Explanation": "rules",
    "envelope_evidence": "evidence",
    "noise_probability": "noise_law",
    "noise_threshold": "noise_law",
    "CLASSIFIERS": "_names",
    "FEATURE_SETS": "_names",
    "make_classifier": "pipelines",
    "make_features": "pipelines",
    "make_pipeline": "pipelines",
    "SPLITS": "_names",
    "MODELS": "_names",
    "BenchmarkResult": "benchmark",
    "run_benchmark": "benchmark",
    "split_indices": "benchmark",
    "write_report": "report",
    "plot_confusion": "report",
    "plot_explanation": "figure",
    "baseline_thresholds": "baseline",
    "EvidenceTransformer": "invariant",
}

__all__ = sorted(_NAMES)


def __getattr__(name: str):
    if name in _NAMES:
        return getattr(importlib.import_module(f".{_NAMES[name]}", __name__), name)
    raise AttributeError(f"module 'ballpass.diagnose' has no attribute {name!r}")


def __dir__():
    return __all__
