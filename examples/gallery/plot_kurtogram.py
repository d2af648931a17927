"""
The fast kurtogram chooses the demodulation band
================================================

Impacts of a fault ring the structure's resonances; the band where the signal is most
impulsive (highest spectral kurtosis) is where to demodulate. Antoni's fast kurtogram
scans a 1/3-binary tree of bands; here it finds the 3 kHz resonance of a simulated
outer-race fault buried in noise.
"""

import matplotlib.pyplot as plt

import ballpass as bp

scene = bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault("outer"), duration_s=1.0,
                 fs=12_000, resonance_hz=3_000, resonance_damping=0.02, snr_db=-5, seed=2)
res = bp.simulate(scene)
kurt = bp.features.fast_kurtogram(res.accel, res.fs)
print(f"best band: {kurt.best_band[0]:.0f}-{kurt.best_band[1]:.0f} Hz")

fig, (ax0, ax1) = plt.subplots(2, 1, figsize=(8, 7))
kurt.plot(ax=ax0)
freqs, ses = bp.features.envelope_spectrum(res.accel, res.fs, band=kurt.best_band)
bp.plot.envelope_spectrum(freqs, ses, frequencies=scene.frequencies, fmax=500, ax=ax1)
fig.tight_layout()
plt.show()
