"""The main job: geometry -> analytical mesh stiffness for an embedded default spur pair.

The default is the assembly-error paper base case (z 50/50, m 3 mm, 20 deg, b 20 mm, 340 N m at
2340 rpm) with EHL friction. Writes to results/default_case/: line of action and
tooth profiles (PNG), the mesh stiffness over a mesh cycle with the ISO 6336
contact-line comparison (CSV, JSON, PNG), friction stiffness/torque coefficients,
and run.json with inputs, versions and the configuration hash.

    python workflows/default_case.py [--out DIR] [--config FILE.toml]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from pipeline.cli import main as cli

DEFAULT = """\
name = "default_case"
[pinion]
teeth = 50
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 20.0
bore_radius_mm = 21.0
[gear]
teeth = 50
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 20.0
bore_radius_mm = 21.0
[operation]
torque_Nm = 340.0
speed_rpm = 2340.0
[stiffness]
friction = "ehl"
roughness_um = 0.5
viscosity_mPas = 20.0
"""


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=Path("results/default_case"))
    ap.add_argument("--config", type=Path, default=None, help="use this TOML instead")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    config = args.config
    if config is None:
        config = args.out / "default_case.toml"
        config.write_text(DEFAULT, encoding="utf-8")
    rc = 0
    for command in ("geometry", "stiffness"):
        print(f"== gearpipe {command} {config}")
        rc |= cli([command, str(config), "--out", str(args.out / command)])
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
