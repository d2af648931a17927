"""
Leakage: why a benchmark splits by run
======================================

Runs recorded on different days differ in ways that have nothing to do with the
bearing: the sensor's mounting (its resonance), the background noise. Here each of 24
simulated runs (six per class: healthy, outer, inner, ball, with faint faults) draws its
own resonance and noise level, and each run is cut into eight segments. A classifier fed
amplitude features (RMS, peak, ...) can recognise a run by its noise level alone.

Split by segment, and the segments of one run land on both sides: the classifier
names a test segment by the run it recognises and looks far better than it is. Split
by run (``group``), as ``ballpass benchmark`` does, and the score falls to what the
features really tell. Dimensionless features (crest factor, kurtosis, fault-band levels
in dB), which no noise level or gain shifts, leak less.
"""

import matplotlib.pyplot as plt
import numpy as np
from sklearn.model_selection import GroupKFold, KFold, cross_val_score

import ballpass as bp

rng = np.random.default_rng(0)
fs, segment = 12_000.0, 3_000               # Hz; 0.25 s segments
runs, labels = [], []
for label in ["healthy", "outer", "inner", "ball"]:
    for _ in range(6):
        scene = bp.Scene(
            bearing="6205", rpm=1797, fs=fs, duration_s=2.0, seed=len(runs),
            fault=None if label == "healthy" else bp.Fault(label, width_mm=0.1, depth_mm=0.01),
            resonance_hz=float(rng.uniform(2_500, 4_500)),         # the run's mounting
            noise_rms=float(np.exp(rng.uniform(0.0, np.log(8.0)))),  # its background, m/s^2
        )
        runs.append(bp.simulate(scene).accel)
        labels.append(label)
X = np.stack(runs)
n = X.shape[1] // segment
segments = X[:, : n * segment].reshape(-1, segment)      # (24 runs x 8, 3000)
y = np.repeat(labels, n)
groups = np.repeat(np.arange(len(runs)), n)              # the run each segment came from

scores = {}
for features in ["all", "dimensionless"]:
    model = bp.diagnose.make_pipeline("random_forest", features=features, fs=fs)
    by_run = cross_val_score(model, segments, y, groups=groups, cv=GroupKFold(3))
    by_segment = cross_val_score(model, segments, y, cv=KFold(3, shuffle=True, random_state=0))
    scores[features] = (by_run.mean(), by_segment.mean())
    print(f"{features:>13} features: split by run {by_run.mean():.2f}, "
          f"split by segment {by_segment.mean():.2f} (chance 0.25)")

fig, ax = plt.subplots(figsize=(6, 3.2))
width = 0.38
for i, (name, colour) in enumerate([("split by run (honest)", "tab:blue"),
                                    ("split by segment (leaky)", "tab:red")]):
    ax.bar(np.arange(2) + (i - 0.5) * width, [scores[f][i] for f in scores], width,
           label=name, color=colour)
ax.axhline(0.25, color="0.5", ls=":", lw=1, label="chance")
ax.set_xticks(range(2), ["amplitude features", "dimensionless features"])
ax.set_ylim(0, 1)
ax.set_ylabel("accuracy")
ax.legend(fontsize="small", loc="upper right")
fig.tight_layout()
plt.show()
