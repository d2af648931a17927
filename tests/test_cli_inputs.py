"""Any recording through the command line: plain .csv/.npy/.wav/.mat files with --fs,
and manifests wherever a folder of CWRU/MFPT files is accepted.

Fixtures: 2 s crops of real CWRU drive-end recordings (tests/data, provenance in
tests/data/README.md), written in tmp_path in the formats a user has.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io
import scipy.io.wavfile

import ballpass as bp
from ballpass.cli import main

DATA = Path(__file__).parent / "data"
PLAIN = ["--fs", "12000", "--rpm", "1797", "--bearing", "6205", "--quiet"]


def _crop(name: str) -> np.ndarray:
    with np.load(DATA / f"cwru_12k_DE_{name}_DE_crop.npz") as d:
        return d["accel_g"].astype(np.float32)


@pytest.fixture
def recordings(tmp_path):
    """The inner-race (0.021 in) crop as .csv/.npy/.wav/.mat, the outer-race one as .npy,
    and a manifest of both with their labels."""
    inner, outer = _crop("IR021_0"), _crop("OR021at6_0")
    pd.DataFrame({"time_s": np.arange(inner.size) / 12e3, "de_g": inner}).to_csv(
        tmp_path / "inner.csv", index=False)
    np.save(tmp_path / "inner.npy", inner)
    scipy.io.wavfile.write(tmp_path / "inner.wav", 12_000, inner)
    scipy.io.savemat(tmp_path / "inner.mat", {"acc": inner})
    np.save(tmp_path / "outer.npy", outer)
    pd.DataFrame({"path": ["inner.npy", "outer.npy"], "fs": 12_000, "rpm": 1797,
                  "bearing": "6205", "label": ["inner", "outer"], "group": ["ir", "or"]}
                 ).to_csv(tmp_path / "recordings.csv", index=False)
    return tmp_path


@pytest.mark.parametrize("extra", [["inner.csv", "--column", "de_g"], ["inner.npy"],
                                   ["inner.wav"], ["inner.mat", "--variable", "acc"],
                                   ["inner.mat"]],
                         ids=["csv", "npy", "wav", "mat", "mat-one-variable"])
def test_diagnose_a_plain_recording(recordings, capsys, monkeypatch, extra):
    """A real inner-race recording in each plain format: the same verdict and evidence
    (the diagnoser sees the same samples whatever the container)."""
    monkeypatch.chdir(recordings)
    fs = [] if extra[0].endswith(".wav") else PLAIN[:2]  # the WAV states its rate
    assert main(["diagnose", *extra, *fs, *PLAIN[2:], "--out", "v.csv"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("inner: inner (grade Y) at 1797 rpm")
    row = pd.read_csv(recordings / "v.csv").iloc[0]
    assert row["prediction"] == "inner" and row["inner_db"] > row["inner_threshold_db"]


def test_plain_recordings_say_what_they_lack(recordings, capsys, monkeypatch):
    monkeypatch.chdir(recordings)
    scipy.io.savemat("two.mat", {"acc": np.zeros(10), "tacho": np.ones(10)})
    cases = [
        (["inner.npy", "--rpm", "1797", "--bearing", "6205"],
         "inner.npy: a .npy file does not state its sampling rate; give fs > 0 Hz "
         "(--fs / fs)"),
        (["inner.wav", "--fs", "48000", "--rpm", "1797", "--bearing", "6205"],
         "inner.wav: fs 48000 Hz given, but the file states 12000 Hz"),
        (["inner.csv", *PLAIN[:2]],
         "inner.csv: 2 numeric columns (time_s, de_g); name the signal's column (--column"),
        (["two.mat", *PLAIN], "two.mat is neither a CWRU recording (variables "),
        (["inner.mat", "--variable", "x", *PLAIN], "inner.mat: no variable 'x'; it holds acc"),
        (["inner.npy", "--fs", "12000"], "inner: the input does not give the bearing "
                                         "(--bearing) or shaft speed (--rpm)"),
    ]
    for argv, message in cases:
        assert main(["diagnose", *argv]) == 2, argv
        err = capsys.readouterr().err
        assert message in err and err.count("\n") == 1, err


def test_diagnose_and_features_read_a_manifest(recordings, capsys):
    """The manifest's rows are diagnosed with their labels, and the tables keep their
    group and label columns and name each row's recording file (not the manifest)."""
    manifest = str(recordings / "recordings.csv")
    assert main(["diagnose", manifest, "--quiet", "--out", str(recordings / "v.csv")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("inner (label: inner): inner (grade Y)")
    assert any(line.startswith("outer (label: outer): outer (grade Y)") for line in lines)
    assert pd.read_csv(recordings / "v.csv")["file"].tolist() == ["inner.npy", "outer.npy"]
    assert main(["features", manifest, "--quiet", "--out", str(recordings / "f.csv")]) == 0
    table = pd.read_csv(recordings / "f.csv")
    assert table[["source", "label", "group", "file"]].values.tolist() == [
        ["inner", "inner", "ir", "inner.npy"], ["outer", "outer", "or", "outer.npy"]]
    # two rigs' files of one name stay two: the path as the manifest gives it
    (recordings / "rig2").mkdir()
    (recordings / "rig2" / "inner.npy").write_bytes((recordings / "inner.npy").read_bytes())
    pd.DataFrame({"path": ["inner.npy", "rig2/inner.npy"], "fs": 12_000, "rpm": 1797,
                  "bearing": "6205"}).to_csv(recordings / "rigs.csv", index=False)
    assert main(["features", str(recordings / "rigs.csv"), "--quiet", "--out",
                 str(recordings / "g.csv")]) == 0
    assert pd.read_csv(recordings / "g.csv")["file"].tolist() == ["inner.npy",
                                                                  "rig2/inner.npy"]
    assert (table["bpfi_1"] > table["bpfo_1"]).tolist() == [True, False]


def test_a_folder_of_logger_mat_files_reads_as_its_files_do(recordings, capsys):
    """A folder of .mat files that are not CWRU/MFPT (one variable each, as the HIT-SM
    rig's): with --fs, every file is diagnosed as it is alone; without, one line says
    what is missing. The folder skipped every such file as 'neither CWRU nor MFPT'."""
    folder = recordings / "logger"
    folder.mkdir()
    scipy.io.savemat(folder / "a.mat", {"acc": _crop("IR021_0")})
    scipy.io.savemat(folder / "b.mat", {"vib": _crop("OR021at6_0")})
    assert main(["diagnose", str(folder), *PLAIN]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("a: inner (grade Y)")
    assert any(line.startswith("b: outer (grade Y)") for line in lines)
    with pytest.warns(UserWarning, match="skipped a.mat: a generic .mat variable does not "
                                         r"state its sampling rate; give fs > 0 Hz \(--fs"):
        assert main(["diagnose", str(folder), *PLAIN[2:]]) == 2
    assert "none of its .mat files could be read" in capsys.readouterr().err


def test_a_manifest_ignores_options_it_states_per_row(recordings, capsys):
    with pytest.warns(UserWarning, match=r"recordings.csv is a manifest, which states --fs per "
                                         "row: ignored for it"):
        assert main(["features", str(recordings / "recordings.csv"), "--fs", "1000",
                     "--quiet"]) == 0
    table = pd.read_csv(__import__("io").StringIO(capsys.readouterr().out))
    assert set(table["fs"]) == {12_000.0}


def test_benchmark_real_takes_a_manifest_and_needs_its_labels(recordings, tmp_path, capsys):
    """sim2real on a manifest of labelled recordings: its segments are scored against
    the table's labels; a table without labels is refused before any work."""
    grid = {"dataset": {"duration_s": 0.25, "fs": 12_000, "repeats": 1, "seed": 1,
                        "model": "impulse"},
            "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"],
                     "fault_width_mm": [0.5], "rpm": [1797], "radial_load_n": [300],
                     "resonance_hz": [3000], "sensor": ["loaded"]}}
    bp.datasets.generate(grid, tmp_path / "ds", n_jobs=1, progress=False)
    argv = ["benchmark", str(tmp_path / "ds"), "--out", str(tmp_path / "rep"), "--splits",
            "sim2real", "--models", "envelope", "--quiet", "--real"]
    assert main([*argv, str(recordings / "recordings.csv")]) == 0, capsys.readouterr().err
    predictions = pd.read_csv(tmp_path / "rep" / "predictions.csv")
    assert len(predictions) == 16  # two 2 s recordings in 0.25 s segments
    assert sorted(predictions["group"].unique()) == ["ir", "or"]
    assert set(zip(predictions["group"], predictions["y_true"], strict=True)) == {
        ("ir", "inner"), ("or", "outer")}
    pd.read_csv(recordings / "recordings.csv").drop(columns="label").to_csv(
        recordings / "unlabelled.csv", index=False)
    assert main([*argv, str(recordings / "unlabelled.csv")]) == 2
    assert "unlabelled.csv: the manifest has no column label" in capsys.readouterr().err


def test_benchmark_of_a_twin_leaves_out_the_recordings_it_was_built_from(recordings,
                                                                          tmp_path, capsys):
    """A twin's healthy rows are its recordings' segments: given to --real as well (as a
    user following docs/twin.md does with a labelled table of the machine), its healthy
    recording was scored on the data it was trained on. Left out, saying so; only it is
    an error. Planted: no check, the healthy recording is among the predictions."""
    np.save(recordings / "healthy.npy", np.random.default_rng(0).standard_normal(24_000))
    pd.DataFrame({"path": ["healthy.npy"], "fs": 12_000, "rpm": 1797, "bearing": "6205"}
                 ).to_csv(recordings / "healthy.csv", index=False)
    table = pd.read_csv(recordings / "recordings.csv")
    pd.concat([table, pd.DataFrame({"path": ["healthy.npy"], "fs": 12_000, "rpm": 1797,
                                    "bearing": "6205", "label": "healthy",
                                    "group": "machine"})]
              ).to_csv(recordings / "labelled.csv", index=False)
    grid = bp.datasets.twin(recordings / "healthy.csv", rpm=[1797], duration_s=0.25,
                            draws=2, out=tmp_path / "twin.toml")
    bp.datasets.generate(grid, tmp_path / "ds", progress=False)
    argv = ["benchmark", str(tmp_path / "ds"), "--splits", "sim2real", "--models",
            "envelope", "--quiet", "--out", str(tmp_path / "rep"), "--real"]
    assert main([*argv, str(recordings / "labelled.csv")]) == 0
    assert ("left out 1 real recording(s) the twin was built from (machine)"
            in capsys.readouterr().err)
    groups = set(pd.read_csv(tmp_path / "rep" / "predictions.csv")["group"])
    assert groups == {"ir", "or"}
    pd.DataFrame({"path": ["healthy.npy"], "fs": 12_000, "rpm": 1797, "bearing": "6205",
                  "label": "healthy"}).to_csv(recordings / "own.csv", index=False)
    assert main([*argv, str(recordings / "own.csv")]) == 2
    assert "--real: every recording is one the twin was built from" in capsys.readouterr().err
