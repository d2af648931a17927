"""plot_explanation draws what the diagnoser read: its band, its lines where it found them."""

import numpy as np
import pytest

import ballpass as bp
from ballpass.diagnose import EnvelopeDiagnoser, plot_explanation

FS = 12_000.0
RPM = 1797.0


def outer_race_fault(seconds=2.0, noise=0.2):
    """Impacts at BPFO ringing 3 kHz in white noise, m/s^2."""
    bpfo = bp.Bearing.catalog("6205").frequencies(RPM / 60).bpfo
    t = np.arange(round(seconds * FS)) / FS
    phase = (t * bpfo) % 1.0 / bpfo
    x = np.exp(-800 * phase) * np.sin(2 * np.pi * 3000 * phase)
    return x + noise * np.random.default_rng(0).standard_normal(t.size)


def _solid_lines(ax):
    """x of the solid vertical lines (carriers), Hz."""
    return sorted(line.get_xdata()[0] for line in ax.lines[1:] if line.get_linestyle() == "-")


def test_marks_the_carriers_where_the_diagnoser_found_them():
    # Catches a plot that marks the kinematic frequencies instead of the lines read
    # (the diagnoser's slip search moves them), or another family's lines.
    x = outer_race_fault()
    why = EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(x[None])[0]
    ax = plot_explanation(x, FS, why)
    carriers = why.lines[(why.lines.fault == "outer") & (why.lines.role == "carrier")]
    counted = carriers[np.isfinite(carriers.level_db)]
    expected = sorted(counted.found_hz.tolist() + carriers[~np.isfinite(
        carriers.level_db)].nominal_hz.tolist())
    assert _solid_lines(ax) == pytest.approx(expected)
    lo, hi = why.band_hz["outer"]
    assert f"band {lo:g}-{hi:g} Hz" in ax.get_title()
    assert ax.get_title().startswith("outer (grade Y)")
    # the SES drawn is the one of that band, to rounding (another band's differs)
    f_ref, ses_ref = bp.features.envelope_spectrum(x, FS, (lo, hi))
    f, ses = ax.lines[0].get_xdata(), ax.lines[0].get_ydata()
    np.testing.assert_allclose(ses, np.interp(f, f_ref, ses_ref), rtol=1e-12)


def test_healthy_shows_the_family_closest_to_its_threshold():
    x = np.random.default_rng(2).standard_normal(24_000)
    why = EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(x[None])[0]
    assert why.label == "healthy"
    closest = max(why.evidence_db, key=lambda f: why.evidence_db[f] - why.threshold_db[f])
    ax = plot_explanation(x, FS, why)
    assert f"\n{closest}: evidence" in ax.get_title()
    ax = plot_explanation(x, FS, why, family="ball")
    assert "\nball: evidence" in ax.get_title()


def test_bad_input_is_refused():
    x = outer_race_fault(1.0)
    why = EnvelopeDiagnoser(fs=FS, rpm=RPM).explain(x[None])[0]
    with pytest.raises(ValueError, match="family must be one of"):
        plot_explanation(x, FS, why, family="cage")
    with pytest.raises(ValueError, match="x must be one signal"):
        plot_explanation(x[None], FS, why)
    with pytest.raises(TypeError, match="explanation must be an Explanation"):
        plot_explanation(x, FS, {"label": "outer"})
