"""``ballpass bearings``: catalogue listing and defect frequencies on the command line."""

from __future__ import annotations

import argparse
import csv
import io
import json

import pytest

import ballpass as bp
from ballpass.cli import main
from ballpass.commands import bearings


def _run(argv: list[str]) -> int:
    """Run the subcommand through its own parser (independent of other subcommands)."""
    parser = argparse.ArgumentParser(prog="ballpass")
    sub = parser.add_subparsers(dest="command")
    bearings.add_parser(sub)
    args = parser.parse_args(["bearings", *argv])
    return args.func(args)


def test_cli_csv_bpfo_cwru(capsys):
    # through the real dispatcher, as a user runs it
    assert main(["bearings", "--rpm", "1797", "--bearing", "6205", "--format", "csv"]) == 0
    records = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    assert len(records) == 1 and records[0]["designation"] == "6205"
    row = {k: v for k, v in records[0].items()}
    # CWRU drive end: BPFO = 3.5848 x 1797/60 = 107.36 Hz; the CSV carries full precision,
    # the 4-figure order (+-1.5e-4 relative, see test_bearing) bounds the reference
    assert float(row["bpfo_hz"]) == pytest.approx(3.5848 * 1797 / 60, rel=1.5e-4)
    assert float(row["bpfi_hz"]) == pytest.approx(5.4152 * 1797 / 60, rel=1.5e-4)
    assert float(row["ftf_hz"]) == pytest.approx(0.39828 * 1797 / 60, rel=1.5e-4)
    assert float(row["ball_defect_2xbsf_hz"]) == pytest.approx(2 * float(row["bsf_hz"]), rel=1e-15)
    assert float(row["ball_defect_2xbsf_hz"]) == pytest.approx(4.7135 * 1797 / 60, rel=1.5e-4)


def test_json_matches_library(capsys):
    assert _run(["--rpm", "2100", "--format", "json"]) == 0
    records = json.loads(capsys.readouterr().out)
    assert [r["designation"] for r in records] == bp.Bearing.catalog_names()
    for r in records:
        f = bp.Bearing.catalog(r["designation"]).frequencies(35.0)
        assert r["bpfo_hz"] == f.bpfo and r["bpfi_hz"] == f.bpfi and r["ftf_hz"] == f.ftf
        assert r["bsf_hz"] == f.bsf and r["ball_defect_2xbsf_hz"] == f.ball_defect
        assert r["shaft_hz"] == 35.0


def test_catalogue_table_without_rpm(capsys):
    assert _run([]) == 0
    out = capsys.readouterr().out
    lines = out.splitlines()
    assert lines[0].split()[:3] == ["designation", "element", "Z"]
    assert "BPFO" not in out  # no frequencies without --rpm
    assert len(lines) == 2 + len(bp.Bearing.catalog_names())
    er16k = next(line for line in lines if line.startswith("ER-16K"))
    assert "39.32" in er16k and "Nakhaeinejad & Bryant (2011)" in er16k


def test_table_labels_ball_defect(capsys):
    assert _run(["--rpm", "2100", "--bearing", "er-16k"]) == 0  # case-insensitive name
    out = capsys.readouterr().out
    assert "ball defect (2xBSF)" in out and "BSF (Hz)" in out
    # ER-16K at 35 Hz: seed 000 prints BPFI 189.28 (exact 189.30) -> 2-decimal table value
    assert "189.30" in out.splitlines()[2]


def test_help_has_runnable_example(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["bearings", "--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    example = next(line for line in out.splitlines() if "--format csv" in line).split("#")[0]
    argv = example.split()[1:]  # drop the program name
    assert argv[0] == "bearings"
    capsys.readouterr()
    assert main(argv) == 0
    assert "6205" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--rpm", "-5"], "--rpm"),
        (["--rpm", "nan"], "--rpm"),
        (["--bearing", "6999"], "unknown bearing '6999'"),
    ],
)
def test_bad_input_exit_code(argv, message, capsys):
    assert main(["bearings", *argv]) == 2
    assert message in capsys.readouterr().err
    with pytest.raises(ValueError, match=message):
        _run(argv)
