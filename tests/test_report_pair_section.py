"""The report's pair table: operating, nominal (zero-backlash) and reference centre distances."""

import math
from dataclasses import replace

import pytest

from pipeline.geometry import GearPair, GearSpec
from pipeline.report.content import pair_section


def _rows(pair: GearPair) -> dict:
    return {q.key: q for q in pair_section(pair, pair).quantities}


def test_reference_distance_external_helical(helical_traction_pair):
    """Yang et al. (2026) traction pair: a = m_n (z1 + z2) / (2 cos beta) = 7.35 mm * 135 /
    (2 cos 4 deg) = 497.336 mm (ISO 21771), beside the zero-backlash distance of its shifts
    x1 + x2 = -0.31219, which is near the paper's 495 mm."""
    rows = _rows(helical_traction_pair)
    ref = 7.35 * (31 + 104) / (2 * math.cos(math.radians(4.0)))
    assert rows["centre_distance_reference"].values[0] == pytest.approx(ref, rel=1e-12)
    assert ref == pytest.approx(497.3365, abs=1e-4)
    assert "z2 + z1" in rows["centre_distance_reference"].label
    nominal = rows["centre_distance_nominal"]
    assert "zero-backlash" in nominal.label
    assert nominal.values[0] == pytest.approx(495.0, abs=0.5)
    assert nominal.values[0] == rows["centre_distance"].values[0]


def test_reference_distance_internal_and_given_distance():
    """Internal spur pair z1 = 21, z2 = 95, m = 15 mm: a = m (z2 - z1) / 2 = 555 mm exactly;
    a centre distance given in the file is called so, not zero-backlash."""
    kw = dict(module=15e-3, pressure_angle=math.radians(20), face_width=0.1)
    p = GearSpec(teeth=21, name="sun", **kw)
    r = GearSpec(teeth=95, internal=True, bore_radius=0.85, name="ring", **kw)
    rows = _rows(GearPair(p, r))
    assert rows["centre_distance_reference"].values[0] == pytest.approx(555.0, rel=1e-12)
    assert "z2 - z1" in rows["centre_distance_reference"].label
    given = _rows(replace(GearPair(p, r), centre_distance=0.5552))
    assert given["centre_distance_nominal"].label.endswith("(pair.centre_distance_mm)")
    assert given["centre_distance_nominal"].values[0] == pytest.approx(555.2, rel=1e-12)
    assert given["centre_distance_reference"].values[0] == pytest.approx(555.0, rel=1e-12)
