"""Speeds of a planetary set with the ring fixed: absolute and relative to the carrier.

With the ring fixed and the sun driving at omega_s, Willis' relation of the set seen from
the carrier, ``(omega_s - omega_c) / (omega_r - omega_c) = -z_r / z_s`` with
``omega_r = 0``, gives the carrier speed ``omega_c = omega_s z_s / (z_s + z_r)``. Relative
to the carrier the sun turns at ``omega_s - omega_c``, the ring at ``-omega_c`` and the
planet at ``-(omega_s - omega_c) z_s / z_p`` (external sun-planet mesh: opposite sense),
which equals ``-omega_c z_r / z_p`` from the internal planet-ring mesh (same sense);
the planet's absolute speed is ``omega_c`` plus its relative speed. Every speed is in
rad/s, + in the sense of the sun's rotation.

The loaded contact of a planetary mesh is solved in the carrier frame, so its speeds are
the relative ones; a report states both (:mod:`pipeline.report.content`).
"""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.geometry.planetary import PlanetarySet


@dataclass(frozen=True)
class PlanetarySpeeds:
    """Speeds of the members of a planetary set, ring fixed (rad/s, + in the sun's sense).

    Attributes
    ----------
    sun, carrier, planet : absolute speeds (the planet about its own axis).
    sun_relative, planet_relative, ring_relative : speeds relative to the carrier.
    """

    sun: float
    carrier: float
    planet: float
    sun_relative: float
    planet_relative: float
    ring_relative: float


def planetary_speeds(planetary: PlanetarySet, sun_speed: float) -> PlanetarySpeeds:
    """Speeds of ``planetary`` with the ring fixed and the sun at ``sun_speed`` (rad/s)
    (module docstring)."""
    zs, zp, zr = planetary.sun.teeth, planetary.planet.teeth, planetary.ring.teeth
    carrier = sun_speed * zs / (zs + zr)
    sun_rel = sun_speed - carrier
    planet_rel = -sun_rel * zs / zp
    return PlanetarySpeeds(sun=sun_speed, carrier=carrier, planet=carrier + planet_rel,
                           sun_relative=sun_rel, planet_relative=planet_rel,
                           ring_relative=-carrier)
