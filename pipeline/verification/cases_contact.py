"""Cases of the contact layer: Hertz line contact (a textbook example), Weber's local
approach against the half-plane solution by quadrature, and Harris (1958)'s light-load
transmission error of tip-relieved spur gears.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.contact.source import UniformSlices
from pipeline.geometry import GearPair, GearSpec, Material
from pipeline.verification.context import Context
from pipeline.verification.display import MM, N_PER_MM2, UM
from pipeline.verification.model import Outcome, Plot, Quantity, Series

HERTZ_CYLINDERS = {"force_N": 250.0, "length_m": 0.02, "d1_m": 0.02, "d2_m": 0.03,
                   "half_width_m": 2.8976e-5, "max_pressure_Pa": 274.65e6}
"""Two steel cylinders (E 207 GPa, nu 0.3) and the half-width b and maximum pressure
p_max worked out by hand from Shigley's formulas, to the digits printed."""
STEEL_207 = Material(youngs_modulus=2.07e11, poisson_ratio=0.3)


def case_hertz_cylinders(context: Context) -> Outcome:
    """Half-width and maximum pressure of two steel cylinders in line contact."""
    from pipeline.contact import (
        contact_modulus,
        effective_radius,
        hertz_half_width,
        hertz_max_pressure,
    )

    F, length, d1, d2 = (HERTZ_CYLINDERS[k] for k in ("force_N", "length_m", "d1_m", "d2_m"))
    R = effective_radius(d1 / 2, d2 / 2)
    es = contact_modulus(STEEL_207, STEEL_207)
    reason = "the reference is printed to 5 digits: half a unit of the last is 2e-5; 1e-4"
    quantities = (
        Quantity("contact half-width b", "m", HERTZ_CYLINDERS["half_width_m"],
                 float(hertz_half_width(F / length, R, es)), "relative", 1e-4, reason, MM),
        Quantity("maximum pressure p_max", "Pa", HERTZ_CYLINDERS["max_pressure_Pa"],
                 float(hertz_max_pressure(F / length, R, es)), "relative", 1e-4, reason,
                 N_PER_MM2))
    inputs = (("load F over length l", f"{F:g} N over {length * 1e3:g} mm"),
              ("diameters", f"{d1 * 1e3:g}, {d2 * 1e3:g} mm"), ("E, nu", "207 GPa, 0.3"))
    return Outcome("Budynas & Nisbett, Shigley's Mechanical Engineering Design, "
                   "\"Contact stresses\": b = sqrt(2F/(pi l) [2 (1 - nu^2)/E] / (1/d1 + "
                   "1/d2)), p_max = 2F/(pi b l)", inputs, quantities)


def half_plane_approach(w: float, a: float, h: float, E: float, nu: float) -> float:
    """Approach (m) of the surface to a point at depth ``h`` (m) on the axis of a
    half-plane (E in Pa, nu) under a Hertz pressure of half-width ``a`` (m) and load ``w``
    per length (N/m): the Flamant line-load stresses (Johnson 1985, Contact Mechanics,
    eq. 2.15) integrated over the pressure give sigma_z and sigma_x on the axis; the
    plane-strain strain eps_z = (1 + nu) / E ((1 - nu) sigma_z - nu sigma_x) is
    integrated from 0 to h by adaptive quadrature."""
    from scipy import integrate

    p0 = 2 * w / (math.pi * a)

    def p(s):
        return p0 * math.sqrt(max(0.0, 1 - (s / a) ** 2))

    def strain(z):
        sz = -2 / math.pi * integrate.quad(lambda s: p(s) * z**3 / (s * s + z * z) ** 2,
                                           -a, a, limit=200, points=[0.0])[0]
        sx = -2 / math.pi * integrate.quad(lambda s: p(s) * s * s * z / (s * s + z * z) ** 2,
                                           -a, a, limit=200, points=[0.0])[0]
        return (1 + nu) / E * ((1 - nu) * sz - nu * sx)

    return -integrate.quad(strain, 0.0, h, limit=400, points=[a, 5 * a])[0]


WEBER_RATIOS = (10.0, 20.0, 40.0, 80.0, 160.0)
"""Depths h / a at which the approach is compared."""


def case_weber_half_plane(context: Context) -> Outcome:
    """Weber-Banaschek's per-body approach against half-plane elasticity by quadrature:
    the difference falls as (a/h)^2 with the coefficient 1/4 + nu / (8 (1 - nu))."""
    from pipeline.contact import HertzLineContact, contact_modulus, hertz_half_width

    E, nu, w, R = STEEL_207.youngs_modulus, STEEL_207.poisson_ratio, 3.0e5, 0.02
    a = float(hertz_half_width(w, R, contact_modulus(STEEL_207, STEEL_207)))
    unit = 2 * w * (1 - nu**2) / (math.pi * E)
    ratios = np.array(WEBER_RATIOS)
    model, exact = [], []
    for r in ratios:
        # one body of a symmetric pair: the model's approach for h1 = h2 = h is twice it
        hz = HertzLineContact(1.0, 2 * R, 2 * R, r * a, r * a, STEEL_207, STEEL_207)
        model.append(float(hz.approach(w)) / 2)
        exact.append(half_plane_approach(w, a, r * a, E, nu))
    errs = (np.array(model) - np.array(exact)) / unit
    order = float(np.polyfit(np.log(1 / ratios), np.log(np.abs(errs)), 1)[0])
    coef = 0.25 + nu / (8 * (1 - nu))
    quantities = [Quantity("order of the difference in a/h", "-", 2.0, order, "absolute",
                           0.01, "the next term is O((a/h)^4): it bends the fit by < 0.01")]
    for r, e in zip(ratios[1:], errs[1:], strict=True):
        quantities.append(Quantity(f"(model - exact) (h/a)^2 at h/a = {r:g}", "-", -coef,
                                   e * r**2, "relative", 1e-3,
                                   "the O((a/h)^4) term: < 0.1 % from h/a = 20 on"))
    plot = Plot("Weber's approach minus the half-plane (Flamant) solution",
                "depth h / half-width a [-]",
                "|model - exact| / (2 w (1 - nu^2) / (pi E)) [-]",
                (Series("Weber-Banaschek against the quadrature", ratios, np.abs(errs)),
                 Series(f"{coef:.4f} (a/h)^2 (expansion)", ratios, coef / ratios**2, "--")),
                loglog=True)
    inputs = (("load per length w", f"{w:g} N/m"), ("radius of each body", f"{2 * R * 1e3:g} "
                                                    "mm"),
              ("E, nu", "207 GPa, 0.3"), ("h / a", ", ".join(f"{r:g}" for r in ratios)))
    return Outcome("Johnson (1985), Contact Mechanics, eq. 2.15 (Flamant), quadrature; "
                   "expansion of the exact on-axis result: model - exact = -(a/h)^2 (1/4 + "
                   "nu/(8(1-nu))) 2w(1-nu^2)/(pi E)", inputs, tuple(quantities), plots=(plot,))


HARRIS = {"relief_m": 10e-6, "c0_N_per_m2": 1.4e10, "load_N": 1.0, "positions": 400,
          "length_shares": (0.55, 0.75, 1.0)}
"""Linear tip relief C on both gears over L = share x D (D = g_alpha - p_b, the
double-contact length), uniform stiffness c0, a light load."""


def _demo_gear(name: str) -> GearSpec:
    return GearSpec(teeth=50, name=name, module=3e-3, pressure_angle=math.radians(20),
                    face_width=0.02, bore_radius=0.021,
                    material=Material(youngs_modulus=2.0e11, poisson_ratio=0.3))


def case_harris_light_load(context: Context) -> Outcome:
    """Light-load transmission error of the demo pair with linear tip relief on both gears
    against Harris's C (1 - D / (2 L))."""
    from pipeline.contact.ltca import loaded_mesh_cycle
    from pipeline.contact.modifications import GearModification, ProfileModification
    from pipeline.contact.separations import FlankModifications

    pair = GearPair(_demo_gear("pinion"), _demo_gear("gear"))
    d = pair.path_length - pair.base_pitch
    c, c0, load, n = (HARRIS[k] for k in ("relief_m", "c0_N_per_m2", "load_N", "positions"))
    elastic = load / (c0 * pair.face_width)
    quantities, series = [], []
    for i, share in enumerate(HARRIS["length_shares"]):
        length = share * d
        relief = GearModification(profile=ProfileModification(tip_relief=c,
                                                               tip_relief_length=length))
        mods = FlankModifications(pinion_flank=relief, gear_flank=relief)
        cyc = loaded_mesh_cycle(UniformSlices(pair, 1, c0), load, mods, "none", n)
        harris = c * (1.0 - d / (2.0 * length))
        step = (c / length) * pair.base_pitch / n  # sampling: the peak is a tent of slope C/L
        quantities.append(Quantity(f"TE peak to peak, L = {share:g} D", "m", harris,
                                   float(np.ptp(cyc.transmission_error)), "absolute",
                                   step + 2 * elastic,
                                   f"the sampling of {n} positions ({step * 1e9:.2f} nm: the "
                                   f"peak is a tent of slope C/L) plus twice the elastic part "
                                   f"P / (c0 b) ({elastic * 1e9:.2f} nm)", UM))
        x = (cyc.s0 - pair.s_start) / pair.base_pitch
        series.append(Series(f"L = {share:g} D", x, cyc.transmission_error * 1e6, f"C{i}-"))
        series.append(Series(f"Harris p-p, L = {share:g} D", (0.0, 1.0),
                             (harris * 1e6, harris * 1e6), f"C{i}:"))
    plot = Plot("Light-load TE with linear tip relief C = 10 um on both gears",
                "position in the mesh cycle (s0 - s_start) / p_b [-]",
                "transmission error [um]", tuple(series))
    inputs = (("pair", "z 50/50, m 3 mm, 20 deg, b 20 mm (the demo pair)"),
              ("tip relief C, linear, both gears", f"{c * 1e6:g} um over L = "
               + ", ".join(f"{s:g}" for s in HARRIS["length_shares"])
               + f" D (D = {d * 1e3:.3f} mm)"),
              ("stiffness c0, load", f"{c0:g} N/m^2 uniform, {load:g} N (light)"))
    return Outcome("Harris (1958), Proc. IMechE 172: light-load TE p-p = C (1 - D / (2 L)) "
                   "for D/2 <= L <= D", inputs, tuple(quantities), plots=(plot,))
