"""Frequency sweeps of the dynamic mesh force, and the dynamic load factors.

One map-style function, :func:`map_chunks`, runs independent work items locally
(:func:`pipeline.parallel.process_pool`: forked workers with one BLAS thread each,
ending with this process; in this process when the work is too short to pay for them,
:data:`POOL_WORTH_S`) or on any ``concurrent.futures.Executor`` (a Dask cluster's
``Client.get_executor()``).

Sweep methods (all return the same :class:`SweepResult`):

* ``"harmonic_balance"`` (default): each mesh frequency is independent; chunks of
  frequencies are mapped over the executor.
* ``"floquet"``: exact periodic steady state of the segment model per frequency
  (independent points, mapped too).
* ``"time"``: transient time integration, period by period, until the steady
  state is detected; each point starts from the steady state of the previous one
  (continuation, Xu et al. 2020, sec. 4), so it runs in order.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass
from functools import partial

import numpy as np

from pipeline.dynamics.hb_sweep import plan_sweep, sweep_point
from pipeline.dynamics.integrate import build_propagator, integrate, steady_state
from pipeline.dynamics.reduction import reduce_rigid_body_modes
from pipeline.dynamics.results import Response
from pipeline.dynamics.system import LinearPeriodicSystem
from pipeline.parallel import one_blas_thread, process_pool
from pipeline.progress import progress
from pipeline.validation import InputError, check_choice, check_int_range

POOL_WORTH_S = 0.5
"""Serial seconds of work below which a local sweep stays in this process: a forked pool
of 2 workers costs 0.1-0.25 s to start and feed (the demo's two 120-point sweeps, 0.1 s
of work each, took 0.31-0.36 s of CPU through the pool against 0.21 s in this process;
measured on 2 shared cores), so it halves only longer work."""


def map_chunks(
    func: Callable,
    items: Sequence,
    executor: Executor | str | None = "local",
    chunks: int | None = None,
    show_progress: bool = False,
) -> list:
    """``[func(item) for item in items]`` run in chunks, locally or on an executor.

    Parameters
    ----------
    func : picklable function of one item (a module-level function or ``partial``).
    items : the work items.
    executor : ``"local"`` (a fresh :func:`~pipeline.parallel.process_pool`, shut down
        afterwards, once the first item, computed here, shows that the rest would take
        more than :data:`POOL_WORTH_S` in this process; else all here), ``None`` (serial,
        in this process, one BLAS thread) or any ``concurrent.futures.Executor`` (e.g.
        Dask's). Every item is computed by the same function with one BLAS thread
        wherever it runs, so the results do not depend on where.
    chunks : number of chunks (default: 4 per worker).
    show_progress : progress bar on stderr.

    Returns
    -------
    list of results in the order of ``items``.
    """
    items = list(items)
    if executor is None or len(items) <= 1:
        with one_blas_thread():
            return [func(i) for i in progress(items, "sweep", enabled=show_progress)]
    own = executor == "local"
    first: list = []
    if own:
        t0 = time.perf_counter()
        with one_blas_thread():
            first = [func(items[0])]
        if (time.perf_counter() - t0) * (len(items) - 1) < POOL_WORTH_S:
            with one_blas_thread():
                return first + [func(i) for i in progress(items[1:], "sweep",
                                                          enabled=show_progress)]
        items = items[1:]
    ex = process_pool() if own else executor
    try:
        nw = getattr(ex, "_max_workers", os.cpu_count() or 1)
        nchunk = min(len(items), chunks or 4 * nw)
        parts = [list(p) for p in np.array_split(np.arange(len(items)), nchunk)]
        futures = [ex.submit(_run_chunk, func, [items[i] for i in p]) for p in parts]
        out: list = first
        for f in progress(futures, "sweep", total=len(futures), enabled=show_progress):
            out.extend(f.result())
        return out
    finally:
        if own:
            ex.shutdown()


def _run_chunk(func: Callable, items: list) -> list:
    return [func(i) for i in items]


@dataclass(frozen=True)
class SweepResult:
    """Mesh-force response against mesh frequency.

    Attributes
    ----------
    frequencies : shape (F,), mesh frequency, Hz.
    rms_force : shape (n_mesh, F), RMS of the dynamic mesh force over a steady period, N.
    rms_alternating : shape (n_mesh, F), RMS of the force minus its mean, N.
    max_force : shape (n_mesh, F), largest mesh force, N.
    mean_force : shape (n_mesh, F), mean mesh force, N.
    mesh_names : labels of the rows.
    method : sweep method.
    max_elastic_force : shape (n_mesh, F), largest elastic mesh force k (delta - e), N, or
        ``None`` (then ``max_force``).
    """

    frequencies: np.ndarray
    rms_force: np.ndarray
    rms_alternating: np.ndarray
    max_force: np.ndarray
    mean_force: np.ndarray
    mesh_names: tuple[str, ...]
    method: str
    max_elastic_force: np.ndarray | None = None

    @property
    def dynamic_factor(self) -> np.ndarray:
        """Largest elastic mesh force k (delta - e) over the mean mesh force, per mesh and
        frequency, shape (n_mesh, F), - (definition and reason:
        :meth:`pipeline.dynamics.results.Response.dynamic_factor`)."""
        top = self.max_force if self.max_elastic_force is None else self.max_elastic_force
        return top / self.mean_force

    def summary(self) -> dict:
        """Points, frequency range (Hz) and the main peaks (Hz) of every mesh."""
        return {"points": int(self.frequencies.size),
                "f_min_Hz": float(self.frequencies[0]), "f_max_Hz": float(self.frequencies[-1]),
                "peaks_Hz": {m: self.peaks(m) for m in self.mesh_names}}

    def columns(self) -> dict[str, np.ndarray]:
        """Mesh frequency (Hz), then per mesh: RMS, max, max elastic, mean and alternating
        RMS force (N) and dynamic factor (max elastic / mean force, -)."""
        cols = {"mesh frequency [Hz]": self.frequencies}
        for i, m in enumerate(self.mesh_names):
            cols[f"rms force {m} [N]"] = self.rms_force[i]
            cols[f"max force {m} [N]"] = self.max_force[i]
            if self.max_elastic_force is not None:
                cols[f"max elastic force {m} [N]"] = self.max_elastic_force[i]
            cols[f"mean force {m} [N]"] = self.mean_force[i]
            cols[f"alternating rms force {m} [N]"] = self.rms_alternating[i]
            cols[f"dynamic factor {m} [-]"] = self.dynamic_factor[i]
        return cols

    def peaks(self, mesh: str, count: int = 3) -> np.ndarray:
        """Frequencies (Hz) of the ``count`` largest local maxima of the RMS force of a mesh."""
        y = self.rms_force[self.mesh_names.index(mesh)]
        i = np.flatnonzero((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:])) + 1
        i = i[np.argsort(y[i])[::-1][:count]]
        return self.frequencies[np.sort(i)]


def _stats(resp: Response) -> np.ndarray:
    f = resp.mesh_force[:, resp.steady_slice()]
    mean = f.mean(axis=1)
    return np.stack(
        [
            np.sqrt((f**2).mean(axis=1)),
            np.sqrt(((f - mean[:, None]) ** 2).mean(axis=1)),
            f.max(axis=1),
            mean,
            resp.elastic_mesh_force()[:, resp.steady_slice()].max(axis=1),
        ]
    )


def hb_samples(n_harmonics: int) -> int:
    """Samples per period at which a harmonic-balance sweep evaluates the mesh forces."""
    return max(8 * n_harmonics, 256)


def _point_floquet(system: LinearPeriodicSystem, segments: int | None, f: float) -> np.ndarray:
    return _stats(steady_state(system.with_mesh_frequency(f), segments))


def mesh_force_sweep(
    system: LinearPeriodicSystem,
    frequencies: Sequence[float],
    method: str = "harmonic_balance",
    n_harmonics: int = 20,
    segments: int | None = None,
    executor: Executor | str | None = "local",
    max_periods: int = 2000,
    tol: float = 1e-6,
    show_progress: bool = False,
) -> SweepResult:
    """RMS dynamic mesh force against mesh frequency (Xu et al. 2020, Figs. 9-10).

    Parameters
    ----------
    system : the system at any reference speed; each point rescales its period and
        carrier speed (:meth:`LinearPeriodicSystem.with_mesh_frequency`).
    frequencies : shape (F,), mesh frequencies in Hz (> 0).
    method : "harmonic_balance", "floquet" or "time" (see module docstring).
    n_harmonics : H for the harmonic balance.
    segments : segments per period for "floquet" and "time".
    executor : see :func:`map_chunks` ("time" always runs in order in this process).
    max_periods, tol : "time" only: periods allowed per point and the steady-state tolerance.
    show_progress : progress bar on stderr.
    """
    check_choice("method", method, ("harmonic_balance", "floquet", "time"))
    f = np.asarray(frequencies, dtype=float)
    if f.ndim != 1 or f.size == 0 or np.any(f <= 0):
        raise InputError("frequencies must be a non-empty 1-D array of positive values in Hz")
    red = reduce_rigid_body_modes(system)
    if method == "harmonic_balance":
        check_int_range("n_harmonics", n_harmonics, 1, 5000)
        plan = plan_sweep(red, n_harmonics, hb_samples(n_harmonics))
        stats = map_chunks(partial(sweep_point, plan), f, executor, show_progress=show_progress)
    elif method == "floquet":
        stats = map_chunks(
            partial(_point_floquet, red, segments), f, executor, show_progress=show_progress
        )
    else:
        stats = []
        x = None
        with one_blas_thread():
            for fi in progress(f, "sweep", enabled=show_progress):
                s = red.with_mesh_frequency(fi)
                prop = build_propagator(s, segments)
                r = integrate(
                    s, max_periods, x0=x, tol=tol, stop_when_steady=True, propagator=prop
                )
                if r.steady_from >= r.time.size - 1:
                    raise InputError(
                        f"no steady state within max_periods = {max_periods} at "
                        f"{fi:.6g} Hz; raise max_periods or tol"
                    )
                x = r.end_state
                m = r.time.size
                seg = (m - 1) // max(1, round((r.time[-1]) / s.period))
                tail = Response(
                    r.time[-seg - 1 :],
                    r.q[-seg - 1 :],
                    r.qd[-seg - 1 :],
                    r.dte[:, -seg - 1 :],
                    r.mesh_force[:, -seg - 1 :],
                    r.dof_names,
                    r.mesh_names,
                    r.period,
                    elastic_force=r.elastic_mesh_force()[:, -seg - 1 :],
                )
                stats.append(_stats(tail))
    S = np.array(stats)  # (F, 5, n_mesh)
    return SweepResult(
        frequencies=f,
        rms_force=S[:, 0].T,
        rms_alternating=S[:, 1].T,
        max_force=S[:, 2].T,
        mean_force=S[:, 3].T,
        mesh_names=tuple(m.name for m in red.meshes),
        method=method,
        max_elastic_force=S[:, 4].T,
    )


def load_sharing_factor(response: Response, meshes: Sequence[str]) -> np.ndarray:
    """Dynamic load factor of Xu et al. (2020), eq. 24: ``N F_n(t) / sum_n F_n(t)``.

    Parameters
    ----------
    response : a response containing the meshes.
    meshes : the N mesh names sharing the load (e.g. the left sun-planet meshes).

    Returns
    -------
    shape (N, n_samples), dimensionless (1 = equal sharing).
    """
    F = np.array([response.mesh_force[response.mesh(m)] for m in meshes])
    return len(meshes) * F / F.sum(axis=0)
