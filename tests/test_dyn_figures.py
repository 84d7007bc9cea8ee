"""Dynamics figures and files: spectra keep every large order, sweeps start at 0 and mark the
natural frequencies, sweep.csv has every computed column, left/right herringbone halves."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from pipeline.cli.dynamics_files import shown_meshes, write_sweep
from pipeline.dynamics.excitation import rectangular_mesh_stiffness
from pipeline.dynamics.models.herringbone_planetary import HerringbonePlanetaryModel
from pipeline.dynamics.results import HarmonicResponse, Response
from pipeline.dynamics.sweep import mesh_force_sweep
from pipeline.viz.dynamics import (
    plot_harmonic_contributions,
    plot_spectrum,
    plot_sweep,
    shown_orders,
)

ROOT = Path(__file__).resolve().parents[1]


def _response(orders_amplitudes: dict[int, float], n: int = 256, T: float = 1e-3) -> Response:
    t = np.linspace(0.0, T, n + 1)
    d = sum(a * np.cos(2 * np.pi * h * t / T) for h, a in orders_amplitudes.items())
    d = np.atleast_2d(d)
    z = np.zeros((n + 1, 1))
    return Response(t, z, z, d, d, ("p.theta",), ("s-p1",), T)


def test_shown_orders_keeps_every_large_order():
    a = np.array([1.0, 0.2, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.02, 0.001])
    assert shown_orders(a) == 12  # order 12 is 2 % of the largest
    assert shown_orders(a, threshold=0.05) == 10  # at least 1-10
    assert shown_orders(a[:5]) == 5  # never beyond H
    assert shown_orders(np.zeros(4)) == 4


def test_spectrum_shows_order_7_and_names_the_mesh():
    """A DTE with order 7 as large as order 1 (the old plot stopped at 8, harmonics at 6)."""
    r = _response({1: 2e-6, 7: 2e-6, 13: 0.5e-6})
    ax = plot_spectrum([r], ["case"])
    heights = {round(p.get_x() + p.get_width() / 2): p.get_height() for p in ax.patches}
    assert heights[7] == pytest.approx(2.0, rel=1e-9) and heights[1] == pytest.approx(2.0)
    assert heights[13] == pytest.approx(0.5, rel=1e-9)
    assert max(heights) == 13 and "s-p1" in ax.get_title()
    assert ax.get_xlim()[1] == pytest.approx(13.6)


def test_harmonic_contributions_keep_order_7():
    r = _response({1: 1e-6})
    share = np.zeros((1, 20))
    share[0, [0, 1, 6]] = [0.45, 0.1, 0.45]
    hr = HarmonicResponse(r, np.arange(21), np.zeros((1, 21)), share, np.zeros((41, 1)))
    ax = plot_harmonic_contributions([hr], ["case"])
    heights = [p.get_height() for p in ax.patches]
    assert len(heights) == 10 and heights[6] == pytest.approx(0.45)
    assert ax.get_title() == "harmonic contributions to the DTE, mesh s-p1"


def _lumped(**kw):
    k = rectangular_mesh_stiffness(2.0e8, 3.0e8, 1.5, 120)
    return HerringbonePlanetaryModel(
        base_helix_angle=np.radians(8.0), k_sun_mesh=k, k_ring_mesh=k, groove=3.0e6,
        sun_torque=200.0, mesh_period=1 / 1500.0, damping_ratio=0.05,
        phase_sun=(0.0, 0.25, 0.5, 0.75), phase_ring=(0.1, 0.35, 0.6, 0.85), **kw,
    ).assembly().assemble()


@pytest.fixture(scope="module")
def herringbone_sweeps():
    f = np.linspace(300.0, 4000.0, 6)
    return {side: mesh_force_sweep(_lumped(sun_load_side=side), f, n_harmonics=8,
                                   executor=None)
            for side in ("both", "R")}


def test_left_right_equal_only_for_the_symmetric_set(herringbone_sweeps):
    """The left and right sun meshes of a herringbone set are mirror images when the sun
    torque acts on both halves and the right meshes have no extra phase (the lumped
    example file): their forces agree to round-off, so the sweep's L and R panels are
    equal. With the torque on the right half only (Xu et al. 2020: the output shaft),
    the left half's torque passes through the groove and the two sides differ."""
    sym, asym = herringbone_sweeps["both"], herringbone_sweeps["R"]
    i, j = sym.mesh_names.index("s-p1L"), sym.mesh_names.index("s-p1R")
    np.testing.assert_allclose(sym.rms_force[i], sym.rms_force[j], rtol=1e-9)
    np.testing.assert_allclose(sym.mean_force[i], sym.mean_force[j], rtol=1e-9)
    diff = np.abs(asym.rms_alternating[i] - asym.rms_alternating[j]) / asym.rms_alternating[i]
    assert diff.max() > 0.05
    fig = plot_sweep([sym], ["sym"], shown_meshes(sym))
    assert fig.axes[1].get_title() == "s-p1R: equal to s-p1L (symmetric model)"
    fig = plot_sweep([asym], ["asym"], shown_meshes(asym))
    assert fig.axes[1].get_title() == ""


def test_sweep_plot_from_zero_with_natural_frequencies(herringbone_sweeps):
    sw = herringbone_sweeps["R"]
    fn = np.array([0.0, 150.0, 700.0, 700.0, 2500.0, 9000.0])
    fig = plot_sweep([sw], ["x"], ["s-p1L", "s-p1R"], natural_frequencies=fn)
    for ax in fig.axes:
        assert ax.get_ylim()[0] == 0.0
        marks = sorted(line.get_xdata()[0] for line in ax.lines if line.get_linestyle() == ":")
        assert marks == [700.0, 2500.0]  # in range, rigid modes and duplicates dropped
        assert ax.get_ylabel().endswith("[kN]")


def test_sweep_csv_has_every_column_with_units(tmp_path, herringbone_sweeps):
    sw = herringbone_sweeps["R"]
    write_sweep(sw, tmp_path, "x", natural_frequencies=np.array([700.0]))
    with open(tmp_path / "sweep.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    assert len(head) == 1 + 6 * len(sw.mesh_names) and all(len(r) == len(head) for r in rows)
    data = np.array(rows[1:], dtype=float)
    k = sw.mesh_names.index("s-p1R")
    for name, ref in (("mean force s-p1R [N]", sw.mean_force[k]),
                      ("alternating rms force s-p1R [N]", sw.rms_alternating[k]),
                      ("max elastic force s-p1R [N]", sw.max_elastic_force[k]),
                      ("dynamic factor s-p1R [-]",
                       sw.max_elastic_force[k] / sw.mean_force[k])):
        assert data[:, head.index(name)] == pytest.approx(ref, rel=1e-8)
    assert (tmp_path / "sweep.png").stat().st_size > 0


def test_shown_meshes_are_the_first_planet_only():
    class _S:
        mesh_names = tuple(f"s-p{n}" for n in range(1, 12)) + ("r-p1",)

    assert shown_meshes(_S()) == ["s-p1"]


def _read_shapes(path):
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    modes = [j for j, h in enumerate(head) if h.startswith("mode ")]
    phi = np.array([[float(r[j]) for j in modes] for r in rows[1:]])
    return head, [r[0] for r in rows[1:]], [r[1] for r in rows[1:]], phi


def test_mode_shape_csv_holds_the_mass_normalised_eigenvectors(tmp_path):
    """Lin and Parker (1999)'s planetary set: mode_shapes.csv read back with csv.reader
    gives the model's eigenvectors (9 digits), one row per named coordinate with its
    unit, and they are mass-normalised: phi^T M phi = I on the model's mass matrix."""
    from pipeline.cli.dynamics_files import write_modes
    from pipeline.dynamics.analysis import analyse_modes
    from pipeline.dynamics.layout import model_layout
    from pipeline.dynamics.models.planetary import PlanetaryModel

    model = PlanetaryModel()
    res = analyse_modes(model)
    files = write_modes(res, tmp_path, model_layout(model))
    head, dofs, units, phi = _read_shapes(tmp_path / "mode_shapes.csv")
    assert dofs == list(res.dof_names) and len(dofs) == 3 * (3 + 4)
    assert units == ["rad/(kg m^2)^0.5" if d.endswith(".theta") else "m/kg^0.5" for d in dofs]
    assert phi.shape == res.shapes.shape
    np.testing.assert_allclose(phi, res.shapes, rtol=1e-8, atol=1e-8 * np.abs(phi).max())
    system = model.assembly().assemble()
    red = np.linalg.lstsq(system.basis, phi, rcond=None)[0]
    np.testing.assert_allclose(red.T @ system.M @ red, np.eye(phi.shape[1]), atol=1e-7)
    assert head[3 + 1] == f"mode 1 {res.frequencies[1]:.6g} Hz [row unit]"
    pngs = sorted(p.name for p in files if p.suffix == ".png")
    assert pngs == ["mode_shapes.png", "mode_shapes_2.png"]  # 20 elastic modes, 12 a page


def test_every_mode_of_the_herringbone_set_is_drawn(tmp_path):
    """28 elastic modes of the lumped herringbone set on 3 pages (the old figure had 8 bar
    charts with 56 tick labels each); panels carry no tick labels."""
    from pipeline.config import load_gearbox
    from pipeline.dynamics.analysis import analyse_modes
    from pipeline.dynamics.layout import model_layout
    from pipeline.viz.modes import mode_pages, plot_mode_shapes

    box = load_gearbox(ROOT / "workflows/configs/herringbone_planetary_lumped.toml")
    model = box.lumped
    res = analyse_modes(model)
    pages = mode_pages(res)
    elastic = [k for k in range(res.frequencies.size) if res.frequencies[k] > 0]
    assert len(elastic) == 28 and sum(pages, []) == elastic and len(pages) == 3
    fig = plot_mode_shapes(res, model_layout(model), pages[0])
    drawn = [a for a in fig.axes if a.get_title()]
    assert len(drawn) == 12 and not any(a.axison for a in fig.axes)
    assert drawn[0].get_title().startswith(f"mode {pages[0][0]}: {res.frequencies[1]:.1f} Hz")


def test_layouts_put_the_gears_where_they_are():
    from pipeline.dynamics.layout import model_layout
    from pipeline.dynamics.models.planetary import PlanetaryModel
    from pipeline.dynamics.models.spur_pair import SpurPairModel

    m = PlanetaryModel(planet_angles=tuple(np.radians([0.0, 80.0, 180.0, 270.0])))
    lay = model_layout(m)
    p2 = lay.place("p2")
    assert np.hypot(*p2.centre) == pytest.approx(m.carrier_radius)
    assert np.degrees(np.arctan2(p2.centre[1], p2.centre[0])) == pytest.approx(80.0)
    assert p2.frame_angle == pytest.approx(np.radians(80.0)) and p2.role == "planet"
    assert lay.place("r").radius == m.base_radius_ring and not lay.schematic
    pair = model_layout(SpurPairModel(rectangular_mesh_stiffness(2e8, 3e8, 1.6, 60)))
    p, g = pair.place("pinion"), pair.place("gear")
    assert np.hypot(p.centre[0] - g.centre[0], p.centre[1] - g.centre[1]) == pytest.approx(
        p.radius + g.radius)  # base circles touch on the line of action (the x axis)


def test_an_internal_pair_draws_the_ring_around_the_pinion():
    """The planet-ring pair of the examples (planet z 37 inside ring z 83): the ring's centre
    lies above the line of action at the operating centre distance a_w from the pinion's,
    both base circles tangent to the line y = -r_b1 (T1 at x = 0, T2 at x = -T1T2 with
    T1T2 = a_w sin alpha_w, ISO 21771), and the ring turns the pinion's way."""
    from pipeline.config import load_gearbox
    from pipeline.dynamics.layout import model_layout
    from pipeline.dynamics.models.spur_pair import spur_pair_model
    from pipeline.dynamics.options import PairDynamicsOptions

    box = load_gearbox(Path(__file__).resolve().parents[1] / "workflows/configs"
                       / "planet_ring_pair.toml")
    pair = box.pair
    options = PairDynamicsOptions(mesh_stiffness=rectangular_mesh_stiffness(2e8, 3e8, 1.6, 60))
    model = spur_pair_model(pair, (box.bodies["pinion"], box.bodies["gear"]), box.operation,
                            options)
    rp, t = pair.pinion.base_radius, pair.t1t2
    lay = model_layout(model)
    p, g = lay.place("pinion"), lay.place("gear")
    assert pair.gear.internal and g.spin == p.spin == 1
    assert np.hypot(g.centre[0], g.centre[1]) == pytest.approx(pair.operating_centre_distance,
                                                               rel=1e-12)
    assert g.centre[1] - g.radius == pytest.approx(-rp, abs=1e-15)  # tangent to y = -r_b1
    assert lay.line_of_action == ((0.0, -rp), (-t, -rp))
    assert t == pytest.approx(pair.operating_centre_distance
                              * math.sin(pair.operating_pressure_angle), rel=1e-14)


def test_other_models_get_a_schematic_grid():
    from pipeline.dynamics.layout import model_layout
    from pipeline.dynamics.models.split_torque_helicopter import split_torque_helicopter_model

    lay = model_layout(split_torque_helicopter_model())
    centres = [p.centre for p in lay.places]
    assert lay.schematic and len(centres) == 18 and len(set(centres)) == 18
    assert max(c[0] for c in centres) == pytest.approx(3.0 * 4)  # 5 columns for 18 bodies
