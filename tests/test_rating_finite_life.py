"""The limited-life range of ISO 6336-2/-3 (pipeline.rating.life, .pitting, .bending): the
influence factors between their endurance values at the knee and their static values.

Rule (method B; DIN 3990-11, equations 4.04-4.10 and 5.04-5.06, section 5.6, equation
5.18 and table 5.1, as transcribed in the public repository hanslhansl/din3990,
``din3990/din3990_11.py``): the permissible stress without S_min runs log-log between its
static value at the line's first point and its endurance value at the knee, ``sigma_G(N)
= sigma_G,ref (N_ref / N)^(c log(sigma_G,stat / sigma_G,ref))`` with ``c = 0.3705`` (10^5 to
5 x 10^7, contact), ``0.2791`` (10^7 to 10^9, pitting permitted), ``0.2876`` (10^3 to 3 x
10^6, case-hardened root); static: ``Z_L Z_v Z_R = Z_X = 1``, ``Y_deltarelT,stat = 0.44
Y_S + 0.12`` (case-hardened), ``Y_RrelT = Y_X = 1``. KISSsoft's ISO 6336:2006 reports
(``@NREL_5MW/stage_03.rtf`` of gfsReboucas/Drivetrain, commit 4a88df34) name Z_W among the
interpolated factors as well; its static value is taken as 1 (DIN 3990-11 keeps it).

Published values at the knee: ISO/TR 6336-30, Annex A, example 1 (Z_L 1.04739, Z_v 0.96911,
Z_R 0.96599, as transcribed in gfsReboucas/Drivetrain's ``MATISO_6336.m``, commit 4a88df34;
tests/test_rating_pitting.py) and KISSsoft's report of the NREL 5 MW parallel stage
(Y_deltarelT 1.001, Y_RrelT 0.957, Y_X 0.910; tests/test_rating_bending.py). The values at
the static point and at the log-midpoint of the two are computed by hand below.
"""

from __future__ import annotations

import math

import nrel_gearbox as nrel
import pytest

from pipeline.contact.iso_root_stress import iso_root_stress
from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.rating import bending as B
from pipeline.rating import pitting as P
from pipeline.rating.life import StrengthCurve, static_weight
from pipeline.validation import InputError

MPA = 1e6


def test_static_weight_at_the_break_points():
    """w = 1 at and below the static point, 0 at and beyond the knee, 1/2 at the
    log-midpoint of a one-segment line (hardened, 10^5 to 5 x 10^7: sqrt(5e12) =
    2.2360680e6); on the line where some pitting is permitted (1.6 at 6e5, 1.3 at 1e7, 1.0
    at 1e9) w = ln 1.3 / ln 1.6 = 0.558218 at 10^7 and (ln 1.6 + ln 1.3) / (2 ln 1.6) =
    0.779109 at sqrt(6e12)."""
    line = P.LIFE_LINES["hardened"]
    assert static_weight(line, 1e5) == 1.0 and static_weight(line, 10.0) == 1.0
    assert static_weight(line, 5e7) == 0.0 and static_weight(line, 1e12) == 0.0
    assert static_weight(line, math.sqrt(1e5 * 5e7)) == pytest.approx(0.5, rel=1e-12)
    permitted = P.LIFE_LINES["pitting_permitted"]
    assert static_weight(permitted, 1e7) == pytest.approx(0.558218, abs=5e-7)
    assert static_weight(permitted, math.sqrt(6e12)) == pytest.approx(0.779109, abs=5e-7)
    assert static_weight(B.LIFE_LINES["through_hardened"], 1e4) == 1.0


@pytest.fixture(scope="module")
def tr30_chain():
    """ISO/TR 6336-30, Annex A, example 1 at 9000 N m and 360 rpm (K_v 1.003, K_Hbeta
    1.16), as in tests/test_rating_pitting.py."""
    steel = Material(youngs_modulus=206e9, poisson_ratio=0.3)
    common = dict(module=8e-3, pressure_angle=math.radians(20.0),
                  helix_angle=math.radians(15.8), face_width=0.1, material=steel)
    pair = GearPair(
        GearSpec(teeth=17, profile_shift=0.14522, hand="left", tip_radius=0.15966 / 2,
                 name="pinion", **common),
        GearSpec(teeth=103, profile_shift=0.0, hand="right", tip_radius=0.87235 / 2,
                 name="wheel", bore_radius=0.2, **common))
    return P.contact_stress(pair, 9000.0, 360.0, 1.003 * 1.16)


def pitting_at(chain, cycles: float, line: str = "hardened") -> P.PittingSafety:
    return P.pitting_safety(1300 * MPA, 1500 * MPA, cycles, line, 320e-6, 6e-6, chain)


def test_pitting_factors_at_the_break_points(tr30_chain):
    """Hardened line (static point 10^5, knee 5 x 10^7), the example's printed endurance
    factors Z_L 1.04739, Z_v 0.96911, Z_R 0.96599 (to their printed 5e-6):

    * knee: Z_NT 1, the printed factors;
    * static point 10^5: Z_NT 1.6, Z_L = Z_v = Z_R = Z_X = 1, sigma_HG = 1500 x 1.6 = 2400
      N/mm^2 exactly;
    * log-midpoint 2.2360680e6 (by hand): Z_NT = sqrt(1.6) = 1.264911, Z_L = sqrt(1.04739)
      = 1.023421, Z_v = sqrt(0.96911) = 0.984434, Z_R = sqrt(0.96599) = 0.982848, sigma_HG
      = sqrt(2400 x 1470.772) = 1878.79 N/mm^2 (1470.772 = 1500 Z_L Z_v Z_R);
    * 10^4 (below the static point): as at 10^5."""
    knee = pitting_at(tr30_chain, 5e7)
    assert knee.life_factor == 1.0
    for got, printed in ((knee.lubricant_factor, 1.04739), (knee.velocity_factor, 0.96911),
                         (knee.roughness_factor, 0.96599)):
        assert got == pytest.approx(printed, abs=5e-6)
    static = pitting_at(tr30_chain, 1e5)
    assert (static.life_factor, static.lubricant_factor, static.velocity_factor,
            static.roughness_factor, static.size_factor) == (1.6, 1.0, 1.0, 1.0, 1.0)
    assert static.permissible == pytest.approx(2400 * MPA, rel=1e-14)
    assert pitting_at(tr30_chain, 1e4) == static
    mid = pitting_at(tr30_chain, math.sqrt(1e5 * 5e7))
    for got, hand in ((mid.life_factor, 1.264911), (mid.lubricant_factor, 1.023421),
                      (mid.velocity_factor, 0.984434), (mid.roughness_factor, 0.982848)):
        assert got == pytest.approx(hand, abs=5e-6)
    assert mid.permissible == pytest.approx(1878.79 * MPA, abs=0.01 * MPA)
    assert mid.safety == pytest.approx(1878.79 / 1300, abs=1e-5)


def test_work_hardening_factor_in_the_limited_life_range(tr30_chain):
    """Z_W 1.1 (a through-hardened wheel against a hardened pinion) at the knee, 1 at the
    static point, sqrt(1.1) = 1.048809 at the log-midpoint; sigma_HG at the static point
    is 2400 N/mm^2 whatever Z_W."""
    def at(n: float) -> P.PittingSafety:
        return P.pitting_safety(1300 * MPA, 1500 * MPA, n, "hardened", 320e-6, 6e-6,
                                tr30_chain, work_hardening=1.1)

    assert at(5e7).work_hardening_factor == 1.1 and at(1e5).work_hardening_factor == 1.0
    assert at(math.sqrt(5e12)).work_hardening_factor == pytest.approx(1.048809, abs=5e-7)
    assert at(1e5).permissible == pytest.approx(2400 * MPA, rel=1e-14)


def test_pitting_against_din_3990_11_equations(tr30_chain):
    """sigma_HG at 10^6 (hardened) and at 10^7 (pitting permitted) against DIN 3990-11's
    closed forms: sigma_HG,dauer (5e7 / N)^(0.3705 log(sigma_HG,stat / sigma_HG,dauer)) and
    sigma_HG,dauer (1e9 / N)^(0.2791 log(...)), sigma_HG,stat = 1500 x 1.6 N/mm^2; within
    the rounding of their constants (0.3705 for 1 / log 500 = 0.370497: 3e-6; 0.2791 and
    the table's 1.3 at 10^7: 3e-5)."""
    endurance = pitting_at(tr30_chain, 5e7).permissible
    exponent = 0.3705 * math.log10(2400 * MPA / endurance)
    din = endurance * (5e7 / 1e6) ** exponent
    assert pitting_at(tr30_chain, 1e6).permissible == pytest.approx(din, rel=1e-5)
    endurance = pitting_at(tr30_chain, 1e9, "pitting_permitted").permissible
    din = endurance * (1e9 / 1e7) ** (0.2791 * math.log10(2400 * MPA / endurance))
    assert pitting_at(tr30_chain, 1e7, "pitting_permitted").permissible == pytest.approx(
        din, rel=1e-4)


@pytest.fixture(scope="module")
def nrel_root():
    """The NREL 5 MW parallel stage's pinion at 40953 N m (tests/test_rating_bending.py):
    Y_S 2.28637, q_s 2.620."""
    pair = nrel.stage_3()
    return iso_root_stress(pair.pinion, pair, 40953.0 / pair.pinion.reference_radius)


def bending_at(root, cycles: float, line: str = "hardened", **kw) -> B.BendingSafety:
    return B.bending_safety(root, 1.5, 430 * MPA, cycles, line, 0.0030e-3, 20e-6,
                            "hardened", 14e-3, **kw)


def test_bending_factors_at_the_break_points(nrel_root):
    """Case-hardened line (static point 10^3, knee 3 x 10^6), KISSsoft's printed endurance
    factors Y_deltarelT 1.001, Y_RrelT 0.957, Y_X 0.910 (to 5e-4):

    * static point: Y_NT 2.5, Y_deltarelT,stat = 0.44 x 2.28637 + 0.12 = 1.126004, Y_RrelT
      = Y_X = 1; sigma_FG = 430 x 2 x 2.5 x 1.126004 = 2420.908 N/mm^2;
    * log-midpoint sqrt(3e9) = 54772 (by hand): Y_NT = sqrt(2.5) = 1.581139, Y_X =
      sqrt(0.91) = 0.953939 (Y_X = 1.05 - 0.01 x 14 exactly), Y_RrelT = sqrt(1.674 - 0.529
      x 21^0.1) = sqrt(0.956738) = 0.978130, Y_deltarelT = sqrt(1.126004 x 1.001123) =
      1.061729."""
    knee = bending_at(nrel_root, 3e6)
    assert (knee.life_factor, knee.size_factor) == (1.0, 0.91)
    assert knee.notch_factor == pytest.approx(1.001, abs=5e-4)
    assert knee.surface_factor == pytest.approx(0.957, abs=5e-4)
    static = bending_at(nrel_root, 1e3)
    assert nrel_root.y_s == pytest.approx(2.28637, abs=5e-6)
    assert static.notch_factor == pytest.approx(0.44 * nrel_root.y_s + 0.12, rel=1e-14)
    assert (static.life_factor, static.surface_factor, static.size_factor) == (2.5, 1.0, 1.0)
    assert static.limit == pytest.approx(2420.908 * MPA, abs=0.005 * MPA)
    mid = bending_at(nrel_root, math.sqrt(1e3 * 3e6))
    for got, hand in ((mid.life_factor, 1.581139), (mid.size_factor, 0.953939),
                      (mid.surface_factor, 0.978130), (mid.notch_factor, 1.061729)):
        assert got == pytest.approx(hand, abs=5e-6)


def test_bending_against_din_3990_11_equation(nrel_root):
    """sigma_FG at 10^5 against sigma_FG,dauer (3e6 / N)^(0.2876 log(sigma_FG,stat /
    sigma_FG,dauer)) (0.2876 for 1 / log 3000 = 0.287603: 2e-5)."""
    endurance, static = bending_at(nrel_root, 3e6).limit, bending_at(nrel_root, 1e3).limit
    din = endurance * (3e6 / 1e5) ** (0.2876 * math.log10(static / endurance))
    assert bending_at(nrel_root, 1e5).limit == pytest.approx(din, rel=2e-5)


def test_static_notch_sensitivity():
    """At the test gear's Y_S = Y_ST = 2 every material's Y_deltarelT,stat is 1 (0.44 x 2
    + 0.12, 0.20 x 2 + 0.60, through-hardened at any proof stress); through-hardened at
    sigma_0.2 = 300 N/mm^2 and Y_S 2.5: (1 + 0.82 x 1.5) / 1.82 = 1.225275."""
    for line in ("hardened", "nitrided", "nitrocarburized"):
        assert B.static_notch_sensitivity(2.0, line) == pytest.approx(1.0, rel=1e-15)
    assert B.static_notch_sensitivity(2.0, "through_hardened", 700 * MPA) == pytest.approx(
        1.0, rel=1e-15)
    assert B.static_notch_sensitivity(2.5, "through_hardened", 300 * MPA) == pytest.approx(
        1.225275, abs=5e-7)


def test_through_hardened_gear_below_the_knee_needs_its_proof_stress(nrel_root):
    """Below the knee a through-hardened gear's Y_deltarelT,stat needs sigma_0.2: a
    one-line error naming the key; at and beyond the knee it is not needed."""
    with pytest.raises(InputError, match=r"rating\.proof_stress is required"):
        bending_at(nrel_root, 1e5, "through_hardened")
    assert bending_at(nrel_root, 3e6, "through_hardened").life_factor == 1.0
    r = bending_at(nrel_root, 1e4, "through_hardened", proof_stress=600 * MPA)
    k = 0.82 * 0.5**0.25
    assert r.notch_factor == pytest.approx((1 + k * (nrel_root.y_s - 1)) / (1 + k), rel=1e-14)


def test_strength_curve_inverse():
    """cycles_to_failure inverts strength on every segment (hardened line, influence 0.9
    at the knee and 1.0 static): at 10^5 (static), 10^6, 5 x 10^7, 10^9; inf at and below
    the 10^10 strength (0.85 x 0.9 x 1500 N/mm^2), 0 above the static strength unless
    extended, then one decade below 10^5 on the first segment's log-log slope; with optimum
    conditions inf at the endurance strength and finite just above it."""
    curve = StrengthCurve(P.LIFE_LINES["hardened"], 1500 * MPA, 0.9, 1.0)
    for n in (1e5, 1e6, 5e7, 1e9):
        assert float(curve.cycles_to_failure(curve.strength(n))) == pytest.approx(n, rel=1e-12)
    floor = 1500 * MPA * 0.85 * 0.9
    assert curve.strength(1e11) == pytest.approx(floor, rel=1e-14)
    assert math.isinf(curve.cycles_to_failure(floor)) and math.isinf(
        curve.cycles_to_failure(0.5 * floor))
    assert float(curve.cycles_to_failure(2400 * MPA * 1.001)) == 0.0
    extended = StrengthCurve(P.LIFE_LINES["hardened"], 1500 * MPA, 0.9, 1.0,
                             extend_static=True)
    # one more decade down from 10^5 along the first segment: ln sigma rises by the
    # segment's d ln sigma / d ln N times ln 10
    slope = math.log(curve.strength(1e5) / curve.strength(1e6)) / math.log(10.0)
    s = curve.strength(1e5) * 10.0**slope
    assert float(extended.cycles_to_failure(s)) == pytest.approx(1e4, rel=1e-12)
    optimum = StrengthCurve(P.LIFE_LINES["hardened"], 1500 * MPA, 0.9, 1.0, optimum=True)
    assert math.isinf(optimum.cycles_to_failure(1500 * MPA * 0.9))
    assert float(optimum.cycles_to_failure(1500 * MPA * 0.9 * 1.0001)) < 5e7
