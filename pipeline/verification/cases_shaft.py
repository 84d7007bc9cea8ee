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
from pipeline.verification.model import UM, Convergence, Outcome, Plot, Quantity, Series

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
