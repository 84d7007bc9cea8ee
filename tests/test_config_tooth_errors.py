"""``[contact.errors]``: read in the file's units, refused where it cannot act, and run by
``gearpipe run`` into the revolution's files and summary keys."""

from __future__ import annotations

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from helpers import Cells, json_value

from pipeline.cli import main as cli
from pipeline.config import gearbox_from_dict, load_gearbox
from pipeline.report.model import format_value
from pipeline.validation import InputError
from workflows.default_case import DEMO_PAIR

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "workflows" / "configs" / "errors_runout_demo.toml"
PLANETARY = ROOT / "workflows" / "configs" / "wind_turbine_herringbone_planetary.toml"


def _box(errors: str, contact: str = ""):
    return gearbox_from_dict(tomllib.loads(DEMO_PAIR + f"[contact]\n{contact}\n"
                                           f"[contact.errors]\n{errors}\n"), name="box")


def test_example_is_read_in_si():
    box = load_gearbox(EXAMPLE)
    e = box.errors
    assert e.span == "hunting" and e.mesh_cycles(box.pair) == 50
    assert e.pinion.eccentricity == pytest.approx(10e-6)
    assert e.pinion.eccentricity_phase == pytest.approx(math.pi / 2)
    fp = e.gear.cumulative(50)
    assert fp[7] == pytest.approx(-5e-6) and fp[8] == pytest.approx(0.0, abs=1e-18)
    assert np.count_nonzero(np.abs(fp) > 1e-12) == 1  # only tooth 7 is off


@pytest.mark.parametrize("errors, contact, message", [
    ("eccentricity_phase_gear_deg = 30.0", "",
     "contact.errors.eccentricity_phase_gear_deg = 30 deg changes nothing without "
     "contact.errors.eccentricity_gear_um > 0"),
    ("single_pitch_gear_um = [1.0, -1.0]", "",
     "contact.errors.single_pitch_gear_um has 2 entries; the gear has 50 teeth (one deviation "
     "per tooth)"),
    ("eccentricity_pinion_um = 2.0", "pitch_errors_um = [0.0, 2.0]",
     "contact.pitch_errors_um offsets the tooth pairs of one mesh cycle; beside "
     "[contact.errors] give each tooth's own deviation (single_pitch_pinion_um, "
     "single_pitch_gear_um) instead"),
    ("eccentricity_pinion_um = 2.0", "positions = 2001",
     'contact.errors.span = "hunting" is 50 mesh cycles x contact.positions = 2001 = 100050 '
     "contact solves, more than 100000"),
])
def test_refusals_name_the_key(errors, contact, message):
    with pytest.raises(InputError) as exc:
        _box(errors, contact)
    assert str(exc.value).startswith(message), str(exc.value)
    assert "\n" not in str(exc.value)


def test_refused_on_a_planetary_set():
    doc = tomllib.loads(PLANETARY.read_text(encoding="utf-8"))
    doc.setdefault("contact", {})["errors"] = {"eccentricity_gear_um": 1.0}
    with pytest.raises(InputError, match=r"^\[contact.errors\] belongs to a gear pair"):
        gearbox_from_dict(doc, name="box")


def test_run_writes_the_revolution(tmp_path):
    """A 20/20 pair (hunting cycle 20 mesh cycles x 6 positions) with a pinion runout of 5 um:
    the TE over the revolution has the runout's once-per-revolution amplitude 5 um (its
    common gap along the line of action, test_contact_revolution) to 2 %: the runout's
    change of the centre distance and turn of the line of centres add the change of the
    mean of each cycle's 6 samples with them, among them the step of the sample at the
    path's start (measured +0.94 %); the CSVs carry units."""
    text = DEMO_PAIR.replace("teeth = 50", "teeth = 20") + (
        "[contact]\ncompliance = \"analytical\"\npositions = 6\n"
        "[contact.errors]\neccentricity_pinion_um = 5.0\n")
    path = tmp_path / "box.toml"
    path.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert cli(["run", str(path), "--out", str(out), "--no-cache", "--json"]) == 0
    for name in ("revolution_te.csv", "revolution_te.png", "revolution_spectrum.csv",
                 "revolution_spectrum.png", "revolution_worst_pair.png",
                 "revolution_worst_pair_load_map.png"):
        assert (out / name).is_file(), name
    head = (out / "revolution_te.csv").read_text().splitlines()[0]
    assert "transmission_error [m]" in head and "pinion_angle [rad]" in head
    rev = json.loads((out / "summary.json").read_text())["meshes"]["mesh"]["revolution"]
    assert rev["mesh_cycles"] == 20 and rev["positions"] == 120
    assert rev["first_order_amplitude_m"] == pytest.approx(5e-6, rel=0.02)
    # the report's section: its numbers the summary's, each shown as the JSON has it, its
    # four figures embedded
    section = json.loads((out / "report.json").read_text())["sections"]["revolution"]
    q = section["quantities"]
    assert q["te_peak_to_peak"]["value"] == pytest.approx(
        rev["transmission_error_peak_to_peak_m"] * 1e6, rel=1e-12)
    assert q["first_order"]["value"] == pytest.approx(rev["first_order_amplitude_m"] * 1e6,
                                                      rel=1e-12)
    assert q["worst_pair"]["value"] == (f"{rev['worst_pair']['pinion_tooth']} / "
                                        f"{rev['worst_pair']['gear_tooth']}")
    html = (out / "report.html").read_text(encoding="utf-8")
    cells = Cells()
    cells.feed(html)
    data = {"sections": {"revolution": section}}
    shown = [(k, t) for k, t in cells.cells if k is not None and k.startswith("revolution.")]
    assert len(shown) == len(q)
    for key, text in shown:
        assert text == format_value(json_value(data, key)), key
    assert [f["file"] for f in section["figures"]] == [
        "revolution_te.png", "revolution_spectrum.png", "revolution_worst_pair.png",
        "revolution_worst_pair_load_map.png"]
    assert html.count("data:image/png;base64,") >= 4


def test_contact_command_says_the_errors_act_in_run(tmp_path, capsys):
    text = DEMO_PAIR + ("[contact]\ncompliance = \"analytical\"\npositions = 4\n"
                        "[contact.errors]\neccentricity_gear_um = 1.0\n")
    path = tmp_path / "box.toml"
    path.write_text(text, encoding="utf-8")
    assert cli(["contact", str(path), "--out", str(tmp_path / "out"), "--json"]) == 0
    assert ("[contact.errors] acts in gearpipe run (the contact through the revolution); "
            "gearpipe contact solves one mesh cycle without them") in capsys.readouterr().err
