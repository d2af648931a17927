"""
Diagnosing real recordings
==========================

Short crops of Case Western Reserve University drive-end recordings (6205 bearing,
1797 rpm, 12 kHz) and of the MFPT set (another rig: an 8-roller bearing at 25 Hz,
48.8 kHz), shipped with the tests (see ``tests/data/README.md``), through the
physics-based envelope diagnoser, which needs no training. The squared envelope
spectra show why it decides as it does.
"""

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import ballpass as bp

data = Path(bp.__file__).resolve().parents[1] / "tests" / "data"
crops = {"inner 0.007 in": "cwru_12k_DE_IR007_0_DE_crop.npz",
         "outer 0.007 in @6": "cwru_12k_DE_OR007at6_0_DE_crop.npz"}
b = bp.Bearing.catalog("6205")
diag = bp.diagnose.EnvelopeDiagnoser(bearing=b, fs=12_000, rpm=1797)

fig, axes = plt.subplots(len(crops), 1, figsize=(8, 6), sharex=True)
for ax, (name, file) in zip(axes, crops.items(), strict=True):
    with np.load(data / file) as z:
        x = z["accel_g"].astype(float) * 9.80665    # g -> m/s^2
        fs = float(z["fs"])
    label = diag.predict(x[None, :12_000])[0]
    freqs, ses = bp.features.envelope_spectrum(x, fs)
    bp.plot.envelope_spectrum(freqs, ses, frequencies=b.frequencies(1797 / 60), fmax=600,
                              ax=ax)
    ax.set_title(f"{name}: diagnosed '{label}'")
fig.tight_layout()

X, meta = bp.datasets.load_mfpt(data / "mfpt_mat", segment_s=0.5)
mfpt = bp.diagnose.EnvelopeDiagnoser(bearing="MFPT-NICE", fs=float(meta.fs[0]),
                                     rpm=float(meta.rpm[0]))
for label, predicted in zip(meta.label, mfpt.predict(X), strict=True):
    print(f"MFPT {label}: diagnosed '{predicted}'")
plt.show()
