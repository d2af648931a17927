"""``info``: what a dataset holds, broken down by condition and by fault size."""

import numpy as np
import pandas as pd

from ballpass.cli import main
from ballpass.datasets import generate, info, twin


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
    assert "float32, m/s^2\n" in printed  # simulated rows: SI units


def test_a_healthy_dataset_has_no_fault_sizes(tmp_path):
    grid = {"dataset": {"duration_s": 0.1, "fs": 12_000, "repeats": 2, "model": "impulse"},
            "grid": {"bearing": ["6205"], "fault": ["healthy"], "rpm": [1797],
                     "resonance_hz": [3000]}}
    generate(grid, tmp_path / "ds", progress=False)
    assert info(tmp_path / "ds")["fault_sizes"] is None


def test_a_twins_signals_are_in_its_recordings_units(tmp_path, capsys):
    """A twin's rows are its machine's recordings, and faults scaled to them: info said
    m/s^2 of them whatever the recordings' unit (the HIT-SM rig's is not stated). Its
    line names the manifest instead; a simulated dataset's stays m/s^2."""
    np.save(tmp_path / "healthy.npy", np.random.default_rng(0).standard_normal(12_000))
    pd.DataFrame({"path": ["healthy.npy"], "fs": [12_000], "rpm": [900],
                  "bearing": ["6205"]}).to_csv(tmp_path / "healthy.csv", index=False)
    grid = twin(tmp_path / "healthy.csv", rpm=[900], out=tmp_path / "twin.toml",
                duration_s=0.25, draws=1)
    generate(grid, tmp_path / "ds", progress=False)
    assert main(["info", str(tmp_path / "ds")]) == 0
    line = next(li for li in capsys.readouterr().out.splitlines() if li.startswith("signals"))
    assert line.endswith(f"float32, in the units of the recordings "
                         f"{tmp_path / 'healthy.csv'} lists"), line
