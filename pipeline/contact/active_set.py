"""Exact primal active-set solver for the load-controlled contact QP.

The linear loaded-contact problem for one mesh position,

    B F + c - x 1 >= 0,   F >= 0,   F_i (B F + c - x 1)_i = 0,   1^T F = P,

is the KKT system of the convex quadratic programme

    minimise 0.5 F^T B F + c^T F   subject to   F >= 0,  1^T F = P,

with ``x`` the multiplier of the load balance (the approach along the line of
action). The feasible set is a scaled simplex, so a feasible start is always
available and the primal active-set method of Lawson and Hanson (Solving Least
Squares Problems, 1974, ch. 23, the NNLS algorithm) carries over with the load
balance kept as an equality: minimise on the face of the points assumed loaded,
step towards the face minimiser until a load would turn negative, drop it, and
add the most penetrating point once the face minimiser is feasible. The
objective never increases and a face is never revisited at its minimum, so the
method ends after finitely many face solves with the exact active set (Nocedal
and Wright, Numerical Optimization, 2nd ed., section 16.5).

Positive semidefinite ``B`` (rigid points, rigidly coupled points) is handled:
a singular face is solved in the least-squares sense, and a face along which the
objective is unbounded yields its descent direction (the least-squares residual
of the bordered KKT system, which lies in its null space), followed until a
load reaches zero.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.validation import InputError

_EPS = np.finfo(float).eps


class ActiveSetError(RuntimeError):
    """The active-set iteration exceeded its face-solve budget (cycling or bad data)."""


@dataclass(frozen=True)
class QPSolution:
    """Result of :func:`solve_qp`.

    Attributes
    ----------
    loads : (n,) loads F in N, exactly zero off the active set.
    multiplier : x, the load-balance multiplier (m): ``B F + c = x`` on loaded points.
    face_solves : number of face (KKT) solves used.
    """

    loads: np.ndarray
    multiplier: float
    face_solves: int


def _face_minimiser(
    B: np.ndarray, c: np.ndarray, P: float, idx: np.ndarray
) -> tuple[np.ndarray, float, np.ndarray | None]:
    """Minimise on the face ``F_i = 0`` for ``i`` not in ``idx``, ``1^T F = P``.

    Returns ``(z, x, None)`` with the face minimiser ``z`` (len(idx),) and its
    multiplier ``x``, or ``(z, x, d)`` with a descent direction ``d``
    (len(idx),), ``1^T d = 0``, ``B d = 0``, along which the objective decreases
    without bound on the face (positive semidefinite ``B`` only).
    """
    m = idx.size
    Bf = B[np.ix_(idx, idx)]
    cf = c[idx]
    # border scaled like B so that LU pivoting sees one magnitude
    s = float(np.max(np.abs(np.diag(Bf)))) or float(np.max(np.abs(Bf))) or 1.0
    K = np.empty((m + 1, m + 1))
    K[:m, :m] = Bf
    K[:m, m] = s
    K[m, :m] = s
    K[m, m] = 0.0
    rhs = np.empty(m + 1)
    rhs[:m] = -cf
    rhs[m] = s * P
    try:
        sol = np.linalg.solve(K, rhs)
        r = K @ sol - rhs
        scale = np.abs(K).max() * np.abs(sol).max() + np.abs(rhs).max()
        ok = bool(np.all(np.isfinite(sol))) and np.abs(r).max() <= 1e3 * m * _EPS * scale
    except np.linalg.LinAlgError:
        ok = False
    if ok:
        return sol[:m], -s * sol[m], None
    return _singular_face(K, rhs, m, s)


def _singular_face(
    K: np.ndarray, rhs: np.ndarray, m: int, s: float
) -> tuple[np.ndarray, float, np.ndarray | None]:
    """Least-squares face solve for a (near-)singular bordered KKT matrix."""
    evals = np.linalg.eigvalsh(K[:m, :m])
    if evals[0] < -1e-8 * max(evals[-1], 0.0):
        raise InputError(
            f"compliance G (plus local contact tangent) is not positive semidefinite: "
            f"smallest eigenvalue {evals[0]:.3g} m/N against largest {evals[-1]:.3g} m/N"
        )
    sol, *_ = np.linalg.lstsq(K, rhs, rcond=1e-13)
    r = K @ sol - rhs
    scale = np.abs(K).max() * np.abs(sol).max() + np.abs(rhs).max()
    if np.abs(r).max() <= 1e-9 * scale:
        return sol[:m], -s * sol[m], None
    # Inconsistent system: K r = 0 for the least-squares residual, so r = (r_F, 0)
    # with B r_F = 0, 1^T r_F = 0 and c^T r_F = |r|^2 > 0: -r_F is a direction of
    # zero curvature and strictly decreasing objective on the face.
    d = -r[:m]
    d -= d.mean()
    return sol[:m], -s * sol[m], d / np.abs(d).max()


def solve_qp(
    B: np.ndarray,
    c: np.ndarray,
    P: float,
    start: np.ndarray,
    max_face_solves: int | None = None,
) -> QPSolution:
    """Exact minimiser of ``0.5 F^T B F + c^T F`` on ``F >= 0``, ``1^T F = P``.

    Parameters
    ----------
    B : (n, n) symmetric positive semidefinite matrix, m/N.
    c : (n,) linear term, m.
    P : total load, N, > 0.
    start : (n,) feasible start (``>= 0``, summing to ``P``), N. A good start
        (the previous mesh position, the previous Newton iterate) saves face solves;
        its support is where the iteration begins.
    max_face_solves : budget of face solves; default ``10 n + 50``.

    Returns
    -------
    QPSolution with the loads (n,), N, and the multiplier x, m.

    Raises
    ------
    ActiveSetError if the budget is exhausted (only possible through round-off cycling).
    InputError if ``B`` is found to be indefinite.
    """
    n = c.size
    budget = 10 * n + 50 if max_face_solves is None else max_face_solves
    F = np.maximum(start.astype(float, copy=True), 0.0)
    # every point starts in the working set: points with zero start load and a
    # negative face load then all leave together in the first ratio test
    W = np.ones(n, dtype=bool)
    for k in range(1, budget + 1):
        idx = np.flatnonzero(W)
        z, x, direction = _face_minimiser(B, c, P, idx)
        if direction is None:
            neg = z < 0.0
            if not neg.any():
                F[:] = 0.0
                F[idx] = z
                w = B @ F + c - x
                tol_w = 10.0 * n * _EPS * max(abs(x), np.abs(c).max(), np.abs(B @ F).max())
                w[W] = np.inf
                j = int(np.argmin(w))
                if w[j] >= -tol_w:
                    # the face solve meets 1^T F = P to round-off; make it exact (a few ulps)
                    F *= P / F.sum()
                    return QPSolution(F, float(x), k)
                W[j] = True
                continue
            Fi = F[idx]
            ratio = Fi[neg] / (Fi[neg] - z[neg])
            alpha = float(ratio.min())
            F[idx] = Fi + alpha * (z - Fi)
            blocked = idx[neg][ratio <= alpha * (1.0 + 1e-12) + 1e-300]
        else:
            Fi = F[idx]
            neg = direction < 0.0
            ratio = Fi[neg] / (-direction[neg])
            alpha = float(ratio.min())
            F[idx] = Fi + alpha * direction
            blocked = idx[neg][ratio <= alpha * (1.0 + 1e-12) + 1e-300]
        F[blocked] = 0.0
        W[blocked] = False
        np.maximum(F, 0.0, out=F)
    raise ActiveSetError(f"active-set QP did not finish within {budget} face solves (n = {n})")
