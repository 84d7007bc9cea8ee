"""Case of the rigid tip-corner geometry beyond the path of contact
(:mod:`pipeline.geometry.tip_contact`) against the textbook involute.

The pipeline's closed form (parallel involutes: the normal distance of a point to a flank
is the difference of their crossings of the line of action) is compared with an
independent construction: each tooth's flank built from the textbook involute
``r_b (cos t + t sin t, sin t - t cos t)`` turned into place, the corner taken as its end on
the tip circle, the gap as the shortest distance from the corner to the mate's flank (the
nearest of 20 001 polyline vertices, then a bounded scalar minimisation on the curve), and
the lever factor as the rate at which a small rigid turn (1e-7 rad) of the turning gear
closes that gap. Pairs: z 50/50 (m 3 mm, 20 deg) and planet 24 / ring 72 (m 2 mm).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Outcome, Quantity

PAST = (1e-4, 2e-3)
"""Roll past the path of contact (m) where the gaps are compared."""


def _spur(z: int, name: str, module: float = 3e-3, bore: float = 0.021,
          internal: bool = False) -> GearSpec:
    return GearSpec(teeth=z, name=name, module=module, pressure_angle=math.radians(20.0),
                    face_width=0.02, bore_radius=bore, internal=internal,
                    material=Material(youngs_modulus=2.0e11, poisson_ratio=0.3))


def tip_contact_pairs() -> dict[str, GearPair]:
    """The external z 50/50 pair and the planet 24 / ring 72 pair."""
    return {"external z 50/50": GearPair(_spur(50, "pinion"), _spur(50, "gear")),
            "ring 24/72": GearPair(_spur(24, "planet", 2e-3, 0.01),
                                   _spur(72, "ring", 2e-3, 0.09, internal=True))}


def _turn(angle: float, xy: np.ndarray) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * xy[0] - s * xy[1], s * xy[0] + c * xy[1]])


def flank_centre(pair: GearPair, who: str) -> np.ndarray:
    """Centre (x, y) in m of ``who``'s gear ("pinion" or "gear") in the frame of
    :mod:`pipeline.geometry.tip_contact`: T1 at the origin, the line of action along +x."""
    if who == "pinion":
        return np.array([0.0, -pair.pinion.base_radius])
    if pair.gear.internal:
        return np.array([-pair.t1t2, -pair.gear.base_radius])
    return np.array([pair.t1t2, pair.gear.base_radius])


def involute_flank(pair: GearPair, who: str, s: float, t: np.ndarray, theta: float = 0.0
                   ) -> np.ndarray:
    """Points (2, n) in m of ``who``'s textbook involute r_b (cos t + t sin t, sin t - t
    cos t) (Litvin & Fuentes 2004, Gear Geometry and Applied Theory) crossing the
    line of action at ``s`` (m), at involute parameters ``t`` (rad), the gear turned by
    ``theta`` (rad, anticlockwise) about its centre (:func:`flank_centre`'s frame)."""
    g = pair.t1t2
    if who == "pinion":
        rb = pair.pinion.base_radius
        angle = math.pi / 2 - s / rb
    elif pair.gear.internal:
        rb = pair.gear.base_radius
        angle = math.pi / 2 - (s + g) / rb
    else:
        rb = pair.gear.base_radius
        angle = -math.pi / 2 - (g - s) / rb
    inv = rb * np.array([np.cos(t) + t * np.sin(t), np.sin(t) - t * np.cos(t)])
    return flank_centre(pair, who)[:, None] + _turn(angle + theta, inv)


def tip_corner(pair: GearPair, who: str, s: float, theta: float = 0.0) -> np.ndarray:
    """The tip corner (x, y) in m of ``who``'s flank crossing the line of action at ``s``:
    the end of its :func:`involute_flank` on the tip circle, the gear turned by ``theta``."""
    gear = pair.pinion if who == "pinion" else pair.gear
    rb = gear.base_radius
    t_tip = math.sqrt(gear.tip_radius_**2 - rb**2) / rb
    return involute_flank(pair, who, s, np.array([t_tip]), theta)[:, 0]


def distance_to_flank(point: np.ndarray, pair: GearPair, who: str, s: float) -> float:
    """Shortest distance (m) from ``point`` (m) to ``who``'s :func:`involute_flank` crossing
    at ``s``: the nearest of 20 001 vertices of the flank up to 1.2 tip radii, then a bounded
    scalar minimisation on the curve around it (parameter tolerance 1e-14)."""
    from scipy.optimize import minimize_scalar

    gear = pair.pinion if who == "pinion" else pair.gear
    rb = gear.base_radius
    t = np.linspace(0.0, math.sqrt((1.2 * gear.tip_radius_)**2 - rb**2) / rb, 20_001)

    def dist(tt):
        xy = involute_flank(pair, who, s, np.atleast_1d(tt))
        return np.hypot(xy[0] - point[0], xy[1] - point[1])

    i = int(np.argmin(dist(t)))
    lo, hi = t[max(i - 1, 0)], t[min(i + 1, t.size - 1)]
    best = minimize_scalar(lambda tt: float(dist(tt)[0]), bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-14})
    return float(best.fun)


def case_tip_corner_gap_and_lever(context: Context) -> Outcome:
    """Gap of the pinion's corner past the end of the path and of the gear's before its
    start, and their lever factors, against the textbook involute construction."""
    from pipeline.geometry.tip_contact import tip_contact

    gap_why = "the minimiser's tolerance on the distance (measured 6e-14 m)"
    lever_why = "first-order finite difference of a 1e-7 rad rigid turn"
    q = []
    for name, pair in tip_contact_pairs().items():
        for past in PAST:
            for s, corner, mate in ((pair.s_end + past, "pinion", "gear"),
                                    (pair.s_start - past, "gear", "pinion")):
                tc = tip_contact(pair, [s])
                ref = distance_to_flank(tip_corner(pair, corner, s), pair, mate, s)
                q.append(Quantity(f"gap of the {corner} corner {past * 1e3:g} mm off the path, "
                                  f"{name}", "m", ref, float(tc.gap[0]), "absolute", 1e-12,
                                  gap_why, UM))
        d = 1e-7
        after, before = pair.s_end + 1e-3, pair.s_start - 1e-3
        tc = tip_contact(pair, [after, before])
        rb1, rb2 = pair.pinion.base_radius, pair.gear.base_radius
        closed = tc.gap[0] - distance_to_flank(tip_corner(pair, "pinion", after, theta=-d),
                                               pair, "gear", after)
        q.append(Quantity(f"lever of the pinion corner 1 mm past the end, {name}", "-",
                          closed / (rb1 * d), float(tc.lever_pinion[0]), "relative", 1e-5,
                          lever_why))
        gear_turn = d if pair.gear.internal else -d
        closed = tc.gap[1] - distance_to_flank(tip_corner(pair, "gear", before,
                                                          theta=gear_turn), pair, "pinion",
                                               before)
        q.append(Quantity(f"lever of the gear corner 1 mm before the start, {name}", "-",
                          closed / (rb2 * d), float(tc.lever_gear[1]), "relative", 1e-5,
                          lever_why))
    inputs = (("pairs", "spur z 50/50, m 3 mm, 20 deg; planet 24 / ring 72, m 2 mm, 20 deg"),
              ("positions", "roll " + ", ".join(f"{p * 1e3:g}" for p in PAST)
               + " mm past either end of the path of contact; levers at 1 mm"),
              ("construction", "textbook involute, 20 001 vertices, bounded minimisation"))
    return Outcome("the textbook involute r_b (cos t + t sin t, sin t - t cos t) (Litvin & "
                   "Fuentes 2004), gap and rigid-turn rate by construction", inputs,
                   tuple(q))
