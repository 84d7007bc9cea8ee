"""Assembly-error geometry, planetary phases (Xu et al. 2020) and the TOML configuration."""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur

from pipeline.config import gearbox_from_dict, load_gearbox
from pipeline.geometry import GearSpec
from pipeline.geometry.assembly_errors import AssembledPair, AssemblyErrors
from pipeline.geometry.planetary import PlanetarySet
from pipeline.validation import InputError

D = math.radians
UM = 1e-6


@pytest.mark.parametrize("cond,e", [(2, 10.0), (3, 100.0)])
def test_assembly_error_geometry(spur_pair_z50, cond, e):
    """Actual centre distance, tangency of the actual line of action, and pressure angles.

    The frame of the assembly-error paper: O_g = (a sin phi, a cos phi) + (e_xg, e_yg); a' = |O'_g
    - O'_p|. T1', T2' lie on the base circles with the line of action tangent there, and the
    pressure angle at a contact point X is acos(r_b / |X - O'|) (the assembly-error paper).
    """
    ap = AssembledPair(spur_pair_z50, AssemblyErrors((0.0, 0.0), (e * UM, e * UM)))
    a, phi = 0.15, D(20)
    expect = math.hypot(a * math.sin(phi) + e * UM, a * math.cos(phi) + e * UM)
    assert ap.centre_distance == pytest.approx(expect, rel=1e-14)
    op, og = ap.centres
    t1, t2 = ap.line_of_action()
    u = (t2 - t1) / np.linalg.norm(t2 - t1)
    rb = spur_pair_z50.pinion.base_radius
    assert np.linalg.norm(t1 - op) == pytest.approx(rb, rel=1e-12)
    assert np.linalg.norm(t2 - og) == pytest.approx(rb, rel=1e-12)
    assert abs(np.dot(t1 - op, u)) < 1e-15 and abs(np.dot(t2 - og, u)) < 1e-15
    s = np.linspace(ap.actual.s_start, ap.actual.s_end, 5)
    a1, a2 = ap.pressure_angles(s)
    e1, e2 = ap.actual.pressure_angles(s)
    np.testing.assert_allclose(a1, e1, atol=1e-12)
    np.testing.assert_allclose(a2, e2, atol=1e-12)
    # start/end of contact lie on the tip circles of the displaced gears
    start, end = ap.contact_limits()
    assert np.linalg.norm(start - og) == pytest.approx(spur_pair_z50.gear.tip_radius_, rel=1e-12)
    assert np.linalg.norm(end - op) == pytest.approx(spur_pair_z50.pinion.tip_radius_, rel=1e-12)


def test_assembly_errors_shorten_double_contact(spur_pair_z50):
    """Larger centre offsets narrow the double-contact zone (condition 3 < 2 < 1)."""
    eps = [AssembledPair(spur_pair_z50, AssemblyErrors((0, 0), (e * UM, e * UM))).actual
           .transverse_contact_ratio for e in (0.0, 10.0, 100.0)]
    assert eps[0] > eps[1] > eps[2]
    assert eps[0] - eps[2] == pytest.approx(0.0422, abs=5e-4)


def wind_turbine_set(n: int = 4) -> PlanetarySet:
    kw = dict(module=15e-3, pressure_angle=D(25), helix_angle=D(8), herringbone=True)
    s = GearSpec(teeth=21, face_width=0.185, hand="right", groove_width=0.04, name="sun", **kw)
    p = GearSpec(teeth=37, face_width=0.175, hand="left", groove_width=0.05, name="planet", **kw)
    r = GearSpec(teeth=95, face_width=0.185, hand="left", internal=True, bore_radius=0.85,
                 groove_width=0.04, name="ring", **kw)
    return PlanetarySet(s, p, r, n)


def test_xu2020_planet_phases():
    """Xu et al. (2020), eq. 10 with psi_n = (n-1) 90 deg: dec(21 (n-1)/4), dec(95 (n-1)/4)."""
    ps = wind_turbine_set()
    np.testing.assert_allclose(ps.sun_phases, [0, 0.25, 0.5, 0.75], atol=1e-12)
    np.testing.assert_allclose(ps.ring_phases, [0, 0.75, 0.5, 0.25], atol=1e-12)
    assert ps.left_right_phase(2 * math.pi / 21 * 0.3) == pytest.approx(0.3)
    assert ps.mesh_period(10.0, 1.0) == pytest.approx(2 * math.pi / (9.0 * 21))


@pytest.mark.parametrize("zp,expect", [(37, 0.0), (36, 0.5), (29, 0.0), (30, 0.5)])
def test_ring_sun_phase_parity(zp, expect):
    """Unshifted planets: pitch-point crossings on the two flanks are in phase for odd z_p and
    half a mesh period apart for even z_p (pi - 2 pi/(2 z_p) = (z_p - 1) pitches / 2)."""
    s = spur(20, "sun", module=2e-3, bore_radius=0.01)
    p = spur(zp, "planet", module=2e-3, bore_radius=0.01)
    r = GearSpec(teeth=20 + 2 * zp, module=2e-3, pressure_angle=D(20), face_width=0.02,
                 internal=True, bore_radius=(20 + 2 * zp) * 1e-3 + 0.02, name="ring")
    n = 2 if (20 + 20 + 2 * zp) % 2 == 0 else 1
    assert PlanetarySet(s, p, r, n).ring_sun_phase == pytest.approx(expect, abs=1e-12)


def test_planetary_errors():
    with pytest.raises(InputError, match="cannot be assembled"):
        wind_turbine_set(3)
    with pytest.raises(InputError, match="ring.teeth"):
        base = wind_turbine_set()
        PlanetarySet(base.sun, base.planet, GearSpec(
            teeth=96, module=15e-3, pressure_angle=D(25), helix_angle=D(8), herringbone=True,
            face_width=0.185, hand="left", internal=True, bore_radius=0.85, name="ring"), 4)
    with pytest.raises(InputError, match="overlap"):
        s, p = spur(24, "sun", bore_radius=0.01), spur(40, "planet")
        r = GearSpec(teeth=104, module=3e-3, pressure_angle=D(20), face_width=0.02, internal=True,
                     bore_radius=0.18, name="ring")
        PlanetarySet(s, p, r, 8)


def test_config_units_and_errors(tmp_path):
    """Unit-suffixed keys convert to SI; unknown keys and bad values name the field."""
    doc = {
        "pinion": {"teeth": 20, "module_mm": 2.5, "pressure_angle_deg": 20, "face_width_mm": 30,
                   "helix_angle_deg": 15, "material": {"youngs_modulus_GPa": 210}},
        "gear": {"teeth": 41, "module_mm": 2.5, "pressure_angle_deg": 20, "face_width_mm": 30,
                 "helix_angle_deg": 15, "hand": "left"},
        "pair": {"assembly_error_gear_um": [5, -5]},
        "operation": {"torque_Nm": 200, "speed_rpm": 3000},
        "stiffness": {"friction": "ehl", "viscosity_mPas": 30},
    }
    cfg = gearbox_from_dict(doc)
    cfg = _PairView(cfg)
    assert cfg.pinion.module == pytest.approx(2.5e-3)
    assert cfg.pinion.helix_angle == pytest.approx(D(15))
    assert cfg.pinion.hand == "right"
    assert cfg.pinion.material.youngs_modulus == pytest.approx(210e9)
    assert cfg.assembly_errors.gear == pytest.approx((5e-6, -5e-6))
    assert cfg.operation.speed == pytest.approx(3000 * 2 * math.pi / 60)
    assert cfg.stiffness.viscosity == pytest.approx(0.03)
    bad = {**doc, "pinion": {**doc["pinion"], "modul_mm": 3}}
    with pytest.raises(InputError, match="modul_mm"):
        gearbox_from_dict(bad)
    bad = {**doc, "stiffness": {"friction": 0.9}}
    with pytest.raises(InputError, match=r"stiffness.friction = 0.9 .*\[0, 0.5\]"):
        gearbox_from_dict(bad)
    path = tmp_path / "broken.toml"
    path.write_text("[pinion\nteeth = 3")
    with pytest.raises(InputError, match="broken.toml"):
        load_gearbox(path)


def test_shipped_configs_load():
    from pathlib import Path

    configs = Path(__file__).parents[1] / "workflows" / "configs"
    for f in sorted(configs.glob("*_pair*.toml")):
        cfg = _PairView(load_gearbox(f))
        assert cfg.pinion.teeth > 0


class _PairView:
    """The fields this module's tests read, from a :class:`~pipeline.config.Gearbox`."""

    def __init__(self, box):
        self.pinion, self.gear = box.gears["pinion"], box.gears["gear"]
        self.assembly_errors, self.operation, self.stiffness = (
            box.assembly_errors, box.operation, box.stiffness)
