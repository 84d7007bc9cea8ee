"""The herringbone section of a sun-planet report (pipeline.report.herringbone_section).

``gearpipe report`` on the herringbone planetary set of Xu et al. (2020) with its groove
(coarse: 8 positions, 6 slices, a 60 mm groove mesh): the sun-planet report must show both
halves from the contact through the groove, each row at a stated torque (N m) and speeds
(rpm, absolute and relative to the carrier: sun 96.67 rpm, carrier 96.67 * 21 / 116, the
sun relative 96.67 * 95 / 116), name the governing half as the one with the larger maximum
line load, and carry the numbers of :func:`herringbone_distribution` as they are.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from helpers import Cells, json_value

from pipeline.cache.folder import CACHE_ENV, Cache
from pipeline.cli import main as cli
from pipeline.config import load_gearbox
from pipeline.contact.herringbone_distribution import herringbone_distribution
from pipeline.output_folder import LONGEST_FILE_NAME
from pipeline.report.model import format_value

CONFIG = Path(__file__).resolve().parents[1] / "workflows/configs/" \
    "wind_turbine_herringbone_planetary.toml"
SUN_RPM = 96.67
T_SUN = 148000.0  # N m, all 4 planets


def coarse_config(folder: Path) -> Path:
    """The set without dynamics, on a coarse contact and groove mesh, no pyvista maps."""
    text = CONFIG.read_text(encoding="utf-8")
    text = text[:text.index("\n[dynamics]")]
    for old, new in (("positions = 60", "positions = 8"), ("slices = 20", "slices = 6"),
                     ("mesh_size_mm = 30.0", "mesh_size_mm = 60.0")):
        assert old in text
        text = text.replace(old, new)
    text = text.replace("[contact]", "[contact]\nrender = false", 1)
    path = folder / "herringbone.toml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    root = tmp_path_factory.mktemp("hbreport")
    cfg = coarse_config(root)
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(CACHE_ENV, str(root / "c"))  # the root stress tables too
        assert cli(["report", str(cfg), "--out", str(root / "out"), "--cache-dir",
                    str(root / "c"), "--json"]) == 0
    return root / "out", cfg, root / "c"


def test_file_names_fit_the_output_folder_check(report):
    """The longest names of any command (mesh-prefixed reports and herringbone load maps)
    stay within what the output folder's length check allows for."""
    out, _, _ = report
    names = [p.name for p in out.iterdir()]
    assert "sun_planet_report_transmission_error.png" in names
    assert max(len(n) for n in names) <= LONGEST_FILE_NAME


def test_halves_with_their_torque_and_speeds(report):
    out, _, _ = report
    sec = json.loads((out / "sun_planet_report.json").read_text())["sections"]["herringbone"]
    assert sec["columns"] == ["left", "right", "equal split"]
    q = sec["quantities"]

    def row(key):
        return q[key]["values"], q[key]["unit"]

    torque, unit = row("torque")
    assert unit == "N m"
    # each half's torque on the sun per planet mesh; together T_s / N; the equal split half
    assert torque["left"] + torque["right"] == pytest.approx(T_SUN / 4, rel=1e-12)
    assert torque["equal split"] == pytest.approx(T_SUN / 8, rel=1e-12)
    sun_torque, _ = row("sun_torque")
    assert sun_torque["left"] + sun_torque["right"] == pytest.approx(T_SUN, rel=1e-12)
    carrier = SUN_RPM * 21 / 116
    for key, value in (("sun_speed", SUN_RPM), ("carrier_speed", carrier),
                       ("sun_speed_relative", SUN_RPM - carrier),
                       ("planet_speed_relative", -(SUN_RPM - carrier) * 21 / 37),
                       ("planet_speed", carrier - (SUN_RPM - carrier) * 21 / 37)):
        values, unit = row(key)
        assert unit == "rpm"
        for col in sec["columns"]:
            assert values[col] == pytest.approx(value, rel=1e-12), (key, col)
    share, _ = row("load_share_mean")
    assert share["left"] + share["right"] == pytest.approx(1.0, abs=1e-12)
    # torque leaving at the right half: the right half carries more and governs
    w, unit = row("max_line_load")
    assert unit == "N/mm"
    governs, _ = row("governs")
    assert governs == {"left": w["left"] > w["right"], "right": w["right"] > w["left"],
                       "equal split": None}
    assert governs["right"] and share["right"] > 0.55
    assert any("The right half governs" in n for n in sec["notes"])
    ratio, _ = row("max_line_load_over_equal_split")
    assert ratio["right"] == pytest.approx(w["right"] / w["equal split"], rel=1e-12)
    root, unit = row("root_stress_sun")
    assert unit == "MPa" and root["right"] > root["equal split"] > root["left"]
    op = json.loads((out / "sun_planet_report.json").read_text())["sections"]["operation"]
    assert "relative to the carrier" in op["quantities"]["speed"]["label"]
    assert op["quantities"]["speed_sun"]["value"] == pytest.approx(SUN_RPM, rel=1e-12)
    ring = json.loads((out / "planet_ring_report.json").read_text())["sections"]
    assert "herringbone" not in ring
    assert ring["operation"]["quantities"]["torque"]["label"].startswith(
        "torque on the planet at its ring mesh, one helical half")
    assert ring["operation"]["quantities"]["speed"]["value"] == pytest.approx(
        (SUN_RPM - carrier) * 21 / 37, rel=1e-12)


def test_csv_rows_per_half(report):
    out, _, _ = report
    rows = [r for r in csv.DictReader((out / "sun_planet_report.csv").open(encoding="utf-8"))
            if r["section"] == "herringbone"]
    by = {(r["key"], r["column"]): r for r in rows}
    for col in ("left", "right"):
        assert by[("torque", col)]["unit"] == "N m"
        for key in ("sun_speed", "sun_speed_relative", "planet_speed",
                    "planet_speed_relative", "carrier_speed"):
            assert by[(key, col)]["unit"] == "rpm"
    assert by[("governs", "right")]["value"] == "True"
    assert by[("governs", "left")]["value"] == "False"


def test_html_shows_the_json_and_the_figure(report):
    out, _, _ = report
    data = json.loads((out / "sun_planet_report.json").read_text())
    cells = Cells()
    cells.feed((out / "sun_planet_report.html").read_text(encoding="utf-8"))
    shown = [(k, t) for k, t in cells.cells if k and k.startswith("herringbone.")]
    assert len(shown) == 3 * len(data["sections"]["herringbone"]["quantities"])
    for key, text in shown:
        assert text == format_value(json_value(data, key)), key
    files = [f["file"] for f in data["sections"]["herringbone"]["figures"]]
    assert files[0] == "sun_planet_report_herringbone_line_load.png"
    assert all((out / f).is_file() for f in files)


def test_numbers_are_the_distributions(report):
    """The section renders herringbone_distribution of the run's stages unchanged."""
    from pipeline.run import RunOptions, run_pipeline

    out, cfg, cache = report
    res = run_pipeline(load_gearbox(cfg), RunOptions(cache=Cache(cache), show_progress=False))
    st = res.meshes["sun_planet"]
    hb = st.herringbone
    hd = herringbone_distribution(hb.cycle, hb.pair, hb.operation, equal_split=st.contact)
    q = json.loads((out / "sun_planet_report.json").read_text())["sections"][
        "herringbone"]["quantities"]
    for col in ("left", "right", "equal split"):
        h = hd.half(col)
        assert q["max_line_load"]["values"][col] == h.max_line_load * 1e-3
        assert q["K_Hbeta"]["values"][col] == h.distribution.k_hbeta
        assert q["max_hertz_pressure"]["values"][col] == h.distribution.hertz_max.value * 1e-6
        assert q["torque"]["values"][col] == h.operation.torque


def test_render_false_leaves_out_the_halves_pyvista_maps(report):
    """``[contact] render = false`` acts on the herringbone halves' maps too: their VTU files
    and the per-position table are written, the pyvista PNGs are not."""
    out, _, _ = report
    names = {p.name for p in out.iterdir()}
    assert {"sun_planet_herringbone.csv", "sun_planet_herringbone_load_map_left.vtu",
            "sun_planet_herringbone_load_map_right.vtu"} <= names
    assert not [n for n in names if n.endswith(".png") and "load_map" in n and "2d" not in n]


@pytest.mark.parametrize("entry, words", [("right", "sun torque taken at the right end"),
                                          ("both", "sun torque taken half at each end")])
def test_load_map_title_names_the_half_both_flanks_and_the_torque_side(entry, words):
    """A half's load map draws the sun *and* planet flanks of that helical half; its title
    says so, how the sun torque leaves ([herringbone] torque_entry), and the band's
    extremes in N/mm (from N/m)."""
    from pipeline.cli.herringbone_files import herringbone_map_title

    title = herringbone_map_title("left", 5.98e7, entry, 266.2e3, 623.4e3)
    assert title == (f"left helical half: sun and planet flanks (K_j = 5.98e+07 N m^2, "
                     f"{words})\nunit load max 623 / min 266 N/mm; one colour scale for "
                     "both halves")
