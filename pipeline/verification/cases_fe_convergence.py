"""Convergence of the 2D FE tables: the single-tooth structural compliance at the pitch
point of a 3-tooth sector (P2 triangles, plane strain) under mesh refinement.

The structural compliance is the influence coefficient with the Hertz near field removed
(:mod:`pipeline.fem.influence`). Refinement r scales every element size by 1 / r, so the
observed order from three levels r, 2r, 4r is p = log2(|c_2r - c_r| / |c_4r - c_2r|).
A compliance is an energy: its error is the energy norm of the displacement error squared
(Galerkin orthogonality), which converges at twice the energy-norm rate, 4 for P2 on a
smooth solution; the load patch's edges and the sector's corners lower it.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.verification.context import Context
from pipeline.verification.display import PERCENT
from pipeline.verification.model import Convergence, Outcome, Plot, Quantity, Series

SECTOR_GEAR = GearSpec(teeth=30, module=3e-3, pressure_angle=math.radians(20),
                       face_width=0.02, bore_radius=0.03)
"""A standard spur gear: z 30, m 3 mm, 20 deg, b 20 mm, bore 60 mm."""

LAST_CHANGE = 0.02
"""The largest relative change between the two finest levels (the tests' bound)."""
MIN_ORDER = 2.0
"""The smallest observed order accepted (module docstring: twice the energy-norm rate;
2 would be an energy-norm rate of 1, a singularity the mesh does not resolve)."""


def case_fe2d_tooth_compliance_convergence(
        context: Context, refinements: tuple[float, ...] = (1.0, 2.0, 4.0, 8.0)) -> Outcome:
    """Single-tooth structural compliance at the pitch point over mesh refinements: the
    change between the two finest levels and the observed order."""
    from pipeline.cache.folder import Cache
    from pipeline.fem.flank import flank_points
    from pipeline.fem.influence import influence_matrix
    from pipeline.fem.mesh_settings import SectorSettings
    from pipeline.fem.sector2d import sector_mesh_2d

    gear = SECTOR_GEAR
    pts = flank_points(gear, 3, [1], np.array([gear.reference_radius]))
    vals = []
    for r in refinements:
        sec = sector_mesh_2d(gear, SectorSettings.for_gear(gear, teeth=3, refinement=r),
                             cache=Cache.off())  # the study's point is to build each mesh
        vals.append(float(influence_matrix(sec, pts).structural[0, 0]))
    vals_a = np.array(vals)
    changes = np.abs(np.diff(vals_a)) / vals_a[1:]
    ratio = refinements[1] / refinements[0]
    orders = np.log(changes[:-1] / changes[1:]) / math.log(ratio)
    order = float(orders[-1])
    # Richardson: the limit the last two levels extrapolate to at the observed order
    limit = vals_a[-1] + (vals_a[-1] - vals_a[-2]) / (ratio**order - 1.0)
    errors = np.abs(vals_a / limit - 1.0)
    h = 1.0 / np.array(refinements)
    why = ("twice the energy-norm rate (a compliance is an energy): 4 for P2 on a smooth "
           "solution; below 2 the mesh would not resolve a singularity")
    conv = Convergence("relative element size 1 / refinement [-]", tuple(h),
                       "single-tooth structural compliance [m/N]", tuple(vals),
                       tuple(errors), "|c / c_extrapolated - 1| [-] (Richardson)", order,
                       4.0, why)
    q = (Quantity("relative change between the two finest levels", "-", 0.0,
                  float(changes[-1]), "upper_bound", LAST_CHANGE,
                  "the tables' discretisation error must stay far below the 5-20 % the FE "
                  "corrects the analytical compliance by; the tests hold 2 %", PERCENT),
         Quantity("observed order of convergence", "-", MIN_ORDER, order, "lower_bound", 0.0,
                  why))
    plot = Plot("2D FE single-tooth compliance at the pitch point (z 30, 3-tooth sector)",
                "relative element size 1 / refinement [-]", "relative change [-]",
                (Series("|c_h - c_2h| / c_h (successive levels)", h[1:], changes),
                 Series("|c_h / c_extrapolated - 1| (Richardson)", h, errors, "-s"),
                 Series("h^4 (smooth solution)", h[1:], h[1:] ** 4 * changes[0] / h[1] ** 4,
                        "--"),
                 Series(f"h^{MIN_ORDER:g} (lowest accepted)", h[1:],
                        h[1:] ** MIN_ORDER * changes[0] / h[1] ** MIN_ORDER, ":")),
                loglog=True)
    inputs = (("gear", "z 30, m 3 mm, 20 deg, b 20 mm, bore 60 mm, steel"),
              ("model", "3-tooth sector, P2 triangles, plane strain, bore clamped"),
              ("load", "unit patch load at the pitch radius, middle tooth"),
              ("refinements", ", ".join(f"{r:g}" for r in refinements)))
    return Outcome("convergence study (Richardson extrapolation; rates per Strang & Fix "
                   "1973)", inputs, q, conv, (plot,),
                   notes=f"Observed orders between successive triples: "
                         f"{', '.join(f'{o:.2f}' for o in orders)}.")


def case_fe2d_tooth_compliance_convergence_fine(context: Context) -> Outcome:
    """The same study with a fifth, finer level (refinement 16)."""
    return case_fe2d_tooth_compliance_convergence(context, (1.0, 2.0, 4.0, 8.0, 16.0))
