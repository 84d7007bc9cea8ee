"""Surface durability (pitting) of ISO 6336-2, method B: contact stress, permissible
contact stress and the safety factor S_H of each gear.

SI inside (m, N, Pa); the standard's formulas are written in N, mm and N/mm^2, and where
a factor's formula holds a dimensional constant the conversion is made at that line.

Contact stress (ISO 6336-2:2019, clause 5):

* zone factor ``Z_H = sqrt(2 cos(beta_b) cos(alpha_wt) / (cos^2(alpha_t) sin(alpha_wt)))``;
* elasticity factor ``Z_E = sqrt(1 / (pi ((1 - nu1^2) / E1 + (1 - nu2^2) / E2)))``;
* contact ratio factor ``Z_eps``: ``sqrt((4 - eps_alpha) / 3)`` for a spur pair,
  ``sqrt((4 - eps_alpha) / 3 (1 - eps_beta) + eps_beta / eps_alpha)`` for ``eps_beta < 1``,
  ``sqrt(1 / eps_alpha)`` for ``eps_beta >= 1``;
* helix angle factor ``Z_beta = 1 / sqrt(cos(beta))`` (ISO/TR 6336-30, example 1:
  1.01944 at 15.8 deg);
* single pair tooth contact factors ``Z_B`` (pinion) and ``Z_D`` (wheel), which move the
  pitch-point stress to the inner point of single pair contact of each gear:
  ``M1 = tan(alpha_wt) / sqrt((sqrt(d_a1^2 / d_b1^2 - 1) - 2 pi / z1)
  (sqrt(d_a2^2 / d_b2^2 - 1) - (eps_alpha - 1) 2 pi / z2))`` and ``M2`` with the gears
  swapped (the ratio of the relative radii of curvature at the pitch point and at those
  points, :func:`single_pair_factors`); spur: ``Z_B = max(M1, 1)``, ``Z_D = max(M2, 1)``;
  helical with ``eps_beta >= 1``: 1; between: ``M - eps_beta (M - 1)``, at least 1; an
  internal gear's ``Z_D`` is 1;
* nominal ``sigma_H0 = Z_H Z_E Z_eps Z_beta sqrt(F_t (u + 1) / (d_1 b u))`` with the
  nominal tangential load ``F_t`` at the reference circle and ``u = z2 / z1`` (negative
  for an internal pair, ISO 21771);
* ``sigma_H = Z_B,D sigma_H0 sqrt(K_A K_gamma K_v K_Hbeta K_Halpha)``.

Permissible contact stress (clause 6): ``sigma_HP = sigma_Hlim Z_NT Z_L Z_v Z_R Z_W Z_X /
S_Hmin``, and the safety factor ``S_H = sigma_Hlim Z_NT Z_L Z_v Z_R Z_W Z_X / sigma_H``:

* life factor ``Z_NT`` (clause 10, table of the four material lines, interpolated
  log-log between the table's points; beyond the endurance knee down to ``Z_NT`` 0.85 at
  10^10 cycles, or 1.0 where the conditions are optimum, :data:`LIFE_LINES`);
* lubricant factor ``Z_L = C_ZL + 4 (1 - C_ZL) / (1.2 + 134 / nu_40)^2`` and velocity
  factor ``Z_v = C_Zv + 2 (1 - C_Zv) / sqrt(0.8 + 32 / v)`` with ``C_ZL`` 0.83 below
  ``sigma_Hlim`` = 850 N/mm^2, 0.91 above 1200, ``sigma_Hlim / 4375 + 0.6357`` between,
  ``C_Zv = C_ZL + 0.02`` (``nu_40`` in mm^2/s, ``v`` the pitch line velocity in m/s);
* roughness factor ``Z_R = (3 / R_z10)^C_ZR``, ``R_z10 = R_z (10 / rho_red)^(1/3)`` (mean
  peak-to-valley roughness of the two flanks in um, ``rho_red`` the relative radius of
  curvature at the pitch point in mm), ``C_ZR = 0.32 - 0.0002 sigma_Hlim`` within [0.08,
  0.15];
* work hardening ``Z_W`` and size ``Z_X`` factors: 1 (equal hardness, module within the
  standard's range for 1).

Limited life (fewer load cycles than the line's endurance knee, :mod:`.life`): ``Z_L``,
``Z_v``, ``Z_R``, ``Z_W`` and ``Z_X`` run log-log from their endurance values at the knee
to 1 at the static point (the line's first point, 10^5 cycles or 6 x 10^5 where some
pitting is permitted), with the weight of the life factor's own interpolation, so that
``sigma_HG`` runs log-log from ``sigma_Hlim Z_NT,stat`` to ``sigma_Hlim Z_L Z_v Z_R Z_W
Z_X`` (the two-point rule of method B: DIN 3990-11's equations 4.04-4.10 with ``Z_LVR,stat
= Z_X,stat = 1``; KISSsoft's ISO 6336:2006 reports state that ``Z_L``, ``Z_v``, ``Z_R``,
``Z_W``, ``Z_X`` are interpolated logarithmically between their fatigue and static values).
``Z_W``'s static value is taken as 1 here: DIN 3990-11 keeps ``Z_W`` at both ends, and
ISO 6336-2's own static ``Z_W`` was not found in a public source (it matters only for a
through-hardened gear against a hardened mate below the knee). Each record states the
factors at the gear's load cycles. :func:`strength_curve` gives the whole S-N line for
ISO 6336-6's Miner sum.

Checked against ISO/TR 6336-30, Annex A, example 1 (``tests/test_rating_pitting.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.contact.hertz import contact_modulus, effective_radius
from pipeline.geometry.pair import GearPair
from pipeline.rating.life import (
    StrengthCurve,
    life_factor_on,
    limited_life_value,
    static_weight,
)
from pipeline.validation import check_choice, check_range

LIFE_LINES: dict[str, tuple[tuple[float, float], ...]] = {
    # (load cycles, Z_NT) at the table's points; log-log between; the last point is the
    # value at 10^10 cycles with Z_NT 0.85 (the optimum conditions use 1.0 instead)
    "pitting_permitted": ((6e5, 1.6), (1e7, 1.3), (1e9, 1.0), (1e10, 0.85)),
    "hardened": ((1e5, 1.6), (5e7, 1.0), (1e10, 0.85)),
    "nitrided": ((1e5, 1.3), (2e6, 1.0), (1e10, 0.85)),
    "nitrocarburized": ((1e5, 1.1), (2e6, 1.0), (1e10, 0.85)),
}
"""ISO 6336-2 life factor lines (clause 10, table): ``pitting_permitted`` St, V, GGG (perl.,
bai.), GTS (perl.), Eh, IF where some pitting is permitted; ``hardened`` the same
materials without pitting (line 2, e.g. case-carburized Eh); ``nitrided`` GG, GGG (ferr.),
NT (nitr.), NV (nitr.); ``nitrocarburized`` NV (nitrocar.)."""


def life_factor(cycles: float, line: str, optimum: bool = False) -> float:
    """``Z_NT`` at ``cycles`` load cycles on the material ``line`` of :data:`LIFE_LINES`:
    the static value up to the first point, log-log interpolation between points, the
    long-life branch falling to 0.85 at 10^10 (1.0 with ``optimum`` lubrication,
    material, manufacturing and experience), constant beyond 10^10."""
    check_choice("rating.life_line", line, tuple(LIFE_LINES))
    return life_factor_on(LIFE_LINES[line], cycles, optimum)


def lubricant_constant(sigma_hlim: float) -> float:
    """``C_ZL`` for ``sigma_Hlim`` (Pa)."""
    s = sigma_hlim / 1e6
    return 0.83 if s < 850.0 else 0.91 if s > 1200.0 else s / 4375.0 + 0.6357


def lubricant_factor(sigma_hlim: float, viscosity_40: float) -> float:
    """``Z_L`` for ``sigma_Hlim`` (Pa) and the kinematic viscosity at 40 deg C (m^2/s)."""
    c = lubricant_constant(sigma_hlim)
    nu = viscosity_40 * 1e6  # mm^2/s
    return c + 4.0 * (1.0 - c) / (1.2 + 134.0 / nu) ** 2


def velocity_factor(sigma_hlim: float, velocity: float) -> float:
    """``Z_v`` for ``sigma_Hlim`` (Pa) and the pitch line velocity (m/s)."""
    c = lubricant_constant(sigma_hlim) + 0.02
    return c + 2.0 * (1.0 - c) / math.sqrt(0.8 + 32.0 / velocity)


def roughness_factor(sigma_hlim: float, roughness: float, relative_radius: float) -> float:
    """``Z_R`` for ``sigma_Hlim`` (Pa), the mean peak-to-valley roughness ``R_z`` of the two
    flanks (m) and the relative radius of curvature at the pitch point (m)."""
    c = min(max(0.32 - 0.0002 * sigma_hlim / 1e6, 0.08), 0.15)
    rz10 = roughness * 1e6 * (10.0 / (relative_radius * 1e3)) ** (1.0 / 3.0)
    return (3.0 / rz10) ** c


@dataclass(frozen=True)
class ContactStress:
    """The contact stress chain of ISO 6336-2 for a pair (SI).

    Attributes
    ----------
    zone_factor, elasticity_factor, contact_ratio_factor, helix_factor : Z_H (-),
        Z_E (sqrt(Pa)), Z_eps (-), Z_beta (-).
    single_pair_factors : (Z_B, Z_D), pinion and wheel (-).
    tangential_load : F_t at the reference circle, N.
    nominal : sigma_H0, Pa.
    load_factor : K_A K_gamma K_v K_Hbeta K_Halpha (-).
    stress : (sigma_H1, sigma_H2), Pa.
    relative_radius : rho_red at the pitch point, m (for Z_R).
    velocity : pitch line velocity, m/s (for Z_v).
    """

    zone_factor: float
    elasticity_factor: float
    contact_ratio_factor: float
    helix_factor: float
    single_pair_factors: tuple[float, float]
    tangential_load: float
    nominal: float
    load_factor: float
    stress: tuple[float, float]
    relative_radius: float
    velocity: float


def zone_factor(pair: GearPair) -> float:
    """``Z_H`` of ``pair``."""
    p = pair.pinion
    at, bb, awt = p.transverse_pressure_angle, p.base_helix_angle, pair.operating_pressure_angle
    return math.sqrt(2.0 * math.cos(bb) * math.cos(awt) / (math.cos(at) ** 2 * math.sin(awt)))


def elasticity_factor(pair: GearPair) -> float:
    """``Z_E = sqrt(E* / pi)`` of ``pair`` (sqrt(Pa)), ``E*`` the contact modulus."""
    return math.sqrt(contact_modulus(pair.pinion.material, pair.gear.material) / math.pi)


def relative_radius(pair: GearPair, s: float) -> float:
    """Relative radius of curvature ``rho1 rho2 / (rho1 + rho2)`` (m) where the flanks meet
    at roll coordinate ``s`` (a ring's concave flank: ``rho2 < 0``)."""
    r1, r2 = pair.curvature_radii(np.array([s]))
    return float(effective_radius(r1[0], r2[0]))


def contact_ratio_factor(eps_alpha: float, eps_beta: float) -> float:
    """``Z_eps`` for the transverse and overlap ratios."""
    if eps_beta >= 1.0:
        return math.sqrt(1.0 / eps_alpha)
    return math.sqrt((4.0 - eps_alpha) / 3.0 * (1.0 - eps_beta) + eps_beta / eps_alpha)


def single_pair_factors(pair: GearPair) -> tuple[float, float]:
    """``(Z_B, Z_D)``: ``M = sqrt(R_C / R_B)`` with the relative radii of curvature ``R = rho1
    rho2 / (rho1 + rho2)`` at the pitch point C and at the inner point of single pair
    contact of the pinion (B, one base pitch inside the end of the path) and of the wheel
    (D, one base pitch inside its start) - ISO's ``M1`` and ``M2`` written through the
    curvatures, so a ring's concave flank (``rho2 < 0``) enters as it is; an internal
    gear's ``Z_D`` is 1 (ISO 6336-2)."""
    eps_b = pair.overlap_ratio
    pb = pair.base_pitch
    rc = relative_radius(pair, pair.s_pitch)

    def factor(s: float) -> float:
        m = math.sqrt(rc / relative_radius(pair, s))
        if eps_b >= 1.0:
            return 1.0
        return max(m - eps_b * (m - 1.0), 1.0)

    zb = factor(pair.s_end - pb)
    zd = 1.0 if pair.gear.internal else factor(pair.s_start + pb)
    return zb, zd


def contact_stress(pair: GearPair, torque: float, speed: float, load_factor: float
                   ) -> ContactStress:
    """The contact stress chain at the pinion ``torque`` (N m) and ``speed`` (rpm) with the
    product of the load factors ``K_A K_gamma K_v K_Hbeta K_Halpha`` (-)."""
    check_range("rating.torque", torque, 0.0, math.inf, lo_open=True, unit="N m")
    check_range("rating.load_factor", load_factor, 1.0, 10.0)
    p, g = pair.pinion, pair.gear
    d1 = 2.0 * p.reference_radius
    u = (-1.0 if g.internal else 1.0) * g.teeth / p.teeth  # ISO 21771: negative for a ring
    b = pair.face_width
    ft = 2.0 * torque / d1
    zh, ze = zone_factor(pair), elasticity_factor(pair)
    zeps = contact_ratio_factor(pair.transverse_contact_ratio, pair.overlap_ratio)
    zbeta = 1.0 / math.sqrt(math.cos(p.helix_angle))
    sigma0 = zh * ze * zeps * zbeta * math.sqrt(ft / (d1 * b) * (u + 1.0) / u)
    zb, zd = single_pair_factors(pair)
    root = math.sqrt(load_factor)
    velocity = p.reference_radius * speed * 2.0 * math.pi / 60.0
    return ContactStress(zh, ze, zeps, zbeta, (zb, zd), ft, sigma0, load_factor,
                         (zb * sigma0 * root, zd * sigma0 * root),
                         relative_radius(pair, pair.s_pitch), velocity)


@dataclass(frozen=True)
class PittingSafety:
    """Permissible contact stress and safety factor of one gear (SI).

    Attributes
    ----------
    life_factor, lubricant_factor, velocity_factor, roughness_factor : Z_NT, Z_L, Z_v,
        Z_R (-) at the gear's load cycles (below the endurance knee the limited-life values
        of Z_L, Z_v, Z_R).
    work_hardening_factor, size_factor : Z_W, Z_X (-), at the load cycles as well.
    permissible : sigma_HP, Pa.
    safety : S_H (-).
    """

    life_factor: float
    lubricant_factor: float
    velocity_factor: float
    roughness_factor: float
    work_hardening_factor: float
    size_factor: float
    permissible: float
    safety: float


def work_hardening_factor(hardness_hb: float) -> float:
    """``Z_W`` of a through-hardened gear of Brinell hardness ``hardness_hb`` meshing with a
    surface-hardened, smooth mate (ISO 6336-2:2006, 10: ``1.2 - (HB - 130) / 1700``, 1.2
    below 130 HB, 1.0 above 470 HB); 1 for the hardened gear itself."""
    check_range("rating.hardness_HB", hardness_hb, 50.0, 800.0)
    return 1.2 - (min(max(hardness_hb, 130.0), 470.0) - 130.0) / 1700.0


def _influence_factors(sigma_hlim: float, viscosity_40: float, roughness: float,
                       chain: ContactStress, minimum_safety: float,
                       mesh_sigma_hlim: float | None, work_hardening: float
                       ) -> tuple[float, float, float]:
    """Check a gear's permissible-stress inputs; its endurance ``(Z_L, Z_v, Z_R)``."""
    check_range("rating.sigma_Hlim", sigma_hlim, 200e6, 2500e6, unit="Pa")
    check_range("rating.viscosity_40", viscosity_40, 1e-6, 5000e-6, unit="m^2/s")
    check_range("rating.roughness_rz", roughness, 0.0, 100e-6, lo_open=True, unit="m")
    check_range("rating.minimum_safety_pitting", minimum_safety, 0.5, 5.0)
    check_range("rating.Z_W", work_hardening, 1.0, 1.2)
    lower = sigma_hlim if mesh_sigma_hlim is None else mesh_sigma_hlim
    return (lubricant_factor(lower, viscosity_40), velocity_factor(lower, chain.velocity),
            roughness_factor(lower, roughness, chain.relative_radius))


def strength_curve(sigma_hlim: float, line: str, viscosity_40: float, roughness: float,
                   chain: ContactStress, optimum: bool = False,
                   mesh_sigma_hlim: float | None = None, work_hardening: float = 1.0
                   ) -> StrengthCurve:
    """The S-N line ``sigma_HG(N)`` of a gear (arguments as :func:`pitting_safety`): the
    life ``line``, ``sigma_Hlim`` and the endurance product ``Z_L Z_v Z_R Z_W Z_X`` (static
    product 1)."""
    check_choice("rating.life_line", line, tuple(LIFE_LINES))
    zl, zv, zr = _influence_factors(sigma_hlim, viscosity_40, roughness, chain, 1.0,
                                    mesh_sigma_hlim, work_hardening)
    # Z_X = 1 at both ends (the module range of this rating)
    return StrengthCurve(LIFE_LINES[line], sigma_hlim, zl * zv * zr * work_hardening, 1.0,
                         optimum)


def pitting_safety(stress: float, sigma_hlim: float, cycles: float, line: str,
                   viscosity_40: float, roughness: float, chain: ContactStress,
                   minimum_safety: float = 1.0, optimum: bool = False,
                   mesh_sigma_hlim: float | None = None, work_hardening: float = 1.0
                   ) -> PittingSafety:
    """``sigma_HP`` and ``S_H`` of a gear under the contact ``stress`` (Pa) with its
    ``sigma_Hlim`` (Pa), ``cycles`` load cycles on the life ``line``, the lubricant's
    kinematic viscosity at 40 deg C (m^2/s), the mean roughness ``R_z`` of the two flanks
    (m) and the pair's contact stress ``chain`` (its pitch line velocity and relative
    radius). ``mesh_sigma_hlim`` (Pa): the lower ``sigma_Hlim`` of the two gears, which sets
    ``C_ZL``, ``C_Zv`` and ``C_ZR`` for both (default this gear's); ``work_hardening``:
    ``Z_W`` (:func:`work_hardening_factor`). Below the line's endurance knee ``Z_L``,
    ``Z_v``, ``Z_R``, ``Z_W`` and ``Z_X`` are their limited-life values (towards 1 at the
    static point)."""
    check_choice("rating.life_line", line, tuple(LIFE_LINES))
    zl, zv, zr = _influence_factors(sigma_hlim, viscosity_40, roughness, chain,
                                    minimum_safety, mesh_sigma_hlim, work_hardening)
    curve = strength_curve(sigma_hlim, line, viscosity_40, roughness, chain, optimum,
                           mesh_sigma_hlim, work_hardening)
    w = static_weight(LIFE_LINES[line], cycles)
    znt = life_factor(cycles, line, optimum)
    strength = curve.strength(cycles)
    return PittingSafety(znt, limited_life_value(zl, 1.0, w), limited_life_value(zv, 1.0, w),
                         limited_life_value(zr, 1.0, w),
                         limited_life_value(work_hardening, 1.0, w),
                         1.0, strength / minimum_safety,
                         strength / stress)
