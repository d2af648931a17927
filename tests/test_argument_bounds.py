"""Arguments that would ask for gigabytes or hours are refused before any work.

Each call is timed and its Python/NumPy allocations traced (tracemalloc sees NumPy's
buffers): a refusal must come at once and allocate nothing near the size asked for.
Before these bounds, each case allocated 7-446 GiB (or hung); the 64 MiB limit below is
far under that and far above what validating a 2 s signal takes (24,000 samples).
"""

import time
import tracemalloc

import numpy as np
import pytest

from ballpass import features as F
from ballpass.cli import main

FS = 12_000.0
X = np.random.default_rng(0).standard_normal(24_000)
LIMIT_BYTES = 64 * 2**20


@pytest.fixture(scope="module", autouse=True)
def warm():
    """Imports and first calls outside the traced, timed part (tracemalloc slows them)."""
    F.fault_band_features(X, FS, "6205", 1797)
    F.order_track(X, FS, rpm=1797)


def refused_at_once(call, match: str) -> None:
    tracemalloc.start()
    t = time.perf_counter()
    try:
        with pytest.raises(ValueError, match=match):
            call()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert time.perf_counter() - t < 2.0        # checked, not computed (this took >4 s)
    assert peak < LIMIT_BYTES


@pytest.mark.parametrize("call, match", [
    (lambda: F.fault_band_features(X, FS, "6205", 1797, harmonics=10**9),
     r"harmonics must be at most 12,001 here, the spectrum's bins: .* beyond harmonic 508 "
     r".* above the spectrum's top, 6000 Hz; got 1,000,000,000"),
    (lambda: F.fault_band_levels(np.arange(12_001) * 0.5, np.ones(12_001), "6205", 1797,
                                 harmonics=10**9), "harmonics must be at most"),
    (lambda: F.fault_band_features(X, FS, "6205", 1797, background_hz=1e9),
     "background_hz must be at most the spectrum's top frequency, 6000 Hz, got 1e"),
    (lambda: F.order_track(X, FS, rpm=1797, samples_per_rev=10**9),
     r"samples_per_rev=1000000000 gives .* of memory available; the default, 401, samples"),
    (lambda: F.spectral_kurtosis(X, FS, nperseg=10**9),
     "at least two full segments of nperseg = 1000000000 samples"),
])
def test_memory_bombs_refused_before_any_work(call, match):
    refused_at_once(call, match)


def test_huge_fs_is_cheap_not_a_bomb():
    """At fs = 1e12 Hz one bin is 4e7 Hz wide: no shaft harmonic is resolved, so the
    shaft guard has nothing to do (it used to enumerate 1.6e10 harmonics: 3.65 GiB)."""
    t = time.perf_counter()
    feats = F.fault_band_features(X, 1e12, "6205", 1797)
    assert time.perf_counter() - t < 5.0      # about 0.03 s (0.7 s loaded); the bomb took minutes
    # every fault line lies in the first bin of a 4e7 Hz-wide grid: no background beside
    # it (cut by 0 Hz), so the levels are those of the edge rule, finite
    assert all(np.isfinite(v) for v in feats.values())


def test_largest_harmonics_allowed_still_computes():
    """The bound keeps what the levels promise (lines above the top read NaN) and stops
    only sizes beyond the spectrum's: as many harmonics as bins are still computed."""
    from ballpass import Bearing

    freqs = np.arange(201) * 0.5                                   # 0..100 Hz
    ses = np.random.default_rng(1).exponential(size=201)
    ftf = Bearing.catalog("6205").frequencies(1797 / 60).ftf        # lowest line, Hz
    fit = int(100 / (ftf * 0.99))                                  # 1 % tolerance
    assert fit == 8
    levels = F.fault_band_levels(freqs, ses, "6205", 1797, harmonics=201)
    assert np.isfinite(levels["ftf_8"]) and np.isnan(levels["ftf_9"])
    with pytest.raises(ValueError, match="at most 201 here, the spectrum's bins"):
        F.fault_band_levels(freqs, ses, "6205", 1797, harmonics=202)
    with pytest.raises(ValueError, match=r"tolerance must be in \[0, 1\)"):
        F.fault_band_features(X, FS, "6205", 1797, tolerance=2)


def test_bifurcation_range_bomb_refused_naming_the_option(tmp_path, capsys):
    t = time.perf_counter()
    assert main(["bifurcation", "--parameter", "rpm", "--range", "500", "600", "1000000",
                 "--out", str(tmp_path / "b.csv")]) == 2
    assert time.perf_counter() - t < 5
    err = capsys.readouterr().err
    assert "--range NUM must be a whole number from 1 to 10,000" in err
    assert list(tmp_path.iterdir()) == []


def test_grid_with_an_invalid_last_point_refused_before_building_the_others():
    """A million points whose last speed is negative (the outermost axis: reached
    last): refused at once, not after building the 666,666 points before it (tens of
    seconds), and by what is wrong with it rather than by its size."""
    from ballpass.datasets import read_grid

    grid = {"dataset": {"duration_s": 0.1, "fs": 12000},
            "grid": {"bearing": ["6205"], "fault": ["outer"], "resonance_hz": [3000],
                     "rpm": [1797, 1800, -5],
                     "radial_load_n": {"start": 0, "stop": 333332, "step": 1}}}
    read_grid({"dataset": grid["dataset"], "grid": {**grid["grid"], "rpm": [1797],
                                                    "radial_load_n": [0]}})   # imports
    t = time.perf_counter()
    with pytest.raises(ValueError, match=r"rpm=-5.0, radial_load_n=333332.0, .*\): rpm "
                                         "must be"):
        read_grid(grid)
    assert time.perf_counter() - t < 5.0   # 1 s loaded; building the points first took 3 min


def test_a_grid_of_ten_million_valid_points_is_refused_before_building_them():
    """10^7 listed points (validated one by one at ~0.1 ms each: 17 minutes) are refused
    at once with what to do instead; the same study with a drawn axis is accepted."""
    from ballpass.datasets import read_grid
    from ballpass.datasets.grid import MAX_POINTS

    dataset = {"duration_s": 0.1, "fs": 12000}
    grid = {"bearing": ["6205"], "fault": ["outer"], "resonance_hz": [3000],
            "rpm": {"start": 600, "stop": 1599, "step": 1},          # 1 000 speeds
            "radial_load_n": {"start": 100, "stop": 5099, "step": 0.5}}  # x 10 000 loads
    t = time.perf_counter()
    with pytest.raises(ValueError, match=rf"lists 1e\+07 points .*at most {MAX_POINTS:,}"):
        read_grid({"dataset": dataset, "grid": grid})
    assert time.perf_counter() - t < 5.0   # refusing takes milliseconds; building, minutes
    drawn = read_grid({"dataset": {**dataset, "draws": 1000},
                       "grid": {**grid, "rpm": {"uniform": [600, 1600]},
                                "radial_load_n": [100, 600, 5099]}})
    assert drawn.n_runs == 3000


@pytest.mark.parametrize("call, match", [
    # found by benchmarks/abuse_sweep.py: a MemoryError after seconds, or a hang
    (lambda: __import__("ballpass").diagnose.envelope_evidence(X, FS, "6205", 1797,
                                                               harmonics=10**9),
     "harmonics must be at most 12,001 here"),
    (lambda: F.bandpass(X, FS, (1000, 3000), order=10**9),
     r"order must be an int in \[1, 200\], got 1000000000"),
    (lambda: F.envelope_spectrum(X, FS, (1000, 3000), order=10**12), r"order must be an int in"),
])
def test_more_bombs_refused_before_any_work(call, match):
    refused_at_once(call, match)
