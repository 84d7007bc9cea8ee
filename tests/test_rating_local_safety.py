"""Local safety over the flank and along the root (pipeline.rating.local_safety).

* exact: one position of a spur pair in single contact at the pitch point, where the
  loaded contact's Hertz pressure is uniform across the face and equals ISO 6336-2's
  closed-form line contact Z_H Z_E sqrt(F_t / (d_1 b) (u + 1) / u) (Johnson 1985, eq.
  4.45 written with the gear data): S_H,loc = sigma_HG / (p sqrt(K_A K_gamma K_v)) there,
  NaN off the loaded line;
* the demo's aligned spur pair (z 50/50, m 3 mm, b 20 mm, 340 N m) against its own ISO
  6336-2 method B rating: the map's minimum is sigma_HG / (max p_H sqrt(K_A K_gamma K_v)),
  and its ratio to ISO's S_H is Z_B Z_eps sqrt(K_Hbeta K_Halpha) / c, c the contact's
  largest pressure over the pitch-point single-contact Hertz pressure, which lies between
  1 and Z_B (reasoned in the test);
* a helical pair with a helix slope deviation: the smallest S_H,loc and the largest FE root
  stress sit at the face end the deviation loads (z = 0 for a positive f_Hb, b for a
  negative one), and the root stress along the face has the gear's FE maximum exactly;
* the report: its local-safety section and ``rating_local.csv``.
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from gearsets import SMALL, spur

from pipeline.cli import main as cli
from pipeline.contact import analyse_contact, analytical_compliance
from pipeline.contact.distribution import load_distribution
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.options import ContactOptions
from pipeline.contact.root_stress import analyse_root_stress
from pipeline.contact.separations import FlankModifications
from pipeline.geometry import GearPair
from pipeline.operation import OperatingPoint
from pipeline.rating.local_safety import (
    local_bending_safety,
    local_pitting_safety,
    local_safety,
    rating_limits,
)
from pipeline.rating.pair_rating import GearRatingInputs, RatingInputs, rate_pair
from pipeline.validation import InputError

MPA = 1e6
LIMITS = (1500 * MPA, 1400 * MPA)  # sigma_HG of pinion and gear, Pa
EXTERNAL = 1.25 * 1.10 * 1.05  # K_A K_gamma K_v


def _iso_line_contact(pair: GearPair, torque: float) -> float:
    """Z_H Z_E sqrt(F_t / (d_1 b) (u + 1) / u), Pa: the Hertz pressure of the whole load on
    one pair at the pitch point (ISO 6336-2, clause 5, without Z_eps)."""
    p1, g = pair.pinion, pair.gear
    e_star = 1.0 / ((1 - p1.material.poisson_ratio**2) / p1.material.youngs_modulus
                    + (1 - g.material.poisson_ratio**2) / g.material.youngs_modulus)
    a_wt, a_t = pair.operating_pressure_angle, p1.transverse_pressure_angle
    z_h = math.sqrt(2.0 * math.cos(a_wt) / (math.cos(a_t) ** 2 * math.sin(a_wt)))
    u = pair.gear_ratio
    return z_h * math.sqrt(e_star / math.pi) * math.sqrt(
        torque / p1.reference_radius / (2 * p1.reference_radius * pair.face_width)
        * (u + 1) / u)


def test_formulas_on_a_given_envelope():
    """The two local safeties from given stresses: sigma_G / (p sqrt(K)) and sigma_G /
    (sigma K); NaN where nothing presses, and S_F,loc NaN for a gear not rated."""
    p = np.array([[0.0, 800 * MPA], [1000 * MPA, 0.0]])
    s = local_pitting_safety(p, 1500 * MPA, 1.44)
    np.testing.assert_array_equal(np.isnan(s), [[True, False], [False, True]])
    assert s[0, 1] == pytest.approx(1500 / (800 * 1.2), rel=1e-15)
    assert s[1, 0] == pytest.approx(1.25, rel=1e-15)
    f = local_bending_safety(np.array([200 * MPA, 0.0]), 900 * MPA, 1.5)
    assert f[0] == pytest.approx(3.0, rel=1e-15) and math.isnan(f[1])
    assert np.isnan(local_bending_safety(np.array([200 * MPA]), None, 1.5)).all()


def test_single_contact_at_the_pitch_point_is_iso_closed_form():
    """z 30/45 spur pair, 300 N m, the one position whose pair sits on the pitch point in
    single contact (no tip contact, Weber local contact): p_H there is Z_H Z_E sqrt(F_t /
    (d_1 b) (u + 1) / u), the same in all 8 slices, so S_H,loc = sigma_HG / (p
    sqrt(K_A K_gamma K_v)) at every face position, for each gear's sigma_HG (1500 / 1400
    MPa), at the pitch diameter within half a grid step; everywhere else on the flank NaN
    (no other pair is in contact at this position)."""
    pair = GearPair(spur(30, "pinion"), spur(45, "gear"))
    torque = 300.0
    op = OperatingPoint(torque=torque, speed=100.0)
    opts = ContactOptions(tip_contact=False, slices=8)
    src = analytical_compliance(pair, op, opts)
    k = int((pair.s_pitch - pair.s_start) // pair.base_pitch)
    s0 = pair.s_pitch - k * pair.base_pitch
    cyc = loaded_mesh_cycle(src, torque / pair.pinion.base_radius, None, "weber", [s0])
    dist = load_distribution(cyc, pair, op)
    n_s = 81
    loc = local_safety(cyc, dist, pair, pitting_limit=LIMITS, load_factor=EXTERNAL,
                       profile_points=n_s)
    p_iso = _iso_line_contact(pair, torque)
    row = int(np.round((pair.s_pitch - pair.s_start) / (pair.s_end - pair.s_start)
                       * (n_s - 1)))
    step = (pair.s_end - pair.s_start) / (n_s - 1)
    d_pitch = 2.0 * np.asarray(pair.operating_pitch_radii)
    a_wt = pair.operating_pressure_angle
    for k, p in enumerate(loc.pitting):
        expected = LIMITS[k] / (p_iso * math.sqrt(EXTERNAL))
        np.testing.assert_allclose(p.safety[row], expected, rtol=1e-9)
        assert np.isnan(np.delete(p.safety, row, axis=0)).all()
        assert p.minimum == pytest.approx(expected, rel=1e-9)
        # the grid point nearest the pitch point: within half a roll step of it, which is
        # 2 (step / 2) sin(alpha) of diameter there (d = 2 sqrt(r_b^2 + u^2), dd/du = 2 sin)
        assert abs(p.minimum_diameter - d_pitch[k]) <= 1.01 * step * math.sin(a_wt)
    assert loc.z[0] == 0.0 and loc.z[-1] == pytest.approx(pair.face_width, rel=1e-12)


@pytest.fixture(scope="module")
def demo_rating():
    """The demo's aligned spur pair at 340 N m, 2340 rpm, analytical compliance, 24
    positions on the path of contact only, rated with K_A 1.25, grade 6, ISO VG 220,
    sigma_Hlim 1500 MPa."""
    pair = GearPair(spur(50, "pinion"), spur(50, "gear"))
    op = OperatingPoint(torque=340.0, speed=2340.0 * math.pi / 30.0)
    opts = ContactOptions(positions=24, tip_contact=False)
    cyc = analyse_contact(analytical_compliance(pair, op, opts), op, opts)
    dist = load_distribution(cyc, pair, op)
    gear = GearRatingInputs(sigma_hlim=1500 * MPA, sigma_flim=430 * MPA)
    inputs = RatingInputs(application_factor=1.25, life_hours=20_000.0, accuracy_grade=6,
                          viscosity_40=220e-6, k_hbeta=dist.k_hbeta)
    r = rate_pair(pair, 340.0, 2340.0, inputs, (gear, gear))
    hg, fg, ext = rating_limits(r, inputs.minimum_safety_pitting)
    loc = local_safety(cyc, dist, pair, pitting_limit=hg, bending_limit=fg, load_factor=ext)
    return pair, dist, r, loc, hg, ext


def test_demo_pair_minimum_against_iso(demo_rating):
    """ISO builds sigma_H = Z_B sigma_H0 sqrt(K_A K_gamma K_v K_Hbeta K_Halpha) with
    sigma_H0 = Z_H Z_E Z_eps sqrt(F_t (u + 1) / (d_1 b u)) = Z_eps p_C, p_C the pitch-point
    Hertz pressure of the whole load on one pair; the map uses the contact's largest p_H
    with sqrt(K_A K_gamma K_v) only. Hence S_H,loc,min / S_H = Z_B Z_eps sqrt(K_Hbeta
    K_Halpha) / c with c = max p_H / p_C. Band of c for this pair (eps_alpha 1.755 < 2,
    equal gears): between B and D one pair carries the whole load, and the relative radius
    of curvature is largest at the pitch point and smallest at B and D, so the single-contact
    pressure lies between p_C and Z_B p_C (Z_B = sqrt(R_C / R_B)); in double contact each
    pair carries less. So 1 <= c <= Z_B. Measured: c 1.00044, Z_B 1.00090, Z_eps 0.86513,
    K_Hbeta (the contact's) 1, K_Halpha 1 (grade 6): S_H,loc,min = 0.8655 S_H, i.e. ISO's
    Z_eps, calibrated on test gears, lowers its stress by 13.5 % below the Hertz pressure
    of the whole load on one pair, which the contact has."""
    pair, dist, r, loc, hg, ext = demo_rating
    c = r.contact
    p_c = _iso_line_contact(pair, 340.0)
    assert c.nominal == pytest.approx(c.contact_ratio_factor * p_c, rel=1e-12)
    ratio = dist.hertz_max.value / p_c
    z_b = c.single_pair_factors[0]
    assert 1.0 <= ratio <= z_b
    assert (ratio, z_b, c.contact_ratio_factor) == pytest.approx((1.00044, 1.00090, 0.86513),
                                                                 abs=1e-5)
    for k, p in enumerate(loc.pitting):
        # the map's minimum is at the contact's largest pressure (exact)
        assert p.minimum == pytest.approx(hg[k] / (dist.hertz_max.value * math.sqrt(ext)),
                                          rel=1e-12)
        s_h = r.pitting[k].safety
        expected = (c.single_pair_factors[k] * c.contact_ratio_factor
                    * math.sqrt(r.k_hbeta * r.transverse.k_halpha) / ratio)
        assert p.minimum / s_h == pytest.approx(expected, rel=1e-12)
        assert p.minimum / s_h == pytest.approx(0.8655, abs=1e-4)
    # one slice across the face: uniform, the minimum named at the middle of the face
    assert dist.slices_across_face == 1
    assert loc.pitting[0].minimum_z == pytest.approx(0.5 * pair.face_width, rel=1e-12)
    # sigma_HG is ISO's sigma_HP S_Hmin and S_H sigma_H alike; K_A K_gamma K_v
    assert hg[0] == pytest.approx(r.pitting[0].safety * c.stress[0], rel=1e-12)
    assert ext == pytest.approx(1.25 * r.dynamic.factor, rel=1e-15)


def _helical(slope: float, slices: int = 10):
    h = math.radians(15.0)
    pair = GearPair(spur(50, "pinion", helix_angle=h, hand="right"),
                    spur(50, "gear", helix_angle=h, hand="left"))
    op = OperatingPoint(torque=340.0, speed=100.0)
    opts = ContactOptions(positions=12, slices=slices,
                          modifications=FlankModifications(slope_deviation=slope))
    with pytest.warns(Warning):  # tip contact beyond the path (no relief): stated, expected
        cyc = analyse_contact(analytical_compliance(pair, op, opts), op, opts)
    return pair, op, cyc, load_distribution(cyc, pair, op)


@pytest.mark.parametrize("slope", [15e-6, -15e-6])
def test_misaligned_helical_pair_weakest_at_the_loaded_end(slope):
    """Demo pair made helical (15 deg), f_Hb = +-15 um: the separation grows with
    f_Hb (z / b - 1/2) (pipeline.contact.separations), so a positive f_Hb loads z = 0 and a
    negative one z = b. The smallest S_H,loc of both flanks sits in the end slice there
    (10 slices of 2 mm: centre 1 mm from the end), and the map's face means fall from that
    end to the other."""
    pair, _, cyc, dist = _helical(slope)
    loc = local_safety(cyc, dist, pair, pitting_limit=LIMITS, load_factor=EXTERNAL)
    b = pair.face_width
    loaded_end = 0.0 if slope > 0 else b
    assert dist.k_hbeta > 1.4  # a real misalignment (1.533 measured for +15 um)
    for p in loc.pitting:
        assert abs(p.minimum_z - loaded_end) == pytest.approx(0.1 * b / 2, rel=1e-9)
        face_mean = np.nanmean(p.safety, axis=0)[1:-1]  # slice centres
        trend = np.diff(face_mean) if slope > 0 else -np.diff(face_mean)
        assert np.all(trend > 0)


@pytest.fixture(scope="module")
def misaligned_root():
    pair, op, cyc, dist = _helical(15e-6)
    return pair, cyc, dist, analyse_root_stress(cyc, pair, op)


def test_root_stress_along_the_face(misaligned_root):
    """The along-face root stress's largest value is the RootStress gear maximum (exact: the
    same states, maximised in another order); it lies in the loaded end slice (z 1 mm, f_Hb
    +15 um); S_F,loc = sigma_FG / (sigma K_A K_gamma K_v) there and the smallest S_F,loc is
    at the largest stress."""
    pair, cyc, dist, rs = misaligned_root
    fg = (900 * MPA, 850 * MPA)
    loc = local_safety(cyc, dist, pair, pitting_limit=LIMITS, bending_limit=fg,
                       load_factor=EXTERNAL, root=rs)
    for k, (b, g) in enumerate(zip(loc.bending, (rs.pinion, rs.gear), strict=True)):
        assert b.stress.max() == g.max_stress
        assert g.face_envelope.max() == g.max_stress
        assert b.minimum_z == pytest.approx(0.001, rel=1e-9) == g.max_face_position
        assert b.minimum == pytest.approx(fg[k] / (g.max_stress * EXTERNAL), rel=1e-15)
        assert np.nanmin(b.safety) == b.minimum
        assert b.stress[0] > 2.0 * b.stress[-1]  # far below at the other end (200 vs 70 MPa)


def test_root_stress_of_another_cycle_is_refused(misaligned_root):
    pair, cyc, dist, rs = misaligned_root
    other_pair, _, other, other_dist = _helical(15e-6, slices=6)
    with pytest.raises(InputError, match="other slices"):
        local_safety(other, other_dist, other_pair, pitting_limit=LIMITS,
                     load_factor=EXTERNAL, root=rs)


def test_report_section_and_csv(tmp_path):
    """``gearpipe run`` of the small demo case made helical and misaligned with a [rating]
    table: the report's local-safety section gives each gear's smallest S_H,loc and S_F,loc
    and where, equal to the CSV's smallest values at the same place, and embeds both
    figures."""
    text = SMALL.split("[dynamics]")[0]
    text = text.replace("pressure_angle_deg = 20.0\n", "pressure_angle_deg = 20.0\n"
                        "helix_angle_deg = 15.0\n", 2)
    text = text.replace("[gear]\n", "[gear]\nhand = \"left\"\n")
    text = text.replace("positions = 24\n", "positions = 12\nslices = 10\n"
                        "slope_deviation_um = 15.0\nrender = false\n") + "[rating]\n"
    cfg = tmp_path / "helical.toml"
    cfg.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert cli(["run", str(cfg), "--out", str(out)]) == 0  # the session cache: FE tables shared
    data = json.loads((out / "report.json").read_text())["sections"]["rating_local"]
    q = data["quantities"]
    assert [f["file"] for f in data["figures"]] == ["report_rating_local_pitting.png",
                                                     "report_rating_root_face.png"]
    with open(out / "rating_local.csv", encoding="utf-8") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    header = [h.strip() for h in rows[0]]
    assert header[:2] == ["roll_coordinate_s [m]", "face_position_z [m]"]
    table = np.array(rows[1:], dtype=float)
    col = {h: table[:, i] for i, h in enumerate(header)}
    for gear in ("pinion", "gear"):
        s_h = col[f"S_H_local_{gear} [-]"]
        i = int(np.nanargmin(s_h))
        assert q["S_H_loc_min"]["values"][gear] == pytest.approx(s_h[i], rel=1e-8)
        assert q["S_H_loc_face"]["values"][gear] == pytest.approx(1.0, rel=1e-6)  # mm
        assert q["S_H_loc_diameter"]["values"][gear] == pytest.approx(
            col[f"diameter_{gear} [m]"][i] * 1e3, rel=1e-8)
        s_f = col[f"S_F_local_{gear} [-]"]
        assert q["S_F_loc_min"]["values"][gear] == pytest.approx(np.nanmin(s_f), rel=1e-8)
        assert q["sigma_F_fe_face"]["values"][gear] == pytest.approx(1.0, rel=1e-6)
        stress = col[f"root_stress_fe_along_face_{gear} [Pa]"]
        assert q["sigma_F_fe_face_max"]["values"][gear] == pytest.approx(stress.max() * 1e-6,
                                                                         rel=1e-8)


def test_figures_mark_the_weakest_points(misaligned_root):
    """The map's marker sits at each flank's smallest S_H,loc (diameter, face position in
    mm), the S_Hmin contour is drawn where the map crosses it (S_Hmin 1.8 here, the maps
    1.67 .. 3.54 and 1.56 .. 3.30), the colour bar is labelled; the root figure marks the
    largest stress."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.contour import ContourSet

    from pipeline.viz.rating import plot_local_pitting_safety, plot_root_stress_along_face

    pair, cyc, dist, rs = misaligned_root
    loc = local_safety(cyc, dist, pair, pitting_limit=LIMITS, bending_limit=(900 * MPA, None),
                       load_factor=EXTERNAL, root=rs)
    fig = plot_local_pitting_safety(loc, 1.8, False, "t")
    FigureCanvasAgg(fig).draw()
    for ax, p in zip(fig.axes[:2], loc.pitting, strict=True):
        assert 1.5 < p.minimum < 1.8 < np.nanmax(p.safety)
        (marker,) = [ln for ln in ax.lines if ln.get_marker() == "P"]
        assert marker.get_xydata()[0] == pytest.approx((p.minimum_diameter * 1e3,
                                                        p.minimum_z * 1e3), rel=1e-12)
        levels = [list(c.levels) for c in ax.collections if isinstance(c, ContourSet)]
        assert [1.8] in levels
    assert "local pitting safety S_H,loc [-]" in fig.axes[2].get_ylabel()
    fig = plot_root_stress_along_face(loc, 1.4, "t")
    FigureCanvasAgg(fig).draw()
    left = fig.axes[0]
    dots = [ln.get_xydata()[0] for ln in left.lines if ln.get_marker() == "o"]
    assert dots[0] == pytest.approx((1.0, rs.pinion.max_stress * 1e-6), rel=1e-12)
    assert "not rated in bending" in fig.axes[1].get_legend().get_texts()[1].get_text()
