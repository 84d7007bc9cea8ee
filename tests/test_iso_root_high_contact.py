"""ISO 6336-3 on a high-contact-ratio pair: where method B puts the load, and what the report
says about comparing it with the FE stress (Yang et al. 2026 traction pair, eps_alpha 2.05)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest
from gearsets import spur

from pipeline.contact.iso_root_stress import iso_root_stress
from pipeline.geometry import GearPair
from pipeline.report.root_section import iso_note


def _pairs_in_contact(u: float, eps: float) -> int:
    """Tooth pairs in contact when one tooth's contact lies u base pitches inside the path
    (measured from its tip end), the path being eps base pitches long (spur section)."""
    return sum(1 for k in range(-4, 5) if 0.0 <= u + k <= eps)


def test_traction_pair_load_point_is_the_outer_point_of_double_contact(helical_traction_pair):
    """eps_alpha = 2.052 (Yang et al. 2026, Table 2 geometry), beta_b = 3.76 deg:
    eps_alpha_n = eps_alpha / cos^2(beta_b) = 2.061 (ISO 6336-3:2019, 6.2). ISO's d_en lies
    p_bn (eps_alpha_n - 1) = 1.061 p_bn inside the virtual gear's tip end of the path, where
    the tooth has two pairs in contact just inside and three just outside: the outer point of
    double pair contact, not a point of single pair contact (there is none)."""
    pair = helical_traction_pair
    eps_n = pair.transverse_contact_ratio / math.cos(pair.pinion.base_helix_angle) ** 2
    assert pair.transverse_contact_ratio == pytest.approx(2.052, abs=1e-3)
    assert eps_n == pytest.approx(2.061, abs=1e-3)
    for gear in (pair.pinion, pair.gear):
        iso = iso_root_stress(gear, pair, 1.0)
        assert iso.high_contact_ratio and iso.virtual_contact_ratio == pytest.approx(eps_n)
        mn, an = gear.module, gear.pressure_angle
        dbn = mn * iso.virtual_teeth * math.cos(an)
        dan = mn * iso.virtual_teeth + 2.0 * (gear.tip_radius_ - gear.reference_radius)
        roll = (math.sqrt(dan**2 - dbn**2) - math.sqrt(iso.load_diameter**2 - dbn**2)) / 2.0
        u = roll / (math.pi * mn * math.cos(an))
        assert u == pytest.approx(eps_n - 1.0, rel=1e-9)
        assert _pairs_in_contact(u + 1e-6, eps_n) == 2
        assert _pairs_in_contact(u - 1e-6, eps_n) == 3
        assert all(_pairs_in_contact(v / 100.0, eps_n) >= 2 for v in range(0, 207))


def _root(iso_p, iso_g, load=1000.0):
    return SimpleNamespace(tangential_load=load, pinion=SimpleNamespace(iso=iso_p),
                           gear=SimpleNamespace(iso=iso_g))


def test_report_says_why_fe_is_below_iso_for_high_contact_ratio(helical_traction_pair):
    """The traction pair's root-stress note names eps_alpha_n 2.061 and ISO's single-tooth
    load at the outer point of double pair contact; a spur pair z 30/60 (eps_alpha < 2)
    keeps the outer point of single pair contact and no such remark."""
    pair = helical_traction_pair
    high = iso_note(_root(iso_root_stress(pair.pinion, pair, 1.0),
                          iso_root_stress(pair.gear, pair, 1.0)))
    assert "eps_alpha_n = 2.061 >= 2" in high
    assert "outer point of double pair contact" in high
    assert "outer point of single pair contact of the virtual spur gear" not in high
    spur_pair = GearPair(spur(30, "pinion"), spur(60, "gear"))
    assert spur_pair.transverse_contact_ratio < 2.0
    low = iso_note(_root(iso_root_stress(spur_pair.pinion, spur_pair, 1.0),
                         iso_root_stress(spur_pair.gear, spur_pair, 1.0)))
    assert "outer point of single pair contact of the virtual spur gear" in low
    assert "high contact ratio" not in low
