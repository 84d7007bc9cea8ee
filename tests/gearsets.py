"""Gear builders shared by the tests (imported as a plain module: tests/ is on sys.path)."""

from __future__ import annotations

import math

from pipeline.geometry import GearSpec, Material
from workflows.default_case import DEMO_PAIR

STEEL = Material(youngs_modulus=2.0e11, poisson_ratio=0.3, density=7850.0)


def spur(z: int, name: str, **kw) -> GearSpec:
    """A spur gear like the assembly-error paper's (m 3 mm, 20 deg, b 20 mm, 21 mm bore) with
    overrides."""
    base = dict(module=3e-3, pressure_angle=math.radians(20), face_width=0.02,
                bore_radius=0.021, material=STEEL)
    base.update(kw)
    return GearSpec(teeth=z, name=name, **base)


# The demo's pair, coarse: 24 contact positions, 60 stiffness positions, a short sweep.
SMALL = 'name = "small"\n' + DEMO_PAIR + """\
[stiffness]
friction = 0.05
positions = 60
[contact]
positions = 24
[dynamics]
damping_ratio = 0.07
[dynamics.response]
n_harmonics = 20
[dynamics.sweep]
f_min_Hz = 500.0
f_max_Hz = 5000.0
points_coarse = 12
"""


# Lin and Parker (1999), Table 2: natural frequencies (Hz) of the example planetary set with
# 3, 4 and 5 planets, by mode type.
LIN_PARKER_1999 = {
    3: dict(
        rot=[0.0, 1475.7, 1930.3, 2658.3, 7462.8, 11775.3],
        trans=[743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9],
        planet=[],
    ),
    4: dict(
        rot=[0.0, 1536.6, 1970.6, 2625.7, 7773.6, 13071.1],
        trans=[727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6],
        planet=[1808.2, 5963.8, 6981.7],
    ),
    5: dict(
        rot=[0.0, 1567.4, 2006.1, 2614.8, 8065.4, 14253.1],
        trans=[710.0, 1072.0, 1888.1, 2425.3, 7382.4, 11172.3],
        planet=[1808.2, 5963.8, 6981.7],
    ),
}
