"""The multibody model after its right-hand side was made cheaper (issue 29) gives what
it gave before: the signal, contact loads, ball angles, ring displacements and fault
crossings of the former code on short scenes covering each branch of the right-hand
side (an inner-race notch at 48 kHz, outer and ball notches with two attenuating
sensors, a run-up without gravity under the Rosenbrock-W solver), stored by
tests/data/make_multibody_reference.py.

The comparison is exact. The model is sensitive to rounding: the former code started
from a state changed by one unit in the last place ends these 10 ms scenes with its
signal off by 2e-6 of the peak (inner_48k), 1e-8 (ball_outer_two_sensors) and 5e-2
(run_up_rosw, whose loads move by 8e-4), and on the 0.05 s cost scene by 1e-2, so a
tolerance loose enough for reordered arithmetic would be set by the scene and its
length, not by the code. Every change to the kernels must keep each floating-point
operation as it was (hoisting, skipping lookups that return nothing). The stored
arrays are those of one platform (glibc's libm, x86-64): on another, whose exp or
sqrt rounds differently in the last place, regenerate them from the commit named in
the make script before changing the kernels."""

from __future__ import annotations

import platform

import llvmlite
import numba
import numpy as np
import pytest
from _reference import reference

ref, STORED = reference("multibody")

#: the platform that wrote the stored arrays: bit for bit holds there only (another
#: processor, libm or compiler may round an exp or sqrt differently in the last place)
WRITTEN_ON = {"machine": "x86_64", "system": "Linux", "numba": "0.68.1", "llvmlite": "0.50.0"}
HERE = {"machine": platform.machine(), "system": platform.system(),
        "numba": numba.__version__, "llvmlite": llvmlite.__version__}


@pytest.mark.skipif(HERE != WRITTEN_ON, reason=f"the reference was written on {WRITTEN_ON}, "
                    f"this is {HERE}: regenerate it (tests/data/make_multibody_reference.py)")
@pytest.mark.parametrize("name", list(ref.SCENES))
def test_output_as_before(name):
    got = ref.outputs(ref.run(name))
    for key, value in got.items():
        old = STORED[f"{name}/{key}"]
        assert value.shape == old.shape, key
        np.testing.assert_array_equal(value, old, err_msg=f"{name}/{key}")
