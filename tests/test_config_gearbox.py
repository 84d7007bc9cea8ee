"""The gearbox file: strict input errors (table-driven), derived values, old formats.

Every bad input gives exit status 2, exactly one line on stderr naming the key as
written, the value in the file's unit and the allowed range in that unit, no
traceback, and nothing written.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pipeline.cli import main as cli
from pipeline.config import gearbox_from_text, load_gearbox
from pipeline.config.units import unit_of_key
from pipeline.validation import InputError

ROOT = Path(__file__).resolve().parents[1]
SPUR = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"
BASE = SPUR.read_text(encoding="utf-8")


def _edit(old: str, new: str) -> bytes:
    assert old in BASE, old
    return BASE.replace(old, new, 1).encode("utf-8")


BAD_INPUTS = [
    # (case, file bytes, words the one-line message must contain)
    ("misspelt table", _edit("[operation]", "[operaton]"),
     ["operaton", "did you mean 'operation'"]),
    ("misspelt key", _edit("torque_Nm = 340.0", "torqe_Nm = 340.0"),
     ["operation", "torqe_Nm", "did you mean 'torque_Nm'"]),
    ("number as string", _edit("module_mm = 3.0", 'module_mm = "3.0"'),
     ["pinion.module_mm", '"3.0"', "a number"]),
    ("integer as words", _edit("teeth = 50", 'teeth = "fifty"'),
     ["pinion.teeth", '"fifty"', "whole number"]),
    ("integer as fraction", _edit("teeth = 50", "teeth = 50.5"),
     ["pinion.teeth", "50.5", "whole number"]),
    ("boolean as string", _edit("bore_radius_mm = 21.0",
                                'bore_radius_mm = 21.0\ninternal = "false"'),
     ["pinion.internal", '"false"', "true or false"]),
    ("list as string", _edit("assembly_error_gear_um = [0.0, 0.0]",
                             'assembly_error_gear_um = "55"'),
     ["pair.assembly_error_gear_um", '"55"', "list of numbers"]),
    ("list too short", _edit("assembly_error_gear_um = [0.0, 0.0]",
                             "assembly_error_gear_um = [5.0]"),
     ["pair.assembly_error_gear_um", "2 numbers"]),
    ("string choice", _edit('driver = "pinion"', 'driver = "motor"'),
     ["operation.driver", '"motor"', "'pinion', 'gear'"]),
    ("range in degrees", _edit("pressure_angle_deg = 20.0", "pressure_angle_deg = 60.0"),
     ["pinion.pressure_angle_deg = 60 deg", "(0, 35] deg"]),
    ("range in um", _edit("assembly_error_gear_um = [0.0, 0.0]",
                          "assembly_error_gear_um = [0.0, 9000.0]"),
     ["pair.assembly_error_gear_um[1] = 9000 um", "[-5000, 5000] um"]),
    ("range in mm", _edit("bore_radius_mm = 21.0", "bore_radius_mm = 80.0"),
     ["pinion.bore_radius_mm = 80 mm", "mm"]),
    ("range in N m", _edit("torque_Nm = 340.0", "torque_Nm = -340.0"),
     ["operation.torque_Nm = -340 N m", "(0, 1e+08] N m"]),
    ("range of a count", _edit("positions = 360", "positions = 3"),
     ["stiffness.positions = 3", "[8, 100000]"]),
    ("wrong type of table", b"operation = 5\n" + _edit("[operation]\n", "[stiffness_x]\n"),
     ["operation = 5", "expected a table"]),
    ("stiffness table missing a key", (BASE + '[dynamics.mesh_stiffness]\nkind = "rectangular"\n'
                                       ).encode(),
     ["[dynamics.mesh_stiffness] needs the key 'k_single_N_per_m'"]),
    ("two keys for one value", _edit("bore_radius_mm = 21.0",
                                     "bore_radius_mm = 21.0\nrim_outer_radius_mm = 30.0"),
     ["pinion.rim_outer_radius_mm", "bore_radius_mm"]),
    ("not finite", _edit("friction = 0.0", "friction = nan"),
     ["stiffness.friction = nan", "finite"]),
    ("old dynamics file", b'model = "spur_pair"\n[parameters]\nmass_pinion_kg = 2.5\n',
     ["old format", "[lumped_model]"]),
    ("non-UTF-8", _edit("# Units", "# Unit\xe9s").decode().encode("latin-1"),
     ["not UTF-8", f"line {BASE[:BASE.index('# Units')].count(chr(10)) + 1}"]),
    ("byte-order mark", b"\xef\xbb\xbf" + BASE.encode(), ["byte-order mark"]),
    ("binary garbage", bytes(range(256)) * 4, ["binary data"]),
    ("syntax error", b"[pinion\nteeth = 3", ["TOML syntax error", "line 1"]),
    ("absurd nesting", b"a = " + b"[" * 5000 + b"]" * 5000, ["nested too deeply"]),
    ("deep tables", b"[a.b.c.d.e.f.g.h.i.j]\nx = 1\n", ["nested too deeply"]),
    ("unknown compliance", (BASE + '[contact]\ncompliance = "fe"\n').encode(),
     ["contact.compliance", '"fe"', "'analytical', 'fe2d', 'fe3d'"]),
    ("fe key of another source", (BASE + '[fe]\nends = "sliding"\n').encode(),
     ["fe.ends applies to [contact] compliance = 'fe3d' only", "'analytical'"]),
    ("fe range of the 3D source", (BASE + '[contact]\ncompliance = "fe3d"\n'
                                   '[fe]\nrefinement = 9.0\n').encode(),
     ["fe.refinement = 9", "[0.2, 4]"]),
    ("2D patch of the 3D source", (BASE + '[contact]\ncompliance = "fe3d"\n'
                                   '[fe]\npatch_mn = 0.05\n').encode(),
     ["fe.patch_mn applies to [contact] compliance = 'fe2d' only", "'fe3d'"]),
    ("2D patch out of range", (BASE + '[contact]\ncompliance = "fe2d"\n'
                               '[fe]\npatch_mn = 0.5\n').encode(),
     ["fe.patch_mn = 0.5", "[0.02, 0.2]"]),
    ("2D patch finer than the mesh", (BASE + '[contact]\ncompliance = "fe2d"\n'
                                      '[fe]\npatch_mn = 0.05\n').encode(),
     ["fe.patch_mn = 0.05 m_n is finer than the mesh resolves at fe.refinement = 1",
      "must be at least 0.1 / fe.refinement = 0.1 m_n"]),
]


@pytest.mark.parametrize("case, data, words", BAD_INPUTS, ids=[c[0] for c in BAD_INPUTS])
def test_bad_input_one_line(tmp_path, capsys, case, data, words):
    path = tmp_path / "box.toml"
    path.write_bytes(data)
    out = tmp_path / "out"
    assert cli(["stiffness", str(path), "--out", str(out)]) == 2
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith("gearpipe stiffness: error: ")
    assert "Traceback" not in err
    for w in words:
        assert w in err, (w, err)
    assert not out.exists()  # nothing written


def test_fe_table_is_the_chosen_fe_model():
    """Each [fe] key sets the field of its name on the FE model [contact] compliance
    names (2D for "analytical" and "fe2d", 3D for "fe3d"), the slices come from
    [contact], and gearpipe fe's sector has 5 teeth where the contact source models the
    whole gear; a key of the other model is refused naming the compliance it needs."""
    from pipeline.fem.settings import FE2DSettings, FE3DSettings

    box = gearbox_from_text(BASE + '[contact]\ncompliance = "fe2d"\nslices = 3\n'
                            '[fe]\npoints = 20\nrefinement = 1.5\n')
    assert isinstance(box.fe, FE2DSettings) and box.fe_source is box.fe
    assert (box.fe.points, box.fe.refinement, box.fe.slices) == (20, 1.5, 3)
    assert box.fe.teeth is None and box.fe.sector_teeth == 5
    box3 = gearbox_from_text(BASE + '[contact]\ncompliance = "fe3d"\n'
                             '[fe]\nface_points = 7\nends = "sliding"\nsolver = "splu"\n')
    assert isinstance(box3.fe, FE3DSettings)
    assert (box3.fe.face_points, box3.fe.ends, box3.fe.solver) == (7, "sliding", "splu")
    plain = gearbox_from_text(BASE + '[fe]\nkind = "plane_stress"\n')
    assert plain.fe_source is None and plain.fe.kind == "plane_stress"
    with pytest.raises(InputError, match=r"^fe.kind applies to \[contact\] compliance = "
                       r"'analytical' or 'fe2d' only; this file's contact compliance is 'fe3d'"):
        gearbox_from_text(BASE + '[contact]\ncompliance = "fe3d"\n[fe]\nkind = "plane_stress"\n')


def test_units_defined_once():
    """Key suffixes map to the SI factors of the one units table."""
    cases = {"module_mm": 1e-3, "roughness_um": 1e-6, "pressure_angle_deg": math.pi / 180,
             "speed_rpm": math.pi / 30, "torque_Nm": 1.0, "youngs_modulus_GPa": 1e9,
             "density_kg_m3": 1.0, "viscosity_mPas": 1e-3, "bearing_stiffness_N_per_m": 1.0,
             "teeth": 1.0, "profile_shift": 1.0}
    for key, factor in cases.items():
        assert unit_of_key(key).factor == pytest.approx(factor, rel=1e-15), key


def test_spur_pair_derived_dynamic_inputs():
    """The spur pair file gives the model's base radii, masses, inertias and mesh period.

    By hand: r_b = (z m / 2) cos 20 deg = 75 mm x 0.9396926 = 70.4769 mm; T_m =
    60 / (z n) = 60 / (50 x 2340) s = 0.512821 ms. Mass and polar moment: the root disc
    minus the 21 mm bore plus 50 teeth, each tooth integrated in polar coordinates with
    the involute half angle psi(r) = s/(2r) + inv(alpha_t) - inv(alpha(r)) from the root
    to the tip circle, A = pi (r_f^2 - r_i^2) + z int 2 psi r dr,
    J = pi/2 (r_f^4 - r_i^4) + z int 2 psi r^3 dr (times rho b). This ignores the fillet
    (the corner between the involute and the root circle that the cutter tip round fills
    with metal), which the exact section includes: 2 (1 - pi/4) rho_f^2 per tooth, 0.17 %
    of the area, so the exact values lie 0-0.3 % above the hand values.
    """
    from pipeline.geometry.involute import inv
    from pipeline.run.runner import gearbox_dynamic_model

    box = load_gearbox(SPUR)
    model = gearbox_dynamic_model(box)
    assert model.base_radius_pinion == pytest.approx(0.0704769, abs=1e-7)
    assert model.base_radius_gear == pytest.approx(0.0704769, abs=1e-7)
    assert model.mesh_period == pytest.approx(60 / (50 * 2340), rel=1e-12)
    g = box.pinion
    r = np.linspace(g.root_radius, g.tip_radius_, 20001)
    a = np.arccos(np.minimum(1.0, g.base_radius / r))
    at = g.transverse_pressure_angle
    psi = g.reference_tooth_thickness / (2 * g.reference_radius) + inv(at) - inv(a)
    ri, rf = g.bore_radius, g.root_radius
    area = math.pi * (rf**2 - ri**2) + g.teeth * np.trapezoid(2 * psi * r, r)
    polar = math.pi / 2 * (rf**4 - ri**4) + g.teeth * np.trapezoid(2 * psi * r**3, r)
    rho_b = g.material.density * g.face_width
    for got in (model.mass_pinion, model.mass_gear):
        assert 0.0 < got / (rho_b * area) - 1 < 3e-3
    for got in (model.inertia_pinion, model.inertia_gear):
        assert 0.0 < got / (rho_b * polar) - 1 < 3e-3


def test_spur_pair_same_frequencies_as_the_hand_typed_model():
    """With the hand-typed masses and k(t) of the former dynamics file given as overrides,
    the gearbox file's model has exactly its natural frequencies; with the derived bodies
    (2.543 kg, 7.72e-3 kg m^2 instead of 2.52 kg, 7.4e-3 kg m^2) they move by < 3 %."""
    from pipeline.dynamics.analysis import analyse_modes
    from pipeline.dynamics.excitation import rectangular_mesh_stiffness
    from pipeline.dynamics.models.spur_pair import SpurPairModel
    from pipeline.run.runner import gearbox_dynamic_model

    hand = SpurPairModel(
        mesh_stiffness=rectangular_mesh_stiffness(2.3e8, 3.9e8, 1.73, samples=360),
        pinion_teeth=50, base_radius_pinion=70.4769e-3, base_radius_gear=70.4769e-3,
        mass_pinion=2.52, mass_gear=2.52, inertia_pinion=7.4e-3, inertia_gear=7.4e-3,
        bearing_stiffness=1e8, bearing_damping=100.0, damping_ratio=0.07, torque=340.0,
        speed=2340 * math.pi / 30)
    ref = analyse_modes(hand).frequencies
    text = BASE.replace("[dynamics]\n", "[dynamics]\nfriction = false\n")
    text += ('[dynamics.mesh_stiffness]\nkind = "rectangular"\nk_single_N_per_m = 2.3e8\n'
             'k_double_N_per_m = 3.9e8\ncontact_ratio = 1.73\nsamples = 360\n')
    derived = analyse_modes(gearbox_dynamic_model(gearbox_from_text(text))).frequencies
    for role in ("pinion", "gear"):
        text = text.replace("bore_radius_mm = 21.0\n", "bore_radius_mm = 21.0\nmass_kg = 2.52\n"
                            "inertia_kgm2 = 7.4e-3\n", 1) if role == "pinion" else \
            text.replace("bore_radius_mm = 21.0\n[gear", "bore_radius_mm = 21.0\nmass_kg = 2.52\n"
                         "inertia_kgm2 = 7.4e-3\n[gear", 1)
    given = analyse_modes(gearbox_dynamic_model(gearbox_from_text(text))).frequencies
    np.testing.assert_allclose(given, ref, rtol=1e-5)  # r_b typed to 6 digits by hand
    np.testing.assert_allclose(derived[1:], ref[1:], rtol=0.03)


def test_planetary_set_is_derived_and_checked():
    """Planet positions and phases come from the set; impossible sets are refused."""
    text = """
[sun]
teeth = 21
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 30.0
bore_radius_mm = 10.0
[planet]
teeth = 37
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 30.0
bore_radius_mm = 15.0
[ring]
teeth = 95
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 30.0
internal = true
rim_outer_radius_mm = 160.0
[carrier]
mass_kg = 5.0
inertia_kgm2 = 0.05
[planetary]
planets = 4
"""
    box = gearbox_from_text(text)
    ps = box.planetary
    np.testing.assert_allclose(np.degrees(ps.angles), [0, 90, 180, 270])
    np.testing.assert_allclose(ps.sun_phases, [0.0, 0.25, 0.5, 0.75])  # 21 psi / 360 deg
    assert box.bodies["ring"].mass_ > 0 and box.bodies["planet"].inertia_ > 0
    with pytest.raises(InputError, match="planets overlap.*planet_angles"):
        gearbox_from_text(text + "planet_angles_deg = [0.0, 0.0, 0.0, 0.0]\n")
    with pytest.raises(InputError, match="ring.rim_outer_radius_mm = 10 mm"):
        gearbox_from_text(text.replace("rim_outer_radius_mm = 160.0",
                                       "rim_outer_radius_mm = 10.0"))
    with pytest.raises(InputError, match="planets overlap"):
        gearbox_from_text(text.replace("planets = 4", "planets = 29"))  # 116 / 29: assembles


def test_lumped_planetary_checks_planets_and_ring(tmp_path):
    """A lumped planetary model refuses coincident planets and a ring inside the planets."""
    base = (ROOT / "workflows/configs/lin_parker_planetary.toml").read_text()
    box = gearbox_from_text(base)
    assert box.lumped.n_planets == 4
    same = base.replace("n_planets = 4", "n_planets = 4\nplanet_angles_deg = [0.0, 0.0, 0.0, 0.0]")
    with pytest.raises(InputError, match="planets overlap"):
        gearbox_from_text(same)
    small = base.replace("n_planets = 4", "n_planets = 4\nbase_radius_ring_mm = 10.0")
    with pytest.raises(InputError, match="base_radius_ring_mm = 10 mm"):
        gearbox_from_text(small)


def test_wind_turbine_gearbox_file_matches_the_model_gears():
    """The example file of Xu et al. (2020)'s stage derives the same planet phases as the
    gears built in code for the dynamic model, and its [groove] names the sun."""
    from pipeline.dynamics.models.wind_turbine_planetary import wind_turbine_planetary_set

    box = load_gearbox(ROOT / "workflows/configs/wind_turbine_herringbone_planetary.toml")
    ref = wind_turbine_planetary_set()
    np.testing.assert_allclose(box.planetary.sun_phases, ref.sun_phases, atol=1e-12)
    np.testing.assert_allclose(box.planetary.ring_phases, ref.ring_phases, atol=1e-12)
    assert box.planetary.ring_sun_phase == pytest.approx(ref.ring_sun_phase, abs=1e-12)
    assert box.groove.gear.teeth == 21 and box.groove.groove_bottom_diameter == 0.27
