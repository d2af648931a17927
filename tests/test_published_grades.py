"""Smith & Randall's (2015) grades of the CWRU 12 kHz drive-end records, shipped with the
package, and the benchmark that scores the diagnoser per grade.

Fixture: a 2 s crop of the real record 105 (tests/data, provenance in
tests/data/README.md) written in tmp_path as the data centre serves it (``105.mat``).
"""

from pathlib import Path

import numpy as np
import scipy.io
from _bench import load_benchmark

from ballpass.datasets import smith_randall_grades
from ballpass.datasets._cwru_table import RECORDS

ROOT = Path(__file__).resolve().parent.parent
bench = load_benchmark("smith_randall", "smith_randall_bench")


def test_every_12k_drive_end_fault_record_is_graded_once():
    """The 60 graded records are exactly the 12 kHz drive-end fault records of the CWRU
    numbering (a mistyped record number would leave one out and add a stranger)."""
    grades = smith_randall_grades()
    fault_records = {r for r, t in RECORDS.items()
                     if t.fs == 12_000.0 and t.end == "DE" and t.kind != "healthy"}
    assert grades["record"].is_unique and set(grades["record"]) == fault_records
    assert set(grades["grade"]) <= {"Y1", "Y2", "P1", "P2", "N1", "N2"}


def test_the_totals_the_study_is_quoted_for():
    """44 of 60 clearly diagnosable, 6 partially; 7 of the 16 ball records clearly."""
    grades = smith_randall_grades()
    assert grades.groupby("diagnosable").size().to_dict() == {"N": 10, "P": 6, "Y": 44}
    ball = grades[grades.label == "ball"]
    assert len(ball) == 16 and (ball.diagnosable == "Y").sum() == 7
    assert grades.set_index("record").loc[3001, "rpm_nominal"] == 1797.0


def test_the_benchmark_finds_a_record_by_its_number_and_scores_it(tmp_path):
    """Record 105 under the data centre's name and under a download script's name is one
    record; its inner-race verdict is counted under its published grade (Y)."""
    with np.load(ROOT / "tests" / "data" / "cwru_12k_DE_IR007_0_DE_crop.npz") as d:
        x_g, rpm = d["accel_g"].astype(np.float64), float(d["rpm"])
    for name in ("105.mat", "12k_DE_IR007_0.mat"):
        scipy.io.savemat(tmp_path / name, {"X105_DE_time": x_g[:, None], "X105RPM": rpm})
    grades = smith_randall_grades()
    found = bench.find_records([tmp_path], grades)
    assert list(found) == [105]
    table = bench.diagnose(found, grades)
    assert table[["record", "grade", "verdict", "named"]].values.tolist() == [
        [105, "Y2", "inner", True]]
    counts = bench.summary(table, grades).set_index(["published", "fault"])
    assert counts.loc[("Y", "inner"), ["graded", "found", "named"]].tolist() == [12, 1, 1]
    assert counts.loc[("Y", "all"), ["graded", "found", "named"]].tolist() == [44, 1, 1]
    text = bench.report(table, bench.summary(table, grades), 2, 1.0)
    assert "named: 1 of the 1 found (44 graded" in text


def test_the_benchmark_fetches_what_it_scores(tmp_path, monkeypatch):
    """--fetch asks the data centre for exactly the 60 graded records, then scores what
    came (here a stand-in download of record 105), writing the table and the figure."""
    with np.load(ROOT / "tests" / "data" / "cwru_12k_DE_IR007_0_DE_crop.npz") as d:
        scipy.io.savemat(tmp_path / "105.mat", {"X105_DE_time": d["accel_g"][:, None],
                                                "X105RPM": float(d["rpm"])})
    asked = []
    monkeypatch.setattr(bench, "fetch_cwru",
                        lambda records: asked.extend(records) or [tmp_path / "105.mat"])
    bench.main(["--fetch", "--out", str(tmp_path / "out")])
    assert sorted(asked) == sorted(smith_randall_grades()["record"])
    assert (tmp_path / "out" / "results" / "smith_randall.png").stat().st_size > 0
    assert "named: 1 of the 1 found" in (tmp_path / "out" / "smith_randall.md").read_text()
