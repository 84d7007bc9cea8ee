"""Modal analysis: natural frequencies, mode shapes and mode types.

The eigenproblem uses the mean stiffness (periodic mesh stiffness replaced by its
mean), without the non-conservative friction terms. With a carrier speed and
gyroscopic terms the state-space eigenproblem is solved instead: the elastic
frequencies are ``Im(lambda) / 2 pi``, and the rigid-body modes (a double zero
eigenvalue each there) are those of the undamped problem, counted once.

Mode types (:func:`classify_modes`) are read from where a mode keeps its kinetic
energy (:meth:`ModalResult.energy_shares`: in-plane translation ``x, y``, rotation
``theta``, axial translation ``z``, each named coordinate weighted by its own body's
mass or inertia), in this order:

* *rigid*: 0 Hz.
* *axial*: the axial share is at least :data:`AXIAL_SHARE` = 1/2.
* otherwise the in-plane coordinates (``x, y, theta``) are typed as Lin and Parker
  (1999) do: in a *rotational* mode the central members (sun, ring, carrier) only
  rotate, in a *translational* mode they only translate (multiplicity 2), in a
  *planet* mode they do not move at all (multiplicity N - 3); *mixed* when they both
  translate and rotate (planets not equally spaced, for instance). "Does not move" is
  tested against round-off (``tol``), since these types are exact properties of
  cyclically symmetric sets.

Models without central members (a gear pair, the split-torque transmission) take
the majority rule alone (:func:`classify_by_energy`): *rigid* at 0 Hz, *axial* as
above, otherwise *rotational* when the rotation share is at least the in-plane
translation share, else *translational*. For a gear pair the rotational modes are
the mesh modes (the torsional pair's single elastic mode, the "mesh mode" at
``sqrt(k (r_1^2 / I_1 + r_2^2 / I_2)) / 2 pi``, is purely rotational); the
translational ones hold most of their energy in the gears' translation on their
bearings, and those without any rotation (both gears moving alike along the line of
action, or either one across it) do not deform the mesh at all. Measured on the default spur
pair (z 50/50, bearings 1e8 N/m): one rigid mode, the coupled mesh-bearing modes at
776 Hz (rotation 41 %: translational) and 3950 Hz (rotation 59 %: rotational), and a
triple bearing mode at 998 Hz with no rotation.

Why 1/2: the kind then names the motion that holds most of the mode's energy, the
shares printed beside it in ``modes.csv`` and the mode-shape panels, so a label never
contradicts its shares. For a herringbone set whose halves mirror each other (equal
left and right meshes; halves, and the sun halves' translations, tied;
:mod:`pipeline.dynamics.models.herringbone_planetary`) the rule also gives an exact
count. The mirror plane between the halves splits the modes: the symmetric ones move
the halves alike in the plane and not axially (axial share 0); the antisymmetric ones
move the members axially (one ``z`` per member, N + 3) and twist the sun halves against
each other on the groove, coupled through the helix. Mass-normalised modes make
``sqrt(M) Phi`` orthogonal, so over the antisymmetric modes the axial shares add up to
N + 3 and the twist shares to 1: at most one of these N + 4 modes can hold less than
half its energy axially, and N + 3 modes are "axial" (N + 4 if the twist spread over
several modes, none holding half of it). With spur halves (no helix) the axial
coordinates decouple and these N + 3 modes are purely axial. Measured: in
``herringbone_planetary_lumped.toml`` and ``wind_turbine_herringbone_planetary.toml`` every
axial share is above 0.999 or below 0.001, so the labels do not hang on the threshold;
where the halves are joined by softer springs (the sun groove of 5e9 N/m in the
hand-built wind-turbine model, ``half_coupling``) the halves also move axially against
each other in symmetric modes, shares in between occur (0.92 and 0.08 there) and the
majority decides.
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


def _gyroscopic_modes(system: LinearPeriodicSystem, K: np.ndarray, rigid: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies (Hz) and mass-normalised complex shapes of ``M q'' + Omega G q' + K q = 0``.

    A rigid-body mode is a double zero eigenvalue of the state-space matrix (a Jordan
    block), which round-off splits into two small eigenvalues, real or imaginary; so
    the r rigid-body modes are taken from the undamped problem (``rigid``, shape (n, r))
    and the elastic ones are the n - r eigenvalues with the largest positive imaginary
    part, one of each conjugate pair.
    """
    n, r = system.n, rigid.shape[1]
    M = system.M
    Minv = np.linalg.inv(M)
    A = np.block(
        [[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ (system.carrier_speed * system.G)]]
    )
    lam, vec = np.linalg.eig(A)
    top = np.argsort(lam.imag)[::-1][: n - r]
    order = top[np.argsort(lam[top].imag)]
    shapes = vec[:n, order]
    shapes = shapes / np.sqrt(np.abs(np.einsum("im,ij,jm->m", shapes.conj(), M, shapes)))
    f = np.concatenate([np.zeros(r), lam[order].imag / (2 * np.pi)])
    return f, np.hstack([rigid.astype(complex), shapes])


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
    w2, undamped = sla.eigh(K, M)
    w2 = np.where(w2 < 1e-9 * max(w2.max(), 1e-300), 0.0, w2)
    f = np.sqrt(w2) / (2 * np.pi)
    shapes = undamped
    if gyroscopic and system.carrier_speed != 0.0:
        f, shapes = _gyroscopic_modes(system, K, undamped[:, w2 == 0.0])
    full = system.basis @ shapes
    weights = np.sqrt(system.coordinate_mass)
    return ModalResult(
        frequencies=f,
        shapes=full,
        dof_names=system.dof_names,
        kinds=tuple("" for _ in f),
        multiplicity=_multiplicity(f, rtol),
        weights=weights,
    )


AXIAL_SHARE = 0.5
"""A mode whose axial kinetic-energy share is at least this is "axial" (module docstring)."""


def classify_by_energy(result: ModalResult) -> ModalResult:
    """Label modes "rigid", "axial", "rotational" or "translational" by their energy shares.

    The rule for models without central members (module docstring): "rigid" at 0 Hz,
    "axial" when the axial share is at least :data:`AXIAL_SHARE`, else "rotational" when
    the rotation share is at least the in-plane translation share, else "translational".

    Parameters
    ----------
    result : modal result of :func:`modal_analysis` (its ``weights`` give the shares).
    """
    shares = result.energy_shares()
    kinds = []
    for k in range(result.frequencies.size):
        if result.frequencies[k] == 0.0:
            kinds.append("rigid")
        elif shares["axial"][k] >= AXIAL_SHARE:
            kinds.append("axial")
        elif shares["rotation"][k] >= shares["in-plane"][k]:
            kinds.append("rotational")
        else:
            kinds.append("translational")
    return replace(result, kinds=tuple(kinds))


def classify_modes(
    result: ModalResult,
    central_translations: Sequence[str],
    central_rotations: Sequence[str],
    tol: float = 1e-6,
) -> ModalResult:
    """Label modes "rigid", "axial", "rotational", "translational", "planet" or "mixed".

    The rule and its threshold :data:`AXIAL_SHARE` are in the module docstring.

    Parameters
    ----------
    result : modal result of :func:`modal_analysis` (its ``weights`` give the shares).
    central_translations : names (``"sun.x"`` ...) of the central members' in-plane
        translations.
    central_rotations : names of their rotations.
    tol : a group "does not move" when its largest entry is below ``tol`` times the
        largest in-plane entry (``x``, ``y``, ``theta``) of the mass-normalised mode.
    """
    idx = {n: i for i, n in enumerate(result.dof_names)}
    it = [idx[n] for n in central_translations]
    ir = [idx[n] for n in central_rotations]
    plane = [i for i, n in enumerate(result.dof_names) if not n.endswith(".z")]
    axial = result.energy_shares()["axial"]
    kinds = []
    for k in range(result.frequencies.size):
        if result.frequencies[k] == 0.0:
            kinds.append("rigid")
            continue
        if axial[k] >= AXIAL_SHARE:
            kinds.append("axial")
            continue
        phi = np.abs(result.shapes[:, k])
        # Compare displacement-like amplitudes: rotations scaled by a typical radius are
        # not needed because "zero" is tested against round-off, not a physical scale.
        top = phi[plane].max()
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
