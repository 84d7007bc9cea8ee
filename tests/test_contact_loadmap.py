"""Load maps (pipeline.contact.loadmap) and the ``gearpipe contact`` command."""

from __future__ import annotations

import argparse
import json
import math

import meshio
import numpy as np
import pytest

from pipeline.cli import contact as commands
from pipeline.config.gearbox import contact_options_from_table
from pipeline.contact.loadmap import (
    flank_load_map,
    flank_surface,
    mapped_members,
    write_load_map_vtu,
)
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.separations import FlankModifications
from pipeline.contact.source import SliceCompliance
from pipeline.stiffness.mesh import PairModel
from pipeline.stiffness.tooth import classical_tooth_model, hertz_compliance
from pipeline.validation import InputError
from workflows.default_case import DEMO_PAIR


@pytest.fixture(scope="module")
def helical_cycle(helical_traction_pair):
    pair = helical_traction_pair
    model = PairModel(pair, classical_tooth_model(pair.pinion), classical_tooth_model(pair.gear),
                      hertz_compliance(pair.pinion, pair.gear))
    L = 0.25 * pair.path_length
    mods = FlankModifications(15e-6, L, 15e-6, L, crowning=8e-6)
    src = SliceCompliance(model, slices=12)
    return loaded_mesh_cycle(src, 6031.0 / pair.pinion.base_radius, mods, positions=30)


def test_load_map_of_spur_pair_single_contact_zone(spur_pair_z50):
    """Spur pair, eps = 0, constant Hertz, contact on the nominal path: in the single-tooth
    zone (s_end - p_bt, s_start + p_bt), one sample spacing in from its ends, one pair
    carries P over the face width, so the map shows p = P / b there exactly (1e-12), and
    less in the double-tooth zones."""
    pair = spur_pair_z50
    model = PairModel(pair, classical_tooth_model(pair.pinion), classical_tooth_model(pair.gear),
                      hertz_compliance(pair.pinion, pair.gear))
    P = 340.0 / pair.pinion.base_radius
    cyc = loaded_mesh_cycle(SliceCompliance(model, slices=1, tip_contact=False), P,
                            local="linear", positions=60)
    lm = flank_load_map(cyc, pair, profile_points=200)
    assert lm.z.tolist() == [0.0, pair.face_width / 2, pair.face_width]  # one slice
    h = 1.01 * pair.base_pitch / 60  # sample spacing: interpolation across the zone edge
    single = (lm.s > pair.s_end - pair.base_pitch + h) & (lm.s < pair.s_start
                                                          + pair.base_pitch - h)
    assert single.sum() > 20
    assert lm.unit_load[single] == pytest.approx(P / pair.face_width, rel=1e-12)
    double = (lm.s < pair.s_end - pair.base_pitch - h) | (lm.s > pair.s_start
                                                          + pair.base_pitch + h)
    assert lm.unit_load[double].max() < P / pair.face_width * (1 - 1e-3)


def test_flank_surface_lies_on_the_involute(helical_traction_pair, helical_cycle):
    """The 3D flank points lie at the pinion radius sqrt(s^2 + r_b1^2) of their roll
    coordinate at every face position, and span the face width."""
    pair = helical_traction_pair
    lm = flank_load_map(helical_cycle, pair, profile_points=50)
    assert lm.unit_load.shape == (50, 12 + 2)
    xyz = flank_surface(pair, lm)
    r = np.hypot(xyz[..., 0], xyz[..., 1])
    assert r == pytest.approx(np.broadcast_to(lm.pinion_radius[:, None], r.shape), rel=1e-12)
    assert xyz[0, -1, 2] == pytest.approx(pair.face_width)
    assert xyz[0, 0, 2] == 0.0


def test_vtu_round_trip(tmp_path, helical_traction_pair, helical_cycle):
    """The VTU read back with meshio holds the grid (n_s x n_z points, mm) and the unit
    load in N/mm equal to the map in N/m / 1000 (float64 round trip: 1e-12)."""
    lm = flank_load_map(helical_cycle, helical_traction_pair, profile_points=20)
    path = write_load_map_vtu(helical_traction_pair, lm, tmp_path / "map.vtu")
    mesh = meshio.read(path)
    assert mesh.points.shape[0] == lm.unit_load.size
    got = np.sort(mesh.point_data["unit_load_N_per_mm"])
    assert got == pytest.approx(np.sort(lm.unit_load.ravel() * 1e-3), rel=1e-12)
    r = np.hypot(mesh.points[:, 0], mesh.points[:, 1]) * 1e-3
    assert r.min() == pytest.approx(lm.pinion_radius.min(), rel=1e-9)


def test_contact_options_table():
    """[contact] keys in um/mm convert to SI; unknown keys and bad values are named."""
    opts = contact_options_from_table({"tip_relief_pinion_um": 12,
                                       "tip_relief_length_pinion_mm": 3,
                                       "pitch_errors_um": [0, 4], "local_contact": "linear"})
    assert opts.modifications.tip_relief_pinion == pytest.approx(12e-6)
    assert opts.modifications.relief_length_pinion == pytest.approx(3e-3)
    assert opts.modifications.pitch_errors == pytest.approx((0.0, 4e-6))
    with pytest.raises(InputError, match="tip_relief_um"):
        contact_options_from_table({"tip_relief_um": 3})
    with pytest.raises(InputError, match="local_contact"):
        contact_options_from_table({"local_contact": "hertz"})


CONFIG = 'name = "spur_contact"\n' + DEMO_PAIR + """\
[stiffness]
friction = 0.05
[contact]
positions = 24
local_contact = "linear"
tip_relief_pinion_um = 10
tip_relief_length_pinion_mm = 2
render = {render}
"""


def test_contact_command_writes_its_outputs(tmp_path, capsys):
    """gearpipe contact on a spur pair like the assembly-error paper's (classical tooth model): all
    files are written, the JSON load equals 340 N m / r_b1 and the LTCA/slice mean ratio is
    above 1: the gear's unrelieved tip corner touches before the path of contact and shares
    the load in single contact (1.092; on the nominal path 0.99, the pinion's relief
    unloading its tip in double contact)."""
    cfg = tmp_path / "spur.toml"
    cfg.write_text(CONFIG.format(render="false"))  # the PNG render is tested above
    parser = argparse.ArgumentParser()
    commands.add_arguments(parser)
    args = parser.parse_args([str(cfg), "--out", str(tmp_path / "out"), "--json",
                              "--tooth-model", "classical"])
    assert commands.run(args) == 0
    summary = json.loads(capsys.readouterr().out)
    out = tmp_path / "out"
    for name in ("contact_cycle.csv", "contact_points.csv", "contact_cycle.png",
                 "load_map_2d.png", "load_map.vtu", "contact.json", "run.json"):
        assert (out / name).is_file(), name
    rb = 0.5 * 50 * 3e-3 * math.cos(math.radians(20))
    assert summary["load_N"] == pytest.approx(340.0 / rb, rel=1e-12)
    assert 1.05 < summary["ltca_over_slice_method_mean"] < 1.15


def test_render_load_map_png(tmp_path, helical_traction_pair, helical_cycle):
    """The off-screen pyvista render: one row per flank (pinion and the external gear), the
    colour scale of both (and of the tube along a tip edge whose corner touches beyond the
    path) from 0 to the largest unit load, a PNG of the requested width that is not blank
    (the coloured flanks give many distinct colours)."""
    from PIL import Image

    from pipeline.viz import save
    from pipeline.viz.loadmap import render_load_map

    lm = flank_load_map(helical_cycle, helical_traction_pair, profile_points=30)
    plotter = render_load_map(helical_traction_pair, lm, "test", window_width=700)
    assert len(plotter.renderers) == 2
    p_max = lm.unit_load.max() * 1e-3
    ranges = [tuple(a.mapper.scalar_range) for r in plotter.renderers
              for a in r.actors.values()
              if getattr(getattr(a, "mapper", None), "scalar_visibility", False)]
    tubes = sum(lm.tip_corner_load(m).max() > 0 for m in ("pinion", "gear"))
    assert len(ranges) == 2 + tubes and all(r == pytest.approx((0.0, p_max)) for r in ranges)
    path = save(plotter, tmp_path / "map.png")
    img = np.asarray(Image.open(path).convert("RGB"))
    assert img.shape[1] == 700
    assert len(np.unique(img.reshape(-1, 3), axis=0)) > 200


def test_gear_flank_surface_and_members(helical_traction_pair, helical_cycle):
    """The gear's flank carries the same grid at the gear radius of each contact point,
    sqrt((T1T2 - s)^2 + r_b2^2) on the path, its tip radius where its tip corner touches
    before the path; an internal gear's flank is refused by name."""
    from pipeline.geometry.tip_contact import contact_radii_at

    pair = helical_traction_pair
    lm = flank_load_map(helical_cycle, pair, profile_points=40)
    xyz = flank_surface(pair, lm, "gear")
    r = np.hypot(xyz[..., 0], xyz[..., 1])
    r2 = contact_radii_at(pair, lm.s)[1]
    assert r == pytest.approx(np.broadcast_to(r2[:, None], r.shape), rel=1e-12)
    on = (lm.s >= pair.s_start) & (lm.s <= pair.s_end)
    assert r2[on] == pytest.approx(np.hypot(pair.t1t2 - lm.s[on], pair.gear.base_radius),
                                   rel=1e-12)
    assert np.all(r2[lm.s < pair.s_start] == pair.gear.tip_radius_)
    assert np.all(xyz[:, 0, 0] < 0.0)  # at z = 0 the flank is on the -x side of the tooth
    assert mapped_members(pair) == ("pinion", "gear")
    with pytest.raises(InputError, match="wheel"):
        flank_surface(pair, lm, "wheel")


def test_load_map_2d_from_zero_and_titles(helical_traction_pair, helical_cycle):
    """The 2D map's colour scale starts at 0; the title says what the map is and which
    modifications were applied, in um and mm."""
    from pipeline.viz.loadmap import load_map_title, plot_load_map_2d

    lm = flank_load_map(helical_cycle, helical_traction_pair, profile_points=30)
    mods = FlankModifications(15e-6, 8e-3, 0.0, 0.0, crowning=8e-6)
    title = load_map_title("pair", mods.describe())
    assert title == ("pair\nunit load, envelope over the mesh cycle; modifications: tip relief "
                     "pinion 15 um over 8 mm (linear), crowning 8 um")
    ax = plot_load_map_2d(lm, title)
    mesh = ax.collections[0]
    assert mesh.norm.vmin == 0.0 and mesh.norm.vmax == pytest.approx(lm.unit_load.max() * 1e-3)
    assert FlankModifications().describe() == "none"
    assert FlankModifications(slope_deviation=-5e-6, pitch_errors=(0.0, 4e-6)).describe() == (
        "helix slope deviation -5 um, pitch errors 0/4 um")
