"""Gmsh-free tetrahedral mesh data -> scikit-fem mesh, named surfaces, surface integrals."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import MeshTet1, MeshTet2
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from pipeline.fem.gmsh_session import TetMeshData


@dataclass(frozen=True, eq=False)
class SkfemTetMesh:
    """A scikit-fem tetrahedral mesh with its named boundary surfaces.

    Attributes
    ----------
    mesh : ``MeshTet2`` (curved quadratic cells) or ``MeshTet1``.
    facets : name -> (n,) facet indices of ``mesh``.
    triangles : name -> (6, n) (quadratic) or (3, n) node indices of each surface
        triangle in the scalar P2 (resp. P1) DOF numbering of ``mesh``, i.e. the
        numbering a scikit-fem P2 (P1) basis uses; vertices first, then the
        mid-edge nodes of edges (0,1) (1,2) (2,0).
    """

    mesh: MeshTet1
    facets: dict
    triangles: dict


def to_skfem(data: TetMeshData) -> SkfemTetMesh:
    """Build the scikit-fem mesh of ``data`` and renumber its named surfaces."""
    cells = data.cells
    n_points = data.points.shape[1]
    if data.order == 2:
        mesh = MeshTet2(data.points, cells)
        # MeshTet2 numbers vertices 0..n_v-1 in increasing original index and the
        # edge nodes by its own edge numbering: follow both.
        node_map = np.full(n_points, -1, dtype=np.int64)
        vertices = np.unique(cells[:4])
        node_map[vertices] = np.arange(vertices.size)
        node_map[cells[4:].ravel()] = mesh.dofs.element_dofs[4:].ravel()
    else:
        mesh = MeshTet1(data.points, cells)
        node_map = np.arange(n_points)
    n_v = mesh.nvertices
    f_sorted = np.sort(mesh.facets, axis=0).astype(np.int64)
    f_keys = (f_sorted[0] * n_v + f_sorted[1]) * n_v + f_sorted[2]
    order = np.argsort(f_keys)
    facets, triangles = {}, {}
    for name, tri in data.surfaces.items():
        tri_new = node_map[tri]
        if np.any(tri_new < 0):
            raise ValueError(f"surface {name!r} has nodes that belong to no cell")
        v = np.sort(tri_new[:3], axis=0)
        keys = (v[0] * n_v + v[1]) * n_v + v[2]
        pos = np.clip(np.searchsorted(f_keys, keys, sorter=order), 0, order.size - 1)
        idx = order[pos]
        if keys.size and not np.array_equal(f_keys[idx], keys):
            raise ValueError(f"surface {name!r} has triangles that are not mesh facets")
        facets[name] = idx
        triangles[name] = tri_new
    return SkfemTetMesh(mesh, facets, triangles)


def tri_shape(X: np.ndarray, nn: int) -> tuple[np.ndarray, np.ndarray]:
    """Shape functions (nn, nq) and their reference gradients (nn, 2, nq) on a triangle."""
    xi, eta = X
    l1, l2, l3 = 1.0 - xi - eta, xi, eta
    if nn == 3:
        N = np.array([l1, l2, l3])
        dN = np.array([[-np.ones_like(xi), -np.ones_like(xi)], [np.ones_like(xi), 0 * xi],
                       [0 * xi, np.ones_like(xi)]])
        return N, dN
    N = np.array([l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1),
                  4 * l1 * l2, 4 * l2 * l3, 4 * l3 * l1])
    # d/dxi and d/deta with dl1 = (-1, -1), dl2 = (1, 0), dl3 = (0, 1)
    dN = np.array([
        [-(4 * l1 - 1), -(4 * l1 - 1)],
        [4 * l2 - 1, 0 * xi],
        [0 * xi, 4 * l3 - 1],
        [4 * (l1 - l2), -4 * l2],
        [4 * l3, 4 * l2],
        [-4 * l3, 4 * (l1 - l3)],
    ])
    return N, dN


def surface_mass(points: np.ndarray, triangles: np.ndarray, n_nodes: int, intorder: int = 4
                 ) -> sp.csr_matrix:
    """Scalar surface mass matrix M_ij = int_S phi_i phi_j dA on (curved) triangles.

    Parameters
    ----------
    points : (3, n_nodes) node coordinates (m) in the numbering of ``triangles``.
    triangles : (6, n) quadratic or (3, n) linear surface triangles.
    n_nodes : size of the returned matrix.
    intorder : quadrature order on the reference triangle.

    Returns
    -------
    (n_nodes, n_nodes) CSR matrix in m^2. Computed directly from the isoparametric
    map of each triangle (no inverse mapping needed, so it is robust on strongly
    curved facets).
    """
    nn = triangles.shape[0]
    X, W = get_quadrature(RefTri, intorder)
    N, dN = tri_shape(X, nn)
    xe = points[:, triangles]  # (3, nn, nf)
    # Tangents (3, 2, nf, nq)
    tang = np.einsum("cnf,ndq->cdfq", xe, dN)
    jac = np.linalg.norm(np.cross(tang[:, 0], tang[:, 1], axis=0), axis=0)  # (nf, nq)
    local = np.einsum("aq,bq,fq,q->fab", N, N, jac, W)
    nf = triangles.shape[1]
    rows = np.broadcast_to(triangles.T[:, :, None], (nf, nn, nn)).ravel()
    cols = np.broadcast_to(triangles.T[:, None, :], (nf, nn, nn)).ravel()
    return sp.coo_matrix((local.ravel(), (rows, cols)), shape=(n_nodes, n_nodes)).tocsr()
