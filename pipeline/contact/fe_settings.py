"""Settings of the FE compliance sources: ``[fe]`` table with ``[contact] compliance``.

:class:`FE2DSettings` for ``"fe2d"`` (:mod:`pipeline.contact.fe2d_source`) and
:class:`FE3DSettings` for ``"fe3d"`` (:mod:`pipeline.contact.fe3d_table`). They live
apart from the sources, which pull in scikit-fem and Gmsh: reading a gearbox file, or a
run that finds its FE tables in the cache, needs the settings only.
"""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.contact.options import MAX_SLICES
from pipeline.fem.options import (
    CUTS,
    ENDS,
    GRADED_BODY,
    GRADED_GROWTH,
    GRADED_TOOTH,
    PLANE_KINDS,
    SOLVERS,
)
from pipeline.validation import InputError, check_choice, check_int_range, check_range

MESHES = ("graded", "uniform")
DEFAULT_REFINEMENT = 1.0  # graded mesh: mean and extremes of k(t) within 1 % (docstring)


@dataclass(frozen=True)
class FE2DSettings:
    """Settings of the FE compliance tables.

    Attributes
    ----------
    teeth : teeth per sector (>= 3, covering the tooth pairs in contact), or None for the
        whole gear (default: a sector with clamped cut faces is too stiff for deep gear
        bodies - the assembly-error paper's gear: -42 % with 7 teeth, -4 % as a whole gear, vs the
        analytical compliance; see :mod:`pipeline.fem.influence`).
    radii : tabulated points per flank (4..1000).
    refinement : mesh refinement, 0.1..20: flank element size m_n / (12 refinement) on the
        loaded teeth (:meth:`SectorSettings2D.graded`; every tooth for ``mesh =
        "uniform"``, :meth:`SectorSettings2D.for_gear`).
    kind : "plane_strain" or "plane_stress".
    slices : slices across the face width, or ``None``: 30 across a helical face, one for a
        spur pair (``compliance_source`` sets the count of the contact options).
    cuts : "clamped" or "free" sector cut faces.
    mesh : "graded" (default: fine on the loaded teeth, coarser away from them; module
        docstring) or "uniform" (every tooth at the flank size; the reference).
    tooth_size : graded mesh: element size on the outline of the unloaded teeth, in m_n
        (0.05..2).
    body_size : graded mesh: largest element size, in m_n (tooth_size..20).
    growth : graded mesh: element size growth per distance from the outline (0.05..1).
    """

    teeth: int | None = None
    radii: int = 30
    refinement: float = DEFAULT_REFINEMENT
    kind: str = "plane_strain"
    slices: int | None = None
    cuts: str = "clamped"
    mesh: str = "graded"
    tooth_size: float = GRADED_TOOTH
    body_size: float = GRADED_BODY
    growth: float = GRADED_GROWTH

    def __post_init__(self) -> None:
        if self.teeth is not None:
            check_int_range("fe.teeth", self.teeth, 3, 99)
        check_int_range("fe.radii", self.radii, 4, 1000)
        check_range("fe.refinement", self.refinement, 0.1, 20.0)
        check_choice("fe.kind", self.kind, PLANE_KINDS)
        if self.slices is not None:
            check_int_range("fe.slices", self.slices, 1, MAX_SLICES)
        check_choice("fe.cuts", self.cuts, CUTS)
        check_choice("fe.mesh", self.mesh, MESHES)
        check_range("fe.tooth_size", self.tooth_size, 0.05, 2.0, unit="m_n")
        check_range("fe.body_size", self.body_size, self.tooth_size, 20.0, unit="m_n")
        check_range("fe.growth", self.growth, 0.05, 1.0)


BODIES = ("whole", "sector")


@dataclass(frozen=True)
class FE3DSettings:
    """Settings of the 3D FE compliance tables.

    Attributes
    ----------
    body : "whole" (default): each gear's whole body (all teeth, body down to the bore,
        full face width; bore clamped, as the 2D whole gear), graded from the loaded
        teeth (:mod:`pipeline.fem.whole3d`); "sector": a sector of ``teeth`` teeth
        clamped at its bore and cut faces (stiffer than the gear: an upper bound).
    teeth : "sector" only: teeth per sector (3..99, odd values centre the loaded teeth),
        or None for the fewest that hold the tooth pairs in contact (``2 max|k| + 1``).
    radii : flank grid points along the profile (2..200).
    face : flank grid points across the face width (1..200), or None for a spacing of
        about one patch half-width (the structural kernel then varies little between
        nodes; coarser face grids blur its peak at the diagonal).
    refinement : mesh refinement, 0.2..4: loaded flanks ``m_n / (3 refinement)``
        (:meth:`SectorSettings3D.for_gear`, :meth:`SectorSettings3D.whole_gear`).
    patch : load patch half-width c in normal modules (0.1..2). Default 0.5, wider than
        the 3D default 0.3 of :func:`pipeline.fem.influence.influence_matrix`: the
        near-field subtraction needs the patch resolved by the mesh (0.3 m_n needs
        refinement 2), and the structural part does not depend on c once it is. At
        refinement 0.6 and c = 0.3 m_n (less than one flank element) the structural
        diagonal fell below its neighbours (table eigenvalues down to -16 % of the
        largest); at c = 0.5-0.6 m_n: -0.2 to -0.4 %.
    face_margin : distance of the outer face grid points from the end faces, in
        patch half-widths (0..10; 1 keeps every patch whole on the flank).
    cuts : "clamped" or "free" sector cut faces (a whole gear has none).
    ends : "free" or "sliding" (u_z = 0) end faces.
    slices : slices across the face width, or ``None``: 30 across a helical face, one for a
        spur pair (``compliance_source`` sets the count of the contact options).
    hub_depth : if given, the body is clamped at ``max(bore, r_f - hub_depth m_n)``
        instead of the bore (1..100 modules): a shallower body for deep gears.
    method : solver (:func:`pipeline.fem.solvers.solver_named`, 3D).
    """

    body: str = "whole"
    teeth: int | None = None
    radii: int = 8
    face: int | None = None
    refinement: float = 1.0
    patch: float = 0.5
    face_margin: float = 1.0
    cuts: str = "clamped"
    ends: str = "free"
    slices: int | None = None
    hub_depth: float | None = None
    method: str = "auto"

    def __post_init__(self) -> None:
        check_choice("fe3d.body", self.body, BODIES)
        if self.teeth is not None:
            if self.body == "whole":
                raise InputError(f"fe3d.teeth = {self.teeth} applies to body = 'sector' only "
                                 "(a whole gear has all its teeth)")
            check_int_range("fe3d.teeth", self.teeth, 3, 99)
        check_int_range("fe3d.radii", self.radii, 2, 200)
        if self.face is not None:
            check_int_range("fe3d.face", self.face, 1, 200)
        check_range("fe3d.refinement", self.refinement, 0.2, 4.0)
        check_range("fe3d.patch", self.patch, 0.1, 2.0, unit="m_n")
        check_range("fe3d.face_margin", self.face_margin, 0.0, 10.0)
        check_choice("fe3d.cuts", self.cuts, CUTS)
        check_choice("fe3d.ends", self.ends, ENDS)
        if self.slices is not None:
            check_int_range("fe3d.slices", self.slices, 1, MAX_SLICES)
        if self.hub_depth is not None:
            check_range("fe3d.hub_depth", self.hub_depth, 1.0, 100.0, unit="m_n")
        check_choice("fe3d.method", self.method, SOLVERS)
