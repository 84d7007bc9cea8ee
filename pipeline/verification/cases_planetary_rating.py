"""Case of the planetary rating: the ISO 6336 rating of the NREL 5 MW gearbox's second
(spur planetary) stage, sun-planet and planet-ring meshes, against KISSsoft's report.

Both meshes are rated from the report's inputs alone; each printed value is compared
within the rounding of its printed digits, and the sun's bending safety against the
quotient of its printed permissible and actual root stresses (the printed 2.82 is that
quotient rounded after K_v and K_Fbeta were rounded to three digits).
"""

from __future__ import annotations

from pipeline.verification.cases_rating import MPA, nrel_stage_2
from pipeline.verification.context import Context
from pipeline.verification.display import N_PER_MM2
from pipeline.verification.model import Outcome, Quantity

KISSSOFT_STAGE_2_RATING = {"K_v": (1.02, 1.06), "S_H_sun_planet": (1.21, 1.38),
                           "S_H_planet_ring": (3.43, 1.81), "sigma_F": (209.38, 210.14),
                           "sigma_FP_sun": 589.60, "S_F_planet": (2.04, 4.18)}
"""KISSsoft Release 03/2017 A, "ISO 6336:2006 Method B", NREL 5 MW second stage
(``stage_02.rtf``): K_V12, K_V23 (-); S_H of sun and planet (sun side), planet (ring side)
and ring (-); sigma_F of sun and planet (sun side) and sigma_FP of the sun (N/mm^2); S_F of
the planet on the sun and ring sides (-). The load cycles N_L of sun, planet and ring are
compared where they are computed (printed 7782.3e6, 1297.1e6, 1506.3e6)."""


def stage_2_gear_inputs():
    """The report's per-gear rating inputs (KISSsoft Release 03/2017 A, ``stage_02.rtf``):
    sun and planet case-carburized, sigma_Hlim 1500, sigma_Flim 430 N/mm^2, the planet an
    idler (Y_M 0.7); the ring through-hardened 34CrNiMo6 240 HBW, sigma_Hlim 700,
    sigma_Flim 290 N/mm^2, R_z 8.0 um. Returns (sun, planet, ring)
    :class:`~pipeline.rating.pair_rating.GearRatingInputs`."""
    from pipeline.rating.pair_rating import GearRatingInputs

    sun = GearRatingInputs(sigma_hlim=1500 * MPA, sigma_flim=430 * MPA)
    planet = GearRatingInputs(sigma_hlim=1500 * MPA, sigma_flim=430 * MPA,
                              mean_stress_factor=0.7)
    ring = GearRatingInputs(sigma_hlim=700 * MPA, sigma_flim=290 * MPA,
                            hardening="through_hardened", hardness_hb=240.0,
                            flank_roughness=8.0e-6)
    return sun, planet, ring


def rate_stage_2(mesh: str, pair, torque: float, speed: float, k_hbeta: float, gears,
                 dynamic=None):
    """:func:`pipeline.rating.pair_rating.rate_pair` of one mesh of the second stage with the
    report's common inputs: K_A 1.25, 175 200 h, grade 6, ISO VG 220, K_gamma 1.10, C_R
    0.862, S_Hmin 1.25, S_Fmin 1.56, three planets; ``torque`` (N m) and ``speed`` (rpm)
    of the pair's first gear, ``k_hbeta`` the report's input, ``dynamic`` a K_v to use."""
    from pipeline.rating.pair_rating import RatingInputs, rate_pair

    inputs = RatingInputs(application_factor=1.25, life_hours=175_200.0, accuracy_grade=6,
                          viscosity_40=220e-6, k_hbeta=k_hbeta, load_sharing=1.10,
                          blank_factor=0.862, minimum_safety_pitting=1.25,
                          minimum_safety_bending=1.56)
    return rate_pair(pair, torque, speed, inputs, gears, mesh, planets=3, dynamic=dynamic)


def case_kisssoft_planetary_rating(context: Context) -> Outcome:
    """The ISO 6336 rating of the NREL 5 MW planetary stage from its inputs: K_v of both
    meshes, K_Halpha, S_H of sun, planet and ring, sigma_F and S_F of sun and planet, the
    load cycles against KISSsoft's printed report."""
    ref = KISSSOFT_STAGE_2_RATING
    sun, planet, ring = stage_2_gear_inputs()
    rel = 294.5 - 47.8  # the sun relative to the carrier, rpm
    t_sun = 162105.5 / 3  # per planet, N m
    t_planet = t_sun * 36 / 18  # the planet's torque on the ring side, N m
    sp, pr = nrel_stage_2()
    first = (rate_stage_2("sun_planet", sp, t_sun, rel, 2.06, (sun, planet)),
             rate_stage_2("planet_ring", pr, t_planet, rel * 18 / 36, 1.15, (planet, ring)))
    kv = max((r.dynamic for r in first), key=lambda d: d.factor)
    r_sp = rate_stage_2("sun_planet", sp, t_sun, rel, 2.06, (sun, planet), kv)
    r_pr = rate_stage_2("planet_ring", pr, t_planet, rel * 18 / 36, 1.15, (planet, ring), kv)
    digits = "printed to 2 decimals"
    q = [Quantity(f"dynamic factor K_v, {name}", "-", ref["K_v"][i], first[i].dynamic.factor,
                  "absolute", 5e-3, digits)
         for i, name in enumerate(("sun-planet", "planet-ring"))]
    q += [Quantity(f"transverse load factor K_Halpha, {name}", "-", 1.00, r.transverse.k_halpha,
                   "absolute", 0.0, "printed 1.00: the factor's lower limit 1, which "
                                    "the tests hold exactly")
          for name, r in (("sun-planet", r_sp), ("planet-ring", r_pr))]
    for label, r, refs in (("sun-planet", r_sp, ref["S_H_sun_planet"]),
                           ("planet-ring", r_pr, ref["S_H_planet_ring"])):
        gears = ("sun", "planet") if label == "sun-planet" else ("planet", "ring")
        q += [Quantity(f"pitting safety S_H, {g} ({label})", "-", refs[i], r.pitting[i].safety,
                       "absolute", 5e-3, digits) for i, g in enumerate(gears)]
    q += [Quantity(f"root stress sigma_F, {g} (sun-planet)", "Pa", ref["sigma_F"][i] * MPA,
                   r_sp.bending[i].stress, "relative", 6e-4,
                   "K_v (printed 1.06) and K_Fbeta (printed 1.94): their unprinted fourth "
                   "digits carry 0.05 %; the tests hold 0.06 %", N_PER_MM2)
          for i, g in enumerate(("sun", "planet"))]
    q += [Quantity("bending safety S_F, sun (sun-planet)", "-",
                   ref["sigma_FP_sun"] / ref["sigma_F"][0], r_sp.bending[0].safety, "relative",
                   6e-4, "the printed sigma_FP 589.60 over sigma_F 209.38 N/mm^2 (printed S_F "
                         "2.82 rounds them after rounding K_v and K_Fbeta); the tests hold "
                         "0.06 %"),
          Quantity("bending safety S_F, planet (sun-planet)", "-", ref["S_F_planet"][0],
                   r_sp.bending[1].safety, "absolute", 5e-3, digits),
          Quantity("bending safety S_F, planet (planet-ring)", "-", ref["S_F_planet"][1],
                   r_pr.bending[0].safety, "absolute", 5e-3, digits)]
    # the printed N_L imply the sun at 246.775 rpm relative to the carrier, the printed
    # speeds (one decimal) 246.7: the reference takes the printed speeds
    speeds = 246.7 / 246.775
    q += [Quantity(f"load cycles N_L, {name}", "-", printed * 1e6 * speeds, n, "relative",
                   tol, f"N_L printed to 5 digits: half a unit of the last is "
                        f"{0.05 / printed:.1e}; the tests hold {tol:.0e}")
          for name, printed, n, tol in (
              ("sun (three planets per turn)", 7782.3, r_sp.cycles[0], 1e-5),
              ("planet (sun side)", 1297.1, r_sp.cycles[1], 5e-5),
              ("ring", 1506.3, r_pr.cycles[1], 5e-5))]
    inputs = (("meshes", "z 18/36 and 36/93 (ring internal), m_n 21 mm, spur, b 550 mm, "
                         "x 0.389 / 0.50387 / 0.11712"),
              ("load", "162 105.5 N m on the sun at 294.5 rpm, carrier 47.8 rpm, three "
                       "planets, K_A 1.25, K_gamma 1.10, 175 200 h"),
              ("accuracy, lubricant", "grade 6, ISO VG 220"),
              ("materials", "sun, planet case carburized (sigma_Hlim 1500, sigma_Flim 430 "
                            "N/mm^2); ring 34CrNiMo6 through hardened 240 HBW (700 / 290 "
                            "N/mm^2, R_z 8.0 um); planet an idler (Y_M 0.7)"),
              ("given", "K_Hbeta 2.06 / 1.15 (the report's inputs), C_R 0.862, S_Hmin 1.25, "
                        "S_Fmin 1.56; K_v of both meshes the larger one, as printed"))
    return Outcome("KISSsoft Release 03/2017 A report of the NREL 5 MW gearbox's second "
                   "(planetary) stage (Nejad et al. 2016), stage_02.rtf of "
                   "gfsReboucas/Drivetrain", inputs, tuple(q),
                   notes="The ring's bending needs ISO 6336-3's internal-gear form factors, "
                         "not built: it is not compared.")
