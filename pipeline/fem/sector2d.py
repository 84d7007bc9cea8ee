"""2D gear sector meshes: several consecutive teeth with the exact profile, down to the bore.

The sector is bounded by the tooth outline of ``teeth`` consecutive teeth
(:func:`pipeline.geometry.profile.gear_outline`: involute, trochoidal fillet,
root and tip circles), two radial *cut* lines through the middles of the outer
tooth spaces, and the *bore* circle (external gear: ``gear.bore_radius``; a
solid gear gets a hub circle, see :func:`inner_radius`; internal gear: the outer
rim circle ``gear.bore_radius``, the outer boundary of a whole ring). Quadratic
(6-node) triangles, graded from ``size_flank`` on the tooth outline to ``size_body`` a
distance ``grading`` away, so flanks and fillets are refined.

Graded meshes (:meth:`~pipeline.fem.mesh_settings.SectorSettings.graded`): only the
``loaded`` teeth get ``size_flank`` on their outline, the others ``size_tooth``; from
either the size grows linearly with the distance up to ``size_body``. A whole gear then
has most of its unknowns where the loads are (the assembly-error paper's gear: 20k
unknowns instead of 221k, mesh stiffness within 0.4 %:
:mod:`pipeline.contact.fe2d_source`). The outline of
unloaded teeth is thinned to every ``THIN``-th profile point.

Size guard: :func:`~pipeline.fem.sector2d_size.check_size` estimates the unknowns of the FE
model before meshing (:func:`~pipeline.fem.sector2d_size.estimated_size`, within about
30 %) and refuses meshes above ``MAX_DOF`` (about 14 GiB of FE memory) with the estimate,
instead of running out of memory.

Tooth ``k`` (``k = 0 .. teeth-1``) is centred on the polar angle
``pi/2 + (k - (teeth-1)/2) 2 pi/z``: tooth 0 is the most clockwise. Its *right*
flank is the clockwise side (x >= 0 in the tooth's own frame). Boundary groups
(3-node edges): ``right{k}`` / ``left{k}`` (each from the middle of the tooth
space over fillet and involute to the middle of the tip land), ``bore``,
``cut_right`` (clockwise cut) and ``cut_left``.

Meshes are cached in ``meshes/`` keyed by the gear and the mesh settings
(:mod:`pipeline.fem.mesh_cache`); the 2D data travel in a ``TetMeshData`` container
(points (2, n), cells (6, m), boundary edges (3, k) as its ``surfaces``).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

import numpy as np

from pipeline.cache.entries import unlabelled
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.gmsh_session import TetMeshData, gmsh_session, size_from_fields
from pipeline.fem.mesh_cache import cached_tet_mesh
from pipeline.fem.mesh_settings import SectorSettings
from pipeline.fem.outline2d import inner_radius, outline_pieces
from pipeline.fem.sector2d_size import check_size
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError

if TYPE_CHECKING:
    from skfem import MeshTri2

# graded meshes (SectorSettings.graded): sizes and growth in pipeline.fem.settings
# (module docstring, "Graded meshes")
THIN = 4  # outline point stride on unloaded teeth of graded meshes


@dataclass(frozen=True, eq=False)
class SectorMesh2D:
    """A scikit-fem quadratic triangle mesh of a gear sector with named boundary edges.

    Attributes
    ----------
    mesh : ``MeshTri2`` (curved quadratic triangles), lengths in m.
    facets : name -> (n,) facet indices of ``mesh`` (groups of the module docstring).
    gear : the gear.
    settings : the mesh settings.
    inner_radius : radius of the bore boundary, m.
    """

    mesh: MeshTri2
    facets: dict
    gear: GearSpec
    settings: SectorSettings
    inner_radius: float

    def tooth_angle(self, k: int) -> float:
        """Polar angle of the centre line of tooth ``k``, rad."""
        n = self.settings.teeth
        return math.pi / 2 + (k - (n - 1) / 2.0) * 2.0 * math.pi / self.gear.teeth

    @property
    def n_nodes(self) -> int:
        return int(self.mesh.doflocs.shape[1])


def _thin_unloaded(pieces: list[tuple[str, np.ndarray]], settings: SectorSettings
                   ) -> list[tuple[str, np.ndarray]]:
    """Every ``THIN``-th outline point (and the ends) on the pieces of unloaded teeth.

    Their elements are ``size_tooth`` (several times ``size_flank``) long, so the spline
    through a quarter of the points is still far more accurate than the P2 edges on it,
    and Gmsh's 1D meshing (which evaluates the size field along every spline) speeds up.
    """
    if settings.loaded is None:
        return pieces
    keep = {f"{side}{k}" for k in settings.loaded for side in ("right", "left")}
    out = []
    for name, seg in pieces:
        if name not in keep and len(seg) > 2 * THIN:
            seg = np.vstack([seg[:-1:THIN], seg[-1:]])
        out.append((name, seg))
    return out


def build_sector_mesh_2d(gear: GearSpec, settings: SectorSettings) -> TetMeshData:
    """Mesh the sector in Gmsh (quadratic triangles); returns 2D data (see module docstring)."""
    full = settings.teeth == gear.teeth
    if 2 * settings.teeth >= gear.teeth and not full:
        raise InputError(f"sector.teeth = {settings.teeth} must be < z/2 = {gear.teeth / 2:g} "
                         f"or = z (whole gear)")
    r_in = inner_radius(gear, settings)
    pieces = _thin_unloaded(outline_pieces(gear, settings.teeth, settings.profile_points),
                            settings)
    with gmsh_session() as gmsh:
        geo = gmsh.model.geo
        first = geo.addPoint(*pieces[0][1][0], 0.0)
        prev = first
        curves: dict[str, list[int]] = {}
        loop = []
        for i, (name, seg) in enumerate(pieces):
            closing = full and i == len(pieces) - 1  # the whole gear: end on the first point
            tags = [prev] + [geo.addPoint(x, y, 0.0) for x, y in seg[1:-1 if closing else None]]
            tags += [first] if closing else []
            prev = tags[-1]
            c = geo.addSpline(tags) if len(tags) > 2 else geo.addLine(*tags)
            curves.setdefault(name, []).append(c)
            loop.append(c)
        outline_curves = list(loop)
        centre = geo.addPoint(0.0, 0.0, 0.0)
        if full:
            circle = [geo.addPoint(r_in * math.cos(a), r_in * math.sin(a), 0.0)
                      for a in (0.0, 2 * math.pi / 3, 4 * math.pi / 3)]
            bore_arcs = [geo.addCircleArc(circle[i], centre, circle[(i + 1) % 3])
                         for i in range(3)]
            # the first loop is the outer boundary: the rim circle of an internal gear
            loops = [geo.addCurveLoop(loop), geo.addCurveLoop(bore_arcs)]
            geo.addPlaneSurface(loops[::-1] if gear.internal else loops)
            geo.synchronize()
            curves["bore"] = bore_arcs
            return _mesh_and_extract(gmsh, curves, outline_curves, settings)
        end = pieces[-1][1][-1]
        a_end, a_start = math.atan2(end[1], end[0]), math.atan2(*pieces[0][1][0][::-1])
        p_end = geo.addPoint(r_in * math.cos(a_end), r_in * math.sin(a_end), 0.0)
        p_start = geo.addPoint(r_in * math.cos(a_start), r_in * math.sin(a_start), 0.0)
        cut_left = geo.addLine(prev, p_end)
        bore = geo.addCircleArc(p_end, centre, p_start)
        cut_right = geo.addLine(p_start, first)
        loop += [cut_left, bore, cut_right]
        geo.addPlaneSurface([geo.addCurveLoop(loop)])
        geo.synchronize()
        curves.update({"cut_left": [cut_left], "bore": [bore], "cut_right": [cut_right]})
        return _mesh_and_extract(gmsh, curves, outline_curves, settings)


def _threshold(fld, curves: list[int], size: float, settings: SectorSettings,
               sampling: int = 400) -> int:
    """Size field: ``size`` on ``curves`` (distance sampled at ``sampling`` points per curve),
    growing linearly with the distance at the rate of ``settings`` up to ``size_body``."""
    dist = fld.add("Distance")
    fld.setNumbers(dist, "CurvesList", curves)
    fld.setNumber(dist, "Sampling", sampling)
    thr = fld.add("Threshold")
    h0, h1 = settings.size_flank, settings.size_body
    ramp = max(settings.grading - 0.5 * h0, 1e-12)  # size_flank -> size_body over this
    fld.setNumber(thr, "InField", dist)
    fld.setNumber(thr, "SizeMin", size)
    fld.setNumber(thr, "SizeMax", h1)
    fld.setNumber(thr, "DistMin", 0.5 * size)
    fld.setNumber(thr, "DistMax", 0.5 * size + ramp * (h1 - size) / max(h1 - h0, 1e-30))
    return thr


def _mesh_and_extract(gmsh, curves: dict[str, list[int]], outline_curves: list[int],
                      settings: SectorSettings) -> TetMeshData:
    """Size field (fine on the loaded teeth' outline), P2 mesh -> 2D data (the groups are
    read per curve: no physical groups, whose creation cost 1 ms each on a whole gear)."""
    fld = gmsh.model.mesh.field
    if settings.loaded is None:
        fine, other = outline_curves, []
    else:
        names = {f"{side}{k}" for k in settings.loaded for side in ("right", "left")}
        fine = [c for name in sorted(names) for c in curves[name]]
        other = [c for c in outline_curves if c not in set(fine)]
    fields = [_threshold(fld, fine, settings.size_flank, settings)]
    if other:
        # coarse teeth: a few samples per element along their curves are enough
        fields.append(_threshold(fld, other, settings.size_tooth or settings.size_flank,
                                 settings, sampling=40))
    size_from_fields(gmsh, fields)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    # Gmsh integrates 1/size along each curve to place the 1D nodes; its default precision
    # (1e-9) made 1D meshing of the whole-gear splines take 1.3 s instead of 0.09 s
    gmsh.option.setNumber("Mesh.LcIntegrationPrecision", 1e-5)
    gmsh.model.mesh.generate(2)
    gmsh.model.mesh.setOrder(2)
    return _extract_tri_mesh(gmsh, curves)


def _extract_tri_mesh(gmsh, curves: dict[str, list[int]]) -> TetMeshData:
    _, nodes = gmsh.model.mesh.getElementsByType(9)  # 6-node triangles
    if nodes.size == 0:
        raise RuntimeError("sector2d: Gmsh produced no triangles (degenerate outline?)")
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    lookup = np.zeros(int(node_tags.max()) + 1, dtype=np.int64)
    lookup[node_tags.astype(np.int64)] = np.arange(node_tags.size)
    points = coords.reshape(-1, 3)[:, :2].T.copy()
    cells = lookup[nodes.astype(np.int64)].reshape(-1, 6).T
    used = np.unique(cells)
    renum = -np.ones(points.shape[1], dtype=np.int64)
    renum[used] = np.arange(used.size)
    edges = {}
    for name, tags in curves.items():
        blocks = []
        for c in tags:
            _, en = gmsh.model.mesh.getElementsByType(8, c)  # 3-node lines: v0, v1, mid
            blocks.append(renum[lookup[en.astype(np.int64)].reshape(-1, 3)])
        edges[name] = np.ascontiguousarray(np.vstack(blocks).T)
    return TetMeshData(np.ascontiguousarray(points[:, used]), np.ascontiguousarray(renum[cells]),
                       edges, {})


def to_skfem_tri(data: TetMeshData) -> tuple[MeshTri2, dict]:
    """``MeshTri2`` of 2D sector data and its named boundary facets (name -> facet indices)."""
    from skfem import MeshTri2  # here: reading a table from the cache needs no scikit-fem

    cells = data.cells
    # Gmsh 6-node triangles: vertices, then edges (0,1) (1,2) (2,0) - scikit-fem's order.
    mesh = MeshTri2(data.points, cells)
    node_map = np.full(data.points.shape[1], -1, dtype=np.int64)
    vertices = np.unique(cells[:3])
    node_map[vertices] = np.arange(vertices.size)
    n_v = mesh.nvertices
    f_sorted = np.sort(mesh.facets, axis=0).astype(np.int64)
    f_keys = f_sorted[0] * n_v + f_sorted[1]
    order = np.argsort(f_keys)
    facets = {}
    for name, e in data.surfaces.items():
        v = np.sort(node_map[e[:2]], axis=0)
        if np.any(v < 0):
            raise ValueError(f"boundary {name!r} has nodes that belong to no triangle")
        keys = v[0] * n_v + v[1]
        pos = np.clip(np.searchsorted(f_keys, keys, sorter=order), 0, order.size - 1)
        idx = order[pos]
        if keys.size and not np.array_equal(f_keys[idx], keys):
            raise ValueError(f"boundary {name!r} has edges that are not mesh facets")
        facets[name] = idx
    return mesh, facets


def sector_mesh_2d(gear: GearSpec, settings: SectorSettings | None = None,
                   cache: Cache = DEFAULT_CACHE) -> SectorMesh2D:
    """The (cached) 2D sector mesh of ``gear``; see the module docstring for the groups."""
    settings = settings or SectorSettings.for_gear(gear)
    r_in = inner_radius(gear, settings)
    check_size(gear, settings)
    inputs = {"gear": unlabelled(gear), "settings": asdict(settings), "inner_radius": r_in}
    data, _, _ = cached_tet_mesh("sector2d", inputs, lambda: build_sector_mesh_2d(gear, settings),
                                 cache=cache)
    mesh, facets = to_skfem_tri(data)
    return SectorMesh2D(mesh, facets, gear, settings, r_in)
