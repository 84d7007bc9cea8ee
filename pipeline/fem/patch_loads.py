"""Consistent nodal forces of smooth pressure patches on the flanks of a 2D or 3D sector.

Each flank point ``j`` gets one load case: a pressure patch centred on it, pressing
along the local inward normal on the facets of its flank (group ``right{k}`` /
``left{k}`` of the sector mesh), as consistent nodal forces of the P2 displacement.

* 2D: ``q(t) = cos^2(pi t / 2c) / c`` over the arc coordinate ``t`` (``|t| < c``), a
  unit line load (N/m) integrated with scikit-fem's ``FacetBasis``.
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
from skfem import ElementTriP2, FacetBasis
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


def _patch_loads_2d(sector: SectorMesh2D, points: FlankPoints, c: float,
                    intorder: int = 12) -> sp.csc_matrix:
    """Consistent nodal forces (2 N_nodes, n) of unit cos^2 pressure patches, N per (N/m).

    Column ``j``: the pressure ``q_j(t) = cos^2(pi t / 2c) / c`` (t: distance from the
    patch centre along the flank tangent, |t| < c) acting along the inward normal on
    the facets of the flank of point ``j``; its resultant is a unit load (N/m).
    """
    mesh = sector.mesh
    n_scalar = mesh.doflocs.shape[1]
    cols = flank_names(points)
    for name in set(cols):
        if name not in sector.facets:
            raise InputError(f"flank {name!r} is not in the sector mesh")
    rows_all, cols_all, vals_all = [], [], []
    for name in sorted(set(cols)):
        idx = [j for j, nm in enumerate(cols) if nm == name]
        fb = FacetBasis(mesh, ElementTriP2(), facets=sector.facets[name], intorder=intorder)
        X = np.asarray(fb.global_coordinates())  # (2, nf, nq)
        nrm = fb.normals  # outward (2, nf, nq)
        phi = np.stack([np.asarray(fb.basis[a][0]) for a in range(fb.Nbfun)])  # (a, nf, nq)
        dofs = fb.element_dofs  # (a, nf)
        for j in idx:
            t = ((X[0] - points.position[j, 0]) * points.tangent[j, 0]
                 + (X[1] - points.position[j, 1]) * points.tangent[j, 1])
            # same-flank facets far along the profile are excluded by |t| < c; facets of
            # the flank bending away (tip land) by requiring the normal to agree.
            agree = (nrm[0] * points.normal[j, 0] + nrm[1] * points.normal[j, 1]) > 0.5
            q = np.where((np.abs(t) < c) & agree, np.cos(0.5 * np.pi * t / c) ** 2 / c, 0.0)
            w = q * fb.dx
            for comp in range(2):
                f = np.einsum("afq,fq->af", phi, -nrm[comp] * w)
                rows_all.append((2 * dofs + comp).ravel())
                cols_all.append(np.full(dofs.size, j))
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
