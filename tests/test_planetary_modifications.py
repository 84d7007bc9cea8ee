"""Per-gear flank modifications of a planetary set (``[sun.modifications]``,
``[planet.modifications]``, ``[ring.modifications]``): each mesh's contact options
(:meth:`pipeline.config.gearbox.Gearbox.mesh_contact`) and loaded cycle are those of the
same two gears run as a pair with the same tables (sun + planet; planet + internal ring),
bit for bit, on rigid supports and through the shafts' fixed point; the gap at the ends of
each path of contact is the sum of the two flanks' amounts as defined (ISO 21771:2007, 7.3:
tip relief C_a reached at the active tip, here the ring's smaller diameter); the rating reads
each mesh's tip reliefs; the short form is unchanged; refusals name the key."""

from __future__ import annotations

import copy
import dataclasses
import tomllib
from pathlib import Path

import numpy as np
import pytest

from pipeline.cache.folder import Cache
from pipeline.config.gearbox import gearbox_from_dict
from pipeline.contact.analysis import analyse_contact
from pipeline.contact.compliance import compliance_source
from pipeline.contact.cycle_io import cycle_arrays
from pipeline.contact.modifications import flank_frames, modification_gap
from pipeline.geometry.pair import GearPair
from pipeline.progress import Steps
from pipeline.run.chain import RunOptions, mesh_stages
from pipeline.run.rating_inputs import gear_inputs
from pipeline.validation import InputError
from pipeline.verification.cases_planetary_modifications import GEARS, MESHES, mesh_pair_doc

CONFIGS = Path(__file__).resolve().parents[1] / "workflows" / "configs"
EXAMPLE = tomllib.loads((CONFIGS / "planetary_modifications.toml").read_text(encoding="utf-8"))
SHAFTS = tomllib.loads((CONFIGS / "shaft_planetary.toml").read_text(encoding="utf-8"))
OPTIONS = RunOptions(show_progress=False, cache=Cache.off())


def _equivalent_pair(doc: dict, planetary, mesh: str, stages):
    """The pair of the two gears of ``mesh`` at the set's centre distance, loaded like the
    planetary mesh (its pinion's torque and speed relative to the carrier)."""
    box = gearbox_from_dict(mesh_pair_doc(doc, mesh))
    pair = GearPair(box.gears["pinion"], box.gears["gear"],
                    planetary.planetary.carrier_radius)
    return dataclasses.replace(box, pair=pair, operation=stages[mesh].case.operation)


def _assert_same_cycle(a, b) -> None:
    x, y = cycle_arrays(a), cycle_arrays(b)
    assert x.keys() == y.keys()
    for k in x:
        assert np.array_equal(x[k], y[k], equal_nan=x[k].dtype.kind in "fc"), k


@pytest.fixture(scope="module")
def example():
    box = gearbox_from_dict(EXAMPLE)
    return box, mesh_stages(box, OPTIONS, Steps("", enabled=False))


def test_each_mesh_is_its_pair_bit_for_bit(example):
    """Sun-planet = the pair sun + planet, planet-ring = the internal pair planet + ring, each
    with the same per-gear tables: equal contact options and every array of the loaded cycle
    equal bit for bit. The modifications act: each mesh's TE peak-to-peak differs from the
    unmodified set's by more than 1 um."""
    box, stages = example
    plain = copy.deepcopy(EXAMPLE)
    for g in GEARS:
        plain[g].pop("modifications")
    bare = mesh_stages(gearbox_from_dict(plain), OPTIONS, Steps("", enabled=False))
    for mesh in MESHES:
        pair_box = _equivalent_pair(EXAMPLE, box, mesh, stages)
        assert pair_box.mesh_contact("mesh") == box.mesh_contact(mesh)
        alone = mesh_stages(pair_box, OPTIONS, Steps("", enabled=False))["mesh"]
        _assert_same_cycle(stages[mesh].contact, alone.contact)
        te = [np.ptp(s.contact.transmission_error) for s in (stages[mesh], bare[mesh])]
        print(mesh, te)
        assert abs(te[0] - te[1]) > 1e-6


def test_gap_at_the_ends_of_each_path_is_both_flanks_amounts(example):
    """At mid-face, where no lead modification acts: at the start of the sun-planet path
    (the planet's tip, the sun's start of active profile) the planet's tip relief 15 um plus
    its profile crowning 2 um (C_alpha at both ends of the active flank); at its end (the
    sun's tip) the sun's 14 um plus the planet's crowning at its root end, 2 um. At the
    start of the planet-ring path the ring's tip, its smaller diameter 234 mm = m (z - 2):
    the ring's 10 um plus the planet's 2 um; at the end the planet's tip, 15 + 2 um. At face
    1 (z = 0) the ring's end relief adds 4 um and the sun's lead crowning 5 um."""
    box, _ = example
    want = {"sun_planet": ((17e-6, 16e-6), (22e-6, 21e-6)),
            "planet_ring": ((12e-6, 17e-6), (16e-6, 21e-6))}
    for mesh, pair in box.contact_meshes():
        flanks = box.mesh_contact(mesh).modifications.flanks
        ends = np.array([pair.s_start, pair.s_end])
        for z, values in zip((0.5 * pair.face_width, 0.0), want[mesh], strict=True):
            gap = modification_gap(pair, ends, np.full(2, z), flanks)
            np.testing.assert_allclose(gap, values, rtol=0, atol=1e-15)
    ring = flank_frames(box.planetary.planet_ring)[1]
    assert ring.diameter(box.planetary.planet_ring.s_start) == pytest.approx(0.234, abs=1e-12)


def test_shafts_fixed_point_takes_each_meshs_flanks(tmp_path):
    """The example with shafts (sun on its shaft, planets on pins) and the per-gear tables:
    each mesh's cycle of the fixed point is the equivalent pair's, solved with the same lead
    gap (the shafts' misalignment at the last iteration), bit for bit."""
    doc = copy.deepcopy(SHAFTS)
    for g in GEARS:
        doc[g]["modifications"] = copy.deepcopy(EXAMPLE[g]["modifications"])
    box = gearbox_from_dict(doc)
    stages = mesh_stages(box, RunOptions(show_progress=False, cache=Cache(tmp_path)),
                         Steps("", enabled=False))
    sh = stages["sun_planet"].shafts.system
    for mesh in MESHES:
        pair_box = _equivalent_pair(doc | {"sun": {k: v for k, v in doc["sun"].items()
                                                   if k != "shaft"},
                                           "planet": {k: v for k, v in doc["planet"].items()
                                                      if k != "shaft"}},
                                    box, mesh, stages)
        opts = pair_box.mesh_contact("mesh")
        gap = tuple(zip(sh.z[mesh].tolist(), sh.gaps[mesh].tolist(), strict=True))
        opts = dataclasses.replace(opts, modifications=dataclasses.replace(
            opts.modifications, lead_gap=gap))
        st = stages[mesh]
        source = compliance_source(pair_box.pair, st.case.operation, opts, box.stiffness,
                                   None, model=st.stiffness.model)
        _assert_same_cycle(st.contact, analyse_contact(source, st.case.operation, opts,
                                                       warn=False))
        assert np.ptp(sh.gaps[mesh]) > 1e-6  # the shafts do open a misalignment


def test_rating_reads_each_meshs_tip_relief():
    """ISO 6336-1's K_v takes C_a of each gear in each mesh: the sun's 14 um and the planet's
    15 um in the sun-planet mesh, the planet's 15 um and the ring's 10 um in the planet-ring
    mesh."""
    box = gearbox_from_dict(EXAMPLE | {"rating": {}})
    got = {(m, r): gear_inputs(box, m, r, k).tip_relief for m, roles in MESHES.items()
           for k, r in enumerate(roles)}
    assert got == {("sun_planet", "sun"): pytest.approx(14e-6, abs=1e-18),
                   ("sun_planet", "planet"): pytest.approx(15e-6, abs=1e-18),
                   ("planet_ring", "planet"): pytest.approx(15e-6, abs=1e-18),
                   ("planet_ring", "ring"): pytest.approx(10e-6, abs=1e-18)}


def test_titles_name_each_meshs_gears(example):
    """The line the load maps' titles carry names the mesh's gears, not pinion and gear."""
    box, _ = example
    assert box.mesh_contact("sun_planet").modifications.describe(
        box.mesh_gears("sun_planet")) == (
        "sun: tip relief 14 um from d 122 mm (parabolic), lead crowning 5 um; planet: tip "
        "relief 15 um over 4 mm (linear), profile crowning 2 um")
    assert box.mesh_contact("planet_ring").modifications.describe(
        box.mesh_gears("planet_ring")) == (
        "planet: tip relief 15 um over 4 mm (linear), profile crowning 2 um; ring: tip relief "
        "10 um from d 237 mm (linear), end relief face 1 4 um, end relief face 2 4 um")


def test_short_form_is_the_contact_table_of_both_meshes():
    """Without per-gear tables each mesh takes ``[contact]`` itself (the short form as
    before: the same object, so the same cache keys and cycles)."""
    doc = copy.deepcopy(EXAMPLE)
    for g in GEARS:
        doc[g].pop("modifications")
    doc["contact"] |= {"tip_relief_pinion_um": 10.0, "tip_relief_length_pinion_mm": 3.0,
                       "crowning_um": 4.0}
    box = gearbox_from_dict(doc)
    assert box.gear_modifications == {}
    for mesh in MESHES:
        assert box.mesh_contact(mesh) is box.contact


def _refusal(edit) -> str:
    doc = copy.deepcopy(EXAMPLE)
    edit(doc)
    with pytest.raises(InputError) as exc:
        gearbox_from_dict(doc)
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


@pytest.mark.parametrize(("edit", "expected"), [
    (lambda d: d["contact"].update(crowning_um=4.0),
     "contact.crowning_um is the short form of [sun.modifications], [planet.modifications] "
     "and [ring.modifications]: give it in [sun.modifications] instead (the file has both)"),
    (lambda d: d["ring"]["modifications"].update(tip_relief_start_diameter_mm=250.0),
     "ring.modifications.tip_relief_start_diameter_mm = 250 mm is outside the allowed range "
     "[234, 245.059] mm (the ring's active flank of the planet_ring mesh)"),
    (lambda d: d["sun"]["modifications"].update(tip_relief_start_diameter_mm=127.0),
     "sun.modifications.tip_relief_start_diameter_mm = 127 mm is outside the allowed range "
     "[116.01, 126] mm (the sun's active flank of the sun_planet mesh)"),
    # 15 mm fits the planet's flank towards the ring (16.7 mm) but not towards the sun
    (lambda d: d["planet"]["modifications"].update(tip_relief_length_mm=15.0),
     "planet.modifications.tip_relief_length_mm = 15 mm is outside the allowed range "
     "[0, 14.4819] mm (the planet's active flank of the sun_planet mesh)"),
    (lambda d: d["ring"]["modifications"].update(end_relief_face1_length_mm=20.0,
                                                 end_relief_face2_length_mm=20.0),
     "ring.modifications.end_relief_face1_length_mm + ring.modifications."
     "end_relief_face2_length_mm = 40 mm is more than the ring's face width 30 mm"),
    (lambda d: d["planet"]["modifications"].update(flank="sun"),
     "[planet.modifications] key 'flank' is not known"),
])
def test_refused_in_one_line_naming_the_key(edit, expected):
    msg = _refusal(edit)
    assert msg.startswith(expected), msg


def test_single_gear_file_refuses_modifications():
    doc = {"gear": dict(EXAMPLE["sun"])}
    with pytest.raises(InputError) as exc:
        gearbox_from_dict(doc)
    assert str(exc.value) == ("[gear.modifications] is read for gears in mesh (a pair or a "
                              "planetary set); this file describes a single gear")


def test_herringbone_stage_takes_the_sun_planet_flanks(tmp_path):
    """The herringbone set of Xu et al. (2020) with its groove (coarse: 8 positions, 6
    slices, a 60 mm groove mesh) and per-gear tables: the contact of both halves through the
    groove is the one solved with the pair sun + planet's contact options, bit for bit, and
    not the one without them (the sun's 10 um lead crowning and the planet's 5 um profile
    crowning change the halves' load)."""
    from pipeline.contact.herringbone import GrooveFlankCoupling
    from pipeline.run.chain import mesh_cases, static_stages
    from pipeline.run.herringbone import cached_herringbone_cycle

    text = (CONFIGS / "wind_turbine_herringbone_planetary.toml").read_text(encoding="utf-8")
    doc = tomllib.loads(text[:text.index("\n[dynamics]")])
    doc["contact"] |= {"positions": 8, "slices": 6}
    doc["groove"]["mesh_size_mm"] = 60.0
    doc["sun"]["modifications"] = {"lead_crowning_um": 10.0}
    doc["planet"]["modifications"] = {"profile_crowning_um": 5.0}
    box = gearbox_from_dict(doc)
    options = RunOptions(show_progress=False, cache=Cache(tmp_path))
    case = mesh_cases(box)[0]
    hb = static_stages(box, case, options, Steps("", enabled=False)).herringbone
    pair_doc = mesh_pair_doc({k: v for k, v in doc.items() if k not in ("groove", "herringbone")},
                         "sun_planet")
    contact = gearbox_from_dict(pair_doc).mesh_contact("mesh")
    assert contact == box.mesh_contact("sun_planet") != box.contact
    coupling = GrooveFlankCoupling.from_matrix(hb.groove.coupling_matrix)
    cycles = [cached_herringbone_cycle(hb.pair, hb.operation, coupling, 4, c, box.stiffness,
                                       box.herringbone, cache=options.cache,
                                       cycle_cache=Cache.off())[0]
              for c in (contact, box.contact)]
    for half in ("left", "right"):
        _assert_same_cycle(getattr(hb.cycle, half), getattr(cycles[0], half))
        assert not np.array_equal(getattr(hb.cycle, half).transmission_error,
                                  getattr(cycles[1], half).transmission_error)


def test_report_names_each_meshs_gears_and_draws_both_maps(tmp_path):
    """``gearpipe run`` of the example: each mesh's report lists its two gears' tables in
    their own names and units (sun-planet: sun 14 um from d 122 mm, planet 15 um over 4 mm;
    planet-ring: planet 15 um, ring 10 um from d 237 mm and 4 um end reliefs) with its
    modification map."""
    import json

    from pipeline.cli import main as cli

    out = tmp_path / "run"
    assert cli(["run", str(CONFIGS / "planetary_modifications.toml"), "--out", str(out),
                "--cache-dir", str(tmp_path / "c")]) == 0
    want = {"sun_planet": {"sun_tip_relief": 14.0, "planet_tip_relief": 15.0,
                           "sun_lead_crowning": 5.0, "planet_profile_crowning": 2.0},
            "planet_ring": {"planet_tip_relief": 15.0, "ring_tip_relief": 10.0,
                            "ring_end_relief_face1": 4.0, "ring_end_relief_face2": 4.0,
                            "planet_profile_crowning": 2.0}}
    starts = {"sun_planet": {"sun": "diameter 122 mm", "planet": "roll length 4 mm from the "
                             "active tip"},
              "planet_ring": {"planet": "roll length 4 mm from the active tip",
                              "ring": "diameter 237 mm"}}
    for mesh, values in want.items():
        report = json.loads((out / f"{mesh}_report.json").read_text())
        section = report["sections"]["modifications"]
        q = section["quantities"]
        got = {k: v["value"] for k, v in q.items() if v["unit"] == "um"
               and not k.startswith(("pitch", "assembly"))}
        assert got == pytest.approx(values, abs=1e-12)
        assert {k: q[f"{k}_tip_relief_start"]["value"] for k in starts[mesh]} == starts[mesh]
        assert [f["file"] for f in section["figures"]] == [f"{mesh}_report_modifications.png"]
        assert (out / f"{mesh}_report_modifications.png").stat().st_size > 10_000
