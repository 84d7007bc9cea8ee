"""The gear pairs of the NREL 5 MW reference gearbox (Nejad et al. 2016) as KISSsoft Release
03/2017 A rates them in the reports ``@NREL_5MW/stage_0{1,2,3}.rtf`` of the public
repository gfsReboucas/Drivetrain (commit 4a88df34): the geometry as printed there (shifts
to their printed digits, more where the repository's KISSsoft files give them), E 206 000
N/mm^2, nu 0.3, KISSsoft's steel density 7830 kg/m^3, the printed inner diameters."""

from __future__ import annotations

import math

from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair

STEEL = Material(youngs_modulus=206e9, poisson_ratio=0.3, density=7830.0)


def _gears(module: float, face_width: float, helix_deg: float = 0.0) -> dict:
    return dict(module=module, pressure_angle=math.radians(20.0),
                helix_angle=math.radians(helix_deg), face_width=face_width, material=STEEL)


def stage_3() -> GearPair:
    """Parallel helical stage: z 24/95, m_n 14 mm, beta 10 deg, b 360 mm, x 0.4800 /
    0.6691, tip diameters 380.747 / 1395.376 mm, bores 179.10 / 1193.32 mm, a 861 mm."""
    c = _gears(14e-3, 0.36, 10.0)
    return GearPair(
        GearSpec(teeth=24, profile_shift=0.48, hand="right", tip_radius=0.380747 / 2,
                 bore_radius=0.17910 / 2, name="pinion", **c),
        GearSpec(teeth=95, profile_shift=0.6691, hand="left", tip_radius=1.395376 / 2,
                 bore_radius=1.19332 / 2, name="wheel", **c))


def stage_2_sun_planet() -> GearPair:
    """Second (spur planetary) stage, sun-planet: z 18/36, m_n 21 mm, b 550 mm, x 0.3890 /
    0.50387, tip diameters 432.838 / 815.663 mm, bores 194.32 / 576.96 mm, a 584 mm."""
    c = _gears(21e-3, 0.55)
    return GearPair(
        GearSpec(teeth=18, profile_shift=0.389, tip_radius=0.432838 / 2,
                 bore_radius=0.19432 / 2, name="sun", **c),
        GearSpec(teeth=36, profile_shift=0.5038693, tip_radius=0.815663 / 2,
                 bore_radius=0.57696 / 2, name="planet", **c))


def stage_2_planet_ring() -> GearPair:
    """Second stage, planet-ring: the planet and the ring z 93 (internal), x 0.11712, tip
    diameter 1906.081 mm, outer diameter 2148.82 mm."""
    c = _gears(21e-3, 0.55)
    planet = stage_2_sun_planet().gear
    return GearPair(planet, GearSpec(teeth=93, profile_shift=0.1171157,
                                     tip_radius=1.906081 / 2, bore_radius=2.14882 / 2,
                                     internal=True, name="ring", **c))


def stage_1_sun_planet() -> GearPair:
    """First (spur planetary) stage, sun-planet: z 19/17, m_n 45 mm, b 491 mm, x 0.61713 /
    0.8021, tip diameters 978.808 / 905.470 mm, bores 482.33 / 408.99 mm, a 863 mm."""
    c = _gears(45e-3, 0.491)
    return GearPair(
        GearSpec(teeth=19, profile_shift=0.6171343, tip_radius=0.978808 / 2,
                 bore_radius=0.48233 / 2, name="sun", **c),
        GearSpec(teeth=17, profile_shift=0.8021, tip_radius=0.905470 / 2,
                 bore_radius=0.40899 / 2, name="planet", **c))
