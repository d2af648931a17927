"""``info``: what a dataset holds, broken down by condition and by fault size."""

import pandas as pd

from ballpass.cli import main
from ballpass.datasets import generate, info


def test_faulty_rows_by_fault_size(tmp_path, capsys):
    grid = {"dataset": {"duration_s": 0.1, "fs": 12_000, "repeats": 2, "model": "impulse"},
            "grid": {"bearing": ["6205"], "fault": ["healthy", "outer", "inner"],
                     "fault_width_mm": [0.18, 0.53], "rpm": [1797], "resonance_hz": [3000]}}
    out = tmp_path / "ds"
    generate(grid, out, progress=False)
    sizes = info(out)["fault_sizes"]
    # healthy rows do not multiply over sizes and are not counted here; each faulty
    # class has its 2 repeats at each of the 2 widths
    assert isinstance(sizes, pd.DataFrame)
    assert sizes.index.get_level_values("fault_width_mm").tolist() == [0.18, 0.53]
    assert sizes.to_dict("list") == {"inner": [2, 2], "outer": [2, 2]}
    assert main(["info", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "faulty rows per fault size (mm) and label" in printed and "0.53" in printed


def test_a_healthy_dataset_has_no_fault_sizes(tmp_path):
    grid = {"dataset": {"duration_s": 0.1, "fs": 12_000, "repeats": 2, "model": "impulse"},
            "grid": {"bearing": ["6205"], "fault": ["healthy"], "rpm": [1797],
                     "resonance_hz": [3000]}}
    generate(grid, tmp_path / "ds", progress=False)
    assert info(tmp_path / "ds")["fault_sizes"] is None
