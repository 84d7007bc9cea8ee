"""Contact beyond the path of contact: a tooth's tip corner against its mate's flank.

Inside the path of contact ``[s_start, s_end]`` both flanks are involutes touching on the
transverse line of action. Outside it one of them has ended: past ``s_end`` the pinion's
flank stops at its tip circle, before ``s_start`` the gear's does. The tooth pair can
still touch there, at the *tip corner* of the tooth whose flank has ended, against the
mate's flank a little off the line of action. This module gives the rigid geometry of
that contact in the transverse plane, exactly, for external and internal (ring) pairs.

Frame. ``T1`` (the pinion's base tangent point) at the origin, the line of action along
``+x``, the pinion centre ``O1 = (0, -r_b1)``; the gear's base tangent point ``T2 =
(+-T1T2, 0)`` with its centre at ``(T1T2, +r_b2)`` (external) or ``(-T1T2, -r_b2)``
(ring, same side as the pinion). Tooth pair ``k`` is described by the roll coordinate
``s`` at which its two (extended) involutes cross the line of action; the pinion pushes
its flank towards ``+x``.

Involute families. The involutes of one base circle with one orientation, turned about
its centre, are parallel curves: two of them are ``r_b dphi`` apart along their common
normals, which are the tangents to the base circle. So every point ``W`` lies on exactly
one involute of a family, identified by where that involute crosses the line of action
(:func:`crossing`), and the normal distance from ``W`` to the flank that crosses at
``s`` is the difference of the two crossings. The rigid gap of a tip corner to the mate's
flank is thus closed form: pinion corner against the gear flank ``s - x_2(C)``, gear
corner against the pinion flank ``x_1(D) - s`` (positive: apart).

Rigid approach. Turning the pinion so that its flank advances by ``delta`` along the line
of action (the transmission error coordinate) moves every point of every pinion involute
by ``delta`` along its normal, so the gap of a gear corner against a pinion flank closes
by ``delta``. A pinion corner moves on its tip circle instead, and its gap to the gear
flank closes by ``a delta`` with ``a = h_1 / r_b1``, ``h_1`` the distance from ``O1`` to
the contact normal (the gear's base tangent through the corner), ``a < 1`` off the line
of action. With the gear turning and the pinion held the roles swap (``a = h_2 / r_b2``
for a gear corner). ``a`` is also the ratio of the torque the contact force exerts on the
turning gear to the torque a force on the line of action would: the same factor enters
the approach and the equilibrium (virtual work).

Local contact of a corner. A sharp corner pressed on a flank has no finite local approach
in plane strain: the contact width goes to zero with the corner's radius, and the
half-plane's logarithmic term with it. Real corners are blunted (an edge break, the
grinding or deburring), and an FE model blunts a sharp one at its element size. The loaded
contact gives a sharp corner the local radius ``rho_c = 0.05 m_n`` (0.15 mm for m_n 3 mm)
in Hertz's line contact against the mate's involute (:func:`curvature_radii_at`); its
rigid gap stays the sharp corner's. How much it matters (demo pair against the CalculiX
reference, which blunts the corner at its 0.1 mm elements, at the positions where a corner
carries 2-33 % of the load, 100 and 340 N m): the loaded TE lies within +0.58 / +0.28 /
0.16 / 0.16 / -0.82 % of the reference's for rho_c 0.05 / 0.1 / 0.15 / 0.2 / 1 mm (module
docstring of ``workflows/reference/calculix_spur_contact.py``).

Rounded tips (``GearSpec.tip_rounding`` rho > 0, external gears). The tip is rounded by
design: the involute ends where the rounding touches it
(:attr:`~pipeline.geometry.gear.GearSpec.active_tip_radius`), which ends the path of
contact (demo pair, 0.3 mm on both: eps_alpha 1.755 -> 1.663), the profile carries the arc
(:func:`pipeline.geometry.profile.tip_rounding_arc`, so the FE meshes do), and beyond the
path the rounding's circle touches the mate: :func:`tip_contact` gives its gap in closed
form (the rounding's centre on a parallel involute; a faster-growing gap than the sharp
corner's: 0.86 against 0.10 um at 0.1 mm of roll past the sharp path's end for 0.15 mm,
14.1 against 10.0 um at 1 mm), and the local contact is Hertz of the rounding against the
mate's involute (:func:`corner_radius`), which the loaded contact corrects where the
contact patch spans the tangency (:func:`tangency_offset` locates the contact point
relative to it).

Lengths in m, angles in rad. The tip corner is the end of the involute on the tip circle
(an unrounded, unchamfered tip).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.pair import GearPair


@dataclass(frozen=True)
class BaseCircle:
    """A base circle and the orientation of its flanks in the frame of the module docstring.

    Attributes
    ----------
    centre : (x, y) of the centre, m.
    radius : base radius r_b, m.
    tangent_x : x of its tangent point on the line of action, m.
    below : True when the centre lies below the line of action (pinion, ring): its
        involute of crossing ``x`` has roll length ``x - tangent_x`` at the line;
        False (external gear): roll length ``tangent_x - x``.
    """

    centre: tuple[float, float]
    radius: float
    tangent_x: float
    below: bool


def base_circles(pair: GearPair) -> tuple[BaseCircle, BaseCircle]:
    """The pinion's and the gear's base circles in the module's frame."""
    g, rb1, rb2 = pair.t1t2, pair.pinion.base_radius, pair.gear.base_radius
    pinion = BaseCircle((0.0, -rb1), rb1, 0.0, True)
    if pair.gear.internal:
        return pinion, BaseCircle((-g, -rb2), rb2, -g, True)
    return pinion, BaseCircle((g, rb2), rb2, g, False)


def _point(base: BaseCircle, phi: np.ndarray, roll: np.ndarray) -> np.ndarray:
    """Points (2, n) at roll length ``roll`` along the base tangent at angle ``phi``
    (``phi = 0``: the tangent point on the line of action)."""
    cx, cy = base.centre
    rb = base.radius
    if base.below:
        return np.array([cx + rb * np.sin(phi) + roll * np.cos(phi),
                         cy + rb * np.cos(phi) - roll * np.sin(phi)])
    return np.array([cx + rb * np.sin(phi) - roll * np.cos(phi),
                     cy - rb * np.cos(phi) - roll * np.sin(phi)])


def _normal(base: BaseCircle, phi: np.ndarray) -> np.ndarray:
    """Unit normals (2, n) of the involutes at base-tangent angle ``phi``: the direction of
    growing roll length (``+x`` on the line of action for a circle below it)."""
    if base.below:
        return np.array([np.cos(phi), -np.sin(phi)])
    return np.array([-np.cos(phi), -np.sin(phi)])


def _tangent_angle(base: BaseCircle, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(phi, roll length) of the base tangent through the points ``w`` (2, n) that touches
    the base circle on the side of the line of action's tangent point."""
    dx, dy = w[0] - base.centre[0], w[1] - base.centre[1]
    rb = base.radius
    roll = np.sqrt(np.maximum(dx * dx + dy * dy - rb * rb, 0.0))
    if base.below:  # w - O is (roll, rb) turned clockwise by phi
        phi = np.arctan2(rb, roll) - np.arctan2(dy, dx)
    else:  # w - O is (-roll, -rb) turned anticlockwise by phi
        phi = np.arctan2(dy, dx) - np.arctan2(-rb, -roll)
    return (phi + math.pi) % (2.0 * math.pi) - math.pi, roll


def crossing(base: BaseCircle, w: ArrayLike) -> np.ndarray:
    """x where the involute of ``base`` through each point of ``w`` (2, n), m, crosses the
    line of action (module docstring: the involutes of one family are parallel, so the
    normal distance between two of them is the difference of their crossings)."""
    w = np.asarray(w, dtype=float).reshape(2, -1)
    phi, roll = _tangent_angle(base, w)
    phase = roll + base.radius * phi if base.below else roll - base.radius * phi
    return base.tangent_x + phase if base.below else base.tangent_x - phase


def _corner(base: BaseCircle, s: np.ndarray, tip_radius: float) -> np.ndarray:
    """Tip corners (2, n): the end on the tip circle of the involute of ``base`` crossing
    the line of action at ``s``."""
    rb = base.radius
    tip_roll = math.sqrt(tip_radius**2 - rb**2)
    if base.below:  # roll = (s - tangent_x) - rb phi
        phi = ((s - base.tangent_x) - tip_roll) / rb
    else:  # roll = (tangent_x - s) + rb phi
        phi = (tip_roll - (base.tangent_x - s)) / rb
    return _point(base, phi, np.full_like(s, tip_roll))


@dataclass(frozen=True)
class TipContact:
    """Rigid geometry of tip-corner contact of tooth pairs at roll coordinates ``s``
    (shape (n,) each; module docstring).

    Attributes
    ----------
    s : roll coordinates where the pairs' involutes cross the line of action, m.
    corner : "pinion" (``s > s_end``: the pinion's tip), "gear" (``s < s_start``) or
        "" (inside the path: an ordinary line-of-action contact).
    gap : rigid gap between the corner and the mate's flank along the contact normal, m
        (0 inside the path).
    point : (2, n) contact point on the mate's flank, m (on the line of action inside).
    normal : (2, n) unit contact normal, pointing from the pinion towards the gear.
    radius_pinion, radius_gear : radii of the contact point on each gear, m (the corner
        is at its tip radius).
    lever_pinion, lever_gear : ``h_i / r_bi``: distance from each centre to the contact
        normal over its base radius (1 on the line of action).
    """

    s: np.ndarray
    corner: np.ndarray
    gap: np.ndarray
    point: np.ndarray
    normal: np.ndarray
    radius_pinion: np.ndarray
    radius_gear: np.ndarray
    lever_pinion: np.ndarray
    lever_gear: np.ndarray

    def lever(self, driver: str) -> np.ndarray:
        """``lever_pinion`` when the pinion turns (drives), else ``lever_gear``: the factor
        ``a`` of the module docstring."""
        return self.lever_pinion if driver == "pinion" else self.lever_gear


def _lever(centre: tuple[float, float], rb: float, point: np.ndarray,
           normal: np.ndarray) -> np.ndarray:
    """Distance from ``centre`` to the lines through ``point`` along ``normal``, over ``rb``."""
    dx, dy = point[0] - centre[0], point[1] - centre[1]
    return np.abs(dx * normal[1] - dy * normal[0]) / rb


def tip_contact(pair: GearPair, s: ArrayLike) -> TipContact:
    """Tip contact geometry of tooth pairs crossing the line of action at ``s`` (m, any
    shape, flattened): the rigid gap, the contact point on the mate's flank and the normal,
    the radii on both gears and the lever factors (module docstring). Inside the path the
    contact is the ordinary one on the line of action (gap 0, levers 1).

    A tip rounded by design (``GearSpec.tip_rounding`` rho, the path ending where it
    touches the involute, :attr:`GearSpec.active_tip_radius`) touches with its circle,
    centre ``Q``: the point on the circle ``r_a - rho`` of the tooth's own involute family
    crossing ``rho`` inside its flank (the parallel involute). The gap is the closed form
    of a sharp corner with ``Q`` for the corner, less ``rho``; the mate's normal through
    ``Q`` is the contact normal, the rounding touches ``rho`` from ``Q`` along it (that
    radius is the corner gear's contact radius) and ``point`` lies a gap further, on the
    mate's flank. A sharp corner is ``rho = 0``."""
    s = np.asarray(s, dtype=float).reshape(-1)
    b1, b2 = base_circles(pair)
    rho1, rho2 = pair.pinion.tip_rounding, pair.gear.tip_rounding
    after, before = s > pair.s_end, s < pair.s_start
    corner = np.where(after, "pinion", np.where(before, "gear", ""))
    point = np.array([s, np.zeros_like(s)])
    normal = np.array([np.ones_like(s), np.zeros_like(s)])
    gap = np.zeros_like(s)
    touch1 = touch2 = None
    if after.any():  # the pinion's corner or rounding against the gear's flank
        q = _corner(b1, s[after] - rho1, pair.pinion.tip_radius_ - rho1)
        gap[after] = s[after] - crossing(b2, q) - rho1
        phi, _ = _tangent_angle(b2, q)
        n2 = _normal(b2, phi)  # growing roll of the gear family
        # from the pinion towards the gear: along -x for the external gear's family
        # (its roll grows towards T1), +x for the ring's
        n = n2 if b2.below else -n2
        touch1 = q + rho1 * n
        point[:, after] = touch1 + gap[after] * n
        normal[:, after] = n
    if before.any():  # the gear's corner or rounding against the pinion's flank
        q = _corner(b2, s[before] + rho2, pair.gear.tip_radius_ - rho2)
        gap[before] = crossing(b1, q) - s[before] - rho2
        phi, _ = _tangent_angle(b1, q)
        n = _normal(b1, phi)  # the pinion family's normal, +x on the line
        touch2 = q - rho2 * n
        point[:, before] = touch2 - gap[before] * n
        normal[:, before] = n
    r1 = np.hypot(point[0] - b1.centre[0], point[1] - b1.centre[1])
    r2 = np.hypot(point[0] - b2.centre[0], point[1] - b2.centre[1])
    if touch1 is not None:  # the corner itself lies on the tip circle
        r1[after] = (pair.pinion.tip_radius_ if rho1 == 0.0 else
                     np.hypot(touch1[0] - b1.centre[0], touch1[1] - b1.centre[1]))
    if touch2 is not None:
        r2[before] = (pair.gear.tip_radius_ if rho2 == 0.0 else
                      np.hypot(touch2[0] - b2.centre[0], touch2[1] - b2.centre[1]))
    return TipContact(s, corner, gap, point, normal, r1, r2,
                      _lever(b1.centre, b1.radius, point, normal),
                      _lever(b2.centre, b2.radius, point, normal))


def contact_radii_at(pair: GearPair, s: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Radii (R1, R2) of the contact point on each gear for tooth pairs crossing the line of
    action at ``s`` (m, any shape; the result has its shape): on the line of action inside
    the path (:meth:`GearPair.contact_radii`), at the tip corner and on the mate's flank
    beyond it (:func:`tip_contact`)."""
    s = np.asarray(s, dtype=float)
    tc = tip_contact(pair, s)
    return tc.radius_pinion.reshape(s.shape), tc.radius_gear.reshape(s.shape)


CORNER_RADIUS_MODULES = 0.05
"""Radius of curvature of a sharp tip corner in its local contact, over m_n (module
docstring)."""


def corner_radius(gear) -> float:
    """Radius of curvature a tip corner of ``gear`` touches with, m: its tip rounding, or
    for a sharp corner :data:`CORNER_RADIUS_MODULES` times its module (module docstring)."""
    return gear.tip_rounding if gear.tip_rounding > 0.0 else CORNER_RADIUS_MODULES * gear.module


def curvature_radii_at(pair: GearPair, s: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Radii of curvature (rho1, rho2), m, of the two surfaces where tooth pairs crossing the
    line of action at ``s`` (m, any shape) touch: the involutes' on the path
    (:meth:`GearPair.curvature_radii`); beyond it the tip corner's local radius
    (:data:`CORNER_RADIUS_MODULES` times its module) against the mate's involute at the
    contact point, ``sqrt(R^2 - r_b^2)``. ``rho2`` is negative where the surface is concave
    (a ring's flank); a ring's tip corner is convex."""
    s = np.asarray(s, dtype=float)
    rho1, rho2 = pair.curvature_radii(s)
    after, before = s > pair.s_end, s < pair.s_start
    if not (after.any() or before.any()):
        return rho1, rho2
    r1, r2 = contact_radii_at(pair, s)
    flank1 = np.sqrt(np.maximum(r1**2 - pair.pinion.base_radius**2, 0.0))
    flank2 = np.sqrt(np.maximum(r2**2 - pair.gear.base_radius**2, 0.0))
    if pair.gear.internal:
        flank2 = -flank2
    rho1 = np.where(after, corner_radius(pair.pinion), np.where(before, flank1, rho1))
    rho2 = np.where(before, corner_radius(pair.gear), np.where(after, flank2, rho2))
    return rho1, rho2


def tangency_offset(gear, radius: ArrayLike) -> np.ndarray:
    """Arc distance (m) of contact points at ``radius`` (m) on ``gear``'s flank from the
    tangency of its tip rounding with the involute: on the rounding (``radius`` above the
    active tip radius) ``rho (gamma_T - gamma(r))`` >= 0, the arc along the rounding's
    circle (centre on the circle ``r_a - rho``, ``cos gamma = (r^2 - r_c^2 - rho^2) /
    (2 r_c rho)``, gamma the angle at the centre between the point and the gear's radial
    line); on the involute the difference of the involute arc coordinates ``(r^2 -
    r_b^2) / (2 r_b)``, < 0. NaN for a gear without a rounding."""
    r = np.asarray(radius, dtype=float)
    rho = gear.tip_rounding
    if rho == 0.0:
        return np.full(r.shape, np.nan)
    rb, rt, rc = gear.base_radius, gear.active_tip_radius, gear.tip_radius_ - rho

    def gamma(x):
        return np.arccos(np.clip((x * x - rc * rc - rho * rho) / (2.0 * rc * rho), -1.0, 1.0))

    on_arc = rho * (gamma(rt) - gamma(np.minimum(r, gear.tip_radius_)))
    on_involute = (r * r - rt * rt) / (2.0 * rb)
    return np.where(r > rt, on_arc, on_involute)


def tip_zone(pair: GearPair, max_gap: float) -> tuple[float, float]:
    """Roll coordinates ``(s_lo, s_hi)``, m, between which a tooth pair's rigid tip-corner
    gap is at most ``max_gap`` (m): the path of contact widened at each end as far as a
    corner can still be reached under load. The gap grows monotonically (about with the
    square of the roll past the path), so each end is found by bisection to 1e-9 m; it is
    capped where the contact point leaves the mate's involute (its form circle, where the
    fillet begins) and at one base pitch (the one more tooth pair
    :meth:`GearPair.pair_indices` holds at each end)."""
    pitch = pair.base_pitch

    def reach(sign: int, start: float) -> float:
        def touches(d: float) -> bool:
            tc = tip_contact(pair, [start + sign * d])
            return bool(np.isfinite(tc.gap[0]) and tc.gap[0] <= max_gap
                        and _on_flank(pair, tc))

        lo, hi = 0.0, 1e-4 * pitch
        while touches(hi):  # doubling until past the end, or the cap reached
            if hi == pitch:
                return pitch
            lo, hi = hi, min(2.0 * hi, pitch)
        while hi - lo > 1e-9:
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if touches(mid) else (lo, mid)
        return lo

    return pair.s_start - reach(-1, pair.s_start), pair.s_end + reach(1, pair.s_end)


def _on_flank(pair: GearPair, tc: TipContact) -> bool:
    """The contact point of a one-point :class:`TipContact` lies on the mate's involute:
    outside an external mate's form circle, inside a ring's."""
    from pipeline.geometry.profile import tooth_profile

    if tc.corner[0] == "pinion":
        form = tooth_profile(pair.gear).form_radius
        r = tc.radius_gear[0]
        return bool(r <= form if pair.gear.internal else r >= form)
    return bool(tc.radius_pinion[0] >= tooth_profile(pair.pinion).form_radius)
