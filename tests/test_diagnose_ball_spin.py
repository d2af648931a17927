"""The ball's own readings: its smeared 2xBSF comb on the averaged squared envelope
spectrum, and the cage-rate swell of its 2xBSF component (ballpass.diagnose.ball_spin)."""

from __future__ import annotations

import numpy as np
import pytest

import ballpass as bp
from ballpass.diagnose.ball_spin import (
    SEGMENT_S,
    averaged_ses,
    cage_modulation_db,
    smeared_ball_evidence,
)
from ballpass.diagnose.evidence import candidate_bands
from ballpass.features.demodulate import BandDemodulator

FS, RPM = 12_000.0, 1797.0
FREQS = bp.Bearing.catalog("6205").frequencies(RPM / 60.0)
BAND = (2000.0, 4000.0)
# Noise: each level is the largest of a few spectrum bins (exponential, one degree of
# freedom pair) over their median (ln 2 of the mean): 13 dB is 20 medians, 13.9 means,
# which one bin exceeds with probability exp(-13.9) = 1e-6; 40 noise seeds read at most
# 10.1 dB. A modulated line reads 20-40 dB.
NOISE_CEILING_DB = 13.0


def _impacts(modulation_hz: float, seconds: float = 5.0, seed: int = 0,
             noise_rms: float = 0.5, spin_jitter: float = 0.0):
    """Impacts at 2xBSF (1 % slip) ringing a 3 kHz resonance, their amplitude
    ``1 + cos`` at ``modulation_hz`` (the cage carrying the defect round the load zone
    at FTF; 0: none); ``spin_jitter`` the relative standard deviation of the ball's
    spin rate, a random walk that smears the line."""
    rng = np.random.default_rng(seed)
    n = int(seconds * FS)
    t = np.arange(n) / FS
    rate = 0.99 * FREQS.ball_defect * (1 + spin_jitter * np.cumsum(rng.standard_normal(n))
                                       / np.sqrt(n))
    cycles = np.cumsum(rate) / FS
    phase = (cycles % 1.0) / rate                            # time since the last impact, s
    ring = np.exp(-800.0 * phase) * np.sin(2 * np.pi * 3000.0 * phase)
    ring = ring * (1 + np.cos(2 * np.pi * modulation_hz * (t - phase)))
    return ring / ring.std() + noise_rms * rng.standard_normal(n)


def _swell(x):
    ftf = 0.99 * FREQS.ftf
    return cage_modulation_db(BandDemodulator(x, FS, max_hz=600.0), BAND,
                              0.99 * FREQS.ball_defect, [ftf, FREQS.shaft], cage_hz=ftf)


@pytest.mark.parametrize("seed", [0, 1])
def test_a_cage_modulated_ball_swells_at_ftf_not_at_the_shaft_rate(seed):
    ftf_db, fr_db = _swell(_impacts(0.99 * FREQS.ftf, seed=seed))
    # The 1 + cos modulation puts the FTF line of the component's envelope at the
    # carrier's power over a background of noise x noise products: well over the noise
    # ceiling, and 6 dB (a factor 4) over the shaft-rate reading, which holds only
    # leakage of the FTF line and its harmonic.
    assert ftf_db > NOISE_CEILING_DB
    assert ftf_db > fr_db + 6.0


@pytest.mark.parametrize("seed", [0, 1])
def test_a_shaft_modulated_comb_at_2xbsf_does_not_swell_at_ftf(seed):
    # The plausible mistake: a comb modulated at the shaft rate (a race's sideband
    # pattern) taken for the cage's. Its swell is at fr, seen only through the +-1.5 FTF
    # pass band's edges; at FTF it reads as noise does.
    ftf_db, fr_db = _swell(_impacts(FREQS.shaft, seed=seed))
    assert ftf_db < NOISE_CEILING_DB
    assert fr_db > ftf_db


@pytest.mark.parametrize("seed", range(4))
def test_noise_swells_at_neither_rate(seed):
    x = np.random.default_rng(100 + seed).standard_normal(int(5 * FS))
    assert np.all(_swell(x) < NOISE_CEILING_DB)


def _smeared(x, seconds_ok=True, **kwargs):
    shaft = RPM / 60.0
    bands, ok = candidate_bands(x[None], FS, 600.0)
    return smeared_ball_evidence(x[None], FS, "6205", np.array([shaft]), bands, ok, **kwargs)


def test_the_averaged_ses_gathers_a_smeared_ball_line():
    # Spin jitter of 1 % (random walk over the record) spreads the 2xBSF line over a
    # few hertz; on 1 Hz bins it gathers again, found within the slip search.
    x = _impacts(0.99 * FREQS.ftf, seconds=10.0, spin_jitter=0.01)
    read = _smeared(x, set_aside_races=False)
    assert read.evidence_db[0] > NOISE_CEILING_DB
    kinematic = FREQS.ball_defect
    assert kinematic * 0.98 - 1.0 <= read.found_hz[0, 0] <= kinematic * 1.005 + 1.0


def test_the_6205_ball_comb_cannot_be_read_clear_of_the_races():
    # BPFO + fr (4.585 orders) lies 2.7 % below 2xBSF (4.7135): within the 2 % slip
    # search and the 1 Hz main lobe, at every harmonic read; the comb is not judged.
    x = _impacts(0.99 * FREQS.ftf, seconds=10.0)
    assert _smeared(x).evidence_db[0] == -np.inf


def test_records_shorter_than_three_segments_are_not_read():
    x = _impacts(0.99 * FREQS.ftf, seconds=1.9 * SEGMENT_S)
    assert _smeared(x, set_aside_races=False).evidence_db[0] == -np.inf


def test_noise_reads_no_smeared_comb():
    x = np.random.default_rng(7).standard_normal(int(10 * FS))
    assert _smeared(x, set_aside_races=False).evidence_db[0] < NOISE_CEILING_DB


def test_averaged_ses_has_one_hertz_bins():
    x = np.random.default_rng(0).standard_normal(int(4 * FS))
    freqs, psd = averaged_ses(BandDemodulator(x, FS, max_hz=600.0), BAND)
    assert freqs[1] == pytest.approx(1.0 / SEGMENT_S, rel=1e-3)
    assert psd.shape == (1, freqs.size)


def test_the_benchmark_reads_a_cage_modulated_ball_as_an_expert_would():
    # benchmarks/diagnose_ball.py's expert row on a synthetic record (no shared data):
    # the comb found within the slip search, its component swelling at FTF rather than
    # fr (as the library test above), and one verdict per one-second segment.
    from _bench import load_benchmark

    bench = load_benchmark("diagnose_ball")
    x = _impacts(0.99 * FREQS.ftf, seconds=10.0)
    row = bench.expert_row(x, FS, "6205", RPM, "synthetic")
    assert row["smear_db"] > NOISE_CEILING_DB
    assert abs(row["found_1x_hz"] - 0.99 * FREQS.ball_defect) <= 1.0 + 1e-9  # one 1 Hz bin
    assert row["cage_ftf_db"] > row["cage_fr_db"] + 6.0
    assert sum(int(k) for k in row["segments"].split("/")) == 10


@pytest.mark.parametrize("kwargs, match", [
    (dict(cage_hz=0.0), "cage_hz"),
    (dict(centre_hz=-1.0), "centre_hz"),
    (dict(rates_hz=[]), "rates_hz"),
])
def test_cage_modulation_bad_input_names_the_argument(kwargs, match):
    x = np.random.default_rng(0).standard_normal(int(2 * FS))
    args = dict(centre_hz=140.0, rates_hz=[12.0], cage_hz=12.0) | kwargs
    with pytest.raises(ValueError, match=match):
        cage_modulation_db(BandDemodulator(x, FS, max_hz=600.0), BAND, args["centre_hz"],
                           args["rates_hz"], cage_hz=args["cage_hz"])


def test_smeared_ball_bad_input_names_the_argument():
    x = np.random.default_rng(0).standard_normal((1, int(3 * FS)))
    bands, ok = candidate_bands(x, FS, 600.0)
    with pytest.raises(ValueError, match="segment_s"):
        smeared_ball_evidence(x, FS, "6205", np.array([30.0]), bands, ok, segment_s=0.0)
    with pytest.raises(ValueError, match="has_signal"):
        smeared_ball_evidence(x, FS, "6205", np.array([30.0]), bands, ok[:, :1])
    with pytest.raises(ValueError, match="shaft_hz"):
        smeared_ball_evidence(x, FS, "6205", np.array([0.0]), bands, ok)
