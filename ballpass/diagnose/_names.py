"""Names and one-line descriptions of labels, models, feature sets and splits.

Plain data, no imports: the command line builds its help from these without loading
scikit-learn.
"""

#: Labels the diagnosers predict, in report order.
LABELS = ("healthy", "outer", "inner", "ball")

#: Trees of the random forest. 100 score as 300 did, side by side on two simulated
#: datasets (within the spread over folds; docs/benchmark_cost.md), at a third of the cost.
FOREST_TREES = 100

#: Classifier name -> description (see :func:`ballpass.diagnose.make_classifier`).
CLASSIFIERS = {
    "random_forest": f"random forest, {FOREST_TREES} trees, balanced class weights",
    "gradient_boosting": "histogram gradient boosting, balanced class weights",
    "svm": "support-vector machine, RBF kernel, C = 10, balanced class weights",
    "knn": "k nearest neighbours, k = 5",
    "logistic": "multinomial logistic regression, balanced class weights",
}

#: Feature set name -> description (see :func:`ballpass.diagnose.make_features`).
FEATURE_SETS = {
    "dimensionless": "shape indicators (crest, kurtosis, skewness, shape, impulse, clearance) "
                     "and fault-band SES levels (dB): nothing scales with the sensor gain",
    "all": "every indicator (also RMS, peak, peak-to-peak in m/s^2) and the fault bands",
    "bands": "fault-band SES levels only (dB)",
    "indicators": "statistical indicators only",
    "evidence": "the diagnoser's evidence: each family's line levels in dB over their "
                "background in the band its evidence picks, and the SES on an order axis in "
                "dB over its median; nothing in absolute units",
    "combined": "the `evidence` features and the `dimensionless` ones together",
}

#: The learned pipeline the docs recommend for simulation-to-real, (classifier, feature
#: set): of the five classifiers on the `dimensionless`, `evidence` and `combined`
#: features, trained on the shipped sim2real_cwru grid (and its 6203 twin at the fan
#: end), the one with the highest median four-class balanced accuracy on the shared
#: CWRU 0 hp records, the drive and fan ends judged as separate rigs, over three training
#: sets (docs/sim2real.md); never chosen on a test set.
RECOMMENDED = ("random_forest", "combined")

#: The learned pipeline recommended for a twin of the user's machine
#: (:func:`ballpass.datasets.twin`: simulated faults through the machine's learned
#: path over its own healthy recording), chosen by the same kind of rule on the shared
#: twin validation: of the five classifiers on the `dimensionless`, `evidence` and
#: `combined` features, the highest mean three-class balanced accuracy on the HIT-SM
#: rig's recordings, each of its three healthy recordings in turn the twin's input, three
#: twins each (docs/twin.md); never chosen on a test set.
RECOMMENDED_TWIN = ("random_forest", "dimensionless")

#: Model name -> description: the physics-based diagnoser and the learned pipelines.
MODELS = {
    "envelope": "EnvelopeDiagnoser (physics; thresholds calibrated on healthy training rows)",
    **CLASSIFIERS,
    "recommended": f"the pipeline recommended for simulation-to-real: {RECOMMENDED[0]} on "
                   f"the `{RECOMMENDED[1]}` features ({RECOMMENDED_TWIN[0]} on the "
                   f"`{RECOMMENDED_TWIN[1]}` features on a twin's dataset), whatever "
                   "--features says",
}

#: Folds of a split on a drawn (continuous) axis: quantile bins of its values, each
#: left out in turn. Four bins leave a quarter of the runs out per fold, as a 4-fold
#: split would, while each test bin still lies beyond the training range on one side.
QUANTILE_BINS = 4

#: Split name -> what it measures (``random`` is optimistic).
SPLITS = {
    "run": "stratified group k-fold over runs (segments of a run stay together)",
    "speed": "leave one shaft speed out (a drawn speed: one of "
             f"{QUANTILE_BINS} quantile bins)",
    "load": f"leave one load out (a drawn load: one of {QUANTILE_BINS} quantile bins)",
    "fault_size": f"leave one fault size out (a drawn size: one of {QUANTILE_BINS} quantile "
                  "bins; healthy runs dealt over the folds by group)",
    "sensor": "train on loaded-zone rows, test on unloaded-zone rows of other runs",
    "random": "OPTIMISTIC: k-fold over rows, segments of one run on both sides",
    "sim2real": "train on all simulated rows, test on the real recordings",
}
