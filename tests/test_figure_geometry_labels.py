"""Pair geometry drawn where it is, and every label says what is drawn, in its unit.

* The transverse layout of a pair against the closed forms of two circles and their common
  tangent (the line of action): T1 = r_b1 (-sin a, cos a) from O1; T2 = O2 + r_b2 (sin a,
  -cos a) for an external pair (beyond the pitch point) and O2 + r_b2 (-sin a, cos a) for an
  internal one, behind T1 at roll coordinate -a_w sin a (ISO 21771: for an internal pair
  both base tangent points lie on the same side of the pitch point); the contact points'
  distances to T1, T2 and the centres are the radii of curvature and the contact radii of
  :class:`GearPair`. The line-of-action figure puts its labels at those exact points.
* The contact-pressure figure says on which side a flank's root is (a ring's root is its
  largest diameter) and keeps its maximum marker inside the axes.
* Dynamics, stiffness, profile and workflow figures: no doubled word ("mesh force mesh",
  "mesh mesh"), units that match the plotted numbers.
"""

from __future__ import annotations

import math
import re
from types import SimpleNamespace

import numpy as np
import pytest
from gearsets import spur
from helpers import UniformSlices, load_workflow
from matplotlib.backends.backend_agg import FigureCanvasAgg

from pipeline.contact.distribution import load_distribution
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.separations import FlankModifications
from pipeline.dynamics.results import HarmonicResponse, Response
from pipeline.geometry import GearPair
from pipeline.geometry.profile import tooth_profile
from pipeline.geometry.transverse import TransverseLayout
from pipeline.operation import OperatingPoint
from pipeline.viz.distribution import plot_contact_pressure
from pipeline.viz.dynamics import (
    plot_harmonic_contributions,
    plot_spectrum,
    plot_sweep,
    plot_time_history,
)
from pipeline.viz.geometry import plot_line_of_action, plot_profiles
from pipeline.viz.stiffness import plot_friction_coefficients

ALPHA = math.radians(20.0)
M = 3e-3


def _ring_pair() -> GearPair:
    """Planet 30 / ring 80, m 3 mm, 20 deg, no shift (workflows/configs/planet_ring_pair.toml):
    a_w = m (80 - 30) / 2 = 75 mm, alpha_wt = 20 deg."""
    return GearPair(spur(30, "planet"), spur(80, "ring", internal=True, bore_radius=0.13575))


def _external_pair() -> GearPair:
    """z 50/50, m 3 mm, 20 deg: a_w = 150 mm, alpha_wt = 20 deg."""
    return GearPair(spur(50, "pinion"), spur(50, "gear"))


def _texts(fig) -> list[str]:
    """Every title, axis label, legend entry and annotation of ``fig`` and its subfigures."""
    out = [fig._suptitle.get_text() if fig._suptitle else ""]
    figs = [fig, *fig.subfigs]
    for f in figs:
        out += [t.get_text() for leg in f.legends for t in leg.get_texts()]
    for ax in fig.get_axes():
        out += [ax.get_title(), ax.get_xlabel(), ax.get_ylabel()]
        if ax.get_legend():
            out += [t.get_text() for t in ax.get_legend().get_texts()]
    return [t for t in out if t]


def _doubled(text: str) -> list[str]:
    """Words written twice in a row ("mesh mesh"), numbers excepted."""
    return [m.group(0) for m in re.finditer(r"\b([A-Za-z_]+)\b[\s,:]+\b\1\b", text)]


def test_doubled_word_finder():
    assert _doubled("mesh force mesh [kN]") == []
    assert _doubled("DTE spectrum, mesh mesh") == ["mesh mesh"]
    assert _doubled("spur: mesh: mesh") == ["mesh: mesh"]


# ---- transverse layout against closed forms ---------------------------------------------


@pytest.mark.parametrize("internal", [False, True])
def test_transverse_layout_against_closed_forms(internal):
    pair = _ring_pair() if internal else _external_pair()
    z1, z2 = (30, 80) if internal else (50, 50)
    a_w = M * (z2 - z1) / 2 if internal else M * (z1 + z2) / 2  # 75 / 150 mm
    rb1, rb2 = M * z1 / 2 * math.cos(ALPHA), M * z2 / 2 * math.cos(ALPHA)
    lay = TransverseLayout(pair)
    sa, ca = math.sin(ALPHA), math.cos(ALPHA)
    o2 = np.array([0.0, -a_w if internal else a_w])
    np.testing.assert_allclose(lay.gear_centre, o2, atol=1e-15)
    np.testing.assert_allclose(lay.t1, rb1 * np.array([-sa, ca]), atol=1e-15)
    t2 = o2 + rb2 * (np.array([-sa, ca]) if internal else np.array([sa, -ca]))
    np.testing.assert_allclose(lay.points["T2"], t2, atol=1e-14)
    assert lay.s_t2 == pytest.approx((-1 if internal else 1) * a_w * sa, rel=1e-13)
    # both radii to the tangent points are normal to the line of action
    for o, t in ((lay.pinion_centre, lay.t1), (o2, lay.points["T2"])):
        assert abs(np.dot(t - o, lay.direction)) < 1e-15
    # the pitch point C is on the centre line at r_w1 from O1 and r_w2 from O2
    r_w1, r_w2 = M * z1 / 2, M * z2 / 2
    np.testing.assert_allclose(lay.points["C"], [0.0, r_w1], atol=1e-14)
    assert np.linalg.norm(lay.points["C"] - o2) == pytest.approx(r_w2, rel=1e-13)
    # A on the gear's tip circle, E on the pinion's
    assert np.linalg.norm(lay.points["A"] - o2) == pytest.approx(pair.gear.tip_radius_, rel=1e-13)
    assert np.linalg.norm(lay.points["E"]) == pytest.approx(pair.pinion.tip_radius_, rel=1e-13)
    # distances from T1, T2 and the centres are GearPair's radii of curvature and contact radii
    s = np.linspace(pair.s_start, pair.s_end, 7)
    x = lay.point(s)
    rho1, rho2 = pair.curvature_radii(s)
    r1, r2 = pair.contact_radii(s)
    np.testing.assert_allclose(np.linalg.norm(x - lay.t1, axis=1), rho1, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(x - lay.points["T2"], axis=1), np.abs(rho2),
                               rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(x, axis=1), r1, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(x - o2, axis=1), r2, rtol=1e-12)


def test_single_contact_points_b_and_d():
    """eps_alpha = 1.755 (z 50/50): B = E - p_bt and D = A + p_bt, p_bt = pi m cos(alpha)."""
    pair = _external_pair()
    rolls = TransverseLayout(pair).rolls
    pb = math.pi * M * math.cos(ALPHA)
    assert rolls["B"] == pytest.approx(pair.s_end - pb, rel=1e-13)
    assert rolls["D"] == pytest.approx(pair.s_start + pb, rel=1e-13)
    assert rolls["A"] < rolls["B"] < rolls["C"] < rolls["D"] < rolls["E"]


def _annotations(ax) -> dict[str, tuple[float, float]]:
    return {t.get_text(): tuple(t.xy) for t in ax.texts}


def test_line_of_action_figure_puts_t2_behind_t1_for_a_ring():
    """Planet 30 / ring 80: T2 = (-r_b2 sin a, -a_w + r_b2 cos a) = (-38.5673, 30.9627) mm,
    at s = -a_w sin a = -25.6515 mm; drawn there in both the plane and the roll strip
    (it was drawn at +25.65 mm, beyond the pitch point)."""
    fig = plot_line_of_action(_ring_pair())
    FigureCanvasAgg(fig).draw()
    whole, near, strip = fig.get_axes()
    rb2 = 0.12 * math.cos(ALPHA)
    t2 = np.array([-rb2 * math.sin(ALPHA), -0.075 + rb2 * math.cos(ALPHA)]) * 1e3
    np.testing.assert_allclose(t2, [-38.5673, 30.9627], atol=1e-4)
    np.testing.assert_allclose(_annotations(near)["T2"], t2, atol=1e-9)
    np.testing.assert_allclose(_annotations(near)["T1"],
                               0.045 * math.cos(ALPHA) * np.array([-math.sin(ALPHA),
                                                                   math.cos(ALPHA)]) * 1e3,
                               atol=1e-9)
    s = _annotations(strip)
    assert s["T2"][0] == pytest.approx(-75.0 * math.sin(ALPHA), abs=1e-9)  # -25.6515 mm
    assert s["T1"][0] == 0.0
    assert s["T2"][0] < s["T1"][0] < s["A"][0] < s["C"][0] < s["E"][0]
    lo, hi = strip.get_xlim()
    assert lo < s["T2"][0] and hi > s["E"][0]  # nothing named falls off the strip
    for ax in (whole, near):
        assert ax.get_aspect() == 1.0
        x0, x1 = ax.get_xlim()
        y0, y1 = ax.get_ylim()
        for name in ("T1", "T2", "A", "E"):
            px, py = _annotations(near)[name]
            assert x0 < px < x1 and y0 < py < y1
    assert _annotations(whole)["O2"] == pytest.approx((0.0, -75.0), abs=1e-12)
    assert fig._suptitle.get_text().startswith("internal pair")


def test_line_of_action_figure_external_t2_beyond_the_pitch_point():
    fig = plot_line_of_action(_external_pair())
    _, near, strip = fig.get_axes()
    rb2 = 0.075 * math.cos(ALPHA)
    t2 = np.array([rb2 * math.sin(ALPHA), 0.150 - rb2 * math.cos(ALPHA)]) * 1e3
    np.testing.assert_allclose(_annotations(near)["T2"], t2, atol=1e-9)
    s = _annotations(strip)
    assert s["T2"][0] == pytest.approx(150.0 * math.sin(ALPHA), abs=1e-9)  # 51.303 mm
    assert s["T1"][0] < s["A"][0] < s["C"][0] < s["E"][0] < s["T2"][0]


# ---- contact pressure: root side and markers ---------------------------------------------


def _pressure_figure(pair: GearPair):
    torque = 150.0
    load = torque / pair.pinion.base_radius
    cyc = loaded_mesh_cycle(UniformSlices(pair, 8, 1.4e10), load, FlankModifications(),
                            "none", 24)
    dist = load_distribution(cyc, pair, OperatingPoint(torque=torque, speed=100.0))
    fig = plot_contact_pressure(cyc, dist, pair, "t")
    FigureCanvasAgg(fig).draw()
    return fig, dist


def _marker_inside(ax) -> bool:
    """The maximum marker (the axes' one line) lies whole inside the axes box, in pixels."""
    (line,) = ax.lines
    px = ax.transData.transform(np.column_stack([line.get_xdata(), line.get_ydata()]))[0]
    half = line.get_markersize() / 2 * ax.figure.dpi / 72.0
    box = ax.get_window_extent()
    return (box.x0 + half < px[0] < box.x1 - half) and (box.y0 + half < px[1] < box.y1 - half)


def test_contact_pressure_ring_root_on_the_right_and_markers_inside():
    """The ring's flank runs from its tip circle (the smallest diameter, 2 r_a2 = 234 mm, met
    at the start of contact A) to near its root (the largest): drawn with the diameter
    growing to the right, its root side is the right one, and the label says so. The
    maximum (at A for this pair, on the edge of the data) is drawn inside the axes."""
    pair = _ring_pair()
    fig, dist = _pressure_figure(pair)
    pin, ring = fig.axes[:2]
    assert ring.get_xlabel() == "gear (internal) diameter [mm], root side right"
    assert pin.get_xlabel() == "pinion diameter [mm], root side left"
    x0, x1 = ring.get_xlim()
    assert x0 < x1  # diameter grows to the right
    mesh_x = ring.collections[0].get_coordinates()[..., 0]
    assert mesh_x.min() == pytest.approx(2e3 * pair.gear.tip_radius_, rel=1e-12)  # 234 mm
    assert mesh_x.min() == pytest.approx(234.0, rel=1e-12)
    assert mesh_x.max() < 2e3 * pair.gear.root_radius  # the root lies further right
    assert dist.hertz_max.gear_radius == pytest.approx(pair.gear.tip_radius_, rel=1e-9)
    assert _marker_inside(pin) and _marker_inside(ring)


def test_contact_pressure_external_gear_root_on_the_left():
    fig, _ = _pressure_figure(_external_pair())
    assert fig.axes[1].get_xlabel() == "gear diameter [mm], root side left"
    mesh_x = fig.axes[1].collections[0].get_coordinates()[..., 0]
    # the external gear's tip (largest diameter) is at the right end of its data
    assert mesh_x.max() == pytest.approx(2e3 * _external_pair().gear.tip_radius_, rel=1e-12)
    assert all(_marker_inside(ax) for ax in fig.axes[:2])


# ---- wording ----------------------------------------------------------------------------


def _response(mesh: str, n: int = 64, T: float = 1e-3) -> Response:
    t = np.linspace(0.0, T, n + 1)
    d = np.atleast_2d(2e-6 * np.cos(2 * np.pi * t / T))
    z = np.zeros((n + 1, 1))
    return Response(t, z, z, d, 4e3 * (1 + d / 2e-6), ("p.theta",), (mesh,), T)


@pytest.mark.parametrize("mesh", ["mesh", "s-p1"])
def test_dynamics_labels_name_the_mesh_once_with_units(mesh):
    """A pair's only mesh is called "mesh": labels said "mesh force mesh [kN]" and titles
    "DTE spectrum, mesh mesh"."""
    r = _response(mesh)
    hr = HarmonicResponse(r, np.arange(11), np.zeros((1, 11)), np.full((1, 10), 0.1),
                          np.zeros((21, 1)))
    sw = SimpleNamespace(frequencies=np.array([100.0, 200.0, 300.0]), mesh_names=(mesh,),
                         rms_force=np.array([[4.1e3, 5.0e3, 4.2e3]]),
                         rms_alternating=np.array([[0.1e3, 1.0e3, 0.2e3]]))
    figs = [plot_time_history([r], ["case"]), plot_spectrum([r], ["case"]).figure,
            plot_harmonic_contributions([hr], ["case"]).figure,
            plot_sweep([sw], ["case"], [mesh])]
    texts = [t for f in figs for t in _texts(f)]
    assert not [d for t in texts for d in _doubled(t)]
    named = mesh != "mesh"
    th, spec, harm, sweep = (f.axes for f in figs)
    assert th[0].get_title() == "DTE and elastic mesh force" + (", mesh s-p1" if named else "")
    assert spec[0].get_title() == "DTE spectrum" + (", mesh s-p1" if named else "")
    assert th[0].get_ylabel() == "DTE [um]" and th[1].get_ylabel() == (
        "elastic mesh force k (delta - e) [kN]")
    assert th[1].lines[0].get_ydata().max() == pytest.approx(8.0)  # 8 kN peak drawn in kN
    assert sweep[0].get_ylabel() == ("RMS mesh force, mesh s-p1 [kN]" if named
                                     else "RMS mesh force [kN]")
    assert sweep[0].lines[0].get_ydata() == pytest.approx([4.1, 5.0, 4.2])


def test_friction_torque_coefficient_in_N_m_per_um():
    """KT_f = sum lam mu k rho is a torque per unit mesh deflection (N m/m); drawn in N m/um:
    mu 0.05, k 3e8 N/m, rho 22 mm give 3.3e5 N m/m = 0.33 N m/um (was labelled kN)."""
    x = np.linspace(0.0, 7.2, 4)
    kt = np.full(4, 0.05 * 3e8 * 0.022)
    fig = plot_friction_coefficients(x, np.full(4, 1.5e7), kt, -kt)
    ax = fig.axes[1]
    assert ax.get_ylabel().endswith("[N m/um]") and "KT_f" in ax.get_ylabel()
    assert "kN" not in ax.get_ylabel()
    assert ax.lines[0].get_ydata() == pytest.approx(np.full(4, 0.33))
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["pinion, KT_f1",
                                                                  "gear, KT_f2"]


def test_profile_titles_say_undercut_in_words():
    """An 8-tooth unshifted pinion is undercut (z < 2 / sin^2(20 deg) = 17.1), a 50-tooth gear
    is not; the titles said "undercut = True/False"."""
    p, g = spur(8, "pinion", bore_radius=0.005), spur(50, "gear")
    profs = (tooth_profile(p), tooth_profile(g))
    assert profs[0].undercut and not profs[1].undercut
    fig = plot_profiles((p, g), profs)
    assert [ax.get_title() for ax in fig.axes] == ["pinion (external): z = 8, undercut",
                                                    "gear (external): z = 50, no undercut"]
    assert fig.axes[0].get_xlabel() == "x [mm]" and fig.axes[0].get_ylabel() == "y [mm]"


def test_profile_panels_fill_their_slots():
    """Equal-scale profile panels of a z 50/50 pair fill their slots (the figure's height
    follows the drawing's aspect): the axes box shrunk to equal scale keeps >= 95 % of the
    slot's height (68 % when every panel was 4 in high, an empty band between them);
    with an undercut z 8 pinion the taller drawing sets the height (its panel >= 95 %)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    for gears, full in (((spur(50, "pinion"), spur(50, "gear")), (0, 1)),
                        ((spur(8, "pinion", bore_radius=0.005), spur(50, "gear")), (0,))):
        fig = plot_profiles(gears, tuple(tooth_profile(g) for g in gears))
        FigureCanvasAgg(fig).draw()
        for i in full:
            ax = fig.axes[i]
            assert ax.get_position().height >= 0.95 * ax.get_position(original=True).height


def test_excitation_comparison_figures_have_their_own_titles(monkeypatch):
    """The sweep figure carried the excitation figure's title. Its dotted line is the mesh
    frequency at the operating speed: 50 teeth at 2340 rpm mesh at 50 x 2340 / 60 = 1950 Hz."""
    wf = load_workflow("excitation_comparison")
    speed = 2340 * math.pi / 30.0  # rad/s
    period = 1.0 / 1950.0
    f = np.linspace(500.0, 6000.0, 5)
    sweep = SimpleNamespace(frequencies=f, rms_force=np.array([np.full(5, 5e3)]),
                            dynamic_factor=np.array([np.full(5, 1.3)]))
    res = SimpleNamespace(
        dynamics=SimpleNamespace(sweep=sweep,
                                 response=SimpleNamespace(response=SimpleNamespace(
                                     period=period))),
        gearbox=SimpleNamespace(operation=SimpleNamespace(speed=speed),
                                stiffness=SimpleNamespace(friction_model=None),
                                dynamics=SimpleNamespace(excitation="analytical")),
        meshes={"mesh": None})
    signal = SimpleNamespace(values=np.full(8, 3e8))
    import pipeline.run.dynamics as run_dynamics

    monkeypatch.setattr(run_dynamics, "mesh_excitation", lambda *a: SimpleNamespace(
        stiffness=signal, transmission_error=None))
    runs = {"analytical k(t)": res}
    sw_fig = wf.plot_sweeps(runs, "pair")
    ex_fig = wf.plot_excitations(runs, "pair")
    sw_title, ex_title = sw_fig.axes[0].get_title(), ex_fig.axes[0].get_title()
    assert sw_title != ex_title
    assert "dynamic mesh force" in sw_title and "excitation" in ex_title
    assert "1950 Hz" in sw_fig.axes[1].get_xlabel() and "2340 rpm" in sw_fig.axes[1].get_xlabel()
    dotted = [ln for ln in sw_fig.axes[0].lines if ln.get_linestyle() == ":"]
    assert dotted[0].get_xdata()[0] == pytest.approx(1950.0)
    assert sw_fig.axes[0].get_ylabel() == "RMS dynamic mesh force [kN]"
    assert ex_fig.axes[0].lines[0].get_ydata() == pytest.approx(np.full(8, 300.0))  # N/um
    assert not [d for fig in (sw_fig, ex_fig) for t in _texts(fig) for d in _doubled(t)]
