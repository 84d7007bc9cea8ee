"""Time integration by exact propagators over segments of constant coefficients.

Within a segment of the period every periodic coefficient is held at its exact
mean over the segment (:func:`pipeline.dynamics.signals.segment_means`); the
linear equations with constant coefficients are then integrated *exactly* with
one matrix exponential of the augmented state matrix

    [x; 1]' = [[A, b], [0, 0]] [x; 1],  A = [[0, I], [-M^-1 K_j, -M^-1 C]].

Stiffness jumps at segment edges cost nothing (no step-size control, no
overshoot), the scheme is second-order in the segment length for smooth
coefficients and exact for piecewise-constant ones on aligned segments, and an
undamped system with constant stiffness conserves energy to round-off.
Because the period's segment maps are reused, N periods cost one batched
``expm`` plus N small matrix products; the periodic steady state comes from the
Floquet fixed point ``x0 = (I - Phi_T)^-1 g_T`` directly.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as sla

from pipeline.dynamics.reduction import reduce_rigid_body_modes
from pipeline.dynamics.results import Response
from pipeline.dynamics.signals import segment_means, segment_slopes
from pipeline.dynamics.system import LinearPeriodicSystem
from pipeline.validation import InputError, check_int_range, check_positive


@dataclass(frozen=True)
class Propagator:
    """Segment maps of one period of a (rigid-mode-free) system.

    Attributes
    ----------
    system : the system the maps belong to (independent coordinates, n).
    edges : shape (m+1,), segment edges in system phase (0..1).
    P : shape (m+1, 2n, 2n), state transition from the period start to each edge.
    h : shape (m+1, 2n), affine part at each edge (zero initial state).
    coef : shape (n_terms, m), segment values of the periodic coefficients.
    """

    system: LinearPeriodicSystem
    edges: np.ndarray
    P: np.ndarray
    h: np.ndarray
    coef: np.ndarray

    @property
    def monodromy(self) -> np.ndarray:
        """Phi_T, shape (2n, 2n)."""
        return self.P[-1]


def default_segments(system: LinearPeriodicSystem) -> int:
    """Segments per period: the finest sample grid of any coefficient (>= 64)."""
    sizes = [t.signal.values.size * t.order for t in system.terms]
    sizes += [f.signal.values.size * f.order for f in system.forcing]
    return max([64] + sizes)


def build_propagator(system: LinearPeriodicSystem, segments: int | None = None) -> Propagator:
    """Matrix-exponential maps of every segment of one period.

    Parameters
    ----------
    system : a system without rigid-body modes (see :func:`reduce_rigid_body_modes`).
    segments : uniform segments per period (default :func:`default_segments`).
    """
    m = (
        default_segments(system)
        if segments is None
        else check_int_range("segments", segments, 4, 10_000_000)
    )
    n = system.n
    edges = np.linspace(0.0, 1.0, m + 1)
    dt = system.period / m
    coef = np.array(
        [segment_means(t.signal, t.order, t.phase, edges) for t in system.terms]
    ).reshape(len(system.terms), m)
    force = np.repeat(system.f0[None, :], m, axis=0)
    for f in system.forcing:
        if f.derivative:
            val = segment_slopes(f.signal, f.order, f.phase, edges) / system.period
        else:
            val = segment_means(f.signal, f.order, f.phase, edges)
        force += val[:, None] * f.vector[None, :]
    Minv = np.linalg.inv(system.M)
    K0 = system.constant_stiffness()
    if system.terms:
        U = np.array([t.u for t in system.terms]).T
        V = np.array([t.v for t in system.terms]).T
        Kseg = K0[None] + np.einsum("ij,jm,kj->mik", U, coef, V)
    else:
        Kseg = np.repeat(K0[None], m, axis=0)
    Z = np.zeros((m, 2 * n + 1, 2 * n + 1))
    Z[:, :n, n : 2 * n] = np.eye(n)
    Z[:, n : 2 * n, :n] = -Minv @ Kseg
    Z[:, n : 2 * n, n : 2 * n] = -Minv @ system.damping_matrix()
    Z[:, n : 2 * n, -1] = force @ Minv.T
    E = sla.expm(Z * dt)
    Phi, g = E[:, : 2 * n, : 2 * n], E[:, : 2 * n, -1]
    P = np.empty((m + 1, 2 * n, 2 * n))
    h = np.empty((m + 1, 2 * n))
    P[0], h[0] = np.eye(2 * n), 0.0
    for j in range(m):
        P[j + 1] = Phi[j] @ P[j]
        h[j + 1] = Phi[j] @ h[j] + g[j]
    return Propagator(system, edges, P, h, coef)


def floquet_multipliers(system: LinearPeriodicSystem, segments: int | None = None) -> np.ndarray:
    """Eigenvalues of the monodromy matrix, shape (2n,); stable when all |mu| < 1 (<= 1 undamped).

    Rigid-body modes are removed first.
    """
    prop = build_propagator(reduce_rigid_body_modes(system), segments)
    return np.linalg.eigvals(prop.monodromy)


def _response(
    prop: Propagator, starts: np.ndarray, method: str, steady_from_period: int = 0
) -> Response:
    """Assemble a Response from period-start states ``starts`` (k, 2n)."""
    sysm = prop.system
    n = sysm.n
    m = prop.edges.size - 1
    X = np.einsum("jab,kb->kja", prop.P[:-1], starts) + prop.h[None, :-1]
    X = X.reshape(-1, 2 * n)
    last = prop.P[-1] @ starts[-1] + prop.h[-1]
    X = np.vstack([X, last])
    kper = starts.shape[0]
    tau = np.arange(kper * m + 1) / m
    q, qd = X[:, :n], X[:, n:]
    V = np.array([ms.v for ms in sysm.meshes]).reshape(len(sysm.meshes), n)
    dte = V @ q.T
    dte_rate = V @ qd.T
    seg = np.arange(tau.size) % m
    force = np.zeros_like(dte)
    elastic = np.zeros_like(dte)
    for i, ms in enumerate(sysm.meshes):
        k = prop.coef[ms.term, seg]
        e = ed = 0.0
        if ms.transmission_error is not None:
            tm = sysm.terms[ms.term]
            e = ms.transmission_error(tm.order * tau - tm.phase)
            ed = (
                segment_slopes(ms.transmission_error, tm.order, tm.phase, prop.edges)[seg]
                / sysm.period
            )
        elastic[i] = k * (dte[i] - e)
        force[i] = elastic[i] + ms.damping * (dte_rate[i] - ed)
    return Response(
        time=tau * sysm.period,
        q=sysm.expand(q),
        qd=sysm.expand(qd),
        dte=dte,
        mesh_force=force,
        dof_names=sysm.dof_names,
        mesh_names=tuple(ms.name for ms in sysm.meshes),
        period=sysm.period,
        steady_from=steady_from_period * m,
        method=method,
        end_state=last,
        elastic_force=elastic,
    )


def static_state(system: LinearPeriodicSystem) -> np.ndarray:
    """[q_static; 0] under the mean stiffness, shape (2n,) (rigid modes removed first)."""
    q = np.linalg.solve(system.mean_stiffness(), system.f0)
    return np.concatenate([q, np.zeros_like(q)])


def steady_state(
    system: LinearPeriodicSystem, segments: int | None = None, periods: int = 1
) -> Response:
    """Periodic steady state by the Floquet fixed point (exact for the segment model).

    Parameters
    ----------
    system : any system; rigid-body modes are removed first.
    segments : segments per period.
    periods : how many identical periods to return (>= 1).

    Returns
    -------
    :class:`Response` with ``periods * segments + 1`` samples.
    """
    check_int_range("periods", periods, 1, 100_000)
    red = reduce_rigid_body_modes(system)
    prop = build_propagator(red, segments)
    A = np.eye(2 * red.n) - prop.monodromy
    try:
        x0 = np.linalg.solve(A, prop.h[-1])
    except np.linalg.LinAlgError:
        raise InputError(
            "no periodic steady state: a Floquet multiplier equals 1 "
            "(undamped resonance or unremoved rigid mode)"
        ) from None
    starts = np.repeat(x0[None], periods, axis=0)
    return _response(prop, starts, "floquet")


def integrate(
    system: LinearPeriodicSystem,
    periods: int,
    x0: np.ndarray | None = None,
    segments: int | None = None,
    tol: float = 1e-6,
    stop_when_steady: bool = False,
    propagator: Propagator | None = None,
    keep_last: int | None = None,
) -> Response:
    """Transient response from an initial state, with steady-state detection.

    Parameters
    ----------
    system : any system (rigid-body modes are removed first).
    periods : number of system periods to integrate (>= 1).
    x0 : shape (2n,), initial [q; q'] in the reduced coordinates; default the static
        deflection under the mean stiffness.
    segments : segments per period.
    tol : steady when the period-to-period change of q and q' at the period start,
        relative to their largest values, is below ``tol``.
    stop_when_steady : stop at the first steady period (at least 2 periods).
    propagator : reuse maps built for this system (speeds up repeated calls).
    keep_last : return only the last ``keep_last`` periods (memory for long runs).

    Returns
    -------
    :class:`Response` with ``steady_from`` at the first sample of the first steady
    period (or at the end if it never became steady within ``periods``).
    """
    check_int_range("periods", periods, 1, 10_000_000)
    check_positive("tol", tol)
    prop = propagator
    if prop is None:
        prop = build_propagator(reduce_rigid_body_modes(system), segments)
    red = prop.system
    x = static_state(red) if x0 is None else np.asarray(x0, dtype=float)
    if x.shape != (2 * red.n,):
        raise InputError(f"x0 has shape {x.shape}; need ({2 * red.n},)")
    PhiT, gT = prop.monodromy, prop.h[-1]
    n = red.n
    starts = [x]
    steady = None
    for k in range(periods - 1):
        x_new = PhiT @ x + gT
        dq = np.abs(x_new[:n] - x[:n]).max() / max(np.abs(x_new[:n]).max(), 1e-300)
        dv = np.abs(x_new[n:] - x[n:]).max() / max(np.abs(x_new[n:]).max(), 1e-300)
        x = x_new
        starts.append(x)
        if steady is None and max(dq, dv) < tol:
            steady = k + 1
            if stop_when_steady:
                break
    starts = np.array(starts)
    first = (
        0
        if keep_last is None
        else max(0, len(starts) - check_int_range("keep_last", keep_last, 1, 10_000_000))
    )
    steady_k = len(starts) if steady is None else steady
    resp = _response(
        prop, starts[first:], "propagator", steady_from_period=max(0, steady_k - first)
    )
    if first:
        resp = replace(resp, time=resp.time + first * red.period)
    return resp
