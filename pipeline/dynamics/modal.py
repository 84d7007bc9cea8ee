"""Modal analysis: natural frequencies, mode shapes and mode types.

The eigenproblem uses the mean stiffness (periodic mesh stiffness replaced by its
mean), without the non-conservative friction terms. With a carrier speed and
gyroscopic terms the state-space eigenproblem is solved instead and the
frequencies are ``|Im(lambda)| / 2 pi``.

Mode types of planetary sets (Lin and Parker 1999): in a *rotational* mode the
central members (sun, ring, carrier) only rotate, in a *translational* mode they
only translate (multiplicity 2), in a *planet* mode they do not move at all
(multiplicity N - 3).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import scipy.linalg as sla

from pipeline.dynamics.results import ModalResult
from pipeline.dynamics.system import LinearPeriodicSystem


def conservative_mean_stiffness(system: LinearPeriodicSystem) -> np.ndarray:
    """K - Omega^2 K_Omega + sum of mean symmetric (u = v) terms, shape (n, n)."""
    K = system.constant_stiffness().copy()
    for t in system.terms:
        if np.array_equal(t.u, t.v):
            K += t.signal.mean() * np.outer(t.u, t.v)
    return 0.5 * (K + K.T)


def _multiplicity(f: np.ndarray, rtol: float) -> np.ndarray:
    scale = max(f.max(initial=0.0), 1e-300)
    close = np.abs(f[:, None] - f[None, :]) <= rtol * np.maximum(np.abs(f[:, None]), 1e-9 * scale)
    return close.sum(axis=1)


def modal_analysis(
    system: LinearPeriodicSystem, gyroscopic: bool = False, rtol: float = 1e-6
) -> ModalResult:
    """Natural frequencies and mass-normalised mode shapes.

    Parameters
    ----------
    system : assembled system.
    gyroscopic : include ``Omega G`` (state-space problem); otherwise the undamped,
        non-gyroscopic problem ``K phi = w^2 M phi``.
    rtol : relative tolerance used to count repeated frequencies.

    Returns
    -------
    :class:`ModalResult` with ``kinds`` empty (see :func:`classify_modes`).
    """
    K = conservative_mean_stiffness(system)
    M = system.M
    if gyroscopic and system.carrier_speed != 0.0:
        n = system.n
        Minv = np.linalg.inv(M)
        A = np.block(
            [[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ (system.carrier_speed * system.G)]]
        )
        lam, vec = np.linalg.eig(A)
        keep = lam.imag >= -1e-9 * np.abs(lam).max()
        lam, vec = lam[keep], vec[:n, keep]
        order = np.argsort(np.abs(lam.imag))[:n]
        f = np.abs(lam[order].imag) / (2 * np.pi)
        shapes = vec[:, order]
        shapes = shapes / np.sqrt(np.abs(np.einsum("im,ij,jm->m", shapes.conj(), M, shapes)))
    else:
        w2, shapes = sla.eigh(K, M)
        w2 = np.where(w2 < 1e-9 * max(w2.max(), 1e-300), 0.0, w2)
        f = np.sqrt(w2) / (2 * np.pi)
    full = system.basis @ shapes
    weights = np.sqrt(np.abs(np.einsum("ij,jk,ik->i", system.basis, M, system.basis)))
    return ModalResult(
        frequencies=f,
        shapes=full,
        dof_names=system.dof_names,
        kinds=tuple("" for _ in f),
        multiplicity=_multiplicity(f, rtol),
        weights=weights,
    )


def classify_modes(
    result: ModalResult,
    central_translations: Sequence[str],
    central_rotations: Sequence[str],
    tol: float = 1e-6,
) -> ModalResult:
    """Label planetary modes "rigid", "rotational", "translational", "planet" or "mixed".

    Parameters
    ----------
    result : modal result.
    central_translations : names (``"sun.x"`` ...) of the central members' translations.
    central_rotations : names of their rotations.
    tol : a group "does not move" when its largest entry is below ``tol`` times the
        largest entry of the (mass-normalised) mode.
    """
    idx = {n: i for i, n in enumerate(result.dof_names)}
    it = [idx[n] for n in central_translations]
    ir = [idx[n] for n in central_rotations]
    kinds = []
    for k in range(result.frequencies.size):
        phi = np.abs(result.shapes[:, k])
        if result.frequencies[k] == 0.0:
            kinds.append("rigid")
            continue
        # Compare displacement-like amplitudes: rotations scaled by a typical radius are
        # not needed because "zero" is tested against round-off, not a physical scale.
        top = phi.max()
        t_still = phi[it].max(initial=0.0) < tol * top
        r_still = phi[ir].max(initial=0.0) < tol * top
        if t_still and r_still:
            kinds.append("planet")
        elif t_still:
            kinds.append("rotational")
        elif r_still:
            kinds.append("translational")
        else:
            kinds.append("mixed")
    return replace(result, kinds=tuple(kinds))
