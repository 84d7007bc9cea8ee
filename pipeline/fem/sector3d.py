"""3D helical (or spur, or herringbone-half) gear sectors and whole gears: P2 tetrahedra.

Geometry. The transverse section is the 2D sector of :mod:`pipeline.fem.sector2d`
(``teeth`` consecutive teeth with the exact involute and trochoidal fillet of
:mod:`pipeline.geometry.profile`, two radial cut lines through the middles of
the outer tooth spaces, the bore arc). The solid is that section swept along
the helix over the face width: the section at axial position ``z`` is the
section at mid-face turned about the gear axis by

    theta(z) = s tan(beta) / r (z - b / 2),    s = +1 right hand, -1 left, 0 spur,

(``r`` the reference radius, ``b`` the meshed width), so tooth ``k`` at mid-face
sits exactly where the 2D sector puts it (centre line at polar angle
``pi/2 + (k - (teeth-1)/2) 2 pi/z``). OpenCASCADE lofts B-spline surfaces
through ``loft_sections`` rotated copies of the section (as
:mod:`pipeline.fem.groove.mesh` does for whole gears). A herringbone gear is
meshed one helical half at a time (``half`` 0 or 1, the second with the
opposite hand), each ``face_width / 2`` wide; the halves and the groove between
them are the groove package's business.

Surface groups (boundary triangles, 6 nodes): ``right{k}`` / ``left{k}`` (the
whole tooth side from the middle of the tooth space over fillet and involute to
the middle of the tip land, as in 2D), ``bore``, ``cut_right``, ``cut_left``, and
the end faces ``end0`` (z = 0) and ``end1`` (z = b). Each lofted face is named by
mapping one of its interior points back to mid-face (turning it by ``-theta(z)``)
and taking the nearest 2D boundary piece.

Whole gears. ``teeth = z`` meshes the whole gear body (all teeth, the body down to
the bore, the full face width; no cut faces), as ``sector2d`` does in 2D; the
geometry is built by :mod:`pipeline.fem.whole3d`, the groups are the same less the cuts.

Mesh. Curved quadratic tetrahedra (a sector: Gmsh places the mid-edge nodes on the CAD
surfaces; a whole gear: :mod:`pipeline.fem.curved_p2` on the exact helicoids), graded
from ``size_flank`` on the tooth sides of the ``loaded`` teeth (all teeth of a sector if
None) to ``size_body`` a distance ``grading`` away; the sides of the other teeth get
``size_tooth`` (:func:`pipeline.fem.grading3d.tooth_size_field`). Meshes are cached in
``meshes/`` by a hash of the gear and the settings (:mod:`pipeline.fem.mesh_cache`).
Lengths in m.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from skfem import Basis, ElementTetP0

from pipeline.cache.entries import unlabelled
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.gmsh_session import TetMeshData, extract_tet_mesh, gmsh_session
from pipeline.fem.loft3d import check_sector_teeth, generate_curved_tets, helix_sign, loft_inputs
from pipeline.fem.mesh_cache import cached_tet_mesh
from pipeline.fem.mesh_settings import SectorSettings3D, meshed_width
from pipeline.fem.outline2d import inner_radius
from pipeline.fem.sector3d_size import estimated_size_3d
from pipeline.fem.size3d import check_size_3d
from pipeline.fem.tetmesh import SkfemTetMesh, to_skfem
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError


@dataclass(frozen=True, eq=False)
class SectorMesh3D:
    """A 3D gear sector: scikit-fem ``MeshTet2`` with named boundary surfaces.

    Attributes
    ----------
    tets : the mesh and its surface groups (module docstring), lengths in m.
    gear : the gear.
    settings : the mesh settings.
    inner_radius : bore radius, m.
    width : meshed face width b, m (``face_width / 2`` for a herringbone half).
    twist_rate : d theta / d z, rad/m (``s tan(beta) / r``).
    """

    tets: SkfemTetMesh
    gear: GearSpec
    settings: SectorSettings3D
    inner_radius: float
    width: float
    twist_rate: float

    @property
    def mesh(self):
        return self.tets.mesh

    @property
    def facets(self) -> dict:
        return self.tets.facets

    def twist(self, z: np.ndarray) -> np.ndarray:
        """theta(z) (rad) of the section at axial position ``z`` (m), shape of ``z``."""
        return self.twist_rate * (np.asarray(z, dtype=float) - 0.5 * self.width)

    def volume(self) -> float:
        """Volume of the (curved P2) mesh, m^3."""
        basis = Basis(self.mesh, ElementTetP0(), intorder=4)
        return float(basis.dx.sum())


def section_area(gear: GearSpec, teeth: int, points: int, r_in: float) -> float:
    """Exact area (m^2) of the transverse section bounded by the profile polyline of
    ``points`` involute points, the two cut lines and the bore arc of radius ``r_in``."""
    from pipeline.geometry.profile import gear_outline

    pts = gear_outline(gear, teeth=teeth, points=points)
    a0, a1 = math.atan2(pts[0, 1], pts[0, 0]), math.atan2(pts[-1, 1], pts[-1, 0])
    poly = np.vstack([pts, r_in * np.array([[math.cos(a1), math.sin(a1)],
                                            [math.cos(a0), math.sin(a0)]])])
    x, y = poly[:, 0], poly[:, 1]
    shoelace = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    th = a1 - a0
    return shoelace - 0.5 * r_in**2 * (th - math.sin(th))  # the bore arc, not its chord


def build_sector_mesh_3d(gear: GearSpec, settings: SectorSettings3D) -> TetMeshData:
    """Loft and mesh the sector in Gmsh (OpenCASCADE); see the module docstring."""
    r_in, b, rate, pieces = loft_inputs(gear, settings, settings.teeth)
    names = [n for n, _ in pieces] + ["cut_left", "bore", "cut_right"]
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        wires = [_section_wire(occ, pieces, r_in, rate * (z - 0.5 * b), z)
                 for z in np.linspace(0.0, b, settings.loft_sections)]
        vol = occ.addThruSections(wires, makeSolid=True, makeRuled=False)[0][1]
        occ.synchronize()
        groups = _classify_surfaces(gmsh, vol, pieces, r_in, b, rate)
        missing = [n for n in names + ["end0", "end1"] if not groups.get(n)]
        if missing:
            raise RuntimeError(f"sector3d: surfaces not found after lofting: {missing}")
        from pipeline.fem.grading3d import tooth_size_field

        tooth_size_field(gmsh, settings, groups, gear.root_radius)
        generate_curved_tets(gmsh)
        return extract_tet_mesh(gmsh, 2, groups, {"sector": [vol]})


def _section_wire(occ, pieces, r_in: float, rot: float, z: float) -> int:
    """Closed wire of the transverse section turned by ``rot`` (rad) at height ``z``."""
    c, s = math.cos(rot), math.sin(rot)

    def point(xy) -> int:
        return occ.addPoint(c * xy[0] - s * xy[1], s * xy[0] + c * xy[1], z)

    first = point(pieces[0][1][0])
    prev, curves = first, []
    for _, seg in pieces:
        tags = [prev] + [point(p) for p in seg[1:]]
        curves.append(occ.addSpline(tags) if len(tags) > 2 else occ.addLine(*tags))
        prev = tags[-1]
    end, start = pieces[-1][1][-1], pieces[0][1][0]
    a_end, a_start = math.atan2(end[1], end[0]), math.atan2(start[1], start[0])
    p_end = point((r_in * math.cos(a_end), r_in * math.sin(a_end)))
    p_start = point((r_in * math.cos(a_start), r_in * math.sin(a_start)))
    centre = occ.addPoint(0.0, 0.0, z)
    curves += [occ.addLine(prev, p_end), occ.addCircleArc(p_end, centre, p_start),
               occ.addLine(p_start, first)]
    return occ.addWire(curves, checkClosed=True)


def _reference_curves(pieces, r_in: float) -> tuple[np.ndarray, list[str]]:
    """Dense samples (m, 2) of every named 2D boundary piece at mid-face and their names."""
    pts, names = [], []
    for name, seg in pieces:
        pts.append(seg)
        names += [name] * len(seg)
    end, start = pieces[-1][1][-1], pieces[0][1][0]
    a_end, a_start = math.atan2(end[1], end[0]), math.atan2(start[1], start[0])
    t = np.linspace(0.0, 1.0, 50)[:, None]
    for name, outer, a in (("cut_left", end, a_end), ("cut_right", start, a_start)):
        inner = r_in * np.array([math.cos(a), math.sin(a)])
        pts.append(inner + t * (np.asarray(outer) - inner))
        names += [name] * t.size
    ang = np.linspace(a_start, a_end, 200)
    pts.append(r_in * np.column_stack([np.cos(ang), np.sin(ang)]))
    names += ["bore"] * ang.size
    return np.vstack(pts), names


def _classify_surfaces(gmsh, vol: int, pieces, r_in: float, b: float, rate: float
                       ) -> dict[str, list[int]]:
    """Name the boundary surfaces of the lofted volume (module docstring)."""
    ref, ref_names = _reference_curves(pieces, r_in)
    groups: dict[str, list[int]] = {}
    for _, s in gmsh.model.getBoundary([(3, vol)], oriented=False):
        _, _, z0, _, _, z1 = gmsh.model.getBoundingBox(2, s)
        if z1 - z0 < 0.5 * b:  # end caps are planes z = 0, b; lofted faces span the width
            name = "end0" if z0 + z1 < b else "end1"
        else:
            lo, hi = gmsh.model.getParametrizationBounds(2, s)
            x, y, z = gmsh.model.getValue(2, s, 0.5 * (np.asarray(lo) + np.asarray(hi)))
            th = -rate * (z - 0.5 * b)
            ct, st = math.cos(th), math.sin(th)
            p = np.array([ct * x - st * y, st * x + ct * y])
            name = ref_names[int(np.argmin(np.sum((ref - p) ** 2, axis=1)))]
        groups.setdefault(name, []).append(s)
    return groups


def sector_mesh_3d(gear: GearSpec, settings: SectorSettings3D | None = None,
                   cache: Cache = DEFAULT_CACHE) -> SectorMesh3D:
    """The (cached) 3D sector mesh of ``gear``; groups as in the module docstring."""
    settings = settings or SectorSettings3D.for_gear(gear)
    if settings.half == 1 and not gear.herringbone:
        raise InputError(f"sector.half = 1 needs a herringbone gear ({gear.name} is not)")
    r_in = inner_radius(gear, settings)
    inputs = {"gear": unlabelled(gear), "settings": asdict(settings), "inner_radius": r_in}
    check_sector_teeth(gear, settings)
    body = "whole gear" if settings.teeth == gear.teeth else f"{settings.teeth}-tooth sector"
    check_size_3d(f"the {body} of {gear.name}",
                  estimated_size_3d(gear, settings, meshed_width(gear)),
                  "use a smaller fe.refinement (elements m_n / (3 refinement) on the loaded "
                  "flanks)")
    if settings.teeth == gear.teeth:
        from pipeline.fem.whole3d import build_whole_gear_mesh_3d as build
    else:
        build = build_sector_mesh_3d
    data, _, _ = cached_tet_mesh("sector3d", inputs, lambda: build(gear, settings),
                                 cache=cache)
    rate = helix_sign(gear, settings.half) * math.tan(gear.helix_angle) / gear.reference_radius
    tets = to_skfem(data)
    _check_cells(tets.mesh)
    return SectorMesh3D(tets, gear, settings, r_in, meshed_width(gear), rate)


def _check_cells(mesh) -> None:
    """Every curved cell must map one-to-one (det J > 0 at the quadrature points of the
    assembly): an inverted cell makes the stiffness matrix indefinite, which the solver
    would report only as 'not positive definite'."""
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTet

    from pipeline.fem.elasticity import default_intorder

    X, _ = get_quadrature(RefTet, default_intorder(mesh, 2))
    worst = mesh.mapping().detDF(X).min(axis=1)
    if np.any(worst <= 0):
        raise RuntimeError(f"sector3d: {int(np.sum(worst <= 0))} curved cell(s) are inverted "
                           "(det J <= 0); change the mesh sizes or refinement")
