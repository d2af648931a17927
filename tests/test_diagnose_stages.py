"""The evidence engine stage by stage: candidate bands (the anti-aliasing roll-off
excluded), line readings, family scores."""

from __future__ import annotations

import numpy as np
import pytest

import ballpass as bp
from ballpass.diagnose import envelope_evidence
from ballpass.diagnose.evidence import (
    ALIAS_FREE_FRACTION,
    OUTER_SIDEBAND_MARGIN_DB,
    LineReadings,
    candidate_bands,
    family_scores,
    line_readings,
)

ORDERS = bp.Bearing.catalog("6205").frequencies(1.0).as_dict()


@pytest.mark.parametrize("fs", [12_000.0, 48_000.0, 51_200.0])
def test_no_band_reaches_into_the_anti_aliasing_roll_off(fs):
    # fs / 2.56 is the alias-free bandwidth of acquisition hardware (20 kHz at 51.2 kHz).
    # Catches the old rule (only the band ending at fs/2 left out: at 12 kHz the
    # 4500-5250 Hz band, at 51.2 kHz 20-22.4 kHz would be searched).
    x = np.random.default_rng(0).standard_normal((1, int(fs)))
    bands, _ = candidate_bands(x, fs, 600.0)
    assert len(bands) > 0
    assert bands[:, 1].max() <= ALIAS_FREE_FRACTION * fs
    # ... and the tree still reaches up to it: the highest band ends within one band
    # of the coarsest level that has bands this narrow (fs / 16, level 3) of the limit.
    assert bands[:, 1].max() >= ALIAS_FREE_FRACTION * fs - fs / 16


def test_impacts_ringing_in_the_roll_off_are_no_evidence():
    # Impacts at BPFO ringing 5.3 kHz at fs = 12 kHz (inside 4.69-6 kHz, the roll-off
    # of a 12 kHz recorder) read as no fault; the same impacts ringing 3 kHz are a
    # clear outer-race fault (10 dB measured). The old band rule read the 5.3 kHz
    # ones in 4500-5250 Hz.
    fs, rpm = 12_000.0, 1797.0
    t = np.arange(24_000) / fs
    bpfo = ORDERS["bpfo"] * rpm / 60
    since = (t * bpfo) % 1.0 / bpfo
    noise = 0.5 * np.random.default_rng(1).standard_normal(t.size)

    def outer(ring_hz):
        x = np.exp(-800 * since) * np.sin(2 * np.pi * ring_hz * since) + noise
        return envelope_evidence(x, fs, "6205", rpm).evidence_db["outer"][0]

    assert outer(3000.0) > 8.0  # 6 dB is the default threshold
    assert outer(5300.0) < 6.0


def _readings(fault, carriers_db, sidebands_db):
    """LineReadings of one row at one scale with the given carrier and sideband levels."""
    level = []
    for c, s in zip(carriers_db, sidebands_db, strict=True):
        level += [c, s, s]
    level = np.array(level, dtype=float)[None, None, :]
    return LineReadings(fault=fault, scales=np.array([1.0]), level_db=level,
                        on_bin_db=level, found_hz=np.zeros_like(level),
                        on_shaft=np.zeros(level.shape, bool),
                        side=np.tile([0.0, -1.0, 1.0], len(carriers_db)),
                        n_carriers=len(carriers_db))


def test_family_scores_closed_forms():
    # Inner race and ball: mean of carriers and strongest sidebands, halved sum.
    score, _ = family_scores(_readings("inner", [20.0, 10.0], [8.0, 4.0]), [True])
    assert score[0, 0] == pytest.approx(0.5 * (15.0 + 6.0))
    # Outer race: carriers, less the shortfall of the +-FTF sidebands below them.
    score, _ = family_scores(_readings("outer", [20.0, 10.0], [15.0, 5.0]), [True])
    assert score[0, 0] == pytest.approx(15.0 - (10.0 - 15.0 + OUTER_SIDEBAND_MARGIN_DB))
    # ... not marked down where the record cannot resolve the sidebands,
    score, _ = family_scores(_readings("outer", [20.0, 10.0], [15.0, 5.0]), [False])
    assert score[0, 0] == pytest.approx(15.0)
    # ... and the ball is not judged there at all.
    score, _ = family_scores(_readings("ball", [20.0, 10.0], [15.0, 5.0]), [False])
    assert score[0, 0] == -np.inf
    # Fewer than two unshared carriers: not judged.
    one = _readings("inner", [20.0], [10.0])
    assert family_scores(one, [True])[0][0, 0] == -np.inf


def test_line_readings_find_a_line_off_its_kinematic_frequency():
    # A line 1.5 % below 2xBPFI (slip) on a flat SES: the reading at the scale 0.985
    # is the line's 20 dB, and the bin it names is the line's.
    df, fr = 0.5, 30.0
    ses = np.ones((1, 4000))
    k = round(0.985 * 2 * ORDERS["bpfi"] * fr / df)
    ses[0, k] = 100.0
    r = line_readings(ses, np.zeros(ses.shape, bool), df, np.array([fr]), ORDERS, "inner", 3,
                      0.02, 10.0, np.zeros(3, bool))
    j = np.argmin(abs(r.scales - 0.985))
    assert r.level_db[0, j, 3] == pytest.approx(20.0, abs=0.01)  # line 3: 2xBPFI
    assert r.found_hz[0, j, 3] == pytest.approx(k * df)
    # A notch (shaft harmonic) on that bin turns it into background.
    notch = np.zeros(ses.shape, bool)
    notch[0, k - 1 : k + 2] = True
    r = line_readings(ses, notch, df, np.array([fr]), ORDERS, "inner", 3, 0.02, 10.0,
                      np.zeros(3, bool))
    assert np.nanmax(r.level_db[0, :, 3]) == pytest.approx(0.0, abs=0.01)
