"""A command given a gearbox file of a kind it does not take names the commands that do."""

import subprocess
import sys
from pathlib import Path

from pipeline.cli.common import COMMAND_KINDS, kind_mismatch

ROOT = Path(__file__).resolve().parents[1]


def test_single_gear_points_to_groove():
    assert kind_mismatch("run", "gear") == (
        "gearpipe run takes a gear pair, a planetary set or a lumped dynamic model; this file "
        "describes a single gear, which gearpipe groove takes")
    assert kind_mismatch("fe", "lumped") == (
        "gearpipe fe takes a gear pair; this file describes a lumped dynamic model, which "
        "gearpipe run, gearpipe modes, gearpipe response and gearpipe sweep take")


def test_every_taken_kind_passes():
    for command, kinds in COMMAND_KINDS.items():
        for kind in kinds:
            assert kind_mismatch(command, kind) is None


def test_cli_run_on_single_gear(tmp_path):
    p = subprocess.run([sys.executable, "-m", "pipeline.cli", "run",
                        str(ROOT / "workflows/configs/wind_turbine_sun_groove.toml"),
                        "--out", str(tmp_path / "o")], capture_output=True, text=True,
                       cwd=tmp_path)
    assert p.returncode == 2
    assert "which gearpipe groove takes" in p.stderr
