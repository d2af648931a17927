"""Every catalogue bearing simulates with the default fault of each kind (issue 16, item 7).

NJ305 (rollers, 0.125 mm radial clearance) used to fail with "static equilibrium did
not converge": the solver started inside the clearance-plus-defect dead zone, where
neither force nor Jacobian exists.
"""

import math

import numpy as np
import pytest

import ballpass as bp
from ballpass.simulate.sr5 import SR5Parameters, build_model

CASES = [(name, kind) for name in bp.Bearing.catalog_names()
         for kind in ("outer", "inner", "ball", None)]


@pytest.mark.parametrize(("name", "kind"), CASES)
def test_catalogue_bearing_simulates_with_the_default_fault(name, kind):
    """10 ms at 48 kHz: long enough to pass the static start and a few contacts; the
    output is finite and the housing moves."""
    scene = bp.Scene(bearing=name, fault=bp.Fault(kind) if kind else None, duration_s=0.01,
                     seed=1)
    res = bp.simulate(scene)
    assert res.accel.shape[-1] == 480
    assert np.isfinite(res.accel).all() and np.ptp(res.accel) > 0


def test_nj305_static_equilibrium_with_an_outer_fault_under_the_load():
    """Closed form: with 0.125 mm clearance only the element at 0 deg (in the defect)
    touches, so the ring drops by clearance + defect depth + (W / K)^(1/n), W the load
    plus the shaft weight. Its neighbours at +-32.7 deg would need c / cos(32.7 deg) =
    148.6 um, far more. Tolerance 1e-12 m: the solver's xtol (1e-13) on 0.13 mm."""
    fault = bp.Fault("outer")
    scene = bp.Scene(bearing="NJ305", fault=fault, duration_s=0.01, radial_load_n=500.0)
    b = scene.bearing
    model = build_model(scene)
    load = 500.0 + SR5Parameters().shaft_mass * 9.80665
    elastic = (load / b.hertz_stiffness()) ** (1.0 / b.load_exponent)
    depth = fault.effective_depth_mm(b) * 1e-3
    drop = model.y0[0] - model.y0[2]  # shaft minus pedestal along the load line
    assert drop == pytest.approx(b.radial_clearance_m + depth + elastic, abs=1e-12)
    assert model.static_deflection == pytest.approx(elastic, rel=1e-9)
    assert b.radial_clearance_m / math.cos(2 * math.pi / b.n_elements) > drop
