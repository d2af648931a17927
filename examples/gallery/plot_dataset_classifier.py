"""
A dataset and a classifier with an honest split
===============================================

Generate a small labelled dataset over a grid, cut each run into segments, and train a
classifier on statistical and fault-band features. Segments of one run share its slip
and noise: a split by segment leaks the run into both sides. Split by run (``group``),
as the benchmark does, and compare.
"""

import tempfile

import matplotlib.pyplot as plt
from sklearn.model_selection import GroupKFold, KFold, cross_val_score

import ballpass as bp

grid = {
    "dataset": {"duration_s": 0.5, "fs": 12_000, "repeats": 3, "seed": 0, "model": "sr5"},
    "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner", "ball"],
             "fault_width_mm": [0.5], "resonance_hz": [3000], "rpm": [1730, 1797],
             "radial_load_n": [500], "noise_rms": [0.3]},
}
with tempfile.TemporaryDirectory() as folder:
    bp.datasets.generate(grid, folder, progress=False)
    X, meta = bp.datasets.load(folder)

model = bp.diagnose.make_pipeline("random_forest", features="dimensionless", fs=12_000)
y, groups = meta["label"].to_numpy(), meta["group"].to_numpy()
honest = cross_val_score(model, X, y, groups=groups, cv=GroupKFold(3))
leaky = cross_val_score(model, X, y, cv=KFold(3, shuffle=True, random_state=0))
print(f"split by run: {honest.mean():.2f}   split by segment: {leaky.mean():.2f}")

fig, ax = plt.subplots(figsize=(5, 3))
ax.bar(["by run (honest)", "by segment (leaky)"], [honest.mean(), leaky.mean()])
ax.set_ylim(0, 1.05)
ax.set_ylabel("accuracy")
fig.tight_layout()
plt.show()
