"""Consistent nodal forces of smooth pressure patches on the flanks of a 2D or 3D sector.

Each flank point ``j`` gets one load case: a pressure patch centred on it, pressing
along the local inward normal on the facets of its flank (group ``right{k}`` /
``left{k}`` of the sector mesh), as consistent nodal forces of the P2 displacement.

* 2D: ``q(t) = cos^2(pi t / 2c) / c`` over the arc coordinate ``t`` (``|t| < c``), a
  unit line load (N/m) integrated on the isoparametric 3-node boundary edges directly
  (scikit-fem's ``FacetBasis`` gives the same forces to 1e-13 but inverts the curved
  triangle map by a Newton iteration that fails on small elements of large gears).
* 3D: ``cos^2(pi t / 2c) cos^2(pi w / 2c)`` in the profile (``t``) and face (``w``)
  directions of the flank frame (:mod:`pipeline.fem.flank_grid`), scaled so that its
  resultant is 1 N (the scale is integrated on the curved facets, so a patch cut by an
  end face still carries 1 N). Integrated on the isoparametric 6-node surface
  triangles directly (no inverse mapping, which fails on coarse curved tetrahedra).

Reading the approach at ``i`` with the *same* weights makes the influence matrix
``F^T K^-1 F`` symmetric (:mod:`pipeline.fem.influence`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from pipeline.fem.flank import FlankPoints
from pipeline.fem.sector2d import SectorMesh2D
from pipeline.fem.sector3d import SectorMesh3D
from pipeline.fem.tetmesh import tri_shape
from pipeline.validation import InputError, check_positive


def patch_loads(sector: SectorMesh2D | SectorMesh3D, points: FlankPoints,
                half_width: float) -> sp.csc_matrix:
    """(dim N_nodes, n) consistent nodal forces of the unit patches of half-width ``half_width``
    (m) centred on ``points`` (module docstring): N per N/m in 2D, N per N in 3D."""
    c = check_positive("influence.patch_half_width", half_width, unit="m")
    return _patch_loads_2d(sector, points, c) if points.dim == 2 else _patch_loads_3d(
        sector, points, c)


def flank_names(points: FlankPoints) -> list[str]:
    """Mesh group of each point's flank: ``right{k}`` or ``left{k}``."""
    return [f"{'right' if s > 0 else 'left'}{int(k)}"
            for k, s in zip(points.tooth, points.side, strict=True)]


def boundary_edges_2d(sector: SectorMesh2D, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Scalar P2 DOFs (3, nf) of the facets of group ``name`` (end vertices, then the edge
    node) and the coordinates (2, 3, nf) of those nodes, m."""
    mesh = sector.mesh
    f = sector.facets[name]
    dofs = np.vstack([mesh.facets[:, f], mesh.nvertices + f])
    return dofs, mesh.doflocs[:, dofs]


def _edge_frames(sector: SectorMesh2D, name: str, order: int
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Quadrature on the curved 3-node edges of group ``name``: scalar DOFs (3, nf), shape
    values (3, nq), points X (2, nf, nq), outward unit normals (2, nf, nq), length weights
    (nf, nq) in m."""
    dofs, xe = boundary_edges_2d(sector, name)
    g, w = np.polynomial.legendre.leggauss(order // 2 + 1)
    xi, w = 0.5 * (g + 1.0), 0.5 * w
    N = np.array([(1 - xi) * (1 - 2 * xi), xi * (2 * xi - 1), 4 * xi * (1 - xi)])
    dN = np.array([4 * xi - 3, 4 * xi - 1, 4 - 8 * xi])
    X = np.einsum("cnf,nq->cfq", xe, N)
    T = np.einsum("cnf,nq->cfq", xe, dN)
    jac = np.hypot(T[0], T[1])
    nrm = np.array([T[1], -T[0]]) / jac
    # outward: away from the third vertex of the triangle that owns the facet
    mesh = sector.mesh
    cell = mesh.f2t[0, sector.facets[name]]
    inside = mesh.doflocs[:, mesh.t[:3, cell]].mean(axis=1)  # (2, nf) vertex centroid
    out = np.einsum("cf,cf->f", nrm.mean(axis=2), xe[:, 2] - inside) > 0
    nrm = np.where(out[None, :, None], nrm, -nrm)
    return dofs, N, X, nrm, jac * w


def _patch_loads_2d(sector: SectorMesh2D, points: FlankPoints, c: float,
                    intorder: int = 12) -> sp.csc_matrix:
    """Consistent nodal forces (2 N_nodes, n) of unit cos^2 pressure patches, N per (N/m).

    Column ``j``: the pressure ``q_j(t) = cos^2(pi t / 2c) / c`` (t: distance from the
    patch centre along the flank tangent, |t| < c) acting along the inward normal on
    the facets of the flank of point ``j``; its resultant is a unit load (N/m).
    Integrated (Gauss-Legendre, exact to degree ``intorder``) on the isoparametric
    3-node boundary edges directly, where the P2 basis is the quadratic Lagrange basis
    of the edge: no inverse mapping of the curved triangles (scikit-fem's Newton
    inversion of ``FacetBasis`` stops at an absolute tolerance that round-off of
    coordinates ~ r_a exceeds once elements are ~1e-3 r_a small: the 104-tooth gear
    at refinement 2, the 50-tooth gear at refinement 4).
    """
    n_scalar = sector.mesh.doflocs.shape[1]
    cols = flank_names(points)
    for name in set(cols):
        if name not in sector.facets:
            raise InputError(f"flank {name!r} is not in the sector mesh")
    rows_all, cols_all, vals_all = [], [], []
    for name in sorted(set(cols)):
        idx = [j for j, nm in enumerate(cols) if nm == name]
        dofs, N, X, nrm, dx = _edge_frames(sector, name, intorder)
        for j in idx:
            t = ((X[0] - points.position[j, 0]) * points.tangent[j, 0]
                 + (X[1] - points.position[j, 1]) * points.tangent[j, 1])
            # same-flank facets far along the profile are excluded by |t| < c; facets of
            # the flank bending away (tip land) by requiring the normal to agree.
            agree = (nrm[0] * points.normal[j, 0] + nrm[1] * points.normal[j, 1]) > 0.5
            q = np.where((np.abs(t) < c) & agree, np.cos(0.5 * np.pi * t / c) ** 2 / c, 0.0)
            hit = np.flatnonzero(q.any(axis=1))
            w = q[hit] * dx[hit]
            for comp in range(2):
                f = np.einsum("aq,fq->af", N, -nrm[comp][hit] * w)
                rows_all.append((2 * dofs[:, hit] + comp).ravel())
                cols_all.append(np.full(f.size, j))
                vals_all.append(f.ravel())
    F = sp.coo_matrix((np.concatenate(vals_all), (np.concatenate(rows_all),
                                                 np.concatenate(cols_all))),
                      shape=(2 * n_scalar, len(points))).tocsc()
    total = np.asarray(F.sum(axis=0)).ravel()
    if np.any(np.abs(total) < 1e-12):
        raise InputError("a load patch missed its flank (is the point on the meshed involute?)")
    return F


def _patch_loads_3d(sector: SectorMesh3D, points: FlankPoints, c: float,
                    intorder: int = 6) -> sp.csc_matrix:
    """Consistent nodal forces (3 N_nodes, n) of unit patches, N per N.

    Column ``j`` presses along the inward surface normal on the triangles of the flank
    of point ``j`` (group ``right{k}`` / ``left{k}``) within ``|t|, |w| < c`` whose
    normal agrees with the point's; its resultant is 1 N. Integrated on the
    isoparametric 6-node surface triangles directly (no inverse mapping, which
    fails on coarse curved tetrahedra).
    """
    n_scalar = sector.mesh.doflocs.shape[1]
    names = flank_names(points)
    Xq, Wq = get_quadrature(RefTri, intorder)
    N, dN = tri_shape(Xq, 6)
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
            t = np.einsum("i,ifq->fq", points.tangent[j], d)
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
