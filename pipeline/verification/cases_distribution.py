"""Cases of the load distribution quantities (:mod:`pipeline.contact.distribution`):
K_Hbeta against ISO 6336-1's closed form and the Hertz pressure against ISO 6336-2.

* A spur pair of uniform mesh stiffness c0 per unit face width and tooth pair, with a helix
  slope deviation f_Hb small enough that the whole face stays loaded, carries a linear line
  load w(z) = P / b - n c0 f_Hb (z / b - 1/2) (n pairs in contact); on N slices
  K_Hbeta = 1 + n c0 f_Hb (1/2 - 1/(2 N)) / (P / b), ISO 6336-1's
  1 + f_Hb c_gamma / (2 F_m / b) as N -> inf. With part of the face lifting off (one pair),
  K_Hbeta = sqrt(2 f_Hb n c0 / (P / b)) (the standard's second regime).
* At the pitch point in single contact on the nominal path the largest Hertz pressure is
  ISO 6336-2's p_H = Z_H Z_E sqrt(F_t / (d_1 b) (u + 1) / u) (the closed-form line
  contact written with the gear data).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.contact.source import UniformSlices
from pipeline.verification.context import Context
from pipeline.verification.model import Outcome, Quantity

TORQUE_LINEAR, TORQUE_PARTIAL = 300.0, 200.0
"""Pinion torques, N m, of the linear and the partial-face cases."""
C0 = 1.4e10
"""Mesh stiffness per unit face width and tooth pair, N/m^2 (14 N/(mm um))."""


def _pair():
    from pipeline.geometry import GearPair, GearSpec, Material

    steel = Material(youngs_modulus=2.0e11, poisson_ratio=0.3, density=7850.0)
    spur = dict(module=3e-3, pressure_angle=math.radians(20), face_width=0.02,
                bore_radius=0.021, material=steel)
    return GearPair(GearSpec(teeth=30, name="pinion", **spur),
                    GearSpec(teeth=45, name="gear", **spur))


def _slope_case(pair, slices, torque, slope):
    """The uniform-slice cycle under a slope deviation, its distribution, the pairs in
    contact at each position and the mean line load P / b (N/m)."""
    from pipeline.contact.distribution import load_distribution
    from pipeline.contact.ltca import loaded_mesh_cycle
    from pipeline.contact.separations import FlankModifications
    from pipeline.operation import OperatingPoint

    op = OperatingPoint(torque=torque, speed=100.0)
    cyc = loaded_mesh_cycle(UniformSlices(pair, slices, C0), torque / pair.pinion.base_radius,
                            FlankModifications(slope_deviation=slope), "none", 24)
    n = pair.pair_positions(cyc.s0)[1].sum(axis=1)
    return load_distribution(cyc, pair, op), n, cyc.load / pair.face_width


def _worst(name, ref, val, tol, reason):
    ref, val = np.ravel(ref), np.ravel(val)
    i = int(np.argmax(np.abs(val / ref - 1.0)))
    return Quantity(name, "-", ref[i], val[i], "relative", tol, reason)


def case_iso_6336_1_k_hbeta(context: Context) -> Outcome:
    """K_Hbeta under a slope deviation: linear regime on 40 slices, partial face on 400."""
    pair = _pair()
    f, slices = 10e-6, 40
    dist, n, w_m = _slope_case(pair, slices, TORQUE_LINEAR, f)
    edge = 0.5 - 0.5 / slices  # the outer slice centre's distance from mid face over b
    if not np.all(n * C0 * f * edge < w_m):
        raise ValueError("the face lifts off: the linear regime's closed form does not apply")
    exact = "the closed form on the slices is exact: the solver's round-off (tests: 1e-9)"
    q = [_worst("K_Hbeta per position, linear load (worst position)",
                1.0 + n * C0 * f * edge / w_m, dist.k_hbeta_position, 1e-9, exact),
         Quantity("K_Hbeta over the cycle, linear load", "-",
                  1.0 + n.mean() * C0 * f * edge / w_m, dist.k_hbeta, "relative", 1e-9, exact),
         Quantity("K_Hbeta over the cycle against ISO 6336-1's continuous "
                  "1 + f_Hb c_gamma / (2 F_m / b)", "-", 1.0 + n.mean() * C0 * f / (2 * w_m),
                  dist.k_hbeta, "relative", 1.0 / slices,
                  "the slices' discretisation: the outer slice centre is 1/(2 N) of the face "
                  "from its edge (the tests hold 1/N)")]
    f2, slices2 = 60e-6, 400
    dist2, n2, w_m2 = _slope_case(pair, slices2, TORQUE_PARTIAL, f2)
    k_iso = np.sqrt(2.0 * f2 * n2 * C0 / w_m2)
    q.append(_worst("K_Hbeta per position, part of the face unloaded, against "
                    "sqrt(2 f_Hb c_gamma / (F_m / b)) (worst position)", k_iso,
                    dist2.k_hbeta_position, 2.0 / slices2,
                    "the loaded length is resolved to a slice (the tests hold 2 / N)"))
    inputs = (("pair", "spur z 30/45, m 3 mm, 20 deg, b 20 mm, steel"),
              ("stiffness", f"uniform c0 = {C0 * 1e-9:g} N/(mm um) per tooth pair, nominal "
                            "path, 24 positions"),
              ("linear case", f"f_Hb {f * 1e6:g} um, {TORQUE_LINEAR:g} N m, {slices} slices"),
              ("partial-face case", f"f_Hb {f2 * 1e6:g} um, {TORQUE_PARTIAL:g} N m, "
                                    f"{slices2} slices"))
    return Outcome("ISO 6336-1 face load factor K_Hbeta, its closed form in both regimes",
                   inputs, tuple(q))


def case_iso_6336_2_hertz_pressure(context: Context) -> Outcome:
    """The Hertz pressure at the pitch point in single contact against Z_H Z_E."""
    from pipeline.contact import analytical_compliance
    from pipeline.contact.distribution import load_distribution
    from pipeline.contact.ltca import loaded_mesh_cycle
    from pipeline.contact.options import ContactOptions
    from pipeline.operation import OperatingPoint

    pair = _pair()
    torque = 300.0
    op = OperatingPoint(torque=torque, speed=100.0)
    src = analytical_compliance(pair, op, ContactOptions(tip_contact=False))
    k = int((pair.s_pitch - pair.s_start) // pair.base_pitch)  # this pair on the pitch point
    s0 = pair.s_pitch - k * pair.base_pitch
    cyc = loaded_mesh_cycle(src, torque / pair.pinion.base_radius, None, "weber", [s0])
    if pair.pair_positions(cyc.s0)[1].sum() != 1:
        raise ValueError("the pitch point is not in single contact for this pair")
    dist = load_distribution(cyc, pair, op)
    p1, g = pair.pinion, pair.gear
    e_star = 1.0 / ((1 - p1.material.poisson_ratio**2) / p1.material.youngs_modulus
                    + (1 - g.material.poisson_ratio**2) / g.material.youngs_modulus)
    z_e = math.sqrt(e_star / math.pi)
    a_wt, a_t = pair.operating_pressure_angle, p1.transverse_pressure_angle
    z_h = math.sqrt(2.0 * math.cos(a_wt) / (math.cos(a_t) ** 2 * math.sin(a_wt)))
    u = pair.gear_ratio
    p_iso = z_h * z_e * math.sqrt(torque / p1.reference_radius
                                  / (2 * p1.reference_radius * pair.face_width) * (u + 1) / u)
    reason = "the same closed form written with other data: round-off (tests: 1e-9)"
    q = (Quantity("largest Hertz pressure p_H", "Pa", p_iso, dist.hertz_max.value, "relative",
                  1e-9, reason, ("N/mm^2", 1e-6)),
         Quantity("roll coordinate of the largest pressure (the pitch point)", "m",
                  pair.s_pitch, dist.hertz_max.s, "relative", 1e-12,
                  "the position solved is the pitch point's: round-off (tests: 1e-12)",
                  ("mm", 1e3)),
         Quantity("pinion diameter there (d_w1)", "m", 2 * pair.operating_pitch_radii[0],
                  2 * dist.hertz_max.pinion_radius, "relative", 1e-12,
                  "round-off (tests: 1e-12)", ("mm", 1e3)))
    inputs = (("pair", "spur z 30/45, m 3 mm, 20 deg, b 20 mm, E 200 GPa, nu 0.3"),
              ("load", f"{torque:g} N m on the pinion, Weber's contact, nominal path only "
                       "(ISO's nominal contact: no tip corner shares the load)"))
    return Outcome("ISO 6336-2, nominal contact stress p_H = Z_H Z_E sqrt(F_t / (d_1 b) "
                   "(u + 1) / u) (Z_H zone factor, Z_E elasticity factor)", inputs, q)
