"""Any recording: ``datasets.load_manifest`` and the plain-file readers behind it.

Fixtures: crops of real CWRU recordings in tests/data (provenance in tests/data/README.md),
written in tmp_path as the plain files a user has (.csv, .npy, .wav, a generic .mat).
"""

import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io
import scipy.io.wavfile

from ballpass.datasets import load_manifest
from ballpass.datasets.manifest import is_manifest, manifest_records
from ballpass.datasets.real import STANDARD_GRAVITY, load_cwru_mat
from ballpass.datasets.recordings import RecordingMismatch, read_recording

DATA = Path(__file__).parent / "data"
CROP = DATA / "cwru_12k_DE_IR021_0_DE_crop.npz"  # 2 s at 12 kHz, inner race, 1797 rpm


@pytest.fixture
def ir021():
    """The inner-race crop, in g, as float32 (as stored in the fixture)."""
    with np.load(CROP) as d:
        return d["accel_g"].astype(np.float32)


@pytest.fixture
def folder(tmp_path, ir021):
    """The crop as a plain CSV (with header), a headerless CSV, .npy, float WAV and a
    generic .mat, plus a real CWRU .mat crop."""
    pd.DataFrame({"accel_g": ir021}).to_csv(tmp_path / "rec.csv", index=False)
    np.savetxt(tmp_path / "bare.csv", ir021, fmt="%.9g")
    np.save(tmp_path / "rec.npy", ir021)
    scipy.io.wavfile.write(tmp_path / "rec.wav", 12_000, ir021)
    scipy.io.savemat(tmp_path / "logger.mat", {"vib": ir021[:, None], "other": np.ones(3)})
    scipy.io.savemat(tmp_path / "one.mat", {"inside2d_1200_1": ir021})
    (tmp_path / "cwru").mkdir()
    (tmp_path / "cwru" / "12k_DE_IR007_0.mat").write_bytes(
        (DATA / "cwru_mat" / "12k_DE_IR007_0.mat").read_bytes())
    return tmp_path


def _manifest(folder: Path, rows: list[dict], name: str = "recordings.csv") -> Path:
    path = folder / name
    table = pd.DataFrame(rows)
    if name.endswith(".parquet"):
        table.to_parquet(path)
    else:
        table.to_csv(path, index=False)
    return path


BASE = {"fs": 12_000, "rpm": 1797, "bearing": "6205", "label": "inner"}


def test_every_format_reads_the_same_samples(folder, ir021):
    """.csv (header or not), .npy, .wav, a generic .mat variable and a .mat file's only
    variable all give back the stored samples, in order, cut into 1 s segments at the
    stated rate. Catches a reader that drops the first row as a header, transposes, or
    rescales a float WAV."""
    rows = [{"path": "rec.csv"}, {"path": "bare.csv"}, {"path": "rec.npy"},
            {"path": "rec.wav"}, {"path": "logger.mat", "variable": "vib"},
            {"path": "one.mat"}]
    X, meta = load_manifest(_manifest(folder, [BASE | r for r in rows]))
    assert X.shape == (12, 12_000)  # 6 recordings x two 1 s segments of 2 s
    for k in range(6):
        # float32 in, float32 out (CSV written with 9 significant digits: exact)
        np.testing.assert_array_equal(X[2 * k], ir021[:12_000])
        np.testing.assert_array_equal(X[2 * k + 1], ir021[12_000:])
    assert meta["group"].tolist() == ["rec", "rec", "bare", "bare", "rec", "rec", "rec", "rec",
                                      "logger", "logger", "one", "one"]
    assert set(meta["label"]) == {"inner"} and set(meta["rpm_source"]) == {"manifest"}
    assert meta["manifest_row"].tolist() == [1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6]
    assert meta["channel"].tolist()[-1] == "inside2d_1200_1"
    assert meta["start_s"].tolist()[:2] == [0.0, 1.0]


def test_a_cwru_file_keeps_its_conversion_and_the_table_wins(folder):
    """A CWRU .mat row is read by the CWRU loader (g -> m/s^2, its DE channel), but the
    table's speed, label and group are the ones kept."""
    X, meta = load_manifest(_manifest(folder, [
        BASE | {"path": "cwru/12k_DE_IR007_0.mat", "rpm": 1790, "label": "outer",
                "group": "rigA", "load": "0 hp"}]), segment_s=0.1)
    rec = load_cwru_mat(folder / "cwru" / "12k_DE_IR007_0.mat")
    n = len(rec.accel) // 1200  # a 0.25 s crop: two 0.1 s segments
    np.testing.assert_allclose(X.ravel(), rec.accel[: n * 1200].astype(np.float32))
    assert np.std(X) > 0.05 * STANDARD_GRAVITY  # m/s^2, not g: the crop's rms is ~0.3 g
    first = meta.iloc[0]
    assert (first["rpm"], first["label"], first["group"], first["load"], first["record"]) == (
        1790.0, "outer", "rigA", "0 hp", 105)


def test_recordings_of_several_rates_are_resampled_to_one(tmp_path):
    """A 1 kHz tone recorded at 48 kHz and at 12 kHz lands at 1 kHz in both rows once
    brought to fs=12000 (catches a resampler that keeps the sample count, shifting every
    line by 4x); without fs the mixed rates are refused."""
    for rate in (12_000, 48_000):
        t = np.arange(2 * rate) / rate
        np.save(tmp_path / f"tone{rate}.npy", np.sin(2 * np.pi * 1000.0 * t))
    path = _manifest(tmp_path, [BASE | {"path": "tone12000.npy"},
                                BASE | {"path": "tone48000.npy", "fs": 48_000}])
    with pytest.raises(ValueError, match=r"sampling rates \[12000.0, 48000.0\] Hz; pass fs"):
        load_manifest(path)
    X, meta = load_manifest(path, fs=12_000)
    assert X.shape == (4, 12_000) and meta["source_fs"].tolist() == [12e3, 12e3, 48e3, 48e3]
    peaks = np.argmax(np.abs(np.fft.rfft(X, axis=1)), axis=1)  # 1 Hz bins over 1 s
    assert peaks.tolist() == [1000] * 4


def test_a_parquet_manifest_with_absolute_paths(folder):
    X, meta = load_manifest(_manifest(folder, [BASE | {"path": str(folder / "rec.npy")}],
                                      "m.parquet"))
    assert X.shape == (2, 12_000) and meta["file"].iloc[0] == str(folder / "rec.npy")


def test_label_is_required_only_where_results_are_scored(folder):
    path = _manifest(folder, [{k: v for k, v in BASE.items() if k != "label"}
                              | {"path": "rec.npy"}])
    _, meta = load_manifest(path)
    assert set(meta["label"]) == {"unknown"}
    with pytest.raises(ValueError, match=r"no column label \(needed: path, fs, rpm, bearing, "
                                         "label"):
        load_manifest(path, require_label=True)


@pytest.mark.parametrize(("change", "message"), [
    ({"bearing": "6299"}, r"recordings.csv row 2 \(rec.npy\): unknown bearing '6299'; the "
                          "catalogue has: 6205"),
    ({"label": "cracked"}, r"row 2 \(rec.npy\): label must be one of healthy, inner, outer, "
                           "ball, got 'cracked'"),
    ({"fs": -5}, r"row 2 \(rec.npy\): fs \(Hz\) must be a finite number > 0, got '-5'"),
    ({"rpm": "fast"}, r"row 2 \(rec.npy\): rpm must be a finite number > 0, got 'fast'"),
    ({"bearing": None}, r"row 2 \(rec.npy\): no bearing given \(bearing: a name `ballpass "
                        r"bearings` lists\)"),
    # an empty cell said "no fs given", not what it needs
    ({"fs": None, "rpm": " "}, r"row 2 \(rec.npy\): no fs, rpm given \(fs: sampling rate, "
                               r"Hz > 0; rpm: shaft speed, rev/min > 0\)"),
])
def test_a_bad_row_is_named_before_any_file_is_read(folder, change, message):
    """Row 1 names a file that does not exist: the table is checked whole before any
    file is read, so the error is row 2's, not a warning about row 1."""
    path = _manifest(folder, [BASE | {"path": "missing.npy"}, BASE | {"path": "rec.npy"} | change])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no "skipped row 1" warning may come first
        with pytest.raises(ValueError, match=message):
            load_manifest(path)


def test_a_missing_required_column_is_named(folder):
    path = _manifest(folder, [{"file": "rec.npy", "fs": 12_000, "rpm": 1797, "bearing": "6205"}])
    with pytest.raises(ValueError, match=r"recordings.csv: the manifest has no column path "
                                         r"\(needed: path, fs, rpm, bearing; it has file, fs"):
        load_manifest(path)


@pytest.mark.parametrize(("row", "message"), [
    ({"path": "logger.mat", "variable": "accel"},
     r"row 1 \(logger.mat\): no variable 'accel'; it holds vib, other"),
    ({"path": "logger.mat"}, r"row 1 \(logger.mat\): .*neither a CWRU recording .* name the "
                             "signal's variable"),
    ({"path": "two.csv"}, r"row 1 \(two.csv\): 2 numeric columns \(t, accel\); name the "
                          "signal's column"),
    ({"path": "two.csv", "column": "acc"}, r"row 1 \(two.csv\): no column 'acc'; its columns: "
                                           "t, accel"),
    ({"path": "rec.wav", "fs": 48_000}, r"row 1 \(rec.wav\): fs 48000 Hz given, but the file "
                                        "states 12000 Hz"),
    ({"path": "stereo.wav"}, r"row 1 \(stereo.wav\): holds 2 channels \(0, 1\); name one"),
    ({"path": "cwru/12k_DE_IR007_0.mat", "channel": "FE"},
     r"row 1 \(cwru/12k_DE_IR007_0.mat\): has no FE channel .* it has \['DE'\]"),
])
def test_a_row_its_file_contradicts_is_an_error(folder, ir021, row, message):
    pd.DataFrame({"t": np.arange(10) / 12e3, "accel": np.ones(10)}).to_csv(
        folder / "two.csv", index=False)
    scipy.io.wavfile.write(folder / "stereo.wav", 12_000, np.stack([ir021, ir021], axis=1))
    with pytest.raises(ValueError, match=message):
        load_manifest(_manifest(folder, [BASE | row]))


def test_a_contradiction_is_found_before_any_recording_is_read(folder, monkeypatch):
    """Every file's header is checked before the first recording is read: row 3's CSV
    of two columns stops the load before rows 1-2 are read (row 1's NaN samples, which
    only a full read sees, would warn first otherwise)."""
    import ballpass.datasets.manifest as manifest

    np.save(folder / "nan.npy", np.full(24_000, np.nan))
    pd.DataFrame({"t": np.arange(10) / 12e3, "accel": np.ones(10)}).to_csv(
        folder / "two.csv", index=False)
    read, original = [], manifest.read_recording
    monkeypatch.setattr(manifest, "read_recording",
                        lambda path, **kw: read.append(path) or original(path, **kw))
    path = _manifest(folder, [BASE | {"path": "nan.npy"}, BASE | {"path": "rec.wav"},
                              BASE | {"path": "two.csv"}])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=r"row 3 \(two.csv\): 2 numeric columns"):
            load_manifest(path)
    assert read == []


def test_the_named_column_or_channel_is_the_one_read(folder, ir021):
    pd.DataFrame({"t": np.arange(ir021.size) / 12e3, "acc": ir021}).to_csv(
        folder / "two.csv", index=False)
    scipy.io.wavfile.write(folder / "stereo.wav", 12_000, np.stack([-ir021, ir021], axis=1))
    X, _ = load_manifest(_manifest(folder, [BASE | {"path": "two.csv", "column": "acc"},
                                            BASE | {"path": "stereo.wav", "channel": 1}]))
    np.testing.assert_array_equal(X[0], ir021[:12_000])
    np.testing.assert_array_equal(X[2], ir021[:12_000])


def test_unreadable_rows_are_skipped_with_a_warning_and_the_rest_go_on(folder):
    (folder / "broken.npy").write_bytes(b"\x93NUMPY garbage")
    np.save(folder / "nan.npy", np.full(24_000, np.nan))
    path = _manifest(folder, [BASE | {"path": "gone.wav"}, BASE | {"path": "broken.npy"},
                              BASE | {"path": "nan.npy"}, BASE | {"path": "rec.npy"}])
    with pytest.warns(UserWarning) as caught:
        X, meta = load_manifest(path)
    said = [str(w.message) for w in caught]
    assert any(s.startswith("skipped recordings.csv row 1 (gone.wav): no such file") for s in said)
    assert any(s.startswith("skipped recordings.csv row 2 (broken.npy): not a readable .npy")
               for s in said)
    assert any(s.startswith("skipped recordings.csv row 3 (nan.npy)") and "NaN" in s
               for s in said)
    assert X.shape == (2, 12_000) and set(meta["manifest_row"]) == {4}
    with pytest.raises(ValueError, match="no recording of the manifest could be read"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            load_manifest(_manifest(folder, [BASE | {"path": "gone.wav"}]))


def test_integer_wav_reads_in_fractions_of_full_scale(tmp_path):
    """16-bit PCM: 16384 is half of full scale (32768); 8-bit is unsigned about 128."""
    scipy.io.wavfile.write(tmp_path / "a.wav", 8000, np.array([16384, -32768, 0] * 10,
                                                              dtype=np.int16))
    scipy.io.wavfile.write(tmp_path / "b.wav", 8000, np.array([192, 0, 128] * 10,
                                                              dtype=np.uint8))
    a, = read_recording(tmp_path / "a.wav")
    b, = read_recording(tmp_path / "b.wav")
    assert a.fs == 8000.0 and a.accel[:3].tolist() == [0.5, -1.0, 0.0]
    assert b.accel[:3].tolist() == [0.5, -1.0, 0.0]


def test_plain_files_need_a_rate_and_mismatches_are_their_own_error(folder):
    with pytest.raises(ValueError, match=r"rec.npy: a .npy file does not state its sampling "
                                         "rate; give fs"):
        read_recording(folder / "rec.npy")
    with pytest.raises(RecordingMismatch):
        read_recording(folder / "rec.wav", fs=11_025)


def test_spreadsheet_csv_files_with_a_byte_order_mark(folder, ir021):
    """Excel writes UTF-8 CSV files with a byte-order mark: the manifest's `path` column
    and a headerless data file's first sample must survive it (a first row mistaken for
    a header would drop a sample)."""
    bare = folder / "excel.csv"
    bare.write_text("\n".join(f"{v:.9g}" for v in ir021), encoding="utf-8-sig")
    path = folder / "excel_manifest.csv"
    pd.DataFrame([BASE | {"path": "excel.csv"}]).to_csv(path, index=False,
                                                        encoding="utf-8-sig")
    assert is_manifest(path)
    X, _ = load_manifest(path)
    np.testing.assert_array_equal(X[0], ir021[:12_000])


@pytest.mark.parametrize("sep", [";", "\t"])
def test_a_spreadsheets_manifest_with_semicolons_and_capitals(folder, ir021, sep):
    """A spreadsheet in a locale with decimal commas saves CSV with semicolons, and people
    write `Path`, `FS`: such a table was read as a signal file ('3 numeric columns (fs,
    rpm, bearing)'). It is the manifest it is, read as the comma one is."""
    path = folder / "semi.csv"
    table = pd.DataFrame([BASE | {"path": "rec.npy"}])
    table.rename(columns=str.capitalize).rename(columns={"Fs": "FS"}).to_csv(
        path, index=False, sep=sep)
    assert path.read_text().startswith(f"FS{sep}Rpm{sep}")
    assert is_manifest(path)
    X, meta = load_manifest(path)
    np.testing.assert_array_equal(X[0], ir021[:12_000])
    assert meta["label"].tolist() == ["inner", "inner"] and set(meta["rpm"]) == {1797}


def test_decimal_commas_are_read_as_decimals_never_as_an_index(folder, ir021):
    """A spreadsheet in a decimal-comma locale writes `-3,63` (one column under a header)
    or `0,01;-3,63` (semicolons between values). The one-column file was read as two
    comma-separated fields under one name: pandas took the integer parts as the row
    index and the signal was the digits after the comma (an outer-race recording written
    with 6 decimals was called healthy, without an error)."""
    text = [f"{v:.9g}".replace(".", ",") for v in ir021]
    (folder / "one.csv").write_text("accel_g\n" + "\n".join(text))
    (folder / "two.csv").write_text("t;accel_g\n" + "\n".join(
        f"{k / 12e3:.9g};{v}".replace(".", ",") for k, v in enumerate(text)))
    one, = read_recording(folder / "one.csv", fs=12_000.0)
    two, = read_recording(folder / "two.csv", fs=12_000.0, column="accel_g")
    for rec in (one, two):  # 9 significant digits of a float32: exact
        np.testing.assert_array_equal(rec.accel.astype(np.float32), ir021)
    # more values than the header names: refused, not shifted into an index
    (folder / "ragged.csv").write_text("a,b\n1,2,3\n4,5,6\n")
    with pytest.raises(RecordingMismatch, match="the header names 2 column.s. but the first "
                                                "row holds 3 value"):
        read_recording(folder / "ragged.csv", fs=12_000.0)


def test_empty_rows_a_spreadsheet_leaves_are_not_recordings(folder, ir021):
    """A spreadsheet's CSV often ends in rows of bare separators (",,,"): they were
    refused as 'row 3: no path, fs, rpm, bearing given'. They are skipped, the rows keep
    their numbers, and a table of nothing else still lists no recording."""
    path = folder / "sheet.csv"
    path.write_text("path,fs,rpm,bearing\n,,,\nrec.npy,12000,1797,6205\n,,,\n")
    X, meta = load_manifest(path)
    np.testing.assert_array_equal(X[0], ir021[:12_000])
    assert set(meta["manifest_row"]) == {2}
    path.write_text("path,fs,rpm,bearing\n,,,\n")
    with pytest.raises(ValueError, match="sheet.csv: the manifest lists no recording"):
        load_manifest(path)


def test_a_manifest_is_told_from_a_signal_table(folder):
    path = _manifest(folder, [BASE | {"path": "rec.npy"}])
    assert is_manifest(path)
    assert not is_manifest(folder / "rec.csv")  # a plain signal column
    assert not is_manifest(folder)
    assert [rec.name for _, rec in manifest_records(path)] == ["rec"]
