"""ISO 6336-2 pitting rating (pipeline.rating.pitting) against a published worked example.

Reference: ISO/TR 6336-30:2017, Annex A, example 1 (single helical, case-carburized pair:
z 17/103, m_n 8 mm, alpha_n 20 deg, beta 15.8 deg, b 100 mm, a 500 mm, x2 = 0, tip
diameters 159.66 / 872.35 mm, 9000 N m at 360 rpm on the pinion, 50 000 h, ISO VG 320,
sigma_Hlim 1500 N/mm^2, R_a 1.0 um, E 206 000 N/mm^2, nu 0.3). Its printed values are
taken as transcribed with their digits in the "Reference" table of ``example_01`` in
``MATISO_6336.m`` of the public repository gfsReboucas/Drivetrain (the report's own pages
were not available here); its 2022 edition prints x1 = 0.14522 and the tip diameters
(quoted in a second public project). Each assertion states the printed value and the
tolerance of its printed rounding; values that the report derives from rounded
intermediates (sigma_H from K_v 1.003 and K_Hbeta 1.16) get the tolerance those
roundings propagate.

The exact ladder below it: Z_NT on each life line at the table's points and log-log
between them; Z_L and Z_v at their limits (C_ZL at infinite viscosity, C_Zv at infinite
speed); Z_eps and Z_B / Z_D for a spur pair against their closed forms.
"""

from __future__ import annotations

import math

import nrel_gearbox as nrel
import pytest

from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.rating import pitting as P
from pipeline.validation import InputError

MPA = 1e6


@pytest.fixture(scope="module")
def tr30_example_1() -> GearPair:
    """ISO/TR 6336-30, Annex A, example 1 (the pinion left hand, the wheel right hand)."""
    steel = Material(youngs_modulus=206e9, poisson_ratio=0.3)
    common = dict(module=8e-3, pressure_angle=math.radians(20.0),
                  helix_angle=math.radians(15.8), face_width=0.1, material=steel)
    pinion = GearSpec(teeth=17, profile_shift=0.14522, hand="left", tip_radius=0.15966 / 2,
                      name="pinion", **common)
    wheel = GearSpec(teeth=103, profile_shift=0.0, hand="right", tip_radius=0.87235 / 2,
                     name="wheel", bore_radius=0.2, **common)
    return GearPair(pinion, wheel)


def test_geometry_of_the_example(tr30_example_1):
    """The pair closes at the example's a = 500 mm with x1 = 0.14522 (0.1 um); eps_alpha
    and eps_beta as the example's Z_eps implies (eps_beta > 1: Z_eps = sqrt(1/eps_alpha))."""
    pair = tr30_example_1
    assert pair.operating_centre_distance == pytest.approx(0.5, abs=1e-7)
    assert pair.overlap_ratio > 1.0
    assert pair.transverse_contact_ratio == pytest.approx(1.549, abs=5e-4)


def test_contact_stress_chain(tr30_example_1):
    """Printed: F_t 127352.0 N, Z_H 2.39533, Z_E 189.81170 sqrt(N/mm^2), Z_eps 0.803,
    Z_beta 1.01944, Z_B = Z_D = 1.0, sigma_H0 1206.58207 N/mm^2, sigma_H 1301.35343
    N/mm^2 (with K_A 1.0, K_v 1.003, K_Hbeta 1.16, K_Halpha 1.0: their rounding
    propagates 0.24 %)."""
    k_v, k_hbeta = 1.003, 1.16
    chain = P.contact_stress(tr30_example_1, 9000.0, 360.0, 1.0 * k_v * k_hbeta * 1.0)
    assert chain.tangential_load == pytest.approx(127352.0, abs=0.5)
    assert chain.zone_factor == pytest.approx(2.39533, abs=5e-6)
    assert chain.elasticity_factor == pytest.approx(189.81170 * math.sqrt(MPA), rel=1e-7)
    assert chain.contact_ratio_factor == pytest.approx(0.803, abs=5e-4)
    assert chain.helix_factor == pytest.approx(1.01944, abs=5e-6)
    assert chain.single_pair_factors == (1.0, 1.0)
    assert chain.nominal == pytest.approx(1206.58207 * MPA, rel=2e-6)
    rounding = 0.5 * (0.0005 / k_v + 0.005 / k_hbeta)
    for s in chain.stress:
        assert s == pytest.approx(1301.35343 * MPA, rel=rounding)
    assert chain.velocity == pytest.approx(2.664, abs=5e-4)


def test_permissible_stress_and_safety(tr30_example_1):
    """Printed: N_L 1.080e9 / 1.783e8, Z_NT 0.91 / 0.962 (ISO 6336-2 line of hardened
    steel without pitting, 0.85 at 10^10), Z_L 1.04739, Z_v 0.96911, Z_R 0.96599 (R_z =
    6 R_a, the standard's conversion, from R_a 1.0 um), Z_W = Z_X = 1.0, sigma_HP
    1338.48050 / 1414.52551 N/mm^2 and S_H 1.02853 / 1.08696 with S_Hmin 1.0 (the safety
    factors with the printed sigma_H 1301.35343 N/mm^2)."""
    pair = tr30_example_1
    chain = P.contact_stress(pair, 9000.0, 360.0, 1.003 * 1.16)
    cycles = (360.0 * 60.0 * 50_000.0, 360.0 * 60.0 * 50_000.0 * 17 / 103)
    assert cycles[0] == pytest.approx(1.080e9, rel=5e-4)
    assert cycles[1] == pytest.approx(1.783e8, rel=5e-4)
    sigma_h = 1301.35343 * MPA
    want = ((0.91, 1338.48050, 1.02853), (0.962, 1414.52551, 1.08696))
    for n, (znt, hp, sh) in zip(cycles, want, strict=True):
        r = P.pitting_safety(sigma_h, 1500 * MPA, n, "hardened", 320e-6, 6.0e-6, chain)
        assert r.life_factor == pytest.approx(znt, abs=5e-4 if znt == 0.962 else 5e-3)
        assert r.lubricant_factor == pytest.approx(1.04739, abs=5e-6)
        assert r.velocity_factor == pytest.approx(0.96911, abs=5e-6)
        assert r.roughness_factor == pytest.approx(0.96599, abs=5e-6)
        assert (r.work_hardening_factor, r.size_factor) == (1.0, 1.0)
        assert r.permissible == pytest.approx(hp * MPA, rel=1e-5)
        assert r.safety == pytest.approx(sh, abs=5e-6)


@pytest.mark.parametrize("line", sorted(P.LIFE_LINES))
def test_life_factor_lines(line):
    """At every point of its line Z_NT is the table's value; static below the first;
    log-log between (the geometric mean of two points' cycles gives the geometric mean of
    their factors); 0.85 at and beyond 10^10, 1.0 with optimum conditions."""
    points = P.LIFE_LINES[line]
    for n, z in points:
        assert P.life_factor(n, line) == pytest.approx(z, rel=1e-12)
    assert P.life_factor(points[0][0] / 10, line) == points[0][1]
    for (n0, z0), (n1, z1) in zip(points[:-1], points[1:], strict=True):
        assert P.life_factor(math.sqrt(n0 * n1), line) == pytest.approx(math.sqrt(z0 * z1),
                                                                        rel=1e-12)
    assert P.life_factor(1e12, line) == 0.85
    assert P.life_factor(1e12, line, optimum=True) == 1.0
    with pytest.raises(InputError, match="rating.life_line"):
        P.life_factor(1e6, "soft")


def test_lubricant_and_velocity_factors_at_their_limits():
    """Z_L -> C_ZL + 4 (1 - C_ZL) / 1.44 for an infinitely viscous oil and Z_v -> C_Zv +
    2 (1 - C_Zv) / sqrt(0.8) at infinite speed; C_ZL 0.83 below 850 and 0.91 above
    1200 N/mm^2, continuous at both ends."""
    for s, c in ((800 * MPA, 0.83), (1300 * MPA, 0.91)):
        assert P.lubricant_factor(s, 1.0) == pytest.approx(c + 4 * (1 - c) / 1.2**2, rel=1e-3)
        assert P.velocity_factor(s, 1e9) == pytest.approx(
            c + 0.02 + 2 * (1 - c - 0.02) / math.sqrt(0.8), rel=1e-6)
    assert P.lubricant_constant(850 * MPA) == pytest.approx(0.83, abs=1e-4)
    assert P.lubricant_constant(1200 * MPA) == pytest.approx(0.91, abs=1e-4)


def test_spur_pair_contact_ratio_and_single_pair_factors():
    """A spur pair (eps_beta = 0): Z_eps = sqrt((4 - eps_alpha) / 3); Z_B from M1 written
    out with the pair's diameters; the wheel's Z_D from M2 (for z 17 / 60 both are >= 1)."""
    from gearsets import spur

    pair = GearPair(spur(17, "pinion"), spur(60, "gear"))
    chain = P.contact_stress(pair, 100.0, 1000.0, 1.0)
    ea = pair.transverse_contact_ratio
    assert chain.contact_ratio_factor == pytest.approx(math.sqrt((4 - ea) / 3), rel=1e-14)
    p, g = pair.pinion, pair.gear
    a1 = math.sqrt((p.tip_radius_ / p.base_radius) ** 2 - 1)
    a2 = math.sqrt((g.tip_radius_ / g.base_radius) ** 2 - 1)
    tan_w = math.tan(pair.operating_pressure_angle)
    m1 = tan_w / math.sqrt((a1 - 2 * math.pi / 17) * (a2 - (ea - 1) * 2 * math.pi / 60))
    m2 = tan_w / math.sqrt((a2 - 2 * math.pi / 60) * (a1 - (ea - 1) * 2 * math.pi / 17))
    assert chain.single_pair_factors == pytest.approx((max(m1, 1.0), max(m2, 1.0)), rel=1e-14)
    assert chain.single_pair_factors[0] > 1.0


@pytest.fixture(scope="module")
def nrel_stage_3() -> GearPair:
    """The parallel helical stage of the NREL 5 MW reference gearbox (Nejad et al. 2016) as
    rated by KISSsoft Release 03/2017 A, "ISO 6336:2006 Method B" (:mod:`nrel_gearbox`)."""
    return nrel.stage_3()


def test_kisssoft_report_of_a_helical_pair(nrel_stage_3):
    """KISSsoft's printed pitting chain at 40953.0 N m, 1165.9 rpm (5 MW), K_A 1.25, its
    K_v 1.092, K_Hbeta 1.150 (user given), K_Halpha 1.069, 175 200 h, ISO VG 220, R_z
    4.80 um, sigma_Hlim 1500 N/mm^2, S_Hmin 1.25, life factors floored at 0.85 (its
    "normal" material quality; the hardened line reaches 0.85 only at 10^10): a 861.000 mm,
    eps_alpha 1.463, eps_beta 1.421, F_t 240064.4 N, v 20.83 m/s, Z_H 2.307, Z_eps 0.827,
    Z_beta 1.008, sigma_H0 570.79 N/mm^2, sigma_H 739.61 N/mm^2 (0.05 % from the printed
    K's rounding), Z_B = Z_D = 1.00, N_L 12255.788 / 3096.199 million, Z_L 1.020, Z_v
    1.022, Z_R 1.007, Z_NT 0.850 / 0.881, sigma_HP 1070.64 / 1109.85 N/mm^2, S_H 1.81 /
    1.88 (on its sigma_H)."""
    pair = nrel_stage_3
    assert pair.operating_centre_distance == pytest.approx(0.861, abs=5e-7)
    assert pair.transverse_contact_ratio == pytest.approx(1.463, abs=5e-4)
    assert pair.overlap_ratio == pytest.approx(1.421, abs=5e-4)
    k = 1.25 * 1.092 * 1.150 * 1.069
    chain = P.contact_stress(pair, 40953.0, 1165.9, k)
    assert chain.tangential_load == pytest.approx(240064.4, abs=0.5)
    assert chain.velocity == pytest.approx(20.83, abs=5e-3)
    assert chain.zone_factor == pytest.approx(2.307, abs=5e-4)
    assert chain.contact_ratio_factor == pytest.approx(0.827, abs=5e-4)
    assert chain.helix_factor == pytest.approx(1.008, abs=5e-4)
    assert chain.nominal == pytest.approx(570.79 * MPA, abs=0.005 * MPA)
    assert chain.single_pair_factors == (1.0, 1.0)
    rounding = 0.5 * (0.0005 / 1.092 + 0.0005 / 1.069)
    assert chain.stress[0] == pytest.approx(739.61 * MPA, rel=rounding + 5e-6)
    hours = 175_200.0  # the cycles at the printed speed, 1165.9 rpm rounded to 4e-5
    assert 1165.9 * 60 * hours == pytest.approx(12255.788e6, rel=5e-5)
    assert 1165.9 * 24 / 95 * 60 * hours == pytest.approx(3096.199e6, rel=5e-5)
    cycles = (12255.788e6, 3096.199e6)
    want = ((0.850, 1070.64, 1.81), (0.881, 1109.85, 1.88))
    for n, (znt, hp, sh) in zip(cycles, want, strict=True):
        r = P.pitting_safety(739.61 * MPA, 1500 * MPA, n, "hardened", 220e-6, 4.8e-6, chain,
                             minimum_safety=1.25)
        assert r.life_factor == pytest.approx(znt, abs=5e-4)
        assert r.lubricant_factor == pytest.approx(1.020, abs=5e-4)
        assert r.velocity_factor == pytest.approx(1.022, abs=5e-4)
        assert r.roughness_factor == pytest.approx(1.007, abs=5e-4)
        # the printed digit and its N_L's (8 digits of 1e10 cycles): 1e-5
        assert r.permissible == pytest.approx(hp * MPA, rel=1e-5)
        assert r.safety == pytest.approx(sh, abs=5e-3)


def test_kisssoft_report_of_a_planetary_sun_planet_mesh():
    """The sun-planet mesh of the NREL 5 MW gearbox's second (spur planetary) stage as
    KISSsoft Release 03/2017 A rates it (``@NREL_5MW/stage_02.rtf`` of gfsReboucas/
    Drivetrain, commit 4a88df34): sun z 18, x 0.3890, planet z 36, x 0.50387, m_n 21 mm,
    alpha_n 20 deg, b 550 mm, a 584 mm, tip diameters 432.838 / 815.663 mm, three planets,
    162105.5 N m on the sun at 294.5 rpm with the carrier at 47.8 rpm, K_A 1.25,
    K_gamma 1.10, K_v 1.06, K_Hbeta 2.06, K_Halpha 1.00 (all printed to 2 digits), sigma_Hlim
    1500 N/mm^2, ISO VG 220, R_z 4.80 um, 175 200 h. The mesh's speed is the sun's relative
    to the carrier (246.7 rpm: Z_v 0.982 with it; the absolute speed would give 0.986).
    Printed: F_t 285900.438 N per planet, Z_H 2.25, Z_eps 0.936, Z_B 1.08 (the sun, spur:
    M1 > 1), Z_D 1.00, sigma_H0 573.40 N/mm^2, sigma_H 1071.17 / 994.13 N/mm^2 (0.6 % from
    the K's two digits), N_L 7782.3 / 1297.1 million, Z_NT 0.857 / 0.905, Z_L 1.020, Z_v
    0.982, Z_R 1.007, sigma_HG 1295.42 / 1368.61 N/mm^2."""
    pair = nrel.stage_2_sun_planet()
    assert pair.operating_centre_distance == pytest.approx(0.584, abs=5e-7)
    k = 1.25 * 1.10 * 1.06 * 2.06 * 1.00
    chain = P.contact_stress(pair, 162105.5 / 3, 294.5 - 47.8, k)
    assert chain.tangential_load == pytest.approx(285900.438, rel=5e-7)
    assert chain.zone_factor == pytest.approx(2.25, abs=5e-3)
    assert chain.contact_ratio_factor == pytest.approx(0.936, abs=5e-4)
    assert chain.single_pair_factors[0] == pytest.approx(1.08, abs=5e-3)
    assert chain.single_pair_factors[1] == 1.0
    # 573.3946: the sun's shift printed to 4 digits moves it by 1e-5
    assert chain.nominal == pytest.approx(573.40 * MPA, rel=2e-5)
    rounding = 0.5 * (0.005 / 1.06 + 0.005 / 2.06 + 0.005 / 1.00)
    for s, want in zip(chain.stress, (1071.17, 994.13), strict=True):
        assert s == pytest.approx(want * MPA, rel=rounding)
    for n, znt, hg in ((7782.3e6, 0.857, 1295.42), (1297.1e6, 0.905, 1368.61)):
        r = P.pitting_safety(1000 * MPA, 1500 * MPA, n, "hardened", 220e-6, 4.8e-6, chain,
                             minimum_safety=1.25)
        assert r.life_factor == pytest.approx(znt, abs=5e-4)
        assert r.lubricant_factor == pytest.approx(1.020, abs=5e-4)
        assert r.velocity_factor == pytest.approx(0.982, abs=5e-4)
        assert r.roughness_factor == pytest.approx(1.007, abs=5e-4)
        # the printed N_L's five digits move Z_NT by up to 2e-6
        assert r.permissible * 1.25 == pytest.approx(hg * MPA, rel=2e-5)


def test_kisssoft_report_of_a_planet_ring_mesh():
    """The planet-ring (internal) mesh of the same stage (``stage_02.rtf``): planet z 36,
    x 0.50387, ring z 93 internal, x 0.11712, tip diameter 1906.081 mm, a 584 mm, F_t
    285900.438 N per planet, the planet at 123.4 rpm relative to the carrier, K_A 1.25,
    K_gamma 1.10, K_v 1.06, K_Hbeta 1.15, K_Halpha 1.00; the ring through-hardened 34 CrNiMo
    6, 240 HBW, sigma_Hlim 700 N/mm^2, R_z 8.0 um (the planet's 4.8 um). The mesh's lower
    sigma_Hlim sets C_ZL, C_Zv and C_ZR for both gears; Z_W = 1.2 - (240 - 130) / 1700
    for the ring against the case-hardened planet. Printed: alpha_wt 15.630 deg,
    eps_alpha 1.618, Z_H 2.85, Z_eps 0.891, Z_B = Z_D = 1.00, sigma_H0 312.44 N/mm^2,
    sigma_H 404.76 N/mm^2 (the K's two digits), Z_L 1.038, Z_v 0.961, Z_R 1.026, Z_W
    1.000 / 1.135, N_L 1297.1 / 1506.3 million, Z_NT 0.905 / 0.901, sigma_HG 1388.39 /
    732.21 N/mm^2."""
    pair = nrel.stage_2_planet_ring()
    assert pair.operating_centre_distance == pytest.approx(0.584, abs=5e-7)
    # 15.62949 deg, as a = 584 mm gives it exactly (cos = 598.5 cos 20 deg / 584)
    assert math.degrees(pair.operating_pressure_angle) == pytest.approx(
        math.degrees(math.acos(598.5 * math.cos(math.radians(20.0)) / 584.0)), abs=1e-6)
    assert math.degrees(pair.operating_pressure_angle) == pytest.approx(15.630, abs=1e-3)
    assert pair.transverse_contact_ratio == pytest.approx(1.618, abs=5e-4)
    k = 1.25 * 1.10 * 1.06 * 1.15 * 1.00
    chain = P.contact_stress(pair, 285900.438 * pair.pinion.reference_radius, 123.4, k)
    assert chain.tangential_load == pytest.approx(285900.438, rel=1e-9)
    assert chain.zone_factor == pytest.approx(2.85, abs=5e-3)
    assert chain.contact_ratio_factor == pytest.approx(0.891, abs=5e-4)
    assert chain.single_pair_factors == (1.0, 1.0)
    assert chain.nominal == pytest.approx(312.44 * MPA, abs=0.005 * MPA)
    rounding = 0.5 * (0.005 / 1.06 + 0.005 / 1.15 + 0.005 / 1.00)
    assert chain.stress[1] == pytest.approx(404.76 * MPA, rel=rounding)
    assert P.work_hardening_factor(240.0) == pytest.approx(1.135, abs=5e-4)
    gears = ((1500 * MPA, 1297.1e6, 1.0, 0.905, 1388.39),
             (700 * MPA, 1506.3e6, P.work_hardening_factor(240.0), 0.901, 732.21))
    for limit, n, zw, znt, hg in gears:
        r = P.pitting_safety(400 * MPA, limit, n, "hardened", 220e-6, (4.8e-6 + 8.0e-6) / 2,
                             chain, minimum_safety=1.25, mesh_sigma_hlim=700 * MPA,
                             work_hardening=zw)
        assert r.life_factor == pytest.approx(znt, abs=5e-4)
        assert r.lubricant_factor == pytest.approx(1.038, abs=5e-4)
        assert r.velocity_factor == pytest.approx(0.961, abs=5e-4)
        assert r.roughness_factor == pytest.approx(1.026, abs=5e-4)
        assert r.work_hardening_factor == pytest.approx(zw, rel=1e-15)
        assert r.permissible * 1.25 == pytest.approx(hg * MPA, rel=3e-5)


def test_kisssoft_report_of_the_first_planetary_stage():
    """The sun-planet mesh of the NREL 5 MW first stage (``stage_01.rtf``, KISSsoft 03/2017
    A): sun z 19, x 0.61713, planet z 17, x 0.8021, m_n 45 mm, b 491 mm, a 863 mm, tip
    diameters 978.808 / 905.470 mm, 999650.9 N m on the sun at 47.8 rpm, carrier 12.1 rpm,
    three planets, K_A 1.25, K_gamma 1.10, K_Hbeta 1.15; K_v K_Halpha = 1.0053 from its
    printed sigma_Hw / sigma_H0 = 958.15 / 759.92 (K_v printed 1.01, K_Halpha 1.00). Both
    single pair factors above 1 here. Printed: F_t 779454.877 N, Z_H 2.06, Z_eps 0.981, Z_B
    1.04, Z_D 1.05, sigma_H0 759.92, sigma_H 996.13 / 1002.73 N/mm^2, Z_L 1.020, Z_v 0.961,
    Z_R 1.024, Z_NT 0.909 / 0.937 (N_L 1124.7 / 419.0 million), sigma_HG 1368.61 / 1410.69."""
    pair = nrel.stage_1_sun_planet()
    # x of the planet to 4 digits: a 863.003 mm
    assert pair.operating_centre_distance == pytest.approx(0.863, abs=5e-6)
    k = (958.15 / 759.92) ** 2
    chain = P.contact_stress(pair, 999650.9 / 3, 47.8 - 12.1, k)
    assert chain.tangential_load == pytest.approx(779454.877, rel=1e-7)
    assert chain.zone_factor == pytest.approx(2.06, abs=5e-3)
    assert chain.contact_ratio_factor == pytest.approx(0.981, abs=5e-4)
    assert chain.single_pair_factors == pytest.approx((1.04, 1.05), abs=5e-3)
    assert chain.nominal == pytest.approx(759.92 * MPA, rel=1e-5)
    for s, want in zip(chain.stress, (996.13, 1002.73), strict=True):
        assert s == pytest.approx(want * MPA, rel=2e-4)
    for n, znt, hg in ((1124.7e6, 0.909, 1368.61), (419.0e6, 0.937, 1410.69)):
        r = P.pitting_safety(1000 * MPA, 1500 * MPA, n, "hardened", 220e-6, 4.8e-6, chain,
                             minimum_safety=1.25)
        assert r.life_factor == pytest.approx(znt, abs=5e-4)
        assert r.lubricant_factor == pytest.approx(1.020, abs=5e-4)
        assert r.velocity_factor == pytest.approx(0.961, abs=5e-4)
        assert r.roughness_factor == pytest.approx(1.024, abs=5.1e-4)  # 1.02450
        assert r.permissible * 1.25 == pytest.approx(hg * MPA, rel=3e-5)
