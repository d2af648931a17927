"""
Poincare sections and a bifurcation diagram of the rotor model
==============================================================

The NJ 305 rotor paper's rigid rotor on an NJ 305 roller bearing (``rotor2``): with no clearance the
once-per-revolution Poincare section of the journal is a single point (periodic
motion); with clearance the rotor rattles in the gap and the section spreads. The
bifurcation diagram stacks the sections over the clearance.
"""

import matplotlib.pyplot as plt

import ballpass as bp

base = bp.Scene(bearing="NJ305", rpm=2000, radial_load_n=200, duration_s=0.6,
                fs=12_000, resonance_hz=3_000)
fig, axes = plt.subplots(1, 3, figsize=(11, 3.6))
for ax, clearance in zip(axes[:2], (0.0, 0.05), strict=True):
    b = bp.Bearing.catalog("NJ305").with_clearance(clearance)
    res = bp.simulate(base.replace(bearing=b), return_forces=True)
    points = bp.dynamics.poincare_section(res, strobe="shaft", discard_s=0.3)
    bp.dynamics.plot_poincare(points, ax=ax)
    ax.set_title(f"clearance {clearance} mm")

df = bp.dynamics.bifurcation_diagram(base, "radial_clearance_mm", [0.0, 0.02, 0.04, 0.06],
                                     discard_s=0.3, progress=False)
bp.dynamics.plot_bifurcation(df, ax=axes[2])
fig.tight_layout()
plt.show()
