"""A simulated healthy machine with its own periodic lines stays healthy at the stated
false-alarm probability; the same machine with a faint localized fault is named.

The machine (``benchmarks/diagnose_healthy_machines.py``): white noise, shaft harmonics
1-10x in the raw signal, a healthy bearing's varying-compliance lines at 1-3x BPFO
(30 dB above the noise), and a structural resonance whose response the shaft modulates
with its first five harmonics (a rub or a bent shaft): the squared envelope of the
resonance band carries a shaft comb; and a tone in the anti-aliasing roll-off modulated
at BPFO (bands there carry no evidence). On a 6203 every fault family falls within 2 % of a
shaft harmonic (BPFO 3.05, 2xBSF 3.99, BPFI 4.95 orders), the case where the machine's
own lines sit where a fault's should.
"""

from __future__ import annotations

import numpy as np
import pytest
from _bench import load_benchmark
from scipy.signal import butter, sosfiltfilt

import ballpass as bp
from ballpass.diagnose import EnvelopeDiagnoser

machines = load_benchmark("diagnose_healthy_machines")


def shaft_modulated_machine(fs, seconds, rpm, bearing, rng):
    """The benchmark's varying-compliance machine, its resonance band modulated by the
    shaft's first five harmonics (depth 30 %, 1 / k)."""
    x = machines.machine("varying compliance", fs, seconds, rpm, rng)
    n = x.size
    t = np.arange(n) / fs
    fr = rpm / 60.0
    sos = butter(2, (3000.0, 3600.0), "bandpass", fs=fs, output="sos")
    band = sosfiltfilt(sos, rng.standard_normal(n))
    gain = 1.0 + sum(0.3 / k * np.cos(2 * np.pi * k * fr * t) for k in range(1, 6))
    # A tone in the anti-aliasing roll-off (0.46 fs), modulated at BPFO by 50 %.
    bpfo = bp.Bearing.catalog(bearing).frequencies(fr).bpfo
    alias = 3.0 * (1.0 + 0.5 * np.cos(2 * np.pi * bpfo * t)) * np.cos(2 * np.pi * 0.46 * fs * t)
    return x + 3.0 * gain * band / band.std() + alias


def outer_fault(fs, seconds, rpm, bearing, depth):
    """Impacts at BPFO (0.8 % slip) ringing 3.3 kHz, ``depth`` times unit amplitude."""
    bpfo = 0.992 * bp.Bearing.catalog(bearing).frequencies(rpm / 60).bpfo
    t = np.arange(round(fs * seconds)) / fs
    phase = (t * bpfo) % 1.0 / bpfo
    return depth * np.exp(-900 * phase) * np.sin(2 * np.pi * 3300 * phase)


CASES = [(12_000.0, 2.0, 1797.0, "6203"), (51_200.0, 1.0, 600.0, "6205"),
         (48_000.0, 5.0, 1200.0, "6205")]


@pytest.mark.parametrize(("fs", "seconds", "rpm", "bearing"), CASES)
def test_healthy_machine_stays_healthy_and_a_faint_fault_is_named(fs, seconds, rpm, bearing):
    # Healthy: no family reaches its threshold, and the stated false-alarm probability
    # is at most the default 1e-3 (the thresholds are raised to it where the search is
    # wide). A faint outer-race fault (impacts 8x the noise's standard deviation at
    # their peak, under the machine's own lines) in the same machine: named outer.
    # Planted: bands allowed up to fs / 2 (ALIAS_FREE_FRACTION 0.5) call the healthy
    # machines outer (the roll-off tone's BPFO modulation); fails.
    rng = np.random.default_rng(int(fs + rpm + seconds))
    healthy = shaft_modulated_machine(fs, seconds, rpm, bearing, rng)
    faulty = healthy + outer_fault(fs, seconds, rpm, bearing, 8.0)
    diag = EnvelopeDiagnoser(bearing, fs=fs, rpm=rpm, speed_tolerance=0.0)
    well, bad = diag.explain(np.stack([healthy, faulty]))
    assert well.label == "healthy", str(well)
    assert well.false_alarm_probability <= 1e-3
    assert bad.label == "outer", str(bad)


def test_supply_lines_set_aside_where_the_supply_frequency_is_stated():
    # The benchmark's electrical machine (supply harmonics 1-6x 50 Hz, the resonance
    # modulated at 100 Hz by 30 %) at 1116 rpm: BPFI (5.415 orders, 100.7 Hz) is 0.7 %
    # from 100 Hz, inside the slip search, and the 100 Hz comb reads as an inner-race
    # fault (6.2-7.1 dB on four seeds). With line_hz=50 the supply's harmonics read as
    # background, as the shaft's do, and the machine is healthy; an outer-race fault
    # on the same machine (BPFO 66.7 Hz, off every supply harmonic) is still named.
    # Planted: the supply notch not applied (line_hz ignored) leaves it inner; fails.
    fs, seconds, rpm = 48_000.0, 5.0, 1116.0
    x = machines.machine("electrical", fs, seconds, rpm, np.random.default_rng(1))
    X = np.stack([x, x + outer_fault(fs, seconds, rpm, "6205", 8.0)])
    unknown = EnvelopeDiagnoser("6205", fs=fs, rpm=rpm).predict(X[:1])
    assert unknown[0] == "inner"  # the collision the supply frequency resolves
    well, bad = EnvelopeDiagnoser("6205", fs=fs, rpm=rpm, line_hz=50.0).explain(X)
    assert well.label == "healthy", str(well)
    assert bad.label == "outer", str(bad)
    with pytest.raises(ValueError, match="line_hz must be"):
        EnvelopeDiagnoser("6205", fs=fs, rpm=rpm, line_hz=-50.0).predict(X[:1])


def test_baseline_sets_the_supply_lines_aside_where_the_supply_frequency_is_stated():
    # --baseline with --line-hz: the electrical machine's 100 Hz comb sits 0.7 % from
    # BPFI at 1116 rpm (above), so a baseline fitted on it without the supply frequency
    # raises the inner-race threshold to where its comb reads (7.3 dB on 5 s, measured
    # 7.2-8.1 dB on three seeds); told the supply frequency, the fit sets the comb aside
    # as the diagnosis does and the thresholds stay at the 6 dB floor. Planted: the
    # CLI's BaselineThresholds dropping line_hz (as it did) gives 7.3 dB; fails.
    from types import SimpleNamespace

    from ballpass.commands.diagnose import BaselineThresholds

    fs, rpm = 48_000.0, 1116.0
    x = machines.machine("electrical", fs, 5.0, rpm, np.random.default_rng(3))
    record = SimpleNamespace(x=x, fs=fs, rpm=rpm, bearing="6205", name="electrical")
    blind = BaselineThresholds([record])(record)
    told = BaselineThresholds([record], line_hz=50.0)(record)
    assert blind["inner"] > 6.5, blind  # the comb raises the fit where it is not told
    assert told == {"outer": 6.0, "inner": 6.0, "ball": 6.0}, told
