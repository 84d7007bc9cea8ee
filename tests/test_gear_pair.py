"""Gear and pair geometry against exact involute formulas (ISO 21771)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur

from pipeline.geometry import GearPair, GearSpec
from pipeline.geometry.involute import inv, inv_inverse
from pipeline.validation import InputError

D = math.radians


def test_inv_inverse_roundtrip():
    """inv_inverse inverts tan(a) - a to round-off over 1..60 deg."""
    a = np.radians(np.linspace(1, 60, 200))
    assert np.max(np.abs(inv_inverse(inv(a)) - a)) < 1e-12


@pytest.mark.parametrize("z,beta,x", [(17, 0.0, 0.0), (31, 4.0, 0.278), (50, 15.0, -0.2)])
def test_radii_and_pitch(z, beta, x):
    """r = z m_n / (2 cos b), r_b = r cos a_t, p_bt = pi m_t cos a_t = 2 pi r_b / z (exact)."""
    hand = "right" if beta else "none"
    g = GearSpec(teeth=z, module=4e-3, pressure_angle=D(20), face_width=0.03,
                 helix_angle=D(beta), hand=hand, profile_shift=x)
    mt = 4e-3 / math.cos(D(beta))
    at = math.atan(math.tan(D(20)) / math.cos(D(beta)))
    assert g.reference_radius == pytest.approx(z * mt / 2, rel=1e-14)
    assert g.base_radius == pytest.approx(z * mt / 2 * math.cos(at), rel=1e-14)
    assert g.transverse_base_pitch == pytest.approx(math.pi * mt * math.cos(at), rel=1e-14)
    assert g.normal_base_pitch == pytest.approx(math.pi * 4e-3 * math.cos(D(20)), rel=1e-14)
    assert g.tip_radius_ == pytest.approx(z * mt / 2 + 4e-3 * (1 + x), rel=1e-14)
    assert g.root_radius == pytest.approx(z * mt / 2 - 4e-3 * (1.25 - x), rel=1e-14)


@pytest.mark.parametrize("x", [-0.3, 0.0, 0.5])
def test_reference_tooth_thickness(x):
    """s = m_t (pi/2 + 2 x tan a_n) and the involute thickness law.

    s_y = 2 r_y (s/2r + inv a - inv a_y).
    """
    g = spur(30, "g", profile_shift=x)
    s = g.reference_tooth_thickness
    assert s == pytest.approx(3e-3 * (math.pi / 2 + 2 * x * math.tan(D(20))), rel=1e-14)
    r = g.reference_radius
    assert 2 * r * g.half_tooth_angle(r) == pytest.approx(s, rel=1e-14)
    ry = 0.5 * (g.base_radius + g.tip_radius_)
    ay = math.acos(g.base_radius / ry)
    expect = 2 * ry * (s / (2 * r) + float(inv(D(20))) - float(inv(ay)))
    assert 2 * ry * g.half_tooth_angle(ry) == pytest.approx(expect, rel=1e-13)


def test_contact_ratio_closed_form(spur_pair_z50):
    """eps_a = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin a_w) / p_bt (standard form)."""
    p, g = spur_pair_z50.pinion, spur_pair_z50.gear
    a = spur_pair_z50.operating_centre_distance
    eps = (math.sqrt(p.tip_radius_**2 - p.base_radius**2)
           + math.sqrt(g.tip_radius_**2 - g.base_radius**2) - a * math.sin(D(20)))
    eps /= p.transverse_base_pitch
    assert spur_pair_z50.transverse_contact_ratio == pytest.approx(eps, rel=1e-13)
    assert spur_pair_z50.transverse_contact_ratio == pytest.approx(1.75467, abs=1e-5)
    assert a == pytest.approx(0.150, rel=1e-14)


def test_shifted_pair_centre_distance():
    """Zero-backlash a_w from inv a_w = inv a + 2 tan a (x1+x2)/(z1+z2); a_w cos a_w = a cos a."""
    p, g = spur(18, "pinion", profile_shift=0.4), spur(40, "gear", profile_shift=0.1)
    pair = GearPair(p, g)
    aw = pair.operating_pressure_angle
    assert float(inv(aw)) == pytest.approx(float(inv(D(20))) + 2 * math.tan(D(20)) * 0.5 / 58,
                                           rel=1e-12)
    a = 3e-3 * 58 / 2
    assert pair.operating_centre_distance * math.cos(aw) == pytest.approx(a * math.cos(D(20)),
                                                                          rel=1e-13)


def test_internal_pair_contact_ratio():
    """Internal pair: eps_a = (sqrt(ra1^2-rb1^2) - sqrt(ra2^2-rb2^2) + a sin a_w) / p_bt."""
    p = spur(20, "pinion")
    r = GearSpec(teeth=80, module=3e-3, pressure_angle=D(20), face_width=0.02, internal=True,
                 bore_radius=0.14, name="ring")
    pair = GearPair(p, r)
    a = pair.operating_centre_distance
    assert a == pytest.approx(3e-3 * 60 / 2, rel=1e-14)
    eps = (math.sqrt(p.tip_radius_**2 - p.base_radius**2)
           - math.sqrt(r.tip_radius_**2 - r.base_radius**2) + a * math.sin(D(20)))
    assert pair.transverse_contact_ratio == pytest.approx(eps / p.transverse_base_pitch, rel=1e-12)
    assert r.tip_radius_ == pytest.approx(0.12 - 3e-3, rel=1e-14)


def test_helical_overlap_ratio_and_contact_lines(helical_traction_pair):
    """eps_b = b sin(b) / (pi m_n); mean contact line length = eps_a b / cos(b_b) (exact)."""
    pair = helical_traction_pair
    assert pair.overlap_ratio == pytest.approx(0.13 * math.sin(D(4)) / (math.pi * 7.35e-3),
                                               rel=1e-13)
    s0 = pair.mesh_cycle(20000)
    total = pair.contact_line_lengths(s0).sum(axis=1)
    bb = pair.pinion.base_helix_angle
    expect = pair.transverse_contact_ratio * 0.13 / math.cos(bb)
    assert total.mean() == pytest.approx(expect, rel=2e-4)
    # contact lines inside the plane of action and inclined at beta_b
    for seg in pair.contact_lines(float(s0[123])):
        ds, dz = seg[1] - seg[0]
        assert ds / dz == pytest.approx(math.tan(bb), rel=1e-12)
        assert pair.s_start - 1e-12 <= seg[:, 0].min() and seg[:, 0].max() <= pair.s_end + 1e-12


def test_yang2026_table2_centre_distance(helical_traction_pair):
    """The numbers of Yang et al. (2026), Table 2 give its 495 mm centre distance with beta = 4 deg
    (to 1 um)."""
    assert helical_traction_pair.operating_centre_distance == pytest.approx(0.495, abs=1e-6)
    # 'alternates between two and three'
    assert 2.0 < helical_traction_pair.total_contact_ratio < 3.0


def test_sliding_velocity_vanishes_at_pitch_point(spur_pair_z50):
    """v_s = (w1 + w2)(s - s_pitch) for an external pair."""
    s = np.linspace(spur_pair_z50.s_start, spur_pair_z50.s_end, 7)
    vs = spur_pair_z50.sliding_velocity(s, 100.0)
    w2 = 100.0 / spur_pair_z50.gear_ratio
    np.testing.assert_allclose(vs, (100.0 + w2) * (s - spur_pair_z50.s_pitch), atol=1e-12)


@pytest.mark.parametrize(
    "kwargs,field",
    [
        (dict(teeth=3), "teeth"),
        (dict(module=-1e-3), "module"),
        (dict(face_width=0.0), "face_width"),
        (dict(pressure_angle=D(50)), "pressure_angle"),
        (dict(profile_shift=1.5), "tooth is pointed"),
        (dict(helix_angle=D(10)), "hand"),
        (dict(cutter_tip_radius_coef=0.6), "cutter_tip_radius_coef"),
        (dict(bore_radius=0.2), "bore_radius"),
    ],
)
def test_bad_gear_inputs_name_the_field(kwargs, field):
    base = dict(teeth=20, module=3e-3, pressure_angle=D(20), face_width=0.02, name="pinion")
    base.update(kwargs)
    with pytest.raises(InputError, match=field):
        GearSpec(**base)


def test_interference_and_contact_ratio_errors():
    """Too few pinion teeth against a large gear: the gear tip passes T1 (interference)."""
    with pytest.raises(InputError, match="interference"):
        GearPair(spur(8, "pinion", bore_radius=0.0), spur(80, "gear"))
    with pytest.raises(InputError, match="contact ratio"):
        GearPair(spur(40, "pinion", addendum_coef=0.45, dedendum_coef=0.8),
                 spur(40, "gear", addendum_coef=0.45, dedendum_coef=0.8))
    with pytest.raises(InputError, match="gear.module"):
        GearPair(spur(20, "pinion"), spur(40, "gear", module=4e-3))
