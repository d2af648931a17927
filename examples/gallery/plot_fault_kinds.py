"""
Each fault kind in its squared envelope spectrum
================================================

A 6205 at 1797 rpm on a CWRU-like rig (12 kHz sampling, a 3 kHz structural
resonance), healthy and with an outer-race, inner-race and ball fault. The squared
envelope spectrum (SES) of the band around the resonance shows each fault as a family
of lines: BPFO for the outer race, BPFI with +-shaft sidebands for the inner race,
2xBSF with +-FTF sidebands for a ball.
"""

import matplotlib.pyplot as plt

import ballpass as bp

fig, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True)
for ax, kind in zip(axes, [None, "outer", "inner", "ball"], strict=True):
    scene = bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault(kind) if kind else None,
                     duration_s=1.0, fs=12_000, resonance_hz=3_000,
                     resonance_damping=0.02, noise_rms=0.05, seed=1)
    res = bp.simulate(scene)
    freqs, ses = bp.features.envelope_spectrum(res.accel, res.fs,
                                               band=scene.demodulation_band)
    bp.plot.envelope_spectrum(freqs, ses, frequencies=scene.frequencies, fmax=500, ax=ax)
    ax.set_title(scene.label)
    ax.legend().set_visible(ax is axes[0])
fig.tight_layout()
plt.show()
