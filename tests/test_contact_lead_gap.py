"""A gap tabulated across the face (``FlankModifications.lead_gap``, the shafts' deflection
in the plane of action): a linear table equals the same helix slope deviation, to round-off,
through the whole loaded contact; the table is checked where it enters."""

from __future__ import annotations

import pytest

from pipeline.contact.options import ContactOptions
from pipeline.contact.separations import FlankModifications
from pipeline.validation import InputError


def _cycle(pair, mods):
    from pipeline.contact.analysis import analyse_contact
    from pipeline.contact.compliance import compliance_source
    from pipeline.operation import OperatingPoint
    from pipeline.stiffness.options import StiffnessOptions

    op = OperatingPoint(torque=340.0, speed=245.0)
    opts = ContactOptions(positions=8, slices=10, modifications=mods)
    src = compliance_source(pair, op, opts, StiffnessOptions(), None)
    return analyse_contact(src, op, opts)


def test_linear_table_equals_the_slope_deviation(spur_pair_z50):
    """f_Hb 15 um across b as slope_deviation, and as the table (0, -7.5 um), (b, +7.5 um):
    the same line load and transmission error to 1e-12 (relative)."""
    b = spur_pair_z50.face_width
    slope = _cycle(spur_pair_z50, FlankModifications(slope_deviation=15e-6))
    table = _cycle(spur_pair_z50, FlankModifications(lead_gap=((0.0, -7.5e-6), (b, 7.5e-6))))
    assert table.transmission_error == pytest.approx(slope.transmission_error, rel=1e-12)
    assert table.point_load == pytest.approx(slope.point_load, rel=1e-9, abs=1e-9)


def test_table_checked_where_it_enters():
    with pytest.raises(InputError, match=r"lead_gap\[1\]: face positions must ascend"):
        FlankModifications(lead_gap=((0.01, 0.0), (0.005, 1e-6)))
    with pytest.raises(InputError, match=r"lead_gap\[0\]"):
        FlankModifications(lead_gap=((0.0, 2e-3),))
    assert FlankModifications(lead_gap=((0.0, 1e-6), (0.02, 1e-6))).varies_across_face is False
    assert FlankModifications(lead_gap=((0.0, 0.0), (0.02, 1e-6))).varies_across_face
