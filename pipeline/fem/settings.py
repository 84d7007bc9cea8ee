"""Settings of the FE models of a gear: the ``[fe]`` table, one type per model.

:class:`FE2DSettings` is the 2D FE model of each gear (``gearpipe fe``'s sector analysis,
:mod:`pipeline.fem.sector_analysis`, and the ``"fe2d"`` compliance source,
:mod:`pipeline.contact.fe2d_source`); :class:`FE3DSettings` the 3D one (the ``"fe3d"``
source, :mod:`pipeline.contact.fe3d_table`). Their fields are named as the ``[fe]`` keys
(``points``, ``face_points``, ``solver``), so a file's key and the field it sets are one
name. The mesh each model is meshed with is described by
:mod:`pipeline.fem.mesh_settings`. Nothing here imports scikit-fem or Gmsh: reading a
gearbox file, or a run that finds its FE tables in the cache, needs the settings only.
"""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.validation import InputError, check_choice, check_int_range, check_range

PLANE_KINDS = ("plane_strain", "plane_stress")
CUTS = ("clamped", "free")  # sector cut faces
ENDS = ("free", "sliding")  # 3D end faces: traction-free or u_z = 0
FACTOR_METHODS = ("auto", "pardiso", "cholmod", "cholespy", "splu")
SOLVERS = FACTOR_METHODS + ("pmg-cg",)  # what configuration files may name
# graded 2D meshes: element size on unloaded teeth and largest body size (m_n), growth
GRADED_TOOTH = 0.6
GRADED_BODY = 4.0
GRADED_GROWTH = 0.5


MAX_TABLE_POINTS = 8000
"""Most flank points in one influence matrix: its dense ``n x n`` matrices (FE, near
field, structural) take 3 x 8 n^2 bytes (1.4 GiB at 8000) and each point is one solve
(7 ms on a 32k-unknown 2D sector, seconds in 3D)."""


def check_table_points(n: int, what: str, change: str) -> int:
    """Refuse (InputError) an influence matrix of more than :data:`MAX_TABLE_POINTS` flank
    points; ``what`` says how ``n`` was counted (keys as written), ``change`` what to do."""
    if n > MAX_TABLE_POINTS:
        gib = 3 * 8 * n * n / 2**30
        raise InputError(f"{what} = {n} flank points: the influence matrices would need about "
                         f"{gib:.3g} GiB; the limit is {MAX_TABLE_POINTS} points: {change}")
    return n


MAX_SLICES = 1000
"""Most slices across the face: the contact solve grows as slices^2.3 (a helical pair, one
position: 0.03 s at 100 slices, 2.5 s at 1000, 13 s at 2000; 10000 would take minutes)."""
MESHES = ("graded", "uniform")
DEFAULT_REFINEMENT = 1.0  # graded mesh: mean and extremes of k(t) within 1 % (docstring)
SECTOR_TEETH = 5
"""Teeth of ``gearpipe fe``'s sector when ``teeth`` is None (the contact source then
models the whole gear)."""


@dataclass(frozen=True)
class FE2DSettings:
    """The 2D FE model of each gear (``[fe]`` with ``[contact] compliance = "fe2d"`` or
    ``"analytical"``).

    Attributes
    ----------
    teeth : teeth per sector (3..99; the contact source needs the tooth pairs in contact
        inside), or None: the contact source models the whole gear, ``gearpipe fe`` a
        sector of :data:`SECTOR_TEETH` teeth. The contact source's default: a sector with
        clamped cut faces is too stiff for deep gear bodies (the assembly-error paper's
        gear: -42 % with 7 teeth, -4 % as a whole gear, against the analytical
        compliance; :mod:`pipeline.fem.influence`).
    points : tabulated points per flank (4..1000).
    refinement : mesh refinement, 0.1..20: flank element size m_n / (12 refinement) on the
        loaded teeth (:meth:`~pipeline.fem.mesh_settings.SectorSettings.graded`; every
        tooth for ``mesh = "uniform"`` and ``gearpipe fe``,
        :meth:`~pipeline.fem.mesh_settings.SectorSettings.for_gear`).
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
    patch : load patch half-width c of the influence coefficients in normal modules
        (0.02..0.2, default 0.1; :func:`pipeline.fem.influence.influence_matrix`). The
        flank grid ends ``1.1 c`` inside both ends of the involute (a patch must lie on
        it), so a smaller patch brings the grid closer to the tip, where a tip corner
        loads its tooth (beyond the grid its compliance is extrapolated,
        :mod:`pipeline.contact.fe2d_source`); a patch below the default must be resolved
        by the mesh: ``c >= 0.1 / refinement`` m_n (1.2 flank elements).
    """

    teeth: int | None = None
    points: int = 30
    refinement: float = DEFAULT_REFINEMENT
    kind: str = "plane_strain"
    slices: int | None = None
    cuts: str = "clamped"
    mesh: str = "graded"
    tooth_size: float = GRADED_TOOTH
    body_size: float = GRADED_BODY
    growth: float = GRADED_GROWTH
    patch: float = 0.1

    def __post_init__(self) -> None:
        if self.teeth is not None:
            check_int_range("fe.teeth", self.teeth, 3, 99)
        check_int_range("fe.points", self.points, 4, 1000)
        check_range("fe.refinement", self.refinement, 0.1, 20.0)
        check_choice("fe.kind", self.kind, PLANE_KINDS)
        if self.slices is not None:
            check_int_range("fe.slices", self.slices, 1, MAX_SLICES)
        check_choice("fe.cuts", self.cuts, CUTS)
        check_choice("fe.mesh", self.mesh, MESHES)
        check_range("fe.tooth_size", self.tooth_size, 0.05, 2.0, unit="m_n")
        check_range("fe.body_size", self.body_size, self.tooth_size, 20.0, unit="m_n")
        check_range("fe.growth", self.growth, 0.05, 1.0)
        check_range("fe.patch", self.patch, 0.02, 0.2, unit="m_n")
        if self.patch < 0.1 and self.patch * self.refinement < 0.1 * (1.0 - 1e-9):
            raise InputError(f"fe.patch = {self.patch:g} m_n is finer than the mesh resolves at "
                             f"fe.refinement = {self.refinement:g}: a patch below 0.1 m_n must "
                             f"be at least 0.1 / refinement = {0.1 / self.refinement:.4g} m_n "
                             "(1.2 flank elements); raise fe.refinement or fe.patch")

    @property
    def sector_teeth(self) -> int:
        """Teeth of ``gearpipe fe``'s sector: ``teeth``, or :data:`SECTOR_TEETH`."""
        return SECTOR_TEETH if self.teeth is None else self.teeth


BODIES = ("whole", "sector")


@dataclass(frozen=True)
class FE3DSettings:
    """The 3D FE model of each gear (``[fe]`` with ``[contact] compliance = "fe3d"``).

    Attributes
    ----------
    body : "whole" (default): each gear's whole body (all teeth, body down to the bore,
        full face width; bore clamped, as the 2D whole gear), graded from the loaded
        teeth (:mod:`pipeline.fem.whole3d`); "sector": a sector of ``teeth`` teeth
        clamped at its bore and cut faces (stiffer than the gear: an upper bound).
    teeth : "sector" only: teeth per sector (3..99, odd values centre the loaded teeth),
        or None for the fewest that hold the tooth pairs in contact (``2 max|k| + 1``).
    points : flank grid points along the profile (2..200).
    face_points : flank grid points across the face width (1..200), or None for a spacing of
        about one patch half-width (the structural kernel then varies little between
        nodes; coarser face grids blur its peak at the diagonal).
    refinement : mesh refinement, 0.2..4: loaded flanks ``m_n / (3 refinement)``
        (:meth:`~pipeline.fem.mesh_settings.SectorSettings3D.for_gear`,
        :meth:`~pipeline.fem.mesh_settings.SectorSettings3D.whole_gear`). The mesh
        stiffness converges at rate 2.1-2.7 in the element size: at 1 it is about 1 %
        above the extrapolated limit, at 2 about 0.2 % (``workflows/fe3d_convergence.py``).
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
    solver : linear solver (:func:`pipeline.fem.solvers.solver_named`, 3D).
    mesh : whole gears: "graded" (default: the loaded tooth and its neighbours at the
        flank size, the other teeth and the body coarser;
        :mod:`pipeline.contact.fe3d_table`) or "uniform" (every tooth at the flank size,
        the body graded from them: the reference, several times the unknowns).
    """

    body: str = "whole"
    teeth: int | None = None
    points: int = 8
    face_points: int | None = None
    refinement: float = 1.0
    patch: float = 0.5
    face_margin: float = 1.0
    cuts: str = "clamped"
    ends: str = "free"
    slices: int | None = None
    hub_depth: float | None = None
    solver: str = "auto"
    mesh: str = "graded"

    def __post_init__(self) -> None:
        check_choice("fe.body", self.body, BODIES)
        check_choice("fe.mesh", self.mesh, MESHES)
        if self.teeth is not None:
            if self.body == "whole":
                raise InputError(f"fe.teeth = {self.teeth} applies to body = 'sector' only "
                                 "(a whole gear has all its teeth)")
            check_int_range("fe.teeth", self.teeth, 3, 99)
        check_int_range("fe.points", self.points, 2, 200)
        if self.face_points is not None:
            check_int_range("fe.face_points", self.face_points, 1, 200)
        check_range("fe.refinement", self.refinement, 0.2, 4.0)
        check_range("fe.patch", self.patch, 0.1, 2.0, unit="m_n")
        check_range("fe.face_margin", self.face_margin, 0.0, 10.0)
        check_choice("fe.cuts", self.cuts, CUTS)
        check_choice("fe.ends", self.ends, ENDS)
        if self.slices is not None:
            check_int_range("fe.slices", self.slices, 1, MAX_SLICES)
        if self.hub_depth is not None:
            check_range("fe.hub_depth", self.hub_depth, 1.0, 100.0, unit="m_n")
        check_choice("fe.solver", self.solver, SOLVERS)
