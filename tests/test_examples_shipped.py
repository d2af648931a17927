"""Example grids and recordings ship with the package: found by name from any folder,
listed by ``ballpass examples``, included in the wheel, and the gallery reads nothing
from ``tests/``."""

import fnmatch
import re
import tomllib
from importlib import resources
from pathlib import Path

import pytest

import ballpass as bp
from ballpass.cli import main

ROOT = Path(__file__).resolve().parent.parent
SHIPPED = resources.files("ballpass") / "examples"


def test_the_four_grids_are_found_by_name():
    assert list(bp.datasets.example_grids()) == ["cwru_like_6205_12k", "quick", "sim2real_cwru",
                                                 "speed_sweep_6004"]
    path = bp.datasets.example_grid("quick")
    assert path.is_file() and path == bp.datasets.example_grid("quick.toml")
    with pytest.raises(ValueError, match=r"no example grid 'quik'; the shipped ones are "
                                         r"cwru_like_6205_12k, quick, sim2real_cwru"):
        bp.datasets.example_grid("quik")


@pytest.mark.parametrize("name", sorted(bp.datasets.example_grids()))
def test_each_grid_holds_the_runs_its_comment_counts(name):
    """Every shipped grid reads, and the run count its header comment states is the one
    read_grid expands (a comment left stale by an edited axis fails here)."""
    text = bp.datasets.example_grid(name).read_text()
    stated = [int(n) for n in re.findall(r"= (\d+) runs", text.split("[dataset]")[0])]
    assert stated, f"{name}: the header comment states no run count"
    assert bp.datasets.read_grid(bp.datasets.example_grid(name)).n_runs == stated[-1]
    assert "seed 00" not in text and "examples/" not in text  # user-facing text


def test_ballpass_examples_lists_each_grid_on_one_line(capsys):
    assert main(["examples"]) == 0
    lines = capsys.readouterr().out.splitlines()
    for name in bp.datasets.example_grids():
        mine = [line for line in lines if line.startswith(f"{name} ")]
        assert len(mine) == 1 and " rows  " in mine[0]
    assert main(["examples", "quick"]) == 0
    assert capsys.readouterr().out == bp.datasets.example_grid("quick").read_text()


def test_generate_takes_a_bare_name_from_another_folder(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)  # no examples/ folder here
    assert main(["generate", "quick", "--out", "ds", "--dry-run"]) == 0
    assert "rows      8 (8 runs" in capsys.readouterr().out
    assert main(["generate", "quik", "--out", "ds"]) == 2
    assert ("GRID 'quik' is neither a file nor a grid shipped with ballpass"
            in capsys.readouterr().err)
    assert not (tmp_path / "ds").exists()


def test_every_shipped_file_is_in_the_wheel():
    """setuptools puts in the wheel the package data that pyproject's globs name: every
    file under ballpass/examples must match one (a new data folder without a glob would
    be missing after `pip install .`)."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())
    globs = config["tool"]["setuptools"]["package-data"]["ballpass"]
    package = ROOT / "ballpass"
    files = [p.relative_to(package).as_posix()
             for p in (package / "examples").rglob("*") if p.is_file()]
    assert any(f.endswith(".toml") for f in files) and any(f.endswith(".npz") for f in files)
    missing = [f for f in files if not any(fnmatch.fnmatch(f, g) for g in globs)]
    assert not missing


def test_the_gallery_reads_no_test_data():
    for script in (ROOT / "examples" / "gallery").glob("*.py"):
        text = script.read_text()
        assert '"tests"' not in text and "tests/" not in text, script.name
