"""Harmonic balance over many mesh frequencies: what does not depend on the speed, once.

A frequency sweep solves the same linear time-periodic system at many periods. The
Fourier coefficients of the stiffness terms, of the forcing and of the transmission
errors, the low-rank factors u_j, v_j of the mesh coupling and the sampled stiffness
and transmission error over one period do not depend on the period (with
:meth:`LinearPeriodicSystem.with_period` only T and the carrier speed change), so
:func:`plan_sweep` computes them once and :func:`sweep_point` does per frequency only
what does: the blocks Z_0..Z_H, the real-form Woodbury solve
(:func:`pipeline.dynamics.harmonic_balance.woodbury_real`) and the mesh forces over a
period. The plan is small (a few hundred kB for 56 DOF) and picklable, so it travels
to process-pool or Dask workers with each chunk of frequencies.

Same values as :func:`pipeline.dynamics.harmonic_balance.harmonic_balance` with the
same H and samples (``tests/test_dyn_sweep.py``, to 1e-12 relative).

The chunks run on a process pool or on Dask's ``Client.get_executor()``
(:func:`pipeline.dynamics.sweep.map_chunks`, the executors of a design study). The
real-form solve uses ``Q_{-h} = conj(Q_h)``: (2H+1) J real unknowns instead of as many
complex ones, a quarter of the LU, 2e-15 from the complex form. The 56-DOF herringbone
planetary at H = 20: 65 -> 21-23 ms per frequency serially (profile: the 656-unknown
capacitance LU is 9-10 ms of it). ``workflows/benchmarks/bench_study.py`` (one run on 2
cores, load average 1.4 at the start): the 500-point sweep 8.56 s serially and 3.84 s on 2
processes (2.23x; identical values; target < 5 s); 11.2 s under other jobs' load (4.5-8).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.dynamics.harmonic_balance import woodbury_real
from pipeline.dynamics.signals import fourier_coefficients
from pipeline.dynamics.system import LinearPeriodicSystem
from pipeline.validation import InputError


@dataclass(frozen=True)
class SweepPlan:
    """The speed-independent parts of a harmonic-balance sweep (full Hill coupling).

    Attributes
    ----------
    system : the system without rigid-body modes, at its reference period.
    H : harmonic orders 0..H kept.
    cf : shape (J, 4H+1), fluctuation coefficients c'_{j,l} of the terms (mean removed),
        l = -2H..2H, N/m.
    c0 : shape (J,), mean of each term, N/m.
    U, V : shape (n, J), low-rank factors of the terms.
    F_static, F_rate : shape (H+1, n), forcing coefficients of orders 0..H; the forcing
        is ``F_static + F_rate / T`` (derivative forcing terms scale with 1/T), N.
    E : shape (samples+1, H+1), ``exp(i 2 pi h tau)`` at the period's samples.
    Vm : shape (n_mesh, n), mesh deflection rows.
    k : shape (n_mesh, samples+1), mesh stiffness over a period, N/m.
    e : shape (n_mesh, samples+1), transmission error over a period, m.
    e_rate : shape (n_mesh, samples+1), d e / d tau (per period), m.
    damping : shape (n_mesh,), mesh damping, N s/m.
    """

    system: LinearPeriodicSystem
    H: int
    cf: np.ndarray
    c0: np.ndarray
    U: np.ndarray
    V: np.ndarray
    F_static: np.ndarray
    F_rate: np.ndarray
    E: np.ndarray
    Vm: np.ndarray
    k: np.ndarray
    e: np.ndarray
    e_rate: np.ndarray
    damping: np.ndarray


def plan_sweep(red: LinearPeriodicSystem, n_harmonics: int, samples: int) -> SweepPlan:
    """Precompute a sweep of ``red`` (no rigid-body modes; see the module docstring).

    Parameters
    ----------
    red : system without rigid-body modes.
    n_harmonics : H (>= the highest term order).
    samples : points per period at which the mesh forces are evaluated.
    """
    H = int(n_harmonics)
    orders = [t.order for t in red.terms] + [f.order for f in red.forcing] + [1]
    if max(orders) > H:
        raise InputError(f"n_harmonics = {H} is below the highest term order {max(orders)}")
    J, n = len(red.terms), red.n
    c = np.array([fourier_coefficients(t.signal, t.order, t.phase, 2 * H) for t in red.terms]
                 ).reshape(J, 4 * H + 1)
    c0 = c[:, 2 * H].real.copy()
    cf = c.copy()
    cf[:, 2 * H] = 0.0
    h = np.arange(H + 1)
    F_static = np.zeros((H + 1, n), dtype=complex)
    F_rate = np.zeros((H + 1, n), dtype=complex)
    F_static[0] += red.f0
    for f in red.forcing:
        g = fourier_coefficients(f.signal, f.order, f.phase, H)[H:]
        if f.derivative:
            F_rate += (2j * np.pi * h * g)[:, None] * f.vector[None, :]
        else:
            F_static += g[:, None] * f.vector[None, :]
    tau = np.arange(samples + 1) / samples
    E = np.exp(2j * np.pi * np.outer(tau, h))
    nm = len(red.meshes)
    k = np.zeros((nm, tau.size))
    e = np.zeros((nm, tau.size))
    e_rate = np.zeros((nm, tau.size))
    for i, ms in enumerate(red.meshes):
        t = red.terms[ms.term]
        k[i] = t.signal(t.order * tau - t.phase)
        if ms.transmission_error is not None:
            ce = fourier_coefficients(ms.transmission_error, t.order, t.phase, H)[H:]
            e[i] = ms.transmission_error(t.order * tau - t.phase)
            e_rate[i] = _real_series(E, 2j * np.pi * h * ce)
    return SweepPlan(
        system=red, H=H, cf=cf, c0=c0,
        U=np.array([t.u for t in red.terms]).T.reshape(n, J),
        V=np.array([t.v for t in red.terms]).T.reshape(n, J),
        F_static=F_static, F_rate=F_rate, E=E,
        Vm=np.array([ms.v for ms in red.meshes]).reshape(nm, n),
        k=k, e=e, e_rate=e_rate,
        damping=np.array([ms.damping for ms in red.meshes], dtype=float))


def _real_series(E: np.ndarray, C: np.ndarray) -> np.ndarray:
    """``sum_{h=-H..H} C_h exp(i 2 pi h tau)`` of a real signal from its orders 0..H.

    E : (N, H+1); C : (H+1,) or (H+1, m) -> (N,) or (N, m).
    """
    return (E[:, :1] @ C[:1].reshape(1, -1)).real.reshape(E.shape[0], *C.shape[1:]) \
        + 2.0 * (E[:, 1:] @ C[1:].reshape(C.shape[0] - 1, -1)).real.reshape(
            E.shape[0], *C.shape[1:])


def mesh_force_parts(plan: SweepPlan, frequency: float) -> tuple[np.ndarray, np.ndarray]:
    """Elastic k (delta - e) and damping c (delta' - e') parts of the mesh forces over one
    steady period at ``frequency`` (Hz), each shape (n_mesh, samples+1), N."""
    s = plan.system.with_mesh_frequency(frequency)
    H, w = plan.H, 2 * np.pi / s.period
    h = np.arange(H + 1)
    K = s.constant_stiffness() + (plan.U * plan.c0) @ plan.V.T
    Z = (-((h * w)[:, None, None] ** 2) * s.M[None] + 1j * (h * w)[:, None, None]
         * s.damping_matrix()[None] + K[None])
    F = plan.F_static + plan.F_rate / s.period
    if plan.U.shape[1]:
        Q = woodbury_real(Z, F, plan.U, plan.V, plan.cf, H)  # orders 0..H, (H+1, n)
    else:
        Q = np.linalg.solve(Z, F[..., None])[..., 0]
    D = Q @ plan.Vm.T  # (H+1, n_mesh)
    dte = _real_series(plan.E, D).T
    rate = _real_series(plan.E, (1j * h * w)[:, None] * D).T
    return (plan.k * (dte - plan.e),
            plan.damping[:, None] * (rate - plan.e_rate / s.period))


def sweep_point(plan: SweepPlan, frequency: float) -> np.ndarray:
    """RMS, alternating RMS, max and mean of every mesh force and max of its elastic part
    at ``frequency`` (Hz), shape (5, n_mesh), N (the statistics of
    :func:`pipeline.dynamics.sweep.mesh_force_sweep`)."""
    elastic, damping = mesh_force_parts(plan, frequency)
    elastic = elastic[:, :-1]  # one period without its repeated end point
    f = elastic + damping[:, :-1]
    mean = f.mean(axis=1)
    return np.stack([np.sqrt((f**2).mean(axis=1)),
                     np.sqrt(((f - mean[:, None]) ** 2).mean(axis=1)), f.max(axis=1), mean,
                     elastic.max(axis=1)])
