"""Where the bodies of a dynamic model sit in the transverse plane, for drawing mode shapes.

A gear pair is two base circles touching the line of action at T1 and T2 (the model's
line of action is the x axis: the pinion's centre at the origin, T1 below it, the gear
below the line and T1 T2 further along +x, the direction the pinion's contact point
moves; the gear turns the other way, ``spin`` -1; an internal gear's centre lies above
the line, T2 a length T1 T2 behind T1, and it turns the pinion's way); a planetary set is the sun,
the planets on the carrier circle at their angles, the ring and the carrier (drawn as
the circle through the planet centres). Both halves of a herringbone member sit at the
same place (``side`` "L" or "R"). Bodies of other models (the split-torque
transmission) are placed on a square grid in the model's order, one unit circle each,
with their own axes: a schematic that still shows every body's motion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.dynamics.bodies import Body


@dataclass(frozen=True)
class BodyPlace:
    """One body in the drawing plane.

    Attributes
    ----------
    name : the body's name in the model (its coordinates are ``"<name>.<dof>"``).
    centre : (x, y) of the body's axis, m.
    radius : radius of the drawn circle (base circle, carrier circle), m.
    frame_angle : rad, direction of the body's own x axis (planets: radial).
    role : "sun", "planet", "ring", "carrier", "pinion", "gear", "drive" (a motor behind
        the pinion's shaft), "load" (a driven machine behind the gear's) or "body".
    side : "L" or "R" for a half of a herringbone member, else "".
    spin : +1 when the body's positive ``theta`` turns it counterclockwise in the
        drawing, -1 clockwise (a pair's gear).
    """

    name: str
    centre: tuple[float, float]
    radius: float
    frame_angle: float = 0.0
    role: str = "body"
    side: str = ""
    spin: int = 1


@dataclass(frozen=True)
class ModelLayout:
    """The places of all bodies of a model.

    Attributes
    ----------
    places : one per body, in the model's body order.
    schematic : True when the positions are a grid of unit circles, not the gears' layout.
    line_of_action : ((x, y), (x, y)) of T1 and T2 in m for a pair, else ``None``.
    """

    places: tuple[BodyPlace, ...]
    schematic: bool = False
    line_of_action: tuple[tuple[float, float], tuple[float, float]] | None = None

    def place(self, name: str) -> BodyPlace:
        """The place of body ``name``."""
        for p in self.places:
            if p.name == name:
                return p
        raise KeyError(name)


_CENTRAL = {"s": "sun", "r": "ring", "c": "carrier"}


def _planetary(model, bodies: tuple[Body, ...]) -> ModelLayout:
    radius = {"sun": model.base_radius_sun, "ring": model.base_radius_ring,
              "carrier": model.carrier_radius, "planet": model.base_radius_planet}
    angles = list(model.angles)
    herringbone = all(b.name[-1] in "LR" for b in bodies)
    places = []
    for b in bodies:
        base, side = (b.name[:-1], b.name[-1]) if herringbone else (b.name, "")
        if base in _CENTRAL:
            role = _CENTRAL[base]
            places.append(BodyPlace(b.name, (0.0, 0.0), radius[role], 0.0, role, side))
            continue
        if not (base[:1] == "p" and base[1:].isdigit() and int(base[1:]) <= len(angles)):
            extra = 1.6 * radius["ring"] + 2.2 * radius["planet"] * len(places)
            places.append(BodyPlace(b.name, (extra, 0.0), radius["planet"], b.frame_angle,
                                    "drive" if b.name == "drive" else "body", side))
            continue
        psi = angles[int(base[1:]) - 1]
        a = model.carrier_radius
        places.append(BodyPlace(b.name, (a * math.cos(psi), a * math.sin(psi)),
                                radius["planet"], b.frame_angle, "planet", side))
    return ModelLayout(tuple(places))


def _pair(model) -> ModelLayout:
    rp, rg = model.base_radius_pinion, model.base_radius_gear
    t1t2 = getattr(model, "t1t2", None) or 0.0
    if getattr(model, "gear_internal", False):
        # the ring's tangent point T2 lies behind T1 (the pitch point is on +x of both)
        gear = BodyPlace("gear", (-t1t2, rg - rp), rg, 0.0, "gear", spin=1)
        line = ((0.0, -rp), (-t1t2, -rp))
    else:
        gear = BodyPlace("gear", (t1t2, -(rp + rg)), rg, 0.0, "gear", spin=-1)
        line = ((0.0, -rp), (t1t2, -rp))
    places = [BodyPlace("pinion", (0.0, 0.0), rp, 0.0, "pinion"), gear]
    # a motor or driven machine behind a gear's shaft: drawn beside its gear, away from the
    # mesh, turning with it
    if getattr(model, "drive", None) is not None:
        places.append(BodyPlace("drive", (-2.2 * rp, 0.0), 0.6 * rp, 0.0, "drive"))
    if getattr(model, "load", None) is not None:
        places.append(BodyPlace("load", (gear.centre[0] + 2.2 * rg, gear.centre[1]), 0.6 * rg,
                                0.0, "load", spin=gear.spin))
    return ModelLayout(tuple(places), line_of_action=line if t1t2 else None)


def _grid(bodies: tuple[Body, ...]) -> ModelLayout:
    cols = math.ceil(math.sqrt(len(bodies)))
    return ModelLayout(tuple(BodyPlace(b.name, (3.0 * (i % cols), -3.0 * (i // cols)), 1.0,
                                       b.frame_angle) for i, b in enumerate(bodies)),
                       schematic=True)


def model_layout(model) -> ModelLayout:
    """The drawing layout of a dynamic model (module docstring).

    Parameters
    ----------
    model : a model with ``assembly()`` (pair, planetary, herringbone planetary,
        split torque, ...).
    """
    bodies = tuple(model.assembly().bodies)
    names = {b.name for b in bodies}
    if hasattr(model, "carrier_radius") and hasattr(model, "angles"):
        return _planetary(model, bodies)
    if hasattr(model, "base_radius_pinion") and names <= {"pinion", "gear", "drive", "load"}:
        return _pair(model)
    return _grid(bodies)
