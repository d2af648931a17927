"""Seed 001's conclusions that the physics supports, on a reduced speed sweep.

The sweep of ``benchmarks/seed001_ratios.py`` (SKF 6004, inner-race notches of 0.25,
0.5 and 0.75 mm, loaded- and unloaded-zone sensors, white noise of a fixed 0.5 m/s^2
RMS for healthy and faulty runs alike) at three speeds, one run per point, 0.5 s.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _bench import load_benchmark

SCRIPT = Path(__file__).resolve().parent.parent / "benchmarks" / "seed001_ratios.py"


@pytest.fixture(scope="module")
def table():
    module = load_benchmark("seed001_ratios")
    return module.ratios(speeds=(500.0, 1500.0, 3000.0), repeats=1, duration_s=0.5, n_jobs=1)


def _ratio(table, indicator, sensor=None):
    part = table[table.indicator == indicator]
    if sensor is not None:
        part = part[part.sensor == sensor]
    return part


def test_rms_ratio_exceeds_one_for_every_size_speed_and_zone(table):
    # the smallest ratio of the full sweep is 1.34 (0.25 mm, unloaded zone): a fault
    # adds vibration on top of the same absolute noise
    rms = _ratio(table, "rms")
    assert len(rms) == 3 * 3 * 2
    assert (rms.ratio > 1.2).all()


def test_rms_ratio_rises_with_speed_in_the_loaded_zone(table):
    # full sweep with the former 1 kg shaft, 500 -> 3000 rpm: 2.2 -> 3.7, 8.8 -> 15.1,
    # 8.3 -> 19.7. With the sourced 3.26 kg shaft (Ruan et al.) the 0.25 mm notch, whose
    # ball drop (2.5 um) is shallower than the contact deflection, no longer rises
    # (3.8 at 500 rpm, 3.5 at 3000 rpm in the reduced sweep); the deeper two do.
    rms = _ratio(table, "rms", "loaded")
    for width, part in rms.groupby("width_mm"):
        r = part.sort_values("rpm").ratio.to_numpy()
        if width > 0.3:
            assert r[-1] > 1.3 * r[0]


def test_crest_factor_is_the_weakest_indicator(table):
    # median over sizes, speeds and zones of log(ratio): crest factor ~0.8 against
    # ~1.6 (RMS) and ~1.9 (kurtosis) in the full sweep. Skewness is left out: its
    # healthy value is ~0 +- 0.01, so its ratio is noise with a random sign.
    strength = {name: np.median(np.log(_ratio(table, name).ratio))
                for name in ("rms", "crest_factor", "kurtosis")}
    assert strength["crest_factor"] < 0.7 * min(strength["rms"], strength["kurtosis"])
    assert (_ratio(table, "crest_factor").ratio > 1.0).all()
