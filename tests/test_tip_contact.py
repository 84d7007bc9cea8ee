"""Rigid geometry of tip-corner contact beyond the path of contact
(:mod:`pipeline.geometry.tip_contact`).

The closed form (parallel involutes: the normal distance of a point to a flank is the
difference of their crossings of the line of action) is checked against an independent
construction: each tooth's flank built from the textbook involute
``r_b (cos t + t sin t, sin t - t cos t)`` turned into place, the corner taken as its end
on the tip circle, and the gap as the shortest distance from the corner to a dense
polyline of the mate's flank; the lever factor against a small rigid rotation of the
turning gear (the construction lives in :mod:`pipeline.verification.cases_tip_contact`).
External pair: the assembly-error paper's z 50/50 (m 3 mm, 20 deg); ring:
planet 24 / ring 72, m 2 mm.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur

from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import tip_contact
from pipeline.verification.cases_tip_contact import (
    distance_to_flank,
    flank_centre,
    involute_flank,
    tip_corner,
)

EXTERNAL = GearPair(spur(50, "pinion"), spur(50, "gear"))
RING = GearPair(spur(24, "planet", module=2e-3, bore_radius=0.01),
                spur(72, "ring", module=2e-3, internal=True, bore_radius=0.09))


@pytest.mark.parametrize("pair", [EXTERNAL, RING], ids=["external", "ring"])
@pytest.mark.parametrize("past", [2e-5, 1e-4, 5e-4, 2e-3])
def test_gap_is_the_distance_from_the_corner_to_the_mate_flank(pair, past):
    """Past the end of the path the pinion's corner, before its start the gear's, is the
    closed-form gap from the mate's flank (to 1e-12 m; measured 6e-14 m); the contact
    point lies on that flank to 2e-10 m (the minimiser's parameter tolerance)."""
    for s, corner, mate in ((pair.s_end + past, "pinion", "gear"),
                            (pair.s_start - past, "gear", "pinion")):
        tc = tip_contact(pair, [s])
        assert tc.corner[0] == corner
        c = tip_corner(pair, corner, s)
        assert tc.gap[0] == pytest.approx(distance_to_flank(c, pair, mate, s), abs=1e-12)
        assert tc.gap[0] > 0.0
        # the contact point lies on the mate's flank, at the gap from the corner
        assert np.hypot(*(tc.point[:, 0] - c)) == pytest.approx(tc.gap[0], abs=1e-12)
        assert distance_to_flank(tc.point[:, 0], pair, mate, s) < 2e-10


def test_gap_grows_with_the_square_of_the_roll_past_the_path():
    """The corner leaves its mate tangentially: the gap is quadratic in the roll past the
    end (gap / roll^2 changes by 3.3e-4 from 1 um to 10 um of roll: the cubic term), 0.097
    um at 0.1 mm on the demo pair (about 0.1 um, as an independent FE contact model of that
    pair shows)."""
    p = EXTERNAL
    d = np.array([1e-6, 1e-5, 1e-4])
    g = tip_contact(p, p.s_end + d).gap
    q = g / d**2
    assert q[1] / q[0] - 1.0 == pytest.approx(0.1 * (q[2] / q[1] - 1.0), rel=0.02)
    assert abs(q[1] / q[0] - 1.0) < 1e-3
    assert g[2] == pytest.approx(0.0969e-6, rel=2e-3)
    inside = tip_contact(p, [p.s_start, 0.5 * (p.s_start + p.s_end), p.s_end])
    assert np.all(inside.gap == 0.0) and np.all(inside.corner == "")
    assert np.all(inside.lever_pinion == pytest.approx(1.0, abs=1e-12))


@pytest.mark.parametrize("pair", [EXTERNAL, RING], ids=["external", "ring"])
def test_lever_is_the_rate_at_which_a_rigid_turn_closes_the_gap(pair):
    """Turning the pinion by d theta (its flank advancing r_b1 d theta along the line of
    action) closes a pinion corner's gap by lever_pinion r_b1 d theta and a gear corner's
    by r_b1 d theta; the gear turning closes them by r_b2 d theta and lever_gear r_b2 d
    theta (finite differences of the independent construction, to 1e-5)."""
    rb1, rb2 = pair.pinion.base_radius, pair.gear.base_radius
    d = 1e-7  # rad
    # the gear turned so that its flank moves towards -x at the line of action
    gear_turn = d if pair.gear.internal else -d
    after, before = pair.s_end + 1e-3, pair.s_start - 1e-3
    tc = tip_contact(pair, [after, before])
    gap_c, gap_d = tc.gap
    c, dd = tip_corner(pair, "pinion", after), tip_corner(pair, "gear", before)
    # pinion turned clockwise (its flank towards +x): the corner moves, the flank advances
    turned = tip_corner(pair, "pinion", after, theta=-d)
    closed = gap_c - distance_to_flank(turned, pair, "gear", after)
    assert closed / (rb1 * d) == pytest.approx(tc.lever_pinion[0], rel=1e-5)
    closed = gap_d - distance_to_flank(dd, pair, "pinion", before + rb1 * d)
    assert closed / (rb1 * d) == pytest.approx(1.0, rel=1e-5)
    # gear turned: its flank advances (crossing moves to -x), its corner moves
    closed = gap_c - distance_to_flank(c, pair, "gear", after - rb2 * d)
    assert closed / (rb2 * d) == pytest.approx(1.0, rel=1e-5)
    turned = tip_corner(pair, "gear", before, theta=gear_turn)
    closed = gap_d - distance_to_flank(turned, pair, "pinion", before)
    assert closed / (rb2 * d) == pytest.approx(tc.lever_gear[1], rel=1e-5)
    assert 0.9 < tc.lever_pinion[0] < 1.0 and 0.9 < tc.lever_gear[1] < 1.0
    far = tip_contact(pair, [pair.s_end + 1e-3, pair.s_start - 1e-3])
    assert far.lever_pinion[0] < 1.0 and far.lever_pinion[1] == pytest.approx(1.0, abs=1e-12)
    assert far.lever_gear[1] < 1.0 and far.lever_gear[0] == pytest.approx(1.0, abs=1e-12)
    assert far.lever("pinion")[0] == far.lever_pinion[0]
    assert far.lever("gear")[1] == far.lever_gear[1]


def test_tip_zone_ends_where_the_gap_reaches_the_limit():
    """The widened path ends where the corner gap equals the limit (to 1e-9 m of roll),
    or where the contact point would leave the mate's involute: the ring pair's path
    already starts below the planet's form circle (22.605 < 22.676 mm), so no ring corner
    can touch the planet's involute before it."""
    from pipeline.geometry.profile import tooth_profile
    from pipeline.geometry.tip_contact import contact_radii_at, tip_zone

    p = EXTERNAL
    lo, hi = tip_zone(p, 50e-6)
    assert lo < p.s_start and hi > p.s_end
    assert tip_contact(p, [lo, hi]).gap == pytest.approx([50e-6, 50e-6], rel=1e-6)
    assert hi - p.s_end == pytest.approx(p.s_start - lo, rel=1e-9)  # a symmetric pair
    # a limit no corner reaches within a base pitch: capped at one pitch at each end
    assert tip_zone(p, 1.0) == pytest.approx((p.s_start - p.base_pitch,
                                              p.s_end + p.base_pitch), rel=1e-15)
    r = RING
    lo, hi = tip_zone(r, 50e-6)
    assert lo == r.s_start
    assert r.contact_radii(r.s_start)[0] < tooth_profile(r.pinion).form_radius
    assert tip_contact(r, [hi]).gap[0] == pytest.approx(50e-6, rel=1e-6)
    # radii: the line of action's inside the path, the corner's and the flank's beyond
    s = np.array([[p.s_start, p.s_pitch], [p.s_end + 1e-3, p.s_start - 1e-3]])
    r1, r2 = contact_radii_at(p, s)
    assert r1.shape == s.shape == r2.shape
    np.testing.assert_allclose(np.array(p.contact_radii(s[0])), [r1[0], r2[0]], rtol=1e-15)
    assert r1[1, 0] == p.pinion.tip_radius_ and r2[1, 1] == p.gear.tip_radius_


@pytest.mark.parametrize("pair", [EXTERNAL, RING], ids=["external", "ring"])
def test_curvature_radii_at_a_corner_are_the_edge_and_the_mates_involute(pair):
    """On the path the flanks' own radii (rho1 = s, rho2 = T1T2 - s, negative for the
    ring's concave flank); past the end the pinion's edge radius against the gear's
    involute at the contact point, before the start the gear's edge (convex, for a ring
    too) against the pinion's involute: each involute's radius of curvature is its
    distance to the base tangent point, ``sqrt(R^2 - r_b^2)`` at the contact radius R,
    checked here against the radius of the circle through three nearby points of the
    independent involute construction (to 1e-6)."""
    from pipeline.geometry.tip_contact import contact_radii_at, curvature_radii_at

    s = np.array([pair.s_pitch, pair.s_end + 5e-4, pair.s_start - 5e-4])
    rho1, rho2 = curvature_radii_at(pair, s)
    on1, on2 = pair.curvature_radii(s[0])
    assert (rho1[0], rho2[0]) == (on1, on2)
    assert rho1[1] == 0.05 * pair.pinion.module and rho2[2] == 0.05 * pair.gear.module
    r1, r2 = contact_radii_at(pair, s)

    def circle_radius(who: str, s_cross: float, radius: float) -> float:
        gear = pair.pinion if who == "pinion" else pair.gear
        t0 = math.sqrt(radius**2 - gear.base_radius**2) / gear.base_radius
        xy = involute_flank(pair, who, s_cross, t0 + np.array([-1e-4, 0.0, 1e-4]))
        a, b, c = xy.T
        ab, bc, ca = (np.hypot(*(u - v)) for u, v in ((a, b), (b, c), (c, a)))
        area = 0.5 * abs((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0])
        return ab * bc * ca / (4.0 * area)

    gear_flank = circle_radius("gear", s[1], r2[1])
    assert abs(rho2[1]) == pytest.approx(gear_flank, rel=1e-6)
    assert (rho2[1] < 0) == pair.gear.internal
    assert rho1[2] == pytest.approx(circle_radius("pinion", s[2], r1[2]), rel=1e-6)



def _rounding_centre(pair: GearPair, who: str, s: float, rho: float) -> tuple[np.ndarray, float]:
    """Independent construction of a tip rounded by ``rho``: on the textbook involute of
    ``who`` crossing at ``s``, the point whose inward normal (into the tooth: -x for the
    pinion's flank, +x for the gear's, near the line of action) reaches the circle ``r_a -
    rho`` at distance ``rho`` (brentq on the involute parameter). Returns the rounding's
    centre and the roll length ``r_b t`` of its tangency point."""
    from scipy.optimize import brentq

    gear = pair.pinion if who == "pinion" else pair.gear
    rb, ra = gear.base_radius, gear.tip_radius_
    sign = -1.0 if who == "pinion" else 1.0

    def centre(t: float) -> np.ndarray:
        (p,), (dp,) = (involute_flank(pair, who, s, np.array([v])).T for v in (t, t + 1e-7))
        tangent = (dp - p) / np.hypot(*(dp - p))
        n = np.array([-tangent[1], tangent[0]])
        n = n if n[0] * sign > 0 else -n
        return p + rho * n

    origin = flank_centre(pair, who)
    t_tip = math.sqrt(ra**2 - rb**2) / rb
    t = brentq(lambda v: np.hypot(*(centre(v) - origin)) - (ra - rho), 0.5 * t_tip, t_tip,
               xtol=1e-15)
    return centre(t), rb * t


@pytest.mark.parametrize("past", [5e-5, 3e-4, 1e-3])
def test_rounded_tip_gap_against_an_independent_construction(past):
    """Tips rounded by 0.3 mm (pinion) and 0.2 mm (gear) on the external pair: the path ends
    where each rounding touches its involute (roll length of the tangency point, to 1e-10 m
    of the independent brentq construction; the active tip radius is that point's); beyond
    it the gap is the distance from the rounding's centre to the mate's flank less the
    radius (to 1e-12 m), 0 at the rounded path's end and larger than the sharp corner's
    (material removed). A ring's rounding is refused by name."""
    from pipeline.validation import InputError

    rounding = (0.3e-3, 0.2e-3)
    p = GearPair(spur(50, "pinion", tip_rounding=rounding[0]),
                 spur(50, "gear", tip_rounding=rounding[1]))
    lo, hi = p.s_start, p.s_end
    assert EXTERNAL.s_start < lo < hi < EXTERNAL.s_end
    q, roll = _rounding_centre(p, "pinion", hi, rounding[0])
    assert roll == pytest.approx(hi, abs=1e-10)
    assert p.pinion.active_tip_radius == pytest.approx(math.hypot(
        p.pinion.base_radius, roll), abs=1e-10)
    q, roll = _rounding_centre(p, "gear", lo, rounding[1])
    assert roll == pytest.approx(p.t1t2 - lo, abs=1e-10)
    tc = tip_contact(p, [hi + past, lo - past, hi, lo])
    assert list(tc.corner) == ["pinion", "gear", "", ""]
    for i, (who, mate, rho, s) in enumerate((("pinion", "gear", rounding[0], hi + past),
                                             ("gear", "pinion", rounding[1], lo - past))):
        q, _ = _rounding_centre(p, who, s, rho)
        assert tc.gap[i] == pytest.approx(distance_to_flank(q, p, mate, s) - rho, abs=1e-12)
        assert tc.gap[i] > tip_contact(EXTERNAL, [s]).gap[0]
        assert distance_to_flank(tc.point[:, i], p, mate, s) < 2e-10  # on the mate's flank
    assert np.all(tc.gap[2:] == 0.0)
    just = tip_contact(p, [hi + 1e-9, lo - 1e-9])
    assert np.all(just.gap < 1e-13)  # continuous at the rounded path's ends
    with pytest.raises(InputError, match=r"ring\.tip_rounding = 0\.0001 m: a rounded tip of "
                       "an internal gear"):
        spur(72, "ring", module=2e-3, internal=True, bore_radius=0.09, tip_rounding=1e-4)


def test_rounded_profile_arc():
    """The rounded tip's arc in the exact profile: it leaves the involute tangentially at the
    active tip radius (the chord directions on both sides agree to the sampling), every
    point lies rho from one centre, it ends on the tip circle, it lies inside the sharp
    tooth (material removed), and the path of contact ends at the tangency point."""
    from pipeline.geometry.profile import TIP_ROUNDING, tooth_profile

    rho = 0.3e-3
    g = spur(50, "pinion", tip_rounding=rho)
    prof = tooth_profile(g, 200)
    arc = prof.kind == TIP_ROUNDING
    x, y = prof.x[arc], prof.y[arc]
    xi, yi = prof.x[~arc][-2:], prof.y[~arc][-2:]
    # the circle through the arc's first, middle and last points (circumcentre)
    (ax, ay), (bx, by), (cx, cy) = ((x[i], y[i]) for i in (0, x.size // 2, -1))
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    q = np.array([((ax**2 + ay**2) * (by - cy) + (bx**2 + by**2) * (cy - ay)
                   + (cx**2 + cy**2) * (ay - by)) / d,
                  ((ax**2 + ay**2) * (cx - bx) + (bx**2 + by**2) * (ax - cx)
                   + (cx**2 + cy**2) * (bx - ax)) / d])
    assert np.abs(np.hypot(x - q[0], y - q[1]) - rho).max() < 1e-11
    assert math.hypot(x[-1], y[-1]) == pytest.approx(g.tip_radius_, abs=1e-12)
    assert math.hypot(xi[-1], yi[-1]) == pytest.approx(g.active_tip_radius, abs=1e-12)
    inv_dir = np.arctan2(yi[1] - yi[0], xi[1] - xi[0])
    arc_dir = np.arctan2(y[0] - yi[1], x[0] - xi[1])
    assert abs(arc_dir - inv_dir) < 0.02  # rad, one sample of the arc
    sharp = tooth_profile(spur(50, "pinion"), 200)
    r = np.hypot(x, y)
    assert np.all(x <= np.interp(r, np.hypot(sharp.x, sharp.y), sharp.x) + 1e-12)
    assert GearPair(g, spur(50, "gear")).s_end == pytest.approx(
        math.sqrt(g.active_tip_radius**2 - g.base_radius**2), rel=1e-15)


def test_profile_figure_draws_each_segment_apart():
    """The tooth-profile panel of a rounded tip: fillet, involute and tip rounding are three
    lines, each holding only its own points (no line joins the fillet to the tip: the
    fillet's highest point lies at the form radius), the rounding reaches the tip circle."""
    from pipeline.geometry.profile import tooth_profile
    from pipeline.viz.geometry import plot_profile

    g = spur(50, "pinion", tip_rounding=0.6e-3)
    prof = tooth_profile(g)
    ax = plot_profile(prof)
    lines = {ln.get_label(): ln for ln in ax.lines}
    assert {"fillet", "involute", "tip rounding"} <= set(lines)
    fx, fy = lines["fillet"].get_data()
    assert np.hypot(fx, fy).max() == pytest.approx(prof.form_radius * 1e3, rel=1e-9)
    rx, ry = lines["tip rounding"].get_data()
    assert np.hypot(rx, ry).max() == pytest.approx(g.tip_radius_ * 1e3, rel=1e-12)
    assert np.hypot(rx, ry).min() == pytest.approx(g.active_tip_radius * 1e3, rel=1e-9)
    sharp = plot_profile(tooth_profile(spur(50, "pinion")))
    assert "tip rounding" not in {ln.get_label() for ln in sharp.lines}
