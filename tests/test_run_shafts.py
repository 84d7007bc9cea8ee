"""The loaded contact with the shafts' deflection (pipeline.run.shafts): a fixed point over
the line load that settles, opens no misalignment where symmetry forbids it, loads the face
end nearest the bearings of an overhung pinion, and under a helical mesh tilts a
straddle-mounted seat by the axial force's moment alone."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.cache.folder import Cache
from pipeline.config.gearbox import gearbox_from_text
from pipeline.contact.analysis import line_of_action_load
from pipeline.run.chain import RunOptions
from pipeline.run.runner import run_pipeline
from pipeline.shaft.misalignment import shaft_gap
from pipeline.validation import InputError
from workflows.default_case import DEMO_PAIR

FAST = '[contact]\ncompliance = "analytical"\npositions = 24\nslices = 20\n'


def _shaft(gear_mm, bearings_mm, model=""):
    rows = "".join(f"[[pinion.shaft.bearings]]\nposition_mm = {p}\n"
                   + ("axial = true\n" if i == 0 else "") for i, p in enumerate(bearings_mm))
    return (f"[pinion.shaft]\n{model}gear_position_mm = {gear_mm}\ntorque_position_mm = 0.0\n"
            "[[pinion.shaft.segments]]\nstart_mm = 0.0\nend_mm = 120.0\n"
            "outer_diameter_mm = 30.0\n" + rows)


def _run(shaft, tmp_path, extra=""):
    text = DEMO_PAIR.replace("[gear]", shaft + "[gear]") + FAST + extra
    box = gearbox_from_text(text)
    return run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_straddle_mounted_at_mid_span_opens_no_misalignment(tmp_path):
    """A rigid seat midway between two rigid bearings: no tilt by symmetry and a uniform
    twist over the rigid seat, so the gap is the same across the face (to 1e-9 um) and the
    line load is the rigid one's (K_Hbeta 1 to 1e-6)."""
    r = _run(_shaft(60.0, (20.0, 100.0)), tmp_path)
    st = r.meshes["mesh"].shafts
    assert np.ptp(st.gap) < 1e-15
    assert r.distributions["mesh"].distribution.k_hbeta == pytest.approx(1.0, abs=1e-6)


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_overhung_pinion_loads_the_face_end_by_its_bearings(tmp_path):
    """A pinion overhung beyond its two bearings (20 and 40 mm, seat 50-70 mm): the seat
    tilts, the face end nearest the bearings carries the most (the largest cycle-mean line
    load at the first slice), K_Hbeta above 1.1; the fixed point settled below its
    tolerance, and its gap is the shafts' gap under its own final line load."""
    r = _run(_shaft(60.0, (20.0, 40.0)), tmp_path)
    st = r.meshes["mesh"].shafts
    dist = r.distributions["mesh"].distribution
    assert st.change < 1e-3 and st.iterations >= 2
    assert np.argmax(dist.cycle_mean) == 0
    assert dist.k_hbeta > 1.1
    rigid_k = np.ptp(st.rigid.transmission_error)  # the rigid contact is kept beside
    assert rigid_k >= 0.0
    from pipeline.run.shafts import shaft_model

    pair = r.meshes["mesh"].stiffness.actual
    w = np.interp(st.z, dist.z, dist.cycle_mean)
    spec = r.gearbox.shafts["pinion"]
    nodes = spec[1].gear_position - 0.5 * spec[1].seat_width + st.z
    gap, _ = shaft_gap([shaft_model(spec, nodes), None],
                       [pair.pinion.base_radius, pair.gear.base_radius], st.z, w)
    assert gap - gap.mean() == pytest.approx(st.gap, abs=2e-3 * np.ptp(st.gap))


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_helical_pair_on_a_straddle_mounted_shaft(tmp_path):
    """The demo pair made helical (beta 15 deg, right-hand pinion, left-hand gear) with its
    pinion's rigid seat midway between two rigid bearings (20 and 100 mm, 30 mm shaft): the
    spur pair opens no misalignment here (test above), the helical one opens what the axial
    force's moment tilts the seat by. The fixed point settles (change < 1e-3, 2 iterations)
    and its gap is, to 1e-9 of its range, the rigid seat's tilt theta_x = M_x / k under M_x
    = -sum F_j (z_j - z_c) - a sum F_j d_j (the transverse loads' moment about the seat's
    centre plus the axial force's; z_j along the shaft, where a right-hand pinion's face runs
    against the shaft; a = -tan(beta_b) for a right-hand pinion; d_j = s_j the cycle-mean
    contact position from T1 in slice j), with k = 2 (l + b / 2)^2 / (l^3 / (3 E I) + l /
    (kappa G A)) (two Timoshenko cantilevers of l = 30 mm clamped in the seat, their tips
    held by the bearings; tests/test_shaft_misalignment.py): the gap, mean out, is -theta_x
    (z_j - mean z) from the seat's slope plus -a theta_x (d_j - mean d) from the contact
    point's lever on the axial give (module docstring of pipeline.shaft.misalignment) -
    from the line load and contact positions the run took. Measured: 0.32 um across the
    face, K_Hbeta 1.016 (1.003 on rigid supports), the pinion's axial force a P = -1173 N."""
    import math

    helical = DEMO_PAIR.replace("face_width_mm = 20.0", "face_width_mm = 20.0\n"
                                "helix_angle_deg = 15.0\nhand = \"right\"", 1)
    helical = helical.replace("face_width_mm = 20.0\nbore", "face_width_mm = 20.0\n"
                              "helix_angle_deg = 15.0\nhand = \"left\"\nbore", 1)
    box = gearbox_from_text(helical.replace("[gear]", _shaft(60.0, (20.0, 100.0)) + "[gear]")
                            + FAST)
    r = run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))
    st = r.meshes["mesh"].shafts
    pair = r.meshes["mesh"].stiffness.actual
    assert st.change < 1e-3 and st.iterations >= 2
    b, n = pair.face_width, st.z.size
    f = st.line_load * b / n
    z_shaft = 0.060 + b / 2 - st.z  # a right-hand pinion's face runs against the shaft
    a = -math.tan(pair.pinion.base_helix_angle)
    roll = st.mesh.roll
    m_x = -np.sum(f * (z_shaft - 0.060)) - a * np.sum(f * roll)
    e, nu, d, ell = 2.06e11, 0.3, 0.030, 0.030
    i_, area = math.pi * d**4 / 64, math.pi * d**2 / 4
    kappa, g = 6 * (1 + nu) / (7 + 6 * nu), e / (2 * (1 + nu))
    k = 2 * (ell + b / 2) ** 2 / (ell**3 / (3 * e * i_) + ell / (kappa * g * area))
    theta = m_x / k
    want = -theta * (z_shaft - z_shaft.mean()) - a * theta * (roll - roll.mean())
    assert st.gap == pytest.approx(want, abs=1e-9 * np.ptp(st.gap))
    assert np.ptp(st.gap) == pytest.approx(0.32e-6, abs=0.01e-6)
    dist = r.distributions["mesh"].distribution
    assert dist.k_hbeta == pytest.approx(1.016, abs=0.001)
    # the slices' cycle-mean loads at their load-weighted mean roll coordinates carry the
    # cycle-mean moment sum F s of all contact points exactly
    from pipeline.run.shafts import mean_roll

    last = st.cycle
    s_bar = mean_roll(last, b, n, pair.s_pitch)
    w_bar = np.interp(st.z, dist.z, dist.cycle_mean)
    assert np.sum(w_bar * b / n * s_bar) == pytest.approx(
        np.sum(last.point_load * last.point_s) / len(last), rel=1e-12)
    assert st.summary()["pinion"]["mesh_axial_force_N"] == pytest.approx(
        a * line_of_action_load(pair, box.operation), rel=1e-12)


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_the_3d_shaft_beside_the_beam(tmp_path):
    """The overhung pinion with the 3D FE superelement (model = "fe3d") instead of the beam:
    the same fixed point, a misalignment 5 % larger (5.07 against 4.83 um; the 3D shaft is
    more flexible at the rigid hub's edges and where it meets the bearings' bands, which a
    beam's rigid segment does not see, tests/test_shaft_fe3d.py) and K_Hbeta within 1 %."""
    beam = _run(_shaft(60.0, (20.0, 40.0)), tmp_path)
    fe3d = _run(_shaft(60.0, (20.0, 40.0), 'model = "fe3d"\n'), tmp_path)
    g_b, g_f = (np.ptp(r.meshes["mesh"].shafts.gap) for r in (beam, fe3d))
    assert g_f / g_b == pytest.approx(1.05, abs=0.02)
    k_b, k_f = (r.distributions["mesh"].distribution.k_hbeta for r in (beam, fe3d))
    assert k_f / k_b == pytest.approx(1.0, abs=0.01)


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_report_shows_the_shafts(tmp_path):
    """gearpipe run of a pair on shafts: the report's shafts section gives the misalignment
    and both K_Hbeta (with the shafts equal to the load distribution section's), its figure
    is written, and summary.json carries the shafts' figures."""
    import json

    from pipeline.cli import main as cli

    path = tmp_path / "box.toml"
    path.write_text(DEMO_PAIR.replace("[gear]", _shaft(60.0, (20.0, 40.0)) + "[gear]") + FAST)
    out = tmp_path / "run"
    assert cli(["run", str(path), "--out", str(out), "--cache-dir", str(tmp_path / "c")]) == 0
    report = json.loads((out / "report.json").read_text())["sections"]
    rows = report["shafts"]["quantities"]
    assert rows["K_Hbeta_shafts"]["value"] == report["load_distribution"]["quantities"][
        "K_Hbeta"]["value"]
    assert rows["K_Hbeta_shafts"]["value"] > rows["K_Hbeta_rigid"]["value"]
    assert rows["misalignment"]["value"] > 1.0
    assert (out / "report_shafts.png").is_file()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["meshes"]["mesh"]["shafts"]["iterations"] >= 2
    # the CSVs: the deflection line through the bearings (rigid: zero there) and the
    # misalignment across the face, its spread the report's
    line = np.genfromtxt(out / "shaft_deflection.csv", delimiter=",", names=True,
                         dtype=None, encoding="utf-8")
    at = {round(float(z), 6): u for z, u in zip(line["z_m"], line["u_y_line_of_action_m"],
                                                strict=True)}
    assert at[0.02] == 0.0 and at[0.04] == 0.0
    assert abs(at[0.07]) > abs(at[0.05]) > 0.0
    face = np.genfromtxt(out / "shaft_face.csv", delimiter=",", names=True)
    assert np.ptp(face["gap_m"]) * 1e6 == pytest.approx(rows["misalignment"]["value"],
                                                        rel=1e-6)
    assert face["pinion_retreat_m"] == pytest.approx(
        face["pinion_translation_m"] + face["pinion_twist_at_base_circle_m"], rel=1e-9)


def test_dynamics_take_the_shafts_support(tmp_path):
    """With a shaft, the pair's dynamic model supports the pinion by its shaft at the seat:
    an integral seat midway between two rigid bearings of a uniform shaft gives k = 1 /
    (L^3 / (48 E I) + L / (4 kappa G A)) (Timoshenko, Cowper's kappa of a solid section),
    the gear keeps [dynamics] bearing_stiffness_N_per_m; with both gears on shafts that key
    is refused (it would change nothing)."""
    import math

    from pipeline.run.dynamics import dynamic_model

    shaft = ("[pinion.shaft]\ngear_position_mm = 60.0\ntorque_position_mm = 0.0\n"
             "hub = \"integral\"\n[[pinion.shaft.segments]]\nstart_mm = 0.0\nend_mm = 120.0\n"
             "outer_diameter_mm = 30.0\n[[pinion.shaft.bearings]]\nposition_mm = 20.0\n"
             "axial = true\n[[pinion.shaft.bearings]]\nposition_mm = 100.0\n")
    dyn = "[dynamics]\nbearing_stiffness_N_per_m = 2.0e8\n"
    text = DEMO_PAIR.replace("[gear]", shaft + "[gear]") + FAST + dyn
    box = gearbox_from_text(text)
    r = run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))
    model, _ = dynamic_model(box, r.meshes)
    e, nu, d, span = 2.06e11, 0.3, 0.030, 0.080
    i_, area = math.pi * d**4 / 64, math.pi * d**2 / 4
    kappa, g = 6 * (1 + nu) / (7 + 6 * nu), e / (2 * (1 + nu))
    want = 1 / (span**3 / (48 * e * i_) + span / (4 * kappa * g * area))
    assert model.bearing_stiffness == pytest.approx(want, rel=1e-9)
    assert model.gear_bearing_stiffness == 2.0e8
    both = text.replace("[operation]", shaft.replace("pinion.shaft", "gear.shaft")
                        + "[operation]")
    with pytest.raises(InputError, match="bearing_stiffness_N_per_m changes nothing"):
        gearbox_from_text(both)


def _helical(pinion_hand: str, gear_hand: str) -> str:
    text = DEMO_PAIR.replace("face_width_mm = 20.0", "face_width_mm = 20.0\nhelix_angle_deg = "
                             f"15.0\nhand = \"{pinion_hand}\"", 1)
    return text.replace("face_width_mm = 20.0\nbore", "face_width_mm = 20.0\nhelix_angle_deg "
                        f"= 15.0\nhand = \"{gear_hand}\"\nbore", 1)


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_the_other_rotation_is_the_mirror_image(tmp_path):
    """The pinion turning counterclockwise loads the other flanks: the mirror image, in the
    plane through both axes, of the gearbox turning clockwise with every hand reversed
    (pipeline.shaft.misalignment, The other rotation). A right-hand pinion on an overhung
    shaft turning counterclockwise opens the same gap as a left-hand one turning clockwise
    (to 1e-12 of its range), its deflection along the line of action is the same and its
    u_x, theta_y, theta_z and torque reaction the negatives; the gear driving is the
    pinion's other rotation (the torque picks the flank); a spur pair's gap is the same
    either way and its twist reverses."""
    shaft = _shaft(100.0, (20.0, 60.0))
    rotation = '[operation]\npinion_rotation = "counterclockwise"\n'

    def stage(text: str):
        box = gearbox_from_text(text.replace("[gear]", shaft + "[gear]") + FAST)
        r = run_pipeline(box, RunOptions(show_progress=False, cache=Cache(tmp_path)))
        return r.meshes["mesh"].shafts

    ccw = stage(_helical("right", "left").replace("[operation]\n", rotation))
    mirror = stage(_helical("left", "right"))
    assert ccw.reflected and not mirror.reflected
    assert np.ptp(ccw.gap) > 1e-7
    assert ccw.gap == pytest.approx(mirror.gap, abs=1e-12 * np.ptp(ccw.gap))
    a, b = ccw.retreats[0].solution, mirror.retreats[0].solution
    flip = np.array([-1.0, 1.0, 1.0])
    assert a.displacement == pytest.approx(b.displacement * flip, abs=1e-12)
    assert a.rotation == pytest.approx(b.rotation * -flip, abs=1e-12)
    assert a.torque_reaction == pytest.approx(-b.torque_reaction, rel=1e-12)
    spur_cw = stage(DEMO_PAIR)
    spur_ccw = stage(DEMO_PAIR.replace("[operation]\n", rotation))
    assert spur_ccw.gap == pytest.approx(spur_cw.gap, abs=1e-15)
    assert spur_ccw.retreats[0].solution.rotation[:, 2] == pytest.approx(
        -spur_cw.retreats[0].solution.rotation[:, 2], abs=1e-15)
    driven = '[operation]\ndriver = "gear"\n'
    assert stage(DEMO_PAIR.replace("[operation]\n", driven)).reflected
    assert not stage(DEMO_PAIR.replace("[operation]\n", driven + rotation[12:])).reflected


def test_the_rotation_needs_shafts():
    """The pinion's sense of rotation only picks the flanks that load its shafts: without a
    shaft it is refused in one line."""
    with pytest.raises(InputError, match=r'operation.pinion_rotation = "counterclockwise" '
                                         r"sets which flanks load a pair's shafts"):
        gearbox_from_text(DEMO_PAIR.replace("[operation]\n", '[operation]\npinion_rotation = '
                                            '"counterclockwise"\n') + FAST)


@pytest.mark.filterwarnings("ignore::pipeline.validation.PhysicsWarning")
def test_fixed_point_that_does_not_settle_is_one_line(tmp_path, monkeypatch):
    """Allowed one iteration, the overhung pinion's fixed point (which needs 3) stops with
    one line naming the iteration and the last change of the line load."""
    import pipeline.run.shafts as shafts

    monkeypatch.setattr(shafts, "MAX_ITERATIONS", 1)
    with pytest.raises(InputError, match=r"^shafts: the line load still changes by [0-9.e-]+ "
                                         r"\(relative\) after iteration 1; the shafts and the "
                                         r"mesh do not settle$"):
        _run(_shaft(60.0, (20.0, 40.0)), tmp_path)


def test_position_memo_gives_the_sources_points_and_matrix():
    """The fixed point's memo of a source: the same points and compliance matrix as the
    source at every position (bit for bit), the matrix computed once and handed out as a
    copy that the caller may change."""
    from pipeline.contact import analytical_compliance
    from pipeline.contact.options import ContactOptions
    from pipeline.run.shafts import PositionMemo

    box = gearbox_from_text(DEMO_PAIR + FAST)
    source = analytical_compliance(box.pair, box.operation, ContactOptions(slices=20))
    calls = []

    class Counted:
        pair, tip_contact, points = source.pair, source.tip_contact, source.points

        def matrix(self, position):
            calls.append(position)
            return source.matrix(position)

    memo = PositionMemo(Counted())
    for s0 in box.pair.mesh_cycle(5):
        a, b = memo.matrix(s0), source.matrix(s0)
        np.testing.assert_array_equal(a, b)
        a[:] = 0.0
        np.testing.assert_array_equal(memo.matrix(s0), b)
        np.testing.assert_array_equal(memo.points(s0).s, source.points(s0).s)
        assert memo.points(s0) is memo.points(s0)
    assert len(calls) == 5
    assert (memo.pair, memo.tip_contact) == (source.pair, source.tip_contact)
