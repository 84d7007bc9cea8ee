"""Condense an elastic body to a 12 x 12 stiffness between two reference nodes.

Each node O_k (k = L, R) is tied to a surface S_k of the body in one of two ways:

``"distributed"`` (RBE3-like, the default)
    A generalised force F = (force, moment) at O_k is applied as the traction
    field ``t(x) = R(x) G^-1 F`` on S_k, where ``R(x)`` (3 x 6) is the rigid-body
    motion of the point x about O_k and ``G = int_S R^T R dA``; the traction has
    resultant F and varies like a rigid motion (uniform + linear), e.g. a uniform
    circumferential shear for a torque on a cylinder - the mesh forces smeared
    over the face width. The conjugate displacement of O_k is the area-weighted
    least-squares rigid fit ``U = G^-1 int_S R^T u dA``. The surface itself
    deforms freely. With nodal P (n_dof x 6) = int phi R dA (consistent loads),
    f = P G^-1 F and U = G^-1 P^T u, and G = P^T R_nodes exactly because rigid
    motions are in the P2 space. Six self-equilibrated load cases (F at O_L
    against its static equivalent at O_R) are solved against one factorisation of
    the body held by a statically determinate 3-2-1 support (whose reactions
    are zero to round-off for such loads): relative flexibility C (6 x 6) and
    stiffness K_rel = C^-1.

``"rigid"`` (RBE2-like)
    Every node of S_k moves with the rigid motion of O_k. The 12 x 12 matrix is
    the Schur complement on the 12 node DOFs: one factorisation of the interior
    block, 12 right-hand sides.

``"tooth_forces"``
    The 12 x 12 matrix is the distributed one; the torsional stiffness comes
    from a seventh load case solved with the same factorisation: the tooth-mesh
    forces of the planets on the left half (``left_loads``, see
    :mod:`pipeline.fem.groove.toothload`), balanced by the distributed traction
    of their static equivalent on the right half. With W its resultant about O_L
    (a torque M_z and the helical axial force F_z) and D its relative motion,
    ``k_t = M_z / (D_rz - C[5, :5] W[:5])``: the twist of the torque alone (the
    part due to the other resultant components, through the distributed
    flexibility C, is removed; it is zero for an axisymmetric body).

Both give ``K12 = A^T K_rel A`` with ``A = [I, -Gamma]``, ``Gamma`` the rigid
transfer of O_R's motion to O_L: symmetric, with exactly the six rigid-body
motions as null space. DOF order [ux, uy, uz, rx, ry, rz] at O_L, then at O_R;
N/m, N/rad, N m/rad.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from pipeline.fem.groove.spec import COUPLINGS
from pipeline.fem.linear_static import ElasticModel, rigid_body_modes
from pipeline.fem.pmultigrid import p1_prolongation, pmg_cg
from pipeline.fem.solvers import cholmod_available, factorize_spd
from pipeline.fem.tetmesh import surface_mass
from pipeline.validation import InputError, check_choice

SOLVERS = ("auto", "cholmod", "cholespy", "splu", "pmg-cg")


@dataclass(frozen=True, eq=False)
class TwoNodeCoupling:
    """Stiffness between two reference nodes of a body.

    Attributes
    ----------
    matrix : (12, 12) stiffness, DOFs [ux, uy, uz, rx, ry, rz] at O_L then O_R
        (N/m, N/rad, N m/rad), symmetric, rigid-body null space.
    relative_stiffness : (6, 6) K_rel mapping the relative motion of O_L with
        respect to O_R (translated rigidly to O_L) to the generalised force at O_L.
    relative_flexibility : (6, 6) inverse of ``relative_stiffness``.
    node_left, node_right : (3,) positions of O_L, O_R in m.
    coupling : "distributed" or "rigid".
    solver : sparse solver used.
    n_dof : DOFs of the finite-element model.
    factor_seconds, solve_seconds : wall times, s (factorisation or, for
        "pmg-cg", preconditioner set-up; then all right-hand sides together).
    displacements : (n_dof, 6) fields of the six unit load cases (distributed) or
        of the six unit relative motions (rigid), m per unit load / motion;
        (n_dof, 7) for "tooth_forces", the last column the tooth-force case per
        N m of torque.
    tooth_torsional_stiffness : k_t from the tooth-force case, N m/rad (None
        for the other couplings).
    """

    matrix: np.ndarray
    relative_stiffness: np.ndarray
    relative_flexibility: np.ndarray
    node_left: np.ndarray
    node_right: np.ndarray
    coupling: str
    solver: str
    n_dof: int
    factor_seconds: float
    solve_seconds: float
    displacements: np.ndarray
    tooth_torsional_stiffness: float | None = None

    @property
    def torsional_stiffness(self) -> float:
        """Relative twist stiffness about z under a pure torque, N m/rad.

        1 / C_zz for "distributed" and "rigid"; the tooth-force value for
        "tooth_forces".
        """
        if self.tooth_torsional_stiffness is not None:
            return float(self.tooth_torsional_stiffness)
        return float(1.0 / self.relative_flexibility[5, 5])


def transfer_matrix(r: np.ndarray) -> np.ndarray:
    """Gamma (6, 6): motion at a point offset by ``r`` (m) from a node moving rigidly.

    ``[u + theta x r, theta] = Gamma [u, theta]``.
    """
    rx = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    gam = np.eye(6)
    gam[:3, 3:] = -rx  # theta x r = -r x theta
    return gam


def two_node_matrix(k_rel: np.ndarray, node_left: np.ndarray, node_right: np.ndarray
                    ) -> np.ndarray:
    """K12 = A^T K_rel A with A = [I, -Gamma(O_L - O_R)] (see module doc)."""
    A = np.hstack([np.eye(6), -transfer_matrix(np.asarray(node_left) - np.asarray(node_right))])
    K = A.T @ k_rel @ A
    return 0.5 * (K + K.T)


def surface_loads(model: ElasticModel, triangles: np.ndarray, centre: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """P (n_dof, 6) = int_S phi R dA and G (6, 6) = int_S R^T R dA about ``centre`` (m).

    ``triangles`` (6, n) are the surface triangles in the basis' node numbering.
    The consistent load of traction R_k(x) is the surface mass matrix times the
    nodal interpolant of R_k (exact: rigid motions lie in the P2 space).
    """
    nodes = model.basis.doflocs[:, ::3]
    n = nodes.shape[1]
    mass = surface_mass(nodes, triangles, n)
    R = rigid_body_modes(nodes - np.asarray(centre)[:, None])
    P = np.asarray(mass @ R.reshape(n, 18)).reshape(3 * n, 6)
    G = P.T @ R
    return P, 0.5 * (G + G.T)


def couple_two_surfaces(
    model: ElasticModel, surface_left: np.ndarray, surface_right: np.ndarray,
    node_left: np.ndarray, node_right: np.ndarray, coupling: str = "distributed",
    solver: str = "auto", left_loads: np.ndarray | None = None,
) -> TwoNodeCoupling:
    """12 x 12 stiffness between O_L (tied to ``surface_left``) and O_R (``surface_right``).

    Parameters
    ----------
    model : assembled 3D elastic P2 body (free-free).
    surface_left, surface_right : (6, n) triangles of the tied surfaces in the
        basis' node numbering (:attr:`pipeline.fem.tetmesh.SkfemTetMesh.triangles`).
    node_left, node_right : (3,) positions of O_L, O_R in m.
    coupling : "distributed", "rigid" or "tooth_forces" (module doc).
    solver : "auto" (scikit-sparse's CHOLMOD if installed, else "pmg-cg"), "cholmod",
        "cholespy", "splu" or "pmg-cg" (:mod:`pipeline.fem.pmultigrid`, P2 bases only).
    left_loads : (n_dof,) nodal tooth-mesh forces on the left half in N, for
        "tooth_forces" only (their torque about z must be non-zero).
    """
    check_choice("groove.coupling", coupling, COUPLINGS)
    check_choice("groove.solver", solver, SOLVERS)
    if (coupling == "tooth_forces") != (left_loads is not None):
        raise InputError("groove: left_loads are needed for, and only for, coupling = "
                         "'tooth_forces'")
    node_left, node_right = np.asarray(node_left, float), np.asarray(node_right, float)
    if coupling == "rigid":
        return _couple_rigid(model, surface_left, surface_right, node_left, node_right, solver)
    return _couple_distributed(model, surface_left, surface_right, node_left, node_right, solver,
                               left_loads)


def solve_free(model: ElasticModel, free: np.ndarray, F: np.ndarray, solver: str
               ) -> tuple[np.ndarray, str, float, float]:
    """Solve K[free, free] X = F[free] for all columns of F (n_dof, k) at once.

    Returns (X (n_free, k) in m, method, set-up seconds, solve seconds). A direct
    method factorises once; "pmg-cg" sets up its preconditioner once and iterates
    to a relative residual of 1e-10 on every column.
    """
    check_choice("groove.solver", solver, SOLVERS)
    if solver == "auto":
        # few right-hand sides: pmg-CG beats cholespy here (bench_groove: 3.4 s vs 12.2 s
        # at 40.6k DOF); scikit-sparse's CHOLMOD when installed (pipeline.fem.solvers)
        solver = "cholmod" if cholmod_available() else "pmg-cg"
    A = model.stiffness[free][:, free]
    rhs = np.ascontiguousarray(F[free])
    if solver == "pmg-cg":
        P, _ = p1_prolongation(model.basis)
        res = pmg_cg(A, rhs, P[free], rtol=1e-10)
        return res.x, "pmg-cg", res.setup_seconds, res.solve_seconds
    factor = factorize_spd(A, solver)
    t0 = time.perf_counter()
    X = factor.solve(rhs)
    return X, factor.method, factor.factor_seconds, time.perf_counter() - t0


def support_321(model: ElasticModel, triangles: np.ndarray) -> np.ndarray:
    """Six DOFs on three far-apart surface nodes that remove rigid motion only."""
    nodes = np.unique(triangles)
    xyz = model.basis.doflocs[:, 3 * nodes]
    a = nodes[np.argmax(xyz[0])]
    b = nodes[np.argmin(xyz[0])]
    c = nodes[np.argmax(xyz[1])]
    return np.array([3 * a, 3 * a + 1, 3 * a + 2, 3 * b + 1, 3 * b + 2, 3 * c + 2])


def _couple_distributed(model, surface_left, surface_right, node_left, node_right, solver,
                        left_loads=None):
    P_L, G_L = surface_loads(model, surface_left, node_left)
    P_R, G_R = surface_loads(model, surface_right, node_right)
    gam = transfer_matrix(node_left - node_right)
    # Generalised force e_k at O_L, its static equivalent -Gamma^T e_k at O_R.
    F = P_L @ np.linalg.solve(G_L, np.eye(6)) - P_R @ np.linalg.solve(G_R, gam.T)
    W = None
    if left_loads is not None:
        f = np.asarray(left_loads, dtype=float).reshape(model.n_dof)
        nodes = model.basis.doflocs[:, ::3]
        W = rigid_body_modes(nodes - node_left[:, None]).T @ f  # resultant about O_L
        if abs(W[5]) <= 1e-9 * np.abs(W).max():
            raise InputError("groove: the tooth-mesh loads carry no torque about the axis")
        f_eq = f - P_R @ np.linalg.solve(G_R, gam.T @ W)
        F = np.column_stack([F, f_eq / W[5]])
        W = W / W[5]
    fixed = support_321(model, surface_right)
    free = np.setdiff1d(np.arange(model.n_dof), fixed)
    X, method, setup_s, solve_s = solve_free(model, free, F, solver)
    U = np.zeros((model.n_dof, F.shape[1]))
    U[free] = X
    reaction = (model.stiffness @ U - F)[fixed]
    scale = np.abs(F).sum(axis=0).max()
    if np.abs(reaction).max() > 1e-6 * scale:
        raise RuntimeError("3-2-1 support carries load: the coupling loads are not balanced")
    D = np.linalg.solve(G_L, P_L.T @ U) - gam @ np.linalg.solve(G_R, P_R.T @ U)
    C = 0.5 * (D[:, :6] + D[:, :6].T)
    K_rel = np.linalg.inv(C)
    K_rel = 0.5 * (K_rel + K_rel.T)
    k_tooth = None
    if W is not None:
        # Twist per N m of the tooth-force torque, less what its axial force etc. cause.
        k_tooth = float(1.0 / (D[5, 6] - C[5, :5] @ W[:5]))
    return TwoNodeCoupling(two_node_matrix(K_rel, node_left, node_right), K_rel, C, node_left,
                           node_right, "distributed" if W is None else "tooth_forces", method,
                           model.n_dof, setup_s, solve_s, U, k_tooth)


def _couple_rigid(model, surface_left, surface_right, node_left, node_right, solver):
    n = model.n_dof
    nodes = model.basis.doflocs[:, ::3]
    blocks, slaves = [], []
    for tri, node in ((surface_left, node_left), (surface_right, node_right)):
        s = (3 * np.unique(tri)[:, None] + np.arange(3)).ravel()
        R = rigid_body_modes(nodes - node[:, None])[s]
        blocks.append(sp.coo_matrix(R).tocsr())
        slaves.append(s)
    if np.intersect1d(slaves[0], slaves[1]).size:
        raise ValueError("the two tied surfaces share nodes")
    s = np.concatenate(slaves)
    T = sp.block_diag(blocks, format="csr")  # (n_s, 12)
    interior = np.setdiff1d(np.arange(n), s)
    K = model.stiffness
    rhs = np.zeros((n, 12))
    rhs[interior] = (K[interior][:, s] @ T).toarray()
    X, method, setup_s, solve_s = solve_free(model, interior, rhs, solver)
    K_is_T = rhs[interior]
    K12 = (T.T @ (K[s][:, s] @ T)).toarray() - K_is_T.T @ X
    K12 = 0.5 * (K12 + K12.T)
    K_rel = K12[:6, :6]
    # Fields of the six unit relative motions of O_L with O_R fixed.
    U = np.zeros((n, 6))
    U[s] = (T @ np.vstack([np.eye(6), np.zeros((6, 6))]))
    U[interior] = -X[:, :6]
    return TwoNodeCoupling(K12, K_rel, np.linalg.inv(K_rel), node_left, node_right, "rigid",
                           method, n, setup_s, solve_s, U)
