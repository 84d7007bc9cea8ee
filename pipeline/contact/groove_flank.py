"""The relief groove of a herringbone sun as the flanks of its two helical halves see it.

The groove FE (:mod:`pipeline.fem.groove`) gives the 12 x 12 stiffness between the half
centres O_L and O_R on ``[ux, uy, uz, rx, ry, rz]`` (z the gear axis). A sun-planet
mesh moves the flanks of a half along the line of action through two of them only:

* the rotation rz about the axis (a twist d_theta moves the flank by ``r_b d_theta``
  along the transverse line of action), and
* the axial translation uz (a helicoid shifted by d_z is the same flank turned by
  ``d_z tan(beta_b) / r_b``, so it moves by ``tan(beta_b) d_z``, opposite on the
  two hands).

Kept: rz and uz of both nodes. Dropped by static condensation (free, zero generalised
force): ux, uy, rx, ry. With N >= 3 equally spaced planets carrying equal loads the
radial and tangential mesh forces on each half cancel, and so do the moments of the
axial forces about x and y, so these DOFs carry no load and condensing them is exact;
the condensed 4 x 4 then holds the rigid axial and rotational motions of the sun as its
null space, and fixing the node where the torque leaves leaves the 2 x 2 compliance
of the other node relative to it (:attr:`GrooveFlankCoupling.compliance`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.validation import InputError, check_positive

_KEEP = [2, 5, 8, 11]  # uz_L, rz_L, uz_R, rz_R
_FREE = [0, 1, 3, 4, 6, 7, 9, 10]  # ux, uy, rx, ry of both nodes


@dataclass(frozen=True, eq=False)
class GrooveFlankCoupling:
    """Relative compliance of the sun halves on the DOFs the meshes move (SI).

    Attributes
    ----------
    compliance : (2, 2) motion of O_L relative to O_R, ``[twist rz (rad), axial uz (m)]``,
        per generalised force on O_L (equal and opposite on O_R) ``[torque (N m),
        axial force (N)]``: rad/(N m), rad/N, m/(N m), m/N. Zero for a rigid groove.
    torsional_stiffness : k_t = 1 / compliance[0, 0], N m/rad (inf for a rigid groove):
        torque over twist with the axial force zero.
    """

    compliance: np.ndarray

    def __post_init__(self) -> None:
        c = np.array(self.compliance, dtype=float)
        if c.shape != (2, 2) or not np.all(np.isfinite(c)):
            raise InputError(f"groove compliance must be a finite (2, 2) array; got {c.shape}")
        c = 0.5 * (c + c.T)
        if np.linalg.eigvalsh(c)[0] < -1e-12 * max(abs(c).max(), 1e-300):
            raise InputError("groove compliance is not positive semidefinite")
        c.setflags(write=False)
        object.__setattr__(self, "compliance", c)

    @property
    def torsional_stiffness(self) -> float:
        """k_t, N m/rad (inf for a rigid groove)."""
        c = float(self.compliance[0, 0])
        return math.inf if c == 0.0 else 1.0 / c

    @classmethod
    def rigid(cls) -> GrooveFlankCoupling:
        """Both halves one rigid body."""
        return cls(np.zeros((2, 2)))

    @classmethod
    def torsion(cls, torsional_stiffness: float) -> GrooveFlankCoupling:
        """A torsion spring of ``torsional_stiffness`` (N m/rad), axially rigid (the beam of
        Xu et al. 2020, eq. 1: ``K_j / l``)."""
        check_positive("groove torsional stiffness", torsional_stiffness, "N m/rad")
        return cls(np.diag([1.0 / torsional_stiffness, 0.0]))

    @classmethod
    def from_matrix(cls, K12: np.ndarray) -> GrooveFlankCoupling:
        """Condense the FE 12 x 12 stiffness (module docstring).

        Parameters
        ----------
        K12 : (12, 12) stiffness between O_L and O_R on [ux, uy, uz, rx, ry, rz] of each
            (N/m, N/rad, N m/rad), e.g. ``GrooveStiffness.coupling_matrix``.
        """
        K = np.asarray(K12, dtype=float)
        if K.shape != (12, 12):
            raise InputError(f"groove coupling matrix has shape {K.shape}; need (12, 12)")
        Kff = K[np.ix_(_FREE, _FREE)]
        # the free block holds the rigid lateral motions and tilts: least squares
        X = np.linalg.lstsq(Kff, K[np.ix_(_FREE, _KEEP)], rcond=1e-12)[0]
        Kc = K[np.ix_(_KEEP, _KEEP)] - K[np.ix_(_KEEP, _FREE)] @ X
        Kc = 0.5 * (Kc + Kc.T)
        # O_R fixed: the (uz_L, rz_L) block, reordered to (rz, uz)
        K_L = Kc[np.ix_([1, 0], [1, 0])]
        return cls(np.linalg.inv(K_L))
