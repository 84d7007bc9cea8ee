"""Gear builders shared by the tests (imported as a plain module: tests/ is on sys.path)."""

from __future__ import annotations

import math

from pipeline.geometry import GearSpec, Material

STEEL = Material(youngs_modulus=2.0e11, poisson_ratio=0.3, density=7850.0)


def spur(z: int, name: str, **kw) -> GearSpec:
    """A spur gear like the assembly-error paper's (m 3 mm, 20 deg, b 20 mm, 21 mm bore) with
    overrides."""
    base = dict(module=3e-3, pressure_angle=math.radians(20), face_width=0.02,
                bore_radius=0.021, material=STEEL)
    base.update(kw)
    return GearSpec(teeth=z, name=name, **base)
