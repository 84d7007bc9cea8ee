"""Coaxial bodies (shafts, gear segments, grooves) described as frozen data.

A body is a stack of segments along the z axis (the gear axis), each a solid of
revolution of one outer radius or a helical toothed ring, all with the same
central bore. Meshing (:mod:`pipeline.fem.groove.mesh`) and the coupling between
segments (:mod:`pipeline.fem.groove.coupling`) only read these objects.
Lengths in m.
"""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError, check_positive, check_range


@dataclass(frozen=True)
class HelicalTeeth:
    """Helical teeth cut on a segment.

    Attributes
    ----------
    gear : the gear whose transverse profile is used (external).
    sign : +1 if the profile turns by +z tan(beta) / r per unit z (right hand),
        -1 for the opposite hand.
    z_reference : z (m) at which tooth 0 is centred on the +x axis.
    """

    gear: GearSpec
    sign: int
    z_reference: float = 0.0

    def __post_init__(self) -> None:
        if self.sign not in (1, -1):
            raise InputError(f"helical teeth sign = {self.sign!r} must be +1 or -1")


@dataclass(frozen=True)
class Segment:
    """One axial piece of a coaxial body.

    Attributes
    ----------
    name : label used for tags ("left_gear", "groove", ...).
    z0, z1 : axial extent in m, z0 < z1.
    outer_radius : outer radius in m (the root radius for a toothed segment).
    teeth : helical teeth on the outside, or None for a plain cylinder.
    """

    name: str
    z0: float
    z1: float
    outer_radius: float
    teeth: HelicalTeeth | None = None

    def __post_init__(self) -> None:
        check_positive(f"{self.name}.length", self.z1 - self.z0, unit="m")
        check_positive(f"{self.name}.outer_radius", self.outer_radius, unit="m")

    @property
    def length(self) -> float:
        return self.z1 - self.z0


@dataclass(frozen=True)
class CoaxialBody:
    """Segments stacked without gaps along z, sharing one bore.

    Attributes
    ----------
    segments : in increasing z; each starts where the previous ends.
    bore_radius : radius of the central bore in m (0 for solid).
    """

    segments: tuple[Segment, ...]
    bore_radius: float = 0.0

    def __post_init__(self) -> None:
        if not self.segments:
            raise InputError("a coaxial body needs at least one segment")
        names = [s.name for s in self.segments]
        if len(set(names)) != len(names):
            raise InputError(f"segment names must be unique, got {names}")
        for a, b in zip(self.segments[:-1], self.segments[1:], strict=True):
            if abs(a.z1 - b.z0) > 1e-12:
                raise InputError(f"segment {b.name!r} starts at z = {b.z0:.6g} m, not at the "
                                 f"end of {a.name!r} (z = {a.z1:.6g} m)")
        for s in self.segments:
            check_range(f"{s.name}.outer_radius", s.outer_radius, self.bore_radius, 1e3,
                        lo_open=True, unit="m (must exceed the bore radius)")

    @property
    def z_start(self) -> float:
        return self.segments[0].z0

    @property
    def z_end(self) -> float:
        return self.segments[-1].z1

    def segment(self, name: str) -> Segment:
        for s in self.segments:
            if s.name == name:
                return s
        raise KeyError(name)
