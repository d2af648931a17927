"""The official numbering of the CWRU Bearing Data Center files.

Every CWRU recording has a record number (the file ``105.mat`` holds the variables
``X105_DE_time``, ``X105RPM``, ...). The data centre's pages list which number is which
test: sampling rate, faulty bearing, fault kind and size, outer-race position and motor
load. This table reproduces those pages so a file named only by its number (``105.mat``,
``97.mat``), or renamed by a download script, still gets its sampling rate, label and
load. The numbers were checked against the data centre's tables as mirrored by the
``cwru`` package's ``metadata.txt`` (Litchiware/cwru on GitHub) and against the variable
names inside 19 of the CWRU files.

Gaps and irregularities of the official numbering (kept as they are):

* 12 kHz drive end, outer race 0.007 in at 12 o'clock: 156, 158, 159, 160 (no 157);
  48 kHz drive end, inner race 0.021 in: 213, 214, 215, 217 (no 216).
* Fan end (12 kHz only): outer race 0.007 in at 12 o'clock is 302, 305, 306, 307;
  0.014 in at 3 o'clock is **310 (0 hp), 309 (1 hp)**, 311, 312; 0.014 in at 6 o'clock
  only 313 (0 hp); 0.021 in at 6 o'clock only 315 (0 hp), at 3 o'clock 316-318 (1-3 hp).
  So a file distributed as ``12k_FE_OR014@3_0.mat`` that holds ``X309`` is, by this
  table, the 1 hp record; its stored 1774 rpm fits 1 hp (nominal 1772), not 0 hp, and
  so does its signal (shaft-harmonic comb at 1773.6 rpm).
* The 0.028 in faults (3001-3008, drive end, 12 kHz) carry no RPM variable.
* The normal baseline (97-100) is sampled at 48 kHz.

Uncertainty: the table mirrors a third-party copy of the data centre's pages (the pages
themselves moved several times); every number in those 19 files agrees with it.
"""

from __future__ import annotations

from typing import NamedTuple

#: Nominal motor speed by motor load, rpm (CWRU data centre: 0-3 hp -> 1797-1730 rpm).
NOMINAL_RPM = {0: 1797.0, 1: 1772.0, 2: 1750.0, 3: 1730.0}


class CwruTest(NamedTuple):
    """What one CWRU record number stands for."""

    fs: float  #: sampling rate, Hz
    end: str | None  #: faulty bearing, "DE" or "FE" (None: healthy)
    kind: str  #: "healthy", "inner", "outer" or "ball"
    size_in: float  #: fault diameter, inches (0 when healthy)
    clock: int | None  #: outer-race fault position, o'clock (3, 6 or 12)
    load_hp: int  #: motor load, hp


# (kHz, end, kind, size in mils, o'clock, record numbers for 0, 1, 2, 3 hp; None = absent)
_ROWS = (
    (48, None, "healthy", 0, None, (97, 98, 99, 100)),
    # 12 kHz drive end
    (12, "DE", "inner", 7, None, (105, 106, 107, 108)),
    (12, "DE", "ball", 7, None, (118, 119, 120, 121)),
    (12, "DE", "outer", 7, 6, (130, 131, 132, 133)),
    (12, "DE", "outer", 7, 3, (144, 145, 146, 147)),
    (12, "DE", "outer", 7, 12, (156, 158, 159, 160)),
    (12, "DE", "inner", 14, None, (169, 170, 171, 172)),
    (12, "DE", "ball", 14, None, (185, 186, 187, 188)),
    (12, "DE", "outer", 14, 6, (197, 198, 199, 200)),
    (12, "DE", "inner", 21, None, (209, 210, 211, 212)),
    (12, "DE", "ball", 21, None, (222, 223, 224, 225)),
    (12, "DE", "outer", 21, 6, (234, 235, 236, 237)),
    (12, "DE", "outer", 21, 3, (246, 247, 248, 249)),
    (12, "DE", "outer", 21, 12, (258, 259, 260, 261)),
    (12, "DE", "inner", 28, None, (3001, 3002, 3003, 3004)),
    (12, "DE", "ball", 28, None, (3005, 3006, 3007, 3008)),
    # 48 kHz drive end
    (48, "DE", "inner", 7, None, (109, 110, 111, 112)),
    (48, "DE", "ball", 7, None, (122, 123, 124, 125)),
    (48, "DE", "outer", 7, 6, (135, 136, 137, 138)),
    (48, "DE", "outer", 7, 3, (148, 149, 150, 151)),
    (48, "DE", "outer", 7, 12, (161, 162, 163, 164)),
    (48, "DE", "inner", 14, None, (174, 175, 176, 177)),
    (48, "DE", "ball", 14, None, (189, 190, 191, 192)),
    (48, "DE", "outer", 14, 6, (201, 202, 203, 204)),
    (48, "DE", "inner", 21, None, (213, 214, 215, 217)),
    (48, "DE", "ball", 21, None, (226, 227, 228, 229)),
    (48, "DE", "outer", 21, 6, (238, 239, 240, 241)),
    (48, "DE", "outer", 21, 3, (250, 251, 252, 253)),
    (48, "DE", "outer", 21, 12, (262, 263, 264, 265)),
    # 12 kHz fan end
    (12, "FE", "inner", 21, None, (270, 271, 272, 273)),
    (12, "FE", "inner", 14, None, (274, 275, 276, 277)),
    (12, "FE", "inner", 7, None, (278, 279, 280, 281)),
    (12, "FE", "ball", 7, None, (282, 283, 284, 285)),
    (12, "FE", "ball", 14, None, (286, 287, 288, 289)),
    (12, "FE", "ball", 21, None, (290, 291, 292, 293)),
    (12, "FE", "outer", 7, 6, (294, 295, 296, 297)),
    (12, "FE", "outer", 7, 3, (298, 299, 300, 301)),
    (12, "FE", "outer", 7, 12, (302, 305, 306, 307)),
    (12, "FE", "outer", 14, 3, (310, 309, 311, 312)),
    (12, "FE", "outer", 14, 6, (313, None, None, None)),
    (12, "FE", "outer", 21, 6, (315, None, None, None)),
    (12, "FE", "outer", 21, 3, (None, 316, 317, 318)),
)

#: record number -> :class:`CwruTest`
RECORDS: dict[int, CwruTest] = {
    number: CwruTest(1000.0 * khz, end, kind, mils / 1000.0, clock, load)
    for khz, end, kind, mils, clock, numbers in _ROWS
    for load, number in enumerate(numbers)
    if number is not None
}
