"""The README's Python API example runs as written (gearbox file -> dynamic response) and
prints the numbers the command line gives for the same file.

References: the mean mesh stiffness and the loaded TE equal ``gearpipe stiffness`` and
``gearpipe contact`` on the same file (two entry points, one computation: round-off of
the printed digits); the mean stiffness lies within +-20 % of ISO 6336-1 method B
(c_gamma_alpha b from the command's ``iso6336`` block, the band of
tests/test_mesh_stiffness.py); the first elastic mode equals that of the 6-DOF
lateral-torsional pair assembled here by hand (bearings k_b in x and y, the mean mesh
stiffness along the line of action x acting on x_p - x_g + r_b1 theta_p + r_b2 theta_g;
mu = 0 in this file, so no friction terms): 778.68 Hz.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

from pipeline.cli import main as cli
from pipeline.config import load_gearbox

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"


def _example_output(capsys, monkeypatch) -> dict[str, float]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Python API", 1)[1]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    assert str(CONFIG.relative_to(ROOT)) in code
    monkeypatch.chdir(ROOT)
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    return {k: float(v) for k, v in re.findall(r"(stiffness|TE|mode|force) ([\d.e+]+)", out)}


def _command_json(capsys, command: str, out: Path) -> dict:
    assert cli([command, str(CONFIG), "--out", str(out), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_readme_python_example(capsys, monkeypatch, tmp_path):
    numbers = _example_output(capsys, monkeypatch)
    stiffness = _command_json(capsys, "stiffness", tmp_path / "s")
    contact = _command_json(capsys, "contact", tmp_path / "c")
    k = stiffness["potential_energy"]["mean_N_per_m"]
    assert numbers["stiffness"] == pytest.approx(k, rel=5e-4)  # printed to 4 digits
    assert numbers["TE"] == pytest.approx(
        contact["transmission_error_peak_to_peak_m"] * 1e6, abs=5e-4)  # 3 decimals
    iso = stiffness["iso6336"]["mesh_stiffness_N_per_m"]
    assert 0.8 <= k / iso <= 1.2
    box = load_gearbox(CONFIG)
    assert box.stiffness.friction_model.mu == 0.0
    p, g = box.bodies["pinion"], box.bodies["gear"]
    pair, kb = box.actual_pair, box.dynamics.bearing_stiffness
    v = np.array([1.0, 0.0, pair.pinion.base_radius, -1.0, 0.0, pair.gear.base_radius])
    stiff = np.diag([kb, kb, 0.0, kb, kb, 0.0]) + k * np.outer(v, v)
    mass = np.diag([p.mass_, p.mass_, p.inertia_, g.mass_, g.mass_, g.inertia_])
    f = np.sqrt(np.clip(scipy.linalg.eigh(stiff, mass, eigvals_only=True), 0.0, None)) / (
        2 * math.pi)
    assert f[0] < 1e-3 and numbers["mode"] == pytest.approx(f[1], abs=0.05)
    assert numbers["force"] > 0.0
