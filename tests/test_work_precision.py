"""Work-precision measurement: the table, the speed-up at equal error, the plot, the CLI."""

import numpy as np
import pandas as pd
import pytest

import ballpass as bp
from ballpass.cli import main
from ballpass.simulate import plot_work_precision, speedup, work_precision

FAST = dict(bearing="6205", rpm=1797.0, fs=12_000.0, resonance_hz=3000.0, duration_s=0.05)


@pytest.fixture(scope="module")
def table():
    scene = bp.Scene(fault=bp.Fault("outer"), **FAST)
    return work_precision(scene, rk4_dt=[5e-6, 2e-5, 4e-5], dopri5_rtol=[1e-4, 1e-7],
                          scipy_methods=["RK45", "LSODA"], scipy_rtol=[1e-4, 1e-7],
                          repeats=1)


def test_table_rows_columns_and_errors(table):
    assert list(table["method"]) == (["ballpass rk4"] * 3 + ["ballpass dopri5"] * 2
                                     + ["scipy RK45"] * 2 + ["scipy LSODA"] * 2)
    assert set(table["family"]) == {"ballpass", "scipy"}
    assert (table["status"] == "ok").all()
    for col in ("wall_s", "wall_per_sim_s", "n_steps", "n_rhs", "error_l2", "error_ses"):
        assert (table[col] > 0).all(), col
    np.testing.assert_allclose(table["wall_per_sim_s"], table["wall_s"] / FAST["duration_s"])
    # the rk4 steps land on the output grid (h_out = 1/48 kHz = 20.8 us): 4.2, 10.4 and
    # 20.8 us; smaller steps, smaller errors, for every solver
    rk4 = table[table["method"] == "ballpass rk4"]
    np.testing.assert_allclose(rk4["dt_s"], [1 / 48_000 / 5, 1 / 48_000 / 2, 1 / 48_000])
    for _, group in table.groupby("method"):
        assert group["error_l2"].is_monotonic_increasing or \
            group["error_l2"].is_monotonic_decreasing
        ordered = group.sort_values("error_l2")
        assert ordered["error_l2"].iloc[0] < ordered["error_l2"].iloc[-1] / 10
    # tight settings reproduce the reference: errors far below the loosest ones
    assert table["error_l2"].min() < 1e-5
    assert table.attrs["reference"] == "ballpass dopri5 rtol=1e-10"
    assert table.attrs["lines"] == ["bpfo_1", "bpfo_2", "bpfo_3"]


def test_speedup_at_equal_error(table):
    ratios = speedup(table, at=(1e-4,))
    assert set(ratios.index) == {"ballpass rk4", "ballpass dopri5"}
    assert ratios.columns.tolist() == [1e-4]
    # both are far faster than scipy at 1e-4 on this scene (a bound loose enough for
    # any machine load and for this 0.05 s run's fixed costs: the benchmark's 1 s
    # runs measure ~100x)
    assert (ratios[1e-4] > 5.0).all()
    # an error no curve reaches gives NaN, not an extrapolation
    assert speedup(table, at=(1e-14,)).isna().all().all()


def test_plot_is_log_log_with_one_curve_per_method(table):
    import matplotlib

    matplotlib.use("Agg")
    ax = plot_work_precision(table, title="outer")
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert len(ax.get_lines()) == table["method"].nunique()


def test_scipy_time_limit_stops_the_sweep():
    scene = bp.Scene(**FAST)
    t = work_precision(scene, rk4_dt=[2e-5], dopri5_rtol=[], scipy_methods=["Radau"],
                       scipy_rtol=[1e-4, 1e-6], scipy_time_limit=1e-9, repeats=1)
    scipy_rows = t[t["family"] == "scipy"]
    assert list(scipy_rows["status"]) == ["time limit"]  # the tighter rtol is skipped
    assert scipy_rows["error_l2"].isna().all()


def test_bad_arguments_name_the_argument():
    scene = bp.Scene(**FAST)
    with pytest.raises(ValueError, match="scipy_methods"):
        work_precision(scene, scipy_methods=["Euler"])
    with pytest.raises(ValueError, match="repeats"):
        work_precision(scene, repeats=0)
    with pytest.raises(TypeError, match="scene"):
        work_precision("6205")


def test_cli_prints_the_table_and_writes_plot_and_csv(tmp_path, capsys):
    png, csv = tmp_path / "wp.png", tmp_path / "wp.csv"
    code = main(["work-precision", "--fault", "inner", "--duration", "0.02", "--fs", "12000",
                 "--resonance", "3000", "--scipy", "RK45", "--repeats", "1",
                 "--plot", str(png), "--csv", str(csv)])
    assert code == 0
    out = capsys.readouterr().out
    assert "ballpass rk4" in out and "scipy RK45" in out and "speed-up" in out
    assert png.stat().st_size > 10_000
    written = pd.read_csv(csv)
    assert {"ballpass rk4", "ballpass dopri5", "scipy RK45"} <= set(written["method"])


def test_cli_help_has_a_runnable_example(capsys):
    with pytest.raises(SystemExit):
        main(["work-precision", "--help"])
    assert "ballpass work-precision --fault outer --duration" in capsys.readouterr().out
