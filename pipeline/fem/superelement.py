"""Condense an elastic body to reference nodes tied to its surfaces: a superelement.

The body (assembled P2 elasticity, free-free) is reached only through reference nodes
N_0 ... N_{n-1}, each tied to a surface patch S_j:

* distributed (RBE3-like), as the relief groove's ``"distributed"`` coupling
  (:mod:`pipeline.fem.groove.coupling`, which gives ``P_j``, ``G_j`` and the rigid transfer
  ``Gamma``): a generalised load F_j at N_j acts as the traction ``R(x) G_j^-1 F_j`` on
  S_j (resultant F_j, varying like a rigid motion), nodal ``B_j F_j`` with
  ``B_j = P_j G_j^-1``; N_j moves with the area-weighted least-squares rigid fit of S_j,
  ``U_j = B_j^T u``. The patch deforms freely.
* rigid (RBE2-like), for N_0 only (``anchor_rigid``): every node of S_0 moves with N_0.

Load cases: a unit generalised load at N_j (j >= 1) balanced by its static equivalent at N_0
(``-B_0 Gamma(r_j - r_0)^T``; for a rigid N_0 the clamped patch takes it), solved with one
set-up of the solver: with a rigid N_0 the nodes of S_0 are clamped (N_0 is then the ground
of the relative motions), otherwise a statically determinate 3-2-1 support on S_0 whose
reactions are zero to round-off for these balanced loads (checked). The readouts
``D_j = B_j^T u - Gamma(r_j - r_0) B_0^T u`` are the motions of N_j relative to N_0
(rigid motions removed), and ``C = f^T K^-1 f`` is symmetric (Maxwell-Betti) to solver
accuracy: :attr:`Superelement.asymmetry` records it before symmetrisation.

The stiffness of the n nodes is ``K = A^T C^-1 A`` with ``A`` the relative-motion map
``[-Gamma(r_j - r_0), I_j]`` (6(n-1) x 6n): symmetric, with exactly the six rigid-body
motions as null space, ready for supports (springs, held DOFs) at the nodes.

Sections: cross-sections read with the same least-squares rigid fit (no load): their motion
relative to N_0 per unit load at N_j, so that the field's deflection line follows from the
nodes' loads without storing a field. DOF order per node ``(u_x, u_y, u_z, theta_x,
theta_y, theta_z)``; m, rad, N, N m.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from pipeline.fem.groove.coupling import support_321, surface_loads, transfer_matrix
from pipeline.fem.linear_static import ElasticModel, solve_static
from pipeline.fem.solvers import Solver


@dataclass(frozen=True, eq=False)
class Patch:
    """A reference node at ``centre`` (3,) m tied to the surface ``triangles`` (6, n) (basis
    node numbering, :attr:`pipeline.fem.tetmesh.SkfemTetMesh.triangles`)."""

    triangles: np.ndarray
    centre: np.ndarray


@dataclass(frozen=True, eq=False)
class Superelement:
    """A body condensed to reference nodes (module docstring).

    Attributes
    ----------
    positions : (n, 3) reference nodes, m; node 0 is the anchor.
    flexibility : (6(n-1), 6(n-1)) motion of nodes 1..n-1 relative to node 0 per unit
        load at them (m/N, rad/(N m), ...), symmetrised.
    section_positions : (n_s, 3) centres of the read cross-sections, m.
    section_flexibility : (6 n_s, 6(n-1)) their motion relative to node 0 per unit load at
        nodes 1..n-1.
    asymmetry : max |C - C^T| / max |C| before symmetrisation.
    n_dof : unknowns of the FE model; method : solver used.
    timings : wall times (s): "factor", "solve".
    """

    positions: np.ndarray
    flexibility: np.ndarray
    section_positions: np.ndarray
    section_flexibility: np.ndarray
    asymmetry: float
    n_dof: int
    method: str
    timings: dict

    def relative_map(self) -> np.ndarray:
        """A (6(n-1), 6n): the motions of nodes 1..n-1 relative to node 0."""
        n = self.positions.shape[0]
        A = np.zeros((6 * (n - 1), 6 * n))
        for j in range(1, n):
            rows = slice(6 * (j - 1), 6 * j)
            A[rows, :6] = -transfer_matrix(self.positions[j] - self.positions[0])
            A[rows, 6 * j:6 * j + 6] = np.eye(6)
        return A

    def stiffness(self) -> np.ndarray:
        """(6n, 6n) stiffness of the free-free body at its nodes, ``A^T C^-1 A``."""
        A = self.relative_map()
        K = A.T @ np.linalg.solve(self.flexibility, A)
        return 0.5 * (K + K.T)


def _fit(model: ElasticModel, patch: Patch) -> sp.csc_array:
    """B = P G^-1 (n_dof, 6): the distributed load per unit generalised load at the node,
    and (transposed) its least-squares rigid fit. Sparse: only the patch's DOFs carry
    load; dense, the readouts ``B^T U`` of 30-odd patches on 42 solutions took 1.1 s and
    the products ``P G^-1`` 0.1-1 s (64k unknowns, 23 patches)."""
    P, G = surface_loads(model, patch.triangles, patch.centre)
    rows = np.flatnonzero(np.any(P, axis=1))  # the patch's DOFs
    B = P[rows] @ np.linalg.inv(G)
    return sp.csc_array((B.ravel(), (np.repeat(rows, 6), np.tile(np.arange(6), rows.size))),
                        shape=P.shape)


def condense(
    model: ElasticModel, anchor: Patch, nodes: Sequence[Patch], sections: Sequence[Patch],
    *, anchor_rigid: bool, solver: Solver | None = None,
) -> Superelement:
    """Condense ``model`` to the ``anchor`` (node 0) and ``nodes`` (module docstring).

    Parameters
    ----------
    model : assembled 3D P2 elastic body, free-free.
    anchor : node 0 and its patch; rigid (``anchor_rigid``) or distributed.
    nodes : nodes 1..n-1, distributed.
    sections : cross-sections read (not loaded).
    solver : :mod:`pipeline.fem.solvers` (default its direct solver).
    """
    r0 = np.asarray(anchor.centre, float)
    B = [_fit(model, p) for p in nodes]
    S = [_fit(model, p) for p in sections]
    gam = [transfer_matrix(np.asarray(p.centre, float) - r0) for p in (*nodes, *sections)]
    if anchor_rigid:
        B0 = sp.csc_array((model.n_dof, 6))
        held = (3 * np.unique(anchor.triangles)[:, None] + np.arange(3)).ravel()
    else:
        B0 = _fit(model, anchor)
        held = support_321(model, anchor.triangles)
    F = np.hstack([Bj.toarray() - B0 @ gj.T for Bj, gj in zip(B, gam[:len(B)], strict=True)])
    sol = solve_static(model, F, held, solver)
    U = sol.displacements
    if not anchor_rigid:
        scale = np.abs(F).sum(axis=0).max()
        if np.abs(sol.reactions).max() > 1e-6 * scale:
            raise RuntimeError("3-2-1 support carries load: the coupling loads are not balanced")
    U0 = B0.T @ U
    D = np.vstack([Bj.T @ U - gj @ U0 for Bj, gj in zip(B, gam[:len(B)], strict=True)])
    Ds = np.vstack([Sk.T @ U - gk @ U0 for Sk, gk in zip(S, gam[len(B):], strict=True)]
                   ) if S else np.zeros((0, D.shape[1]))
    asym = float(np.abs(D - D.T).max() / np.abs(D).max())
    positions = np.array([r0] + [np.asarray(p.centre, float) for p in nodes])
    spos = np.array([np.asarray(p.centre, float) for p in sections]).reshape(-1, 3)
    return Superelement(positions, 0.5 * (D + D.T), spos, Ds, asym, model.n_dof, sol.method,
                        {"factor": sol.factor_seconds, "solve": sol.solve_seconds})

