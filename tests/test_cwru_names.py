"""Every CWRU fault record's names parse to what the data centre's table says; every
MFPT file name to its label.

The label, fault size, outer-race clock position, motor load, rate and faulty end of a
CWRU file come from its name when its record number is unknown (a renamed copy, a
record outside the official numbering). Each of the 157 fault records of the table
(:mod:`ballpass.datasets._cwru_table`) is written as a tiny file under each usual
naming, once with an unlisted record number (the name alone must tell) and once with
its own (name and table must agree, without a warning).
"""

import math
import warnings

import numpy as np
import pytest
import scipy.io

from ballpass.datasets._cwru_table import RECORDS
from ballpass.datasets.mfpt import load_mfpt_mat
from ballpass.datasets.real import _CLOCK_DEG, load_cwru_mat

FAULTS = sorted((number, test) for number, test in RECORDS.items() if test.kind != "healthy")
_CODE = {"inner": "IR", "outer": "OR", "ball": "B"}
_LONG_END = {"DE": "Drive_End", "FE": "Fan_End"}
_SIGNAL = np.random.default_rng(0).standard_normal((500, 1))  # g; no RPM variable


def _fault_code(test):
    """``OR007@12_3``: kind, size in mils, clock position (outer race), load in hp."""
    clock = f"@{test.clock}" if test.clock is not None else ""
    return f"{_CODE[test.kind]}{round(test.size_in * 1000):03d}{clock}_{test.load_hp}"


def _names(test):
    """The names download scripts give a fault file, the end said or not."""
    rate, code = f"{round(test.fs / 1000)}k", _fault_code(test)
    return {f"{rate}_{test.end}_{code}": True, f"{rate}_{_LONG_END[test.end]}_{code}": True,
            code: False}


def _write(folder, name, number):
    path = folder / f"{name}.mat"
    scipy.io.savemat(path, {f"X{number}_DE_time": _SIGNAL})
    return path


def test_the_table_has_157_fault_records_of_every_kind_and_clock():
    assert len(FAULTS) == 157
    clocks = {t.clock for _, t in FAULTS if t.kind == "outer"}
    assert clocks == {3, 6, 12} and {t.kind for _, t in FAULTS} == {"inner", "outer", "ball"}


def test_every_fault_record_name_parses_to_the_table(tmp_path):
    """Under an unlisted record number (X999) every naming of every record gives the
    table's kind, size, clock (an outer race at 12 o'clock is 180 deg from the load
    zone, ``@12`` is two digits), load, and, where the name says them, rate and end.
    The bare name (``OR007@12_0``) says neither: fs is passed and the bearing is the
    accelerometer's, with a warning."""
    assert 999 not in RECORDS
    for _number, test in FAULTS:
        for name, says_end in _names(test).items():
            path = _write(tmp_path, name, 999)
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                rec = load_cwru_mat(path, fs=None if says_end else test.fs)
            got = (rec.label, rec.fault_width_mm / 25.4, rec.fault_clock, rec.load_hp, rec.fs)
            assert got == (test.kind, pytest.approx(test.size_in), test.clock, test.load_hp,
                           test.fs), name
            assert rec.rpm_source == "nominal" and rec.record == 999
            assert rec.columns()["fault_size_in"] == pytest.approx(test.size_in)
            if test.kind == "outer":
                assert rec.fault_angle_deg == _CLOCK_DEG[test.clock], name
            else:
                assert math.isnan(rec.fault_angle_deg), name
            if says_end:
                assert rec.fault_end == test.end and not caught, (name, caught)
                assert rec.bearing == {"DE": "6205", "FE": "6203"}[test.end]
            else:
                assert rec.fault_end is None and rec.bearing == "6205", name
                assert any("which bearing" in str(w.message) for w in caught), name


def test_every_normal_baseline_name_parses_to_healthy_48k_at_its_load(tmp_path):
    """The normal baseline (records 97-100, 0-3 hp) is sampled at 48 kHz, which its
    download names do not say (``Normal_0``, ``Normal_Normal_0``, ``Normal_0_48k``)."""
    for load in range(4):
        for name in (f"Normal_{load}", f"Normal_Normal_{load}", f"Normal_{load}_48k"):
            rec = load_cwru_mat(_write(tmp_path, name, 999))
            assert (rec.label, rec.fs, rec.load_hp, rec.fault_end, rec.bearing) == (
                "healthy", 48_000.0, load, None, "6205"), name
            assert math.isnan(rec.fault_width_mm) and rec.fault_clock is None


def test_every_fault_record_under_its_own_number_agrees_with_its_name(tmp_path):
    """With the record's own number the name and the table agree: no warning, the same
    label; a name contradicting the table on the kind keeps the name's (and warns)."""
    for number, test in FAULTS:
        name = next(iter(_names(test)))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            rec = load_cwru_mat(_write(tmp_path, name, number))
        assert (rec.label, rec.fault_clock, rec.load_hp, rec.fs, rec.fault_end) == (
            test.kind, test.clock, test.load_hp, test.fs, test.end), name
    with pytest.warns(UserWarning, match="lists as"):
        rec = load_cwru_mat(_write(tmp_path, "12k_DE_OR007@12_0", 105))  # 105: inner race
    assert (rec.label, rec.fault_clock) == ("outer", 12)


#: The 20 files of the MFPT set (Bechhoefer 2013) and their labels.
MFPT_NAMES = {**{f"baseline_{i}": "healthy" for i in range(1, 4)},
              **{f"OuterRaceFault_{i}": "outer" for i in range(1, 4)},
              **{f"OuterRaceFault_vload_{i}": "outer" for i in range(1, 8)},
              **{f"InnerRaceFault_vload_{i}": "inner" for i in range(1, 8)}}


def test_every_mfpt_file_name_gives_its_label(tmp_path):
    """Renamed case (``outerracefault_3``) included; the label comes from the name. The
    units: shaft rate 25 Hz is 1500 rpm, 270 lbs of load is 270 x 0.45359237 kg x
    9.80665 m/s^2 (the definition of the pound-force) = 1201.0 N."""
    bearing = {"gs": _SIGNAL, "sr": np.array([[48828.0]]), "rate": np.array([[25.0]]),
               "load": np.array([[270.0]])}
    assert len(MFPT_NAMES) == 20
    for name, label in {**MFPT_NAMES, "outerracefault_3": "outer"}.items():
        scipy.io.savemat(tmp_path / f"{name}.mat", {"bearing": bearing})
        rec = load_mfpt_mat(tmp_path / f"{name}.mat")
        assert rec.label == label, name
    assert (rec.rpm, rec.fs, rec.load_lbs) == (1500.0, 48828.0, 270.0)
    assert rec.columns()["radial_load_n"] == pytest.approx(270.0 * 0.45359237 * 9.80665,
                                                           rel=1e-12)
