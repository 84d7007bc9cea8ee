"""The tooth load distribution report (pipeline.report, ``gearpipe report``).

The report of a small case is built through the command line and read back as a user's
tools would: every figure embedded as a data URI (nothing fetched from elsewhere), every
number in the HTML equal to the JSON's value as printed, the CSV the same numbers, the
numbers themselves the stages' (K_Hbeta, Hertz pressure, TE, ISO 6336-1 stiffness,
provenance hash); the failure paths are one line and write nothing.
"""

from __future__ import annotations

import base64
import csv
import json
import re
from pathlib import Path

import numpy as np
import pytest
from gearsets import SMALL
from helpers import Cells, json_value, small_report

from pipeline.cache.folder import Cache
from pipeline.cli import main as cli
from pipeline.config import gearbox_from_text
from pipeline.contact.distribution import load_distribution
from pipeline.contact.results import pairs_in_order_of_entry
from pipeline.io import content_hash
from pipeline.report.model import format_value

CONFIGS = Path(__file__).resolve().parents[1] / "workflows" / "configs"


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    return small_report(tmp_path_factory.mktemp("report")), gearbox_from_text(SMALL, "small")


def test_every_figure_is_embedded(report):
    out, _ = report
    html = (out / "report.html").read_text(encoding="utf-8")
    data = json.loads((out / "report.json").read_text())
    p = Cells()
    p.feed(html)
    figures = [f["file"] for s in data["sections"].values() for f in s["figures"]]
    assert len(p.images) == len(figures) >= 8
    # the stage figures too: queued for drawing, not yet written, when the report was
    # assembled (gearpipe run draws them with the report's own, side by side)
    assert {"tooth_profiles.png", "load_map.png", "load_map_2d.png", "sweep.png",
            "dte_spectrum.png", "harmonics.png"} <= set(figures)
    for src, name in zip(p.images, figures, strict=True):
        assert src.startswith("data:image/png;base64,")
        png = base64.b64decode(src.split(",", 1)[1])
        assert png == (out / name).read_bytes()  # the figure the stage wrote, unchanged
    # opens offline: no script, no style sheet or image from elsewhere
    assert all(link.startswith("#") for link in p.links)
    assert not re.search(r"(src|href)=\"(http|//|file:)", html)
    assert "@media print" in html


def test_every_number_shown_equals_the_json(report):
    out, _ = report
    data = json.loads((out / "report.json").read_text())
    p = Cells()
    p.feed((out / "report.html").read_text(encoding="utf-8"))
    shown = [(k, t) for k, t in p.cells if k is not None]
    n_json = sum(len(s["columns"]) * len(s["quantities"]) for s in data["sections"].values())
    assert len(shown) == n_json > 100
    for key, text in shown:
        assert text == format_value(json_value(data, key)), key
    # every other cell is a label or a unit, never a number
    for key, text in p.cells:
        if key is None:
            assert not re.fullmatch(r"[-+]?\d[\d.eE+-]*", text.strip()), text


def test_csv_holds_the_same_numbers(report):
    out, _ = report
    data = json.loads((out / "report.json").read_text())
    with open(out / "report.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == sum(len(s["columns"]) * len(s["quantities"])
                            for s in data["sections"].values())
    for r in rows:
        cols = data["sections"][r["section"]]["columns"]
        key = f"{r['section']}.{r['key']}" + (f".{r['column']}" if len(cols) > 1 else "")
        v = json_value(data, key)
        if isinstance(v, float):
            assert float(r["value"]) == v
        else:
            assert r["value"] == ("" if v is None else str(v))
    cycle = np.genfromtxt(out / "report_cycle.csv", delimiter=",", names=True)
    assert cycle.size == 24


def test_numbers_are_the_stages(report):
    out, box = report
    s = json.loads((out / "report.json").read_text())["sections"]

    def val(section, key, col=None):
        row = s[section]["quantities"][key]
        return row["values"][col] if col else row["value"]

    # spur pair, one slice: even face load, stated as such
    assert val("load_distribution", "K_Hbeta") == 1.0
    assert any("one slice" in n for n in s["load_distribution"]["notes"])
    assert val("operation", "load_line_of_action") == pytest.approx(
        340.0 / box.pair.pinion.base_radius)
    assert val("stiffness", "iso_mesh") == pytest.approx(
        json.loads((out / "summary.json").read_text())["meshes"]["mesh"][
            "iso6336_mesh_stiffness_N_per_m"] * 1e-6)
    assert val("geometry", "teeth", "pinion") == 50
    assert val("pair", "transverse_contact_ratio") == pytest.approx(
        box.pair.transverse_contact_ratio)
    # single contact of the nominal path would carry P near the pitch point (820 MPa); the
    # tip corners touching beyond the path share it, so the flanks see 710 MPa, and the
    # corners' own edge pressure is given apart (GPa)
    assert 690.0 < val("contact_pressure", "max_hertz_pressure") < 740.0
    assert val("contact_pressure", "max_tip_corner_pressure") > 2000.0
    te = json.loads((out / "summary.json").read_text())["meshes"]["mesh"]["loaded_contact"][
        "transmission_error_peak_to_peak_m"]
    assert val("transmission_error", "peak_to_peak") == pytest.approx(te * 1e6, rel=1e-12)
    assert val("transmission_error", "peak_to_peak_angle") == pytest.approx(
        te / box.pair.pinion.base_radius * 1e6, rel=1e-12)
    assert val("transmission_error", "order_1") > val("transmission_error", "order_10") > 0
    # root stress: FE under the solved loads below ISO 6336-3 (3 % on the nominal path,
    # tests/test_root_stress.py), here by 31 %: the tip corners share the load where ISO
    # puts all of it on one tooth, and a note says so with their share
    assert any("tip corners, which carry up to" in n for n in s["root_stress"]["notes"])
    for g in ("pinion", "gear"):
        d = val("root_stress", "difference", g)
        assert -35.0 < d < -25.0
        assert val("geometry", "root_diameter", g) <= val("root_stress", "fe_max_diameter", g) \
            <= val("geometry", "form_diameter", g)
    prov = s["provenance"]["quantities"]
    assert prov["configuration_hash"]["value"] == content_hash(box.to_dict())
    assert prov["code_revision"]["value"]
    assert "dynamics" in s and val("dynamics_meshes", "dynamic_factor") > 1.0


def test_report_numbers_match_the_distribution(report):
    """The report is a rendering of load_distribution (the function a study calls)."""
    from pipeline.run import RunOptions, run_pipeline

    out, box = report
    res = run_pipeline(box, RunOptions(cache=Cache(out.parent / "c"), show_progress=False))
    st = res.meshes["mesh"]
    dist = load_distribution(st.contact, st.stiffness.actual, st.case.operation)
    s = json.loads((out / "report.json").read_text())["sections"]
    q = s["contact_pressure"]["quantities"]
    assert q["max_hertz_pressure"]["value"] == dist.hertz_max.value * 1e-6
    assert s["transmission_error"]["quantities"]["peak_to_peak"]["value"] == \
        dist.te_peak_to_peak * 1e6
    # tooth pairs as the reader counts them (1, 2, ... in the order they take load), the
    # internal indices k (-1, 0, 1 ...) never shown: the spur pair's k = 0 enters at the
    # start of the cycle and is pair 1, k = 1 (leaving) pair 2, k = -1 (touching at the
    # gear's tip corner before it enters, at the end of the cycle) pair 3
    order = [int(dist.pair_index[j]) for j in pairs_in_order_of_entry(dist.load_share)]
    assert order == [0, 1, -1]
    assert [dist.pair_number(k) for k in (0, 1, -1)] == [1, 2, 3]
    assert q["tooth_pair"]["value"] == dist.pair_number(dist.hertz_max.tooth_pair)
    with open(out / "report_cycle.csv", newline="") as fh:
        header = next(csv.reader(fh))
    assert [h for h in header if "load_share" in h] == [
        "load_share_tooth_pair_1 [-]", "load_share_tooth_pair_2 [-]",
        "load_share_tooth_pair_3 [-]"]


def test_run_writes_the_report_last(tmp_path):
    cfg = tmp_path / "small.toml"
    cfg.write_text(SMALL.replace("[dynamics]", "[nodynamics]").split("[nodynamics]")[0],
                   encoding="utf-8")
    out = tmp_path / "out"
    assert cli(["run", str(cfg), "--out", str(out), "--cache-dir", str(tmp_path / "c"),
                "--json"]) == 0
    for name in ("report.html", "report.json", "report.csv", "report_face.csv"):
        assert (out / name).is_file(), name
    data = json.loads((out / "report.json").read_text())
    assert "dynamics" not in data["sections"]
    assert "report.html" in json.loads((out / "run.json").read_text())["outputs"]


def test_report_refuses_a_file_without_meshes(tmp_path, capsys):
    out = tmp_path / "out"
    rc = cli(["report", str(CONFIGS / "lin_parker_planetary.toml"), "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1
    assert err[0].startswith("gearpipe report: error:")
    assert "gearpipe report takes a gear pair or a planetary set" in err[0]
    assert "lumped dynamic model, which gearpipe run" in err[0]
    assert not out.exists() or not any(out.iterdir())


def test_misaligned_spur_pair_face_load_factor(tmp_path):
    """A spur pair with a helix slope deviation f_Hb: ``gearpipe report`` solves it with
    ``[contact] slices`` across the face (one slice would give K_Hbeta = 1 whatever the
    misalignment). Linear local contact on the nominal path (as the slice method), the
    whole face loaded: the line load at each
    position is linear over the face with slope k(s0) f_Hb / b, k the mesh stiffness, so
    K_Hbeta(s0) = 1 + k(s0) f_Hb (1/2 - 1/(2 N)) / P on N slices, with k taken from the
    stiffness stage (Yang et al. 2026's slice method, a code path apart from the contact
    solve), and the cycle's K_Hbeta is ISO 6336-1's 1 + f_Hb c_gamma / (2 F_m / b) within
    1/N."""
    from pipeline.contact.analysis import analytical_compliance
    from pipeline.stiffness.mesh import stiffness_at

    f_hb, n = 10e-6, 30
    text = SMALL.replace("[contact]\n", f"[contact]\nslope_deviation_um = {f_hb * 1e6}\n"
                         f"local_contact = \"linear\"\nslices = {n}\ntip_contact = false\n")
    text = text.split("[dynamics]")[0]
    cfg = tmp_path / "misaligned.toml"
    cfg.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert cli(["report", str(cfg), "--out", str(out), "--cache-dir", str(tmp_path / "c"),
                "--json"]) == 0
    s = json.loads((out / "report.json").read_text())["sections"]
    q = s["load_distribution"]["quantities"]
    assert s["operation"]["quantities"]["slices"]["value"] == n
    assert not any("one slice" in note for note in s["load_distribution"]["notes"])
    cycle = np.genfromtxt(out / "report_cycle.csv", delimiter=",", names=True)

    box = gearbox_from_text(text, "misaligned")
    pair = box.actual_pair
    src = analytical_compliance(pair, box.operation, box.contact, box.stiffness)
    s0 = pair.mesh_cycle(box.contact.positions)
    # the positions the report's cycle table lists (the CSV holds 10 significant digits)
    np.testing.assert_allclose(cycle["pinion_angle_rad"], (s0 - s0[0]) / pair.pinion.base_radius,
                               rtol=1e-8, atol=0)
    k = stiffness_at(src.model, s0, n, src.friction, src.operating,
                     src.foundation_correction).total
    load = 340.0 / pair.pinion.base_radius
    edge = 0.5 - 0.5 / n
    assert np.all(k * f_hb * edge < load)  # linear regime: no slice lifts off
    np.testing.assert_allclose(cycle["K_Hbeta_at_position_"], 1.0 + k * f_hb * edge / load,
                               rtol=1e-6)
    k_hbeta = q["K_Hbeta"]["value"]
    assert k_hbeta == pytest.approx(1.0 + k.mean() * f_hb * edge / load, rel=1e-6)
    assert k_hbeta > 1.2  # a real effect (1.395 measured; ISO 1.408)
    iso = 1.0 + f_hb * k.mean() / (2.0 * load)  # c_gamma b = mean k, F_m = P
    assert k_hbeta == pytest.approx(iso, rel=1.0 / n)


def test_one_slice_with_lead_crowning_is_stated_as_such():
    """slices = 1 with lead crowning: the note says the crowning cannot shape the line load
    (not that the pair has none); without modifications, the plain one-slice note."""
    from pipeline.contact import analyse_contact, analytical_compliance
    from pipeline.contact.options import ContactOptions
    from pipeline.contact.separations import FlankModifications
    from pipeline.report.content import load_distribution_section
    from pipeline.validation import PhysicsWarning

    box = gearbox_from_text(SMALL, "small")
    pair = box.actual_pair
    mods = FlankModifications(crowning=8e-6)
    with pytest.warns(PhysicsWarning, match="contact.slices = 1"):
        opts = ContactOptions(positions=6, slices=1, modifications=mods)
    cyc = analyse_contact(analytical_compliance(pair, box.operation, opts), box.operation, opts)
    dist = load_distribution(cyc, pair, box.operation)
    crowned = load_distribution_section(dist, pair, [], mods).notes
    plain = load_distribution_section(dist, pair, [], FlankModifications()).notes
    assert any("cannot shape the line load" in n and "raise [contact] slices" in n
               for n in crowned)
    assert not any("without lead crowning" in n for n in crowned)
    assert any("without lead crowning" in n for n in plain)


@pytest.mark.parametrize(("relief_um", "shape"), [
    (0.0, "none (no tip relief)"),   # the default shape of an absent relief is not reported
    (12.0, "parabolic"),
])
def test_relief_shape_row_says_none_without_relief(relief_um, shape):
    from types import SimpleNamespace

    from pipeline.contact.options import ContactOptions
    from pipeline.contact.separations import FlankModifications
    from pipeline.report.content import modifications_section

    mods = FlankModifications(tip_relief_gear=relief_um * 1e-6,
                              relief_length_gear=4e-3 if relief_um else 0.0,
                              relief_shape="parabolic")
    assembly = SimpleNamespace(pinion=(0.0, 0.0), gear=(0.0, 0.0))
    section = modifications_section(ContactOptions(modifications=mods), assembly, None)
    row = next(q for q in section.quantities if q.key == "relief_shape")
    assert row.values == (shape,)
