"""Real CWRU recordings: envelope analysis on the crops in tests/data, and the loaders.

The crops (tests/data/README.md) are 2 s of the drive-end channel, in g. With the band
chosen automatically (kurtogram), the squared envelope spectrum must peak at the fault
frequency of the bearing: BPFO for the outer-race fault, BPFI for the inner-race fault.
"""

from pathlib import Path

import numpy as np
import pytest
import scipy.io
import scipy.signal

import ballpass as bp
from ballpass import features as F
from ballpass.datasets.real import STANDARD_GRAVITY, load_cwru, load_cwru_mat

DATA = Path(__file__).parent / "data"
SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"


def crop(name):
    with np.load(DATA / f"cwru_{name}_DE_crop.npz") as z:
        return z["accel_g"] * STANDARD_GRAVITY, float(z["fs"]), float(z["rpm"])


def strongest_line(freqs, ses, lo=5.0, hi=500.0):
    """Frequency of the largest SES line between lo and hi Hz (fault lines live there)."""
    band = (freqs > lo) & (freqs < hi)
    return freqs[band][np.argmax(ses[band])]


@pytest.mark.parametrize(
    ("name", "line", "expected_hz"),
    [("12k_DE_OR007at6_0", "bpfo", 107.3), ("12k_DE_IR007_0", "bpfi", 162.2)],
)
def test_ses_peaks_at_the_fault_frequency(name, line, expected_hz):
    """±1 Hz: twice the 0.5 Hz resolution of a 2 s crop, and the slip (~0.5 %) of the
    rig keeps the real line within 1 Hz of the kinematic value at these speeds."""
    x, fs, rpm = crop(name)
    kinematic = getattr(bp.Bearing.catalog("6205").frequencies(rpm / 60), line)
    assert kinematic == pytest.approx(expected_hz, abs=0.05)
    freqs, ses = F.envelope_spectrum(x, fs)  # band=None: kurtogram
    assert abs(strongest_line(freqs, ses) - expected_hz) <= 1.0
    band = F.fast_kurtogram(x, fs).best_band
    assert band == (0.0, fs / 2) or band[1] < 5_000.0  # not the dead band above 5.4 kHz


def test_inner_race_sidebands_and_fault_band_features():
    """IR007: BPFI line with shaft sidebands well above the SES background; the OR007
    crop does not show BPFI, and vice versa for BPFO.

    Thresholds: the local SES background of these crops scatters by about +-3 dB from bin
    to bin, so > 10 dB is an unambiguous line and < 6 dB no line (measured: 17.8 / 14.6 dB
    at BPFI / BPFO, 12.6-13.2 dB at the sidebands, 4.8 / 5.1 dB at the absent lines).
    Note that 2 x BPFI (324 Hz) and 3 x BPFO (322 Hz) fall into each other's 1 % windows.
    """
    x_ir, fs, rpm_ir = crop("12k_DE_IR007_0")
    x_or, _, rpm_or = crop("12k_DE_OR007at6_0")
    ir = F.fault_band_features(x_ir, fs, "6205", rpm_ir)
    outer = F.fault_band_features(x_or, fs, "6205", rpm_or)
    assert ir["bpfi_1"] > 10.0 and ir["bpfi_1_lsb"] > 10.0 and ir["bpfi_1_usb"] > 10.0
    assert outer["bpfo_1"] > 10.0 and outer["bpfo_2"] > 10.0
    assert ir["bpfi_1"] > outer["bpfi_1"] + 6.0 and outer["bpfo_1"] > ir["bpfo_1"] + 6.0


def test_faulty_to_healthy_indicator_ratios():
    """Against the healthy baseline (48 kHz, brought to 12 kHz), the faults raise RMS
    several-fold and the kurtosis of the outer-race fault (its impacts are sharp)."""
    healthy, fs_h, _ = crop("Normal_0_48k")
    assert fs_h == 48_000.0  # the classic pitfall: the baseline is not 12 kHz
    healthy = scipy.signal.resample_poly(healthy, 1, 4)
    for name in ("12k_DE_OR007at6_0", "12k_DE_IR007_0"):
        faulty, _, _ = crop(name)
        r = F.indicator_ratios(faulty, healthy)
        assert r["rms"] > 3.0
    assert F.indicator_ratios(crop("12k_DE_OR007at6_0")[0], healthy)["kurtosis"] > 2.0


# ---------------------------------------------------------------- loaders
def write_mat(folder, name, record=130, n=6000, rpm=1796, with_fe=True, value=0.5):
    """A CWRU-like .mat file with the variable names of the real ones, values in g."""
    t = np.arange(n)
    data = {
        f"X{record:03d}_DE_time": (value * np.sin(t / 5.0))[:, None],
        f"X{record:03d}RPM": np.array([[rpm]], dtype=np.uint16),
    }
    if with_fe:
        data[f"X{record:03d}_FE_time"] = np.full((n, 1), 0.1)
    path = folder / f"{name}.mat"
    scipy.io.savemat(path, data)
    return path


def test_load_cwru_mat_converts_g_and_parses_the_name(tmp_path):
    path = write_mat(tmp_path, "12k_DE_OR021@6_2", record=236, rpm=1750)
    rec = load_cwru_mat(path)
    np.testing.assert_allclose(rec.accel, 0.5 * np.sin(np.arange(6000) / 5.0) * 9.80665)
    assert (rec.fs, rec.rpm, rec.label, rec.fault_end, rec.load_hp) == (
        12_000.0,
        1750.0,
        "outer",
        "DE",
        2,
    )
    assert rec.fault_width_mm == pytest.approx(0.5334)  # 0.021 in
    assert rec.fault_angle_deg == 0.0  # 6 o'clock = centre of the load zone
    assert rec.bearing == "6205"
    fe = load_cwru_mat(path, channel="fe")
    # the fan-end channel of a drive-end fault file: the label is about the 6205
    assert fe.bearing == "6205" and fe.accel[0] == pytest.approx(0.1 * 9.80665)


@pytest.mark.parametrize(
    ("name", "record", "rpm", "fs", "label"),
    [
        ("Normal_0_48k", 97, 1796, 48_000.0, "healthy"),
        ("Normal_1", 98, 1772, 48_000.0, "healthy"),
        ("48k_DE_IR007_0", 109, 1797, 48_000.0, "inner"),
        ("12k_FE_B014_3", 289, 1730, 12_000.0, "ball"),
        ("97", 97, 1796, 48_000.0, "healthy"),
    ],
)
def test_sampling_rate_from_the_name(tmp_path, name, record, rpm, fs, label):
    rec = load_cwru_mat(write_mat(tmp_path, name, record=record, rpm=rpm))
    assert (rec.fs, rec.label) == (fs, label)


def test_loader_errors_and_warnings(tmp_path):
    odd = write_mat(tmp_path, "my_recording", record=999)
    with pytest.raises(ValueError, match="cannot infer fs"):
        load_cwru_mat(odd)
    assert load_cwru_mat(odd, fs=12_000.0).label == "unknown"
    with pytest.raises(ValueError, match="no BA channel"):
        load_cwru_mat(odd, channel="BA", fs=12_000.0)
    with pytest.raises(ValueError, match="^channel"):
        load_cwru_mat(odd, channel="XX", fs=12_000.0)
    with pytest.warns(UserWarning, match="says 48000 Hz"):
        load_cwru_mat(write_mat(tmp_path, "Normal_0", record=97), fs=12_000.0)
    with pytest.raises(FileNotFoundError):
        load_cwru_mat(tmp_path / "missing.mat")


def test_load_cwru_resamples_and_segments(tmp_path):
    write_mat(tmp_path, "12k_DE_IR007_0", record=105, n=30_000, rpm=1797)
    write_mat(tmp_path, "Normal_0_48k", record=97, n=100_000, rpm=1796)
    X, meta = load_cwru(tmp_path, fs=12_000, segment_s=0.5)
    # 30 000 samples -> 5 segments of 6000; 100 000 at 48 kHz -> 25 000 -> 4 segments
    assert X.shape == (9, 6000) and X.dtype == np.float32
    assert meta.groupby("group").size().to_dict() == {"12k_DE_IR007_0": 5, "Normal_0_48k": 4}
    healthy = meta[meta.label == "healthy"]
    assert (healthy.source_fs == 48_000.0).all() and (healthy.fs == 12_000.0).all()
    assert meta.start_s.tolist()[:3] == [0.0, 0.5, 1.0]
    # resample_poly keeps a slow sine (0.2 rad/sample at 48 kHz) intact, g -> m/s^2
    x48 = 0.5 * np.sin(np.arange(100_000) / 5.0) * 9.80665
    np.testing.assert_allclose(X[5, 1000:2000], x48[4000:8000:4], atol=0.02)
    with pytest.raises(ValueError, match="^segment_s"):
        load_cwru(tmp_path, segment_s=0)


@pytest.mark.skipif(not SHARED.is_dir(), reason="full CWRU files not present")
def test_full_files_when_available():
    X, meta = load_cwru(SHARED, fs=12_000, segment_s=1.0)
    assert set(meta.label) == {"healthy", "inner", "outer", "ball"}
    ir = meta.index[meta.group == "12k_DE_IR007_0"]
    freqs, ses = F.envelope_spectrum(X[ir], 12_000.0)
    peaks = [strongest_line(freqs, s) for s in ses]
    assert all(abs(p - 162.2) <= 1.0 for p in peaks)
