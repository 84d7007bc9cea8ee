"""Linear static elasticity: assemble once, factorise once, solve every load case.

This is the layer that FE stiffness studies build on (relief-groove coupling,
tooth influence coefficients): give a scikit-fem mesh, a material, the element
order, the DOFs to clamp, a block of load vectors and a solver
(:mod:`pipeline.fem.solvers`), and get all displacement fields
(:func:`solve_static`) or the compliance between the load cases
(:func:`load_compliance`) from one set-up of the free-free block.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import cached_property, partial

import numpy as np
import scipy.sparse as sp
from skfem import Basis
from skfem.mesh import Mesh

from pipeline.fem.condensation import condense
from pipeline.fem.elasticity import (
    assemble_fast,
    assemble_stiffness,
    default_intorder,
    lame_constants,
    vector_basis,
)
from pipeline.fem.solvers import DirectSolver, Factorization, Solver, SPDFactor
from pipeline.geometry.gear import Material
from pipeline.progress import Steps
from pipeline.validation import InputError, check_int_range


@dataclass(frozen=True, eq=False)
class ElasticModel:
    """An assembled linear-elastic body.

    Attributes
    ----------
    dofs : scikit-fem vector basis with one quadrature point per cell: the DOF numbering
        (``d * node + component``), facet DOFs and node locations, cheap to build.
    stiffness : (n_dof, n_dof) CSR stiffness matrix in N/m.
    lam, mu : Lame constants used, Pa.
    kind : "3d", "plane_strain" or "plane_stress".
    assembly_seconds : wall time of the assembly, s.
    order, intorder : Lagrange order and the quadrature order the stiffness was
        assembled with.
    """

    dofs: Basis
    stiffness: sp.csr_matrix
    lam: float
    mu: float
    kind: str
    assembly_seconds: float
    order: int = 2
    intorder: int = 2

    @property
    def n_dof(self) -> int:
        return self.stiffness.shape[0]

    @cached_property
    def basis(self) -> Basis:
        """The vector basis at the assembly's quadrature (values and gradients at every
        quadrature point: built on first use; on a 38k-cell P2 mesh it takes 0.5 GB)."""
        return vector_basis(self.dofs.mesh, self.order, self.intorder)


def build_model(
    mesh: Mesh, material: Material, order: int = 2, kind: str = "3d", assembly: str = "fast",
    intorder: int | None = None,
) -> ElasticModel:
    """Assemble the stiffness matrix of ``mesh`` (m) with ``material``.

    Parameters
    ----------
    mesh : scikit-fem triangle (2D, unit thickness) or tetrahedron mesh, lengths in m.
    material : elastic constants.
    order : Lagrange order of the displacement (1 or 2).
    kind : "3d" for tetrahedra; "plane_strain" or "plane_stress" for triangles.
    assembly : "fast" (batched) or "generic" (scikit-fem form).
    intorder : quadrature order (default exact for affine cells).
    """
    if (mesh.dim() == 3) != (kind == "3d"):
        raise InputError(f"elasticity.kind = {kind!r} does not fit a {mesh.dim()}D mesh")
    lam, mu = lame_constants(material, kind)
    t0 = time.perf_counter()
    intorder = default_intorder(mesh, order) if intorder is None else intorder
    if assembly == "fast":
        K = assemble_fast(mesh, lam, mu, order, intorder)
    else:
        K = assemble_stiffness(vector_basis(mesh, order, intorder), lam, mu, assembly)
    return ElasticModel(vector_basis(mesh, order, 0), K, lam, mu, kind,
                        time.perf_counter() - t0, order, intorder)


@dataclass(frozen=True, eq=False)
class StaticSolution:
    """Displacements of all load cases from one factorisation.

    Attributes
    ----------
    displacements : (n_dof, n_cases) in m (zero on clamped DOFs).
    reactions : (n_dof, n_cases) K u - f in N, non-zero only on clamped DOFs.
    method : solver used ("pardiso", "cholmod", "cholespy", "splu" or "pmg-cg").
    n_free : number of unknowns solved for.
    factor_seconds, solve_seconds : wall times, s.
    """

    displacements: np.ndarray
    reactions: np.ndarray
    method: str
    n_free: int
    factor_seconds: float
    solve_seconds: float


def free_system(model: ElasticModel, clamped_dofs: np.ndarray, solver: Solver | None = None,
                far: np.ndarray | None = None
                ) -> tuple[np.ndarray, Callable[[], Factorization]]:
    """Free DOFs (ascending) and a call that sets ``solver`` up on their block of the
    stiffness matrix (only its upper triangle for a direct solver that takes no more,
    PARDISO: on the traction gear of Yang et al. (2026), 282k free unknowns,
    :func:`free_block` builds it in 0.3-0.5 s of CPU against 0.7-0.8 s for
    ``K[free][:, free]`` and its triangle, without the two full copies).

    The call holds the block, not the model: a caller that drops its model before calling
    it factorises without the full stiffness in memory (145 MiB on the traction gear's
    176k unknowns).

    ``far`` : (n_dof,) boolean mask of DOFs that carry no load and are not read, to be
    eliminated exactly before the factorisation (:func:`pipeline.fem.condensation.condense`;
    a :class:`~pipeline.fem.solvers.DirectSolver` only). The DOFs returned are then the
    free DOFs kept, and the set-up solves for them alone.
    """
    fixed = np.zeros(model.n_dof, dtype=bool)
    fixed[np.asarray(clamped_dofs, dtype=np.int64)] = True
    free = np.flatnonzero(~fixed)
    solver = DirectSolver() if solver is None else solver
    eliminated = None if far is None else np.asarray(far, dtype=bool)[free]
    if eliminated is not None and eliminated.any():
        if not isinstance(solver, DirectSolver):
            raise InputError("far DOFs are condensed for a direct solver only, not "
                             f"{type(solver).__name__}")
        box = [free_block(model.stiffness, free, upper=True)]
        return free[~eliminated], partial(_condensed_factor, solver, box, eliminated)
    if isinstance(solver, DirectSolver) and solver.upper:
        return free, partial(solver.factorize_upper, free_block(model.stiffness, free,
                                                                upper=True))
    return free, partial(solver, free_block(model.stiffness, free), model.dofs, free)


def _condensed_factor(solver: DirectSolver, box: list[sp.csr_matrix], far: np.ndarray
                      ) -> SPDFactor:
    """Condense the upper triangle in ``box`` (taken out of it: the block is not held
    while the condensed system is factorised) and factorise what is kept; the
    condensation's time counts in the factorisation's."""
    condensed = condense(box.pop(), far, solver.method)
    factor = solver.factorize_upper(condensed.upper)
    return replace(factor, factor_seconds=factor.factor_seconds + condensed.seconds)


def free_block(K: sp.spmatrix, free: np.ndarray, upper: bool = False,
               rows_per_pass: int = 20_000) -> sp.csr_matrix:
    """``K[free][:, free]`` (or its upper triangle, diagonal included, if ``upper``) as a
    CSR matrix with sorted indices, built in one pass over ``K``'s rows without the
    intermediate copies of fancy indexing.

    Parameters
    ----------
    K : (n, n) sparse matrix.
    free : (m,) ascending DOF indices kept.
    upper : keep only the entries on and above the diagonal of the block.
    rows_per_pass : rows filtered together (bounds the temporary index arrays).
    """
    K = sp.csr_matrix(K)
    if not K.has_sorted_indices:
        K = K.copy()
        K.sort_indices()
    free = np.asarray(free, dtype=np.int64)
    n = K.shape[0]
    if free.size and (np.any(np.diff(free) <= 0) or free[0] < 0 or free[-1] >= n):
        raise InputError("free DOFs must be ascending, distinct and inside the matrix")
    new = np.full(n, -1, dtype=np.int64)
    new[free] = np.arange(free.size)
    index = np.int32 if K.nnz < 2**31 else np.int64
    counts = np.zeros(free.size, dtype=np.int64)
    data, indices = [], []
    for a in range(0, free.size, rows_per_pass):
        rows = free[a:a + rows_per_pass]
        lo, hi = K.indptr[rows], K.indptr[rows + 1]
        # the entries of these rows, in order (each row's slice of K.indices)
        take = np.repeat(lo - np.cumsum(np.r_[0, (hi - lo)[:-1]]), hi - lo) + np.arange(
            int((hi - lo).sum()))
        row = np.repeat(np.arange(a, a + rows.size), hi - lo)
        col = new[K.indices[take]]
        keep = col >= (row if upper else 0)
        counts[a:a + rows.size] = np.bincount(row[keep] - a, minlength=rows.size)
        data.append(K.data[take[keep]])
        indices.append(col[keep].astype(index))
    indptr = np.zeros(free.size + 1, dtype=index)
    np.cumsum(counts, out=indptr[1:])
    out = sp.csr_matrix((np.concatenate(data) if data else np.zeros(0),
                         np.concatenate(indices) if indices else np.zeros(0, index), indptr),
                        shape=(free.size, free.size))
    out.has_sorted_indices = True  # K's rows were sorted and the relabelling is monotone
    return out


def solve_static(
    model: ElasticModel, loads: np.ndarray, clamped_dofs: np.ndarray,
    solver: Solver | None = None,
) -> StaticSolution:
    """Solve K u = f with u = 0 on ``clamped_dofs`` for every column of ``loads``.

    Parameters
    ----------
    model : from :func:`build_model`.
    loads : (n_dof,) or (n_dof, n_cases) nodal forces in N.
    clamped_dofs : (m,) integer DOF indices held at zero (enough to remove all
        rigid-body motion, else the factorisation fails).
    solver : default ``DirectSolver()`` (sparse Cholesky, else SuperLU; see
        :mod:`pipeline.fem.solvers`).
    """
    F = np.asarray(loads, dtype=float)
    F = F[:, None] if F.ndim == 1 else F
    if F.shape[0] != model.n_dof:
        raise InputError(f"loads have {F.shape[0]} rows, the model has {model.n_dof} DOFs")
    free, factorize = free_system(model, clamped_dofs, solver)
    factor = factorize()
    t0 = time.perf_counter()
    U = np.zeros_like(F)
    U[free] = factor.solve(np.ascontiguousarray(F[free]))
    R = model.stiffness @ U - F
    R[free] = 0.0
    return StaticSolution(U, R, factor.method, free.size, factor.factor_seconds,
                          time.perf_counter() - t0)


@dataclass(frozen=True, eq=False)
class LoadCompliance:
    """Compliance between load cases ``F^T K^-1 F`` from one solver set-up.

    Attributes
    ----------
    matrix : (n_read, n_cases) work-conjugate displacement of reading ``i`` per unit of
        case ``j`` (m/N for loads in N); reading the load cases themselves it is square
        and symmetric to solver accuracy.
    method : solver used; iterations : CG iterations of the slowest block (0: direct).
    n_free : number of unknowns solved for.
    factor_seconds, solve_seconds : wall times (set-up; all blocks), s.
    """

    matrix: np.ndarray
    method: str
    iterations: int
    n_free: int
    factor_seconds: float
    solve_seconds: float


def load_compliance(
    model: ElasticModel, loads: sp.spmatrix, clamped_dofs: np.ndarray,
    solver: Solver | None = None, block: int | None = None, steps: Steps | None = None,
    read: sp.spmatrix | None = None,
) -> LoadCompliance:
    """``R^T K^-1 F`` with u = 0 on ``clamped_dofs`` (``R = F`` unless ``read`` is given):
    set up once (:func:`set_up`), solve ``block`` columns at a time
    (:func:`compliance_blocks`; only the block's displacements are ever held in memory).

    Parameters
    ----------
    model : from :func:`build_model`.
    loads : (n_dof, n_cases) sparse nodal forces in N.
    clamped_dofs : (m,) DOF indices held at zero.
    solver : default ``DirectSolver()`` (:mod:`pipeline.fem.solvers`).
    block : right-hand sides solved together (default: :func:`compliance_blocks`).
    steps : progress of the set-up ("factorise") and of the blocks ("solve") on stderr
        (:class:`pipeline.progress.Steps`); default silent.
    read : (n_dof, n_read) sparse work-conjugate weights of the displacements read (e.g.
        the patch loads of more points than are loaded); the matrix is then
        (n_read, n_cases): the reading ``i`` per unit of load case ``j``.
    """
    read = loads if read is None else read
    for name, m in (("loads", loads), ("read", read)):
        if m.shape[0] != model.n_dof:
            raise InputError(f"{name} have {m.shape[0]} rows, the model has {model.n_dof} DOFs")
    free, factor = set_up(model, clamped_dofs, solver, steps)
    return compliance_blocks(factor, free, loads, read, block, steps)


def set_up(model: ElasticModel, clamped_dofs: np.ndarray, solver: Solver | None = None,
           steps: Steps | None = None) -> tuple[np.ndarray, Factorization]:
    """The free DOFs (ascending) and ``solver`` set up on their block of the stiffness
    (:func:`free_system`, :func:`factorized`); the model is not needed by the solves that
    follow (:func:`compliance_blocks`)."""
    free, factorize = free_system(model, clamped_dofs, solver)
    return free, factorized(factorize, model.n_dof, steps)


def factorized(factorize: Callable[[], Factorization], n_dof: int, steps: Steps | None = None
               ) -> Factorization:
    """``factorize()`` (from :func:`free_system`) reported by ``steps`` as "factorise"
    (announced at once from 50k DOF: a sparse Cholesky of a large 3D model holds the GIL
    for seconds)."""
    steps = Steps("", enabled=False) if steps is None else steps
    with steps.step("factorise", announce=n_dof >= 50_000):
        return factorize()


def compliance_blocks(
    factor: Factorization, free: np.ndarray, loads: sp.spmatrix,
    read: sp.spmatrix | None = None, block: int | None = None, steps: Steps | None = None,
) -> LoadCompliance:
    """``R^T K^-1 F`` from a set-up ``factor`` of the free block (:func:`set_up`).

    Parameters
    ----------
    factor, free : from :func:`set_up`.
    loads : (n_dof, n_cases) sparse nodal forces in N (all DOFs; clamped rows ignored).
    read : (n_dof, n_read) sparse work-conjugate weights read (default ``loads``).
    block : right-hand sides solved together. Default: the cases split into equal
        blocks, as few as keep one block of vectors under 64 MB for a factor (its solves
        stream the whole factor once per block), 24 MB for an iteration (at least 16, at
        most 256 cases a block). A factor's block and its solution are the peak memory
        above the factor: on the traction gear of Yang et al. (2026) (89.6k unknowns
        kept, 272 cases), blocks of 133 (96 MB) solved in 3.4-3.5 s and took 0.19 GiB
        above the factor, blocks of 45 (32 MB) in 4.4-4.5 s and 0.06 GiB.
        Above glibc's largest mmap
        threshold (32 MB) every temporary of an iterative loop is a fresh mmap that the
        kernel must fault in: 150 columns at 50k DOF spent ~30 % of the time in the
        kernel (68.7 s vs 50 s at 60 columns, 63 s at 8, measured with the p-multigrid CG).
    steps : progress of the blocks ("solve") on stderr; default silent.
    """
    read = loads if read is None else read
    if loads.shape[0] != read.shape[0]:
        raise InputError(f"loads have {loads.shape[0]} rows, read {read.shape[0]}")
    steps = Steps("", enabled=False) if steps is None else steps
    if block is None:
        # a factor's solves stream the whole factor once per block: few blocks, but each
        # block and its solution add to the peak memory (PARDISO, 211k unknowns, 272
        # cases: 8.5 s in blocks of 16, 7.5 s of 32-64, 15 s in one block; measured)
        size = 24e6 if factor.method == "pmg-cg" else 64e6
        most = int(np.clip(size / (8 * free.size), 16, 256))
        n_blocks = max(1, math.ceil(loads.shape[1] / most))
        block = max(1, math.ceil(loads.shape[1] / n_blocks))  # equal blocks
    check_int_range("solver.block", block, 1, 100000)
    t0 = time.perf_counter()
    Ff = sp.csc_matrix(loads)[free]
    Rt = sp.csc_matrix(read)[free].T.tocsr()
    n = loads.shape[1]
    C = np.empty((read.shape[1], n))
    with steps.step("solve"):
        for a in range(0, n, block):
            # column-major blocks: PARDISO reads and writes them without a copy
            X = factor.solve(Ff[:, a:a + block].toarray(order="F"))
            C[:, a:a + block] = _read(Rt, X)
            del X
            steps.advance("solve", min(a + block, n), n, "load cases")
    return LoadCompliance(C, factor.method, factor.iterations, int(free.size),
                          factor.factor_seconds, time.perf_counter() - t0)


def _read(Rt: sp.csr_matrix, X: np.ndarray) -> np.ndarray:
    """``Rt @ X`` without a row-major copy of a column-major ``X`` (scipy's product
    makes one: 96 MB per block): one sparse product per column."""
    if X.ndim == 1 or X.flags.c_contiguous or not X.flags.f_contiguous:
        return Rt @ X
    out = np.empty((Rt.shape[0], X.shape[1]))
    for j in range(X.shape[1]):
        out[:, j] = Rt @ X[:, j]
    return out


def rigid_body_modes(points: np.ndarray) -> np.ndarray:
    """Rigid-body displacement fields on nodes (the near-null space of elasticity).

    Parameters
    ----------
    points : (dim, n_nodes) node coordinates in m, dim 2 or 3.

    Returns
    -------
    (dim * n_nodes, 3) in 2D (u_x, u_y, r_z) or (dim * n_nodes, 6) in 3D
    (u_x, u_y, u_z, r_x, r_y, r_z), DOF ``dim * node + component``; rotation
    columns are the displacement per radian of small rotation about the origin.
    """
    dim, n = points.shape
    if dim == 2:
        x, y = points
        B = np.zeros((n, 2, 3))
        B[:, 0, 0] = B[:, 1, 1] = 1.0
        B[:, 0, 2], B[:, 1, 2] = -y, x
        return B.reshape(2 * n, 3)
    x, y, z = points
    B = np.zeros((n, 3, 6))
    B[:, 0, 0] = B[:, 1, 1] = B[:, 2, 2] = 1.0
    # theta x r for theta = e_x, e_y, e_z
    B[:, 1, 3], B[:, 2, 3] = -z, y
    B[:, 0, 4], B[:, 2, 4] = z, -x
    B[:, 0, 5], B[:, 1, 5] = -y, x
    return B.reshape(3 * n, 6)
