"""
model="auto": the cheapest model that represents the scene
==========================================================

Every model declares the phenomena it represents and its cost relative to ``sr5``; a
scene says what it needs, and ``model="auto"`` runs the cheapest model that covers it.
The figure is the registry: which model represents what, and at what cost.
"""

import matplotlib.pyplot as plt
import numpy as np

import ballpass as bp
from ballpass.phenomena import PHENOMENA

scene = bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault("outer"))
print("needs:", sorted(bp.simulate.scene_needs(scene)))
print("auto runs:", bp.simulate.resolve_model(scene))

table = bp.simulate.model_table()
phenomena = list(PHENOMENA)
grid = table[phenomena].to_numpy(dtype=float)

fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 3.5), width_ratios=(3, 1))
ax0.imshow(grid, cmap="Greens", vmin=0, vmax=1.4, aspect="auto")
ax0.set_xticks(np.arange(len(phenomena)), phenomena, rotation=35, ha="right")
ax0.set_yticks(np.arange(len(table)), table["model"])
ax0.set_title("represents")
ax1.barh(table["model"], table["relative_cost"])
ax1.set_xscale("log")
ax1.invert_yaxis()
ax1.set_xlabel("cost per simulated second (sr5 = 1)")
fig.tight_layout()
plt.show()
