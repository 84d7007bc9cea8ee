"""Exact tooth profile: involute, trochoidal fillet, undercut, internal gears, outlines."""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.generation import generate, rack_flank
from pipeline.geometry.profile import INVOLUTE, gear_outline, tooth_profile
from pipeline.validation import InputError
from pipeline.verification.cases_generation import worst_heights

D = math.radians


def helical(z: int = 31, **kw) -> GearSpec:
    base = dict(module=7.35e-3, pressure_angle=D(20), face_width=0.13, helix_angle=D(14),
                hand="right", profile_shift=0.278, addendum_coef=1.2, dedendum_coef=1.55)
    base.update(kw)
    return GearSpec(teeth=z, **base)


def ring(z: int = 80, **kw) -> GearSpec:
    base = dict(module=3e-3, pressure_angle=D(20), face_width=0.02, internal=True,
                bore_radius=0.14)
    base.update(kw)
    return GearSpec(teeth=z, **base)


GEARS = {
    "spur25": lambda: spur(25, "p"),
    "spur25_x05": lambda: spur(25, "p", profile_shift=0.5),
    "spur12_undercut": lambda: spur(12, "p", bore_radius=0.0),
    "helical31": helical,
    "ring80": ring,
}


@pytest.mark.parametrize("name", GEARS)
def test_reference_thickness_and_involute(name):
    """Involute points sit on the closed-form involute; chordal thickness on the reference circle.

    Compares the profile's polar angle with s/2r + inv(a_t) - inv(a_y) (external) or
    s/2r + inv(a_y) - inv(a_t) (ring), and the half thickness at the reference circle's
    height with r sin(s / 2r), s = m_t (pi/2 + 2 x tan a_n).
    """
    g = GEARS[name]()
    p = tooth_profile(g, points=200)
    inv = p.kind == INVOLUTE
    r = p.radius[inv]
    psi = np.arctan2(p.x[inv], p.y[inv])
    at = g.transverse_pressure_angle
    ay = np.arccos(g.base_radius / r)
    s = g.transverse_module * (math.pi / 2 + 2 * g.profile_shift * math.tan(g.pressure_angle))
    sign = -1.0 if g.internal else 1.0
    expect = s / (2 * g.reference_radius) + sign * ((math.tan(at) - at) - (np.tan(ay) - ay))
    np.testing.assert_allclose(psi, expect, rtol=0, atol=1e-13)
    rr = g.reference_radius
    p = tooth_profile(g, points=2000)  # linear interpolation between points: error ~ h^2
    h = p.half_thickness(rr * math.cos(s / (2 * rr)))
    assert h == pytest.approx(rr * math.sin(s / (2 * rr)), rel=1e-6)


@pytest.mark.parametrize("name", ["spur25", "spur25_x05", "helical31", "spur12_undercut"])
def test_rack_flank_generates_the_involute(name):
    """The envelope of the rack's straight flank (law of gearing) is the closed-form involute."""
    g = GEARS[name]()
    yn = np.linspace(-0.9, 0.9, 50) * g.module
    x, y = generate(g, rack_flank(g, yn))
    r = np.hypot(x, y)
    ok = r > g.base_radius * 1.001  # the branch beyond the interference point is not involute
    if g.reference_radius - (g.reference_radius + g.profile_shift * g.module + yn[0]) > \
            g.reference_radius * math.sin(g.transverse_pressure_angle) ** 2:
        ok &= (g.reference_radius + g.profile_shift * g.module + yn) > \
            g.reference_radius * math.cos(g.transverse_pressure_angle) ** 2
    psi = np.arctan2(x[ok], y[ok])
    expect = [g.half_tooth_angle(float(v)) for v in r[ok]]
    np.testing.assert_allclose(psi, expect, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["spur25", "spur25_x05", "helical31"])
def test_base_pitch_between_neighbouring_flanks(name):
    """Along the normal of a right flank, the neighbouring right flank's involute is p_bt away.

    Normals of the first tooth's involute (points whose roll length exceeds p_bt, so
    the hit lies on the same side of the base-circle tangent point) are intersected with the
    involute part of the second tooth's right flank in the 3-tooth outline (tests the
    involute and the placement of the teeth together); every hit must be one transverse
    base pitch away.
    """
    g = GEARS[name]()
    out = gear_outline(g, teeth=3, points=400)
    one = tooth_profile(g, points=400)
    n_flank, per_tooth = len(one.x), len(one.outline()) - 1
    inv = np.nonzero(one.kind == INVOLUTE)[0]
    f0, f1 = out[:n_flank], out[per_tooth: per_tooth + n_flank][inv]
    hits = []
    roll = np.sqrt(np.maximum(one.radius**2 - g.base_radius**2, 0.0))  # 0 in the fillet
    for i in inv[5:-5:20][roll[inv[5:-5:20]] > g.transverse_base_pitch]:  # same side of T
        t = f0[i + 1] - f0[i - 1]
        normal = np.array([t[1], -t[0]]) / np.hypot(*t)
        d = (f1 - f0[i]) @ np.array([-normal[1], normal[0]])  # side of the normal line
        for j in np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0]:
            w = d[j] / (d[j] - d[j + 1])
            hits.append(np.linalg.norm(f1[j] + w * (f1[j + 1] - f1[j]) - f0[i]))
    assert len(hits) >= 3
    np.testing.assert_allclose(hits, g.transverse_base_pitch, rtol=2e-6)


@pytest.mark.parametrize("name", ["spur25", "spur25_x05", "helical31", "ring80"])
def test_fillet_meets_involute_tangentially(name):
    """Fillet's last chord direction vs the involute tangent at the form radius (< 0.05 deg)."""
    g = GEARS[name]()
    p = tooth_profile(g, points=4000)
    k = int(np.argmax(p.kind == INVOLUTE))  # first involute point after the junction
    fillet_dir = np.array([p.x[k - 1] - p.x[k - 2], p.y[k - 1] - p.y[k - 2]])
    r = p.form_radius
    eps = 1e-9 * r
    pa = np.array([(rr * math.sin(g.half_tooth_angle(rr)), rr * math.cos(g.half_tooth_angle(rr)))
                   for rr in (r, r + eps)]) if not g.internal else np.array(
        [(rr * math.sin(g.half_tooth_angle(rr)), rr * math.cos(g.half_tooth_angle(rr)))
         for rr in (r, r - eps)])
    inv_dir = pa[1] - pa[0]
    cosang = fillet_dir @ inv_dir / np.linalg.norm(fillet_dir) / np.linalg.norm(inv_dir)
    assert math.degrees(math.acos(min(1.0, cosang))) < 0.05
    # and the fillet starts on the root circle in the middle of the tooth space
    assert p.radius[0] == pytest.approx(g.root_radius, rel=1e-12)
    assert math.atan2(p.x[0], p.y[0]) == pytest.approx(math.pi / g.teeth, rel=1e-12)


@pytest.mark.parametrize("name", ["spur25", "spur12_undercut", "helical31"])
def test_profile_is_the_envelope_of_the_swept_cutter(name):
    """Independent check: roll the cutter past the profile; it never cuts in, touches every point
    (the construction: pipeline.verification.cases_generation.worst_heights).

    For 30,000 rack positions the profile points are moved into the rack frame; the
    largest penetration above the rack edge must be ~0 (touching, within 1e-4 m_n
    sampling error) and never positive beyond it.
    """
    g = GEARS[name]()
    worst, fillet = worst_heights(g)
    tol = 1e-4 * g.module
    assert worst.max() < tol
    np.testing.assert_array_less(-tol, worst[fillet])


@pytest.mark.parametrize(("z", "x", "undercut"), [(18, 0.0, False), (17, 0.0, True),
                                                   (12, 0.35, False), (12, 0.25, True)])
def test_undercut_limit(z, x, undercut):
    """Undercut starts below z_min = 2 (h_a0* - x) / sin^2(a):
    17.1 for x = 0, 11.1 / 12.8 for 12 teeth.

    h_a0* is the height of the rack's straight flank, h_f* - rho (1 - sin a) = 1.0 here.
    """
    g = spur(z, "p", profile_shift=x, bore_radius=0.0)
    assert tooth_profile(g).undercut is undercut


def test_undercut_thins_the_root():
    """An undercut tooth is thinner just above the base circle than the involute would make it."""
    g = spur(10, "p", bore_radius=0.0)
    p = tooth_profile(g, points=400)
    assert p.undercut and p.form_radius > g.base_radius
    y = (g.base_radius + 0.3 * (p.form_radius - g.base_radius))
    assert p.half_thickness(y) < y * math.tan(g.half_tooth_angle(p.form_radius))


@pytest.mark.parametrize("name", ["spur25", "helical31", "ring80"])
def test_area_converges_second_order(name):
    """Tooth area from the polygon converges at second order as the point count doubles."""
    g = GEARS[name]()
    areas = np.array([tooth_profile(g, points=n).area() for n in (25, 50, 100, 200, 3200)])
    err = np.abs(areas[:-1] - areas[-1])
    ratios = err[:-1] / err[1:]
    assert np.all(ratios > 3.0), ratios
    assert err[-1] / areas[-1] < 1e-5
    # a sanity bound: between the chordal trapezoid of tip and root and the sector ring
    assert 0.0 < areas[-1] < abs(g.tip_radius_ - g.root_radius) * 2 * math.pi * g.root_radius / \
        g.teeth


def test_ring_fillet_is_tangent_arc_to_root_circle():
    """Ring gear: the fillet is a circle of radius rho_a0* m_n tangent to the root circle."""
    g = ring()
    p = tooth_profile(g, points=400)
    fil = (p.kind != INVOLUTE) & (p.radius < g.root_radius - 1e-12)
    pts = np.column_stack([p.x[fil], p.y[fil]])
    rho = g.cutter_tip_radius_coef * g.module
    # centre: at distance r_f - rho from the gear centre, equidistant (rho) from the fillet points
    c = pts.mean(axis=0)
    for _ in range(50):  # Gauss-Newton circle fit with fixed radius
        d = np.linalg.norm(pts - c, axis=1)
        jac = (c - pts) / d[:, None]
        c = c - np.linalg.lstsq(jac, d - rho, rcond=None)[0]
    assert np.linalg.norm(pts - c, axis=1) == pytest.approx(rho, rel=1e-6)
    assert np.hypot(*c) == pytest.approx(g.root_radius - rho, rel=1e-6)
    # ring teeth are widest at their root
    assert p.half_thickness(p.y[len(p.y) // 2]) > p.tip_thickness / 2


def test_outline_sector_and_full_gear():
    """Sector ends on the root circle at pi/2 -/+ n pi/z; the full outline is closed and CCW."""
    g = spur(25, "p")
    sec = gear_outline(g, teeth=3)
    ang = np.arctan2(sec[[0, -1], 1], sec[[0, -1], 0])
    half = 3 * math.pi / 25
    np.testing.assert_allclose(ang, [math.pi / 2 - half, math.pi / 2 + half], atol=1e-12)
    np.testing.assert_allclose(np.hypot(*sec[[0, -1]].T), g.root_radius, rtol=1e-12)
    full = gear_outline(g)
    x, y = full[:, 0], full[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    assert area == pytest.approx(math.pi * g.root_radius**2 + 25 * tooth_profile(g).area(),
                                 rel=1e-9)
    with pytest.raises(InputError, match="outline.teeth"):
        gear_outline(g, teeth=0)


def test_thin_and_pointed_tips():
    """Tip thickness < 0.2 m_n is flagged; a pointed tooth is refused with the field named."""
    g = spur(12, "p", profile_shift=0.75, bore_radius=0.0)
    p = tooth_profile(g)
    assert p.tip_thickness == pytest.approx(g.tooth_thickness_tip, rel=2e-3)
    assert p.thin_tip is (p.tip_thickness < 0.2 * g.module)
    with pytest.raises(InputError, match="pointed"):
        spur(10, "p", profile_shift=1.2, bore_radius=0.0)
