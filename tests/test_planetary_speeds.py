"""Speeds of a planetary set with the ring fixed (pipeline.geometry.planetary_speeds).

Exact kinematics: Willis' relation seen from the carrier for both meshes, the rolling
condition of each mesh, and the operating points the contact is solved at.
"""

from __future__ import annotations

import math

import pytest

from pipeline.config import load_gearbox
from pipeline.dynamics.models.planetary_gears import carrier_speed, mesh_operations
from pipeline.geometry.planetary_speeds import planetary_speeds

CONFIG = "workflows/configs/wind_turbine_herringbone_planetary.toml"
RPM = 2.0 * math.pi / 60.0


def test_wind_turbine_set_speeds():
    """Xu et al. (2020): sun 21, planet 37, ring 95; sun at 96.67 rpm -> carrier
    96.67 * 21 / 116 = 17.50 rpm (the paper's 17.5 rpm rotor speed); the planet turns at
    -(96.67 - 17.50) 21 / 37 = -44.93 rpm relative to the carrier, -27.43 rpm absolute."""
    box = load_gearbox(CONFIG)
    ps = box.planetary
    v = planetary_speeds(ps, box.operation.speed)
    assert v.sun / RPM == pytest.approx(96.67, rel=1e-12)
    assert v.carrier / RPM == pytest.approx(96.67 * 21 / 116, rel=1e-12)
    assert v.carrier / RPM == pytest.approx(17.50, abs=0.005)
    assert v.planet_relative / RPM == pytest.approx(-(96.67 - 96.67 * 21 / 116) * 21 / 37,
                                                    rel=1e-12)
    assert v.planet / RPM == pytest.approx(-27.43, abs=0.005)
    # Willis, both meshes seen from the carrier: the sun-planet pair rolls (external, opposite
    # senses), the planet-ring pair rolls (internal, same sense), the ring stands still
    assert v.sun_relative * 21 == pytest.approx(-v.planet_relative * 37, rel=1e-12)
    assert v.planet_relative * 37 == pytest.approx(v.ring_relative * 95, rel=1e-12)
    assert v.ring_relative + v.carrier == pytest.approx(0.0, abs=1e-15)
    assert (v.sun_relative / v.ring_relative) == pytest.approx(-95 / 21, rel=1e-12)
    # the same carrier speed and the relative speeds the meshes are solved at
    assert v.carrier == pytest.approx(carrier_speed(ps, box.operation), rel=1e-15)
    sp, pr = mesh_operations(ps, box.operation, 2)
    assert sp.speed == pytest.approx(v.sun_relative, rel=1e-15)
    assert pr.speed == pytest.approx(abs(v.planet_relative), rel=1e-15)
