"""Whole 3D gear bodies: all teeth, the body down to the bore, the full face width.

Geometry. The transverse section of the whole gear (the outline of all ``z`` teeth:
involute, trochoidal fillet, root and tip circles of :mod:`pipeline.geometry.profile`,
split into the named pieces of :func:`pipeline.fem.outline2d.outline_pieces`, with the
bore circle of :func:`pipeline.fem.outline2d.inner_radius` as a hole) is swept along the
helix: the section at ``z`` is the mid-face section turned by
``theta(z) = s tan(beta) / r (z - b/2)``, exactly as the sectors of
:mod:`pipeline.fem.sector3d` are lofted. So tooth ``k`` at mid-face sits where the 2D
whole gear of ``sector2d`` (``teeth = z``) puts it, and the flank grids, load patches and
influence routine of the sectors apply unchanged (a whole gear is a "sector" of
``teeth = z`` teeth without cut faces).

Surface groups: ``right{k}`` / ``left{k}`` (k = 0 .. z-1, the teeth kept), ``rim``
(where teeth are left out, below), ``bore``, ``end0`` (z = 0) and ``end1`` (z = b).
Boundary conditions are those of the 2D whole gear
(:func:`pipeline.fem.influence.constrained_dofs`): the bore is clamped; nothing else.

Mesh. One P2 tetrahedral mesh graded by :func:`pipeline.fem.grading3d.tooth_size_field`:
``size_flank`` on both sides of the *loaded* teeth (those whose flanks carry grid
points), ``size_near`` on the *near* teeth (read but not loaded: the flank tables'
neighbours of their loaded tooth), ``size_tooth`` on the other teeth, growing to
``size_body`` in the rim and web
(:meth:`~pipeline.fem.mesh_settings.SectorSettings3D.whole_gear`; defaults: flank cells
m_n / (3 refinement), 1.5 times that on the near teeth, 2 m_n on the other teeth, 8 m_n
in the body, at most two face widths).

Far teeth left out. A tooth far from the loaded ones carries no load; it only thickens
the rim, where the body's deformation under a tooth load has died out over a few rim
depths. The default whole gear keeps the teeth within ``WHOLE_REACH`` = 2 rim depths
(root radius minus inner radius) of the loaded and near teeth along the root circle, at
least 2 on each side (``reach``, :func:`pipeline.fem.mesh_settings.whole_reach`);
elsewhere the rim ends at the root circle (:func:`kept_pieces`: the root arc, group
``rim``).

Where the unknowns are, and what each saving costs. Refinement 1, the flank tables' model
(one loaded tooth, a read neighbour on each side), P2 nodes x 3, teeth counted above the
root circle, the rim the 2 m_n below it. The traction pair of Yang et al. (2026): pinion
z 31 (bore 45 mm) had 164.7k unknowns = loaded tooth 33k + neighbours 65k + 28 other
teeth 35k + rim 25k + body 6k (30.7k cells); gear z 104 (bore 150 mm) 284.0k = 31k + 60k
+ 101 other teeth 115k + 41k + 37k (51.5k cells). Now (neighbours at 1.5 flank sizes, 6
and 20 teeth kept on each side of them, 8 m_n body cells): pinion 103.0k = 33k + 27k +
12 other teeth 15k + 22k + 6k (19.1k cells), gear 175.8k = 31k + 31k + 40 other teeth
58k + 31k + 25k (31.9k cells; cell quality, the mean ratio of the vertices, 0.20 / 0.28
and 0.18 / 0.25 at its minimum / 1st percentile, were 0.12 / 0.28 and 0.20 / 0.22). The
pair's loaded contact at its rated 6031 N m (60
positions) moved by +0.04 / +0.05 / +0.04 % (mesh stiffness mean / min / max) and
-0.22 % (TE p-p); the z 30/30 pair of ``bench_fe3d`` (46.5k -> 26.5k unknowns) by +0.05 %
and -0.04 %. Time (``workflows/benchmarks/bench_fe3d.py --full`` side by side with the
former meshes, OMP_NUM_THREADS=2, load 3-4): the traction pair's tables 33 s against 84 s
cold (pinion mesh 1.2 s, assembly 2.0, factorisation 4.1, solves 3.6; gear 2.2, 1.9, 6.7,
6.1), peak memory 1.65 against 2.34 GiB; the z 30/30 pair's 2.3 s against 3.1 s. One
change at a time (traction pair; z 30/30): the teeth left out -0.07 %,
TE +0.11 % (3 rim depths -0.01 %, 1.5 rim depths -0.10 %; a fixed 4 or 2 teeth on each
side -0.25 or -0.46 %: these thick rims deform over more teeth than that; z 30/30, 3
teeth on each side, -0.02 %); the body cells +0.04 %, TE -0.07 %; the neighbours at 1.5
flank sizes +0.06 % (z 30/30 +0.10 %, at 2 flank sizes +0.25 %, coarse +0.5 %,
:mod:`pipeline.contact.fe3d_table`). Measured and not taken: the unloaded, unread left
sides of the fine teeth at twice the flank size made the traction pair 0.23 % stiffer
and its TE p-p 0.70 % smaller (z 30/30: +0.35 %, -0.41 %); the fine zone graded over 1
instead of 1.5 body sizes +0.23 % (z 30/30: +0.41 %); the far teeth at 3 m_n left the
load patches of the read teeth three teeth away without a flank facet to act on; a
structured sweep (prisms split into tetrahedra, layers three flank cells thick) needs as
many layers through the coarse body as through the loaded teeth: 3 x 596 section
triangles x 18 layers = 32k cells for the pinion, 101k for the gear (1869 triangles).

The solve eliminates the body more than a pitch beyond the loaded and read teeth
exactly before the factorisation (:func:`pipeline.fem.influence.far_part`,
:mod:`pipeline.fem.condensation`): on the gear above, 85.4k of its 175.8k unknowns. With
the C heap handed back before each factorisation and solve blocks under 64 MB, that
brought the traction pair's peak memory from 1.31 to 0.82 GiB, the tables unchanged.

How it is meshed, and why. Gmsh's built-in kernel twists the plane section (splines
through outline points :data:`SPLINE_SPACING` flank cells apart, the bore circle as a hole)
about the gear axis while translating it over the face (``geo.twist``; a plain extrusion
for spur gears; the herringbone half 1 twists the other way): the lateral faces are
helicoids of their source curves, born with the names of the curves, so there is no loft,
no boolean cut and no naming by geometry. Gmsh meshes it with linear tetrahedra (sizes
as before; :data:`SIZE_INTEGRATION_PRECISION`); :func:`pipeline.fem.curved_p2.curve_p2`
then adds the mid-edge nodes and puts every boundary node (vertices too) on the exact
surface: the helicoid of the cubic spline through :data:`EXACT_POINTS` times the outline
points of its piece (13 nm from the exact involute and fillet of a m_n 3 mm gear), the
bore cylinder; the end faces are planes. A cell that curving would fold is curved less
(a few cells of the far teeth, whose cells are as large as the tooth; none on the loaded
teeth).

Measured (2 shared cores, ``workflows/benchmarks/bench_mesh3d.py``: both meshers side by
side in one run, load average 4, so read the ratios). z 30, m_n 3 mm, beta 15 deg,
b 12 mm, bore 30 mm, loaded teeth 13..16, refinement 1: 0.63 s for 9.6k cells / 18k
nodes against 6.1 s for 9.0k cells / 17k nodes with the OpenCASCADE loft it replaced
(:mod:`pipeline.fem.whole3d_loft`, kept as the reference). Profiled on a quieter machine,
0.5 s: sweep 0.06 s, Gmsh's 1D 0.07, 2D 0.07, 3D 0.13, outline splines 0.04, P2 nodes
0.1; the loft's 5.5 s were wires 0.3, loft 0.6, bore cut 0.4, synchronise 0.5, 1D 0.7-1.9
(the size fields at Gmsh's default integration precision), curved order 2 with CAD
projection 2.5, its optimisation 0.2. The gear of Yang et al. (2026) (z 104,
m_n 7.35 mm, b 130 mm, loaded teeth 51..54): refinement 0.6, 32k cells, 2.2 s (Gmsh 2.0,
P2 nodes 0.3) against 25 s; refinement 1, 58k cells, 6.1 s (Gmsh 5.6, most of it the 3D
Delaunay meshing and its optimisation) against 63 s (a second, busier run: speed-ups
13.9, 8.9 and 7.6; cell quality, the mean ratio of the vertices, 0.22 / 0.32 at its
minimum / 1st percentile on z 30 as with the loft, 0.19 / 0.29 against 0.16 / 0.16 on the
Yang gear at refinement 0.6). Mesh volume against the exact
section area x b: +8e-6 (z 30), +7e-4 and +3e-4 (Yang; the loft: +1.9e-3, +1.1e-3,
+1.1e-3). The flank compliances of a loaded tooth equal the loft's within 0.42 % (two
meshes of one model; tests/test_fem_whole3d.py).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.fem.curved_p2 import SweptOutline, curve_p2
from pipeline.fem.gmsh_session import TetMeshData, extract_tet_mesh, gmsh_session
from pipeline.fem.grading3d import tooth_size_field
from pipeline.fem.loft3d import generate_linear_tets, loft_inputs
from pipeline.fem.mesh_settings import SectorSettings3D, far_teeth
from pipeline.fem.outline2d import outline_pieces
from pipeline.geometry.gear import GearSpec

SPLINE_SPACING = 0.75
"""Gmsh's splines pass through outline points about this far apart (in flank cell sizes
``size_flank``): the twist's cost grows fast with the points (3.7 s with all 10200 points
of a z 30 gear, 0.05 s at this spacing). The mesh does not inherit the splines' error:
its boundary nodes are put on the exact surface; Gmsh's vertices moved by at most 1.2 %
of a flank cell getting there (z 30, refinement 1; 10 % at twice the spacing)."""

RIM_SPACING = 8.0
"""The splines of the rim arcs (:func:`kept_pieces`) pass through points this many times
:data:`SPLINE_SPACING` apart: a circle needs few (a cubic spline through points 8 x 0.75
flank cells apart strays from the root circle of the gear of Yang et al. (2026) by
less than a nanometre), and the twist's cost grows with the points."""

EXACT_POINTS = 4
"""The exact surfaces the nodes are put on are swept splines through this many times the
model's ``profile_points`` outline points (the same curves, named alike): a spline
through 30 points per flank strays up to 2.4e-5 m_n from the involute and fillet where
they meet (their curvatures jump), one through 120 points 2e-6 m_n."""

SIZE_INTEGRATION_PRECISION = 1e-5
"""Relative precision of Gmsh's integral of 1 / size along the curves, which places the
1D mesh nodes (Gmsh's default 1e-9 made the 1D meshing 0.57 s of a z 30 gear's total
instead of 0.08 s, for nodes moved by a fraction 1e-5 of a cell)."""


def build_whole_gear_mesh_3d(gear: GearSpec, settings: SectorSettings3D) -> TetMeshData:
    """The whole gear's curved P2 mesh (module docstring); lengths in m."""
    return curve_p2(*linear_whole_gear_mesh_3d(gear, settings))


def linear_whole_gear_mesh_3d(gear: GearSpec, settings: SectorSettings3D
                              ) -> tuple[TetMeshData, SweptOutline]:
    """Sweep and mesh the whole gear with linear tetrahedra in Gmsh: the mesh (order 1,
    named groups) and the exact surfaces of its curved groups (tooth sides, bore) that
    :func:`pipeline.fem.curved_p2.curve_p2` puts the nodes on."""
    r_in, b, rate, pieces = loft_inputs(gear, settings, gear.teeth)
    pieces = kept_pieces(gear, settings, pieces)
    with gmsh_session() as gmsh:
        vol, groups = _swept_section(gmsh, pieces, r_in, b, rate, settings.size_flank)
        tooth_size_field(gmsh, settings, groups, gear.root_radius, extent=b)
        gmsh.option.setNumber("Mesh.LcIntegrationPrecision", SIZE_INTEGRATION_PRECISION)
        generate_linear_tets(gmsh)
        data = extract_tet_mesh(gmsh, 1, groups, {"gear": [vol]})
    exact = kept_pieces(gear, settings, outline_pieces(
        gear, gear.teeth, EXACT_POINTS * settings.profile_points))
    return data, SweptOutline(exact, r_in, b, rate)


def kept_pieces(gear: GearSpec, settings: SectorSettings3D,
                pieces: list[tuple[str, np.ndarray]]) -> list[tuple[str, np.ndarray]]:
    """The outline ``pieces`` of the whole gear with every run of left-out teeth
    (:func:`far_teeth`) replaced by a ``"rim"`` piece: the arc from the root point before
    the run to the one after it (their radii are the root radius; the arc's radius runs
    linearly from one to the other, so the outline stays closed), sampled as densely
    as the tooth outline (twice the pieces' points per flank, per angular pitch)."""
    far = far_teeth(settings, gear.teeth)
    if not far:
        return pieces
    per_pitch = 2 * max(seg.shape[0] for _, seg in pieces)
    out, run = [], []

    def close_run() -> None:
        if run:
            out.append(("rim", _root_arc(run[0][0], run[-1][-1], per_pitch, gear.teeth)))
            run.clear()

    for name, seg in pieces:
        if int(name.removeprefix("right").removeprefix("left")) in far:
            run.append(seg)
        else:
            close_run()
            out.append((name, seg))
    close_run()
    return out


def _root_arc(start: np.ndarray, end: np.ndarray, per_pitch: int, z: int) -> np.ndarray:
    """(m, 2) points of the counter-clockwise arc from ``start`` to ``end`` (m)."""
    a0, a1 = math.atan2(start[1], start[0]), math.atan2(end[1], end[0])
    if a1 <= a0:
        a1 += 2 * math.pi
    n = max(2, math.ceil((a1 - a0) * z / (2 * math.pi) * per_pitch))
    t = np.linspace(0.0, 1.0, n + 1)
    r = np.hypot(*start) + (np.hypot(*end) - np.hypot(*start)) * t
    a = a0 + (a1 - a0) * t
    pts = np.column_stack([r * np.cos(a), r * np.sin(a)])
    pts[0], pts[-1] = start, end
    return pts


def _swept_section(gmsh, pieces, r_in: float, b: float, rate: float, size_flank: float
                   ) -> tuple[int, dict[str, list[int]]]:
    """The section at z = 0 (turned by theta(0)) swept over ``b``: (volume tag, groups)."""
    geo = gmsh.model.geo
    rot = -0.5 * rate * b
    spacing = SPLINE_SPACING * size_flank
    c, s = math.cos(rot), math.sin(rot)

    def point(xy) -> int:
        return geo.addPoint(c * xy[0] - s * xy[1], s * xy[0] + c * xy[1], 0.0)

    first = point(pieces[0][1][0])
    prev, curves, names = first, [], []
    for i, (name, seg) in enumerate(pieces):
        end = first if i == len(pieces) - 1 else point(seg[-1])
        step = RIM_SPACING * spacing if name == "rim" else spacing
        tags = [prev, *(point(seg[k]) for k in _spline_points(seg, step)[1:-1]), end]
        curves.append(geo.addSpline(tags) if len(tags) > 2 else geo.addLine(*tags))
        names.append(name)
        prev = end
    centre = geo.addPoint(0.0, 0.0, 0.0)
    ring = [geo.addPoint(r_in * math.cos(a), r_in * math.sin(a), 0.0)
            for a in 0.5 * math.pi * np.arange(4)]
    arcs = [geo.addCircleArc(ring[i], centre, ring[(i + 1) % 4]) for i in range(4)]
    base = geo.addPlaneSurface([geo.addCurveLoop(curves), geo.addCurveLoop(arcs)])
    if rate == 0.0:
        out = geo.extrude([(2, base)], 0.0, 0.0, b)
    else:
        out = geo.twist([(2, base)], 0.0, 0.0, 0.0, 0.0, 0.0, b, 0.0, 0.0, 1.0, rate * b)
    geo.synchronize()
    # extrude/twist return the top face, the volume, then one lateral face per boundary
    # curve of the base in the order of its curve loops
    names += ["bore"] * len(arcs)
    if len(out) != 2 + len(names):
        raise RuntimeError(f"whole3d: the sweep returned {len(out)} entities, "
                           f"expected {2 + len(names)}")
    groups: dict[str, list[int]] = {"end0": [base], "end1": [out[0][1]]}
    for name, (_, tag) in zip(names, out[2:], strict=True):
        groups.setdefault(name, []).append(tag)
    return out[1][1], groups


def _spline_points(seg: np.ndarray, spacing: float) -> np.ndarray:
    """Indices of the points of ``seg`` (m, 2) about ``spacing`` (m) apart along it, first
    and last included (even in arc length: Gmsh meshes a surface in the parameters of its
    curves, and a spline's parameter runs evenly over its points)."""
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(seg, axis=0).T))]
    n = max(1, math.ceil(s[-1] / spacing))
    return np.unique(np.r_[np.searchsorted(s, np.linspace(0.0, s[-1], n + 1)[:-1]),
                           len(seg) - 1])


def whole_gear_area(gear: GearSpec, points: int, r_in: float) -> float:
    """Exact area (m^2) of the transverse section: the outline polyline of ``points``
    involute points per flank minus the bore disc of radius ``r_in``."""
    from pipeline.geometry.profile import gear_outline

    x, y = gear_outline(gear, points=points).T
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)) - math.pi * r_in**2
