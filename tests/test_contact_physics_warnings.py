"""The loaded contact says when one tooth pair carries the whole load at a time.

The loaded contact ratio (mean number of loaded pairs over the cycle) is checked against
the geometric transverse contact ratio at a light load (an independent reference: the
pairs then carry load exactly where the unloaded flanks touch, to within the sampling of
the positions), and the warning is table-driven: the seed 001 pair unmodified (its tip
corners touch beyond the path: the tip-contact warning, 2.03 pairs loaded on average),
with tip reliefs of 1 mm over 5 mm of roll on both gears (one pair loaded
everywhere; warning with the value), and through ``gearpipe contact`` and a cached
``gearpipe run``.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import pytest
from gearsets import spur

from pipeline.cache.folder import Cache
from pipeline.cli import main as cli
from pipeline.contact.analysis import analyse_contact, analytical_compliance
from pipeline.contact.options import ContactOptions
from pipeline.contact.separations import FlankModifications
from pipeline.geometry import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.options import StiffnessOptions
from pipeline.validation import PhysicsWarning

PAIR = GearPair(spur(50, "pinion"), spur(50, "gear"))
SPUR = Path(__file__).resolve().parents[1] / "workflows" / "configs" / \
    "spur_pair_assembly_errors.toml"
RELIEF = FlankModifications(tip_relief_pinion=1e-3, relief_length_pinion=5e-3,
                            tip_relief_gear=1e-3, relief_length_gear=5e-3)


def _cycle(torque: float, modifications=None, positions: int = 60, tip_contact: bool = True):
    op = OperatingPoint(torque=torque, speed=245.0)
    opts = ContactOptions(positions=positions, tip_contact=tip_contact,
                          modifications=modifications or FlankModifications())
    src = analytical_compliance(PAIR, op, opts, StiffnessOptions(friction=0.0))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        cycle = analyse_contact(src, op, opts)
    return cycle, [str(r.message) for r in record if r.category is PhysicsWarning]


def test_light_load_loaded_contact_ratio_is_the_geometric_one():
    """On the nominal path at 1 N m the pairs carry load exactly where the unloaded flanks
    touch; with tip contact the corners touch a little beyond it too, where their rigid gap
    (0.1 um at 0.1 mm of roll) is below the 0.05 um light-load deflection: a few hundredths
    more."""
    cycle, found = _cycle(1.0, positions=120, tip_contact=False)
    eps = PAIR.transverse_contact_ratio
    assert abs(cycle.loaded_contact_ratio - eps) <= 1.0 / 120 + 1e-12
    assert found == []
    tip, _ = _cycle(1.0, positions=120)
    assert 0.0 < tip.loaded_contact_ratio - cycle.loaded_contact_ratio < 0.03


CASES = [
    ("unmodified 340 N m", 340.0, None, (2.0, 2.07),
     r"tip contact beyond the path of contact at \d+ of 60 positions: the (pinion|gear)'s "
     r"tip corner carries up to \d+ N \(\d+\.\d% of the load\) at mesh position \d+, Hertz "
     r"pressure of its edge \d+ MPa"),
    ("1 mm tip relief", 340.0, RELIEF, (1.0, 1.034),
     r"loaded contact ratio 1\.017: one tooth pair carries the whole load over 98% of the "
     r"mesh cycle.*transmission error 321 um peak to peak"),
]


@pytest.mark.parametrize(("case", "torque", "mods", "ratio", "message"), CASES,
                         ids=[c[0] for c in CASES])
def test_loaded_contact_ratio_warning(case, torque, mods, ratio, message):
    cycle, found = _cycle(torque, mods)
    assert ratio[0] <= cycle.loaded_contact_ratio <= ratio[1]
    assert cycle.summary()["loaded_contact_ratio"] == cycle.loaded_contact_ratio
    if message is None:
        assert found == [] and cycle.physics_warnings() == []
    else:
        assert len(found) == 1 and re.search(message, found[0]), found


def _relief_file(tmp_path: Path) -> Path:
    cfg = tmp_path / "relief.toml"
    cfg.write_text(SPUR.read_text() + "\n[contact]\ntip_relief_pinion_um = 1000.0\n"
                   "tip_relief_length_pinion_mm = 5.0\ntip_relief_gear_um = 1000.0\n"
                   "tip_relief_length_gear_mm = 5.0\nrender = false\n")
    return cfg


def test_cli_prints_one_warning_line(tmp_path, capsys):
    assert cli(["contact", str(_relief_file(tmp_path)), "--out", str(tmp_path / "o"),
                "--json"]) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert len(err) == 1, err
    assert err[0].startswith("gearpipe contact: warning: loaded contact ratio 1.017")


def test_a_cycle_read_from_the_cache_warns_again(tmp_path):
    from pipeline.config import load_gearbox
    from pipeline.progress import Steps
    from pipeline.run import RunOptions
    from pipeline.run.chain import mesh_stages

    box = load_gearbox(_relief_file(tmp_path))
    options = RunOptions(cache=Cache(tmp_path / "cache"), show_progress=False)
    for _ in range(2):
        with pytest.warns(PhysicsWarning, match="loaded contact ratio 1.017"):
            mesh_stages(box, options, Steps("", enabled=False))
