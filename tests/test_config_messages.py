"""Every refusal of a gearbox file speaks the file's language, over the whole schema.

Table-driven over :mod:`pipeline.config.tables` (and the ``[lumped_model]`` keys of each
model): every numeric key of every table is given a value far outside any sensible range
(+-1e30 in the key's unit; +-1e15 for whole numbers) and must be refused in one line
``table.key = value unit is outside the allowed range [lo, hi] unit``, the key as written,
the value and the range in the key's unit. The printed range is then probed at each finite
bound, just outside (refused, naming the key) and just inside (not refused for this key):
this is what proves the range is in the file's unit and not in SI. A table added to
``tables.py`` without a context here fails :func:`test_every_table_is_swept`.

Then the messages that once leaked internals (field names of the dataclasses, SI values,
``PeriodicSignal``, a path said not to exist when it is a device, an example file that
does not exist), each as written by a user.
"""

from __future__ import annotations

import ast
import copy
import math
import re
import tomllib
import warnings
from pathlib import Path

import pytest

from pipeline.cli import main as cli
from pipeline.config import gearbox_from_dict
from pipeline.config import tables as T
from pipeline.config.lumped import MODELS, _model_class, model_keys
from pipeline.config.schema import Key, Scope, restated
from pipeline.validation import InputError

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "workflows" / "configs"


def _doc(name: str) -> dict:
    return tomllib.loads((CONFIGS / name).read_text(encoding="utf-8"))


PAIR = _doc("spur_pair_assembly_errors.toml")          # z 50/50, m 3 mm, dynamics
PLANETARY = _doc("wind_turbine_herringbone_planetary.toml")  # herringbone, groove
SUN_GROOVE = _doc("wind_turbine_sun_groove.toml")      # one gear and its groove
LUMPED = {
    "planetary": _doc("lin_parker_planetary.toml"),
    "herringbone_planetary": _doc("herringbone_planetary_lumped.toml"),
    "spur_pair": {"lumped_model": {
        "model": "spur_pair", "pinion_teeth": 50, "base_radius_pinion_mm": 70.5,
        "base_radius_gear_mm": 70.5, "mass_pinion_kg": 2.52, "mass_gear_kg": 2.52,
        "inertia_pinion_kgm2": 7.4e-3, "inertia_gear_kgm2": 7.4e-3, "torque_Nm": 340.0,
        "speed_rpm": 2340.0,
        "mesh_stiffness": {"kind": "rectangular", "k_single_N_per_m": 4e8,
                           "k_double_N_per_m": 6e8, "contact_ratio": 1.6}}},
}
SIGNALS = {  # a valid [dynamics.mesh_stiffness] of each kind
    "rectangular": {"k_single_N_per_m": 4e8, "k_double_N_per_m": 6e8, "contact_ratio": 1.5},
    "contact_line": {"k_mean_N_per_m": 5e8, "transverse_ratio": 1.5, "overlap_ratio": 1.0},
    "harmonic": {"mean_N_per_m": 5e8, "amplitudes_N_per_m": [1e7], "phases_rad": [0.5]},
    "constant": {"value_N_per_m": 5e8},
    "csv": {"path": "k.csv"},
}
RELIEFS = {"tip_relief_pinion_um": 10.0, "tip_relief_length_pinion_mm": 2.0,
           "tip_relief_gear_um": 10.0, "tip_relief_length_gear_mm": 2.0}
WEB = {"web_width_mm": 10.0, "rim_inner_radius_mm": 60.0, "hub_radius_mm": 30.0}


def _with(doc: dict, where: str, values: dict) -> dict:
    """A copy of ``doc`` with ``values`` set in the table at ``where`` (created if absent)."""
    out = copy.deepcopy(doc)
    table = out
    for part in where.split("."):
        table = table.setdefault(part, {})
    table.update(values)
    return out


def _signal(kind: str) -> dict:
    doc = _with(PAIR, "dynamics", {"friction": False})
    return _with(doc, "dynamics.mesh_stiffness", {"kind": kind, **SIGNALS[kind]})


def _fe_keys(compliance: str) -> tuple[Key, ...]:
    """The ``[fe]`` keys that act with this contact compliance."""
    return tuple(k for k in T.FE if k.name in T.FE_MODEL_KEYS[compliance])


# (tables.py name, base document, table path, its keys)
SHAFT = {"span_mm": 300.0, "offset_mm": 30.0, "shaft_diameter_mm": 60.0, "arrangement": "a"}
"""A pinion shaft of ISO 6336-1 Figure 13 (method C's f_sh)."""

SHAFT_TABLE = {"gear_position_mm": 60.0, "torque_position_mm": 0.0,
               "segments": [{"start_mm": 0.0, "end_mm": 120.0, "outer_diameter_mm": 30.0}],
               "bearings": [{"position_mm": 20.0, "axial": True}, {"position_mm": 100.0}]}
"""A pinion shaft (pipeline.config.shafts); its [[segments]] and [[bearings]] rows are
arrays of tables, which tests/test_config_shafts.py sweeps."""
ARRAY_TABLES = {"SHAFT_SEGMENT", "SHAFT_BEARING"}

CONTEXTS = [
    *[("GEAR", PAIR, role, T.GEAR) for role in ("pinion", "gear")],
    *[("GEAR", PLANETARY, role, T.GEAR) for role in ("sun", "planet", "ring")],
    ("BODY", PAIR, "pinion", T.BODY),
    ("BODY", PLANETARY, "planet", T.BODY),
    ("MATERIAL", PAIR, "pinion.material", T.MATERIAL),
    ("MATERIAL", PLANETARY, "ring.material", T.MATERIAL),
    ("CARRIER", PLANETARY, "carrier", T.CARRIER),
    ("PAIR", PAIR, "pair", T.PAIR),
    ("PLANETARY", PLANETARY, "planetary", T.PLANETARY),
    ("OPERATION", PAIR, "operation", T.OPERATION),
    ("OPERATION", PLANETARY, "operation", T.OPERATION),
    ("STIFFNESS", _with(PAIR, "stiffness", {"friction": "ehl"}), "stiffness", T.STIFFNESS),
    ("CONTACT", PAIR, "contact", T.CONTACT),
    ("MODIFICATIONS", _with(PAIR, "contact", RELIEFS), "contact", T.MODIFICATIONS),
    ("MODIFICATIONS", _with(PLANETARY, "contact", RELIEFS), "contact", T.MODIFICATIONS),
    *[("GEAR_MODIFICATIONS", _with(PAIR, f"{role}.modifications", {}), f"{role}.modifications",
       T.GEAR_MODIFICATIONS) for role in ("pinion", "gear")],
    *[("FE", _with(PAIR, "contact", {"compliance": c}), "fe", _fe_keys(c))
      for c in ("analytical", "fe2d", "fe3d")],
    ("GROOVE", _with(SUN_GROOVE, "groove", {"coupling": "tooth_forces"}), "groove", T.GROOVE),
    ("HERRINGBONE", PLANETARY, "herringbone", T.HERRINGBONE),
    ("RATING", _with(PLANETARY, "rating", {}), "rating", T.RATING),
    ("RATING_GEAR", _with(PAIR, "rating", {"pinion": {}}), "rating.pinion", T.RATING_GEAR),
    ("RATING_GEAR", _with(PLANETARY, "rating", {"ring": {}}), "rating.ring", T.RATING_GEAR),
    ("RATING_METHOD_C", _with(PAIR, "rating", {"method_c": {}}), "rating.method_c",
     T.RATING_METHOD_C),
    ("RATING_PINION_SHAFT", _with(PAIR, "rating", {"pinion_shaft": SHAFT}),
     "rating.pinion_shaft", T.RATING_PINION_SHAFT),
    ("SHAFT", _with(PAIR, "pinion", {"shaft": SHAFT_TABLE}), "pinion.shaft", T.SHAFT),
    ("PLANET_PIN", _doc("shaft_planetary.toml"), "planet.shaft", T.PLANET_PIN),
    ("DYNAMICS", PAIR, "dynamics", T.DYNAMICS),
    ("DYNAMICS_PLANETARY", _with(PLANETARY, "dynamics", {"excitation": "analytical"}), "dynamics",
     T.DYNAMICS_PLANETARY),
    ("RESPONSE", PAIR, "dynamics.response", T.RESPONSE),
    ("SWEEP", PAIR, "dynamics.sweep", T.SWEEP),
    *[("SIGNAL", _signal(kind), "dynamics.mesh_stiffness", T.SIGNAL[kind])
      for kind in T.SIGNAL_KINDS],
    *[("lumped_model", doc, "lumped_model", model_keys(_model_class(name)))
      for name, doc in LUMPED.items()],
]

NOT_APPLICABLE = {
    # (table, key): why the key cannot be given a range there (refused for another reason)
    **{(r, "rim_outer_radius_mm"): "external gear" for r in ("pinion", "gear", "sun", "planet")},
    ("ring", "bore_radius_mm"): "internal gear",
    **{("rating.pinion", k): "external gear: the cutter keys are an internal gear's"
       for k in ("cutter_teeth", "cutter_profile_shift", "cutter_tip_radius_coef",
                 "cutter_addendum_coef")},
}
SETUP = {
    # (table, key) -> other keys of the same table the key needs to act
    **{("pinion", k): WEB for k in WEB}, **{("planet", k): {
        "web_width_mm": 100.0, "rim_inner_radius_mm": 200.0, "hub_radius_mm": 150.0}
        for k in WEB},
    ("planetary", "planet_angles_deg"): {"planet_angles_deg": [0.0, 90.0, 180.0, 270.0]},
    ("lumped_model", "planet_angles_deg"): {"planet_angles_deg": [0.0, 90.0, 180.0, 270.0]},
    **{(f"rating.{g}", "surface_hardness_HBW"): {"material": "normalized_steel"}
       for g in ("pinion", "ring")},
    **{(f"rating.{g}", k): {"material": "through_hardened_alloy", "surface_hardness_HV": 300.0}
       for g in ("pinion", "ring") for k in ("hardness_HB", "proof_stress_MPa")},
    **{("rating.ring", k): {"cutter_teeth": 30} for k in ("cutter_profile_shift",
                                                         "cutter_tip_radius_coef",
                                                         "cutter_addendum_coef")},
    ("dynamics.response", "segments"): {"method": "floquet", "n_harmonics": None},
    ("dynamics.response", "periods"): {"method": "time", "n_harmonics": None},
    ("dynamics", "groove_lateral_stiffness_N_per_m"): {
        "groove_torsional_stiffness_Nm_per_rad": 1e9},
    # a relief amount needs its start, a start its amount
    **{(f"{role}.modifications", k): need for role in ("pinion", "gear") for k, need in (
        ("tip_relief_um", {"tip_relief_length_mm": 2.0}),
        ("tip_relief_length_mm", {"tip_relief_um": 10.0}),
        ("tip_relief_start_diameter_mm", {"tip_relief_um": 10.0}),
        ("root_relief_um", {"root_relief_length_mm": 2.0}),
        ("root_relief_length_mm", {"root_relief_um": 10.0}),
        ("root_relief_start_diameter_mm", {"root_relief_um": 10.0}),
        ("end_relief_face1_um", {"end_relief_face1_length_mm": 3.0}),
        ("end_relief_face1_length_mm", {"end_relief_face1_um": 5.0}),
        ("end_relief_face2_um", {"end_relief_face2_length_mm": 3.0}),
        ("end_relief_face2_length_mm", {"end_relief_face2_um": 5.0}))},
}
CHOICES = {("planetary", "direction"): "is not one of +1, -1"}
"""Whole-number keys that take a few values rather than a range."""
UNBOUNDED_ABOVE = {("herringbone", "axial_support_stiffness_N_per_m"):
                   "rigid when left out (inf); any finite stiffness is a support"}
NUMERIC = ("number", "integer", "numbers", "number_or_string")
PAIR_BOUND_ABOVE_TABLE = {("fe", "teeth"): 5}
"""Keys whose lower bound for the test pair is above the table's range: the 3D sector must
hold the tooth pairs that can touch, -1..2 with tip contact, so 5 teeth (the table allows
3; the pair's own range is named when it is checked, test_fe3d_limits_named_as_in_the_file
_before_any_meshing)."""


def _cases():
    for _, doc, path, keys in CONTEXTS:
        where = doc.get("name") or doc["lumped_model"]["model"]
        for key in keys:
            if key.kind in NUMERIC and (path, key.name) not in NOT_APPLICABLE:
                yield pytest.param(doc, path, key, id=f"{path}.{key.name}@{where}")


def _document(doc: dict, path: str, key: Key, value) -> dict:
    setup = SETUP.get((path, key.name), {})
    out = _with(doc, path, {k: v for k, v in setup.items() if v is not None})
    table = out
    for part in path.split("."):
        table = table[part]
    for k, v in setup.items():
        if v is None:
            table.pop(k, None)
    if key.kind == "numbers":
        given = list(table.get(key.name) or [0.0] * (key.length or 1))
        given[0] = value
        value = given
    table[key.name] = value
    return out


def _message(doc: dict) -> str | None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            gearbox_from_dict(doc, name="box")
        except InputError as exc:
            return str(exc)
    return None


def _range_pattern(path: str, key: Key) -> re.Pattern:
    label = f" {re.escape(key.unit.label)}" if key.unit.label else ""
    return re.compile(
        rf"^{re.escape(path)}\.{re.escape(key.name)}(?:\[0\])? = (?P<value>\S+){label} is "
        rf"outside the allowed range (?P<lb>[\[(])(?P<lo>\S+), (?P<hi>\S+?)(?P<rb>[\])])"
        rf"{label}(?: \([^()]+\))?$")


def _refuses(doc, path, key, value) -> re.Match | None:
    msg = _message(_document(doc, path, key, value))
    return None if msg is None else _range_pattern(path, key).match(msg)


@pytest.mark.parametrize("doc, path, key", list(_cases()))
def test_out_of_range_names_the_key_value_and_range_in_its_unit(doc, path, key):
    whole = key.kind == "integer"
    for huge in ((10**15, -(10**15)) if whole else (1e30, -1e30)):
        if huge > 0 and (path, key.name) in UNBOUNDED_ABOVE:
            continue
        msg = _message(_document(doc, path, key, huge))
        assert msg is not None, f"{path}.{key.name} = {huge} accepted"
        assert "\n" not in msg
        if (path, key.name) in CHOICES:
            assert msg == f"{path}.{key.name} = {huge} {CHOICES[path, key.name]}"
            return
        m = _range_pattern(path, key).match(msg)
        assert m, msg
        assert float(m["value"]) == pytest.approx(huge, rel=1e-5)
        # the bounds are in the key's unit: just beyond each finite bound is refused,
        # naming this key; just inside is not refused for this key
        lo, hi = float(m["lo"]), float(m["hi"])
        assert lo < hi, msg
        scale = max([abs(b) for b in (lo, hi) if math.isfinite(b)] + [1.0])
        for bound, sign, bracket in ((lo, -1, m["lb"]), (hi, 1, m["rb"])):
            if not math.isfinite(bound):
                continue
            if whole:  # whole-number bounds: the next number beyond / the bound itself
                closed = bracket in "[]"
                outside, inside = int(bound) + sign * closed, int(bound) - sign * (not closed)
            else:  # 1e-4 beyond / within: wider than the 6 digits the bound is shown with
                step = max(abs(bound) * 1e-4, scale * 1e-6)
                outside, inside = bound + sign * step, bound - sign * step
            assert _refuses(doc, path, key, outside), (path, key.name, outside, msg)
            need = PAIR_BOUND_ABOVE_TABLE.get((path, key.name))
            if sign < 0 and need is not None and _refuses(doc, path, key, need - 1):
                refusal = _message(_document(doc, path, key, need - 1))
                assert f"allowed range [{need}, " in refusal, refusal
                inside = need
            assert not _refuses(doc, path, key, inside), (path, key.name, inside, msg)


FREE_TEXT = ("name", "path", "column", "topography_csv")
"""String keys that take any text (a label, a file, a column of it)."""


def _word_cases():
    for _, doc, path, keys in CONTEXTS:
        where = doc.get("name") or doc["lumped_model"]["model"]
        for key in keys:
            if key.kind in ("string", "boolean") and key.name not in FREE_TEXT:
                yield pytest.param(doc, path, key, id=f"{path}.{key.name}@{where}")


@pytest.mark.parametrize("doc, path, key", list(_word_cases()))
def test_bad_word_names_the_key_and_what_it_takes(doc, path, key):
    """A string key given an unknown word, a boolean given a string: one line naming the
    key as written, the value as written (TOML quotes) and what the key takes."""
    msg = _message(_document(doc, path, key, "bogus"))
    assert msg is not None and "\n" not in msg
    if key.kind == "boolean":
        assert msg == f'{path}.{key.name} = "bogus": expected true or false (without quotes)'
    else:
        assert msg.startswith(f'{path}.{key.name} = "bogus" is not one of \''), msg


def test_every_table_is_swept():
    """Every table of the schema has a context above, so a new table is swept too."""
    tables = {name for name, value in vars(T).items() if name.isupper()
              and isinstance(value, tuple) and value and isinstance(value[0], Key)}
    covered = {name for name, *_ in CONTEXTS} | ARRAY_TABLES
    assert tables - covered == set()
    assert {kind for kind in T.SIGNAL} == set(T.SIGNAL_KINDS)
    assert set(LUMPED) == set(MODELS)  # every [lumped_model] model


# ---- the messages that once leaked internals ------------------------------------------


def _one_line(tmp_path, capsys, doc_text: str, command: str = "geometry") -> str:
    path = tmp_path / "box.toml"
    path.write_text(doc_text, encoding="utf-8")
    out = tmp_path / "out"
    assert cli([command, str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert not out.exists()
    prefix = f"gearpipe {command}: error: "
    assert err.startswith(prefix), err
    return err[len(prefix):]


SPUR_TEXT = (CONFIGS / "spur_pair_assembly_errors.toml").read_text(encoding="utf-8")


def _spur(old: str, new: str, count: int = 1) -> str:
    assert old in SPUR_TEXT
    return SPUR_TEXT.replace(old, new, count)


def test_other_table_named_in_its_unit(tmp_path, capsys):
    text = _spur("[gear]\nteeth = 50\nmodule_mm = 3.0", "[gear]\nteeth = 50\nmodule_mm = 3.5")
    assert _one_line(tmp_path, capsys, text) == (
        "gear.module_mm = 3.5 mm must equal pinion.module_mm = 3 mm for the gears to mesh")


def test_relief_longer_than_the_path_of_contact_refused_when_read(tmp_path, capsys):
    # path of contact g_alpha = sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin(alpha)
    # (ISO 21771:2007, 5.4.2; unshifted gears): z 50/50, m 3 mm, 20 deg -> 15.540 mm
    r, ra, alpha = 75.0, 78.0, math.radians(20.0)
    g_alpha = 2 * math.sqrt(ra**2 - (r * math.cos(alpha)) ** 2) - 2 * r * math.sin(alpha)
    assert g_alpha == pytest.approx(15.540, abs=1e-3)
    text = SPUR_TEXT + "[contact]\ntip_relief_pinion_um = 20\ntip_relief_length_pinion_mm = 1000\n"
    msg = _one_line(tmp_path, capsys, text, "stiffness")  # refused before the stiffness runs
    m = re.fullmatch(r"contact\.tip_relief_length_pinion_mm = 1000 mm is outside the allowed "
                     r"range \[0, (\S+)\] mm \(the path of contact\)", msg)
    assert m, msg
    assert float(m[1]) == pytest.approx(g_alpha, rel=1e-5)


def test_gear_named_by_the_user_is_still_its_table(tmp_path, capsys):
    text = _spur("bore_radius_mm = 21.0", 'bore_radius_mm = 21.0\nname = "Driver pinion"\n'
                 "groove_width_mm = 40.0")
    assert _one_line(tmp_path, capsys, text) == (
        "pinion.groove_width_mm = 40 mm needs pinion.herringbone = true: the relief groove "
        "separates a herringbone gear's halves")


def test_fe_setting_named_as_in_the_file(tmp_path, capsys):
    text = SPUR_TEXT + '[contact]\ncompliance = "fe3d"\n[fe]\nsolver = "fast"\n'
    msg = _one_line(tmp_path, capsys, text, "stiffness")
    assert msg.startswith('fe.solver = "fast" is not one of '), msg
    assert "fe3d" not in msg and "method" not in msg


def test_fe3d_limits_named_as_in_the_file_before_any_meshing(tmp_path, capsys):
    # a 30 deg helical pair 60 mm wide has tooth pairs -4..4 in contact: 9 sector teeth
    text = (_spur("face_width_mm = 20.0", 'face_width_mm = 60.0\nhelix_angle_deg = 30.0\n'
                  'hand = "right"')
            .replace("[gear]\nteeth = 50\nmodule_mm = 3.0\npressure_angle_deg = 20.0\n"
                     "face_width_mm = 20.0", '[gear]\nteeth = 50\nmodule_mm = 3.0\n'
                     'pressure_angle_deg = 20.0\nface_width_mm = 60.0\nhelix_angle_deg = 30.0'
                     '\nhand = "left"'))
    text += '[contact]\ncompliance = "fe3d"\n[fe]\nteeth = 3\n'
    assert _one_line(tmp_path, capsys, text, "stiffness") == (
        "fe.teeth = 3 is outside the allowed range [9, 99] (the tooth pairs in contact)")
    ring = (CONFIGS / "planet_ring_pair.toml").read_text(encoding="utf-8")
    ring += '[fe]\nteeth = 5\n' if "[fe]" not in ring else ""
    ring = ring.replace("[contact]", '[contact]\ncompliance = "fe3d"', 1)
    assert _one_line(tmp_path, capsys, ring, "stiffness") == (
        'contact.compliance = "fe3d": the 3D models are of external gears only; the gear is '
        'internal: use "fe2d"')


@pytest.mark.parametrize("edits, expected", [
    # z 10 at 11.76 deg, x = -0.308, h_f* = 2.414: the rack's tip cuts the whole flank away
    ([("teeth = 50\nmodule_mm = 3.0\npressure_angle_deg = 20.0",
       "teeth = 10\nmodule_mm = 3.0\npressure_angle_deg = 11.76\nprofile_shift = -0.308\n"
       "addendum_coef = 0.36\ndedendum_coef = 2.414\ncutter_tip_radius_coef = 0.30"),
      ("bore_radius_mm = 21.0", "bore_radius_mm = 3.0")],
     "[pinion]: the undercut root fillet reaches the tip circle (form radius 16.2365 mm >= "
     "tip radius 15.156 mm), leaving no involute flank; raise pinion.profile_shift = -0.308 "
     "or lower pinion.dedendum_coef = 2.414"),
    # a ring of 29 teeth at 7.75 deg, x = 1.496, h_f* = 1.23: r_f = r + (h_f* - x) m =
    # 42.702 mm < r_b = r cos(alpha_t) = 43.103 mm (ISO 21771 for internal gears)
    ([("[gear]\nteeth = 50\nmodule_mm = 3.0\npressure_angle_deg = 20.0\nface_width_mm = 20.0"
       "\nbore_radius_mm = 21.0",
       "[gear]\nteeth = 29\nmodule_mm = 3.0\npressure_angle_deg = 7.75\nface_width_mm = 20.0"
       "\nprofile_shift = 1.496\naddendum_coef = 0.81\ndedendum_coef = 1.23\ninternal = true"
       "\nrim_outer_radius_mm = 60.0")],
     "[gear]: the root circle of the internal gear (radius 42.702 mm) lies inside its base "
     "circle (43.1027 mm), where no involute exists; lower gear.profile_shift = 1.496 or raise "
     "gear.dedendum_coef = 1.23"),
])
def test_gear_without_involute_refused_with_the_fix(tmp_path, capsys, edits, expected):
    r = 29 * 3.0 / 2  # the ring's numbers, independently: 43.5 mm reference radius
    assert r + (1.23 - 1.496) * 3.0 == pytest.approx(42.702)
    assert r * math.cos(math.radians(7.75)) == pytest.approx(43.1027, abs=1e-4)
    text = SPUR_TEXT
    for old, new in edits:
        assert old in text
        text = text.replace(old, new, 1)
    assert _one_line(tmp_path, capsys, text) == expected


def test_internal_pinion_refused_as_such(tmp_path, capsys):
    text = _spur("bore_radius_mm = 21.0", "bore_radius_mm = 21.0\ninternal = true")
    msg = _one_line(tmp_path, capsys, text)
    assert msg.startswith("pinion.internal = true: the pinion of a gear pair is an external "
                          "gear"), msg
    assert "rim_outer_radius_mm" not in msg


GIVE_CSV = "; give a CSV file with one mesh period of stiffness values (N/m) in a column"


@pytest.mark.parametrize("target, tail", [
    ("/dev/zero", " is not a regular file (a device, pipe or socket)" + GIVE_CSV),
    ("FOLDER", " is a folder, not a file" + GIVE_CSV),
    ("missing.csv", " does not exist" + GIVE_CSV),
    ("three.csv", ": column 'k' holds 3 values; one mesh period needs at least 4 finite values"),
    ("text.csv", ": line 3, column 'k' holds 'abc', not a number"),
])
def test_stiffness_file_gets_the_true_reason(tmp_path, capsys, target, tail):
    (tmp_path / "three.csv").write_text("k\n1e8\n2e8\n3e8\n")
    (tmp_path / "text.csv").write_text("k\n1e8\nabc\n3e8\n4e8\n")
    path = str(tmp_path) if target == "FOLDER" else target
    text = _spur('dofs = "lateral_torsional"', 'dofs = "lateral_torsional"\nfriction = false')
    text += f'[dynamics.mesh_stiffness]\nkind = "csv"\npath = "{path}"\n'
    shown = path if path.startswith("/") else str(tmp_path / path)  # relative to the file
    msg = _one_line(tmp_path, capsys, text, "stiffness")
    assert msg == f'dynamics.mesh_stiffness.path = "{shown}"{tail}'


def test_files_named_by_the_package_exist():
    """Every workflow or test file a message or docstring of the package points to exists."""
    named = set()
    for source in (ROOT / "pipeline").rglob("*.py"):
        for node in ast.walk(ast.parse(source.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                named |= set(re.findall(r"(?:workflows|tests)/[\w/.-]*\w\.(?:toml|py|csv)",
                                        node.value))
    assert "workflows/configs/spur_pair_assembly_errors.toml" in named  # the old-format hint
    assert [n for n in sorted(named) if not (ROOT / n).is_file()] == []


# ---- the rewriting itself ---------------------------------------------------------------

GEAR_SCOPE = {"Driver pinion": Scope("pinion", T.GEAR + T.BODY, {"bore_radius_mm": 1}),
              "pinion": Scope("pinion", T.GEAR + T.BODY, {"bore_radius_mm": 1}),
              "gear": Scope("gear", T.GEAR + T.BODY, {"rim_outer_radius_mm": 1})}


@pytest.mark.parametrize("where, keys, raised, expected", [
    # another table's field in SI -> its key in mm (3.5 mm = 0.0035 m)
    ("pair", T.PAIR, "gear.module = 0.0035 m must equal pinion.module = 0.003 m",
     "gear.module_mm = 3.5 mm must equal pinion.module_mm = 3 mm"),
    # a gear's own name as prefix; two keys setting one field: the one the table gave
    ("pair", T.PAIR, "Driver pinion.bore_radius = 0.021 m; gear.bore_radius = 0.3 m",
     "pinion.bore_radius_mm = 21 mm; gear.rim_outer_radius_mm = 300 mm"),
    # an unknown prefix with a value: the table's own key; strings in TOML quotes
    ("fe", tuple(Key(k.name, k.kind, field="method") if k.name == "solver" else k
                 for k in T.FE), "fe3d.method = 'x' is not one of 'a', 'b'",
     'fe.solver = "x" is not one of \'a\', \'b\''),
    # a range in SI after the value, with a note; degrees from radians
    ("pinion", T.GEAR, "pinion.helix_angle = 0.785398 rad is outside the allowed range "
     "[0, 0.785398) rad (why)",
     "pinion.helix_angle_deg = 45 deg is outside the allowed range [0, 45) deg (why)"),
    # bare field names with an underscore become key names; prose stays prose
    ("pinion", T.BODY, "pinion: a web needs web_width and hub_radius; the teeth stay",
     "[pinion]: a web needs web_width_mm and hub_radius_mm; the teeth stay"),
    # another table's field under an unknown prefix is not taken for this table's key
    ("groove", T.GROOVE, "operation.torque = 340 N m differs from groove.sun_torque = 3 N m",
     "[groove]: operation.torque = 340 N m differs from groove.torque_Nm = 3 N m"),
    # a key already as written keeps its value; a value in another unit is left alone
    ("pinion", T.GEAR, "pinion.module_mm = 3 mm, pinion.module = 3 mm",
     "pinion.module_mm = 3 mm, pinion.module_mm = 3 mm"),
])
def test_restated_rewrites_fields_into_the_file_terms(where, keys, raised, expected):
    with pytest.raises(InputError) as info:
        with restated(where, keys, also=GEAR_SCOPE):
            raise InputError(raised)
    assert str(info.value) == expected
