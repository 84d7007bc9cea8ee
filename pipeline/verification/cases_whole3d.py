"""Case of the 3D whole-gear FE model (:mod:`pipeline.fem.whole3d`) at its plane-strain
limit.

A spur gear with sliding end faces (u_z = 0) under a load uniform across its face *is* a
plane-strain problem, at any face width: its approach per unit line load equals the 2D
plane-strain whole gear's. The 3D model is the coarse whole gear (z 30, m 3 mm, b 6 mm,
bore 30 mm; refinement 0.6, 20k unknowns), loaded on tooth 15 at the pitch circle by a
row of 7 cos^2 patches across the face spaced by their half-width c = b / 6 (a partition
of unity: a uniform line load); the 2D reference is the plane-strain whole gear at
refinement 2 (0.26M unknowns) with the same patch. The coarse 3D mesh is stiffer than its
limit, most at the loaded patch (c = 1 mm under flank cells of 1.7 mm; it converges,
4.1 / 1.8 / 1.0 % at refinement 0.6 / 1 / 1.6), less for the neighbours (the rim coupling
through the body).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.verification.context import Context
from pipeline.verification.model import Outcome, Quantity

LOADED = (14, 15, 16)
"""The loaded tooth 15 and its neighbours."""
PATCHES = 7


def _gear() -> GearSpec:
    return GearSpec(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.015,
                    face_width=6e-3)


def case_whole3d_plane_strain(context: Context) -> Outcome:
    """Approach of teeth 14, 15, 16 per unit line load on tooth 15, 3D with sliding ends
    over the 2D plane-strain whole gear."""
    from pipeline.cache.folder import Cache
    from pipeline.fem.flank import flank_points
    from pipeline.fem.flank_grid import flank_grid
    from pipeline.fem.influence import influence_matrix
    from pipeline.fem.mesh_settings import SectorSettings, SectorSettings3D
    from pipeline.fem.sector2d import sector_mesh_2d
    from pipeline.fem.sector3d import sector_mesh_3d

    gear = _gear()
    b = gear.face_width
    c = b / (PATCHES - 1)
    sec = sector_mesh_3d(gear, SectorSettings3D.whole_gear(gear, LOADED, 0.6),
                         cache=context.cache)
    pts = flank_grid(sec, LOADED, [gear.reference_radius], np.linspace(0.0, b, PATCHES))
    g3 = influence_matrix(sec, pts, patch_half_width=c, ends="sliding")
    w = np.full(PATCHES, c)
    w[[0, -1]] *= 0.5  # the end patches are cut in half by the end faces
    rows = np.arange(3) * PATCHES + PATCHES // 2
    load = PATCHES + np.arange(PATCHES)
    fe3 = g3.fe[np.ix_(rows, load)] @ w
    st3 = g3.structural[np.ix_(rows, load)] @ w
    sec2 = sector_mesh_2d(gear, SectorSettings.for_gear(gear, gear.teeth, 2.0),
                          cache=Cache.off())
    g2 = influence_matrix(sec2, flank_points(gear, gear.teeth, LOADED,
                                             [gear.reference_radius] * 3),
                          patch_half_width=c, kind="plane_strain")
    ratio = fe3 / g2.fe[:, 1]
    ratio_st = st3[1] / g2.structural[1, 1]
    above = ("above 1.005 the 3D model would be softer than its exact limit (a P2 "
             "displacement model is stiff)")
    near = ("the coarse mesh's stiffening through the body, measured 0.989 and 0.993: "
            "0.98")
    loaded_why = ("the coarse mesh's stiffening at the loaded patch (c = 1 mm under 1.7 mm "
                  "flank cells; converges, 4.1 / 1.8 / 1.0 % at refinement 0.6 / 1 / 1.6), "
                  "measured 0.959 (FE), 0.951 (structural): 0.93")
    q = []
    for name, value, low, why in (("tooth 14 (neighbour), FE", ratio[0], 0.98, near),
                                  ("tooth 15 (loaded), FE", ratio[1], 0.93, loaded_why),
                                  ("tooth 15 (loaded), structural", ratio_st, 0.93, loaded_why),
                                  ("tooth 16 (neighbour), FE", ratio[2], 0.98, near)):
        q += [Quantity(f"3D / 2D plane strain, {name} (lower end)", "-", low, float(value),
                       "lower_bound", 0.0, why),
              Quantity(f"3D / 2D plane strain, {name} (upper end)", "-", 1.005, float(value),
                       "upper_bound", 0.0, above)]
    inputs = (("gear", "spur z 30, m 3 mm, 20 deg, b 6 mm, bore 30 mm"),
              ("3D", "whole gear, refinement 0.6 (20k unknowns), end faces sliding (u_z = 0)"),
              ("load", f"{PATCHES} cos^2 patches across the face on tooth 15 at the pitch "
                       f"circle, half-width {c * 1e3:g} mm, trapezoidal weights"),
              ("2D", "plane-strain whole gear, refinement 2 (0.26M unknowns), same patch"))
    return Outcome("exact: a spur gear with sliding end faces under a load uniform across "
                   "its face is in plane strain; the 2D plane-strain whole gear evaluates it",
                   inputs, tuple(q))
