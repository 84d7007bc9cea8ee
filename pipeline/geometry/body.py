"""Mass and polar moment of inertia of a gear body: the exact toothed section, a bore or
ring rim, an optional web.

The transverse section is the whole-gear outline of :func:`pipeline.geometry.profile.
gear_outline` (involute, trochoidal fillet, root and tip circles), integrated exactly as
a polygon (area and polar moment about the axis by the shoelace formulas), times the
face width; the bore (external gears) is a disc removed, the rim of an internal gear is
the annulus out to ``rim_outer_radius`` minus the tooth outline. A web thinner than the
face removes the annulus between the hub and the rim on the missing width. A
herringbone gear adds its relief groove as a cylinder of the root radius less the bore
(a ring: the rim from its root circle out), the groove bottom not being part of the gear
description (the error is that of the groove depth).

The polygon has 60 involute points per flank; its area differs from the exact curve
by < 1e-5 relative (measured against 480 points).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError, check_range


def polygon_section(points: np.ndarray) -> tuple[float, float]:
    """Area (m^2) and polar moment about the origin (m^4) of a closed polygon, CCW positive.

    ``points`` has shape (n, 2); the last point connects back to the first.
    """
    x, y = points[:, 0], points[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cross = x * y1 - x1 * y
    area = 0.5 * cross.sum()
    j = (cross * (x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1)).sum() / 12.0
    return float(area), float(j)


def annulus_section(r_out: float, r_in: float) -> tuple[float, float]:
    """Area (m^2) and polar moment (m^4) of an annulus."""
    return math.pi * (r_out**2 - r_in**2), 0.5 * math.pi * (r_out**4 - r_in**4)


@dataclass(frozen=True)
class GearBody:
    """A gear as a rigid body of the dynamic models.

    Attributes
    ----------
    gear : the gear (its bore radius, or for a ring its outer rim radius, is part of it).
    web_width : axial width of a web thinner than the face, m, or ``None`` (solid body).
    rim_inner_radius : inner radius of the rim around the web, m (with ``web_width``).
    hub_radius : outer radius of the hub inside the web, m (with ``web_width``).
    mass : override of the derived mass, kg, or ``None``.
    inertia : override of the derived polar moment of inertia, kg m^2, or ``None``.
    """

    gear: GearSpec
    web_width: float | None = None
    rim_inner_radius: float | None = None
    hub_radius: float | None = None
    mass: float | None = None
    inertia: float | None = None

    def __post_init__(self) -> None:
        g = self.gear
        web = (self.web_width, self.rim_inner_radius, self.hub_radius)
        if any(v is not None for v in web):
            if any(v is None for v in web):
                raise InputError(f"{g.name}: a web needs web_width, rim_inner_radius and "
                                 "hub_radius together")
            if g.internal:
                raise InputError(f"{g.name}: a web is modelled for external gears only")
            check_range(f"{g.name}.web_width", self.web_width, 0.0, g.face_width, lo_open=True,
                        unit="m")
            check_range(f"{g.name}.rim_inner_radius", self.rim_inner_radius, g.bore_radius,
                        g.root_radius, lo_open=True, hi_open=True, unit="m")
            check_range(f"{g.name}.hub_radius", self.hub_radius, g.bore_radius,
                        self.rim_inner_radius, hi_open=True, unit="m")
        if self.mass is not None:
            check_range(f"{g.name}.mass", self.mass, 0.0, 1e7, lo_open=True, unit="kg")
        if self.inertia is not None:
            check_range(f"{g.name}.inertia", self.inertia, 0.0, 1e7, lo_open=True,
                        unit="kg m^2")

    @cached_property
    def section(self) -> tuple[float, float]:
        """Area (m^2) and polar moment (m^4) of the transverse section through the teeth."""
        from pipeline.geometry.profile import gear_outline

        g = self.gear
        a_teeth, j_teeth = polygon_section(gear_outline(g))
        if g.internal:
            a_rim, j_rim = annulus_section(g.bore_radius, 0.0)
            return a_rim - a_teeth, j_rim - j_teeth
        a_bore, j_bore = annulus_section(g.bore_radius, 0.0)
        return a_teeth - a_bore, j_teeth - j_bore

    @cached_property
    def derived_mass_properties(self) -> tuple[float, float]:
        """(mass kg, polar moment of inertia kg m^2) from the geometry, without overrides."""
        g = self.gear
        rho = g.material.density
        area, polar = self.section
        mass, inertia = rho * g.face_width * area, rho * g.face_width * polar
        if g.herringbone and g.groove_width > 0:
            a, j = (annulus_section(g.bore_radius, g.root_radius) if g.internal
                    else annulus_section(g.root_radius, g.bore_radius))
            mass += rho * g.groove_width * a
            inertia += rho * g.groove_width * j
        if self.web_width is not None:
            a, j = annulus_section(self.rim_inner_radius, self.hub_radius)
            missing = g.face_width - self.web_width
            mass -= rho * missing * a
            inertia -= rho * missing * j
        return mass, inertia

    @property
    def mass_(self) -> float:
        """Mass in kg (the override if given)."""
        return self.mass if self.mass is not None else self.derived_mass_properties[0]

    @property
    def inertia_(self) -> float:
        """Polar moment of inertia in kg m^2 (the override if given)."""
        return self.inertia if self.inertia is not None else self.derived_mass_properties[1]

    def summary(self) -> dict[str, float | bool]:
        """Mass properties with their units, and whether they were given or derived."""
        return {"mass_kg": self.mass_, "inertia_kgm2": self.inertia_,
                "mass_given": self.mass is not None, "inertia_given": self.inertia is not None}
