"""What every shaft model gives: one interface for the beam and the 3D FE superelement.

Generalised vectors at a point are ``(u_x, u_y, u_z, theta_x, theta_y, theta_z)`` (m, rad)
and loads ``(F_x, F_y, F_z, M_x, M_y, M_z)`` (N, N m), in the shaft's frame
(:mod:`pipeline.shaft.layout`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from pipeline.shaft.layout import ShaftLayout


@dataclass(frozen=True)
class PointLoad:
    """A load at axial position ``z`` (m): ``force`` (3,) N and ``moment`` (3,) N m."""

    z: float
    force: tuple[float, float, float]
    moment: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class ShaftSolution:
    """A shaft's static solution.

    Attributes
    ----------
    z : (n,) axial positions of the deflection line, m.
    displacement : (n, 3) u_x, u_y, u_z there, m.
    rotation : (n, 3) theta_x, theta_y, theta_z there, rad.
    reactions : (n_bearings, 6) loads of the supports on the shaft (F, M; N, N m), in the
        layout's bearing order.
    torque_reaction : the moment about z the torque point puts on the shaft, N m (a load
        on the shaft like the reactions: it and the loads' moments about z sum to zero).
    """

    z: np.ndarray
    displacement: np.ndarray
    rotation: np.ndarray
    reactions: np.ndarray
    torque_reaction: float

    def reflected(self) -> ShaftSolution:
        """The solution mirrored in the shaft's ``y``-``z`` plane (``x -> -x``): ``u_x``,
        ``theta_y``, ``theta_z`` and the loads ``F_x``, ``M_y``, ``M_z`` negated (polar
        vectors flip their x part, axial vectors their y and z parts)."""
        u = np.array([-1.0, 1.0, 1.0])
        theta = np.array([1.0, -1.0, -1.0])
        return ShaftSolution(self.z, self.displacement * u, self.rotation * theta,
                             self.reactions * np.concatenate([u, theta]),
                             -self.torque_reaction)


class ShaftModel(Protocol):
    """A shaft model: ``"beam"`` (Timoshenko beam FE) or ``"fe3d"`` (Gmsh + scikit-fem,
    condensed to the seat and the bearings)."""

    layout: ShaftLayout

    def solve(self, loads: Sequence[PointLoad]) -> ShaftSolution:
        """The deflection line and the reactions under ``loads`` (on the seat)."""
        ...

    def flexibility(self, z: np.ndarray) -> np.ndarray:
        """(6m, 6m): generalised displacements at the seat points ``z`` (m,) per unit
        generalised load at each of them (symmetric)."""
        ...

    def seat_stiffness(self) -> np.ndarray:
        """(6, 6): the stiffness at the seat's centre with the bearings and the torque point
        as supports (bearings and shaft in series; the torsional stiffness to the torque
        point), N/m, N, N m/rad."""
        ...
