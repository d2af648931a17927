"""Ball faults read as an expert reads them: a 2xBSF comb with cage (FTF) modulation,
and the enhanced envelope spectrum (band-integrated cyclic coherence) that shows it."""

from __future__ import annotations

import math

import numpy as np
import pytest

import ballpass as bp
from ballpass.diagnose import EnvelopeDiagnoser
from ballpass.diagnose.ball import (
    CAGE_SIDEBAND_MARGIN_DB,
    cage_shortfall_db,
    cyclic_family_evidence,
    load_zone_sideband_db,
)
from ballpass.features.cyclic import enhanced_envelope_spectrum

FS, RPM = 12_000.0, 1797.0
FREQS = bp.Bearing.catalog("6205").frequencies(RPM / 60.0)


def _ball_impacts(cage_modulated: bool, seconds: float = 4.0, seed: int = 0,
                  noise_rms: float = 0.5):
    """Impacts at 2xBSF (1 % slip) ringing a 3 kHz resonance, their amplitude the
    Stribeck load zone (epsilon = 0.5) the defect meets as the cage carries it round
    (``cage_modulated``), or constant (a comb at 2xBSF with no cage modulation)."""
    t = np.arange(int(seconds * FS)) / FS
    rate, ftf = 0.99 * FREQS.ball_defect, 0.99 * FREQS.ftf
    phase = (t * rate) % 1.0 / rate                           # time since the last impact, s
    ring = np.exp(-800.0 * phase) * np.sin(2 * np.pi * 3000.0 * phase)
    if cage_modulated:
        psi = 2 * np.pi * ftf * (t - phase)                   # cage angle at the impact
        ring = ring * np.clip(1 - (1 - np.cos(psi)) / (2 * 0.5), 0, None) ** 1.5
    noise = np.random.default_rng(seed).standard_normal(t.size)
    return ring / ring.std() + noise_rms * noise


def test_load_zone_sidebands_match_the_closed_form():
    # epsilon = 0.5: q^2 = cos^3 over +-90 deg; c1 / c0 = (3 pi / 8) / (4 / 3) = 9 pi / 32
    # exactly. The quadrature (20 000 points) is good to 1e-6 dB; 1e-3 leaves room.
    assert load_zone_sideband_db(0.5) == pytest.approx(20 * math.log10(9 * math.pi / 32),
                                                       abs=1e-3)
    # The 6 dB margin admits every load zone up to epsilon = 1.7 (the docstring's claim).
    assert load_zone_sideband_db(1.7) > -CAGE_SIDEBAND_MARGIN_DB > load_zone_sideband_db(2.0)
    with pytest.raises(ValueError, match="epsilon"):
        load_zone_sideband_db(0.0)


def test_cage_shortfall_compares_each_carrier_with_its_own_sidebands():
    side = np.array([0, -1, 1, 0, -1, 1])
    levels = np.array([[20.0, 15.0, np.nan, 20.0, 2.0, 1.0],     # 0 and 20 - 2 - 6 = 12
                       [20.0, np.nan, np.nan, 20.0, 0.0, 0.0],   # no sideband read: 14
                       [np.nan, 1.0, 1.0, 20.0, 1.0, 1.0]])      # carrier 1 left out
    on_shaft = np.zeros(levels.shape, bool)
    np.testing.assert_allclose(cage_shortfall_db(levels, side, on_shaft), [6.0, 14.0, 13.0])
    # A carrier on a shaft harmonic (read as background) is not compared,
    on_shaft[0, 3] = True
    assert cage_shortfall_db(levels, side, on_shaft)[0] == 0.0
    # ... nor one whose sidebands are both unreadable (left out, or on a shaft
    # harmonic: the sr5 6205's 2x2xBSF-FTF at 1200 and 1797 rpm). Planted: a sideband
    # on a shaft harmonic read as its 0 dB marked those simulated faults down 2 dB.
    on_shaft[1, 4] = on_shaft[1, 5] = True
    assert cage_shortfall_db(levels, side, on_shaft)[1] == 0.0


@pytest.mark.parametrize("seed", [0, 1])
def test_cage_modulated_ball_comb_is_named_ball(seed):
    why = EnvelopeDiagnoser(bearing="6205", fs=FS, rpm=RPM).explain(
        _ball_impacts(True, seed=seed)[None])[0]
    assert why.label == "ball"
    # Measured 17.3-17.7 dB: clear of the 6 dB threshold by far more than the 3 dB grade
    # margin.
    assert why.evidence_db["ball"] > 12.0


@pytest.mark.parametrize("seed", [0, 1])
def test_a_2xbsf_comb_without_cage_modulation_is_not_a_ball_fault(seed):
    # The same impacts without the load zone: the 2xBSF carriers stand 13-25 dB, their
    # +-FTF sidebands 2-4 dB. Planted bug: the ball scored (C + S) / 2 without the cage
    # requirement (the rule before this test) reads 6.4 dB, over the 6 dB threshold,
    # and names both seeds "ball".
    why = EnvelopeDiagnoser(bearing="6205", fs=FS, rpm=RPM).explain(
        _ball_impacts(False, seed=seed)[None])[0]
    assert why.label != "ball"
    assert why.evidence_db["ball"] < 6.0


@pytest.mark.parametrize("seed", [0, 1])
def test_a_clear_2xbsf_comb_without_cage_modulation_is_graded_not_diagnosable(seed):
    # Where the unmodulated comb stands clear in the band the ball keeps (less noise:
    # carriers 17-25 dB), the verdict says what it cannot tell: grade N and why. Its
    # harmonics feed the inner race's slip search (4-7 dB measured; just over the
    # threshold at the lowest noise), so the label may be inner or healthy, but not
    # ball, and never a clear grade. Planted: without the N rule both seeds read "healthy
    # Y" / "inner Y" and fail. The note is read in
    # the band the ball kept: on a weaker comb (the test above, seed 1) that band may
    # show too little to say so.
    for noise_rms in (0.2, 0.05):
        why = EnvelopeDiagnoser(bearing="6205", fs=FS, rpm=RPM).explain(
            _ball_impacts(False, seed=seed, noise_rms=noise_rms)[None])[0]
        assert why.label in ("healthy", "inner") and why.grade == "N"
        assert any("no cage modulation" in note for note in why.notes)


@pytest.mark.parametrize("seed", range(3))
def test_the_same_2xbsf_comb_swelling_at_the_shaft_rate_is_not_a_ball(seed):
    # One carrier, two modulations: the load zone met once per cage revolution (FTF, a
    # ball) or once per shaft revolution (the pattern of a race turning with the
    # shaft). Only the first is a ball; noise alone is healthy. Measured over 4 seeds:
    # ball Y at 17.3-17.7 dB; the shaft-modulated comb's ball evidence 0.9-2.7 dB (its
    # sidebands sit at +-fr, not +-FTF); noise healthy, 2.8-3.3 dB. Planted: the ball
    # family's sidebands at +-fr instead of +-FTF (FAULT_FAMILIES["ball"] = (...,
    # "shaft", ...)) names the shaft-modulated comb ball and not the cage-modulated one.
    t = np.arange(int(4 * FS)) / FS
    rate = 0.99 * FREQS.ball_defect
    phase = (t * rate) % 1.0 / rate                           # time since the last impact, s
    ring = np.exp(-800.0 * phase) * np.sin(2 * np.pi * 3000.0 * phase)
    noise = np.random.default_rng(seed)

    def swelling(hz):  # the Stribeck load zone (epsilon 0.5) met at ``hz``
        psi = 2 * np.pi * hz * (t - phase)
        x = ring * np.clip(1 - (1 - np.cos(psi)) / (2 * 0.5), 0, None) ** 1.5
        return x / x.std() + 0.5 * noise.standard_normal(t.size)

    X = np.stack([swelling(0.99 * FREQS.ftf), swelling(FREQS.shaft),
                  noise.standard_normal(t.size)])
    cage, shaft, quiet = EnvelopeDiagnoser(bearing="6205", fs=FS, rpm=RPM).explain(X)
    assert cage.label == "ball" and cage.grade == "Y"
    assert shaft.label != "ball" and shaft.evidence_db["ball"] < 6.0  # the threshold
    assert quiet.label == "healthy"


def test_an_inner_race_fault_is_not_called_ball():
    # Impacts at BPFI modulated by the shaft (the load zone seen by a rotating race).
    t = np.arange(int(4 * FS)) / FS
    phase = (t * FREQS.bpfi) % 1.0 / FREQS.bpfi
    x = (1 + np.cos(2 * np.pi * RPM / 60 * t)) * np.exp(-800 * phase) * np.sin(
        2 * np.pi * 3000 * phase)
    x = x / x.std() + 0.5 * np.random.default_rng(3).standard_normal(t.size)
    why = EnvelopeDiagnoser(bearing="6205", fs=FS, rpm=RPM).explain(x[None])[0]
    assert why.label == "inner"


@pytest.mark.parametrize("m", [0.3, 0.8])
def test_enhanced_envelope_spectrum_of_am_noise_matches_the_closed_form(m):
    # x = (1 + m cos 2 pi a t) n(t), n white: S(a, f) / S(0, f) = m / (1 + m^2 / 2) for
    # every f, so |gamma|^2 = (m / (1 + m^2 / 2))^2 (Antoni 2007). a = 141 Hz is 3 window
    # bins (46.875 Hz) plus 0.4 Hz: the window's scalloping there is below 0.01 dB. The
    # estimator's bias is +1/K (K ~ 700 effective frames: 0.0014) and its spread over
    # ~80 carrier bins about 1 / sqrt(80) of the line: 0.5 dB covers both.
    t = np.arange(120_000) / FS
    x = (1 + m * np.cos(2 * np.pi * 141.0 * t)) * np.random.default_rng(0).standard_normal(
        t.size)
    alpha, ees = enhanced_envelope_spectrum(x, FS, (500.0, 5500.0), max_alpha=300.0)
    k = int(np.argmin(np.abs(alpha - 141.0)))
    expected = (m / (1 + m**2 / 2)) ** 2
    assert 10 * np.log10(ees[0, k - 1 : k + 2].max() / expected) == pytest.approx(0.0, abs=0.5)
    # Away from the line, the flat background of stationary noise: about 1 / K, K the
    # effective number of frames (1872 frames of a quarter-window hop, Hann-tapered:
    # about 700); a factor 2 either way.
    assert 1 / 1400 < np.median(ees[0, 300:]) < 1 / 350
    # At alpha = 0 the coherence of a signal with itself: 1, up to the taper's weighting
    # of the frames' power (the record's power varies 0.1 % here; 1 % covers it).
    assert ees[0, 0] == pytest.approx(1.0, rel=0.01)


def test_enhanced_envelope_spectrum_bad_input_names_the_argument():
    x = np.zeros(12_000)
    with pytest.raises(ValueError, match="max_alpha"):
        enhanced_envelope_spectrum(x, FS, (1000.0, 2000.0), max_alpha=2000.0)
    with pytest.raises(ValueError, match="nperseg"):
        enhanced_envelope_spectrum(x, FS, (1000.0, 2000.0), max_alpha=100.0, nperseg=8192)


def test_cyclic_family_evidence_reads_the_cage_modulated_ball():
    # The same lines in the EES: the ball stands out of the band-integrated coherence
    # (measured about 20 dB) and well above the races (below 6 dB measured).
    x = _ball_impacts(True)
    ball = cyclic_family_evidence(x, FS, "6205", RPM, (2000.0, 4000.0))
    inner = cyclic_family_evidence(x, FS, "6205", RPM, (2000.0, 4000.0), fault="inner")
    assert ball > 12.0 and ball - inner > 6.0


def test_a_ball_named_despite_a_partly_unmodulated_harmonic_keeps_its_grade():
    # The sr5 ball fault (6205, 12 kHz, 1200 rpm, 10 dB, seed 0): one harmonic's carrier
    # stands more than 6 dB above its sidebands, the ball still clears its threshold and
    # is named. The unmodulated-comb N rule is about a comb rivalling *another* verdict;
    # planted (the rule applied to the ball's own verdict): graded N, it fails here.
    scene = bp.Scene(bearing="6205", rpm=1200.0, radial_load_n=500.0,
                     fault=bp.Fault("ball", width_mm=0.53, depth_mm=0.28), duration_s=2.0,
                     fs=FS, snr_db=10.0, seed=0, resonance_hz=3000.0)
    x = np.atleast_2d(bp.simulate(scene).accel)[0]
    why = EnvelopeDiagnoser(bearing="6205", fs=FS, rpm=1200.0).explain(x[None])[0]
    assert why.label == "ball" and why.grade != "N"
