"""The main job: ``gearpipe run`` on an embedded default spur pair, geometry to dynamics.

The default is the assembly-error paper base case (z 50/50, m 3 mm, 20 deg, b 20 mm, 340 N m at
2340 rpm) with EHL friction, FE-enriched loaded contact (2D FE influence coefficients
of both whole gears, ``[contact] compliance = "fe2d"``) and the 6-DOF lateral-torsional
dynamic model excited by the loaded contact (loaded k(t), static transmission error and
friction); the pinion is cut on a straddle-mounted shaft (Timoshenko beam on elastic
bearings): the contact is solved with its deflection, the rating takes that K_Hbeta, the
dynamics its support and the torsion to a motor. Writes to results/default_case/: the
gearbox file it ran, and in ``run/`` the
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

PAPER_CASE = 'name = "default_case"\n' + DEMO_PAIR + """\
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
[rating]                        # ISO 6336 method B
application_factor = 1.25
life_h = 20000.0
"""
"""The assembly-error paper's base case as the demo ran it before the shafts: both gears on
bearings of 1e8 N/m (the paper's), FE 2D contact, the dynamics excited by the contact, the
rating with method C's K_Hbeta (the dynamics' regression tests pin this case)."""

PINION_SHAFT = """\
[pinion.shaft]                  # the pinion cut on a straddle-mounted shaft (pipeline/shaft)
model = "beam"
gear_position_mm = 80.0
torque_position_mm = 0.0        # the coupling at the shaft's first end
hub = "integral"
[[pinion.shaft.segments]]
start_mm = 0.0
end_mm = 70.0
outer_diameter_mm = 35.0
[[pinion.shaft.segments]]
start_mm = 70.0
end_mm = 90.0
outer_diameter_mm = 142.5       # the pinion's body (its root diameter)
[[pinion.shaft.segments]]
start_mm = 90.0
end_mm = 160.0
outer_diameter_mm = 35.0
[[pinion.shaft.bearings]]
position_mm = 40.0
radial_stiffness_N_per_m = 5.0e8
axial = true
[[pinion.shaft.bearings]]
position_mm = 140.0
radial_stiffness_N_per_m = 5.0e8
"""

DEFAULT = PAPER_CASE.replace("[gear]\n", PINION_SHAFT + "[gear]\n", 1).replace(
    "[dynamics]\n", "[dynamics]\ndrive_inertia_kgm2 = 0.05       # the motor behind the pinion's "
    "shaft\n", 1)
"""The demo's gearbox file: the paper's base case with the pinion cut on a straddle-mounted
shaft (the loaded contact solved with its deflection, the rating with the system's
K_Hbeta, the dynamics with the shaft's support and a motor behind its torsion); the gear
stays on the paper's 1e8 N/m bearings."""


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
