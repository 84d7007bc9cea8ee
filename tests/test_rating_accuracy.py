"""ISO 1328-1:1995 tolerances (pipeline.rating.accuracy) against a commercial report.

Reference: the tolerances KISSsoft Release 03/2017 A prints ("According to ISO 1328-1:1995")
for the eight gears of the NREL 5 MW reference gearbox (Nejad et al. 2016), grade 6, in
its reports ``@NREL_5MW/stage_01.rtf``, ``stage_02.rtf`` and ``stage_03.rtf`` of the
public repository gfsReboucas/Drivetrain (commit 4a88df34). Each printed value in um.
"""

from __future__ import annotations

import math

import pytest

from pipeline.rating.accuracy import range_mean, rounded, tolerances
from pipeline.validation import InputError

# name: (m_n mm, d mm, b mm, alpha_t deg), printed f_pt, f_pb, F_p, F_alpha, f_falpha,
# f_Halpha, F_beta, f_fbeta, f_Hbeta (um)
KISSSOFT = {
    "stage 1 sun": ((45.0, 855.0, 491.0, 20.0), (33, 31.0, 81, 42, 33, 27, 30, 21, 21)),
    "stage 1 planet": ((45.0, 765.0, 491.0, 20.0), (33, 31.0, 81, 42, 33, 27, 30, 21, 21)),
    "stage 1 ring": ((45.0, 2520.0, 491.0, 20.0), (38, 35.7, 132, 51, 40, 32, 34, 24, 24)),
    "stage 2 sun": ((21.0, 378.0, 550.0, 20.0), (18, 16.9, 54, 27, 21, 17, 29, 21, 21)),
    "stage 2 planet": ((21.0, 756.0, 550.0, 20.0), (19, 17.9, 67, 30, 23, 19, 30, 21, 21)),
    "stage 2 ring": ((21.0, 1953.0, 550.0, 20.0), (22, 20.7, 97, 35, 27, 22, 32, 23, 23)),
    "stage 3 pinion": ((14.0, 341.183, 360.0, 20.284), (14, 13.1, 50, 23, 18, 15, 25, 18, 18)),
    "stage 3 wheel": ((14.0, 1350.517, 360.0, 20.284), (17, 15.9, 78, 28, 22, 18, 27, 19, 19)),
}


@pytest.mark.parametrize("name", list(KISSSOFT))
def test_grade_6_tolerances_of_the_nrel_gearbox(name):
    (m, d, b, at), printed = KISSSOFT[name]
    t = tolerances(6, m * 1e-3, d * 1e-3, b * 1e-3, math.radians(at))
    got = (t.f_pt, t.f_pb, t.F_p, t.F_alpha, t.f_falpha, t.f_Halpha, t.F_beta, t.f_fbeta,
           t.f_Hbeta)
    assert [round(g * 1e6, 1) for g in got] == [float(p) for p in printed]


def test_ranges_grades_and_rounding():
    """Range means at and inside the limits (upper limit included), the grade step sqrt(2)
    between neighbouring grades before rounding, the three rounding steps, and a size
    outside the standard refused."""
    assert range_mean(10.0, "m_n") == pytest.approx(math.sqrt(6 * 10))
    assert range_mean(10.0001, "m_n") == pytest.approx(math.sqrt(10 * 16))
    assert (rounded(14.4), rounded(7.3), rounded(3.14)) == (14.0, 7.5, 3.1)
    # m 3 mm in (2, 3.5], d 150 mm in (125, 280]: F_p(5) = 0.3 sqrt(7) + 1.25 sqrt(sqrt(
    # 35000)) + 7 = 24.891 um, grade 7 twice that, 49.78 um
    f5 = 0.3 * math.sqrt(7.0) + 1.25 * 35000.0**0.25 + 7.0
    assert f5 == pytest.approx(24.891, abs=5e-4)
    for grade, want in ((5, 25.0), (7, 50.0), (3, 12.0)):
        t = tolerances(grade, 3e-3, 0.15, 0.02, math.radians(20))
        assert t.F_p == pytest.approx(want * 1e-6, rel=1e-12)
    with pytest.raises(InputError, match="d = 12000 mm is outside"):
        tolerances(6, 3e-3, 12.0, 0.02, 0.35)
