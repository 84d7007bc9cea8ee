"""Each example gearbox file sets what its header comment says it sets.

The header is read from the file itself (its leading ``#`` lines), the numbers it names are
compared with what ``load_gearbox`` gives: a header that promises errors, friction or a
contact ratio the values do not have fails here.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from pipeline.config import load_gearbox

CONFIGS = Path(__file__).resolve().parents[1] / "workflows" / "configs"


def _header(name: str) -> str:
    """The leading comment lines of the file, joined into one line."""
    lines = []
    for line in (CONFIGS / name).read_text().splitlines():
        if not line.startswith("#"):
            break
        lines.append(line.lstrip("# ").rstrip())
    return " ".join(lines)


def _number(pattern: str, text: str) -> float:
    match = re.search(pattern, text)
    assert match, f"header lacks {pattern!r}: {text}"
    return float(match.group(1))


def test_spur_pair_assembly_errors_header():
    """The header promises the study's base case: no assembly errors, no friction, z 50/50,
    m 3 mm, 20 deg, b 20 mm, 340 N m, 2340 rpm; the file sets exactly these."""
    head = _header("spur_pair_assembly_errors.toml")
    box = load_gearbox(CONFIGS / "spur_pair_assembly_errors.toml")
    assert "no assembly errors" in head and "without friction" in head
    assert box.assembly_errors.pinion == (0.0, 0.0) and box.assembly_errors.gear == (0.0, 0.0)
    assert box.stiffness.friction == 0.0
    pair, op = box.pair, box.operation
    z = re.search(r"z (\d+)/(\d+)", head)
    assert (pair.pinion.teeth, pair.gear.teeth) == (int(z.group(1)), int(z.group(2)))
    assert pair.pinion.module * 1e3 == _number(r"m ([\d.]+) mm", head)
    assert math.degrees(pair.pinion.pressure_angle) == pytest.approx(
        _number(r"([\d.]+) deg", head), abs=1e-12)
    assert pair.face_width * 1e3 == pytest.approx(_number(r"b ([\d.]+) mm", head), abs=1e-9)
    assert op.torque == _number(r"([\d.]+) N m", head)
    assert op.speed * 30.0 / math.pi == pytest.approx(_number(r"([\d.]+) rpm", head), rel=1e-12)


def _contact_ratio(signal, k_double: float) -> float:
    """1 + the share of the mesh period at the double-contact stiffness (rectangular wave)."""
    return 1.0 + float(np.mean(np.isclose(signal.values, k_double)))


def test_lin_parker_planetary_header(tmp_path, capsys):
    """The header's 4 planets, contact ratio 1.5 and mean mesh stiffness 5e8 N/m (Lin and
    Parker 1999, Table 1: k_sp = k_rp = 5e8 N/m) are what the file sets, and the first
    elastic mode is the paper's 727 Hz."""
    head = _header("lin_parker_planetary.toml")
    model = load_gearbox(CONFIGS / "lin_parker_planetary.toml").lumped
    assert model.n_planets == _number(r"(\d+) planets", head) == 4
    ratio = _number(r"contact ratio ([\d.]+)", head)
    mean = _number(r"mean ([\d.e+]+) N/m", head)
    assert (ratio, mean) == (1.5, 5e8)
    for k in (model.k_sun_mesh, model.k_ring_mesh):
        assert _contact_ratio(k, 6.0e8) == pytest.approx(ratio, abs=1.0 / k.values.size)
        assert k.mean() == pytest.approx(mean, rel=1e-3)
    from pipeline.cli import main

    assert main(["modes", str(CONFIGS / "lin_parker_planetary.toml"), "--out",
                 str(tmp_path), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    first = _number(r"first at (\d+) Hz", head)
    assert summary["frequencies_Hz"][1] == pytest.approx(first, rel=1e-3)
