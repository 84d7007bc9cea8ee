"""Influence coefficients of a 2D or 3D gear sector: the normal compliance between flank points.

``G_ij`` is the approach (displacement into the tooth along the normal) at flank
point ``i`` per unit normal load at flank point ``j``, for points on all loaded
teeth of the sector, so the coupling of neighbouring teeth through the rim is in
the matrix. One routine serves both dimensions, as scikit-fem's bases do:

1. assemble the P2 elasticity model (:func:`pipeline.fem.linear_static.build_model`,
   batched assembly tested against scikit-fem's forms);
2. load every point with a smooth pressure patch of half-width ``c``
   (:mod:`pipeline.fem.patch_loads`) and read its approach with the *same* patch
   weights, so ``G_FE = F^T K^-1 F`` is symmetric (Maxwell-Betti) to solver accuracy;
3. hold the bore, the cut faces and (3D, optionally) the end faces
   (:func:`constrained_dofs`);
4. set the solver up once on the free block, the model dropped first (on a large 3D
   whole gear with a direct solver, the part of the body far from the loaded and read
   points eliminated exactly first: :func:`far_part`), and solve all
   patches in blocks of right-hand sides (:func:`pipeline.fem.linear_static.free_system`,
   :func:`~pipeline.fem.linear_static.factorized` and
   :func:`~pipeline.fem.linear_static.compliance_blocks`);
5. remove the local near field analytically, leaving the *structural* compliance to
   which the contact solver adds the local Hertzian approach (Yang et al. 2026, eq. 24):
   the half-plane in 2D (:func:`~pipeline.fem.nearfield_halfplane.nearfield_halfplane`),
   the Boussinesq half-space in 3D
   (:func:`~pipeline.fem.nearfield_halfspace.nearfield_halfspace`), same-flank pairs.

What differs by dimension is only the flank geometry (2D profile points of
:func:`pipeline.fem.flank.flank_points`, 3D profile x face grids of
:func:`pipeline.fem.flank_grid.flank_grid`), the patch and the near-field kernel.
2D models are per unit face width: ``G`` is in m^2/N (m per N/m);
:meth:`InfluenceMatrix.matrix` divides by a face width for m/N. 3D ``G`` is in m/N.

Boundary conditions. The sector is clamped on its bore (external gear) or outer
rim (internal gear, 2D). Its radial cut faces are clamped too by default: with free
cut faces a narrow sector rotates as a wedge about the bore, which a full gear
cannot do (the assembly-error paper's gear, bore 21 mm under a 71 mm root circle: 13x the
analytical compliance with 5 free-cut teeth). Clamped cuts approach the full-gear
value from the stiff side as teeth are added, free cuts from the flexible side;
z 30, bore 30 mm, plane stress, middle tooth vs the analytical compliance:
3 teeth -25 % / +12 %, 7 teeth -18 % / -15 %, 11 teeth -17 % / -16 % (clamped /
free, lowest point on the flank). Use >= 5 teeth (more for deep bodies) when the
body compliance matters. 3D end faces are free (``ends = "free"``) or ``"sliding"``
(``u_z = 0``: a slice of a longer face; for a spur sector with a load uniform across
the face this is exactly plane strain, which the tests use to compare with 2D).

3D resolution. The FE must resolve the patch for the subtraction to cancel the near
field: with the default ``c = 0.3 m_n`` the flank elements should be ``m_n / 6``
(:class:`~pipeline.fem.mesh_settings.SectorSettings3D` refinement 2). At refinement 1
(``m_n / 3``) the structural self compliance at the pitch point is ~10 % below the
refinement-2 value (z 30, m_n 3 mm, beta 15 deg: 3.74e-9 vs 4.16e-9 m/N), and the
raw FE value ~6 % below; off-diagonal terms converge faster. The structural matrix
is symmetric but, like the 2D one, positive definite only up to that discretisation
error (smallest eigenvalue ~ -2 % of the largest on coarse meshes).

Solvers are passed in (:mod:`pipeline.fem.solvers`); the default,
``solver_named("auto", dim)``, is the sparse Cholesky (MKL PARDISO where its wheels
exist, else scikit-sparse's CHOLMOD, else the cholespy wheel), without one SuperLU in 2D
and the p-multigrid CG of :mod:`pipeline.fem.pmultigrid` in 3D (SuperLU took 36 s to
factorise 42k DOF on 2 cores).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from pipeline.fem.condensation import far_by_angle
from pipeline.fem.flank import FlankPoints
from pipeline.fem.linear_static import (
    ElasticModel,
    build_model,
    compliance_blocks,
    factorized,
    free_system,
)
from pipeline.fem.nearfield_halfplane import nearfield_halfplane
from pipeline.fem.patch_loads import patch_loads
from pipeline.fem.sector2d import SectorMesh2D
from pipeline.fem.sector3d import SectorMesh3D
from pipeline.fem.settings import CUTS, ENDS
from pipeline.fem.solvers import DirectSolver, Solver, solver_named
from pipeline.progress import Steps
from pipeline.validation import InputError, check_choice, check_positive

KINDS = {2: ("plane_strain", "plane_stress"), 3: ("3d",)}


@dataclass(frozen=True, eq=False)
class InfluenceMatrix:
    """Flank compliance matrix of a sector.

    Attributes
    ----------
    points : the ``n`` flank points.
    fe : (n, n) FE patch-to-patch compliance (symmetric), m^2/N in 2D (per unit face
        width), m/N in 3D.
    local : (n, n) analytical near field removed from it (half-plane in 2D, Boussinesq
        half-space in 3D; same-flank pairs), same unit.
    patch_half_width : c, m.
    kind : "plane_strain", "plane_stress" or "3d".
    n_dof : DOFs of the FE model; n_free : unknowns after the boundary conditions.
    n_condensed : of them, eliminated before the factorisation (the far body,
        :func:`far_part`; the factorisation solved for ``n_free - n_condensed``).
    method : solver used ("cholmod", "cholespy", "splu" or "pmg-cg").
    iterations : CG iterations of the slowest block (0 for direct solvers).
    timings : wall times, s ("assembly", "loads", "factor" (set-up), "solve",
        "nearfield", "total").
    loaded : (m,) indices of the points that carried a load case, or None for all; with
        ``m < n`` the matrices are (n, m): the approach at every point per unit load at
        each loaded point.
    """

    points: FlankPoints
    fe: np.ndarray
    local: np.ndarray
    patch_half_width: float
    kind: str
    n_dof: int
    n_free: int
    method: str
    iterations: int
    timings: dict
    loaded: np.ndarray | None = None
    n_condensed: int = 0

    @property
    def structural(self) -> np.ndarray:
        """(n, n) structural compliance ``fe - local``, without the Hertz approach."""
        return self.fe - self.local

    def matrix(self, face_width: float) -> np.ndarray:
        """(n, n) structural compliance in m/N of a 2D matrix for a tooth of ``face_width``
        (m)."""
        if self.kind == "3d":
            raise InputError("a 3D influence matrix is in m/N already: use .structural")
        return self.structural / check_positive("face_width", face_width, unit="m")

    def symmetry_error(self) -> float:
        """max |G - G^T| / max |G| of the FE matrix between the loaded points
        (Maxwell-Betti check)."""
        fe = self.fe if self.loaded is None else self.fe[self.loaded]
        return float(np.abs(fe - fe.T).max() / np.abs(fe).max())


def constrained_dofs(sector: SectorMesh2D | SectorMesh3D, model: ElasticModel,
                     cuts: str = "clamped", ends: str = "free") -> np.ndarray:
    """DOFs held at zero: bore (all), cut faces (all, unless ``cuts`` is "free"; a whole
    gear, 2D or 3D, has none), end faces of a 3D sector (axial component, if ``ends`` is
    "sliding")."""
    check_choice("influence.cuts", cuts, CUTS)
    check_choice("influence.ends", ends, ENDS)
    if ends == "sliding" and model.kind != "3d":
        raise InputError("influence.ends = 'sliding' needs a 3D sector")
    names = ["bore"] + ([n for n in ("cut_left", "cut_right") if n in sector.facets]
                        if cuts == "clamped" else [])
    out = [model.dofs.get_dofs(sector.facets[n]).all() for n in names]
    if ends == "sliding":
        out += [model.dofs.get_dofs(sector.facets[n]).all("u^3") for n in ("end0", "end1")]
    return np.unique(np.concatenate(out))


def _patch_half_width(sector: SectorMesh2D | SectorMesh3D, points: FlankPoints,
                      c: float | None) -> float:
    """Default c: 0.1 m_n in 2D (fine meshes), 0.3 m_n in 3D (m_n / 3 on the flanks at
    refinement 1: a patch must span a few elements). In 2D the patch must fit on the
    involute (mesh-independent, so the FE part converges)."""
    gear = sector.gear
    if points.dim == 3:
        return 0.3 * gear.module if c is None else c
    c = 0.1 * gear.module if c is None else c
    rb = gear.base_radius
    arc_tip = (gear.active_tip_radius**2 - rb**2) / (2 * rb)  # the involute's end
    room = np.abs(arc_tip - points.arc)  # internal gears: the tip is the small radius
    if np.any(room < c):
        raise InputError(f"flank point(s) closer than the patch half-width {c:.4g} m to the end "
                         f"of the involute (arc room {room.min():.4g} m)")
    return c


def influence_matrix(
    sector: SectorMesh2D | SectorMesh3D, points: FlankPoints,
    patch_half_width: float | None = None, *, kind: str | None = None,
    solver: Solver | None = None, cuts: str = "clamped", ends: str = "free",
    block: int | None = None, model: ElasticModel | None = None, steps: Steps | None = None,
    loaded: np.ndarray | None = None, condense: bool | None = None,
) -> InfluenceMatrix:
    """Structural flank compliance matrix of ``points`` on ``sector`` (one solver set-up).

    Parameters
    ----------
    sector : a 2D (:func:`pipeline.fem.sector2d.sector_mesh_2d`) or 3D
        (:func:`pipeline.fem.sector3d.sector_mesh_3d`) sector.
    points : flank points on it (:func:`pipeline.fem.flank.flank_points` with the same
        ``teeth``, or :func:`pipeline.fem.flank_grid.flank_grid` on the same sector).
    patch_half_width : c, m; default 0.1 m_n in 2D, 0.3 m_n in 3D.
    kind : 2D "plane_strain" (default) or "plane_stress"; 3D "3d" (default).
    solver : default ``solver_named("auto", dim)`` (module docstring).
    cuts : "clamped" (default) or "free" cut faces.
    ends : 3D end faces, "free" (default) or "sliding".
    block : right-hand sides solved together (default:
        :func:`pipeline.fem.linear_static.compliance_blocks`).
    model : a prebuilt P2 model of ``sector`` (reuse across calls), else assembled here.
    steps : progress and wall time of each step (assembly, loads, factorise, solve, near
        field) on stderr (:class:`pipeline.progress.Steps`); default silent.
    loaded : indices of the points that carry a load case (default: all): one solve per
        loaded point, every point read (the matrices are then (n, m)); the near field of
        the loaded points' flanks only (it is zero between flanks).
    condense : eliminate the body far from the loaded and read points before the
        factorisation (:func:`far_part`; the same matrix to round-off, less memory).
        Default: where it pays, a 3D whole gear (no cut faces) with a direct solver, at
        least :data:`CONDENSE_MIN_DOFS` DOFs of which :data:`CONDENSE_MIN_SHARE` or more
        are far.
    """
    dim = points.dim
    kind = KINDS[dim][0] if kind is None else kind
    check_choice("influence.kind", kind, KINDS[dim])
    gear = sector.gear
    c = _patch_half_width(sector, points, patch_half_width)
    if model is not None and model.kind != kind:
        raise InputError(f"model kind {model.kind!r} differs from influence.kind {kind!r}")
    steps = Steps("", enabled=False) if steps is None else steps
    t0 = time.perf_counter()
    if model is None:
        with steps.step("assembly"):
            model = build_model(sector.mesh, gear.material, order=2, kind=kind)
    t1 = time.perf_counter()
    cols = None if loaded is None else np.asarray(loaded, dtype=np.int64).reshape(-1)
    with steps.step("loads"):
        R = patch_loads(sector, points, c)
        F = R if cols is None else R[:, cols]
    t2 = time.perf_counter()
    n_dof = model.n_dof
    solver = solver_named("auto", dim) if solver is None else solver
    far = far_part(sector, model, R, solver, condense)
    clamped = constrained_dofs(sector, model, cuts, ends)
    free, factorize = free_system(model, clamped, solver, far)
    n_free = n_dof - clamped.size
    # the factorisation and the solves need the free block only: a model built here is
    # dropped before them (its full stiffness is 145 MiB on the traction gear's 176k
    # unknowns, while the factorisation holds its peak memory)
    del model
    _drop_mapping_cache(sector.mesh)
    factor = factorized(factorize, n_dof, steps)
    fe = compliance_blocks(factor, free, F, None if cols is None else R, block, steps)
    del factor
    t3 = time.perf_counter()
    with steps.step("near field"):
        local = _near_field(points, c, gear.material, kind, cols)
    t4 = time.perf_counter()
    timings = {"assembly": t1 - t0, "loads": t2 - t1, "factor": fe.factor_seconds,
               "solve": fe.solve_seconds, "nearfield": t4 - t3, "total": t4 - t0}
    return InfluenceMatrix(points, fe.matrix, local, c, kind, n_dof, n_free,
                           fe.method, fe.iterations, timings, cols, n_free - free.size)


def _drop_mapping_cache(mesh) -> None:
    """Forget the isoparametric mapping scikit-fem keeps on ``mesh`` with the Jacobians of
    every basis built on it (77 MB on the traction gear of Yang et al. (2026)), so that
    the factorisation does not hold them; a later basis builds it again."""
    mesh.__dict__.pop("_cached_mapping", None)


CONDENSE_MIN_DOFS = 60_000
"""Smallest model condensed by default (below it a factorisation takes a few hundred MB
at most and a second: the two-step one is not worth its extra set-up)."""
CONDENSE_MIN_SHARE = 0.25
"""Smallest share of the DOFs far from the loads for the default condensation (the
traction pair of Yang et al. (2026): the gear z 104 has 49 % far and its factorisation
takes 506 instead of 770 MB; the pinion z 31 has 16 % far, 488 instead of 500 MB)."""


def far_part(sector: SectorMesh2D | SectorMesh3D, model: ElasticModel, read: sp.spmatrix,
             solver: Solver, condense: bool | None = None) -> np.ndarray | None:
    """The DOFs of a whole 3D gear eliminated before its factorisation, or None.

    Far: more than one pitch angle (2 pi / z) outside the angular span, about the gear
    axis, of the DOFs that ``read`` (the patch weights of every point) touches
    (:func:`pipeline.fem.condensation.far_by_angle`). ``condense``: True (a whole 3D gear
    with a :class:`~pipeline.fem.solvers.DirectSolver` required), False (None returned)
    or None (where it pays: :func:`influence_matrix`).
    """
    if condense is False:
        return None
    whole = model.kind == "3d" and not {"cut_left", "cut_right"} & set(sector.facets)
    if not whole or not isinstance(solver, DirectSolver):
        if condense:
            raise InputError("influence.condense needs a whole 3D gear (no cut faces) and a "
                             "direct solver")
        return None
    touched = np.zeros(model.n_dof, dtype=bool)
    touched[sp.coo_matrix(read).row] = True
    far = far_by_angle(model.dofs.doflocs, touched, 2 * np.pi / sector.gear.teeth)
    if condense is None and (model.n_dof < CONDENSE_MIN_DOFS
                             or far.mean() < CONDENSE_MIN_SHARE):
        return None
    return far if far.any() else None


def _near_field(points: FlankPoints, c: float, material, kind: str,
                cols: np.ndarray | None) -> np.ndarray:
    """The analytical near field (n, n), or (n, m) at the loaded points ``cols``: computed
    on the flanks that carry them only (same-flank pairs; zero elsewhere)."""
    def near(pts: FlankPoints) -> np.ndarray:
        if pts.dim == 2:
            return nearfield_halfplane(pts, c, material, kind)
        # 3D only: its spline imports scipy.interpolate (0.7 s), which 2D runs do without
        from pipeline.fem.nearfield_halfspace import nearfield_halfspace

        return nearfield_halfspace(pts, c, material)

    if cols is None:
        return near(points)
    flank = points.tooth * 2 + (points.side > 0)
    rows = np.flatnonzero(np.isin(flank, flank[cols]))
    local = np.zeros((len(points), cols.size))
    H = near(points.subset(rows))
    local[rows] = H[:, np.searchsorted(rows, cols)]
    return local
