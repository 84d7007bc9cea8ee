"""Exact constraints of a beam model: a rigid seat (master-slave) and rigid supports.

Two steps map the reduced unknowns ``p`` to the nodal DOFs ``u`` (6 per node, order of
:mod:`pipeline.shaft.timoshenko`): ``u = T q`` and ``q = Z p``.

* ``T`` (:func:`rigid_body_transform`): the seat's nodes follow its centre node as one
  rigid body; a node at axial offset ``d`` from the master moves as
  ``u = u_c + theta_c x (0, 0, d)``, i.e. ``u_x = u_xc + d theta_yc``,
  ``u_y = u_yc - d theta_xc``, ``u_z = u_zc``, ``theta = theta_c``. The slaves' DOFs are
  eliminated; ``q`` holds every other node's DOFs.
* ``Z`` (:func:`eliminate`): rigid supports are rows ``C u = 0`` (a bearing's u_x, u_y,
  the axial bearing's u_z, the torque point's theta_z). In ``q`` they read ``A q = 0``
  with ``A = C T``; on a free node that is one DOF (its column is dropped), on a slave node
  a combination of the master's DOFs. ``Z`` is the identity on the DOFs no row touches
  and an orthonormal null-space basis of ``A`` on the few it does, so the constraints
  hold to round-off (no penalty).

The supports' loads on the shaft are the multipliers ``lambda`` of ``K u = f + C^T
lambda`` (:func:`multipliers`), found from the residual the reduced solution leaves.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp


def rigid_body_transform(z: np.ndarray, master: int, slaves: np.ndarray) -> sp.csr_matrix:
    """(6n, 6 (n - len(slaves))) sparse ``T``: the slaves follow the master rigidly.

    Parameters
    ----------
    z : (n,) node positions, m.
    master : the index of the master node.
    slaves : indices of the slave nodes (not the master).
    """
    n = z.size
    free = np.setdiff1d(np.arange(n), slaves)
    col_of = -np.ones(n, int)
    col_of[free] = np.arange(free.size)
    rows, cols, vals = [], [], []
    free_dof = (6 * free[:, None] + np.arange(6)).ravel()
    rows.append(free_dof)
    cols.append((6 * col_of[free][:, None] + np.arange(6)).ravel())
    vals.append(np.ones(free_dof.size))
    m0 = 6 * col_of[master]
    for s in slaves:
        d = z[s] - z[master]
        r = 6 * s
        # u_x = u_xc + d theta_yc; u_y = u_yc - d theta_xc; u_z, theta follow
        rows.append(np.array([r, r, r + 1, r + 1, r + 2, r + 3, r + 4, r + 5]))
        cols.append(m0 + np.array([0, 4, 1, 3, 2, 3, 4, 5]))
        vals.append(np.array([1.0, d, 1.0, -d, 1.0, 1.0, 1.0, 1.0]))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(6 * n, 6 * free.size))


def eliminate(a: sp.spmatrix) -> sp.csr_matrix:
    """(nq, np) sparse ``Z`` with ``A Z = 0`` (to round-off) spanning the null space of
    ``A`` (r, nq); ``ValueError`` if the rows are dependent (a support given twice)."""
    a = sp.csr_matrix(a)
    nq = a.shape[1]
    touched = np.unique(a.indices)
    ad = a[:, touched].toarray()
    _, sv, vt = sla.svd(ad)
    rank = int(np.sum(sv > 1e-12 * sv.max())) if sv.size else 0
    if rank < a.shape[0]:
        raise ValueError("the rigid supports constrain the same motion twice")
    null = vt[rank:].T                                     # (len(touched), k)
    untouched = np.setdiff1d(np.arange(nq), touched)
    k = null.shape[1]
    rows = np.concatenate([untouched, np.repeat(touched, k)])
    cols = np.concatenate([np.arange(untouched.size),
                           untouched.size + np.tile(np.arange(k), touched.size)])
    vals = np.concatenate([np.ones(untouched.size), null.ravel()])
    return sp.csr_matrix((vals, (rows, cols)), shape=(nq, untouched.size + k))


def multipliers(a: sp.spmatrix, residual_q: np.ndarray) -> np.ndarray:
    """(r,) ``lambda`` with ``A^T lambda = residual_q`` (least squares on the DOFs the rows
    touch; exact when the reduced equations hold): the loads the rigid supports put on the
    shaft, one per row of ``C``."""
    a = sp.csr_matrix(a)
    touched = np.unique(a.indices)
    lam, *_ = sla.lstsq(a[:, touched].toarray().T, residual_q[touched])
    return lam
