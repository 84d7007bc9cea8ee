"""The main job: ``gearpipe run`` on an embedded default spur pair, geometry to dynamics.

The default is the assembly-error paper base case (z 50/50, m 3 mm, 20 deg, b 20 mm, 340 N m at
2340 rpm) with EHL friction, FE-enriched loaded contact (2D FE influence coefficients
of both whole gears, ``[contact] compliance = "fe2d"``) and the 6-DOF lateral-torsional
dynamic model excited by the loaded contact (loaded k(t), static transmission error and
friction). Writes to results/default_case/: the gearbox file it ran, and in ``run/`` the
line of action and tooth profiles, the analytical mesh stiffness with the ISO 6336
comparison, the loaded contact cycle and load maps, modes, the response at 2340 rpm, a
speed sweep with the dynamic factor, the ISO 6336 rating (safety factors S_H and S_F of
both gears with every factor; the smallest in the summary), the tooth load distribution
report (``report.html``
with its ``report.json`` and ``report.csv``), one ``summary.json`` and ``run.json`` (inputs,
versions, configuration hash). FE tables and the contact cycle are cached in ``meshes/``:
a second run reads them back.

    python workflows/default_case.py [--out DIR] [--config FILE.toml]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from pipeline.cli import main as cli
from pipeline.io import atomic_write_text

DEMO_PAIR = """\
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
"""
"""The demo's gears and operating point (the assembly-error paper's pair: z 50/50, m 3 mm,
20 deg, b 20 mm, 340 N m at 2340 rpm): the one copy that the demo and the tests build on."""

DEFAULT = 'name = "default_case"\n' + DEMO_PAIR + """\
[stiffness]
friction = "ehl"
roughness_um = 0.5
viscosity_mPas = 20.0
[contact]
compliance = "fe2d"             # 2D FE of both whole gears ([fe]: its settings)
positions = 60
[dynamics]
bearing_stiffness_N_per_m = 1.0e8
bearing_damping_Ns_per_m = 100.0
damping_ratio = 0.07
excitation = "contact"          # loaded k(t), static TE, friction of the FE-enriched contact
[dynamics.sweep]
f_min_Hz = 200.0
f_max_Hz = 6000.0
points_coarse = 120
[rating]                        # ISO 6336 method B; K_Hbeta by method C, the contact's beside
application_factor = 1.25
life_h = 20000.0
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
        atomic_write_text(config, DEFAULT)
    print(f"== gearpipe run {config}")
    return cli(["run", str(config), "--out", str(args.out / "run")])


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
