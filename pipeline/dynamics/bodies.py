"""Rigid bodies with named degrees of freedom.

A body carries up to four degrees of freedom (DOF): translations ``x``, ``y``
(in the transverse plane), ``z`` (axial) in m, and the rotation ``theta`` about
its own axis in rad. A coordinate is addressed as ``(body_name, dof)``; the
assembled system names it ``"body.dof"``.

Frames: translations are measured in the body's own frame, turned by
``frame_angle`` (rad, counter-clockwise) from the assembly frame. Planets use
this for radial/tangential coordinates. When ``rotating_frame`` is true the
assembly frame of this body rotates at the carrier speed Omega, which adds the
gyroscopic terms ``2 m Omega`` and the centripetal softening ``m Omega^2`` on
x, y (Xu et al. 2020, eq. 22; Lin and Parker 1999).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from pipeline.validation import InputError, check_range

DOF_KINDS = ("x", "y", "z", "theta")
TRANSLATIONS = ("x", "y", "z")

Coordinate = tuple[str, str]
"""A generalized coordinate: (body name, dof kind)."""


@dataclass(frozen=True)
class Body:
    """A rigid body of the lumped-parameter model.

    Attributes
    ----------
    name : unique label, no dots.
    mass : kg; needed (> 0) when the body has a translational DOF.
    inertia : polar moment of inertia about the spin axis, kg m^2; needed (> 0) with ``theta``.
    dofs : subset of ("x", "y", "z", "theta"), in that order of preference.
    frame_angle : rad, orientation of the body's x axis in the assembly frame.
    rotating_frame : translations are measured in a frame spinning at the carrier speed.
    """

    name: str
    mass: float = 0.0
    inertia: float = 0.0
    dofs: tuple[str, ...] = ("x", "y", "theta")
    frame_angle: float = 0.0
    rotating_frame: bool = False

    def __post_init__(self) -> None:
        if not self.name or "." in self.name:
            raise InputError(f"body name {self.name!r} must be non-empty and contain no '.'")
        dofs = tuple(self.dofs)
        object.__setattr__(self, "dofs", dofs)
        if not dofs:
            raise InputError(f"body {self.name!r} has no degrees of freedom")
        for d in dofs:
            if d not in DOF_KINDS:
                raise InputError(f"body {self.name!r}: dof {d!r} is not one of {DOF_KINDS}")
        if len(set(dofs)) != len(dofs):
            raise InputError(f"body {self.name!r}: repeated dof in {dofs}")
        if any(d in TRANSLATIONS for d in dofs):
            check_range(f"{self.name}.mass", self.mass, 0.0, 1e7, lo_open=True, unit="kg")
        if "theta" in dofs:
            check_range(
                f"{self.name}.inertia", self.inertia, 0.0, 1e7, lo_open=True, unit="kg m^2"
            )
        check_range(
            f"{self.name}.frame_angle", self.frame_angle, -4 * math.pi, 4 * math.pi, unit="rad"
        )

    def mass_of(self, dof: str) -> float:
        """Mass (kg) or inertia (kg m^2) on one DOF."""
        return self.inertia if dof == "theta" else self.mass

    def in_plane(self, direction_angle: float, scale: float = 1.0) -> dict[Coordinate, float]:
        """Projection of the body's transverse displacement on a unit direction.

        Parameters
        ----------
        direction_angle : rad, direction in the assembly frame.
        scale : factor on the projection (e.g. cos(beta_b) for a helical mesh).

        Returns
        -------
        ``{(name, "x"): c_x, (name, "y"): c_y}`` such that the displacement along the
        direction is ``c_x x + c_y y`` (entries for missing DOFs are dropped).
        """
        a = direction_angle - self.frame_angle
        out = {}
        if "x" in self.dofs:
            out[(self.name, "x")] = scale * math.cos(a)
        if "y" in self.dofs:
            out[(self.name, "y")] = scale * math.sin(a)
        return out


def add_measures(*measures: Mapping[Coordinate, float]) -> dict[Coordinate, float]:
    """Sum sparse linear measures ``{coordinate: coefficient}``."""
    out: dict[Coordinate, float] = {}
    for m in measures:
        for k, v in m.items():
            out[k] = out.get(k, 0.0) + float(v)
    return out
