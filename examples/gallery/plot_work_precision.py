"""
Speed against error: the work-precision diagram
===============================================

The solvers of a model on one scene: wall time against the relative L2 error of the
sensor signal, measured against a tight reference. A fixed-step RK4 swept over its step
and the adaptive Dormand-Prince 5(4) over its tolerance; pick the cheapest point below
the error you need.
"""

import matplotlib.pyplot as plt

import ballpass as bp

scene = bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault("inner"), duration_s=0.05,
                 fs=12_000, resonance_hz=3_000)
table = bp.simulate.work_precision(scene, rk4_dt=[4e-5, 2e-5, 1e-5, 5e-6],
                                   dopri5_rtol=[1e-4, 1e-6, 1e-8], scipy_methods=[],
                                   repeats=1)
print(table[["method", "setting", "wall_s", "error_l2"]].to_string(index=False))
bp.simulate.plot_work_precision(table)
plt.show()
