"""Loaded tooth contact of one mesh position: compatibility, F >= 0 and load balance.

Find the loads ``F`` (N, shape (n,)) on the ``n`` candidate contact points and the
approach ``x_s`` (m) such that (Yang et al. 2026, eqs. 27-29)

    G F + u_c(F) + eps - x_s = 0   where F > 0,
    G F + u_c(F) + eps - x_s >= 0  where F = 0   (the gap stays open),
    F >= 0,   sum(F) = P,

with ``G`` (m/N, (n, n)) the symmetric positive (semi)definite structural
compliance (FE influence coefficients, or the diagonal/banded slice compliance),
``eps`` (m, (n,)) the initial separations and ``u_c`` the local contact approach
(:mod:`pipeline.contact.hertz`).

Method. Because ``u_c`` is increasing, it is the gradient of the convex
``phi(F) = sum_i int_0^F_i u_c,i``, and the conditions above are exactly the KKT
conditions of the convex programme

    minimise 0.5 F^T G F + phi(F) + eps^T F   on   F >= 0, sum(F) = P,

with ``x_s`` the multiplier of the load balance. Hence a solution exists, it is
unique when ``G`` is definite or ``u_c`` strictly increasing, and ``x_s`` is
unique.

* Linear (``hertz=None``): the exact primal active-set method of
  :mod:`pipeline.contact.active_set` solves the QP in finitely many face solves.
* Nonlinear: a Newton method on the active set. Each iteration linearises
  ``u_c`` at the current loads (tangent ``D = du_c/dF``), solves the resulting
  QP exactly (this also finds the new contact set), and takes the step to its
  solution with an exact line search on the convex objective (root of its
  directional derivative, which is monotone, so bracketing always succeeds).
  With a positive definite model every step is a descent step, so the iteration
  is the scaled gradient projection method with a minimisation step rule,
  which converges to the minimiser of a convex problem (Bertsekas, Nonlinear
  Programming, 2nd ed., 1999, section 2.3); close to the solution it takes full
  Newton steps and converges quadratically. If a step stalls (no descent, or a
  line-search step below 1e-3) the model is damped,
  ``B = G + D + mu diag(G + D)`` with ``mu`` growing tenfold per stall, moving
  towards short scaled-gradient steps; it is relaxed again after good steps.

Every solution is checked: :func:`complementarity_residual` must be below
``tol`` times the largest elastic approach (plus a floor of a few ulps of the
absolute positions); otherwise :class:`ContactConvergenceError` is raised,
naming the mesh position. Nothing unconverged is ever returned.

Points with ``eps_i = +inf`` are out of mesh: they never carry load and their
rows and columns of ``G`` are not read.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from pipeline.contact.active_set import ActiveSetError, solve_qp
from pipeline.contact.hertz import LocalCompliance
from pipeline.contact.results import ContactSolution
from pipeline.validation import InputError, check_int_range, check_range

_EPS = np.finfo(float).eps


class ContactConvergenceError(RuntimeError):
    """The contact solve did not meet its residual tolerance (message names the position)."""


def complementarity_residual(g: np.ndarray, loads: np.ndarray) -> tuple[float, float]:
    """Approach and maximum complementarity violation of a load state.

    Parameters
    ----------
    g : (n,) ``G F + u_c(F) + eps``, m: where each point's surfaces meet.
    loads : (n,) F >= 0, N; points with F > 0 are taken as loaded.

    Returns
    -------
    approach : x_s (m) minimising the violation below.
    residual : ``max(max_{F>0} |g_i - x_s|, max_{F=0} max(x_s - g_i, 0))``, m:
        how far loaded points are from touching and unloaded points penetrate.
        For ``F = 0`` everywhere, ``x_s = min g`` (first contact) and the residual is 0.
    """
    act = loads > 0.0
    if not act.any():
        return float(g.min()), 0.0
    hi = float(g[act].max())
    lo = float(g[act].min())
    if not act.all():
        lo = min(lo, float(g[~act].min()))
    x = 0.5 * (hi + lo)
    return x, 0.5 * (hi - lo)


def _check_compliance(G: ArrayLike, n: int, cand: np.ndarray, label: str) -> np.ndarray:
    """Validate and symmetrise the candidate block of G (m/N)."""
    Gf = np.asarray(G, dtype=float)
    if Gf.shape != (n, n):
        raise InputError(f"{label}G has shape {Gf.shape}; expected ({n}, {n}) to match eps")
    idx = np.flatnonzero(cand)
    Gc = Gf[np.ix_(idx, idx)]
    if not np.all(np.isfinite(Gc)):
        i, j = np.argwhere(~np.isfinite(Gc))[0]
        raise InputError(f"{label}G[{idx[i]}, {idx[j]}] = {float(Gc[i, j]):.6g} m/N "
                         f"must be finite")
    d = np.diag(Gc)
    if (d < 0.0).any():
        i = int(np.argmin(d))
        raise InputError(f"{label}G[{idx[i]}, {idx[i]}] = {d[i]:.6g} m/N is outside the "
                         f"allowed range [0, inf) m/N (a compliance)")
    big = np.abs(Gc).max()
    asym = np.abs(Gc - Gc.T).max()
    if asym > 1e-8 * big:
        raise InputError(f"{label}G is not symmetric: max |G - G^T| = {asym:.3g} m/N against "
                         f"max |G| = {big:.3g} m/N (allowed relative asymmetry 1e-8)")
    # reciprocity makes exact influence matrices symmetric; remove discretisation noise
    return 0.5 * (Gc + Gc.T)


def _check_semidefinite(Gc: np.ndarray, label: str) -> None:
    """Reject an indefinite G; cheap Cholesky first, eigenvalues only if that fails."""
    if Gc.size == 0:
        return
    shift = 1e-12 * max(float(np.max(np.diag(Gc))), 1e-300)
    try:
        np.linalg.cholesky(Gc + shift * np.eye(Gc.shape[0]))
        return
    except np.linalg.LinAlgError:
        ev = np.linalg.eigvalsh(Gc)
    if ev[0] < -1e-8 * max(ev[-1], 0.0):
        raise InputError(f"{label}G is not positive semidefinite: smallest eigenvalue "
                         f"{ev[0]:.3g} m/N against largest {ev[-1]:.3g} m/N")


class _OnCandidates:
    """A local-compliance model seen only on the candidate points."""

    def __init__(self, model: LocalCompliance, idx: np.ndarray, n: int, label: str):
        self.model, self.idx, self.n, self.label = model, idx, n, label
        self.full = idx.size == n

    def _scatter(self, Fc: np.ndarray) -> np.ndarray:
        if self.full:
            return Fc
        F = np.zeros(self.n)
        F[self.idx] = Fc
        return F

    def approach(self, Fc: np.ndarray) -> np.ndarray:
        u = np.asarray(self.model.approach(self._scatter(Fc)), dtype=float)
        u = u if self.full else u[self.idx]
        if not np.all(np.isfinite(u)):
            raise InputError(f"{self.label}local contact model returned a non-finite approach "
                             f"u_c at loads {Fc[~np.isfinite(u)][:3]} N")
        return u

    def tangent(self, Fc: np.ndarray) -> np.ndarray:
        t = np.asarray(self.model.tangent(self._scatter(Fc)), dtype=float)
        return t if self.full else t[self.idx]


def _tolerance(g: np.ndarray, F: np.ndarray, eps: np.ndarray, x: float, tol: float) -> float:
    """Residual bound: ``tol`` x largest elastic approach + a floor of ulps of the positions."""
    act = F > 0.0
    if not act.any():
        return 0.0
    elastic = float(np.max(x - eps[act]))
    ref = max(abs(x), float(np.abs(eps[act]).max()), float(np.abs(g[act]).max()))
    return tol * max(elastic, 0.0) + 64.0 * _EPS * ref


def mesh_stiffnesses(G: np.ndarray, loads: np.ndarray, approach: float, separations: np.ndarray,
                     local=None) -> tuple[float, float, float]:
    """(tangent, secant, pointwise) mesh stiffness of loaded contact points, N/m.

    Tangent ``k_t = 1^T (G_AA + D_A)^-1 1`` over the loaded points A (D the local contact
    tangent compliance, when ``local`` gives one), secant ``k_s = P / (x - min eps)`` and
    pointwise ``k_m = sum_A F_i / (x - eps_i)`` (:mod:`pipeline.contact.results`), with
    ``x`` the approach and ``eps`` the initial separations (m; ``inf`` off the path of
    contact). A set of points without load has none of them: (0, 0, 0); a loaded set whose
    approach does not exceed a separation (no deflection to divide by) gives ``inf``.

    Parameters
    ----------
    G : (n, n) compliance of the points, m/N. loads : (n,) N.
    approach : x, m. separations : (n,) eps, m.
    local : local contact model with ``tangent(loads)`` (m/N per point), or ``None``.
    """
    act = loads > 0.0
    if not act.any():
        return 0.0, 0.0, 0.0
    M = G[np.ix_(act, act)]
    if local is not None:
        with np.errstate(divide="ignore", invalid="ignore"):  # +inf at unloaded points
            M = M + np.diag(np.asarray(local.tangent(loads), dtype=float)[act])
    P = float(loads[act].sum())
    delta = approach - float(separations[np.isfinite(separations)].min())
    k_s = P / delta if delta > 0.0 else math.inf
    defl = approach - separations[act]
    k_m = float(np.sum(loads[act] / defl)) if np.all(defl > 0.0) else math.inf
    return _bordered_tangent(M), k_s, k_m


def _bordered_tangent(M: np.ndarray) -> float:
    """``1^T M^{-1} 1`` (N/m) via the bordered system, robust to singular ``M``."""
    m = M.shape[0]
    s = float(np.max(np.abs(np.diag(M)))) or 1.0
    K = np.zeros((m + 1, m + 1))
    K[:m, :m] = M
    K[:m, m] = s
    K[m, :m] = s
    rhs = np.zeros(m + 1)
    rhs[m] = s
    try:
        sol = np.linalg.solve(K, rhs)
        if not np.all(np.isfinite(sol)):
            raise np.linalg.LinAlgError
    except np.linalg.LinAlgError:
        sol = np.linalg.lstsq(K, rhs, rcond=1e-13)[0]
    dx = -s * sol[m]  # approach per unit load, m/N
    return 1.0 / dx if dx > 0.0 else math.inf


def _line_search(local: _OnCandidates, GF: np.ndarray, Gd: np.ndarray, eps: np.ndarray,
                 F: np.ndarray, d: np.ndarray, x: float) -> float:
    """Minimise the convex objective on ``F + alpha d``, ``alpha`` in [0, 1].

    ``sum(d) = 0``, so shifting ``g`` by the constant ``x`` leaves the slope
    unchanged in exact arithmetic and removes the round-off ``x sum(d)``, which
    near convergence is larger than the slope itself.
    """
    shifted = eps - x

    def slope(a: float) -> float:
        Fa = np.maximum(F + a * d, 0.0)
        return float(d @ (GF + a * Gd + local.approach(Fa) + shifted))

    if slope(1.0) <= 0.0:
        return 1.0
    # the slope is increasing (convexity) and changes sign in (0, 1)
    from scipy.optimize import brentq  # 0.6 s to import; only the line search needs it

    return float(brentq(slope, 0.0, 1.0, xtol=1e-14, rtol=1e-6, maxiter=200))


def _solve_nonlinear(Gc, ec, P, local, F, tol, max_iter, label):
    """Damped Newton on the active set; returns loads, approach, residual, bound, counts."""
    n = ec.size
    floor = 1e-6 * P / n
    mu = 0.0
    faces = 0
    for it in range(1, max_iter + 1):
        u = local.approach(F)
        GF = Gc @ F
        g = GF + u + ec
        x, res = complementarity_residual(g, F)
        bound = _tolerance(g, F, ec, x, tol)
        if res <= bound:
            return F, x, res, bound, faces, it - 1
        D = local.tangent(np.maximum(F, floor))
        if not np.all(np.isfinite(D)):
            raise InputError(f"{label}local contact model returned a non-finite tangent "
                             f"du_c/dF at positive load")
        Dm = np.maximum(D, 0.0)  # the physics is checked at the solution; the model stays PD
        B = Gc + np.diag(Dm + mu * (np.diag(Gc) + Dm))
        try:
            qp = solve_qp(B, g - B @ F, P, F)
        except ActiveSetError as exc:
            raise ContactConvergenceError(f"{label}{exc}") from None
        faces += qp.face_solves
        d = qp.loads - F
        if float(d @ (g - x)) >= 0.0 or not d.any():  # no descent: round-off or bad model
            mu = max(10.0 * mu, 1.0)
            if mu > 1e8:
                break
            continue
        alpha = _line_search(local, GF, Gc @ d, ec, F, d, x)
        F = qp.loads.copy() if alpha == 1.0 else np.maximum(F + alpha * d, 0.0)
        mu = max(10.0 * mu, 1.0) if alpha < 1e-3 else (0.0 if mu < 1e-6 else 0.1 * mu)
    raise ContactConvergenceError(
        f"{label}nonlinear contact solve did not converge in {max_iter} Newton iterations: "
        f"residual {res:.3g} m > bound {bound:.3g} m (tol = {tol:g})"
    )


def _solve(G, eps, P, hertz, tol, max_iter, label, start) -> ContactSolution:
    """Solve one validated position. ``label`` is '' or 'name: ' for messages."""
    n = eps.size
    cand = np.isfinite(eps)
    idx = np.flatnonzero(cand)
    Gc = _check_compliance(G, n, cand, label)
    _check_semidefinite(Gc, label)
    ec = eps[idx]
    local = None if hertz is None else _OnCandidates(hertz, idx, n, label)
    Fc = np.zeros(idx.size)
    faces = newton = 0
    if P == 0.0:
        x, res, bound = float(ec.min()), 0.0, 0.0
    else:
        F0 = None
        if start is not None:
            s = np.maximum(np.asarray(start, dtype=float)[idx], 0.0)
            if s.sum() > 0.0 and np.all(np.isfinite(s)):
                F0 = s * (P / s.sum())
        if F0 is None:
            F0 = np.zeros(idx.size)
            F0[int(np.argmin(ec))] = P
        if local is None:
            try:
                qp = solve_qp(Gc, ec, P, F0)
            except ActiveSetError as exc:
                raise ContactConvergenceError(f"{label}{exc}") from None
            Fc, faces = qp.loads, qp.face_solves
            g = Gc @ Fc + ec
            x, res = complementarity_residual(g, Fc)
            bound = _tolerance(g, Fc, ec, x, tol)
            if res > bound:
                raise ContactConvergenceError(
                    f"{label}linear contact solve residual {res:.3g} m exceeds bound "
                    f"{bound:.3g} m (tol = {tol:g}); G is probably too ill-conditioned")
        else:
            if start is None:
                # first model: the secant compliance of u_c at an even share of the load
                Fm = np.full(idx.size, P / idx.size)
                sec = local.approach(Fm) / Fm
                try:
                    qp = solve_qp(Gc + np.diag(sec), ec, P, F0)
                except ActiveSetError as exc:
                    raise ContactConvergenceError(f"{label}{exc}") from None
                F0, faces = qp.loads, qp.face_solves
            Fc, x, res, bound, f2, newton = _solve_nonlinear(
                Gc, ec, P, local, F0, tol, max_iter, label)
            faces += f2
            _check_validity(hertz, n, idx, Fc, label)
    return _assemble(G, eps, P, idx, Fc, x, res, bound, faces, newton, local, Gc, ec, label)


def _check_validity(hertz, n: int, idx: np.ndarray, Fc: np.ndarray, label: str) -> None:
    """Reject loads beyond where a Hertz model's tangent compliance stays positive."""
    if not hasattr(hertz, "max_valid_load"):
        return
    fmax = np.broadcast_to(hertz.max_valid_load(), (n,))[idx]
    over = Fc > fmax
    if over.any():
        i = int(np.argmax(Fc - fmax))
        raise InputError(f"{label}point {idx[i]} carries {Fc[i]:.6g} N, beyond the "
                         f"{fmax[i]:.6g} N where the Weber local contact approach stops "
                         f"increasing (half-width comparable to the tooth depth)")


def _assemble(G, eps, P, idx, Fc, x, res, bound, faces, newton, local, Gc, ec, label):
    n = eps.size
    act_c = Fc > 0.0
    uc = np.zeros(idx.size) if local is None else local.approach(Fc)
    gap_c = Gc @ Fc + uc + ec - x
    if P == 0.0:
        first = ec == ec.min()
        k_t = 0.0 if local is not None else _bordered_tangent(Gc[np.ix_(first, first)])
        k_s = k_m = k_t
    else:
        k_t, k_s, k_m = mesh_stiffnesses(Gc, Fc, x, ec, local)
    loads = np.zeros(n)
    loads[idx] = Fc
    active = np.zeros(n, dtype=bool)
    active[idx] = act_c
    gap = np.full(n, math.inf)
    gap[idx] = gap_c
    u = np.zeros(n)
    u[idx] = uc
    return ContactSolution(
        loads=loads, approach=float(x), active=active, gap=gap, contact_deformation=u,
        total_load=float(P), residual=float(res), tolerance=float(bound), iterations=int(faces),
        newton_iterations=int(newton), mesh_stiffness_secant=float(k_s),
        mesh_stiffness_tangent=float(k_t), mesh_stiffness_pointwise=float(k_m),
        label=label[:-2] if label else None,
    )


def _check_gaps(eps: ArrayLike, label: str) -> np.ndarray:
    e = np.array(eps, dtype=float)
    if e.ndim != 1 or e.size == 0:
        raise InputError(f"{label}eps has shape {e.shape}; expected (n,) with n >= 1")
    bad = np.isnan(e) | (e == -math.inf)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise InputError(f"{label}eps[{i}] = {float(e[i]):.6g} m is outside the allowed range "
                         f"(-inf, inf] m (+inf marks a point out of mesh)")
    if not np.isfinite(e).any():
        raise InputError(f"{label}eps is +inf at every point: no point can carry the load")
    return e


def _check_options(tol: float, max_iter: int) -> None:
    check_range("tol", tol, 0.0, 1e-2, lo_open=True)
    check_int_range("max_iter", max_iter, 1)


def solve_contact(
    G: ArrayLike,
    eps: ArrayLike,
    P: float,
    hertz: LocalCompliance | None = None,
    *,
    tol: float = 1e-10,
    max_iter: int = 100,
    start: ArrayLike | None = None,
    label: str | None = None,
) -> ContactSolution:
    """Loads and approach of one mesh position (module docstring for the method).

    Parameters
    ----------
    G : (n, n) structural compliance, m/N, symmetric positive semidefinite
        (relative asymmetry up to 1e-8 is accepted and symmetrised away).
    eps : (n,) initial separations, m (profile/lead modifications, errors);
        ``+inf`` marks a point out of mesh. Only differences matter.
    P : total normal load along the line of action, N, >= 0.
    hertz : local contact approach ``u_c(F)`` of the n points (a
        :class:`~pipeline.contact.hertz.LocalCompliance`, e.g.
        :class:`~pipeline.contact.hertz.HertzLineContact`), or None for a linear problem.
    tol : relative tolerance (-): the complementarity residual must not exceed
        ``tol`` times the largest elastic approach ``max(x_s - eps_i)`` on loaded
        points (plus 64 ulps of the absolute positions). In (0, 1e-2].
    max_iter : maximum number of Newton iterations (nonlinear case), >= 1.
    start : optional (n,) initial loads, N (e.g. the neighbouring mesh position);
        rescaled to ``P``.
    label : mesh-position name used in error messages and stored in the result.

    Returns
    -------
    ContactSolution

    Raises
    ------
    InputError for invalid inputs (names the field, value and allowed range).
    ContactConvergenceError if the residual bound is not met.
    """
    lab = f"{label}: " if label else ""
    e = _check_gaps(eps, lab)
    check_range(f"{lab}P", P, 0.0, math.inf, unit="N")
    _check_options(tol, max_iter)
    return _solve(G, e, float(P), hertz, tol, max_iter, lab, start)
