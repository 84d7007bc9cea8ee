"""Harmonic balance (Fourier series method) for the linear time-periodic equations.

The steady response is sought as ``q(t) = sum_{h=-H}^{H} Q_h exp(i h w t)`` with
``w = 2 pi / T``. Balancing each harmonic of

    M q'' + C q' + (K + sum_j s_j(t) u_j v_j^T) q = f(t)

gives, with ``s_j = sum_l c_{j,l} exp(i l w t)``,

    Z_h Q_h + sum_j u_j sum_p c'_{j,h-p} (v_j . Q_p) = F_h,
    Z_h = -(h w)^2 M + i h w C + K + sum_j c_{j,0} u_j v_j^T,

where ``c'`` has its mean removed (the mean sits in Z_h so that Z_0 is regular).
Two couplings are offered:

* ``"full"`` (Hill's method): all harmonics are coupled through the stiffness
  fluctuation. The coupling is low rank (one rank per mesh term and harmonic), so
  the solve uses the Woodbury identity: per-harmonic solves with Z_h, then one
  dense "capacitance" system of size n_terms (2H+1). ``method="dense"`` assembles
  the whole n (2H+1) system instead (for checks).
* ``"first_order"`` (Jin et al. 2018, sec. 5): the fluctuation acts only on the static
  deflection, ``Z_h Q_h = F_h - sum_j u_j c'_{j,h} (v_j . Q_0)``, so every order is
  an independent time-invariant problem and the response is the superposition of
  the responses to each order. It neglects products of fluctuations.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from pipeline.dynamics.reduction import reduce_rigid_body_modes
from pipeline.dynamics.results import HarmonicResponse, Response
from pipeline.dynamics.signals import fourier_coefficients
from pipeline.dynamics.system import LinearPeriodicSystem
from pipeline.validation import InputError, check_choice, check_int_range


def _coefficients(system: LinearPeriodicSystem, H: int):
    """Term coefficients for orders -2H..2H, shape (J, 4H+1); forcing F_h, shape (2H+1, n)."""
    J = len(system.terms)
    c = np.array(
        [fourier_coefficients(t.signal, t.order, t.phase, 2 * H) for t in system.terms]
    ).reshape(J, 4 * H + 1)
    h = np.arange(-H, H + 1)
    F = np.zeros((2 * H + 1, system.n), dtype=complex)
    F[H] += system.f0
    for f in system.forcing:
        g = fourier_coefficients(f.signal, f.order, f.phase, H)
        if f.derivative:
            g = g * (2j * np.pi * h / system.period)
        F += g[:, None] * f.vector[None, :]
    return c, F


def _block_matrices(system: LinearPeriodicSystem, H: int, c0: np.ndarray) -> np.ndarray:
    """Z_h for h = -H..H, shape (2H+1, n, n), complex."""
    w = 2 * np.pi / system.period
    h = np.arange(-H, H + 1)
    K = system.constant_stiffness().astype(complex)
    if system.terms:
        U = np.array([t.u for t in system.terms]).T
        V = np.array([t.v for t in system.terms]).T
        K = K + (U * c0) @ V.T
    Cd = system.damping_matrix()
    return (
        -((h * w)[:, None, None] ** 2) * system.M[None]
        + 1j * (h * w)[:, None, None] * Cd[None]
        + K[None]
    )


def solve_coefficients(
    system: LinearPeriodicSystem,
    n_harmonics: int,
    coupling: str = "full",
    method: str = "woodbury",
) -> np.ndarray:
    """Harmonic coefficients Q_h of the independent coordinates, shape (2H+1, n).

    Parameters
    ----------
    system : a system without rigid-body modes.
    n_harmonics : H (>= 1); the response keeps orders -H..H of 1/T.
    coupling : "full" (Hill) or "first_order" (Jin et al. 2018).
    method : "woodbury" (real-form capacitance, :func:`woodbury_real`), "woodbury_complex"
        (all orders in complex arithmetic) or "dense" (full coupling only; for checks).
    """
    H = check_int_range("n_harmonics", n_harmonics, 1, 5000)
    check_choice("coupling", coupling, ("full", "first_order"))
    check_choice("method", method, ("woodbury", "woodbury_complex", "dense"))
    n, J = system.n, len(system.terms)
    c, F = _coefficients(system, H)
    c0 = c[:, 2 * H].real if J else np.zeros(0)
    cf = c.copy()
    if J:
        cf[:, 2 * H] = 0.0
    Z = _block_matrices(system, H, c0)
    if J == 0:
        return np.linalg.solve(Z, F[..., None])[..., 0]
    U = np.array([t.u for t in system.terms]).T.astype(complex)
    V = np.array([t.v for t in system.terms]).T
    if coupling == "first_order":
        Q0 = np.linalg.solve(Z[H], F[H])
        w0 = V.T @ Q0  # (J,)
        hh = np.arange(-H, H + 1)
        rhs = F - (cf[:, hh + 2 * H].T * w0[None, :]) @ U.T
        rhs[H] = F[H]
        return np.linalg.solve(Z, rhs[..., None])[..., 0]
    hh = np.arange(-H, H + 1)
    # Ct[h, p, j] = c'_{j, h - p}
    Ct = cf[:, (hh[:, None] - hh[None, :]) + 2 * H].transpose(1, 2, 0)
    if method == "dense":
        NH = 2 * H + 1
        A = np.zeros((NH, n, NH, n), dtype=complex)
        A[hh + H, :, hh + H, :] = Z
        A += np.einsum("ij,hpj,kj->hipk", U, Ct, V)
        Q = np.linalg.solve(A.reshape(NH * n, NH * n), F.reshape(-1))
        return Q.reshape(NH, n)
    if method == "woodbury_complex":
        return _woodbury_complex(Z, F, U, V, Ct)
    Qp = woodbury_real(Z[H:], F[H:], U.real, V, cf, H)
    return np.concatenate([Qp[:0:-1].conj(), Qp], axis=0)


def _woodbury_complex(Z, F, U, V, Ct) -> np.ndarray:
    """Woodbury over all orders -H..H in complex arithmetic (the reference of the real form)."""
    NH, n = F.shape
    J = U.shape[1]
    rhs = np.concatenate([F[..., None], np.broadcast_to(U, (NH, n, J))], axis=2)
    Y = np.linalg.solve(Z, rhs)  # (NH, n, 1+J)
    ZF, ZU = Y[..., 0], Y[..., 1:]
    A = np.einsum("nj,hnk->hjk", V, ZU)  # (NH, J, J) = V^T Z^-1 U
    b = ZF @ V  # (NH, J)
    cap = np.einsum("hjk,hpk->hjpk", A, Ct).reshape(NH * J, NH * J) + np.eye(NH * J)
    W = np.linalg.solve(cap, b.reshape(-1)).reshape(NH, J)
    G = np.einsum("hpj,pj->hj", Ct, W)  # sum_p c'_{h-p} w_p
    return ZF - np.einsum("hnj,hj->hn", ZU, G)


def woodbury_real(Z: np.ndarray, F: np.ndarray, U: np.ndarray, V: np.ndarray, cf: np.ndarray,
                  H: int) -> np.ndarray:
    """Q_0..Q_H, shape (H+1, n): Woodbury with the capacitance system in real arithmetic.

    M, C, K, u_j, v_j and the signals are real, so ``Q_{-h} = conj(Q_h)`` and the mesh
    deflections ``w_h = V^T Q_h`` too. The unknowns are then ``Re w_0`` and the real and
    imaginary parts of ``w_1..w_H``: (2H+1) J reals instead of as many complex numbers,
    and the equations of orders 0..H (real part of order 0, both parts of the others).
    A real LU of the same size costs a quarter of the complex one, and only the H+1
    blocks Z_0..Z_H are solved. Same coefficients as the complex form to round-off.

    Z : (H+1, n, n) blocks Z_0..Z_H; F : (H+1, n) forcing orders 0..H; U, V : (n, J);
    cf : (J, 4H+1) fluctuation coefficients c'_{j,l}, l = -2H..2H.
    """
    n, J = U.shape
    rhs = np.concatenate([F[..., None], np.broadcast_to(U.astype(complex), (H + 1, n, J))],
                         axis=2)
    Y = np.linalg.solve(Z, rhs)  # (H+1, n, 1+J)
    ZF, ZU = Y[..., 0], Y[..., 1:]
    A = V.T[None] @ ZU  # (H+1, J, J)
    b = ZF @ V  # (H+1, J)
    h = np.arange(H + 1)
    cm = cf[:, h[:, None] - h[None, :] + 2 * H].transpose(1, 2, 0)  # c'_{h-p}, (h, p, J)
    cp = cf[:, h[:, None] + h[None, :] + 2 * H].transpose(1, 2, 0)  # c'_{h+p}
    Dr = cm + cp  # multiplies Re w_p (p >= 1): c'_{h-p} w_p + c'_{h+p} conj(w_p)
    Dr[:, 0] = cm[:, 0]
    Di = 1j * (cm[:, 1:] - cp[:, 1:])  # multiplies Im w_p, p = 1..H
    # rows: Re of orders 0..H, then Im of orders 1..H; columns: Re w_0..w_H, Im w_1..w_H
    NR, NI = (H + 1) * J, H * J
    Ar, Ai = A.real[:, :, None, :], A.imag[:, :, None, :]  # (h, j, 1, k)
    mat = np.empty((NR + NI, NR + NI))
    # block (h, p) of A_h diag(D[h, p]) in real arithmetic, laid out as (h, j, p, k)
    for cols, D in ((slice(0, NR), Dr), (slice(NR, NR + NI), Di)):
        Dre, Dim = D.real[:, None], D.imag[:, None]
        mat[:NR, cols] = (Ar * Dre - Ai * Dim).reshape(NR, -1)
        mat[NR:, cols] = (Ar[1:] * Dim[1:] + Ai[1:] * Dre[1:]).reshape(NI, -1)
    mat[np.diag_indices(NR + NI)] += 1.0
    rhs_w = np.concatenate([b.real.ravel(), b[1:].imag.ravel()])
    x = sla.solve(mat, rhs_w, overwrite_a=True, overwrite_b=True, check_finite=False)
    W = x[:(H + 1) * J].reshape(H + 1, J).astype(complex)
    W[1:] += 1j * x[(H + 1) * J:].reshape(H, J)
    Gh = np.einsum("hpj,pj->hj", Dr, W.real) + np.einsum("hpj,pj->hj", Di, W[1:].imag)
    return ZF - (ZU @ Gh[..., None])[..., 0]


def harmonic_balance(
    system: LinearPeriodicSystem,
    n_harmonics: int = 20,
    coupling: str = "full",
    method: str = "woodbury",
    samples: int | None = None,
) -> HarmonicResponse:
    """Steady periodic response by harmonic balance, with per-order contributions.

    Parameters
    ----------
    system : any system (rigid-body modes are removed first).
    n_harmonics : H, highest harmonic order of 1/T kept.
    coupling : "full" (Hill, agrees with time integration) or "first_order" (Jin et al. 2018).
    method : "woodbury" (fast), "woodbury_complex" or "dense" (see :func:`solve_coefficients`).
    samples : points of the returned period (default max(16 H, 512)).

    Returns
    -------
    :class:`HarmonicResponse`.
    """
    red = reduce_rigid_body_modes(system)
    H = int(n_harmonics)
    max_order = max([t.order for t in red.terms] + [f.order for f in red.forcing] + [1])
    if coupling == "full" and max_order > H:
        raise InputError(
            f"n_harmonics = {H} is below the highest term order {max_order}; "
            "use coupling='first_order' or raise n_harmonics"
        )
    Q = solve_coefficients(red, H, coupling, method)
    N = max(16 * H, 512) if samples is None else check_int_range("samples", samples, 8, 10**7)
    tau = np.arange(N + 1) / N
    h = np.arange(-H, H + 1)
    E = np.exp(2j * np.pi * np.outer(tau, h))  # (N+1, NH)
    w = 2 * np.pi / red.period
    q = (E @ Q).real
    qd = (E @ ((1j * h * w)[:, None] * Q)).real
    V = np.array([ms.v for ms in red.meshes]).reshape(len(red.meshes), red.n)
    dte = V @ q.T
    rate = V @ qd.T
    force = np.zeros_like(dte)
    elastic = np.zeros_like(dte)
    for i, ms in enumerate(red.meshes):
        t = red.terms[ms.term]
        k = t.signal(t.order * tau - t.phase)
        e = ed = 0.0
        if ms.transmission_error is not None:
            ce = fourier_coefficients(ms.transmission_error, t.order, t.phase, H)
            e = ms.transmission_error(t.order * tau - t.phase)
            ed = (E @ (1j * h * w * ce)).real
        elastic[i] = k * (dte[i] - e)
        force[i] = elastic[i] + ms.damping * (rate[i] - ed)
    resp = Response(
        time=tau * red.period,
        q=red.expand(q),
        qd=red.expand(qd),
        dte=dte,
        mesh_force=force,
        dof_names=red.dof_names,
        mesh_names=tuple(ms.name for ms in red.meshes),
        period=red.period,
        method="harmonic-balance",
        elastic_force=elastic,
    )
    dh = Q @ V.T  # (NH, n_mesh)
    amp = np.abs(dh[H:]).T.copy()
    amp[:, 1:] *= 2.0
    tot = amp[:, 1:].sum(axis=1, keepdims=True)
    contrib = np.divide(amp[:, 1:], tot, out=np.zeros_like(amp[:, 1:]), where=tot > 0)
    return HarmonicResponse(
        response=resp,
        orders=np.arange(H + 1),
        dte_amplitude=amp,
        dte_contribution=contrib,
        coefficients=red.expand(Q),
        dte_coefficients=dh,
    )
