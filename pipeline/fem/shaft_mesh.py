"""Gmsh meshes of stepped shafts: solids of revolution cut into axial pieces (P2 tetrahedra).

A shaft is a stack of :class:`ShaftPiece` along ``z`` (m), each a cylinder with its own
outer and bore radius. The pieces are cut wherever something is attached (a seat, a
bearing band, a diameter step) or read (a section of the deflection line), and fragmented
together so that the mesh conforms across every cut. Named surfaces:

* ``"outer:<i>"`` - the lateral outer surface of piece ``i`` (the bands that couple
  bearings, seats and torque points to reference nodes are unions of these);
* ``"section:<k>"`` - the cross-section at section cut ``k`` (``z = section_cuts[k]``):
  the interface between the pieces on either side (the smaller disc or annulus at a
  shoulder) and the end faces at ``k = 0`` and the last cut. Shoulder annuli and bores
  are free surfaces and are not named.

A cut may instead be a ring (:attr:`ShaftMeshSpec.rings`): a circle that splits only the
outer surface, the pieces either side being one solid. Narrow bands on a wide, short piece
(the stations of a pinion's body) are then surface patches, not thin full-diameter slabs
that force flat elements across the whole disc and a large sparse factor.

Size field: ``size`` (m) inside each piece; at every re-entrant shoulder (the circle where
a smaller piece meets a larger one) ``shoulder_factor`` times the smaller piece's size,
growing linearly with the distance from that circle (``grading`` m per m), and likewise
at further circles the caller names (the edges of a rigid hub bonded to the surface); at a
large step (radii ``large_step_ratio`` apart) ``large_step_factor`` growing at
``large_step_grading``: there the 3D stress and the local flexibility differ from beam
theory, and a sharp corner is a singularity.
Second-order nodes are placed on the true cylinders (curved P2 cells), as in
:mod:`pipeline.fem.groove.mesh`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.fem.gmsh_session import TetMeshData, extract_tet_mesh, gmsh_session, size_from_fields
from pipeline.fem.size3d import SizeEstimate, uniform_cells
from pipeline.validation import InputError, check_positive, check_range

_TOL = 1e-9
"""Axial positions closer than this (m) are the same cut."""


@dataclass(frozen=True)
class ShaftPiece:
    """An axial piece ``[z0, z1]`` (m) of outer radius ``outer_radius`` and bore radius
    ``inner_radius`` (m, 0: solid), meshed at edge ``size`` (m)."""

    z0: float
    z1: float
    outer_radius: float
    inner_radius: float
    size: float

    def __post_init__(self) -> None:
        check_positive("shaft piece length", self.z1 - self.z0, unit="m")
        check_range("shaft piece inner_radius", self.inner_radius, 0.0, self.outer_radius,
                    hi_open=True, unit="m")
        check_positive("shaft piece size", self.size, unit="m")


@dataclass(frozen=True)
class ShaftMeshSpec:
    """The pieces of a shaft, contiguous in increasing ``z``, and the shoulder refinement.

    Attributes
    ----------
    pieces : contiguous pieces (each starts where the one before ends).
    shoulder_factor : edge at a shoulder circle over the smaller piece's ``size``.
    grading : growth of the edge away from a shoulder circle, m per m.
    large_step_ratio : outer radii this far apart (larger over smaller) make a large step.
    large_step_factor, large_step_grading : ``shoulder_factor`` and ``grading`` at a large
        step's shoulder (a stronger corner singularity, whose zone holds a larger share of
        the shaft's flexibility).
    edges : further circles ``(z, radius)`` (m) refined like shoulders (the edges of a
        rigid ring bonded to the surface, another corner singularity).
    rings : cuts (m, piece ends between pieces of one cross-section) that split only the
        outer surface: the pieces either side are one solid, with no cross-section there,
        so that narrow bands on a large diameter do not cut it into thin slabs.
    """

    pieces: tuple[ShaftPiece, ...]
    shoulder_factor: float = 0.35
    grading: float = 0.5
    large_step_ratio: float = 2.0
    large_step_factor: float = 0.08
    large_step_grading: float = 1.0
    edges: tuple[tuple[float, float], ...] = ()
    rings: tuple[float, ...] = ()

    def __post_init__(self) -> None:
        if not self.pieces:
            raise InputError("a shaft mesh needs at least one piece")
        for a, b in zip(self.pieces[:-1], self.pieces[1:], strict=True):
            if abs(a.z1 - b.z0) > _TOL:
                raise InputError(f"shaft pieces leave a gap or overlap at z = {a.z1:.6g} m")
        joints = {round(a.z1, 12): (a, b)
                  for a, b in zip(self.pieces[:-1], self.pieces[1:], strict=True)}
        for z in self.rings:
            a, b = joints.get(round(z, 12), (None, None))
            if a is None or (a.outer_radius, a.inner_radius) != (b.outer_radius, b.inner_radius):
                raise InputError(f"shaft mesh ring at z = {z:.6g} m is not a cut between two "
                                 "pieces of the same cross-section")
        check_range("shaft mesh shoulder_factor", self.shoulder_factor, 0.05, 1.0)
        check_range("shaft mesh grading", self.grading, 0.05, 2.0)
        check_range("shaft mesh large_step_ratio", self.large_step_ratio, 1.0, 100.0,
                    lo_open=True)
        check_range("shaft mesh large_step_factor", self.large_step_factor, 0.02, 1.0)
        check_range("shaft mesh large_step_grading", self.large_step_grading, 0.05, 2.0)

    @property
    def cuts(self) -> np.ndarray:
        """(n_pieces + 1,) axial positions of the cuts (m): piece ends."""
        return np.array([self.pieces[0].z0] + [p.z1 for p in self.pieces])

    @property
    def section_cuts(self) -> np.ndarray:
        """The cuts with a cross-section (all but the :attr:`rings`), m."""
        cuts = self.cuts
        ring = np.array([any(abs(c - z) < _TOL for z in self.rings) for c in cuts], bool)
        return cuts[~ring]

    def solids(self) -> list[list[int]]:
        """Indices of the pieces of each solid: runs of pieces joined at :attr:`rings`."""
        out = [[0]]
        for i in range(1, len(self.pieces)):
            if any(abs(self.pieces[i].z0 - z) < _TOL for z in self.rings):
                out[-1].append(i)
            else:
                out.append([i])
        return out

    def shoulders(self) -> list[tuple[float, float, float, float, float]]:
        """(z, radius, size at the circle, size it grows to, grading) of every refined
        circle: each re-entrant shoulder (a change of outer radius; the smaller piece's
        size; a large step's factor and grading) and each of :attr:`edges` (its piece's
        size)."""
        out = []
        for a, b in zip(self.pieces[:-1], self.pieces[1:], strict=True):
            if abs(a.outer_radius - b.outer_radius) > _TOL:
                small, big = (a, b) if a.outer_radius < b.outer_radius else (b, a)
                large = big.outer_radius >= self.large_step_ratio * small.outer_radius
                f, g = ((self.large_step_factor, self.large_step_grading) if large
                        else (self.shoulder_factor, self.grading))
                out.append((a.z1, small.outer_radius, f * small.size, small.size, g))
        cuts = self.cuts
        for z, r in self.edges:
            k = int(np.clip(np.searchsorted(cuts, z) - 1, 0, len(self.pieces) - 1))
            h = self.pieces[k].size
            out.append((z, r, self.shoulder_factor * h, h, self.grading))
        return out

    def estimated_size(self) -> SizeEstimate:
        """Cells of the P2 mesh before meshing (:mod:`pipeline.fem.size3d`): each piece at its
        size, plus the refined torus around each shoulder circle (edge growing from the
        shoulder size to the piece size over ``(size - shoulder size) / grading``). It guards
        against models too large to solve (:func:`pipeline.fem.size3d.check_size_3d`):
        over the actual unknowns it was 0.73 and about 1.0 at 89k and 200k unknowns (a
        plain 40 mm shaft), but only 0.2-0.6 on coarse meshes of 5k-65k, where the
        surface and the thin bands hold most of the nodes."""
        cells = sum(uniform_cells(math.pi * (p.outer_radius**2 - p.inner_radius**2)
                                  * (p.z1 - p.z0), p.size) for p in self.pieces)
        for _, r, hs, h, grading in self.shoulders():
            reach = (h - hs) / grading
            # quarter torus of radius ``reach`` around the circle, mean edge ~ (hs + h) / 2
            vol = 2 * math.pi * r * math.pi * reach**2 / 4
            cells += uniform_cells(vol, 0.5 * (hs + h)) - uniform_cells(vol, h)
        return SizeEstimate(cells)


def mesh_shaft(spec: ShaftMeshSpec, order: int = 2) -> TetMeshData:
    """Mesh the shaft of ``spec`` in Gmsh (module docstring); lengths in m."""
    cuts = spec.section_cuts
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        solids = []
        for group in spec.solids():
            first, last = spec.pieces[group[0]], spec.pieces[group[-1]]
            z0, z1 = first.z0, last.z1
            tag = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, first.outer_radius)
            if first.inner_radius > 0:
                bore = occ.addCylinder(0, 0, z0 - 1e-3, 0, 0, z1 - z0 + 2e-3,
                                       first.inner_radius)
                tag = occ.cut([(3, tag)], [(3, bore)])[0][0][1]
            solids.append(tag)
        circles = [(1, occ.addCircle(0, 0, z, _piece_at(spec, z).outer_radius))
                   for z in spec.rings]
        if len(solids) > 1 or circles:
            _, out_map = occ.fragment([(3, solids[0])],
                                      [(3, t) for t in solids[1:]] + circles)
            volumes = [[t for d, t in out_map[i] if d == 3] for i in range(len(solids))]
        else:
            volumes = [solids]
        occ.synchronize()
        surfaces = _name_surfaces(gmsh, spec, volumes, cuts)
        _set_sizes(gmsh, spec)
        gmsh.option.setNumber("Mesh.ElementOrder", order)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.model.mesh.generate(3)
        return extract_tet_mesh(gmsh, order, surfaces, {})


def _piece_at(spec: ShaftMeshSpec, z: float) -> ShaftPiece:
    """The piece that ends at ``z`` (m)."""
    return min(spec.pieces, key=lambda p: abs(p.z1 - z))


def _name_surfaces(gmsh, spec: ShaftMeshSpec, volumes: list[list[int]], cuts: np.ndarray
                   ) -> dict[str, list[int]]:
    """Outer lateral surfaces per piece (by the axial middle of their bounding box) and
    cross-sections per section cut (by how many volumes share a transverse surface: two,
    an interface; one, a free face)."""
    tol = 1e-6 * max(1.0, cuts[-1] - cuts[0])
    names: dict[str, list[int]] = {f"section:{k}": [] for k in range(cuts.size)}
    names |= {f"outer:{i}": [] for i in range(len(spec.pieces))}
    mids = np.array([0.5 * (p.z0 + p.z1) for p in spec.pieces])
    for group, vols in zip(spec.solids(), volumes, strict=True):
        inner = spec.pieces[group[0]].inner_radius
        for vol in vols:
            for _, s in gmsh.model.getBoundary([(3, vol)], oriented=False):
                x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, s)
                if abs(z1 - z0) < tol:
                    k = int(np.argmin(np.abs(cuts - z0)))
                    shared = len(gmsh.model.getAdjacencies(2, s)[0]) == 2
                    end = k in (0, cuts.size - 1)
                    if (shared or end) and s not in names[f"section:{k}"]:
                        names[f"section:{k}"].append(s)
                    continue
                rmax = max(abs(x0), abs(x1), abs(y0), abs(y1))
                if inner > 0 and rmax < inner * (1 + 1e-4) + tol:
                    continue  # the bore
                i = int(np.argmin(np.abs(mids - 0.5 * (z0 + z1))))
                names[f"outer:{i}"].append(s)
    return names


def _set_sizes(gmsh, spec: ShaftMeshSpec) -> None:
    """Each piece at its size (Box fields), refined around the shoulder circles (MathEval:
    the size grows with the distance from the circle)."""
    fld = gmsh.model.mesh.field
    big = 10.0 * max(p.size for p in spec.pieces)
    fields = []
    for p in spec.pieces:
        box = fld.add("Box")
        r = p.outer_radius * 1.01
        for key, value in (("VIn", p.size), ("VOut", big), ("XMin", -r), ("XMax", r),
                           ("YMin", -r), ("YMax", r), ("ZMin", p.z0 - 1e-9),
                           ("ZMax", p.z1 + 1e-9)):
            fld.setNumber(box, key, value)
        fields.append(box)
    for z, r, hs, _, grading in spec.shoulders():
        ev = fld.add("MathEval")
        # fixed-point numbers: Gmsh's expression parser refuses exponents (1e-05)
        hs_, g_, r_, z_ = (f"{v:.15f}" for v in (hs, grading, r, z))
        rho = f"(Sqrt(x*x + y*y) - {r_})"
        fld.setString(ev, "F", f"{hs_} + {g_} * Sqrt({rho}*{rho} + (z - {z_})*(z - {z_}))")
        fields.append(ev)
    size_from_fields(gmsh, fields)
