"""Cases of the rating and ISO stiffness: ISO/TR 6336-30 example 1 (pitting) and the
ISO 6336-1 stiffness of the NREL 5 MW gearbox's helical and planetary stages as KISSsoft prints it.

Each printed value is compared within the rounding of its printed digits; values the
report derives from rounded intermediates get the tolerance those roundings propagate.
"""

from __future__ import annotations

import math

from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.verification.context import Context
from pipeline.verification.display import N_PER_MM2, N_PER_MM_UM
from pipeline.verification.model import Outcome, Quantity

MPA = 1e6

TR30_EXAMPLE_1 = {"F_t": 127352.0, "Z_H": 2.39533, "Z_E": 189.81170, "Z_eps": 0.803,
                  "Z_beta": 1.01944, "sigma_H0": 1206.58207, "sigma_H": 1301.35343,
                  "Z_L": 1.04739, "Z_v": 0.96911, "Z_R": 0.96599,
                  "sigma_HP": (1338.48050, 1414.52551), "S_H": (1.02853, 1.08696)}
"""ISO/TR 6336-30:2017, Annex A, example 1, printed values (N, N/mm^2, sqrt(N/mm^2), -),
as transcribed in ``MATISO_6336.m`` of the public repository gfsReboucas/Drivetrain."""


def tr30_example_1_pair() -> GearPair:
    """The example's pair: z 17/103, m_n 8 mm, alpha_n 20 deg, beta 15.8 deg, b 100 mm,
    x1 0.14522, x2 0, tip diameters 159.66 / 872.35 mm, E 206 GPa."""
    steel = Material(youngs_modulus=206e9, poisson_ratio=0.3)
    common = dict(module=8e-3, pressure_angle=math.radians(20.0),
                  helix_angle=math.radians(15.8), face_width=0.1, material=steel)
    return GearPair(GearSpec(teeth=17, profile_shift=0.14522, hand="left",
                             tip_radius=0.15966 / 2, name="pinion", **common),
                    GearSpec(teeth=103, profile_shift=0.0, hand="right",
                             tip_radius=0.87235 / 2, name="wheel", bore_radius=0.2, **common))


def case_iso_tr_6336_30_example_1(context: Context) -> Outcome:
    """The pitting chain of ISO/TR 6336-30's example 1 from its inputs: F_t, Z_H, Z_E,
    Z_eps, Z_beta, sigma_H0, sigma_H, Z_L, Z_v, Z_R, sigma_HP and S_H of both gears."""
    from pipeline.rating import pitting as P

    ref = TR30_EXAMPLE_1
    k_v, k_hbeta = 1.003, 1.16
    pair = tr30_example_1_pair()
    chain = P.contact_stress(pair, 9000.0, 360.0, k_v * k_hbeta)
    digits = "half a unit of the printed last digit"
    rounding = 0.5 * (0.0005 / k_v + 0.005 / k_hbeta)
    q = [Quantity("tangential load F_t", "N", ref["F_t"], chain.tangential_load, "absolute",
                  0.5, digits),
         Quantity("zone factor Z_H", "-", ref["Z_H"], chain.zone_factor, "absolute", 5e-6,
                  digits),
         Quantity("elasticity factor Z_E", "sqrt(Pa)", ref["Z_E"] * math.sqrt(MPA),
                  chain.elasticity_factor, "relative", 1e-7, "printed to 8 digits"),
         Quantity("contact ratio factor Z_eps", "-", ref["Z_eps"], chain.contact_ratio_factor,
                  "absolute", 5e-4, digits),
         Quantity("helix angle factor Z_beta", "-", ref["Z_beta"], chain.helix_factor,
                  "absolute", 5e-6, digits),
         Quantity("nominal contact stress sigma_H0", "Pa", ref["sigma_H0"] * MPA,
                  chain.nominal, "relative", 2e-6, "printed to 9 digits; F_t rounded", N_PER_MM2),
         Quantity("contact stress sigma_H", "Pa", ref["sigma_H"] * MPA, chain.stress[0],
                  "relative", rounding,
                  "K_v 1.003 and K_Hbeta 1.16 are printed rounded: their rounding "
                  f"propagates {rounding * 100:.2f} %", N_PER_MM2)]
    cycles = 360.0 * 60.0 * 50_000.0
    for i, (name, n) in enumerate((("pinion", cycles), ("wheel", cycles * 17 / 103))):
        r = P.pitting_safety(ref["sigma_H"] * MPA, 1500 * MPA, n, "hardened", 320e-6, 6.0e-6,
                             chain)
        if i == 0:
            q += [Quantity("lubricant factor Z_L", "-", ref["Z_L"], r.lubricant_factor,
                           "absolute", 5e-6, digits),
                  Quantity("velocity factor Z_v", "-", ref["Z_v"], r.velocity_factor,
                           "absolute", 5e-6, digits),
                  Quantity("roughness factor Z_R", "-", ref["Z_R"], r.roughness_factor,
                           "absolute", 5e-6, digits)]
        q += [Quantity(f"permissible stress sigma_HP, {name}", "Pa", ref["sigma_HP"][i] * MPA,
                       r.permissible, "relative", 1e-5, "Z_NT printed to 2-3 digits", N_PER_MM2),
              Quantity(f"safety factor S_H, {name}", "-", ref["S_H"][i], r.safety, "absolute",
                       5e-6, digits + " (with the printed sigma_H)")]
    inputs = (("pair", "z 17/103, m_n 8 mm, alpha_n 20 deg, beta 15.8 deg, b 100 mm, "
                       "a 500 mm, x1 0.14522"),
              ("load", "9000 N m at 360 rpm on the pinion, 50 000 h"),
              ("load factors", "K_A 1.0, K_v 1.003, K_Hbeta 1.16, K_Halpha 1.0 (printed)"),
              ("material, lubricant", "sigma_Hlim 1500 N/mm^2, E 206 GPa, ISO VG 320, "
                                      "R_z 6 um (R_a 1.0 um)"))
    return Outcome("ISO/TR 6336-30:2017, Annex A, example 1 (case-carburized helical pair), "
                   "as transcribed in gfsReboucas/Drivetrain MATISO_6336.m", inputs, tuple(q))


KISSSOFT_STAGE_3 = {"C_R": 0.898, "C_B": 0.975, "c_single": 13.832, "c_gamma_alpha": 18.632,
                    "c_gamma_beta": 15.837}
"""KISSsoft Release 03/2017 A, NREL 5 MW parallel stage (``stage_03.rtf``): C_R, C_B (-),
c', c_gamma_alpha, c_gamma_beta (N/(mm um))."""


def nrel_stage_3() -> GearPair:
    """The NREL 5 MW parallel helical stage as KISSsoft rates it: z 24/95, m_n 14 mm,
    beta 10 deg, b 360 mm, x 0.48 / 0.6691, tip diameters 380.747 / 1395.376 mm."""
    steel = Material(youngs_modulus=206e9, poisson_ratio=0.3, density=7830.0)
    c = dict(module=14e-3, pressure_angle=math.radians(20.0), helix_angle=math.radians(10.0),
             face_width=0.36, material=steel)
    return GearPair(
        GearSpec(teeth=24, profile_shift=0.48, hand="right", tip_radius=0.380747 / 2,
                 bore_radius=0.17910 / 2, name="pinion", **c),
        GearSpec(teeth=95, profile_shift=0.6691, hand="left", tip_radius=1.395376 / 2,
                 bore_radius=1.19332 / 2, name="wheel", **c))


def case_iso_6336_1_stiffness_kisssoft(context: Context) -> Outcome:
    """ISO 6336-1 method B single and mesh stiffness of the NREL 5 MW helical stage
    against KISSsoft's printed report."""
    from pipeline.stiffness.iso6336 import blank_factor_cr, iso_stiffness

    ref = KISSSOFT_STAGE_3
    pair = nrel_stage_3()
    c_r = blank_factor_cr(5.0, 0.25)
    st = iso_stiffness(pair, 40953.0 / pair.pinion.reference_radius, 1.25, 0.8, c_r)
    unit = 1e9  # N/(mm um) in N/m^2
    digits = "printed to 3 decimals: half a unit of the last"
    q = (Quantity("blank factor C_R", "-", ref["C_R"], c_r, "absolute", 5e-4, digits),
         Quantity("basic rack factor C_B", "-", ref["C_B"], st.factors["C_B"], "absolute",
                  5e-4, digits),
         Quantity("single stiffness c'", "N/m^2", ref["c_single"] * unit, st.c_single,
                  "absolute", 5e-4 * unit, digits, N_PER_MM_UM),
         Quantity("mesh stiffness c_gamma_alpha", "N/m^2", ref["c_gamma_alpha"] * unit,
                  st.c_gamma_alpha, "absolute", 5e-4 * unit, digits, N_PER_MM_UM),
         Quantity("mesh stiffness c_gamma_beta", "N/m^2", ref["c_gamma_beta"] * unit,
                  st.c_gamma_beta, "absolute", 5e-4 * unit, digits, N_PER_MM_UM))
    inputs = (("pair", "z 24/95, m_n 14 mm, beta 10 deg, b 360 mm, x 0.48 / 0.6691, ISO 53 "
                       "profile A"),
              ("load", "40953.0 N m on the pinion, K_A 1.25"),
              ("C_M, b_s / b, s_R / m_n", "0.8, 0.25, 5.0"))
    return Outcome("ISO 6336-1:2019, 9.3 (method B), against KISSsoft Release 03/2017 A's "
                   "report of the NREL 5 MW gearbox (Nejad et al. 2016), stage_03.rtf of "
                   "gfsReboucas/Drivetrain", inputs, q)


KISSSOFT_STAGE_3_RATING = {"K_v": 1.092, "K_Halpha": 1.069, "K_Fbeta": 1.136,
                           "sigma_H": 739.61, "S_H": (1.81, 1.88), "sigma_F": (195.64, 211.85),
                           "S_F": (3.26, 3.09)}
"""KISSsoft Release 03/2017 A, "ISO 6336:2006 Method B", NREL 5 MW parallel stage
(``stage_03.rtf``): printed factors (-), stresses (N/mm^2), safety factors of pinion and
wheel (-)."""


def case_kisssoft_helical_rating(context: Context) -> Outcome:
    """The whole ISO 6336 rating of the NREL 5 MW helical stage from its inputs: K_v,
    K_Halpha, K_Fbeta, sigma_H, S_H, sigma_F, S_F against KISSsoft's printed report."""
    from pipeline.rating.pair_rating import GearRatingInputs, RatingInputs, rate_pair

    ref = KISSSOFT_STAGE_3_RATING
    gear = GearRatingInputs(sigma_hlim=1500 * MPA, sigma_flim=430 * MPA,
                            flank_roughness=4.8e-6, root_roughness=20e-6)
    inputs = RatingInputs(application_factor=1.25, life_hours=175_200.0, accuracy_grade=6,
                          viscosity_40=220e-6, k_hbeta=1.150, blank_factor=0.898,
                          minimum_safety_pitting=1.25, minimum_safety_bending=1.56)
    r = rate_pair(nrel_stage_3(), 40953.0, 1165.9, inputs, (gear, gear))
    digits = "half a unit of the printed last digit"
    q = [Quantity("dynamic factor K_v", "-", ref["K_v"], r.dynamic.factor, "relative", 1e-3,
                  "printed to 4 digits (measured -0.06 %); the tests hold 0.1 %"),
         Quantity("transverse load factor K_Halpha", "-", ref["K_Halpha"],
                  r.transverse.k_halpha, "absolute", 1e-3, "printed to 3 decimals (measured "
                                                           "+0.4e-3); the tests hold 1e-3"),
         Quantity("face load factor K_Fbeta", "-", ref["K_Fbeta"], r.k_fbeta, "absolute",
                  6e-4, digits + " and K_Hbeta's printed 1.150"),
         Quantity("contact stress sigma_H", "Pa", ref["sigma_H"] * MPA, r.contact.stress[0],
                  "relative", 1e-3, "K_v's -0.06 % carried into sigma_H (measured -0.04 %)",
                  N_PER_MM2)]
    for i, name in enumerate(("pinion", "wheel")):
        q += [Quantity(f"pitting safety S_H, {name}", "-", ref["S_H"][i], r.pitting[i].safety,
                       "absolute", 5e-3, "printed to 2 decimals"),
              Quantity(f"root stress sigma_F, {name}", "Pa", ref["sigma_F"][i] * MPA,
                       r.bending[i].stress, "relative", 3e-3,
                       "sigma_F0's -0.08 % and K_v's -0.06 % (measured -0.14 %); the tests "
                       "hold 0.3 %", N_PER_MM2),
              Quantity(f"bending safety S_F, {name}", "-", ref["S_F"][i], r.bending[i].safety,
                       "absolute", 5e-3, "printed to 2 decimals")]
    inputs_ = (("pair", "z 24/95, m_n 14 mm, beta 10 deg, b 360 mm, x 0.48 / 0.6691"),
               ("load", "40953.0 N m at 1165.9 rpm, K_A 1.25, 175 200 h"),
               ("accuracy, lubricant", "grade 6, ISO VG 220"),
               ("material", "18CrNiMo7-6 case carburized: sigma_Hlim 1500, sigma_Flim 430 "
                            "N/mm^2, R_z 4.8 / 20 um"),
               ("given", "K_Hbeta 1.150 (the report's input), C_R 0.898, S_Hmin 1.25, "
                         "S_Fmin 1.56"))
    return Outcome("KISSsoft Release 03/2017 A report of the NREL 5 MW gearbox's parallel "
                   "stage (Nejad et al. 2016), stage_03.rtf of gfsReboucas/Drivetrain",
                   inputs_, tuple(q))


KISSSOFT_STAGE_2 = {"C_B": 0.975, "c_single": (12.240, 14.053), "c_gamma_alpha": (15.640, 20.563)}
"""KISSsoft Release 03/2017 A, NREL 5 MW second (planetary) stage (``stage_02.rtf``): C_B
(-), c' and c_gamma_alpha of the sun-planet and planet-ring meshes (N/(mm um))."""


def nrel_stage_2() -> tuple[GearPair, GearPair]:
    """The NREL 5 MW second stage's sun-planet and planet-ring pairs: z 18/36/93 (ring
    internal), m_n 21 mm, spur, b 550 mm, x 0.389 / 0.50387 / 0.11712, tip diameters
    432.838 / 815.663 / 1906.081 mm."""
    steel = Material(youngs_modulus=206e9, poisson_ratio=0.3, density=7830.0)
    c = dict(module=21e-3, pressure_angle=math.radians(20.0), face_width=0.55, material=steel)
    sun = GearSpec(teeth=18, profile_shift=0.389, tip_radius=0.432838 / 2,
                   bore_radius=0.19432 / 2, name="sun", **c)
    planet = GearSpec(teeth=36, profile_shift=0.5038693, tip_radius=0.815663 / 2,
                      bore_radius=0.57696 / 2, name="planet", **c)
    ring = GearSpec(teeth=93, profile_shift=0.1171157, tip_radius=1.906081 / 2,
                    bore_radius=2.14882 / 2, internal=True, name="ring", **c)
    return GearPair(sun, planet), GearPair(planet, ring)


def case_iso_6336_1_stiffness_planetary(context: Context) -> Outcome:
    """ISO 6336-1 method B single and mesh stiffness of the NREL 5 MW planetary stage's
    sun-planet and planet-ring (internal) meshes against KISSsoft's printed report."""
    from pipeline.stiffness.iso6336 import iso_stiffness

    ref = KISSSOFT_STAGE_2
    unit = 1e9  # N/(mm um) in N/m^2
    why = ("C_R is given as printed, 0.862 (3 digits): its rounding carries 0.06 % (measured "
           "-0.03 %)")
    q = []
    for i, (name, pair) in enumerate(zip(("sun-planet", "planet-ring"), nrel_stage_2(),
                                         strict=True)):
        st = iso_stiffness(pair, 285900.438, 1.25, 0.8, 0.862)
        q += [Quantity(f"basic rack factor C_B, {name}", "-", ref["C_B"], st.factors["C_B"],
                       "absolute", 5e-4, "printed to 3 decimals: half a unit of the last"),
              Quantity(f"single stiffness c', {name}", "N/m^2", ref["c_single"][i] * unit,
                       st.c_single, "relative", 6e-4, why, N_PER_MM_UM),
              Quantity(f"mesh stiffness c_gamma_alpha, {name}", "N/m^2",
                       ref["c_gamma_alpha"][i] * unit, st.c_gamma_alpha, "relative", 6e-4,
                       why, N_PER_MM_UM)]
    inputs = (("meshes", "z 18/36 and 36/93 (ring internal: z_n2 = inf in ISO's q'), m_n 21 "
                         "mm, spur, b 550 mm"),
              ("load", "F_t 285 900.438 N per mesh, K_A 1.25"),
              ("C_M, C_R", "0.8, 0.862 (printed; b_s / b 0.250)"))
    return Outcome("ISO 6336-1:2019, 9.3 (method B), against KISSsoft Release 03/2017 A's "
                   "report of the NREL 5 MW gearbox (Nejad et al. 2016), stage_02.rtf of "
                   "gfsReboucas/Drivetrain", inputs, tuple(q))
