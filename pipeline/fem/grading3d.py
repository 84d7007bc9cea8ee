"""Element-size grading of 3D gear meshes: fine on the loaded teeth, coarse elsewhere.

Shared by the sectors of :mod:`pipeline.fem.sector3d` and the whole gears of
:mod:`pipeline.fem.whole3d`; called inside their Gmsh session (:mod:`pipeline.fem.gmsh_session`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from pipeline.fem.gmsh_session import size_from_fields

if TYPE_CHECKING:
    from pipeline.fem.mesh_settings import SectorSettings3D


def tooth_size_field(gmsh, settings: SectorSettings3D, groups: dict[str, list[int]],
                     root_radius: float, extent: float | None = None) -> None:
    """Background size (Gmsh fields, their minimum): ``size_flank`` on the sides of the
    loaded teeth (``size_near`` on those of the ``near`` teeth) growing linearly to
    ``size_body`` a distance ``grading`` away (Distance + Threshold), and, if some teeth
    are neither, ``size_tooth`` outside
    the root circle (``root_radius``, m) growing to ``size_body`` at ``grading`` below
    it (a radial MathEval + Threshold: a Distance field to the sides of every tooth of
    a whole gear made Gmsh's 1D meshing take 30 s). Gmsh samples the loaded sides at
    20 points per parametric direction for the distances, or, given the largest
    surface ``extent`` (m), at about two points per flank element (a coarse sampling
    leaves the fine zone ragged along a wide face)."""
    loaded = range(settings.teeth) if settings.loaded is None else settings.loaded
    fld = gmsh.model.mesh.field
    fields = []
    for teeth, size in ((loaded, settings.size_flank),
                        (settings.near, settings.size_near or settings.size_flank)):
        if not teeth:
            continue
        dist = fld.add("Distance")
        fld.setNumbers(dist, "SurfacesList", [s for k in teeth for side in ("right", "left")
                                              for s in groups[f"{side}{k}"]])
        if extent is not None:
            n = int(min(400, max(20, math.ceil(2 * extent / size))))
            fld.setNumber(dist, "Sampling", n)
        fields.append((dist, size, 0.25 * settings.size_flank))
    if len(loaded) + len(settings.near) < settings.teeth:
        depth = fld.add("MathEval")
        fld.setString(depth, "F", f"{root_radius!r} - Sqrt(x * x + y * y)")
        fields.append((depth, settings.size_tooth or settings.size_flank, 0.0))
    thresholds = []
    for f, size, d_min in fields:
        thr = fld.add("Threshold")
        fld.setNumber(thr, "InField", f)
        fld.setNumber(thr, "SizeMin", size)
        fld.setNumber(thr, "SizeMax", settings.size_body)
        fld.setNumber(thr, "DistMin", d_min)
        fld.setNumber(thr, "DistMax", settings.grading)
        thresholds.append(thr)
    size_from_fields(gmsh, thresholds)
    gmsh.option.setNumber("Mesh.MeshSizeMax", settings.size_body)
