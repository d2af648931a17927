"""
From a recording to a first diagnosis
=====================================

A vibration recording of a faulty bearing taken to a diagnosis you can defend: the
squared envelope spectrum, the fault lines in it, and the diagnoser's verdict with its
evidence. The recording is a two-second crop of a Case Western Reserve University file
(``12k_DE_IR007_0.mat``: drive-end 6205, inner-race fault of 0.007 in, 1797 rpm,
12 kHz), shipped with ballpass; your own file enters the same way.

Install first (the first simulation compiles the numba kernels once, 15-60 s; analysis
of recordings starts at once)::

    python3 -m venv .venv && .venv/bin/pip install -q -e .
"""

# %%
# Load the recording
# ------------------
# A plain recording is an array and its sampling rate. Here the crop is stored in g;
# ballpass works in m/s^2. (A CWRU ``.mat`` file goes through
# ``bp.datasets.load_cwru(path, channel="DE", segment_s=1.0)``, which converts the unit,
# reads the rate and the fault from the name, and cuts the record into segments that
# share a ``group``; recordings of any rig through ``bp.datasets.load_manifest``.)
from importlib import resources

import numpy as np

import ballpass as bp

with np.load(resources.files("ballpass") / "examples" / "data"
             / "cwru_12k_DE_IR007_0_DE_crop.npz") as z:
    x = z["accel_g"].astype(float) * 9.80665      # g -> m/s^2
    fs, rpm = float(z["fs"]), float(z["rpm"])
X = x.reshape(2, -1)                               # two one-second segments
print(f"{X.shape[0]} segments of {X.shape[1] / fs:g} s at {fs:g} Hz, {rpm:g} rpm")
print({k: round(float(v), 2) for k, v in bp.features.indicators(x).items()})

# %%
# Look before you decide
# ----------------------
# A localized fault strikes once per pass of a rolling element and rings the structure's
# resonances; the squared envelope spectrum (SES) of a band around such a resonance
# shows a family of lines at the defect frequency. The kurtogram picks the band; with
# the bearing and speed known, it picks among bands above the fault lines it must carry.
b = bp.Bearing.catalog("6205")
f = b.frequencies(shaft_hz=rpm / 60)
print(f"BPFO {f.bpfo:.1f} Hz, BPFI {f.bpfi:.1f} Hz, 2xBSF {f.ball_defect:.1f} Hz, "
      f"FTF {f.ftf:.1f} Hz")
analysis = bp.features.envelope_analysis(X[0], fs, rpm=rpm, bearing=b)
print("band chosen by the kurtogram:", analysis.band, "Hz")
fig = analysis.plot()

# %%
# An inner-race fault shows BPFI (162 Hz here) and its harmonics with sidebands at the
# shaft speed (the fault turns in and out of the load zone); an outer-race fault BPFO
# without them; a ball fault 2xBSF with sidebands at the cage speed (FTF).
#
# Diagnose
# --------
# The diagnoser needs no training: it scores each fault family by the lines only it
# explains, searched over the slip range, against a threshold from noise statistics,
# and grades how sure it is (Y clear, P partial, N not diagnosable).
diag = bp.diagnose.EnvelopeDiagnoser(bearing="6205", fs=fs, rpm=rpm)
print("verdicts:", list(diag.predict(X)))
why = diag.explain(X[:1])[0]
print(why)

# %%
# The lines it read, on the SES it read them in:
ax = bp.diagnose.plot_explanation(X[0], fs, why)

# %%
# A healthy machine is not noise: it carries its own lines (shaft harmonics, a loaded
# bearing's varying compliance), and one may sit where a fault family's lines fall. With
# a healthy recording of the same machine and sensor, let it set the thresholds::
#
#     thresholds = bp.diagnose.baseline_thresholds(
#         [(h, fs, rpm) for h in healthy_segments], "6205", seconds=1.0)
#     diag = bp.diagnose.EnvelopeDiagnoser(bearing="6205", fs=fs, rpm=rpm,
#                                          threshold_db=thresholds)
#
# From the command line
# ---------------------
# ``ballpass diagnose ir007.npy --fs 12000 --rpm 1797 --bearing 6205``, here run through
# the command's own entry point. It takes a plain file (``.npy``, ``.csv``, ``.wav``) with
# its rate, speed and bearing, or a manifest table listing many recordings.
import contextlib  # noqa: E402
import io  # noqa: E402
import tempfile  # noqa: E402
from pathlib import Path  # noqa: E402

from ballpass.cli import main  # noqa: E402  (what the `ballpass` command runs)

path = Path(tempfile.mkdtemp()) / "ir007.npy"
np.save(path, X[0])
printed = io.StringIO()
with contextlib.redirect_stdout(printed):
    main(["diagnose", str(path), "--fs", str(fs), "--rpm", str(rpm), "--bearing", "6205",
          "--quiet"])
print(printed.getvalue())
