"""Cases of the shaft beam model (:mod:`pipeline.shaft.beam`): a simply supported hollow
shaft under a central load, and the convergence of its first torsional frequency.

The element is the exact Timoshenko element (static condensation of the exact solution),
so nodal deflections are exact for loads at nodes: the tolerance is round-off.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.geometry.gear import Material
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Convergence, Outcome, Plot, Quantity, Series

SIMPLY_SUPPORTED = {"length_m": 0.4, "outer_m": 0.06, "inner_m": 0.03,
                    "force_N": (2000.0, -3000.0)}
"""The hollow shaft on two bearings, loaded at mid-span in x and y."""


def _layout(segments, *, gear, width, bearings, torque):
    from pipeline.shaft.layout import ShaftLayout, ShaftSegment

    segs, start = [], 0.0
    for length, outer, inner in segments:
        segs.append(ShaftSegment(start, start + length, outer, inner))
        start += length
    return ShaftLayout(segments=tuple(segs), gear_position=gear, seat_width=width,
                       bearings=tuple(bearings), torque_position=torque, hub="integral",
                       material=Material())


def case_simply_supported_shaft(context: Context) -> Outcome:
    """Mid-span deflection F L^3 / (48 E I) + F L / (4 kappa G A) in both planes."""
    from pipeline.shaft.beam import BeamShaft
    from pipeline.shaft.layout import Bearing
    from pipeline.shaft.model import PointLoad
    from pipeline.shaft.timoshenko import shear_coefficient

    mat = Material()
    L, D, d = (SIMPLY_SUPPORTED[k] for k in ("length_m", "outer_m", "inner_m"))
    fx, fy = SIMPLY_SUPPORTED["force_N"]
    lay = _layout([(L, D, d)], gear=L / 2, width=0.04, torque=L,
                  bearings=[Bearing(0.0, axial=True), Bearing(L)])
    ei = mat.youngs_modulus * math.pi / 64.0 * (D**4 - d**4)
    kga = float(shear_coefficient(mat.poisson_ratio, D, d)) * mat.shear_modulus \
        * math.pi / 4.0 * (D**2 - d**2)
    sol = BeamShaft(lay).solve([PointLoad(L / 2, (fx, fy, 0.0))])
    i = int(np.argmin(np.abs(sol.z - L / 2)))
    unit = L**3 / (48 * ei) + L / (4 * kga)
    reason = "the exact Timoshenko element is exact at its nodes: round-off only"
    quantities = (Quantity("mid-span deflection u_x", "m", fx * unit, sol.displacement[i, 0],
                           "relative", 1e-9, reason, UM),
                  Quantity("mid-span deflection u_y", "m", fy * unit, sol.displacement[i, 1],
                           "relative", 1e-9, reason, UM),
                  Quantity("bearing reaction R_y", "N", -fy / 2, sol.reactions[0, 1],
                           "relative", 1e-12, "statics: round-off only"))
    inputs = (("span, outer / bore diameter", f"{L * 1e3:g} mm, {D * 1e3:g} / {d * 1e3:g} mm"),
              ("load at mid-span F_x, F_y", f"{fx:g} N, {fy:g} N"),
              ("E, nu", f"{mat.youngs_modulus / 1e9:g} GPa, {mat.poisson_ratio:g}"),
              ("shear coefficient", "Cowper (1966), hollow circle"))
    return Outcome("Timoshenko & Gere, Mechanics of Materials: F L^3 / (48 E I), shear term "
                   "F L / (4 kappa G A) by the unit-load method", inputs, quantities)


def _torsional_frequency(model, near: float) -> float:
    """The torsion-dominated natural frequency (rad/s) nearest ``near``, torque point free
    (shift-invert Lanczos)."""
    import scipy.sparse.linalg as spla

    b = model.basis(hold_torque=False)
    k = (b.T @ model.stiffness_matrix() @ b).tocsc()
    m = (b.T @ model.mass_matrix([]) @ b).tocsc()
    w2, v = spla.eigsh(k, 6, m, sigma=near**2)
    shapes = (b @ v).reshape(-1, 6, v.shape[1])
    twist = np.linalg.norm(shapes[:, 5, :], axis=0) / np.linalg.norm(shapes, axis=(0, 1))
    torsion = np.flatnonzero(twist > 0.99)
    return math.sqrt(w2[torsion[np.argmin(np.abs(w2[torsion] - near**2))]])


def free_free_torsion_frequency(material: Material, length: float) -> float:
    """First elastic torsional frequency of a free-free uniform shaft, omega = pi
    sqrt(G / rho) / L (rad/s): the wave equation's exact value."""
    return math.pi * math.sqrt(material.shear_modulus / material.density) / length


def case_torsional_frequency_convergence(context: Context,
                                         elements: tuple[int, ...] = (32, 64, 96)) -> Outcome:
    """First free-free torsional frequency of a bare shaft, omega = pi sqrt(G / rho) / L,
    on uniform meshes: the fitted rate of its error against 2."""
    from pipeline.shaft.beam import BeamShaft
    from pipeline.shaft.layout import Bearing

    mat = Material()
    L, D = 0.5, 0.03
    lay = _layout([(L, D, 0.0)], gear=L / 16, width=L / 8, torque=L,
                  bearings=[Bearing(L / 4, axial=True), Bearing(3 * L / 4)])
    exact = free_free_torsion_frequency(mat, L)
    hs, vals = [], []
    for n in elements:
        hs.append(L / n)
        vals.append(_torsional_frequency(BeamShaft(lay, element_length=L / n), exact))
    errs = [abs(v / exact - 1.0) for v in vals]
    rate = float(np.polyfit(np.log(hs), np.log(errs), 1)[0])
    why = ("linear twist elements with consistent mass converge at O(h^2) in frequency "
           "(Strang & Fix 1973, ch. 6); 0.01 for the fit (measured 2.0001)")
    conv = Convergence("element length h [m]", tuple(hs), "first torsional frequency [rad/s]",
                       tuple(vals), tuple(errs), "|omega_h / omega - 1| [-]", rate, 2.0, why)
    quantities = (Quantity("fitted convergence rate", "-", 2.0, rate, "absolute", 0.01, why),
                  Quantity("frequency on the finest mesh", "rad/s", exact, vals[-1],
                           "relative", 1e-4, "O(h^2) error of the finest mesh (4.5e-5)"))
    plot = Plot("Shaft torsion: error of the first free-free frequency",
                "element length h [m]", "relative error [-]",
                (Series("beam FE", hs, errs),
                 Series("h^2", hs, np.array(hs) ** 2 * errs[0] / hs[0] ** 2, "--")),
                loglog=True)
    inputs = (("length, diameter", f"{L * 1e3:g} mm, {D * 1e3:g} mm (solid)"),
              ("G, rho", f"{mat.shear_modulus / 1e9:.4g} GPa, {mat.density:g} kg/m^3"),
              ("elements", ", ".join(str(n) for n in elements) + " (uniform)"))
    return Outcome("free-free shaft in torsion: omega_1 = pi sqrt(G / rho) / L (wave "
                   "equation, exact)", inputs, quantities, conv, (plot,))


FE3D_REFINEMENTS = (0.5, 0.75, 1.0, 1.25, 1.5)
"""Mesh refinements of the 3D shaft study (5k to 46k unknowns)."""


def timoshenko_central_flexibility(span: float, d: float) -> float:
    """Central deflection per unit load (m/N) of a simply supported solid Timoshenko beam,
    shear coefficient 6 (1 + nu) / (7 + 6 nu) (Cowper 1966, solid circle)."""
    mat = Material()
    nu = mat.poisson_ratio
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    inertia, area = math.pi * d**4 / 64, math.pi * d**2 / 4
    a = 0.5 * span
    return 0.5 * a**3 / (3 * mat.youngs_modulus * inertia) \
        + 0.5 * a / (kappa * mat.shear_modulus * area)


def case_shaft_fe3d_convergence(context: Context,
                                refinements: tuple[float, ...] = FE3D_REFINEMENTS) -> Outcome:
    """The 3D shaft superelement (P2 tetrahedra, integral seat): central flexibility over
    mesh refinements, its extrapolated limit against Timoshenko's beam and its rate."""
    from scipy.optimize import curve_fit

    from pipeline.cache.folder import Cache
    from pipeline.shaft.fe3d import Fe3dShaft
    from pipeline.shaft.fe3d_plan import Fe3dSettings
    from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment

    d, span, seat = 0.04, 0.2, 0.02
    layout = ShaftLayout((ShaftSegment(0.0, 0.24, d),), 0.12, seat,
                         (Bearing(0.02, axial=True), Bearing(0.22)), 0.23, hub="integral")
    c = np.array([Fe3dShaft(layout, Fe3dSettings(refinement=r), cache=Cache.off())
                  .flexibility(np.array([0.12]))[1, 1] for r in refinements])
    h = d / 4 / np.array(refinements)
    scale = c[-1]
    (a, k, p), _ = curve_fit(lambda x, a, k, p: a - k * x**p, h / h[0], c / scale,
                             p0=(1.01, 0.05, 1.5), maxfev=20000)
    c_inf = a * scale
    errors = np.abs(c_inf - c) / c_inf
    rate = float(np.polyfit(np.log(h), np.log(np.abs(c_inf - c)), 1)[0])
    beam = timoshenko_central_flexibility(span, d)
    why = ("measured 2.2; a P2 displacement model's deflection under a distributed load "
           "converges from below at up to h^4 on a smooth solution, the edges of the loaded "
           "ring and of the bearing bands lower it; the tests' bracket is 1.5 to 3")
    q = (Quantity("observed rate (lower end)", "-", 1.5, rate, "lower_bound", 0.0, why),
         Quantity("observed rate (upper end)", "-", 3.0, rate, "upper_bound", 0.0, why),
         Quantity("extrapolated central flexibility", "m/N", beam, c_inf, "relative", 5e-3,
                  "Timoshenko's beam takes the bearing bands and the loaded ring (10 and 4 mm "
                  "wide) as points: measured +0.27 %", ("um/kN", 1e9)),
         Quantity("finest mesh against the extrapolated value", "-", 0.0, float(errors[-1]),
                  "upper_bound", 1e-3, "the finest level's discretisation error (the tests "
                  "hold 0.1 %)", ("%", 100.0)))
    conv = Convergence("element size d / (4 refinement) [m]", tuple(h),
                       "central flexibility [m/N]", tuple(c), tuple(errors),
                       "|c / c_extrapolated - 1| [-]", rate, math.nan, why)
    plot = Plot("3D shaft superelement: central flexibility against the mesh",
                "element size [m]", "|c / c_extrapolated - 1| [-]",
                (Series("P2 tetrahedra, integral seat", h, errors),
                 Series(f"h^{rate:.2f} (fitted)", h, errors[-1] * (h / h[-1]) ** rate, "--")),
                loglog=True)
    inputs = (("shaft", f"solid, d {d * 1e3:g} mm, 240 mm long; bearings at 20 and 220 mm "
                        "(10 mm bands), load at mid-span on a 4 mm ring"),
              ("refinements", ", ".join(f"{r:g}" for r in refinements)),
              ("E, nu", "steel defaults of pipeline.geometry.Material"))
    return Outcome("Timoshenko & Gere, Mechanics of Materials: F L^3 / (48 E I) + F L / (4 kappa "
                   "G A), kappa from Cowper (1966)", inputs, q, conv, (plot,))
