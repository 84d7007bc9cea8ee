"""Gmsh meshes of coaxial bodies: quadratic (curved) tetrahedra with named surfaces.

Each segment is built as an OpenCASCADE solid - a cylinder, or a helical toothed
ring lofted through rotated copies of the transverse outline - the bore is cut,
and all segments are fragmented together so that the mesh is conforming across
the interfaces. Surfaces are named ``"<segment>:outer"`` (the lateral surface:
the tooth surface, or the cylinder) and ``"end:left"`` / ``"end:right"`` (the end
faces of the whole body); volumes carry the segment names.

With ``order = 2`` Gmsh places the mid-edge nodes on the true (curved) geometry,
so a cylinder's volume and polar moment are represented to O(h^4) rather than
by the inscribed polygon of straight-sided elements.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.fem.gmsh_session import TetMeshData, extract_tet_mesh, gmsh_session
from pipeline.fem.groove.body import CoaxialBody, Segment
from pipeline.fem.groove.outline import tooth_outline
from pipeline.validation import check_int_range, check_positive, check_range


@dataclass(frozen=True)
class MeshSettings:
    """Mesh controls.

    Attributes
    ----------
    size : largest element edge in m.
    order : geometric and displacement order (2: curved quadratic tetrahedra).
    curvature_points : elements per 2 pi of curvature (Gmsh MeshSizeFromCurvature).
    min_size_factor : smallest edge as a fraction of ``size`` (limits curvature refinement).
    tooth_size_factor : edge on tooth surfaces as a fraction of the normal module.
    loft_sections : transverse sections the helical teeth are lofted through.
    threads : Gmsh threads. Keep 1: with 2 threads Gmsh 4.15 crashed the process
        (segmentation fault) on a groove 0.3 mm below the root; meshing is not
        the bottleneck.
    """

    size: float
    order: int = 2
    curvature_points: int = 16
    min_size_factor: float = 0.2
    tooth_size_factor: float = 0.8
    loft_sections: int = 5
    threads: int = 1

    def __post_init__(self) -> None:
        check_positive("mesh.size", self.size, unit="m")
        check_int_range("mesh.order", self.order, 1, 2)
        check_int_range("mesh.curvature_points", self.curvature_points, 0, 360)
        check_range("mesh.min_size_factor", self.min_size_factor, 0.01, 1.0)
        check_range("mesh.tooth_size_factor", self.tooth_size_factor, 0.05, 10.0)
        check_int_range("mesh.loft_sections", self.loft_sections, 3, 50)
        check_int_range("mesh.threads", self.threads, 1, 64)


def mesh_coaxial_body(body: CoaxialBody, settings: MeshSettings) -> TetMeshData:
    """Mesh ``body`` (see module doc); lengths in m."""
    with gmsh_session(threads=settings.threads) as gmsh:
        occ = gmsh.model.occ
        solids = []
        for seg in body.segments:
            if seg.teeth is not None:
                tag = _toothed_solid(occ, seg, settings.loft_sections)
            else:
                tag = occ.addCylinder(0, 0, seg.z0, 0, 0, seg.length, seg.outer_radius)
            if body.bore_radius > 0:
                bore = occ.addCylinder(0, 0, seg.z0 - 1e-3, 0, 0, seg.length + 2e-3,
                                       body.bore_radius)
                out, _ = occ.cut([(3, tag)], [(3, bore)])
                tag = out[0][1]
            solids.append(tag)
        if len(solids) > 1:
            _, out_map = occ.fragment([(3, solids[0])], [(3, t) for t in solids[1:]])
            volume_of = {seg.name: [t for d, t in out_map[i] if d == 3]
                         for i, seg in enumerate(body.segments)}
        else:
            volume_of = {body.segments[0].name: solids}
        occ.synchronize()
        surfaces = _name_surfaces(gmsh, body, volume_of)
        _set_sizes(gmsh, body, settings, surfaces)
        gmsh.option.setNumber("Mesh.ElementOrder", settings.order)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.model.mesh.generate(3)
        return extract_tet_mesh(gmsh, settings.order, surfaces, volume_of)


def _toothed_solid(occ, seg: Segment, n_sec: int) -> int:
    """Loft the transverse outline through rotated sections: a helical toothed ring."""
    teeth = seg.teeth
    gear = teeth.gear
    outline = tooth_outline(gear)
    z = gear.teeth
    pitch = 2 * math.pi / z
    lead_rate = teeth.sign * math.tan(gear.helix_angle) / gear.reference_radius  # rad/m
    wires = []
    for zk in np.linspace(seg.z0, seg.z1, n_sec):
        rot = lead_rate * (zk - teeth.z_reference)
        wires.append(_outline_wire(occ, outline, z, pitch, rot, zk))
    return occ.addThruSections(wires, makeSolid=True, makeRuled=False)[0][1]


def _outline_wire(occ, outline, z: int, pitch: float, rot: float, zk: float) -> int:
    """Closed wire of all teeth at height zk, turned by ``rot`` (rad).

    Per tooth: left flank (root -> tip), tip arc, right flank (tip -> root); the
    right flank's root point is the next tooth's left root point (mid-space).
    """

    def rotate(p, ang):
        c, s = math.cos(ang), math.sin(ang)
        return np.column_stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]])

    def point(xy):
        return occ.addPoint(float(xy[0]), float(xy[1]), zk)

    centre = occ.addPoint(0.0, 0.0, zk)
    roots = [point(rotate(outline.left_flank[:1], rot + i * pitch)[0]) for i in range(z)]
    curves = []
    for i in range(z):
        ang = rot + i * pitch
        left = rotate(outline.left_flank, ang)
        right = rotate(outline.right_flank, ang)
        lp = [roots[i]] + [point(p) for p in left[1:]]
        rp = [roots[(i + 1) % z]] + [point(p) for p in right[1:]]
        curves.append(occ.addSpline(lp))
        curves.append(occ.addCircleArc(lp[-1], centre, rp[-1]))  # tip land
        curves.append(occ.addSpline(rp[::-1]))
    return occ.addWire(curves, checkClosed=True)


def _name_surfaces(gmsh, body: CoaxialBody, volume_of: dict[str, list[int]]) -> dict:
    """Classify boundary surfaces by bounding box: outer surface, bore, end faces."""
    tol = 1e-6 * max(1.0, body.z_end - body.z_start)
    surfaces: dict[str, list[int]] = {"end:left": [], "end:right": []}
    for seg in body.segments:
        outer = []
        for vol in volume_of[seg.name]:
            for _, s in gmsh.model.getBoundary([(3, vol)], oriented=False):
                x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, s)
                rmax = max(abs(x0), abs(x1), abs(y0), abs(y1))
                if abs(z1 - z0) < tol:  # a transverse plane
                    if abs(z0 - body.z_start) < tol and s not in surfaces["end:left"]:
                        surfaces["end:left"].append(s)
                    elif abs(z0 - body.z_end) < tol and s not in surfaces["end:right"]:
                        surfaces["end:right"].append(s)
                elif body.bore_radius > 0 and rmax < body.bore_radius * (1 + 1e-4) + tol:
                    continue  # bore
                else:
                    outer.append(s)
        surfaces[f"{seg.name}:outer"] = outer
    return surfaces


def _set_sizes(gmsh, body: CoaxialBody, settings: MeshSettings, surfaces: dict) -> None:
    h = settings.size
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeMin", h * settings.min_size_factor)
    toothed = [s for seg in body.segments if seg.teeth is not None
               for s in surfaces[f"{seg.name}:outer"]]
    # Curvature sizing would resolve every root fillet with tiny elements; on
    # toothed bodies the tooth size below (and curved P2 cells) control it instead.
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0 if toothed else
                          settings.curvature_points)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0 if toothed else 1)
    if toothed:
        module = next(seg.teeth.gear.module for seg in body.segments if seg.teeth is not None)
        ht = min(h, settings.tooth_size_factor * module)
        f = gmsh.model.mesh.field
        dist = f.add("Distance")
        f.setNumbers(dist, "SurfacesList", toothed)
        thr = f.add("Threshold")
        f.setNumber(thr, "InField", dist)
        f.setNumber(thr, "SizeMin", ht)
        f.setNumber(thr, "SizeMax", h)
        f.setNumber(thr, "DistMin", 0.5 * module)
        f.setNumber(thr, "DistMax", 3.0 * module)
        f.setAsBackgroundMesh(thr)
