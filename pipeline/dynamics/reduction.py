"""Removal of rigid-body modes before a forced-response solve.

A geared train whose torques balance has a free rigid rotation (every mesh
deflection stays zero when all gears turn together). Its position is arbitrary,
so ``I - monodromy`` and the harmonic-balance matrix at order 0 are singular. We
solve in the M-orthogonal complement of those modes: ``q = T p`` with
``T^T M r = 0`` for each rigid mode r. Responses are then measured from the
nominal rigid rotation, which is what the DTE and mesh forces need.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.linalg as sla

from pipeline.dynamics.system import ForcingTerm, LinearPeriodicSystem, MeshOutput, ParametricTerm
from pipeline.validation import InputError


def rigid_body_modes(system: LinearPeriodicSystem, rtol: float = 1e-9) -> np.ndarray:
    """Coordinate patterns r with K_elastic(t) r = 0 for all t, shape (n, n_rigid).

    The centripetal term ``-Omega^2 K_Omega`` is left out on purpose: in a rigid turn of
    the whole set the centrifugal forces stay radial and are balanced by the bearing
    preload (a geometric stiffness the linear model does not carry), so the rigid
    rotation is still free. Keeping the term would turn the rigid rotation into a
    spurious divergent mode growing at a rate proportional to the carrier speed.
    """
    K = system.K
    scale = max(
        np.abs(K).max(),
        max(
            (np.abs(t.signal.values).max() * np.abs(t.v).max() ** 2 for t in system.terms),
            default=0.0,
        ),
        1e-300,
    )
    rows = [K / scale] + [
        np.abs(t.signal.values).max() * np.abs(t.v).max() * t.v[None, :] / scale
        for t in system.terms
    ]
    A = np.vstack(rows)
    return sla.null_space(A, rcond=rtol)


def reduce_rigid_body_modes(system: LinearPeriodicSystem) -> LinearPeriodicSystem:
    """The same system without its rigid-body modes (returned unchanged if it has none).

    Raises
    ------
    InputError
        When the constant load drives a rigid-body mode (unbalanced torques): the
        gearbox would accelerate and has no steady state.
    """
    R = rigid_body_modes(system)
    if R.shape[1] == 0:
        return system
    fr = R.T @ system.f0
    fscale = max(np.linalg.norm(system.f0), 1e-300)
    if np.linalg.norm(fr) > 1e-6 * fscale:  # null space of stiff, badly scaled K: ~1e-8
        raise InputError(
            "the loads are unbalanced: net generalized force "
            f"{np.linalg.norm(fr):.6g} on a rigid-body mode (check that the output torque "
            "equals the input torque times the ratio)"
        )
    T = sla.null_space(R.T @ system.M)

    def red(A: np.ndarray) -> np.ndarray:
        return T.T @ A @ T

    return replace(
        system,
        basis=system.basis @ T,
        M=red(system.M),
        C=red(system.C),
        K=red(system.K),
        G=red(system.G),
        K_omega=red(system.K_omega),
        f0=T.T @ system.f0,
        terms=tuple(
            ParametricTerm(t.name, t.signal, T.T @ t.u, T.T @ t.v, t.phase, t.order)
            for t in system.terms
        ),
        forcing=tuple(
            ForcingTerm(f.signal, T.T @ f.vector, f.phase, f.order, f.derivative)
            for f in system.forcing
        ),
        meshes=tuple(
            MeshOutput(m.name, T.T @ m.v, m.term, m.damping, m.transmission_error)
            for m in system.meshes
        ),
    )
