"""The example ``workflows/configs/modifications_demo.toml`` end to end, with physical checks.

* ``gearpipe run`` writes the flanks' modification map and embeds it in the report's
  modifications section, which lists each gear's modifications in the file's units;
* the K_Hbeta of its lead modifications follows ISO 6336-1's linear-load model (w(z) = c
  (delta - g(z)) over a face in full contact, so K_Hbeta = 1 + c (mean g - min g) / w_m),
  with the mesh stiffness per unit face width over the mean line load ``c / w_m`` calibrated
  on the same pair under a helix slope alone (K = 1 + c f / 2 / w_m), to 3 % (Weber's local
  contact is not linear); the run's K_Hbeta, with the tip reliefs, lies below it;
  crowning lowers the K_Hbeta of a slope by the closed-form ratio of (mean g - min g);
* Harris (1958): at light load the transmission error follows the file's tip reliefs, p-p
  C (1 - D / (2 L)) = 9.95 um (C 30 um, L 5 mm, D = g_alpha - p_b = 6.684 mm).
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
from helpers import load_workflow

from pipeline.cli import main as cli
from pipeline.config import load_gearbox
from pipeline.contact.analysis import analyse_contact
from pipeline.contact.compliance import compliance_source
from pipeline.contact.distribution import load_distribution
from pipeline.contact.modifications import GearModification, LeadModification
from pipeline.contact.separations import FlankModifications
from pipeline.operation import OperatingPoint

EXAMPLE = Path(__file__).resolve().parents[1] / "workflows" / "configs" / "modifications_demo.toml"
UM = 1e-6


@pytest.fixture(scope="module")
def box():
    return load_gearbox(EXAMPLE)


def _cycle(box, mods, torque, **kw):
    op = OperatingPoint(torque=torque, speed=box.operation.speed)
    opts = dataclasses.replace(box.contact, modifications=mods, **kw)
    cyc = analyse_contact(compliance_source(box.pair, op, opts, box.stiffness, None), op, opts)
    return cyc, op


def _k_hbeta(box, mods):
    cyc, op = _cycle(box, mods, box.operation.torque)
    return load_distribution(cyc, box.pair, op).k_hbeta


def test_gearpipe_run_draws_and_reports_the_modifications(tmp_path, box):
    out = tmp_path / "run"
    assert cli(["run", str(EXAMPLE), "--out", str(out), "--cache-dir", str(tmp_path / "c")]) == 0
    assert (out / "report_modifications.png").stat().st_size > 20_000
    report = json.loads((out / "report.json").read_text())
    section = report["sections"]["modifications"]
    assert [f["file"] for f in section["figures"]] == ["report_modifications.png"]
    rows = section["quantities"]
    assert rows["pinion_tip_relief"]["value"] == pytest.approx(30.0, rel=1e-12)
    assert rows["pinion_lead_crowning"]["value"] == pytest.approx(6.0, rel=1e-12)
    assert rows["gear_end_relief_face2"]["value"] == pytest.approx(5.0, rel=1e-12)
    assert rows["gear_twist"]["value"] == pytest.approx(3.0, rel=1e-12)
    assert rows["gear_tip_relief_start"]["value"] == "roll length 5 mm from the active tip"
    html = (out / "report.html").read_text()
    start = html.index('<section id="modifications"')
    assert "report_modifications.png" in html[start:html.index("</section>", start)]

    # K_Hbeta against ISO 6336-1's linear-load model, on the file's lead modifications alone
    # (a face in full contact at every position): c / w_m of this pair from a helix slope f,
    # K_s - 1 = (c / w_m) (mean g - min g) with g = f (z/b - 1/2) on the slices
    b, n = box.pair.face_width, box.contact.slices
    z = (np.arange(n) + 0.5) * b / n
    f = 15 * UM
    k_slope = _k_hbeta(box, FlankModifications(pinion_flank=GearModification(
        lead=LeadModification(slope=f))))
    g_slope = f * (z / b - 0.5)
    c_per_wm = (k_slope - 1.0) / (g_slope.mean() - g_slope.min())
    # the file's lead gap: pinion crowning 6 um, gear parabolic end reliefs 5 um over 3 mm
    g = (6 * UM * (2 * z / b - 1) ** 2 + 5 * UM * (np.clip(3e-3 - z, 0, None) / 3e-3) ** 2
         + 5 * UM * (np.clip(z - (b - 3e-3), 0, None) / 3e-3) ** 2)
    flanks = box.contact.modifications.flanks
    k_lead = _k_hbeta(box, FlankModifications(pinion_flank=GearModification(lead=flanks[0].lead),
                                              gear_flank=GearModification(lead=flanks[1].lead)))
    assert k_lead - 1.0 == pytest.approx(c_per_wm * (g.mean() - g.min()), rel=0.03)
    # with the deep tip reliefs the pairs near the ends of the path carry less and lift off
    # the crowned face ends first: the run's K_Hbeta lies below the lead-only one (the linear
    # model no longer holds exactly there)
    k_run = report["sections"]["load_distribution"]["quantities"]["K_Hbeta"]["value"]
    assert 1.1 < k_run < k_lead < k_slope


def test_crowning_lowers_k_hbeta_under_a_slope_as_the_closed_form_says(box):
    """f = 15 um with and without lead crowning C = 6 um on the pinion: (K_c - 1) / (K_s - 1)
    = (mean g_c - min g_c) / (mean g_s - min g_s) over the 20 slice centres, 0.6084 (the
    continuous face's (C/3 + f^2/(16 C)) / (f/2) = 0.579), here within 3 % (Weber's local
    contact is not linear; measured 1.3 %)."""
    f, c = 15 * UM, 6 * UM
    k_s = _k_hbeta(box, FlankModifications(pinion_flank=GearModification(
        lead=LeadModification(slope=f))))
    k_c = _k_hbeta(box, FlankModifications(pinion_flank=GearModification(
        lead=LeadModification(slope=f, crowning=c))))
    n = box.contact.slices
    x = 2 * (np.arange(n) + 0.5) / n - 1  # slice centres, 2 z / b - 1
    g_s, g_c = f * x / 2, c * x**2 + f * x / 2
    ratio = (g_c.mean() - g_c.min()) / (g_s.mean() - g_s.min())
    assert ratio == pytest.approx(0.6084, abs=1e-4)
    assert (c / 3 + f * f / (16 * c)) / (f / 2) == pytest.approx(0.5792, abs=1e-4)
    assert k_s < 2.0  # the whole face carries load: the linear model holds
    assert (k_c - 1) / (k_s - 1) == pytest.approx(ratio, rel=0.03)


def test_light_load_te_follows_the_tip_reliefs_harris(box):
    """The file's tip reliefs alone (lead modifications left out) at 0.34 N m (1/1000 of the
    file's torque): TE p-p rises from the unmodified pair's by C (1 - D / (2 L)) = 9.949 um,
    within the sampling of the peak (a tent of slope C / L over p_b / positions) and the
    elastic TE at that load."""
    pair = box.pair
    flanks = box.contact.modifications.flanks
    reliefs = FlankModifications(pinion_flank=GearModification(profile=flanks[0].profile),
                                 gear_flank=GearModification(profile=flanks[1].profile))
    c, length = flanks[0].profile.tip_relief, flanks[0].profile.tip_relief_length
    assert (c, length) == (flanks[1].profile.tip_relief, flanks[1].profile.tip_relief_length)
    d = pair.path_length - pair.base_pitch
    harris = c * (1.0 - d / (2.0 * length))
    assert harris == pytest.approx(9.949 * UM, abs=1e-3 * UM)
    positions = 120
    plain = np.ptp(_cycle(box, FlankModifications(), 0.34, positions=positions)[0]
                   .transmission_error)
    relieved = np.ptp(_cycle(box, reliefs, 0.34, positions=positions)[0].transmission_error)
    assert plain < 0.02 * UM  # light load: the elastic part is small
    step = (c / length) * pair.base_pitch / positions
    assert relieved == pytest.approx(harris, abs=step + plain)


def test_catalogue_workflow_draws_each_modification_alone(tmp_path):
    """workflows/modification_catalogue.py: every kind 10 um alone on the demo pinion; the
    twist S = 10 um removes S/4 = 2.5 um at the root of face 1 and the tip of face 2 and adds
    2.5 um at the other corners (ISO 21771 profile twist, f_Halpha = S (z/b - 1/2))."""
    summary = load_workflow("modification_catalogue").main(["--out", str(tmp_path / "w")])
    assert (tmp_path / "w" / "modification_catalogue.png").stat().st_size > 50_000
    assert summary["twist S"]["corners_um"] == pytest.approx([2.5, -2.5, -2.5, 2.5], rel=1e-12)
    for name in ("tip relief (arc, 5 mm)", "lead crowning C_beta", "end reliefs (linear, 4 mm)"):
        assert summary[name]["max_um"] == pytest.approx(10.0, rel=1e-9)
        assert summary[name]["min_um"] == pytest.approx(0.0, abs=1e-12)
