"""Whole 3D gear bodies: all teeth, the body down to the bore, the full face width.

Geometry. The transverse outline of all ``z`` teeth (involute, trochoidal fillet,
root and tip circles of :mod:`pipeline.geometry.profile`, split into the named
pieces of :func:`pipeline.fem.outline2d.outline_pieces`) is lofted along the helix
exactly as the sectors of :mod:`pipeline.fem.sector3d` are (section at ``z`` turned
by ``theta(z) = s tan(beta) / r (z - b/2)``), giving a toothed solid; a cylinder of
the bore radius (:func:`pipeline.fem.outline2d.inner_radius`) is cut out of it. So
tooth ``k`` at mid-face sits where the 2D whole gear of ``sector2d`` (``teeth = z``)
puts it, and the flank grids, load patches and influence routine of the sectors
apply unchanged (a whole gear is a "sector" of ``teeth = z`` teeth without cut faces).

Surface groups: ``right{k}`` / ``left{k}`` (k = 0 .. z-1), ``bore``, ``end0`` (z = 0)
and ``end1`` (z = b). Boundary conditions are those of the 2D whole gear
(:func:`pipeline.fem.influence.constrained_dofs`): the bore is clamped; nothing else.

Mesh. One P2 tetrahedral mesh graded by :func:`pipeline.fem.grading3d.tooth_size_field`:
``size_flank`` on both sides of the *loaded* teeth (those whose flanks carry grid
points), ``size_tooth`` on the other teeth, growing to ``size_body`` in the rim,
web and far teeth (:meth:`~pipeline.fem.mesh_settings.SectorSettings3D.whole_gear`).
The unknowns then scale with the loaded teeth, not with ``z`` (defaults: flank cells
m_n / (3 refinement), 2 m_n on the other teeth, 5 m_n in the body).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.fem.gmsh_session import TetMeshData, extract_tet_mesh, gmsh_session
from pipeline.fem.grading3d import tooth_size_field
from pipeline.fem.loft3d import generate_curved_tets, loft_inputs
from pipeline.fem.mesh_settings import SectorSettings3D
from pipeline.geometry.gear import GearSpec


def build_whole_gear_mesh_3d(gear: GearSpec, settings: SectorSettings3D) -> TetMeshData:
    """Loft, cut the bore and mesh the whole gear in Gmsh (module docstring)."""
    r_in, b, rate, pieces = loft_inputs(gear, settings, gear.teeth)
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        wires = [_outline_wire(occ, pieces, rate * (z - 0.5 * b), z)
                 for z in np.linspace(0.0, b, settings.loft_sections)]
        solid = occ.addThruSections(wires, makeSolid=True, makeRuled=False)[0][1]
        bore = occ.addCylinder(0.0, 0.0, -0.1 * b, 0.0, 0.0, 1.2 * b, r_in)
        out, _ = occ.cut([(3, solid)], [(3, bore)])
        vol = out[0][1]
        occ.synchronize()
        groups = _classify(gmsh, vol, pieces, r_in, b, rate)
        missing = [f"{side}{k}" for k in range(gear.teeth) for side in ("right", "left")
                   if not groups.get(f"{side}{k}")]
        missing += [n for n in ("bore", "end0", "end1") if not groups.get(n)]
        if missing:
            raise RuntimeError(f"whole3d: surfaces not found after lofting: {missing[:6]}")
        tooth_size_field(gmsh, settings, groups, gear.root_radius, extent=b)
        generate_curved_tets(gmsh)
        return extract_tet_mesh(gmsh, 2, groups, {"gear": [vol]})


def _outline_wire(occ, pieces, rot: float, z: float) -> int:
    """Closed wire of the whole outline turned by ``rot`` (rad) at height ``z`` (m)."""
    c, s = math.cos(rot), math.sin(rot)

    def point(xy) -> int:
        return occ.addPoint(c * xy[0] - s * xy[1], s * xy[0] + c * xy[1], z)

    first = point(pieces[0][1][0])
    prev, curves = first, []
    for i, (_, seg) in enumerate(pieces):
        last = i == len(pieces) - 1  # the outline closes on its first point
        tags = [prev] + [point(p) for p in seg[1:-1 if last else None]] + ([first] if last else [])
        curves.append(occ.addSpline(tags) if len(tags) > 2 else occ.addLine(*tags))
        prev = tags[-1]
    return occ.addWire(curves, checkClosed=True)


def _classify(gmsh, vol: int, pieces, r_in: float, b: float, rate: float
              ) -> dict[str, list[int]]:
    """Name the boundary surfaces: end caps by their axial extent, the bore by its radius,
    lofted faces by the nearest named outline piece at mid-face."""
    ref = np.vstack([seg for _, seg in pieces])
    ref_names = [name for name, seg in pieces for _ in range(len(seg))]
    groups: dict[str, list[int]] = {}
    for _, s in gmsh.model.getBoundary([(3, vol)], oriented=False):
        _, _, z0, _, _, z1 = gmsh.model.getBoundingBox(2, s)
        lo, hi = gmsh.model.getParametrizationBounds(2, s)
        x, y, z = gmsh.model.getValue(2, s, 0.5 * (np.asarray(lo) + np.asarray(hi)))
        if z1 - z0 < 0.5 * b:
            name = "end0" if z0 + z1 < b else "end1"
        elif abs(math.hypot(x, y) - r_in) < 1e-6 * r_in:
            name = "bore"
        else:
            th = -rate * (z - 0.5 * b)
            ct, st = math.cos(th), math.sin(th)
            p = np.array([ct * x - st * y, st * x + ct * y])
            name = ref_names[int(np.argmin(np.sum((ref - p) ** 2, axis=1)))]
        groups.setdefault(name, []).append(s)
    return groups


def whole_gear_area(gear: GearSpec, points: int, r_in: float) -> float:
    """Exact area (m^2) of the transverse section: the outline polyline of ``points``
    involute points per flank minus the bore disc of radius ``r_in``."""
    from pipeline.geometry.profile import gear_outline

    x, y = gear_outline(gear, points=points).T
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)) - math.pi * r_in**2
