"""
Choosing a model and a solver
=============================

"Model only what a scene needs": each model of the hierarchy declares the phenomena it
represents and its cost relative to ``sr5``; a scene says what it needs, and
``model="auto"`` runs the cheapest model that covers it. Then the solver: speed against
error, measured on your own scene.
"""

# %%
# The model: say what the scene needs
# -----------------------------------
import ballpass as bp

scene = bp.Scene(bearing="6205", rpm=1797, fault=bp.Fault("outer"), fs=48_000,
                 duration_s=0.2)
print("needs:", sorted(bp.simulate.scene_needs(scene)))
print("auto runs:", bp.simulate.resolve_model(scene))
print(bp.simulate.model_table()[["model", "relative_cost", "solvers"]].to_string(index=False))

# %%
# Ask for less and you get a cheaper model: the envelope-level signature a diagnosis
# reads needs no contact dynamics, and the impulse model gives it.
envelope_only = scene.replace(needs=("envelope",))
bp.simulate(envelope_only), bp.simulate(scene)   # first calls load the compiled kernels
for res in (bp.simulate(envelope_only), bp.simulate(scene)):
    print(f"{res.info['model']:8s} {res.info['wall_time_s'] * 1e3:7.1f} ms  "
          f"{res.info['model_reason']}")

# %%
# Ask for more (contact forces, ball dynamics, a gear mesh) and ``auto`` moves up the
# hierarchy, or refuses the scene, saying what each model lacks.
try:
    bp.simulate(scene.replace(needs=("gear_mesh",)))
except ValueError as err:
    print(err)

# %%
# The solver: speed against error
# -------------------------------
# Each model's default solver and step keep the output's relative L2 error below 1e-3.
# When the error matters more than the time, use the adaptive solver with a tolerance.
ref = bp.simulate(scene, solver="dopri5", rtol=1e-8)
print(ref.info["solver"], ref.info["n_steps"], "steps")

# %%
# Measure it on your own scene (here without scipy's solvers, which take seconds to
# minutes per simulated second):
table = bp.simulate.work_precision(scene.replace(duration_s=0.05), scipy_methods=())
print(table[["method", "setting", "wall_s", "n_steps", "error_l2"]].to_string(index=False))
ax = bp.simulate.plot_work_precision(table)
