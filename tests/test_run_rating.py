"""The rating step of a run (pipeline.run.rating): what it takes from the run, checked
against the rating chain called directly with the same inputs, and the refusals.

The chain itself is checked against ISO/TR 6336-30 and KISSsoft's reports in the
``test_rating_*`` files; here: that the run hands it the right K_Hbeta (method C, the
loaded contact's, a number), K_gamma (a planetary set's default, computed from the
dynamic model's planets), K_v (the larger of a planetary set's meshes), the planet as an
idler, the load cycles of the sun and ring per planet, and that the summary, the report and
the study KPIs carry its numbers.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

from pipeline.cache.folder import Cache
from pipeline.config.gearbox import gearbox_from_text
from pipeline.rating.pair_rating import GearRatingInputs, RatingInputs, rate_pair
from pipeline.run.chain import RunOptions
from pipeline.run.runner import run_pipeline
from pipeline.validation import InputError
from workflows.default_case import DEMO_PAIR

WORKFLOWS = Path(__file__).resolve().parents[1] / "workflows"
FAST = '[contact]\ncompliance = "analytical"\npositions = 24\n'

PLANETARY = """
name = "spur_planetary"
[sun]
teeth = 21
module_mm = 15.0
pressure_angle_deg = 25.0
face_width_mm = 185.0
[planet]
teeth = 37
module_mm = 15.0
pressure_angle_deg = 25.0
face_width_mm = 175.0
bore_radius_mm = 100.0
[ring]
teeth = 95
module_mm = 15.0
pressure_angle_deg = 25.0
face_width_mm = 185.0
internal = true
rim_outer_radius_mm = 799.5
[carrier]
mass_kg = 2273.1
inertia_kgm2 = 440.1
[planetary]
planets = 4
[operation]
torque_Nm = 74000.0
speed_rpm = 96.67
"""
"""A spur planetary set with the gears of Xu et al. (2020)'s wind-turbine stage (z 21/37/95,
m_n 15 mm, 25 deg, four planets)."""


def _run(text: str, tmp_path):
    box = gearbox_from_text(text, "box")
    return run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))


def _direct(result, name, k_hbeta, roles=("pinion", "gear"), mesh="pair", planets=1, **kw):
    """rate_pair on the run's own mesh with the run's own inputs (the defaults)."""
    box = result.gearbox
    st = result.meshes[name]
    g = [box.rating.gear(r) for r in roles]
    gears = tuple(GearRatingInputs(sigma_hlim=x.sigma_hlim, sigma_flim=x.sigma_flim,
                                   mean_stress_factor=0.7 if r == "planet" else 1.0)
                  for x, r in zip(g, roles, strict=True))
    inputs = RatingInputs(application_factor=1.25, life_hours=20000.0, accuracy_grade=6,
                          viscosity_40=220e-6, k_hbeta=k_hbeta, face_load=box.rating.method_c,
                          **kw)
    op = st.case.operation
    return rate_pair(st.stiffness.actual, op.torque, op.speed * 30 / math.pi, inputs, gears,
                     mesh, planets)


def test_pair_takes_method_c_the_contact_or_a_number(tmp_path):
    """The default K_Hbeta is method C's; "contact" takes the loaded contact's (the line
    load's largest over its mean: 1.589 with a 15 um slope deviation, 1.8 % below ISO
    6336-1's Eq. (41) for the same misalignment, 1 + F_betay c_gamma_beta / (2 F_m / b) =
    1.619 with c_gamma_beta = 0.85 c_gamma_alpha of method B: the contact's own mesh
    stiffness is lower than ISO's); a number is used as given. Each run's S_H and S_F equal
    rate_pair's with that K_Hbeta to the last bit, and the others are shown beside it."""
    slope = FAST + "slope_deviation_um = 15.0\n"
    runs = {src: _run(DEMO_PAIR + slope + f"[rating]\nface_load_factor = {src}\n", tmp_path)
            for src in ('"method_c"', '"contact"', "1.4")}
    contact_khb = runs['"contact"'].distributions["mesh"].distribution.k_hbeta
    r = runs['"contact"'].rating.meshes["mesh"].rating
    eq41 = 1 + 15e-6 * 0.85 * r.mesh_stiffness / (2 * r.tangential_load / 0.020)
    assert eq41 == pytest.approx(1.619, abs=5e-4)
    assert contact_khb == pytest.approx(1.589, abs=5e-4)
    assert contact_khb / eq41 - 1 == pytest.approx(-0.018, abs=1e-3)
    method_c = runs['"method_c"'].rating.meshes["mesh"].rating.face_load.k_hbeta
    for src, khb in (('"method_c"', None), ('"contact"', contact_khb), ("1.4", 1.4)):
        m = runs[src].rating.meshes["mesh"]
        want = _direct(runs[src], "mesh", khb)
        assert m.rating.k_hbeta == (method_c if khb is None else khb)
        assert [p.safety for p in m.rating.pitting] == [p.safety for p in want.pitting]
        assert [b.safety for b in m.rating.bending] == [b.safety for b in want.bending]
        assert m.k_hbeta_contact == contact_khb
        assert m.rating.face_load.k_hbeta == method_c
    sources = {src: r.rating.meshes["mesh"].k_hbeta_source for src, r in runs.items()}
    assert sources == {'"method_c"': "ISO 6336-1 method C", '"contact"': "loaded contact",
                       "1.4": "given"}
    # the larger K_Hbeta lowers S_H by sqrt of the ratio (same K_v, K_Halpha = 1)
    s = {src: r.rating.smallest("pitting")[0] for src, r in runs.items()}
    assert s["1.4"] / s['"contact"'] == pytest.approx(math.sqrt(contact_khb / 1.4), rel=1e-9)


def test_pair_summary_and_verdict(tmp_path):
    """The run summary's verdict names the smallest S_H and S_F and the gear; the z 50/50
    demo pair's gears are alike, so the pinion (the first) is named."""
    r = _run(DEMO_PAIR + FAST + "[rating]\n", tmp_path)
    summary = r.summary()["rating"]
    s_h, gear, mesh = r.rating.smallest("pitting")
    assert (gear, mesh) == ("pinion", "mesh")
    assert summary["safety_pitting_min"] == s_h
    assert summary["verdict"] == (f"S_H min {s_h:.3f} (pinion); S_F min "
                                  f"{r.rating.smallest('bending')[0]:.3f} (pinion)")
    pair = summary["meshes"]["mesh"]
    assert pair["pinion"]["S_H"] == pytest.approx(pair["gear"]["S_H"], rel=1e-12)
    assert pair["K_gamma_source"] == "single mesh"


def test_planetary_set_every_mesh(tmp_path):
    """Both meshes rated: K_gamma 1.25 by default for four planets (IEC 61400-4 / AGMA
    6123), K_v the larger of the two meshes' (KISSsoft's KV = max(KV12, KV23)), the planet
    an idler (Y_M 0.7) in both meshes, the sun and the ring four load cycles per revolution
    relative to the carrier, the ring not rated in bending without its cutter (the note
    names the key)."""
    r = _run(PLANETARY + FAST + "[rating]\n", tmp_path)
    sp, pr = r.rating.meshes["sun_planet"], r.rating.meshes["planet_ring"]
    assert sp.gears == ("sun", "planet") and pr.gears == ("planet", "ring")
    assert sp.rating.load_sharing == pr.rating.load_sharing == 1.25
    assert sp.load_sharing_source == "default for 4 planets"
    own = {n: _direct(r, n, None, m.gears, mesh=n, planets=4, load_sharing=1.25).dynamic
           for n, m in r.rating.meshes.items()}
    assert own["planet_ring"].factor > own["sun_planet"].factor
    assert sp.rating.dynamic == pr.rating.dynamic == own["planet_ring"]
    assert sp.rating.bending[1].mean_stress_factor == 0.7
    assert pr.rating.bending[0].mean_stress_factor == 0.7
    assert sp.rating.bending[0].mean_stress_factor == 1.0
    assert pr.rating.bending[1] is None
    assert pr.unrated == (None, "ring: give rating.ring.cutter_teeth (its pinion-type cutter "
                                "sets its root section)")
    rel = r.meshes["sun_planet"].case.operation.speed * 30 / math.pi  # sun, carrier frame
    assert sp.rating.cycles[0] == pytest.approx(rel * 60 * 20000 * 4, rel=1e-12)
    assert sp.rating.cycles[1] == pytest.approx(rel * 21 / 37 * 60 * 20000, rel=1e-12)
    assert pr.rating.cycles[1] == pytest.approx(rel * 21 / 95 * 60 * 20000 * 4, rel=1e-12)


def test_planet_load_sharing_computed_from_the_dynamic_model(tmp_path):
    """``load_sharing = "computed"`` takes the dynamic model's planets: equally spaced, equal
    planets without errors share the load equally (K_gamma 1 to 1e-5); without a [dynamics]
    table it is refused in one line."""
    dyn = '[dynamics]\nexcitation = "analytical"\n'
    r = _run(PLANETARY + FAST + dyn + '[rating]\nload_sharing = "computed"\n', tmp_path)
    m = r.rating.meshes["sun_planet"]
    assert m.load_sharing_source == "computed"
    assert m.rating.load_sharing == pytest.approx(1.0, abs=1e-5)
    assert m.k_gamma_computed == m.rating.load_sharing
    assert m.dynamic_factor_model > 1.0
    with pytest.raises(InputError, match=r'load_sharing = "computed" .* needs a \[dynamics\]'):
        _run(PLANETARY + FAST + '[rating]\nload_sharing = "computed"\n', tmp_path)


def test_rating_inputs_refused_where_they_enter():
    """One line naming the key: a pair has no K_gamma, an unknown gear table, two oils, a
    through-hardened material without its hardness, a core hardness beside both stresses."""
    cases = {
        "[rating]\nload_sharing = 1.2\n": "rating.load_sharing = 1.2 applies to a planetary",
        "[rating.wheel]\n": r"\[rating\] key 'wheel' is not known",
        "[rating]\noil_grade = \"VG 220\"\noil_viscosity_40_mm2_per_s = 220\n":
            "keep one",
        "[rating.gear]\nmaterial = \"through_hardened_alloy\"\n":
            r"rating.gear.surface_hardness_HV is needed: .* \(allowed 200 to 360 HV\)",
        ("[rating.gear]\nsigma_Hlim_MPa = 1400\nsigma_Flim_MPa = 400\n"
         "core_hardness = \"30HRC\"\n"): "rating.gear.core_hardness selects ISO 6336-5's",
        "[rating]\nlife_h = 0\n":
            r"rating.life_h = 0 h is outside the allowed range \(0, 1e\+07\] h",
    }
    for extra, message in cases.items():
        with pytest.raises(InputError, match=message):
            gearbox_from_text(DEMO_PAIR + extra)


def test_load_spectrum_of_one_bin_is_the_constant_load_rating(tmp_path):
    """ISO 6336-6 in a run: a spectrum of one bin at K_A times the operating torque for the
    required life gives the constant-load rating's S_H and S_F (the spectrum stands for K_A:
    its bins are rated with K_A = 1) to 1e-9; a second, lighter bin adds cycles but, below
    the endurance limit here, no damage, and leaves the safety unchanged; a bin's bad key is
    refused naming its index."""
    bins = ("[[rating.spectrum]]\ntorque_Nm = 425.0\nspeed_rpm = 2340.0\n"
            "duration_h = 20000.0\n")
    r = _run(DEMO_PAIR + FAST + "[rating]\n" + bins, tmp_path)
    m = r.rating.meshes["mesh"]
    for k in range(2):
        assert m.spectrum.pitting[k].safety == pytest.approx(m.rating.pitting[k].safety,
                                                             rel=1e-9)
        assert m.spectrum.bending[k].safety == pytest.approx(m.rating.bending[k].safety,
                                                             rel=1e-9)
    light = bins + ("[[rating.spectrum]]\ntorque_Nm = 100.0\nspeed_rpm = 2340.0\n"
                    "duration_h = 500.0\n")
    r2 = _run(DEMO_PAIR + FAST + "[rating]\n" + light, tmp_path)
    m2 = r2.rating.meshes["mesh"]
    assert m2.spectrum.pitting[0].damage[1] == 0.0
    assert m2.spectrum.pitting[0].safety == m.spectrum.pitting[0].safety
    assert "spectrum (ISO 6336-6): S_H min" in r2.rating.line()
    with pytest.raises(InputError, match=r"rating\.spectrum\[0\]\.torque_kNm is not a key"):
        gearbox_from_text(DEMO_PAIR + "[[rating.spectrum]]\ntorque_kNm = 1.0\n")


def test_ring_rated_in_bending_with_its_cutter(tmp_path):
    """Given its pinion-type cutter (and, through-hardened, its proof stress for the slip
    layer), the ring is rated in bending: its nominal root stress is iso_root_stress's for
    the section that cutter generates, its S_F = sigma_FG / sigma_F; without the proof
    stress a through-hardened ring is not rated and the note names the key."""
    from pipeline.contact.iso_root_stress import ShaperCutter, iso_root_stress

    ring = ('[rating.ring]\nmaterial = "through_hardened_alloy"\nsurface_hardness_HV = 300\n'
            "cutter_teeth = 30\ncutter_tip_radius_coef = 0.15\n")
    r = _run(PLANETARY + FAST + "[rating]\n" + ring + "proof_stress_MPa = 900\n", tmp_path)
    m = r.rating.meshes["planet_ring"]
    b, root = m.rating.bending[1], m.rating.roots[1]
    pair = r.meshes["planet_ring"].stiffness.actual
    want = iso_root_stress(pair.gear, pair, m.rating.tangential_load,
                           cutter=ShaperCutter(30, tip_radius_coef=0.15))
    assert root.sigma_f0 == want.sigma_f0 and root.s_fn == want.s_fn
    assert b.safety == pytest.approx(b.limit / b.stress, rel=1e-14)
    assert m.unrated == (None, None)
    r2 = _run(PLANETARY + FAST + "[rating]\n" + ring, tmp_path)
    assert r2.rating.meshes["planet_ring"].rating.bending[1] is None
    assert "rating.ring.proof_stress_MPa" in r2.rating.meshes["planet_ring"].unrated[1]


def test_study_kpis_are_the_runs_smallest_safety_factors(tmp_path):
    """The study KPIs safety_pitting_min and safety_bending_min of a point equal the
    smallest S_H and S_F of the run's rating of the same file; they are left out of a
    study's default KPIs without a [rating] table, and asking for one then is refused."""
    import tomllib

    from pipeline.study.evaluate import evaluate_point
    from pipeline.study.kpis import KPI_BY_NAME, select_kpis

    text = DEMO_PAIR + FAST + "[rating]\n"
    kpis = select_kpis(("safety_pitting_min", "safety_bending_min"), False, rating=True)
    row = evaluate_point(tomllib.loads(text), kpis=kpis, cache=Cache(tmp_path))
    r = _run(text, tmp_path)
    assert row["safety_pitting_min"] == r.rating.smallest("pitting")[0]
    assert row["safety_bending_min"] == r.rating.smallest("bending")[0]
    assert "safety_pitting_min" not in [k.name for k in select_kpis((), False)]
    assert KPI_BY_NAME["safety_pitting_min"] in select_kpis((), False, rating=True)
    with pytest.raises(InputError, match=r"'safety_bending_min' needs a \[rating\] table"):
        select_kpis(("safety_bending_min",), False)


def test_life_in_load_cycles(tmp_path):
    """``life_cycles`` (of the driving gear) gives the same rating as the life in hours at
    the operating speed (2340 rpm: 2.808e9 cycles = 20 000 h); both at once are refused."""
    hours = _run(DEMO_PAIR + FAST + "[rating]\nlife_h = 20000.0\n", tmp_path)
    cycles = _run(DEMO_PAIR + FAST + "[rating]\nlife_cycles = 2.808e9\n", tmp_path)
    assert cycles.rating.meshes["mesh"].rating.cycles == pytest.approx(
        hours.rating.meshes["mesh"].rating.cycles, rel=1e-12)
    assert cycles.rating.smallest("pitting")[0] == pytest.approx(
        hours.rating.smallest("pitting")[0], rel=1e-12)
    with pytest.raises(InputError, match="life_h and rating.life_cycles both"):
        gearbox_from_text(DEMO_PAIR + "[rating]\nlife_h = 1.0\nlife_cycles = 1e6\n")


def test_a_gearbox_file_reproduces_a_commercial_rating(tmp_path):
    """``workflows/configs/nrel_5mw_parallel_stage.toml``: the NREL 5 MW gearbox's parallel
    helical stage written as a gearbox file with the inputs of KISSsoft Release 03/2017 A's
    rating (``@NREL_5MW/stage_03.rtf``, gfsReboucas/Drivetrain 4a88df34). The run derives
    the gear blank factor from the wheel's web (0.25 b) and rim (s_R = (d_f - d_i) / 2 =
    (1334.25 - 1193.32) / 2 = 70.47 mm = 5.033 m_n): 0.8987, where the report prints 0.898
    with its own s_R / m_n = 5.000; K_v's wheel mass from its rim's inner diameter; and
    gives, as the report prints, K_v 1.092, K_Halpha 1.069, K_Fbeta 1.136, S_H 1.81 / 1.88,
    S_F 3.26 / 3.09."""
    from pathlib import Path

    from pipeline.config import load_gearbox

    path = Path(__file__).parent.parent / "workflows/configs/nrel_5mw_parallel_stage.toml"
    box = load_gearbox(path)
    r = run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))
    m = r.rating.meshes["mesh"].rating
    gear = box.gears["gear"]
    s_r = gear.root_radius - box.bodies["gear"].rim_inner_radius
    assert 2 * gear.root_radius == pytest.approx(1334.252e-3, abs=5e-6)
    assert m.blank_factor == pytest.approx(1 + math.log(0.25) / (5 * math.exp(s_r / 0.070)),
                                           rel=1e-12)
    assert m.blank_factor == pytest.approx(0.898, abs=1e-3)
    assert m.dynamic.factor == pytest.approx(1.092, abs=1e-3)
    # K_Halpha 1.06956: the report's own C_R (s_R / m_n 5.000) gives 1.0694
    # (tests/test_rating_pair.py); this file's geometry, 1.3e-4 more through c_gamma_alpha
    assert m.transverse.k_halpha == pytest.approx(1.0694 + 1.3e-4, abs=5e-5)
    assert m.k_fbeta == pytest.approx(1.136, abs=6e-4)
    assert [p.safety for p in m.pitting] == pytest.approx([1.81, 1.88], abs=5e-3)
    assert [b.safety for b in m.bending] == pytest.approx([3.26, 3.09], abs=5e-3)


def test_a_web_acts_in_the_rating_beside_given_mass_and_inertia(tmp_path):
    """With mass_kg and inertia_kgm2 given, a web changes nothing but a rating: there its
    width and rim set C_R (and K_v's gear mass), so the file with [rating] is accepted and
    the web lowers C_R below 1."""
    web = ("bore_radius_mm = 21.0\nmass_kg = 2.52\ninertia_kgm2 = 7.4e-3\nweb_width_mm = 8.0\n"
           "rim_inner_radius_mm = 60.0\nhub_radius_mm = 35.0\n")
    text = DEMO_PAIR.replace("bore_radius_mm = 21.0\n", web, 1) + FAST + "[rating]\n"
    r = _run(text, tmp_path)
    assert r.rating.meshes["mesh"].rating.blank_factor < 1.0


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_a_pair_on_shafts_is_rated_with_the_systems_k_hbeta(tmp_path):
    """The overhung-pinion example (workflows/configs/shaft_overhung_pinion.toml), whose
    ``[rating]`` leaves ``face_load_factor`` out: the rating takes the K_Hbeta of the
    contact solved with the shaft's deflection (the shaft stage's cycle, to 1e-9), says so,
    and it is not the rigid contact's (1.000 for this aligned spur pair). Rated again
    with the rigid contact's K_Hbeta given, sigma_H scales as sqrt(K_Hbeta K_Halpha)
    (ISO 6336-2 Eq. (2)-(3); nothing else changes, 1e-9) and S_H inversely. Given
    ``"method_c"`` the file is rated by method C; a ``[rating.pinion_shaft]`` beside the
    shaft model changes method C's K_Hbeta shown beside, not the one used."""
    from pipeline.contact.distribution import load_distribution

    text = (WORKFLOWS / "configs" / "shaft_overhung_pinion.toml").read_text()
    assert "face_load_factor" not in tomllib.loads(text)["rating"]
    r = run_pipeline(gearbox_from_text(text),
                     RunOptions(show_progress=False, cache=Cache(tmp_path)))
    st = r.meshes["mesh"]
    pair, op = st.stiffness.actual, st.case.operation
    system = load_distribution(st.shafts.cycle, pair, op).k_hbeta
    rigid = load_distribution(st.shafts.rigid, pair, op).k_hbeta
    m = r.rating.meshes["mesh"]
    assert m.rating.k_hbeta == pytest.approx(system, rel=1e-9)
    assert m.k_hbeta_source == "loaded contact with the shafts' deflection"
    assert system > 1.05 and rigid == pytest.approx(1.0, abs=1e-3)

    given = gearbox_from_text(text.replace("[rating]", f"[rating]\nface_load_factor = {rigid!r}",
                                           1))
    g = run_pipeline(given, RunOptions(show_progress=False, cache=Cache(tmp_path))
                     ).rating.meshes["mesh"]
    assert g.k_hbeta_source == "given"
    a, b = m.rating, g.rating
    scale = math.sqrt(a.k_hbeta * a.transverse.k_halpha / (b.k_hbeta * b.transverse.k_halpha))
    for k in range(2):
        assert a.contact.stress[k] / b.contact.stress[k] == pytest.approx(scale, rel=1e-9)
        assert b.pitting[k].safety / a.pitting[k].safety == pytest.approx(scale, rel=1e-9)
    assert a.pitting[0].safety < b.pitting[0].safety

    c = gearbox_from_text(text.replace("[rating]", '[rating]\nface_load_factor = "method_c"',
                                       1))
    assert c.rating.face_load_factor == "method_c"
    assert gearbox_from_text(text).rating.face_load_factor == "contact"

    # method C's own pinion shaft beside the shaft model: shown, not used (its f_sh carries
    # the offset term of a 40 mm span, s = 10 mm, K' = 1.33)
    both = text + ("[rating.pinion_shaft]\nspan_mm = 40.0\noffset_mm = 10.0\n"
                   'shaft_diameter_mm = 35.0\narrangement = "c"\n')
    d = run_pipeline(gearbox_from_text(both),
                     RunOptions(show_progress=False, cache=Cache(tmp_path))).rating.meshes["mesh"]
    assert d.rating.k_hbeta == pytest.approx(system, rel=1e-9)
    assert d.rating.face_load.offset_term > 0.0
    assert d.rating.face_load.k_hbeta != pytest.approx(m.rating.face_load.k_hbeta, rel=1e-3)
