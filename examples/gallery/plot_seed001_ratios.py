"""
Nabhan & Rashed (2020): faulty/healthy indicator ratios against speed
=====================================================================

Nabhan & Rashed (2020) judges an inner-race fault by the ratio of statistical indicators (RMS,
crest factor, kurtosis) of the faulty to the healthy signal, over speed. Here a 6004
with a 0.5 mm inner-race notch, loaded-zone sensor, the same absolute noise on both
runs (``benchmarks/seed001_ratios.py`` runs the whole study).
"""

import matplotlib.pyplot as plt

import ballpass as bp

speeds = [500, 1000, 2000, 3000]
ratios = {"rms": [], "crest_factor": [], "kurtosis": []}
for rpm in speeds:
    common = dict(bearing="6004", rpm=rpm, radial_load_n=500, duration_s=0.5,
                  fs=48_000, noise_rms=0.5, seed=1)
    healthy = bp.simulate(bp.Scene(**common)).accel
    faulty = bp.simulate(bp.Scene(**common, fault=bp.Fault("inner", width_mm=0.5,
                                                           depth_mm=0.1))).accel
    r = bp.features.indicator_ratios(faulty, healthy)
    for name in ratios:
        ratios[name].append(r[name])

fig, ax = plt.subplots(figsize=(6, 4))
for name, values in ratios.items():
    ax.plot(speeds, values, "o-", label=name)
ax.axhline(1.0, color="k", lw=0.7)
ax.set_yscale("log")
ax.set_xlabel("shaft speed (rpm)")
ax.set_ylabel("faulty / healthy")
ax.legend()
fig.tight_layout()
plt.show()
