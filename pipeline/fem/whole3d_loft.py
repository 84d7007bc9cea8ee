"""The whole 3D gear lofted and cut in OpenCASCADE: the reference mesher.

Before :mod:`pipeline.fem.whole3d` swept the section, whole gears were built this way:
the transverse outline of all ``z`` teeth (the named pieces of
:func:`pipeline.fem.outline2d.outline_pieces`) as spline wires at ``loft_sections``
heights turned by ``theta(z) = s tan(beta) / r (z - b/2)``, lofted through them
(``addThruSections``), a bore cylinder cut out, the faces named by geometry, the
background size of :func:`pipeline.fem.grading3d.tooth_size_field`, then Gmsh's curved
P2 tetrahedra (mid-edge nodes projected on the CAD surfaces, high-order optimisation).
Same surface groups, same grading; kept as the reference the swept mesher is compared
with (tests/test_fem_whole3d.py, ``workflows/benchmarks/bench_mesh3d.py``). It is several
times slower (z 30, b 12 mm: 5.3 s against under 1 s; the breakdown is in
:mod:`pipeline.fem.whole3d`).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.fem.gmsh_session import TetMeshData, extract_tet_mesh, gmsh_session
from pipeline.fem.grading3d import tooth_size_field
from pipeline.fem.loft3d import generate_curved_tets, loft_inputs
from pipeline.fem.mesh_settings import SectorSettings3D, far_teeth
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError


def build_lofted_whole_gear_3d(gear: GearSpec, settings: SectorSettings3D) -> TetMeshData:
    """Loft, cut the bore and mesh the whole gear in Gmsh (module docstring); every tooth
    (``settings.reach`` must leave none out)."""
    if far_teeth(settings, gear.teeth):
        raise InputError(f"sector.reach = {settings.reach}: the lofted whole gear keeps "
                         "every tooth (reach = None)")
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

