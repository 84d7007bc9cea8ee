"""Influence coefficients of a 3D (helical) gear sector: normal compliance between flank points.

``G_ij`` (m/N) is the approach (displacement into the tooth along the normal) at
flank grid point ``i`` per unit normal load at point ``j``, for the points on
all loaded teeth of the sector, so the coupling of neighbouring teeth through
the rim is in the matrix. As in 2D (:mod:`pipeline.fem.influence`) loads are
consistent nodal forces of a smooth pressure patch: here
``cos^2(pi t / 2c) cos^2(pi w / 2c)`` in the profile (``t``) and face (``w``)
directions of the flank frame of :mod:`pipeline.fem.flank3d`, pressing along the
local inward surface normal, scaled so that its resultant is 1 N (the scale is
integrated on the curved facets, so a patch cut by an end face still carries
1 N). The approach at ``i`` is read with the *same* patch weights, which makes
``G_FE = F^T K^-1 F`` symmetric (Maxwell-Betti) to solver accuracy. All patches
are solved against one factorisation (or one preconditioner set-up) in blocks
of right-hand sides. The local near field is then removed analytically with the
Boussinesq half-space (:mod:`pipeline.fem.halfspace_separation`, pairs on the
same flank), leaving the *structural* compliance to which the contact solver
adds the local Hertzian approach.

Boundary conditions: the bore is clamped; the radial cut faces are clamped by
default (``cuts``, see :mod:`pipeline.fem.influence` for why); the end faces
are free (``ends = "free"``) or ``"sliding"`` (``u_z = 0``: a slice of a longer
face; for a spur sector with a load uniform across the face this is exactly
plane strain, which the tests use to compare with 2D).

Resolution. The FE must resolve the patch for the subtraction to cancel the near
field: with the default ``c = 0.3 m_n`` the flank elements should be ``m_n / 6``
(:class:`~pipeline.fem.sector3d.Sector3DSettings` refinement 2). At refinement 1
(``m_n / 3``) the structural self compliance at the pitch point is ~10 % below the
refinement-2 value (z 30, m_n 3 mm, beta 15 deg: 3.74e-9 vs 4.16e-9 m/N), and the
raw FE value ~6 % below; off-diagonal terms converge faster. The structural matrix
is symmetric but, like the 2D one, positive definite only up to that discretisation
error (smallest eigenvalue ~ -2 % of the largest on coarse meshes).

Solvers: ``"auto"`` takes CHOLMOD (scikit-sparse if installed, else the cholespy
wheel, see :mod:`pipeline.fem.solvers`), else the two-level p-multigrid CG of
:mod:`pipeline.fem.pmultigrid` (block right-hand sides, one set-up); ``"splu"``
(SuperLU) is fine for coarse models only (DESIGN.md: 36 s to factorise 42k DOF).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from pipeline.fem.flank3d import FlankGrid3D
from pipeline.fem.halfspace_separation import patch_halfspace_compliance
from pipeline.fem.linear_static import ElasticModel, build_model
from pipeline.fem.pmultigrid import TwoLevelPreconditioner, p1_prolongation, pmg_cg
from pipeline.fem.sector3d import SectorMesh3D
from pipeline.fem.solvers import factorize_spd, sparse_cholesky
from pipeline.fem.tetmesh import _tri_shape
from pipeline.validation import InputError, check_choice, check_int_range, check_positive

CUTS = ("clamped", "free")
ENDS = ("free", "sliding")
SOLVERS = ("auto", "cholmod", "cholespy", "splu", "pmg-cg")


@dataclass(frozen=True, eq=False)
class InfluenceMatrix3D:
    """Flank compliance matrix of a 3D sector.

    Attributes
    ----------
    points : the ``n`` flank grid points.
    fe : (n, n) FE patch-to-patch compliance, m/N (symmetric).
    local : (n, n) Boussinesq near field removed from it, m/N (same-flank pairs).
    patch_half_width : c, m.
    n_dof : DOFs of the FE model; n_free : unknowns after the boundary conditions.
    method : solver used ("cholmod", "cholespy", "splu" or "pmg-cg").
    iterations : CG iterations of the slowest block (0 for direct solvers).
    timings : wall times, s ("assembly", "loads", "factor" (set-up), "solve",
        "halfspace", "total").
    """

    points: FlankGrid3D
    fe: np.ndarray
    local: np.ndarray
    patch_half_width: float
    n_dof: int
    n_free: int
    method: str
    iterations: int
    timings: dict

    @property
    def structural(self) -> np.ndarray:
        """(n, n) structural compliance ``fe - local``, m/N."""
        return self.fe - self.local

    def symmetry_error(self) -> float:
        """max |G - G^T| / max |G| of the FE matrix (Maxwell-Betti check)."""
        return float(np.abs(self.fe - self.fe.T).max() / np.abs(self.fe).max())


def patch_loads(sector: SectorMesh3D, points: FlankGrid3D, half_width: float,
                intorder: int = 6) -> sp.csc_matrix:
    """Consistent nodal forces (3 N_nodes, n) of unit patches (module docstring), N per N.

    Column ``j`` presses along the inward surface normal on the triangles of the flank
    of point ``j`` (group ``right{k}`` / ``left{k}``) within ``|t|, |w| < c`` whose
    normal agrees with the point's; its resultant is 1 N. Integrated on the
    isoparametric 6-node surface triangles directly (no inverse mapping, which
    fails on coarse curved tetrahedra).
    """
    c = check_positive("influence3d.patch_half_width", half_width, unit="m")
    n_scalar = sector.mesh.doflocs.shape[1]
    names = [f"{'right' if s > 0 else 'left'}{int(k)}" for k, s in zip(points.tooth, points.side,
                                                                       strict=True)]
    Xq, Wq = get_quadrature(RefTri, intorder)
    N, dN = _tri_shape(Xq, 6)
    rows_all, cols_all, vals_all = [], [], []
    for name in sorted(set(names)):
        if name not in sector.tets.triangles:
            raise InputError(f"flank {name!r} is not in the sector mesh")
        tri = sector.tets.triangles[name]  # (6, nf)
        xe = sector.mesh.doflocs[:, tri]  # (3, 6, nf)
        X = np.einsum("cnf,nq->cfq", xe, N)  # (3, nf, nq)
        tang = np.einsum("cnf,ndq->cdfq", xe, dN)
        cr = np.cross(tang[:, 0], tang[:, 1], axis=0)  # (3, nf, nq)
        jac = np.linalg.norm(cr, axis=0)
        nrm = cr / jac
        dA = jac * Wq
        for j in (j for j, nm in enumerate(names) if nm == name):
            d = X - points.position[j][:, None, None]
            t = np.einsum("i,ifq->fq", points.tangent_profile[j], d)
            w = np.einsum("i,ifq->fq", points.tangent_face[j], d)
            cosn = np.einsum("i,ifq->fq", points.normal[j], nrm)
            inside = (np.abs(t) < c) & (np.abs(w) < c) & (np.abs(cosn) > 0.5)
            hit = np.flatnonzero(inside.any(axis=1))
            if hit.size == 0:
                raise InputError(f"load patch {j} missed flank {name!r} (is the point on it?)")
            q = np.where(inside[hit], (np.cos(0.5 * np.pi * t[hit] / c)
                                       * np.cos(0.5 * np.pi * w[hit] / c)) ** 2, 0.0)
            qw = q * dA[hit]
            qw /= qw.sum()  # unit resultant on the actual (curved, possibly cut) surface
            outward = nrm[:, hit] * np.sign(cosn[hit])  # triangle orientation is arbitrary
            for comp in range(3):
                f = np.einsum("aq,fq->af", N, -outward[comp] * qw)
                rows_all.append((3 * tri[:, hit] + comp).ravel())
                cols_all.append(np.full(f.size, j))
                vals_all.append(f.ravel())
    return sp.coo_matrix((np.concatenate(vals_all), (np.concatenate(rows_all),
                                                    np.concatenate(cols_all))),
                         shape=(3 * n_scalar, len(points))).tocsc()


def constrained_dofs(sector: SectorMesh3D, model: ElasticModel, cuts: str = "clamped",
                     ends: str = "free") -> np.ndarray:
    """DOFs held at zero: bore (all), cut faces (all, unless ``cuts`` is "free"),
    end faces (axial component, if ``ends`` is "sliding")."""
    check_choice("influence3d.cuts", cuts, CUTS)
    check_choice("influence3d.ends", ends, ENDS)
    names = ["bore"] + (["cut_left", "cut_right"] if cuts == "clamped" else [])
    out = [model.basis.get_dofs(sector.facets[n]).all() for n in names]
    if ends == "sliding":
        out += [model.basis.get_dofs(sector.facets[n]).all("u^3") for n in ("end0", "end1")]
    return np.unique(np.concatenate(out))


def influence_matrix_3d(
    sector: SectorMesh3D, points: FlankGrid3D, patch_half_width: float | None = None,
    method: str = "auto", cuts: str = "clamped", ends: str = "free", block: int | None = None,
    rtol: float = 1e-9, model: ElasticModel | None = None,
) -> InfluenceMatrix3D:
    """Structural flank compliance matrix of ``points`` on ``sector``.

    Parameters
    ----------
    sector : the 3D sector (:func:`pipeline.fem.sector3d.sector3d_mesh`).
    points : flank grid (:func:`pipeline.fem.flank3d.flank_grid` on the same sector).
    patch_half_width : c, m; default 0.3 m_n (the 3D meshes are coarser than 2D ones,
        m_n / 3 on the flanks at refinement 1: a patch must span a few elements).
    method : "auto", "cholmod", "cholespy", "splu" or "pmg-cg" (module docstring).
    cuts : "clamped" (default) or "free" radial cut faces.
    ends : "free" (default) or "sliding" end faces.
    block : right-hand sides solved together. Default: as many as keep one block of
        vectors under 24 MB (at least 16, at most 256). Above glibc's largest mmap
        threshold (32 MB) every temporary of the CG loop is a fresh mmap that the
        kernel must fault in: 150 columns at 50k DOF spent ~30 % of the time in the
        kernel (68.7 s vs 50 s at 60 columns, 63 s at 8, measured).
    rtol : relative residual of "pmg-cg" per right-hand side.
    model : a prebuilt model of ``sector`` (3D, P2), else assembled here.
    """
    check_choice("influence3d.method", method, SOLVERS)
    gear = sector.gear
    c = 0.3 * gear.module if patch_half_width is None else patch_half_width
    t0 = time.perf_counter()
    if model is None:
        model = build_model(sector.mesh, gear.material, order=2, kind="3d")
    t1 = time.perf_counter()
    F = patch_loads(sector, points, c)
    t2 = time.perf_counter()
    fixed = np.zeros(model.n_dof, dtype=bool)
    fixed[constrained_dofs(sector, model, cuts, ends)] = True
    free = np.flatnonzero(~fixed)
    K = model.stiffness[free][:, free].tocsr()
    if block is None:
        block = int(np.clip(24e6 / (8 * free.size), 16, 256))
    check_int_range("influence3d.block", block, 1, 100000)
    Ff = F[free].tocsc()
    if method == "auto":
        method = sparse_cholesky() or "pmg-cg"
    iterations = 0
    if method == "pmg-cg":
        P, _ = p1_prolongation(model.basis)
        M = TwoLevelPreconditioner(K, P[free])
    else:
        factor = factorize_spd(K, method)
    t3 = time.perf_counter()
    fe = np.empty((len(points), len(points)))
    for a in range(0, len(points), block):
        rhs = Ff[:, a:a + block].toarray()
        if method == "pmg-cg":
            sol = pmg_cg(K, rhs, None, rtol=rtol, preconditioner=M)
            U, iterations = sol.x, max(iterations, sol.iterations)
        else:
            U = factor.solve(rhs)
        fe[:, a:a + block] = Ff.T @ U
    t4 = time.perf_counter()
    local = np.zeros_like(fe)
    ii, jj = np.nonzero(points.same_flank())
    d = points.position[ii] - points.position[jj]
    # separation in the frame of j (and of i, averaged: H is even in s, so symmetric)
    st = 0.5 * (np.abs(np.einsum("ij,ij->i", d, points.tangent_profile[jj]))
                + np.abs(np.einsum("ij,ij->i", d, points.tangent_profile[ii])))
    sw = 0.5 * (np.abs(np.einsum("ij,ij->i", d, points.tangent_face[jj]))
                + np.abs(np.einsum("ij,ij->i", d, points.tangent_face[ii])))
    h = np.sqrt(points.depth[ii] * points.depth[jj])
    local[ii, jj] = patch_halfspace_compliance(st, sw, h, c, gear.material)
    t5 = time.perf_counter()
    timings = {"assembly": t1 - t0, "loads": t2 - t1, "factor": t3 - t2, "solve": t4 - t3,
               "halfspace": t5 - t4, "total": t5 - t0}
    return InfluenceMatrix3D(points, fe, local, c, model.n_dof, int(free.size), method,
                             iterations, timings)
