"""Every input acts, or is refused, or is warned about in one line.

Table-driven: each row is a shipped gearbox file edited so that one key would do nothing
(overridden by another table, read by no method the file chose, or describing tooth pairs
that never mesh); the exact one-line message, from the loader and from the command line
(``gearpipe <command>: error: ...`` with exit status 2, or ``gearpipe <command>: warning:
...`` on stderr with the run going on). The last tests show that an accepted pitch error
does act, by the amount the contact model gives in closed form.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np
import pytest

from pipeline.cli import main as cli
from pipeline.config import InputError, gearbox_from_text
from pipeline.contact import analyse_contact
from pipeline.contact.analysis import analytical_compliance
from pipeline.validation import InputWarning

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "workflows" / "configs"
SPUR = CONFIGS / "spur_pair_assembly_errors.toml"
WIND = CONFIGS / "wind_turbine_herringbone_planetary.toml"

# z 40/20/80, m 3 mm, 20 deg, standard addenda (Lin and Parker's set); transverse contact
# ratios from ISO 21771 (2007), 5.4: epsilon_alpha = (sqrt(r_a1^2 - r_b1^2) +- sqrt(r_a2^2 -
# r_b2^2) -+ a sin(alpha)) / (pi m cos(alpha)) (lower signs: internal): sun-planet (r_a 63 / 33
# mm, a 90 mm) 1.6352, planet-ring (r_a 33 / 117 mm, a 90 mm) 1.8897
PLANETARY = """
[sun]
teeth = 40
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 30.0
bore_radius_mm = 15.0
[planet]
teeth = 20
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 30.0
bore_radius_mm = 10.0
[ring]
teeth = 80
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 30.0
internal = true
rim_outer_radius_mm = 140.0
[carrier]
mass_kg = 5.43
inertia_kgm2 = 0.05
[planetary]
planets = 4
[operation]
torque_Nm = 200.0
speed_rpm = 1000.0
[contact]
pitch_errors_um = [0.0, 3.0, -2.0]
"""


def _edit(base: Path | str, pattern: str, value: str) -> str:
    """``base`` (a file or the text of one) with the first match of ``pattern`` replaced."""
    text = base.read_text() if isinstance(base, Path) else base
    text, n = re.subn(pattern, value, text, count=1, flags=re.MULTILINE)
    assert n == 1, pattern
    return text


def _pitch(values: list[float]) -> str:
    return f"[contact]\npitch_errors_um = {values}\n[dynamics]"


REFUSED = [
    ("typed groove torsion beside the FE groove", WIND, r"^sun_load_side = .*$",
     'sun_load_side = "R"\ngroove_torsional_stiffness_Nm_per_rad = 7.909e7',
     'dynamics.groove_torsional_stiffness_Nm_per_rad = 7.909e+07 N m/rad contradicts the '
     '[groove] table: with excitation = "contact" the sun\'s halves are joined by the groove\'s '
     '3D FE stiffness (the left/right sun-mesh excitations carry its static twist); remove '
     'this key, or the [groove] table to use it'),
    ("typed groove torsion and lateral beside the FE groove", WIND, r"^sun_load_side = .*$",
     'groove_torsional_stiffness_Nm_per_rad = 5.0e7\ngroove_lateral_stiffness_N_per_m = 5.0e9',
     'dynamics.groove_torsional_stiffness_Nm_per_rad = 5e+07 N m/rad contradicts the '
     '[groove] table: with excitation = "contact" the sun\'s halves are joined by the groove\'s '
     '3D FE stiffness (the left/right sun-mesh excitations carry its static twist); remove '
     'this key, or the [groove] table to use it'),
    ("sun load side against the torque entry", WIND, r"^sun_load_side = .*$",
     'sun_load_side = "L"',
     'dynamics.sun_load_side = "L" contradicts herringbone.torque_entry = "right": with the '
     '[groove] table and excitation = "contact" the sun is loaded where the contact through '
     'the groove takes its torque out (sun_load_side = "R"); give the same side in both or '
     'leave sun_load_side out'),
    ("51 pitch errors on 50 teeth", SPUR, r"^\[dynamics\]", _pitch([1.5] * 51),
     "contact.pitch_errors_um = [1.5, 1.5, 1.5, 1.5, 1.5, 1.5, ...] um has 51 entries, more "
     "than the 50 teeth of the pinion: entry k offsets tooth pair k of the mesh cycle, and "
     "pairs k and k + 50 would share a tooth (allowed: at most 50 entries)"),
    ("EHL roughness with a constant friction", SPUR, r"^foundation_correction = .*$",
     "foundation_correction = 1.0\nroughness_um = 0.4",
     'stiffness.roughness_um = 0.4 um applies to friction = "ehl" only; this table\'s '
     "friction is 0"),
    ("harmonics of a Floquet response", SPUR, r'^method = "harmonic_balance"$',
     'method = "floquet"',
     'dynamics.response.n_harmonics = 40 applies to method = "harmonic_balance" only; this '
     'table\'s method is "floquet"'),
    ("time-integration periods of a harmonic balance", SPUR, r"^n_harmonics = 40$",
     "n_harmonics = 40\nperiods = 300",
     'dynamics.response.periods = 300 applies to method = "time" only; this table\'s method '
     'is "harmonic_balance"'),
    ("planets of a distributed groove coupling", WIND, r"^mesh_size_mm = .*$",
     "mesh_size_mm = 30.0\nplanets = 3",
     'groove.planets = 3 applies to coupling = "tooth_forces" only; this table\'s coupling '
     'is "distributed" (the default)'),
    ("tooth-force groove with other planets than the set", WIND, r"^mesh_size_mm = .*$",
     'mesh_size_mm = 30.0\ncoupling = "tooth_forces"\nplanets = 3',
     "groove.planets = 3 contradicts planetary.planets = 4: leave groove.planets out (it "
     "follows the set)"),
    ("the planet's groove in a planetary set", WIND, r'^gear = "sun"$', 'gear = "planet"',
     'groove.gear = "planet": a planetary set\'s [groove] is the sun\'s (its halves are '
     "joined through it in the contact and the dynamics); analyse the planet's groove from a "
     "file with that gear alone"),
    ("bearings of a torsional pair model", SPUR, r'^dofs = "lateral_torsional"$',
     'dofs = "torsional"',
     'dynamics.bearing_stiffness_N_per_m = 1e+08 N/m applies to dofs = "lateral_torsional" '
     'only; this table\'s dofs is "torsional"'),
    ("excitation replaced by an explicit mesh stiffness", SPUR, r"^damping_ratio = 0.07$",
     'damping_ratio = 0.07\nfriction = false\nexcitation = "contact"\n'
     '[dynamics.mesh_stiffness]\nkind = "constant"\nvalue_N_per_m = 3.0e8',
     'dynamics.excitation = "contact" does nothing: [dynamics.mesh_stiffness] replaces the '
     'mesh excitation and friction = false; leave it out'),
    ("axial stiffness of a spur planetary set", PLANETARY, r"^\[contact\]",
     "[dynamics]\nsun_axial_stiffness_N_per_m = 1.0e9\n[contact]",
     "dynamics.sun_axial_stiffness_N_per_m = 1e+09 N/m applies to a herringbone set; this "
     "planetary set has no herringbone gears"),
    ("groove torque other than the sun's", WIND, r"^torque_Nm = 148000.0 .*as \[groove\].*$",
     "torque_Nm = 150000.0",
     "groove.torque_Nm = 148000 N m contradicts operation.torque_Nm = 150000 N m, the sun's "
     "torque of this planetary set: leave groove.torque_Nm out (it follows [operation])"),
    ("slice coupling of an FE compliance", SPUR, r"^\[dynamics\]",
     '[contact]\ncompliance = "fe2d"\nslice_coupling = 0.1\n[dynamics]',
     'contact.slice_coupling = 0.1 applies to compliance = "analytical" only; this table\'s '
     'compliance is "fe2d"'),
    ("a web beside both mass and inertia", SPUR, r"^bore_radius_mm = 21.0$",
     "bore_radius_mm = 21.0\nmass_kg = 2.52\ninertia_kgm2 = 7.4e-3\nweb_width_mm = 8.0\n"
     "rim_inner_radius_mm = 60.0\nhub_radius_mm = 35.0",
     "pinion.web_width_mm = 8 mm changes nothing: [pinion] gives both mass_kg and "
     "inertia_kgm2, and without [rating] those are the only quantities the web shapes"),
    ("axial support of a free sun", WIND, r'^sun_axial = "held".*$', 'sun_axial = "free"',
     'herringbone.axial_support_stiffness_N_per_m = 1e+09 N/m applies to sun_axial = "held" '
     'only; this table\'s sun_axial is "free"'),
]


# the command that reads the refused key (the refusal comes when the file is loaded)
COMMAND = {"51 pitch errors on 50 teeth": "contact", "EHL roughness with a constant friction":
           "stiffness", "harmonics of a Floquet response": "response",
           "time-integration periods of a harmonic balance": "response",
           "planets of a distributed groove coupling": "groove",
           "tooth-force groove with other planets than the set": "groove",
           "the planet's groove in a planetary set": "groove",
           "bearings of a torsional pair model": "modes",
           "excitation replaced by an explicit mesh stiffness": "modes",
           "axial stiffness of a spur planetary set": "modes",
           "groove torque other than the sun's": "groove",
           "slice coupling of an FE compliance": "contact",
           "a web beside both mass and inertia": "modes"}


@pytest.mark.parametrize(("case", "base", "pattern", "value", "message"), REFUSED,
                         ids=[r[0] for r in REFUSED])
def test_an_input_that_would_do_nothing_is_refused(tmp_path, capsys, case, base, pattern,
                                                   value, message):
    command = COMMAND.get(case, "run")
    text = _edit(base, pattern, value)
    if case == "axial support of a free sun":
        text = text.replace("axial_slide_mm = 0.0", "", 1)
    with pytest.raises(InputError) as info:
        gearbox_from_text(text)
    assert str(info.value) == message
    cfg = tmp_path / "bad.toml"
    cfg.write_text(text)
    out = tmp_path / "out"
    assert cli([command, str(cfg), "--out", str(out)]) == 2
    assert capsys.readouterr().err.splitlines() == [f"gearpipe {command}: error: {message}"]
    assert not out.exists()


def test_typed_groove_acts_without_the_fe_groove_in_the_dynamics():
    """With ``excitation = "analytical"`` the model does not take the [groove] FE, so the
    typed groove is accepted and is what the model's sun halves are joined by; the shipped
    file (sun_load_side "R" = torque_entry "right") is accepted as it is."""
    from pipeline.dynamics.mesh_input import excitation_from_signal
    from pipeline.dynamics.models.planetary_gears import herringbone_planetary_model_from_gears
    from pipeline.signals import PeriodicSignal

    shipped = gearbox_from_text(WIND.read_text())
    assert shipped.fe_groove_in_dynamics and shipped.dynamics.sun_load_side == "R"
    text = _edit(WIND, r'^excitation = "contact"', 'excitation = "analytical"')
    text = text.replace('sun_load_side = "R"', 'sun_load_side = "R"\n'
                        "groove_torsional_stiffness_Nm_per_rad = 7.909e7", 1)
    box = gearbox_from_text(text)
    assert not box.fe_groove_in_dynamics
    k = excitation_from_signal(PeriodicSignal(np.full(8, 2e9)))
    model = herringbone_planetary_model_from_gears(box.planetary, box.bodies, box.carrier,
                                                   box.operation, box.dynamics, k, k)
    assert model.groove == 7.909e7


def test_pitch_errors_of_pairs_that_never_mesh_are_one_warning(tmp_path, capsys):
    """z 50/50, m 3 mm, 20 deg: epsilon_alpha = (2 sqrt(78^2 - r_b^2) - 150 sin(20 deg)) /
    (3 pi cos(20 deg)) = 1.7547 (ISO 21771 (2007), 5.4; r_b = 75 cos(20 deg) mm), so on the
    nominal path tooth pairs k = 0 and 1 mesh in a mesh cycle (k p_bt < g_alpha) and the
    entries for k = 2, 3 change nothing; with tip contact pair 2 touches at the pinion's tip
    corner past the end of the path (the tip zone reaches 2.233 base pitches past the start
    of the path), and only the entry for k = 3 changes nothing."""
    nominal = _edit(SPUR, r"^\[dynamics\]", "[contact]\npitch_errors_um = [0.0, 3.0, 2.0, -1.0]"
                    "\ntip_contact = false\n[dynamics]")
    with pytest.warns(InputWarning) as record:
        gearbox_from_text(nominal)
    assert [str(r.message) for r in record] == [
        "contact.pitch_errors_um[2:] = [2, -1] um change nothing: only tooth pairs k = 0 to 1 "
        "mesh in the analysed mesh cycle (pair k meshes when k < transverse contact ratio "
        "1.755)"]
    text = _edit(SPUR, r"^\[dynamics\]", _pitch([0.0, 3.0, 2.0, -1.0]))
    message = ("contact.pitch_errors_um[3:] = [-1] um change nothing: only tooth pairs "
               "k = 0 to 2 mesh in the analysed mesh cycle (pair k touches when k < 2.233, the "
               "path of contact and the tip zone past its end in base pitches)")
    with pytest.warns(InputWarning) as record:
        box = gearbox_from_text(text)
    assert [str(r.message) for r in record] == [message]
    assert box.pair.transverse_contact_ratio == pytest.approx(1.7547, abs=1e-4)
    cfg = tmp_path / "warned.toml"
    cfg.write_text(text)
    assert cli(["geometry", str(cfg), "--out", str(tmp_path / "out")]) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert err == [f"gearpipe geometry: warning: {message}"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        gearbox_from_text(_edit(SPUR, r"^\[dynamics\]", _pitch([0.0, 3.0, 2.0])))  # all used


def test_planetary_pitch_errors_are_checked_on_each_mesh():
    """[contact] applies to both meshes of a planetary set: epsilon_alpha 1.6352 / 1.8897
    (both: pairs k = 0, 1), so on the nominal path the third entry is unused on each, one line
    per mesh; with tip contact the ring mesh's pair 2 touches at the planet's tip corner (its
    tip zone reaches 2.8 base pitches), the sun mesh's does not (1.874); more entries than
    the planet's 20 teeth are refused."""
    with pytest.warns(InputWarning) as record:
        gearbox_from_text(PLANETARY)
    assert [str(r.message) for r in record] == [
        "contact.pitch_errors_um[2:] = [-2] um change nothing: only tooth pairs k = 0 to 1 "
        "mesh in the analysed mesh cycle of the sun_planet mesh (pair k touches when k < "
        "1.874, the path of contact and the tip zone past its end in base pitches)"]
    with pytest.warns(InputWarning) as record:
        gearbox_from_text(PLANETARY.replace("[contact]\n", "[contact]\ntip_contact = false\n"))
    assert [str(r.message) for r in record] == [
        f"contact.pitch_errors_um[2:] = [-2] um change nothing: only tooth pairs k = 0 to 1 "
        f"mesh in the analysed mesh cycle of the {name} mesh (pair k meshes when k < "
        f"transverse contact ratio {eps})" for name, eps in (("sun_planet", "1.635"),
                                                             ("planet_ring", "1.89"))]
    with pytest.raises(InputError) as info:
        gearbox_from_text(PLANETARY.replace("[0.0, 3.0, -2.0]", str([1.0] * 21)))
    assert str(info.value) == (
        "contact.pitch_errors_um = [1, 1, 1, 1, 1, 1, ...] um has 21 entries, more than the "
        "20 teeth of the planet of the sun_planet mesh: entry k offsets tooth pair k of the "
        "mesh cycle, and pairs k and k + 20 would share a tooth (allowed: at most 20 entries)")


def _te(extra: str):
    """Loaded TE (m) of the z 50/50 pair over 24 positions with ``extra`` [contact] keys,
    the cycle and its source."""
    text = _edit(SPUR, r"^\[dynamics\]", f"[contact]\npositions = 24\n{extra}\n[dynamics]")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputWarning)
        box = gearbox_from_text(text)
    src = analytical_compliance(box.actual_pair, box.operation, box.contact, box.stiffness)
    return analyse_contact(src, box.operation, box.contact), src


@pytest.mark.parametrize("local", ["weber", "linear"])
def test_an_accepted_pitch_error_shifts_the_loaded_te_by_the_model_amount(local):
    """A pitch error e of pair k adds e to that pair's gaps (``eps``), nothing else.

    * Where pair 0 carries the load alone (single tooth contact, pair 1 out of the path),
      the same load gives the same deflection, so the approach, the loaded TE, rises by e
      exactly, whatever the local contact model (e = 2 um on pair 0).
    * Where pairs 0 and 1 share the load, both loaded: with the linear local contact and one
      slice per pair (spur, no crowning) each pair is a spring of compliance c_k (the
      diagonal of its compliance: the slices of different teeth are uncoupled), and
      ``x = e_0 + c_0 F_0 = e_1 + c_1 F_1``, ``F_0 + F_1 = P`` give
      ``dx = e_1 c_0 / (c_0 + c_1)`` for e_1 = 2 um on pair 1 (to 1e-18 m).
    * An entry for pair 2, which never meshes (epsilon_alpha = 1.755), changes nothing.

    Contact confined to the nominal path (``tip_contact = false``): with tip contact the
    corners share the load in single contact (:func:`test_pitch_error_of_a_corner_pair`).
    """
    from pipeline.stiffness.tooth import hertz_compliance

    key = f'local_contact = "{local}"\ntip_contact = false'
    base, src = _te(key)
    on0, _ = _te(f"{key}\npitch_errors_um = [2.0]")
    on1, _ = _te(f"{key}\npitch_errors_um = [0.0, 2.0]")
    on2, _ = _te(f"{key}\npitch_errors_um = [0.0, 2.0, 5.0]")
    e = 2e-6
    k1 = list(base.pair_index).index(1)
    single = base.pair_loads[:, k1] == 0.0
    assert 3 <= single.sum() < len(base)
    np.testing.assert_allclose((on0.transmission_error - base.transmission_error)[single],
                               e, rtol=1e-9)
    np.testing.assert_array_equal(on2.transmission_error, on1.transmission_error)
    shift = on1.transmission_error - base.transmission_error
    np.testing.assert_array_equal(shift[single], 0.0)
    assert np.all(on1.pair_loads[~single][:, k1] > 0)  # both pairs stay loaded
    if local == "linear":
        pair = src.pair
        hertz = hertz_compliance(pair.pinion, pair.gear)
        expected = []
        for s0 in base.s0[~single]:
            pts = src.points(float(s0))
            c = np.diag(src.matrix(float(s0))) + hertz / pts.width
            inside = (pts.s >= pair.s_start) & (pts.s <= pair.s_end)
            c0, c1 = (c[inside & (pts.pair == k)][0] for k in (0, 1))
            expected.append(e * c0 / (c0 + c1))
        np.testing.assert_allclose(shift[~single], expected, rtol=0, atol=1e-18)
    # the shift lies between none and the whole error: 0.43-0.58 e here
    assert np.all((shift[~single] > 0.4 * e) & (shift[~single] < 0.6 * e))


@pytest.mark.parametrize(("config", "pairs", "tip_pairs", "tip_loaded"), [
    ("spur_pair_assembly_errors", 2, 3, 2), ("traction_helical_pair", 3, 3, 3),
    ("planet_ring_pair", 2, 3, 3)])
def test_the_pairs_that_mesh_are_those_the_contact_solve_sees(config, pairs, tip_pairs,
                                                              tip_loaded):
    """Which entries can act, seen from the solver: over 60 positions of the cycle the tooth
    pairs k >= 0 with candidate points that can touch are exactly k = 0 .. meshing_pairs - 1:
    on the nominal path ceil(epsilon_alpha) - 1, for a spur pair (epsilon_alpha 1.755), a
    helical pair (2.052, where pair k = -1 also meshes through the far face end and has no
    entry) and an internal pair (1.938); with tip contact also the pair whose tip corner
    can touch past the end of the path (k = 2: loaded on the ring pair; on the spur pair it
    stays 40 um or more from its mate at 340 N m, a candidate that carries nothing)."""
    import dataclasses

    from pipeline.config import load_gearbox
    from pipeline.contact.separations import meshing_pairs

    box = load_gearbox(CONFIGS / f"{config}.toml")
    pair = box.actual_pair
    assert pairs == int(np.ceil(pair.transverse_contact_ratio))
    for tip, n, m in ((False, pairs, pairs), (True, tip_pairs, tip_loaded)):
        opts = dataclasses.replace(box.contact, positions=60, tip_contact=tip)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            cycle = analyse_contact(analytical_compliance(pair, box.operation, opts,
                                                          box.stiffness), box.operation, opts)
        can_touch = set(cycle.point_pair[np.isfinite(cycle.point_separation)].tolist())
        assert meshing_pairs(pair, tip) == n
        assert {k for k in can_touch if k >= 0} == set(range(n))
        loaded = {k for k in cycle.point_pair[cycle.point_load > 0].tolist() if k >= 0}
        assert loaded == set(range(m))


def test_a_density_beside_both_mass_and_inertia_is_one_warning(tmp_path, capsys):
    """The density sets only the derived mass and inertia; with both given it is unused (a
    material is stated whole, so this is a warning, not a refusal)."""
    text = _edit(SPUR, r"^bore_radius_mm = 21.0$",
                 "bore_radius_mm = 21.0\nmass_kg = 2.52\ninertia_kgm2 = 7.4e-3")
    message = ("pinion.material.density_kg_m3 = 7850 kg/m^3 changes nothing: [pinion] gives "
               "both mass_kg and inertia_kgm2, the only quantities the density sets")
    with pytest.warns(InputWarning) as record:
        box = gearbox_from_text(text)
    assert [str(r.message) for r in record] == [message]
    assert (box.bodies["pinion"].mass_, box.bodies["pinion"].inertia_) == (2.52, 7.4e-3)
    cfg = tmp_path / "warned.toml"
    cfg.write_text(text)
    assert cli(["modes", str(cfg), "--out", str(tmp_path / "out")]) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert err == [f"gearpipe modes: warning: {message}"]


def test_pitch_error_of_a_corner_pair():
    """With tip contact pair 1 goes on touching at the pinion's tip corner after it has left
    the path (the single-contact part of the nominal cycle), so its pitch error acts there
    too: 2 um on it raises the loaded TE at those positions by less than the error (the
    corner shares the load), where on the nominal path it changed nothing."""
    base, src = _te("")
    on1, _ = _te("pitch_errors_um = [0.0, 2.0]")
    past = base.s0 + src.pair.base_pitch > src.pair.s_end  # pair 1 past the end of the path
    k1 = list(base.pair_index).index(1)
    corner = past & (base.pair_loads[:, k1] > 0)
    assert corner.sum() >= 2
    shift = on1.transmission_error - base.transmission_error
    assert np.all((shift[corner] > 0) & (shift[corner] < 2e-6))
