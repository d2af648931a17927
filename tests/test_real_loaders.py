"""Loaders for the files users have: every CWRU naming, the MFPT set, broken files.

Fixtures: tests/data/cwru_mat and tests/data/mfpt_mat (crops of real files and two
synthetic ones, provenance in tests/data/README.md).
"""

import math
import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
import scipy.io
import scipy.signal

import ballpass as bp
from ballpass.cli import main
from ballpass.datasets import load_cwru, load_mfpt
from ballpass.datasets._cwru_table import NOMINAL_RPM, RECORDS
from ballpass.datasets.real import STANDARD_GRAVITY, load_cwru_mat, load_real

DATA = Path(__file__).parent / "data"
CWRU = DATA / "cwru_mat"
MFPT = DATA / "mfpt_mat"


@pytest.mark.parametrize(
    ("name", "fs", "label", "rpm", "rpm_source", "load_hp", "clock"),
    [
        # real crops: fs and label from the name, rpm stored in the file
        ("12k_DE_IR007_0", 12_000.0, "inner", 1797.0, "file", 0, None),
        ("12k_DE_OR007@6_0", 12_000.0, "outer", 1796.0, "file", 0, 6),
        ("12k_FE_OR007@12_0", 12_000.0, "outer", 1797.0, "file", 0, 12),
        ("12k_FE_OR014@3_0", 12_000.0, "outer", 1774.0, "file", 1, 3),  # misnamed, below
        # named by record number only: everything from the official table
        ("105", 12_000.0, "inner", 1797.0, "file", 0, None),
        ("97", 48_000.0, "healthy", 1796.0, "file", 0, None),
        # normal baseline under download-script names: 48 kHz although unsaid
        ("Normal_0", 48_000.0, "healthy", 1796.0, "file", 0, None),
        ("Normal_Normal_0", 48_000.0, "healthy", 1796.0, "file", 0, None),
        # synthetic: a 48 kHz fault file, and a 0.028 in file without RPM at 2 hp
        ("48k_DE_B007_1", 48_000.0, "ball", 1772.0, "file", 1, None),
        ("12k_DE_IR028_2", 12_000.0, "inner", 1750.0, "nominal", 2, None),
    ],
)
def test_every_naming_loads(name, fs, label, rpm, rpm_source, load_hp, clock):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # 12k_FE_OR014@3_0 warns; tested below
        rec = load_cwru_mat(CWRU / f"{name}.mat")
    assert (rec.fs, rec.label, rec.rpm, rec.rpm_source, rec.load_hp, rec.fault_clock) == (
        fs, label, rpm, rpm_source, load_hp, clock)
    assert rec.rpm_nominal == NOMINAL_RPM[load_hp]


def test_a_renamed_file_reads_like_the_original():
    """105.mat and 12k_DE_IR007_0.mat are the same crop: same samples, label, size."""
    a, b = load_cwru_mat(CWRU / "105.mat"), load_cwru_mat(CWRU / "12k_DE_IR007_0.mat")
    np.testing.assert_array_equal(a.accel, b.accel)
    assert a.fault_width_mm == b.fault_width_mm == pytest.approx(0.007 * 25.4)
    assert a.record == b.record == 105


def test_values_are_converted_from_g():
    raw = scipy.io.loadmat(CWRU / "12k_DE_IR007_0.mat")["X105_DE_time"].ravel()
    np.testing.assert_allclose(load_cwru_mat(CWRU / "12k_DE_IR007_0.mat").accel,
                               raw * 9.80665)


def test_a_misnamed_load_is_resolved_by_record_number_and_stored_speed():
    """12k_FE_OR014@3_0 stores 1774 rpm, 1.3 % below the 1797 rpm of 0 hp. Its variables
    are record 309, which the CWRU table lists as the 1 hp test (nominal 1772 rpm), and
    the shaft-harmonic comb of the full file peaks at 1773.6 rpm: the name's "_0" is
    wrong, not the speed. Two sources against the name: 1 hp, no speed flag."""
    with pytest.warns(UserWarning, match=r"record 309, the 1 hp record, and its stored "
                                         r"1774 rpm fits 1 hp"):
        rec = load_cwru_mat(CWRU / "12k_FE_OR014@3_0.mat")
    assert (rec.load_hp, rec.rpm, rec.rpm_nominal, rec.rpm_mismatch) == (1, 1774.0, 1772.0,
                                                                          False)


def test_a_stored_speed_off_the_motor_load_is_kept_and_flagged(tmp_path):
    """Record 105 is 0 hp like its name; a stored 1750 rpm (2.6 % off 1797) is kept,
    flagged, and the nominal speed recorded for downstream checks."""
    x = scipy.io.loadmat(CWRU / "105.mat")["X105_DE_time"]
    scipy.io.savemat(tmp_path / "12k_DE_IR007_0.mat",
                     {"X105_DE_time": x, "X105RPM": np.array([[1750]], dtype=np.uint16)})
    with pytest.warns(UserWarning, match="1750 rpm differs from the nominal 1797 rpm"):
        rec = load_cwru_mat(tmp_path / "12k_DE_IR007_0.mat")
    assert (rec.rpm, rec.rpm_source, rec.rpm_nominal, rec.rpm_mismatch, rec.load_hp) == (
        1750.0, "file", 1797.0, True, 0)
    assert not load_cwru_mat(CWRU / "12k_DE_IR007_0.mat").rpm_mismatch
    # 1 % is the line (17.97 rpm): 1780 rpm (0.95 % off) passes, 1778 (1.06 %) is flagged
    for rpm, flagged in ((1780, False), (1778, True)):
        scipy.io.savemat(tmp_path / "12k_DE_IR007_0.mat",
                         {"X105_DE_time": x, "X105RPM": np.array([[rpm]], dtype=np.uint16)})
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert load_cwru_mat(tmp_path / "12k_DE_IR007_0.mat").rpm_mismatch is flagged


def test_the_table_matches_the_shipped_files():
    """Every record number inside the real crops agrees with the table on what the file
    name says (the one exception, 309, is the flagged load above)."""
    expect = {105: ("inner", "DE", 0), 130: ("outer", "DE", 0), 302: ("outer", "FE", 0),
              97: ("healthy", None, 0), 309: ("outer", "FE", 1)}
    for number, (kind, end, load) in expect.items():
        test = RECORDS[number]
        assert (test.kind, test.end, test.load_hp) == (kind, end, load)
    # every test appears once per load it was recorded at, and numbers are unique
    assert len(RECORDS) == len(set(RECORDS))
    assert RECORDS[3001].size_in == 0.028 and RECORDS[97].fs == 48_000.0


def test_missing_speed_is_filled_from_the_motor_load(tmp_path):
    """A file without RPM variable gets the nominal speed of each motor load."""
    x = scipy.io.loadmat(CWRU / "12k_DE_IR028_2.mat")["X3003_DE_time"]
    for load, rpm in NOMINAL_RPM.items():
        for name in (f"12k_DE_IR028_{load}", f"{3001 + load}", f"{3005 + load}"):
            # by name, and by number alone (3001-3004 inner race, 3005-3008 ball)
            path = tmp_path / f"{name}.mat"
            scipy.io.savemat(path, {f"X{int(name) if name.isdigit() else 3001 + load}_DE_time": x})
            rec = load_cwru_mat(path)
            assert (rec.rpm, rec.rpm_source, rec.load_hp) == (rpm, "nominal", load)
            assert rec.fault_width_mm == pytest.approx(0.028 * 25.4)


def test_folder_load_skips_broken_files_with_a_warning(tmp_path):
    for path in CWRU.glob("*.mat"):
        shutil.copy(path, tmp_path)
    good = (tmp_path / "12k_DE_IR007_0.mat").read_bytes()
    (tmp_path / "12k_DE_B007_0.mat").write_bytes(good[: len(good) // 3])  # truncated
    (tmp_path / "notes.mat").write_text("not a MATLAB file")
    (tmp_path / "my_recording.mat").write_bytes(b"")
    scipy.io.savemat(tmp_path / "unknown_rate.mat", {"X999_DE_time": np.ones((500, 1))})
    with pytest.warns(UserWarning) as caught:
        X, meta = load_cwru(tmp_path, fs=12_000, segment_s=0.1)
    skipped = [str(w.message) for w in caught if str(w.message).startswith("skipped")]
    assert len(skipped) == 4
    for name in ("12k_DE_B007_0.mat", "notes.mat", "my_recording.mat", "unknown_rate.mat"):
        line = next(m for m in skipped if name in m)
        assert "\n" not in line and "[" not in line.replace("['", "")  # no array printed
    assert "cannot infer fs" in next(m for m in skipped if "unknown_rate" in m)
    assert set(meta.group) == {p.stem for p in CWRU.glob("*.mat")}
    assert X.dtype == np.float32 and X.shape == (len(meta), 1200)
    # 48 kHz files were brought to 12 kHz; every row carries a speed and its source
    assert (meta.fs == 12_000.0).all() and set(meta.source_fs) == {12_000.0, 48_000.0}
    assert meta.rpm.gt(0).all()
    assert set(meta.rpm_source) == {"file", "nominal"}
    assert {"file", "label", "group", "segment", "load_hp", "bearing", "channel",
            "fault_width_mm", "fault_angle_deg"} <= set(meta.columns)
    # with source_fs, the file of unknown rate loads too
    with pytest.warns(UserWarning):
        _, meta2 = load_cwru(tmp_path / "unknown_rate.mat", source_fs=12_000, segment_s=0.01)
    assert (meta2.label == "unknown").all() and math.isnan(meta2.rpm.iloc[0])


def test_nothing_readable_is_one_clear_error(tmp_path):
    (tmp_path / "a.mat").write_text("x")
    with pytest.warns(UserWarning, match="skipped a.mat"), \
            pytest.raises(ValueError, match="no recording could be loaded"):
        load_cwru(tmp_path)
    with pytest.raises(ValueError, match="^segment_s"):
        load_cwru(CWRU, segment_s=1e-9)


def test_load_cwru_resamples_the_48k_files_exactly():
    """Normal_0 (48 kHz) at fs=12 kHz is resample_poly(x, 1, 4) of the file."""
    _, meta = load_cwru(CWRU / "Normal_0.mat", fs=12_000, segment_s=0.1)
    X, _ = load_cwru(CWRU / "Normal_0.mat", fs=12_000, segment_s=0.1)
    raw = scipy.io.loadmat(CWRU / "Normal_0.mat")["X097_DE_time"].ravel() * STANDARD_GRAVITY
    np.testing.assert_allclose(X[0], scipy.signal.resample_poly(raw, 1, 4)[:1200], rtol=1e-6)
    assert meta.source_fs.iloc[0] == 48_000.0


# ---------------------------------------------------------------- MFPT
def test_mfpt_files_load_with_their_own_rate_speed_and_load():
    X, meta = load_mfpt(MFPT, segment_s=0.1)
    first = meta.groupby("group").first()
    assert first.loc["InnerRaceFault_vload_1", ["label", "load_lbs"]].tolist() == ["inner", 0.0]
    assert first.loc["OuterRaceFault_vload_1", ["label", "load_lbs"]].tolist() == ["outer", 25.0]
    assert (meta.fs == 48_828.0).all() and (meta.rpm == 1500.0).all()
    assert (meta.rpm_source == "file").all() and (meta.bearing == "MFPT-NICE").all()
    assert X.shape == (len(meta), 4883) and len(meta) == 8  # 0.5 s crops, 0.1 s segments
    raw = scipy.io.loadmat(MFPT / "InnerRaceFault_vload_1.mat")["bearing"][0, 0]["gs"]
    np.testing.assert_allclose(X[0], (raw.ravel()[:4883] * 9.80665).astype(np.float32))


def test_mfpt_mixed_rates_need_fs(tmp_path):
    """A baseline at 97 656 Hz next to a 48 828 Hz file: refused without fs, halved with."""
    d = scipy.io.loadmat(MFPT / "OuterRaceFault_vload_1.mat")
    b = d["bearing"][0, 0]
    gs = scipy.signal.resample_poly(b["gs"].ravel(), 2, 1)[:, None]
    baseline = {"gs": gs, "sr": np.array([[97656]]), "rate": b["rate"], "load": 270.0}
    scipy.io.savemat(tmp_path / "baseline_1.mat", {"bearing": baseline})
    shutil.copy(MFPT / "InnerRaceFault_vload_1.mat", tmp_path)
    with pytest.raises(ValueError, match=r"sampling rates \[48828.0, 97656.0\] Hz; pass fs"):
        load_mfpt(tmp_path)
    X, meta = load_mfpt(tmp_path, fs=48_828, segment_s=0.1)
    healthy = meta[meta.label == "healthy"]
    assert set(healthy.group) == {"baseline_1"} and len(healthy) == 4  # 0.5 s -> 4 x 0.1 s
    assert (healthy.source_fs == 97_656.0).all() and (healthy.load_lbs == 270.0).all()
    assert (meta.fs == 48_828.0).all()


def test_mfpt_bearing_geometry_against_the_stored_frequencies():
    """The stored BPFO 81.125 and BPFI 118.875 Hz (25 Hz shaft) are met by the geometry
    to 0.01 %; the stored FTF 14.8375 Hz is not: BPFO = Z x FTF gives 10.14 Hz, and the
    textbook FTF = fr/2 (1 - d/D) computed here independently gives the same."""
    stored = {k: v.item() for k, v in scipy.io.loadmat(MFPT / "InnerRaceFault_vload_1.mat",
                                                      variable_names=["BPFO", "BPFI", "FTF",
                                                                      "BSF"]).items()
              if not k.startswith("__")}
    f = bp.Bearing.catalog("MFPT-NICE").frequencies(25.0)
    assert f.bpfo == pytest.approx(stored["BPFO"], rel=1e-4)
    assert f.bpfi == pytest.approx(stored["BPFI"], rel=1e-4)
    ratio = 0.235 / 1.245
    assert f.ftf == pytest.approx(0.5 * 25.0 * (1 - ratio), rel=1e-12)
    assert f.ftf == pytest.approx(stored["BPFO"] / 8, rel=1e-4)
    assert abs(f.ftf - stored["FTF"]) > 4.0  # the stored FTF is wrong
    # BSF = D/(2d) (1 - (d/D)^2) fr: 63.86 Hz (the files say 63.91, within 0.1 %)
    assert f.bsf == pytest.approx(stored["BSF"], rel=1e-3)


def test_load_real_tells_mfpt_from_cwru(tmp_path):
    shutil.copy(MFPT / "OuterRaceFault_vload_1.mat", tmp_path)
    shutil.copy(CWRU / "97.mat", tmp_path)
    X, meta = load_real(tmp_path, fs=12_000, segment_s=0.1)
    assert set(meta.dataset) == {"cwru", "mfpt"}
    assert set(meta.bearing) == {"6205", "MFPT-NICE"}


# ---------------------------------------------------------------- the CLI
@pytest.mark.filterwarnings("ignore:12k_FE_OR014")
def test_features_cli_reads_folders_of_both_sets(tmp_path, capsys):
    out = tmp_path / "f.csv"
    assert main(["features", str(CWRU), str(MFPT), "--segment", "0.1", "--out", str(out)]) == 0
    import pandas as pd

    table = pd.read_csv(out)
    assert set(table.label) == {"healthy", "inner", "outer", "ball"}
    assert set(table.rpm_source) == {"file", "nominal"}
    assert set(table.fs) == {12_000.0, 48_000.0, 48_828.0}  # each file at its own rate
    assert table.bpfo_1.notna().all()  # every row has a bearing and a speed


@pytest.mark.parametrize(("bearing", "fs", "real"),
                         [("MFPT-NICE", 48_828, MFPT), ("6205", 12_000, CWRU)])
@pytest.mark.filterwarnings("ignore:12k_FE_OR014")
def test_benchmark_real_accepts_both_sets(tmp_path, capsys, bearing, fs, real):
    """A small simulated dataset benchmarked against the MFPT crops (48 828 Hz) and the
    CWRU crops (12 and 48 kHz files, brought to the dataset's 12 kHz)."""
    # 0.25 s: the envelope diagnoser refuses records shorter than two cage periods
    # (0.197 s for the MFPT bearing at 1500 rpm)
    grid = {"dataset": {"duration_s": 0.25, "fs": fs, "repeats": 1, "seed": 1},
            "grid": {"bearing": [bearing], "fault": ["healthy", "outer", "inner"],
                     "fault_width_mm": [0.5], "rpm": [1500], "radial_load_n": [300],
                     "resonance_hz": [4000], "sensor": ["loaded"]}}
    bp.datasets.generate(grid, tmp_path / "ds", n_jobs=1, progress=False)
    code = main(["benchmark", str(tmp_path / "ds"), "--real", str(real), "--out",
                 str(tmp_path / "rep"), "--splits", "sim2real", "--models", "envelope"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "sim2real" in captured.out
    if real == CWRU:  # the fan-end fault files are about the 6203: left out, and said
        assert "left out 2 real recording(s) about another bearing (6203" in captured.err


def test_benchmark_refuses_real_recordings_of_another_bearing_only(tmp_path, capsys):
    grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "repeats": 1, "seed": 1},
            "grid": {"bearing": ["6205"], "fault": ["healthy", "outer"],
                     "fault_width_mm": [0.5], "rpm": [1797], "radial_load_n": [300],
                     "resonance_hz": [4000], "sensor": ["loaded"]}}
    bp.datasets.generate(grid, tmp_path / "ds", n_jobs=1, progress=False)
    (tmp_path / "fe").mkdir()
    shutil.copy(CWRU / "12k_FE_OR007@12_0.mat", tmp_path / "fe")
    code = main(["benchmark", str(tmp_path / "ds"), "--real", str(tmp_path / "fe"), "--out",
                 str(tmp_path / "rep"), "--splits", "sim2real", "--models", "envelope"])
    assert code != 0
    assert "none of the recordings is about the simulated bearing 6205" in \
        capsys.readouterr().err


@pytest.mark.filterwarnings("ignore:12k_FE_OR014")
def test_a_fault_file_is_about_its_faulty_bearing_at_either_sensor():
    """The label of a fan-end fault file is about the fan-end 6203 even at the drive-end
    accelerometer: a diagnosis there must look for the 6203's lines (the loader gave the
    6205, the bearing at that sensor, and benchmarks scored fan-end faults against the
    drive-end bearing's kinematics). Healthy records keep the bearing at the sensor."""
    for channel in ("DE", "FE"):
        rec = load_cwru_mat(CWRU / "12k_FE_OR007@12_0.mat", channel=channel)
        assert (rec.label, rec.fault_end, rec.bearing) == ("outer", "FE", "6203")
    # (these crops carry the drive-end channel only)
    assert load_cwru_mat(CWRU / "12k_DE_IR007_0.mat").bearing == "6205"
    assert load_cwru_mat(CWRU / "Normal_0.mat").bearing == "6205"


def test_resampling_between_unrelated_rates_keeps_frequencies_exact():
    """48 828 Hz -> 12 000 Hz is exactly 1000/4069. A ratio rounded to a small
    denominator (29/118) puts a 1 kHz tone 8.5 ppm off, a phase drift of 0.53 rad over
    10 s; the exact ratio must keep the drift below 0.05 rad (< 1 ppm)."""
    from ballpass.datasets.real import segment_records

    class Tone:
        fs, name = 48_828.0, "tone"
        accel = np.sin(2 * np.pi * 1000.0 * np.arange(48_828 * 11) / 48_828.0)

        def columns(self):
            return {}

    X, meta = segment_records([(Path("tone.mat"), Tone())], 12_000.0, 120_000)
    t = np.arange(120_000) / 12_000.0
    phase = np.unwrap(np.angle(scipy.signal.hilbert(X[0].astype(float))))
    drift = (phase - 2 * np.pi * 1000.0 * t)[5000:-5000]
    assert np.ptp(drift) < 0.05


SHARED_CWRU = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"


def _unlisted(tmp_path, x_g: np.ndarray, channel: str = "DE") -> Path:
    """``x_g`` saved as a renamed file of an unlisted record: no RPM, no load, no name."""
    path = tmp_path / "recording.mat"
    scipy.io.savemat(path, {f"X999_{channel}_time": x_g[:, None]})
    return path


@pytest.mark.parametrize("rpm", [1725.0, 1762.0, 1799.0])  # the rig's 3 hp .. 0 hp range
def test_a_speed_nothing_states_is_estimated_from_the_shaft_comb(tmp_path, rpm):
    fs, fr = 12_000.0, rpm / 60.0
    t = np.arange(int(3 * fs)) / fs
    rng = np.random.default_rng(0)
    # shaft harmonics 1x..8x decaying, phases random, in noise: a motor's signature
    x = sum(np.cos(2 * np.pi * k * fr * t + rng.uniform(0, 2 * np.pi)) / k for k in range(1, 9))
    x = 0.01 * (x + rng.standard_normal(t.size))
    with pytest.warns(UserWarning, match="estimated .* rpm from the signal's shaft-harmonic"):
        rec = load_cwru_mat(_unlisted(tmp_path, x), fs=fs)
    assert rec.rpm_source == "estimated"
    # 3 s padded to a quarter bin: the search steps 1/12 Hz at the 10th harmonic, i.e.
    # 0.5 rpm of shaft speed; 1 rpm allows a step either side. A search that stays near
    # one nominal speed (e.g. +-1 % around 1797) misses 1725 rpm by tens of rpm.
    assert rec.rpm == pytest.approx(rpm, abs=1.0)


def test_no_clear_comb_or_too_short_leaves_the_speed_unknown(tmp_path):
    rng = np.random.default_rng(1)
    with pytest.warns(UserWarning, match=r"comb stands only .* dB"):
        noise = load_cwru_mat(_unlisted(tmp_path, rng.standard_normal(36_000)), fs=12_000.0)
    assert noise.rpm_source == "unknown" and math.isnan(noise.rpm)
    with pytest.warns(UserWarning, match="shorter than the 2 s"):
        short = load_cwru_mat(_unlisted(tmp_path, rng.standard_normal(12_000)), fs=12_000.0)
    assert short.rpm_source == "unknown" and math.isnan(short.rpm)


@pytest.mark.skipif(not SHARED_CWRU.is_dir(), reason="needs ../shared/data/cwru")
@pytest.mark.parametrize(("name", "channel"), [("12k_DE_B021_0", "DE"),
                                               ("12k_FE_OR014@3_0", "FE"),
                                               ("Normal_0_48k", "FE")])
def test_real_records_stripped_of_their_speed_get_it_back(tmp_path, name, channel):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = load_cwru_mat(SHARED_CWRU / f"{name}.mat", channel=channel)
    with pytest.warns(UserWarning, match="estimated"):
        rec = load_cwru_mat(_unlisted(tmp_path, ref.accel / STANDARD_GRAVITY, channel),
                            channel=channel, fs=ref.fs)
    # the stored speed is the rig's tachometer reading, in whole rpm; the comb of a 10 s
    # record resolves 0.1 Hz bins (6 rpm / 10 harmonics): 0.1 % = 1.8 rpm covers both
    assert rec.rpm_source == "estimated"
    assert rec.rpm == pytest.approx(ref.rpm, rel=1e-3)
