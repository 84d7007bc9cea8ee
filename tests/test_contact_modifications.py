"""Each gear's flank modifications (pipeline.contact.modifications) against closed forms.

* every shape at sampled contact points against its formula written in the gear's own
  coordinates (roll length ``rho = sqrt(r^2 - r_b^2)`` and face position, ISO 21771:2007
  4.3 / 7.3), independently of the code, to 1e-12 of the amount (the formulas, and the
  grids of the topography check, are :mod:`pipeline.verification.cases_modifications`'s);
* symmetry: lead crowning about mid-face, the pinion's and the gear's tip relief mirror
  images on a pair of equal gears;
* ``[contact]``'s short form and the same modifications given per gear: the same initial
  gaps as the former closed form and the same loaded mesh cycle, bit for bit;
* a topography grid written from analytical modifications (linear reliefs with grid lines
  at their starts, slopes, a twist, an end relief) equals them through the loaded contact
  to round-off (bilinear interpolation reproduces a function bilinear on each cell);
* crowning under a helix slope: K_Hbeta of independent slices of uniform stiffness in
  closed form, ``1 + n c0 (mean g - min g) / w_m`` (the ISO 6336-1 linear-load model,
  Annex E, with the gap g of the modifications), and lower than the slope's alone;
* Harris (1958): at light load the transmission error follows the reliefs: with linear tip
  relief C over L on both gears and D = g_alpha - p_b the double-contact zone, its
  peak-to-peak is C (1 - D / (2 L)) for D / 2 <= L <= D.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur
from helpers import UniformSlices

from pipeline.config.modifications import read_topography
from pipeline.contact.analysis import analyse_contact
from pipeline.contact.compliance import compliance_source
from pipeline.contact.distribution import load_distribution
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.modifications import (
    GearModification,
    LeadModification,
    ProfileModification,
    flank_frames,
    modification_gap,
    shapes,
)
from pipeline.contact.options import ContactOptions
from pipeline.contact.separations import FlankModifications, initial_separations
from pipeline.contact.source import ContactPoints
from pipeline.geometry import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.options import StiffnessOptions
from pipeline.validation import InputError
from pipeline.verification.cases_modifications import (
    bilinear_topography,
    internal_gear_terms,
    terms_in_own_coordinates,
)

UM, MM = 1e-6, 1e-3


def _flank_points(pair: GearPair, n_s: int = 41, n_z: int = 9) -> tuple[np.ndarray, ...]:
    s = np.linspace(pair.s_start, pair.s_end, n_s)
    z = np.linspace(0.0, pair.face_width, n_z)
    ss, zz = np.meshgrid(s, z)
    return ss.ravel(), zz.ravel()


def test_relief_shapes_closed_form():
    """Linear, parabolic and circular-arc relief: C x / L, C (x / L)^2 and the circle through
    (0, 0) tangent to the flank and through (L, C): x^2 + (R - w)^2 = R^2."""
    c, n = 20 * UM, 5 * MM
    x = np.linspace(-1 * MM, n, 61)
    inside = np.clip(x, 0.0, None)
    np.testing.assert_allclose(shapes.relief(x, c, n, "linear"), c * inside / n, rtol=1e-12,
                               atol=1e-12 * c)
    np.testing.assert_allclose(shapes.relief(x, c, n, "parabolic"), c * (inside / n) ** 2,
                               rtol=1e-12, atol=1e-12 * c)
    w = shapes.relief(x, c, n, "arc")
    r = (n * n + c * c) / (2 * c)
    np.testing.assert_allclose(inside**2 + (r - w) ** 2, r * r, rtol=1e-15)
    assert w[-1] == pytest.approx(c, rel=1e-12)  # reaches C at L
    assert np.all(w[x <= 0.0] == 0.0)
    # tangent at its start: slope w' = x / sqrt(R^2 - x^2) -> 0; at L the arc is steeper
    # than the parabola's end slope 2 C / L only by the tiny C^2 / L^2 (R >> L)
    assert shapes.relief(np.array([1e-6 * n]), c, n, "arc")[0] < 1e-11 * c


def test_each_term_against_its_formula_in_the_gears_own_coordinates():
    """Pinion 20 mm wide, gear 24 mm (centred: its face position is z + 2 mm); each term at
    41 x 9 points of the path of contact against its formula in that gear's roll length and
    face position (frame docstring), to 1e-12 of the amount."""
    pair = GearPair(spur(50, "pinion"), spur(50, "gear", face_width=0.024))
    s, z = _flank_points(pair)
    p = pair.pinion
    rho1_tip = math.sqrt(p.active_tip_radius**2 - p.base_radius**2)
    assert rho1_tip - pair.s_start == pytest.approx(pair.path_length, rel=1e-12)
    flanks = terms_in_own_coordinates(pair, s, z)
    pinion, gear = flanks.pinion, flanks.gear
    expected_p, expected_g = flanks.pinion_terms, flanks.gear_terms
    b2 = 0.024
    fp, fg = flank_frames(pair)
    terms_p, terms_g = pinion.terms(fp, s, z), gear.terms(fg, s, z)
    for got, want in ((terms_p, expected_p), (terms_g, expected_g)):
        assert set(got) == set(want)
        for name, value in want.items():
            amount = np.abs(value).max()
            assert amount > 0.5 * UM, name  # each term really acts on the sampled points
            np.testing.assert_allclose(got[name], value, rtol=0, atol=1e-12 * amount,
                                       err_msg=name)
    # the gap is the sum of both flanks' terms
    gap = modification_gap(pair, s, z, (pinion, gear))
    total = sum(expected_p.values()) + sum(expected_g.values())
    np.testing.assert_allclose(gap, total, rtol=0, atol=1e-12 * np.abs(total).max())
    # the twist's corners: +S/4 at the gear's tip on face 2 and its root on face 1
    corners = gear.terms(fg, np.array([pair.s_start, pair.s_end]),  # its tip, its root
                         np.array([b2, 0.0]) - 0.002)["twist"]  # face 2, face 1
    np.testing.assert_allclose(corners, [5 * UM / 4, 5 * UM / 4], rtol=1e-12)


def test_symmetry(spur_pair_z50):
    """Lead crowning is symmetric about mid-face; on a pair of equal gears the pinion's tip
    relief at s is the gear's at s_start + s_end - s."""
    pair = spur_pair_z50
    s, z = _flank_points(pair)
    b = pair.face_width
    crowned = GearModification(lead=LeadModification(crowning=8 * UM))
    fp, fg = flank_frames(pair)
    np.testing.assert_allclose(crowned.deviation(fp, s, z), crowned.deviation(fp, s, b - z),
                               rtol=1e-12, atol=1e-12 * 8 * UM)
    assert crowned.deviation(fp, s, z).max() == pytest.approx(8 * UM, rel=1e-12)
    for shape in ("linear", "parabolic", "arc"):
        relief = GearModification(profile=ProfileModification(
            tip_relief=15 * UM, tip_relief_length=6 * MM, tip_relief_shape=shape))
        mirror = pair.s_start + pair.s_end - s
        np.testing.assert_allclose(relief.deviation(fp, s, z), relief.deviation(fg, mirror, z),
                                   rtol=0, atol=1e-12 * 15 * UM)
        assert relief.deviation(fp, np.array([pair.s_end]), np.array([0.0]))[0] == \
            pytest.approx(15 * UM, rel=1e-12)


SHORT = FlankModifications(15 * UM, 4 * MM, 12 * UM, 3.5 * MM, "parabolic", crowning=8 * UM,
                           slope_deviation=-5 * UM, pitch_errors=(0.0, 3 * UM))


def _explicit(short: FlankModifications) -> FlankModifications:
    """The short form's modifications given per gear."""
    def gear(amount, length, lead):
        return GearModification(profile=ProfileModification(
            tip_relief=amount, tip_relief_length=length, tip_relief_shape=short.relief_shape),
            lead=lead)
    return FlankModifications(
        pitch_errors=short.pitch_errors,
        pinion_flank=gear(short.tip_relief_pinion, short.relief_length_pinion,
                          LeadModification(crowning=short.crowning,
                                           slope=short.slope_deviation, common_width=True)),
        gear_flank=gear(short.tip_relief_gear, short.relief_length_gear, LeadModification()))


def _former_eps(pair, s, z, m):
    """The closed form the short form was evaluated with before the per-gear model (kept here
    as the reference): tip reliefs along the path, crowning and slope over b."""
    power = 1 if m.relief_shape == "linear" else 2
    on = np.clip(s, pair.s_start, pair.s_end)
    eps = m.tip_relief_pinion * np.clip((on - (pair.s_end - m.relief_length_pinion))
                                        / m.relief_length_pinion, 0.0, None) ** power
    eps = eps + m.tip_relief_gear * np.clip(((pair.s_start + m.relief_length_gear) - on)
                                            / m.relief_length_gear, 0.0, None) ** power
    b = pair.face_width
    return eps + m.crowning * (2.0 * z / b - 1.0) ** 2 + m.slope_deviation * (z / b - 0.5)


def _analytical_cycle(pair, mods, torque=340.0, positions=12, slices=10):
    op = OperatingPoint(torque=torque, speed=245.0)
    opts = ContactOptions(positions=positions, slices=slices, modifications=mods)
    return analyse_contact(compliance_source(pair, op, opts, StiffnessOptions(), None), op,
                           opts)


def test_short_form_is_the_per_gear_model_bit_for_bit(spur_pair_z50):
    """Also on a pinion wider than its gear (24 / 20 mm): the short form's crowning and slope
    stay over the common face width, as before the gears had modifications of their own."""
    for pair in (spur_pair_z50, GearPair(spur(50, "pinion", face_width=0.024),
                                         spur(50, "gear"))):
        s, z = _flank_points(pair)
        pts = ContactPoints(s=s, z=z, pair=np.zeros(s.size, int), width=np.ones(s.size))
        plain = initial_separations(pair, pts, FlankModifications(
            **{k: getattr(SHORT, k) for k in ("tip_relief_pinion", "relief_length_pinion",
                                              "tip_relief_gear", "relief_length_gear",
                                              "relief_shape", "crowning", "slope_deviation")}))
        assert np.array_equal(plain, _former_eps(pair, s, z, SHORT))
    pair = spur_pair_z50
    a = _analytical_cycle(pair, SHORT)
    b = _analytical_cycle(pair, _explicit(SHORT))
    for name in ("transmission_error", "mesh_stiffness", "pair_loads", "point_load",
                 "point_separation", "point_pressure"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.ptp(a.transmission_error) > 1 * UM  # the modifications act


def test_topography_equals_the_analytical_modification(tmp_path, spur_pair_z50):
    """The issue's check: a CSV grid written from analytical modifications that are bilinear
    on its cells equals them through the loaded contact to round-off."""
    pair = spur_pair_z50
    analytic, gridded = bilinear_topography(pair, tmp_path)
    s, z = _flank_points(pair, 97, 13)
    want = modification_gap(pair, s, z, analytic.flanks)
    assert np.ptp(want) > 10 * UM
    np.testing.assert_allclose(modification_gap(pair, s, z, gridded.flanks), want, rtol=0,
                               atol=1e-15 * np.abs(want).max() * 100)
    a, b = _analytical_cycle(pair, analytic), _analytical_cycle(pair, gridded)
    np.testing.assert_allclose(b.transmission_error, a.transmission_error, rtol=1e-11)
    np.testing.assert_allclose(b.point_load, a.point_load, rtol=1e-8,
                               atol=1e-10 * a.point_load.max())


def test_grid_checked_where_it_enters(tmp_path, spur_pair_z50):
    fp, _ = flank_frames(spur_pair_z50)
    lo, hi = fp.active_roll
    path = tmp_path / "short.csv"
    rows = ["face_position_mm,roll_length_mm,deviation_um"] + [
        f"{z},{r * 1e3},1.0" for z in (0.0, 20.0) for r in (lo + 1 * MM, hi)]
    path.write_text("\n".join(rows), encoding="utf-8")
    grid = read_topography(path, "pinion.modifications.topography_csv")
    with pytest.raises(InputError, match=r"^pinion.modifications.topography_csv \"short.csv\": "
                       r"roll lengths 18\.\d+ to 33\.4\d+ mm do not cover the pinion's active "
                       r"flank, 17\.\d+ to 33\.4\d+ mm$"):
        GearModification(topography=grid).check_fits(fp)
    path.write_text("\n".join(rows[:-1]), encoding="utf-8")
    with pytest.raises(InputError, match=r"3 rows are not a full grid of the 2 face positions "
                                         r"x 2 roll_length_mm values"):
        read_topography(path, "pinion.modifications.topography_csv")
    path.write_text("face_mm,roll_length_mm,deviation_um\n0,1,2\n", encoding="utf-8")
    with pytest.raises(InputError, match="must name face_position_mm"):
        read_topography(path, "pinion.modifications.topography_csv")


def test_crowning_under_a_slope_lowers_k_hbeta_in_closed_form():
    """Independent slices of uniform stiffness c0 (local contact left out): the line load is
    n c0 (delta - g(z)), so K_Hbeta = 1 + n c0 (mean g - min g) / w_m over the slice
    centres. Helix slope 15 um on the pinion, lead crowning 10 um on the gear (the gap is
    their sum): K_Hbeta falls from the slope's 1 + n c0 f / 2 (1 - 1/N) / w_m."""
    pair = GearPair(spur(30, "pinion"), spur(45, "gear"))
    c0, slices, torque = 1.4e10, 40, 500.0
    load = torque / pair.pinion.base_radius
    w_m = load / pair.face_width
    z = (np.arange(slices) + 0.5) * pair.face_width / slices
    results = {}
    x = 2 * z / pair.face_width - 1
    for name, mods, g in (
            ("slope", FlankModifications(pinion_flank=GearModification(
                lead=LeadModification(slope=15 * UM))), 15 * UM * x / 2),
            ("slope_and_crowning", FlankModifications(
                pinion_flank=GearModification(lead=LeadModification(slope=15 * UM)),
                gear_flank=GearModification(lead=LeadModification(crowning=10 * UM))),
             15 * UM * x / 2 + 10 * UM * x**2)):
        cyc = loaded_mesh_cycle(UniformSlices(pair, slices, c0), load, mods, "none", 24)
        dist = load_distribution(cyc, pair, OperatingPoint(torque=torque, speed=100.0))
        _, inside = pair.pair_positions(cyc.s0)
        n = inside.sum(axis=1)
        assert np.all(n * c0 * (g.max() - g.min()) < w_m)  # the whole face carries load
        np.testing.assert_allclose(dist.k_hbeta_position,
                                   1.0 + n * c0 * (g.mean() - g.min()) / w_m, rtol=1e-9)
        results[name] = dist.k_hbeta
    # continuous closed forms of mean g - min g: slope f (z/b - 1/2) -> f / 2; with crowning
    # C x^2 + f x / 2 (x = 2 z / b - 1) -> C / 3 + f^2 / (16 C) (minimum at x = -f / (4 C))
    f, c = 15 * UM, 10 * UM
    ratio = (c / 3 + f * f / (16 * c)) / (f / 2)
    assert ratio == pytest.approx(0.632, abs=1e-3)
    assert (results["slope_and_crowning"] - 1) / (results["slope"] - 1) == pytest.approx(
        ratio, rel=2.0 / slices)
    assert results["slope"] > 1.2


def test_light_load_transmission_error_follows_the_reliefs_harris():
    """Harris (1958): tip relief C = 10 um over L on both gears (linear), light load: TE p-p
    = C (1 - D / (2 L)), D = g_alpha - p_b (the double-contact zone), for D / 2 <= L <= D;
    checked on the sampled positions against min over the pairs of their gap (the exact
    light-load limit), within the elastic part P / (c0 b)."""
    pair = GearPair(spur(50, "pinion"), spur(50, "gear"))
    d = pair.path_length - pair.base_pitch
    c0, load, c = 1.4e10, 1.0, 10 * UM
    for length in (0.55 * d, 0.75 * d, d):
        relief = GearModification(profile=ProfileModification(tip_relief=c,
                                                               tip_relief_length=length))
        mods = FlankModifications(pinion_flank=relief, gear_flank=relief)
        cyc = loaded_mesh_cycle(UniformSlices(pair, 1, c0), load, mods, "none", 400)
        k = pair.pair_indices(beyond=False)
        s = cyc.s0[:, None] + k[None, :] * pair.base_pitch
        on = (s >= pair.s_start) & (s <= pair.s_end)
        gaps = modification_gap(pair, np.clip(s, pair.s_start, pair.s_end), np.zeros_like(s),
                                mods.flanks)
        min_gap = np.where(on, gaps, np.inf).min(axis=1)
        elastic = load / (c0 * pair.face_width)
        assert np.all(np.abs(cyc.transmission_error - min_gap) <= elastic * (1 + 1e-9))
        harris = c * (1.0 - d / (2.0 * length))
        step = (c / length) * pair.base_pitch / 400  # sampling: the peak is a tent of slope C/L
        assert np.ptp(cyc.transmission_error) == pytest.approx(harris, abs=step + 2 * elastic)


def test_internal_gear_in_its_own_coordinates():
    """A ring (internal gear, 80 teeth) against a 30-tooth planet: its roll length is
    |rho_2| = T1T2 + s, its tip the small diameter at s_start; a linear tip relief from a
    start diameter and a parabolic root relief by roll length against their formulas."""
    pair = GearPair(spur(30, "pinion"), spur(80, "gear", internal=True, bore_radius=0.13575))
    g = pair.gear
    s, z = _flank_points(pair)
    rho_tip = math.sqrt(g.active_tip_radius**2 - g.base_radius**2)
    assert rho_tip == pytest.approx(pair.t1t2 + pair.s_start, rel=1e-12)
    ring, want = internal_gear_terms(pair, s, z)
    terms = ring.terms(flank_frames(pair)[1], s, z)
    tip, root = want["tip_relief"], want["root_relief"]
    np.testing.assert_allclose(terms["tip_relief"], tip, rtol=0, atol=1e-12 * 15 * UM)
    np.testing.assert_allclose(terms["root_relief"], root, rtol=0, atol=1e-12 * 5 * UM)
    assert tip.max() == pytest.approx(15 * UM, rel=1e-9)
    assert root.max() == pytest.approx(5 * UM, rel=1e-9)
