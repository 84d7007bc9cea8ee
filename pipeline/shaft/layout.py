"""A shaft as the gearbox file describes it: segments, the gear's seat, bearings, the torque.

Coordinates: the shaft's axis is ``z`` (m, from the shaft's first end), ``x`` and ``y``
transverse; the shaft's frame is the gear's (the pair's frame places it). Everything SI.

* Segments: contiguous ``[start, end]`` intervals from ``z = 0`` with an outer and an inner
  (bore) diameter each; the shaft's length is the last segment's end.
* The gear's seat: the gear's mid-face at ``gear_position``, over the gear's face width;
  ``hub = "rigid"`` (a gear body fixed on the shaft: the seat moves as a rigid body) or
  ``"integral"`` (a pinion cut on its shaft: the seat bends and twists as a shaft of the
  seat's own diameter, ISO 6336-1's f_sh picture).
* Bearings: at an axial position, a radial stiffness (N/m, ``inf`` rigid), a tilting
  stiffness (N m/rad, 0 for a ball or cylindrical roller bearing that lets the shaft tilt),
  and whether it locates the shaft axially (one bearing does).
* The torque: held against rotation about ``z`` at ``torque_position`` (a coupling or the
  other gear of a countershaft); the mesh's torque flows between the seat and there.

Refused in one line naming the key as written (``pinion.shaft.bearings[1].position_mm``):
gaps or overlaps between segments, a bore not inside its segment, a seat or a bearing or
the torque point outside the shaft, a bearing inside the seat, no radial support that holds
the shaft (two radial bearings, or one with a tilting stiffness), not exactly one axial
location.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from pipeline.geometry.gear import Material
from pipeline.validation import InputError, check_choice, check_range

HUBS = ("rigid", "integral")


@dataclass(frozen=True)
class ShaftSegment:
    """A cylinder of the shaft: ``start`` to ``end`` (m), ``outer_diameter`` and
    ``inner_diameter`` (m, 0 for solid)."""

    start: float
    end: float
    outer_diameter: float
    inner_diameter: float = 0.0

    @property
    def length(self) -> float:
        return self.end - self.start

    @property
    def area(self) -> float:
        """Cross-section area, m^2."""
        return math.pi / 4.0 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> float:
        """Second moment of area about a diameter, m^4 (the polar moment is twice it)."""
        return math.pi / 64.0 * (self.outer_diameter**4 - self.inner_diameter**4)


@dataclass(frozen=True)
class Bearing:
    """A support at ``position`` (m): radial stiffness (N/m; ``math.inf``: rigid), tilting
    stiffness (N m/rad; 0 lets the shaft tilt), ``axial``: it locates the shaft axially
    (rigidly)."""

    position: float
    radial_stiffness: float = math.inf
    tilting_stiffness: float = 0.0
    axial: bool = False

    def __post_init__(self) -> None:
        # math.inf is the rigid bearing (check_range refuses non-finite values)
        if self.radial_stiffness != math.inf:
            check_range("radial_stiffness", self.radial_stiffness, 0.0, math.inf, lo_open=True,
                        unit="N/m")
        if self.tilting_stiffness != math.inf:
            check_range("tilting_stiffness", self.tilting_stiffness, 0.0, math.inf,
                        unit="N m/rad")


@dataclass(frozen=True)
class ShaftLayout:
    """One shaft with its gear's seat, bearings and torque point (module docstring).

    Attributes
    ----------
    segments : contiguous from ``z = 0``.
    gear_position : the gear's mid-face, m.
    seat_width : the gear's face width (its seat), m.
    bearings : at least one; together they hold the shaft radially and locate it axially.
    torque_position : where the torque is held about ``z``, m.
    hub : "rigid" or "integral" (module docstring).
    material : the shaft's (E, nu, density).
    name : the key prefix of messages (``pinion.shaft``).
    """

    segments: tuple[ShaftSegment, ...]
    gear_position: float
    seat_width: float
    bearings: tuple[Bearing, ...]
    torque_position: float
    hub: str = "rigid"
    material: Material = field(default_factory=Material)
    name: str = field(default="shaft", compare=False)

    def __post_init__(self) -> None:
        n = self.name
        if not self.segments:
            raise InputError(f"{n}.segments: give at least one segment")
        end = 0.0
        for i, s in enumerate(self.segments):
            key = f"{n}.segments[{i}]"
            if not math.isclose(s.start, end, rel_tol=0.0, abs_tol=1e-9):
                what = "a gap" if s.start > end else "an overlap"
                raise InputError(f"{key}.start_mm = {s.start * 1e3:.6g} mm leaves {what} after "
                                 f"the segment before, which ends at {end * 1e3:.6g} mm")
            check_range(f"{key}.end_mm", s.end * 1e3, s.start * 1e3, 1e5, lo_open=True,
                        unit="mm", note="after its start_mm")
            check_range(f"{key}.outer_diameter_mm", s.outer_diameter * 1e3, 0.0, 1e4,
                        lo_open=True, unit="mm")
            check_range(f"{key}.inner_diameter_mm", s.inner_diameter * 1e3, 0.0,
                        s.outer_diameter * 1e3, hi_open=True, unit="mm",
                        note="below its outer_diameter_mm")
            end = s.end
        check_choice(f"{n}.hub", self.hub, HUBS)
        check_range(f"{n}.seat_width", self.seat_width * 1e3, 0.0, end * 1e3, lo_open=True,
                    unit="mm", note="the shaft's length")
        half = 0.5 * self.seat_width
        check_range(f"{n}.gear_position_mm", self.gear_position * 1e3, half * 1e3,
                    (end - half) * 1e3, unit="mm",
                    note="the gear's face on the shaft: half its face width from each end")
        check_range(f"{n}.torque_position_mm", self.torque_position * 1e3, 0.0, end * 1e3,
                    unit="mm", note="on the shaft")
        if not self.bearings:
            raise InputError(f"{n}.bearings: give at least one bearing")
        for i, b in enumerate(self.bearings):
            key = f"{n}.bearings[{i}].position_mm"
            check_range(key, b.position * 1e3, 0.0, end * 1e3, unit="mm", note="on the shaft")
            if abs(b.position - self.gear_position) < half:
                raise InputError(f"{key} = {b.position * 1e3:.6g} mm lies inside the gear's "
                                 f"seat ({(self.gear_position - half) * 1e3:.6g} to "
                                 f"{(self.gear_position + half) * 1e3:.6g} mm)")
        held = sum(1 for b in self.bearings) >= 2 or any(
            b.tilting_stiffness > 0.0 for b in self.bearings)
        if not held:
            raise InputError(f"{n}.bearings: one bearing without a tilting stiffness lets the "
                             "shaft tilt freely; give a second bearing or its "
                             "tilting_stiffness_Nm_per_rad")
        axial = [i for i, b in enumerate(self.bearings) if b.axial]
        if len(axial) != 1:
            raise InputError(f"{n}.bearings: exactly one bearing locates the shaft axially "
                             f"(axial = true); {len(axial)} do")

    @property
    def length(self) -> float:
        """The shaft's length, m."""
        return self.segments[-1].end

    @property
    def seat(self) -> tuple[float, float]:
        """The seat's ends (m)."""
        half = 0.5 * self.seat_width
        return self.gear_position - half, self.gear_position + half

    def segment_at(self, z: float) -> ShaftSegment:
        """The segment that holds ``z`` (the later one at a joint)."""
        for s in reversed(self.segments):
            if s.start <= z:
                return s
        return self.segments[0]
