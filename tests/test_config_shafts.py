"""``[<gear>.shaft]`` tables (pipeline.config.shafts): read into the layout, and every bad
layout refused in one line naming the key as written, with the row's index."""

from __future__ import annotations

import math

import pytest

from pipeline.config.gearbox import gearbox_from_text
from pipeline.validation import InputError
from workflows.default_case import DEMO_PAIR

SHAFT = """[pinion.shaft]
gear_position_mm = 60.0
torque_position_mm = 0.0
[[pinion.shaft.segments]]
start_mm = 0.0
end_mm = 120.0
outer_diameter_mm = 30.0
[[pinion.shaft.bearings]]
position_mm = 20.0
axial = true
[[pinion.shaft.bearings]]
position_mm = 100.0
radial_stiffness_N_per_m = 5.0e8
"""


def _box(shaft: str):
    return gearbox_from_text(DEMO_PAIR.replace("[gear]", shaft + "[gear]"))


def test_layout_read_in_si():
    model, lay = _box(SHAFT).shafts["pinion"]
    assert model == "beam" and lay.hub == "rigid"
    assert lay.gear_position == pytest.approx(0.060) and lay.seat_width == pytest.approx(0.020)
    assert lay.segments[0].outer_diameter == pytest.approx(0.030)
    assert lay.bearings[0].radial_stiffness == math.inf and lay.bearings[0].axial
    assert lay.bearings[1].radial_stiffness == 5.0e8


@pytest.mark.parametrize("change, message", [
    (("position_mm = 100.0", "position_mm = 65.0"),
     r"pinion.shaft.bearings\[1\].position_mm = 65 mm lies inside the gear's seat "
     r"\(50 to 70 mm\)"),
    (("gear_position_mm = 60.0", "gear_position_mm = 115.0"),
     r"pinion.shaft.gear_position_mm = 115 mm is outside the allowed range \[10, 110\] mm"),
    (("axial = true\n", ""), r"exactly one bearing locates the shaft axially"),
    (("outer_diameter_mm = 30.0\n", "outer_diameter_mm = 30.0\n[[pinion.shaft.segments]]\n"
      "start_mm = 110.0\nend_mm = 140.0\nouter_diameter_mm = 25.0\n"),
     r"pinion.shaft.segments\[1\].start_mm = 110 mm leaves an overlap"),
    (("outer_diameter_mm = 30.0", "outer_diameter_mm = 30.0\ninner_diameter_mm = 31.0"),
     r"pinion.shaft.segments\[0\].inner_diameter_mm = 31 mm is outside the allowed range"),
    (("radial_stiffness_N_per_m = 5.0e8", "radial_stiffness_N_per_m = -1.0"),
     r"pinion.shaft.bearings\[1\].radial_stiffness_N_per_m = -1 N/m is outside"),
    (("position_mm = 20.0", "position_mm = 20.0\nwidth_mm = 10.0"),
     r"\[pinion.shaft.bearings\[0\]\] key 'width_mm' is not known"),
    (("gear_position_mm = 60.0", 'gear_position_mm = 60.0\nmodel = "shell"'),
     r"pinion.shaft.model = \"shell\" is not one of"),
    (("torque_position_mm = 0.0", "torque_position_mm = 60.0"),
     r"pinion.shaft.torque_position_mm = 60 mm lies inside the gear's seat"),
])
def test_bad_layouts_name_the_key(change, message):
    with pytest.raises(InputError, match=message):
        _box(SHAFT.replace(*change, 1))


def test_a_ring_has_no_shaft():
    text = DEMO_PAIR.replace("[gear]\n", "[gear]\ninternal = true\n")
    with pytest.raises(InputError):
        gearbox_from_text(text.replace("bore_radius_mm = 21.0\n[operation]",
                                       "rim_outer_radius_mm = 90.0\n[operation]")
                          + SHAFT.replace("pinion.shaft", "gear.shaft"))
