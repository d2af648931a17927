"""
Diagnosing real recordings
==========================

Two-second crops of Case Western Reserve University drive-end recordings (6205 bearing,
1797 rpm, 12 kHz; inner-race and outer-race faults of 0.007 in), shipped with ballpass,
through the physics-based envelope diagnoser, which needs no training. The squared
envelope spectra show why it decides as it does.

Your own recordings enter the same way from a manifest: a table with one row per
recording (``path``, ``fs``, ``rpm``, ``bearing``, and ``label`` where you score the
results), read by :func:`ballpass.datasets.load_manifest`, or by ``ballpass diagnose
recordings.csv`` on the command line.
"""

import tempfile
from importlib import resources
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import ballpass as bp

data = resources.files("ballpass") / "examples" / "data"
crops = {"inner 0.007 in": "cwru_12k_DE_IR007_0_DE_crop.npz",
         "outer 0.007 in @6": "cwru_12k_DE_OR007at6_0_DE_crop.npz"}
b = bp.Bearing.catalog("6205")
diag = bp.diagnose.EnvelopeDiagnoser(bearing=b, fs=12_000, rpm=1797)

fig, axes = plt.subplots(len(crops), 1, figsize=(8, 6), sharex=True)
signals = {}
for ax, (name, file) in zip(axes, crops.items(), strict=True):
    with np.load(data / file) as z:
        x = z["accel_g"].astype(float) * 9.80665    # g -> m/s^2
        fs = float(z["fs"])
    signals[name] = x
    label = diag.predict(x[None, :])[0]
    freqs, ses = bp.features.envelope_spectrum(x, fs)
    bp.plot.envelope_spectrum(freqs, ses, frequencies=b.frequencies(1797 / 60), fmax=600,
                              ax=ax)
    ax.set_title(f"{name}: diagnosed '{label}'")
fig.tight_layout()

# %%
# The same recordings as a user's files: one ``.npy`` each and a manifest that lists
# them. ``load_manifest`` cuts every recording into one-second segments (a recording's
# segments share its ``group``), which the diagnoser then calls one by one.
folder = Path(tempfile.mkdtemp())
rows = []
for x, label in zip(signals.values(), ["inner", "outer"], strict=True):
    np.save(folder / f"{label}.npy", x)
    rows.append({"path": f"{label}.npy", "fs": 12_000, "rpm": 1797, "bearing": "6205",
                 "label": label})
pd.DataFrame(rows).to_csv(folder / "recordings.csv", index=False)
X, meta = bp.datasets.load_manifest(folder / "recordings.csv", require_label=True)
meta["diagnosed"] = diag.predict(X)
print(meta[["group", "segment", "label", "diagnosed"]].to_string(index=False))
plt.show()
