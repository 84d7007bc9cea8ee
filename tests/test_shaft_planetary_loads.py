"""A planetary set's meshes on the sun's shaft and a planet's pin
(pipeline.shaft.misalignment, planetary block) against exact statics.

* A planet's two mesh forces: the sun pushes the planet along its sun-planet line of action
  away from the sun, the ring along the planet-ring one towards the sun's axis; both drive
  the carrier, so N pins carry the carrier torque ``T_c = T_s (1 + z_r / z_s)`` (ring
  fixed; the torque balance of a simple planetary set, e.g. Mueller, *Epicyclic Drive
  Trains*, 1982, ch. 2), and the angle between the two forces is ``alpha_sp + alpha_pr``.
* The sun under N equally spaced meshes: the forces cancel (sum of ``N`` unit vectors at
  ``2 pi / N``), the moments about the axis add to ``N P r_b``.
* A cantilevered pin (clamped at one end, the planet's rigid seat beyond a free length
  ``a``): the seat's deflection and tilt are those of a Timoshenko cantilever loaded at its
  end by the resultant ``F`` and the moment ``F b / 2`` (Roark, 8th ed., Table 8.1 cases 1a
  and 3a, with the shear term ``F a / (kappa G A)``, kappa Cowper's 1966).
* An integral sun seat held against rotation at ``z = 0``: the twist at ``z`` under torques
  ``T_k`` at ``z_k`` is ``sum_k T_k min(z, z_k) / (G J)`` (a uniform shaft).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pipeline.config import load_gearbox
from pipeline.contact.analysis import line_of_action_load
from pipeline.dynamics.models.planetary_gears import mesh_operations
from pipeline.geometry.gear import Material
from pipeline.run.planetary_shafts import MESHES, build_system, sun_unit_loads
from pipeline.shaft.beam import BeamShaft
from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
from pipeline.shaft.misalignment import body_retreats, planet_unit_loads, rotated_unit_loads
from pipeline.shaft.timoshenko import shear_coefficient
from pipeline.validation import InputError

EXAMPLE = "workflows/configs/shaft_planetary.toml"
MAT = Material()
E, G, NU = MAT.youngs_modulus, MAT.shear_modulus, MAT.poisson_ratio


def test_rotated_unit_loads_turn_forces_and_moments_about_the_axis():
    """(0, 1, 0.2, -0.3, 0.4, 0.05) turned by 90 deg: (F_x, F_y) -> (-F_y, F_x), the moment's
    x-y part likewise, the z parts unchanged (exact to round-off)."""
    unit = np.array([[0.0, 1.0, 0.2, -0.3, 0.4, 0.05]])
    out = rotated_unit_loads(unit, math.pi / 2)
    np.testing.assert_allclose(out, [[-1.0, 0.0, 0.2, -0.4, -0.3, 0.05]], atol=1e-15)


@pytest.mark.parametrize("n_planets", [3, 4, 5, 7])
def test_sun_meshes_cancel_for_equal_spacing(n_planets):
    """N equally spaced sun-planet meshes: the unit forces sum to 0 (1e-14) and the moments
    about the axis to N r_b (r_b = 0.05 m)."""
    angles = 2 * math.pi * np.arange(n_planets) / n_planets
    units = sun_unit_loads(0.05, tuple(angles), 6)
    total = sum(units)
    np.testing.assert_allclose(total[:, :5], 0.0, atol=1e-14)
    np.testing.assert_allclose(total[:, 5], n_planets * 0.05, rtol=1e-14)


def test_unequal_spacing_leaves_the_closed_form_net_force():
    """Planets at 0, 100 and 230 deg: the net unit force is sum (-sin psi, cos psi) =
    (-sin 100 - sin 230, 1 + cos 100 + cos 230) = (-0.21876, 0.18356), of magnitude 0.28558
    (exact to round-off): unequal spacing leaves a net force on the sun."""
    psi = np.radians([0.0, 100.0, 230.0])
    total = sum(sun_unit_loads(0.05, tuple(psi), 1))
    expected = np.array([-np.sin(psi).sum(), np.cos(psi).sum()])
    np.testing.assert_allclose(total[0, :2], expected, rtol=1e-14)
    assert np.hypot(*total[0, :2]) == pytest.approx(0.2855752, rel=1e-6)


def test_planet_forces_drive_the_carrier_with_the_set_s_torque():
    """The example set (z 40/20/80, 4 planets, 500 N m on the sun): the two forces P on a
    planet (P = T_s / (N r_b,s), the same along both lines of action) make the angle
    alpha_sp + alpha_pr; N pins carry a tangential force whose moment about the sun's axis
    is T_s (1 + z_r / z_s) = 1500 N m (1e-12), with no radial part for equal pressure angles
    (1e-12 of P)."""
    box = load_gearbox(EXAMPLE)
    ps = box.planetary
    ops = mesh_operations(ps, box.operation)
    p = [line_of_action_load(pair, op) for pair, op in zip((ps.sun_planet, ps.planet_ring),
                                                            ops, strict=True)]
    assert p[0] == pytest.approx(500.0 / (4 * ps.sun.base_radius), rel=1e-12)
    assert p[1] == pytest.approx(p[0], rel=1e-12)
    a_sp, a_pr = (ps.sun_planet.operating_pressure_angle,
                  ps.planet_ring.operating_pressure_angle)
    e_sp, e_pr = (u[0, :2] for u in planet_unit_loads((a_sp, a_pr), 1))
    assert math.acos(float(e_sp @ e_pr)) == pytest.approx(a_sp + a_pr, rel=1e-12)
    force = p[0] * e_sp + p[1] * e_pr
    carrier = ps.n_planets * ps.carrier_radius * force[0]
    assert carrier == pytest.approx(500.0 * (1 + ps.ring.teeth / ps.sun.teeth), rel=1e-12)
    assert abs(force[1]) < 1e-12 * p[0]


def test_body_retreats_is_the_work_conjugate_of_the_loads():
    """For any symmetric C, two meshes' unit loads and forces: d = C sum L_m F_m and each
    retreat is L_m . d (against an explicit sum, 1e-13)."""
    rng = np.random.default_rng(3)
    n = 4
    a = rng.normal(size=(6 * n, 6 * n))
    c = a @ a.T
    units = [rng.normal(size=(n, 6)) for _ in range(2)]
    forces = [rng.normal(size=n) for _ in range(2)]
    d, ret = body_retreats(c, units, forces)
    f = (units[0] * forces[0][:, None] + units[1] * forces[1][:, None]).reshape(-1)
    np.testing.assert_allclose(d.reshape(-1), c @ f, rtol=1e-13)
    for u, r in zip(units, ret, strict=True):
        np.testing.assert_allclose(r, (u * d).sum(axis=1), rtol=1e-13)
    with pytest.raises(InputError, match="one force row per mesh"):
        body_retreats(c, units, forces[:1])


def _cantilever(a, b, tail, d):
    """A pin of diameter d clamped at z = 0, the rigid seat from a to a + b, then tail."""
    lay = ShaftLayout(segments=(ShaftSegment(0.0, a + b + tail, d),), gear_position=a + b / 2,
                      seat_width=b, bearings=(Bearing(0.0, tilting_stiffness=math.inf,
                                                      axial=True),),
                      torque_position=0.0, hub="rigid", material=MAT)
    i = math.pi / 64 * d**4
    area = math.pi / 4 * d**2
    kga = float(shear_coefficient(NU, d, 0.0)) * G * area
    return lay, E * i, kga


def test_cantilevered_pin_under_both_meshes_is_the_closed_form():
    """A 35 mm pin clamped at 0, the planet's 30 mm rigid seat from 15 mm, both meshes'
    uniform line loads 74 and 60 N/mm at 20 deg: each face point's retreat along each mesh
    is e_m . (v(a) + theta(a) (z - a)) with v(a) = F a^3 / 3EI + F a / kGA + M a^2 / 2EI and
    theta(a) = F a^2 / 2EI + M a / EI, F the resultant, M = F b / 2 (1e-9)."""
    a, b, n = 0.015, 0.030, 10
    lay, ei, kga = _cantilever(a, b, 0.005, 0.035)
    z = (np.arange(n) + 0.5) * b / n
    points = lay.gear_position + z - b / 2
    model = BeamShaft(lay, extra_nodes=tuple(points))
    alpha = math.radians(20.0)
    units = planet_unit_loads((alpha, alpha), n)
    w = (74e3, 60e3)
    forces = [np.full(n, wi * b / n) for wi in w]
    d, ret = body_retreats(model.flexibility(points), units, forces)
    resultant = sum(u[0, :2] * wi * b for u, wi in zip(units, w, strict=True))
    v_a = resultant * (a**3 / (3 * ei) + a / kga + (b / 2) * a**2 / (2 * ei))
    t_a = resultant * (a**2 / (2 * ei) + (b / 2) * a / ei)
    u = v_a[None, :] + np.outer(points - a, t_a)
    np.testing.assert_allclose(d[:, :2], u, rtol=1e-9)
    for unit, r in zip(units, ret, strict=True):
        np.testing.assert_allclose(r, u @ unit[0, :2], rtol=1e-9)
    # the seat tilts about the axis normal to the resultant: theta = z x t_a
    np.testing.assert_allclose(d[0, 3:5], [-t_a[1], t_a[0]], rtol=1e-9)


def test_straddled_symmetric_pin_opens_no_misalignment():
    """A pin on two rigid supports 60 mm apart, the planet's seat in the middle: by symmetry
    the seat translates without tilting, so each mesh's retreat is the same across the face
    (range below 1e-12 of its value), under any pair of uniform line loads."""
    lay = ShaftLayout(segments=(ShaftSegment(0.0, 0.060, 0.035),), gear_position=0.030,
                      seat_width=0.030, bearings=(Bearing(0.0, axial=True), Bearing(0.060)),
                      torque_position=0.0, hub="rigid", material=MAT)
    n = 8
    points = 0.015 + (np.arange(n) + 0.5) * 0.030 / n
    model = BeamShaft(lay, extra_nodes=tuple(points))
    units = planet_unit_loads((math.radians(20.0), math.radians(22.0)), n)
    _, ret = body_retreats(model.flexibility(points), units,
                           [np.full(n, 2000.0 / n), np.full(n, 2100.0 / n)])
    for r in ret:
        assert np.ptp(r) < 1e-12 * abs(r.mean())


def test_integral_sun_twist_under_four_planets_is_the_closed_form():
    """The example's sun made a uniform 112.5 mm shaft held at z = 0 against rotation with
    rigid bearings: four planets' meshes at a uniform line load P / b leave no transverse
    displacement (below 1e-12 of the twist), and each planet's retreat is r_b theta_z(z_j)
    with theta_z(z) = sum_k N r_b F_k min(z, z_k) / (G J) (1e-9); all planets alike (1e-12)."""
    box = load_gearbox(EXAMPLE)
    ps = box.planetary
    d = 0.1125
    lay = ShaftLayout(segments=(ShaftSegment(0.0, 0.170, d),), gear_position=0.120,
                      seat_width=0.030, bearings=(Bearing(0.060, axial=True), Bearing(0.160)),
                      torque_position=0.0, hub="integral", material=MAT)
    box = dataclasses.replace(box, shafts={"sun": ("beam", lay)})
    n, b = 10, ps.sun_planet.face_width
    system = build_system(box, {m: b for m in MESHES}, n)
    p = 2217.0
    w = {m: np.full(n, p / b) for m in MESHES}
    gaps, sun, pin = system.deflect(w)
    assert pin is None
    rb = ps.sun.base_radius
    points = 0.120 - b / 2 + (np.arange(n) + 0.5) * b / n
    gj = G * math.pi / 32 * d**4
    theta = np.array([sum(4 * rb * p / n * min(zj, zk) for zk in points) / gj
                      for zj in points])
    np.testing.assert_allclose(sun.retreats[0], rb * theta, rtol=1e-9)
    assert np.abs(sun.displacement[:, :2]).max() < 1e-12 * rb * theta.max()
    assert sun.net_force < 1e-9 * p * n
    for r in sun.retreats[1:]:
        np.testing.assert_allclose(r, sun.retreats[0], rtol=1e-12)
    np.testing.assert_allclose(gaps["sun_planet"], sun.retreats[0], rtol=1e-15)
    assert not gaps["planet_ring"].any()


def test_planet_bearing_adds_an_approach_only():
    """The example's pin with a planet bearing of 5e8 N/m: under uniform line loads P / b on
    both meshes (P = 2217 N) the planet moves by the net force 2 P cos(20 deg) along the
    tangent over k_pb, so each mesh's gap grows by e_m . F_net / k_pb = 2 P cos^2(20 deg) /
    k_pb = 7.83 um uniformly (1e-12) and its variation across the face is unchanged
    (1e-12)."""
    box = load_gearbox(EXAMPLE)
    b, n, p = 0.030, 10, 2217.0
    w = {m: np.full(n, p / b) for m in MESHES}
    rigid, _, _ = build_system(box, {m: b for m in MESHES}, n).deflect(w)
    soft_box = dataclasses.replace(box, planet_bearing_stiffness=5.0e8)
    soft, _, pin = build_system(soft_box, {m: b for m in MESHES}, n).deflect(w)
    alpha = box.planetary.sun_planet.operating_pressure_angle
    extra = 2 * p * math.cos(alpha) ** 2 / 5.0e8
    for m in MESHES:
        assert pin.bearing[m] == pytest.approx(extra, rel=1e-12)
        np.testing.assert_allclose(soft[m] - rigid[m], extra, rtol=1e-12)
    assert extra == pytest.approx(7.83e-6, rel=1e-3)
