"""``[<gear>.modifications]`` where they enter: read in SI, each
refusal one line naming the key as written, its value in the file's unit and the range or
the conflict (the ranges of every key are swept in tests/test_config_messages.py)."""

from __future__ import annotations

import copy
import math
import re
import tomllib
from pathlib import Path

import pytest

from pipeline.config import gearbox_from_dict
from pipeline.validation import InputError

CONFIGS = Path(__file__).resolve().parents[1] / "workflows" / "configs"
DEMO = tomllib.loads((CONFIGS / "modifications_demo.toml").read_text(encoding="utf-8"))
PLANETARY = tomllib.loads((CONFIGS / "wind_turbine_herringbone_planetary.toml")
                          .read_text(encoding="utf-8"))


def _box(edits: dict, base: Path | None = None, doc: dict = DEMO):
    out = copy.deepcopy(doc)
    for where, values in edits.items():
        table = out
        for part in where.split("."):
            table = table.setdefault(part, {})
        if values is None:
            parent = out
            for part in where.split(".")[:-1]:
                parent = parent[part]
            parent.pop(where.split(".")[-1])
        else:
            table.update(values)
    return gearbox_from_dict(out, base=base)


def _refusal(edits: dict, base: Path | None = None, doc: dict = DEMO) -> str:
    with pytest.raises(InputError) as exc:
        _box(edits, base, doc)
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


def test_example_read_in_si():
    pinion, gear = _box({}).contact.modifications.flanks
    assert pinion.profile.tip_relief == pytest.approx(30e-6)
    assert pinion.profile.tip_relief_length == pytest.approx(5e-3)
    assert pinion.lead.crowning == pytest.approx(6e-6)
    assert gear.lead.end_relief_face2_length == pytest.approx(3e-3)
    assert gear.lead.end_relief_shape == "parabolic"
    assert gear.twist == pytest.approx(3e-6)


def test_start_outside_the_active_flank_named_with_its_range():
    """Active flank of the z 50/50 pinion: from d = 2 sqrt(s_start^2 + r_b^2) to its tip
    diameter 156 mm (m (z + 2)); s_start = T1T2 - sqrt(r_a^2 - r_b^2) (ISO 21771)."""
    rb = 75.0 * math.cos(math.radians(20.0))
    s_start = 150.0 * math.sin(math.radians(20.0)) - math.sqrt(78.0**2 - rb**2)
    d_sap = 2 * math.hypot(s_start, rb)
    assert d_sap == pytest.approx(145.42, abs=0.01)
    msg = _refusal({"pinion.modifications": {"root_relief_um": 5.0,
                                             "root_relief_start_diameter_mm": 140}})
    m = re.fullmatch(r"pinion\.modifications\.root_relief_start_diameter_mm = 140 mm is outside "
                     r"the allowed range \[(\S+), (\S+)\] mm \(the pinion's active flank\)", msg)
    assert m, msg
    assert float(m[1]) == pytest.approx(d_sap, rel=1e-5)
    assert float(m[2]) == pytest.approx(156.0, rel=1e-6)


def test_root_relief_overlapping_the_tip_relief_refused():
    # path of contact 15.54 mm: tip relief from 5 mm below the tip, root relief up to 12 mm
    msg = _refusal({"pinion.modifications": {"root_relief_um": 5.0,
                                             "root_relief_length_mm": 12.0}})
    assert msg.startswith("pinion.modifications.root_relief_um overlaps pinion.modifications."
                          "tip_relief_um by 1.46"), msg
    assert "the root relief must end below where the tip relief starts" in msg


@pytest.mark.parametrize("edits, expected", [
    ({"gear.modifications": {"tip_relief_start_diameter_mm": 150.0}},
     "gear.modifications.tip_relief_um = 30 um needs its start: "
     "gear.modifications.tip_relief_length_mm or gear.modifications."
     "tip_relief_start_diameter_mm (one of them; both given)"),
    ({"gear.modifications": {"end_relief_face1_length_mm": 12.0,
                             "end_relief_face2_length_mm": 12.0}},
     "gear.modifications.end_relief_face1_length_mm + gear.modifications."
     "end_relief_face2_length_mm = 24 mm is "
     "more than the gear's face width 20 mm: the end reliefs would overlap"),
    ({"pinion.modifications": {"flank": 1.0}},
     "[pinion.modifications] key 'flank' is not known"),
    ({"contact": {"crowning_um": 4.0}},
     "contact.crowning_um is the short form of [pinion.modifications] and "
     "[gear.modifications]: give it in [pinion.modifications] instead (the file has both)"),
    ({"pinion.modifications": {"root_relief_length_mm": 2.0}},
     "pinion.modifications.root_relief_length_mm = 2 mm changes nothing without an amount "
     "pinion.modifications.root_relief_um"),
])
def test_refused_in_one_line(edits, expected):
    msg = _refusal(edits)
    assert msg.startswith(expected), msg


def test_planetary_set_reads_each_gears_table():
    """A planetary set's [sun.modifications] goes on the sun-planet mesh's pinion flank
    (tests/test_planetary_modifications.py: the meshes against their pairs)."""
    box = _box({"sun.modifications": {"lead_crowning_um": 5.0}}, doc=PLANETARY)
    assert box.mesh_contact("sun_planet").modifications.pinion_flank.lead.crowning == \
        pytest.approx(5e-6)
    assert box.mesh_contact("planet_ring").modifications.pinion_flank is None


def test_topography_file_problems_name_the_file(tmp_path):
    msg = _refusal({"gear.modifications": {"topography_csv": "missing.csv"}}, base=tmp_path)
    assert msg == (f'gear.modifications.topography_csv = "{tmp_path / "missing.csv"}" does not '
                   "exist; give a CSV file with columns face_position_mm, roll_length_mm (or "
                   "diameter_mm), deviation_um")
    # a grid over the diameter that stops 1 mm short of the gear's tip (156 mm)
    rows = ["face_position_mm,diameter_mm,deviation_um"] + [
        f"{z},{d},0.5" for z in (0.0, 20.0) for d in (140.0, 155.0)]
    (tmp_path / "short.csv").write_text("\n".join(rows), encoding="utf-8")
    msg = _refusal({"gear.modifications": {"topography_csv": "short.csv"}}, base=tmp_path)
    assert re.fullmatch(r'gear\.modifications\.topography_csv "short\.csv": diameters 140 to 155 '
                        r"mm do not cover the gear's active flank, 145\.42\d* to 156 mm", msg), msg
    # the same grid to the tip is read and acts: 0.5 um everywhere on the gear
    rows = [r.replace(",155.0,", ",156.0,") for r in rows]
    (tmp_path / "full.csv").write_text("\n".join(rows), encoding="utf-8")
    box = _box({"gear.modifications": {"topography_csv": "full.csv"}}, base=tmp_path)
    grid = box.contact.modifications.flanks[1].topography
    assert grid.axis == "diameter"
    assert grid.at(0.01, 0.150)[()] == pytest.approx(0.5e-6, rel=1e-12)
