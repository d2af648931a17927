"""Published reference results on real recordings, shipped with the package.

smith_randall_grades   the diagnosability grade (Y/P/N) of each CWRU 12 kHz drive-end
                       fault record in Smith & Randall's benchmark study (2015)

References
----------
.. [1] W. A. Smith, R. B. Randall, "Rolling element bearing diagnostics using the Case
   Western Reserve University data: A benchmark study", Mechanical Systems and Signal
   Processing 64-65 (2015) 100-131, Appendix B.
"""

from __future__ import annotations

from importlib import resources

__all__ = ["smith_randall_grades"]

_GRADES = "smith_randall_2015_de12k.csv"


def smith_randall_grades():
    """Smith & Randall's (2015) grade of each CWRU 12 kHz drive-end fault record.

    Smith and Randall applied three established envelope methods to every CWRU record
    and graded each by how diagnosable it proved: ``Y`` clearly, ``P`` partially,
    ``N`` not diagnosable (the digit is the study's sub-category as transcribed).
    Of the 60 12 kHz drive-end fault records, 44 are graded ``Y``, 6 ``P`` and 10
    ``N``; of the 16 ball-fault records, 7 are ``Y``. A diagnoser is judged first on the
    ``Y`` records; a verdict on an ``N`` record is no evidence either way.

    The grades are a transcription (source and checks in
    ``ballpass/datasets/data/README.md``); what a record is (fault, size, position,
    load) comes from the CWRU numbering (:mod:`ballpass.datasets._cwru_table`).

    Returns
    -------
    pandas.DataFrame
        One row per record, sorted by record number: ``record`` (int, as in ``105.mat``),
        ``grade`` (``"Y1"``, ``"Y2"``, ``"P1"``, ``"P2"``, ``"N1"``), ``diagnosable``
        (``"Y"``, ``"P"``, ``"N"``), ``label`` (``"inner"``, ``"outer"``, ``"ball"``),
        ``fault_size_in``, ``fault_clock`` (outer race: 3, 6 or 12 o'clock; else None),
        ``load_hp`` and ``rpm_nominal``.

    Examples
    --------
    >>> from ballpass.datasets import smith_randall_grades
    >>> grades = smith_randall_grades()
    >>> grades.groupby("diagnosable").size().to_dict()
    {'N': 10, 'P': 6, 'Y': 44}
    >>> grades.set_index("record").loc[105, ["label", "grade"]].tolist()
    ['inner', 'Y2']
    """
    import pandas as pd

    from ._cwru_table import NOMINAL_RPM, RECORDS

    with (resources.files(__package__) / "data" / _GRADES).open() as fh:
        table = pd.read_csv(fh)
    tests = [RECORDS[int(r)] for r in table["record"]]
    return table.assign(
        diagnosable=table["grade"].str[0],
        label=[t.kind for t in tests],
        fault_size_in=[t.size_in for t in tests],
        fault_clock=[t.clock for t in tests],
        load_hp=[t.load_hp for t in tests],
        rpm_nominal=[NOMINAL_RPM[t.load_hp] for t in tests],
    )
