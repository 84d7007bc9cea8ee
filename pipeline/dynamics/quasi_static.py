"""The zero-speed limit of a linear time-periodic system: static equilibrium at every phase.

As the mesh frequency falls far below the natural frequencies, inertia, damping,
gyroscopic and centripetal forces vanish, and so does the damping force of a
transmission error (``c e'``). What remains at each system phase ``tau`` is the static
problem ``K(tau) q = F(tau)`` with the stiffness and the forces of that phase (the mesh
stiffness k(tau), the forcing ``k(tau) e(tau)`` of a transmission error, the constant
loads), solved in the complement of the rigid-body modes
(:func:`pipeline.dynamics.reduction.reduce_rigid_body_modes`). It is what the steady
response of :mod:`pipeline.dynamics.harmonic_balance` and :mod:`pipeline.dynamics.integrate`
tends to at vanishing speed, and the state a static analysis (the loaded tooth contact)
should reproduce.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from pipeline.dynamics.reduction import reduce_rigid_body_modes
from pipeline.dynamics.results import Response
from pipeline.dynamics.system import LinearPeriodicSystem


def quasi_static_response(system: LinearPeriodicSystem,
                          tau: np.ndarray | None = None) -> Response:
    """The zero-speed limit: static equilibrium ``K(tau) q = F(tau)`` at each phase ``tau``
    (module docstring). Between the samples of a signal the forcing interpolates the
    product k e, not k times e, so compare with sampled data at the sample phases.

    Parameters
    ----------
    system : any system.
    tau : system phases (-), shape (N,); default the finest sample grid of the periodic
        coefficients, ``k / n`` for k = 0..n-1.

    Returns
    -------
    :class:`Response` with ``method = "quasi-static"``, zero velocities, mesh forces
    ``k (delta - e)`` (N) and DTE ``delta`` (m) at the phases ``tau`` (time ``tau T``).
    """
    red = replace(reduce_rigid_body_modes(system), carrier_speed=0.0)
    if tau is None:
        n = max([t.signal.values.size * t.order for t in red.terms] + [1])
        tau = np.arange(n) / n
    tau = np.atleast_1d(np.asarray(tau, dtype=float))
    static = [f for f in red.forcing if not f.derivative]
    q = np.empty((tau.size, red.n))
    for i, t in enumerate(tau):
        f = red.f0 + sum((g.vector * float(np.squeeze(g.signal(g.order * t - g.phase)))
                          for g in static), np.zeros(red.n))
        q[i] = np.linalg.solve(red.stiffness(float(t)), f)
    V = np.array([ms.v for ms in red.meshes]).reshape(len(red.meshes), red.n)
    dte = V @ q.T
    force = np.zeros_like(dte)
    for i, ms in enumerate(red.meshes):
        term = red.terms[ms.term]
        x = term.order * tau - term.phase
        e = 0.0 if ms.transmission_error is None else ms.transmission_error(x)
        force[i] = term.signal(x) * (dte[i] - e)
    return Response(time=tau * red.period, q=red.expand(q), qd=np.zeros((tau.size,
                    red.basis.shape[0])), dte=dte, mesh_force=force, dof_names=red.dof_names,
                    mesh_names=tuple(ms.name for ms in red.meshes), period=red.period,
                    method="quasi-static")
