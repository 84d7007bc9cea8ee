"""Planetary models from the gearbox description (pipeline.dynamics.models.planetary_gears).

* Published reference: a gear set whose transverse pressure angle is Lin and Parker
  (1999)'s 24.6 deg, given their Table 1 masses, I/r^2, bearing and mesh stiffnesses,
  has their Table 2 natural frequencies for 3, 4 and 5 planets (in the coordinates
  u = r theta the model depends on nothing else; see tests/test_dyn_planetary.py).
* Same parameters, same model: the wind-turbine set of Xu et al. (2020) built from its
  gearbox file, given the masses, supports and mesh stiffness of the hand-built
  ``wind_turbine_herringbone_model``, has its natural frequencies (round-off).
* Exact values: the masses and inertias the models take are the gear bodies' (exact
  toothed sections; checked against a polar integration of the involute teeth, and the
  relief groove as the root cylinder exactly); phases follow Xu et al. (2020), eq. 10
  shifted to signals that start at the start of contact.
* Static limit: with planets in phase (or one planet) the sun- and ring-planet meshes
  reproduce the contact analysis' static TE and load at zero speed, planar and herringbone
  (normal direction: delta_n = x_s cos(beta_b), F_n = P / cos(beta_b)).
* ``gearpipe modes`` on the wind-turbine gearbox file.
"""

import dataclasses
import json
import math

import numpy as np
import pytest
from gearsets import LIN_PARKER_1999

from pipeline.config import gearbox_from_text, load_gearbox
from pipeline.contact import analyse_contact, analytical_compliance
from pipeline.contact.options import ContactOptions
from pipeline.dynamics.analysis import analyse_modes
from pipeline.dynamics.contact_excitation import excitation_from_contact
from pipeline.dynamics.mesh_input import excitation_from_signal
from pipeline.dynamics.modal import modal_analysis
from pipeline.dynamics.models import planetary_gears as pg
from pipeline.dynamics.models.wind_turbine_planetary import (
    K_J,
    L_TORSION,
    wind_turbine_herringbone_model,
)
from pipeline.dynamics.options import PlanetaryDynamicsOptions
from pipeline.dynamics.quasi_static import quasi_static_response
from pipeline.geometry.body import GearBody
from pipeline.geometry.involute import inv
from pipeline.geometry.planetary import dec
from pipeline.operation import OperatingPoint
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError

WIND = "workflows/configs/wind_turbine_herringbone_planetary.toml"


def _gears_text(n_planets: int, pressure_angle: float = 24.6) -> str:
    gear = f"module_mm = 3.0\npressure_angle_deg = {pressure_angle}\nface_width_mm = 30.0\n"
    return (f"[sun]\nteeth = 40\n{gear}bore_radius_mm = 15.0\n"
            f"[planet]\nteeth = 20\n{gear}bore_radius_mm = 10.0\n"
            f"[ring]\nteeth = 80\n{gear}internal = true\nrim_outer_radius_mm = 140.0\n"
            "[carrier]\nmass_kg = 5.43\ninertia_kgm2 = 0.05\n"
            f"[planetary]\nplanets = {n_planets}\n"
            "[operation]\ntorque_Nm = 200.0\nspeed_rpm = 1000.0\n")


def _constant(k: float) -> object:
    return excitation_from_signal(PeriodicSignal(np.full(8, k)))


@pytest.mark.parametrize("n_planets", [3, 4, 5])
def test_gears_with_lin_parker_parameters_give_their_table_2(n_planets):
    """z 40/20/80, m 3 mm, alpha_n 24.6 deg (spur: transverse 24.6 deg) with Lin and Parker's
    masses, I = (I/r^2) r^2 on the base radii (carrier: on the carrier radius), k_sp = k_rp
    5e8, bearings 1e8 N/m, ring support 1e9 N/m at its base circle (the default): Table 2
    within 0.05 % (its rounding), with the mode types (non-gyroscopic, as the table)."""
    box = gearbox_from_text(_gears_text(n_planets))
    ps = box.planetary
    lp = {"sun": (0.4, 0.39), "planet": (0.66, 0.61), "ring": (2.35, 3.00)}
    bodies = {r: dataclasses.replace(box.bodies[r], mass=m,
                                     inertia=i * box.gears[r].base_radius**2)
              for r, (m, i) in lp.items()}
    carrier = dataclasses.replace(box.carrier, mass=5.43, inertia=6.29 * ps.carrier_radius**2)
    model = pg.planetary_model_from_gears(ps, bodies, carrier, box.operation,
                                          PlanetaryDynamicsOptions(), _constant(5e8),
                                          _constant(5e8))
    assert model.pressure_angle_sun == pytest.approx(math.radians(24.6), rel=1e-12)
    assert model.pressure_angle_ring == pytest.approx(math.radians(24.6), rel=1e-12)
    res = model.classify(modal_analysis(model.assembly().assemble()))
    ref = LIN_PARKER_1999[n_planets]
    f, kinds = res.frequencies, np.array(res.kinds)
    for kind, values, mult in (("rotational", ref["rot"][1:], 1),
                               ("translational", ref["trans"], 2),
                               ("planet", ref["planet"], n_planets - 3)):
        np.testing.assert_allclose(np.sort(f[kinds == kind]), np.sort(np.repeat(values, mult)),
                                   rtol=5e-4)


def _hand_built_equivalent():
    """The wind-turbine file's set with the hand-built model's parameters (groove_mesh=None)."""
    ref = wind_turbine_herringbone_model(groove_mesh=None)
    box = load_gearbox(WIND)
    ps = box.planetary
    bodies = {r: dataclasses.replace(box.bodies[r], mass=getattr(ref, f"mass_{r}"),
                                     inertia=getattr(ref, f"inertia_{r}"))
              for r in pg.ROLES}
    carrier = dataclasses.replace(box.carrier, mass=ref.mass_carrier,
                                  inertia=ref.inertia_carrier)
    options = PlanetaryDynamicsOptions(
        sun_bearing_stiffness=2e9, ring_bearing_stiffness=5e9, carrier_bearing_stiffness=5e9,
        planet_bearing_stiffness=3e9, ring_torsional_stiffness=5e10,
        sun_axial_stiffness=1e9, ring_axial_stiffness=5e9, carrier_axial_stiffness=5e9,
        planet_axial_stiffness=2e9, groove_torsional_stiffness=K_J[0] / L_TORSION,
        groove_lateral_stiffness=5e9, sun_load_side="R", damping_ratio=0.05,
        modal_damping_ratio=0.02)
    zs, zr = ps.sun.teeth, ps.ring.teeth
    speed = 2 * math.pi * 1440.0 * (zs + zr) / (zs * zr)  # sun speed of a 1440 Hz mesh
    operation = OperatingPoint(ref.sun_torque, speed)
    cb2 = math.cos(ps.sun.base_helix_angle) ** 2

    def transverse(k):  # the hand-built model's normal-direction signal
        return excitation_from_signal(PeriodicSignal(k.values * cb2, k.period))

    model = pg.herringbone_planetary_model_from_gears(
        ps, bodies, carrier, operation, options, transverse(ref.k_sun_mesh),
        transverse(ref.k_ring_mesh))
    return ref, model, box


def test_wind_turbine_file_with_the_hand_built_parameters_has_its_frequencies():
    """Same masses, supports, groove and mesh stiffness: the model derived from the gearbox
    file has the hand-built model's natural frequencies (with the gyroscopic terms of its
    95.2 rad/s carrier) to round-off, and its radii, angles and groove phase."""
    ref, model, _ = _hand_built_equivalent()
    for name in ("base_radius_sun", "base_radius_planet", "base_radius_ring", "carrier_radius",
                 "pressure_angle_sun", "pressure_angle_ring", "base_helix_angle",
                 "carrier_speed", "mesh_period", "phase_lr"):
        assert getattr(model, name) == pytest.approx(getattr(ref, name), rel=1e-10), name
    np.testing.assert_allclose(model.k_sun_mesh.values, ref.k_sun_mesh.values, rtol=1e-14)
    f_ref, f = analyse_modes(ref).frequencies, analyse_modes(model).frequencies
    assert f.size == f_ref.size == 8 * 7 - 6 * 4  # 8(N+3) less the ties of 6 members
    np.testing.assert_allclose(f, f_ref, rtol=1e-9, atol=1e-6)


def test_phases_are_xu2020_eq10_from_the_start_of_contact():
    """Sun mesh n lags lambda_sn - o_sp, ring mesh n lambda_rn + lambda_rs - o_pr mesh periods,
    o = (s_pitch - s_start) / p_b of each pair (by hand from the pairs' geometry)."""
    _, model, box = _hand_built_equivalent()
    ps = box.planetary
    sp, pr = ps.sun_planet, ps.planet_ring
    o_sp = (sp.s_pitch - sp.s_start) / sp.base_pitch
    o_pr = (pr.s_pitch - pr.s_start) / pr.base_pitch
    psi = np.arange(4) * math.pi / 2
    np.testing.assert_allclose(model.planet_angles, psi, atol=1e-15)
    np.testing.assert_allclose(model.phase_sun, dec(21 * psi / (2 * math.pi) - o_sp), atol=1e-12)
    np.testing.assert_allclose(model.phase_ring,
                               dec(95 * psi / (2 * math.pi) + ps.ring_sun_phase - o_pr),
                               atol=1e-12)


def _polar_integral(g) -> tuple[float, float]:
    """Area (m^2) and polar moment (m^4) of the section with involute flanks from the root to
    the tip circle (external) or from the tip to the root circle (internal), no fillet,
    times the toothed width, plus a herringbone groove: mass and inertia per unit density."""
    at = g.transverse_pressure_angle
    s_half = g.reference_tooth_thickness / (2 * g.reference_radius)
    lo, hi = sorted((g.root_radius, g.tip_radius_))
    r = np.linspace(lo, hi, 20001)
    a = np.arccos(np.minimum(1.0, g.base_radius / r))
    psi = s_half - inv(at) + inv(a) if g.internal else s_half + inv(at) - inv(a)
    teeth = g.teeth * np.array([np.trapezoid(2 * psi * r, r), np.trapezoid(2 * psi * r**3, r)])
    r_out, r_in = (g.bore_radius, hi) if g.internal else (lo, g.bore_radius)  # the rim
    disc = np.array([math.pi * (r_out**2 - r_in**2), math.pi / 2 * (r_out**4 - r_in**4)])
    return tuple(g.face_width * (disc + teeth) + g.groove_width * disc)


def test_planetary_bodies_are_the_exact_gear_sections():
    """The wind-turbine file's model takes the gear bodies' mass and inertia. Planet (bore
    100 mm) and ring (internal, rim 799.5 mm), both herringbone: the polar integral of the
    involute teeth without the fillets, plus the groove (planet: root circle to bore; ring:
    root circle to rim), lies 0-0.3 % below the exact section (the fillets add the corner
    between involute and root: 0.15 % / 0.27 % estimated as 2 (1 - pi/4) rho^2 per tooth).
    The sun (root circle below its base circle, where the hand integral has no flank) is
    checked through its groove: exactly the root cylinder."""
    box = load_gearbox(WIND)
    model = pg.herringbone_planetary_model_from_gears(
        box.planetary, box.bodies, box.carrier,
        OperatingPoint(148000.0, 10.0), PlanetaryDynamicsOptions(), _constant(2e9),
        _constant(2e9))
    for role in pg.ROLES:
        body = box.bodies[role]
        assert getattr(model, f"mass_{role}") == body.mass_
        assert getattr(model, f"inertia_{role}") == body.inertia_
    assert (model.mass_carrier, model.inertia_carrier) == (2273.1, 440.1)
    for role in ("planet", "ring"):
        g = box.gears[role]
        mass, inertia = (g.material.density * v for v in _polar_integral(g))
        assert 0.0 < box.bodies[role].mass_ / mass - 1 < 3e-3, role
        assert 0.0 < box.bodies[role].inertia_ / inertia - 1 < 3e-3, role
    sun = box.gears["sun"]
    no_groove = GearBody(dataclasses.replace(sun, groove_width=0.0))
    rho, rf = sun.material.density, sun.root_radius
    assert box.bodies["sun"].mass_ - no_groove.mass_ == pytest.approx(
        rho * 0.040 * math.pi * rf**2, rel=1e-12)
    assert box.bodies["sun"].inertia_ - no_groove.inertia_ == pytest.approx(
        rho * 0.040 * math.pi / 2 * rf**4, rel=1e-12)


def _contact(pair, operation, positions: int, slices: int):
    """Loaded contact cycle (analytical slices) of one mesh and its excitation."""
    opts = ContactOptions(positions=positions, slices=slices)
    cycle = analyse_contact(analytical_compliance(pair, operation, opts), operation, opts)
    return cycle, excitation_from_contact(cycle, pair, operation)


def test_in_phase_planetary_reproduces_the_contact_at_zero_speed():
    """z 40/20/80, 4 planets: all sun meshes in phase (40/4 whole), all ring meshes in phase
    (80/4). Zero speed: every sun and ring mesh carries P = T_s / (N r_bs), the load of
    both contact analyses, at the DTE of their static TE x_s (rel. 1e-9)."""
    box = gearbox_from_text(_gears_text(4, 20.0))
    ps = box.planetary
    op_sp, op_pr = pg.mesh_operations(ps, box.operation)
    cycle, sun = _contact(ps.sun_planet, op_sp, 60, 1)
    ring_cycle, ring = _contact(ps.planet_ring, op_pr, 60, 1)
    P = cycle.load
    assert P == pytest.approx(200.0 / (4 * ps.sun.base_radius), rel=1e-12)
    assert ring_cycle.load == pytest.approx(P, rel=1e-12)
    model = pg.planetary_model_from_gears(ps, box.bodies, box.carrier, box.operation,
                                          PlanetaryDynamicsOptions(), sun, ring)
    assert np.ptp(model.phase_sun) == 0 and np.ptp(model.phase_ring) == 0
    system = model.assembly().assemble()
    # at the sample phases of each mesh's signals (mesh n runs k(tau - phase_n)); between
    # samples the product k e of the forcing is interpolated, not k times e
    samples = np.arange(60) / 60
    r_s = quasi_static_response(system, samples + model.phase_sun[0])
    r_r = quasi_static_response(system, samples + model.phase_ring[0])
    for n in range(4):
        i_s, i_r = r_s.mesh(f"s-p{n + 1}"), r_s.mesh(f"r-p{n + 1}")
        np.testing.assert_allclose(r_s.mesh_force[i_s], P, rtol=1e-9)
        np.testing.assert_allclose(r_s.dte[i_s], cycle.transmission_error, rtol=1e-9)
        np.testing.assert_allclose(r_r.mesh_force[i_r], P, rtol=1e-9)
        np.testing.assert_allclose(r_r.dte[i_r], ring_cycle.transmission_error, rtol=1e-9)


def test_herringbone_one_planet_reproduces_the_contact_of_a_half_at_zero_speed():
    """The wind-turbine gears with one planet, sun torque on both halves, halves tied: each
    half of the sun and ring meshes carries the contact load of its helical half (the sun's
    and the internal ring's), P / cos(beta_b) along the flank normal, at DTE x_s cos(beta_b)
    (rel. 1e-8)."""
    box = load_gearbox(WIND)
    ps = dataclasses.replace(box.planetary, n_planets=1)
    operation = OperatingPoint(148000.0 / 4, 10.0)
    ops = pg.mesh_operations(ps, operation, halves=2)
    halves = [pg.helical_half(p) for p in (ps.sun_planet, ps.planet_ring)]
    assert halves[0].face_width == pytest.approx(0.175, rel=1e-12)
    assert not halves[1].gear.herringbone and halves[1].gear.internal
    (cycle, sun), (ring_cycle, ring) = (_contact(h, op, 40, 6)
                                        for h, op in zip(halves, ops, strict=True))
    assert cycle.load == pytest.approx(operation.torque / (2 * ps.sun.base_radius), rel=1e-12)
    assert ring_cycle.load == pytest.approx(cycle.load, rel=1e-12)
    model = pg.herringbone_planetary_model_from_gears(
        ps, box.bodies, box.carrier, operation, PlanetaryDynamicsOptions(), sun, ring)
    system = model.assembly().assemble()
    cb = math.cos(ps.sun.base_helix_angle)
    for mesh, phase, c in (("s", model.phase_sun[0], cycle), ("r", model.phase_ring[0],
                                                              ring_cycle)):
        r = quasi_static_response(system, np.arange(40) / 40 + phase)
        for side in "LR":
            i = r.mesh(f"{mesh}-p1{side}")
            np.testing.assert_allclose(r.mesh_force[i], c.load / cb, rtol=1e-8)
            np.testing.assert_allclose(r.dte[i], c.transmission_error * cb, rtol=1e-8)


def test_planetary_options_and_models_refuse_bad_inputs():
    box = gearbox_from_text(_gears_text(4))
    ex = _constant(5e8)
    with pytest.raises(InputError, match="groove_torsional_stiffness applies to a herringbone"):
        pg.planetary_model_from_gears(box.planetary, box.bodies, box.carrier, box.operation,
                                      PlanetaryDynamicsOptions(groove_torsional_stiffness=1e8),
                                      ex, ex)
    with pytest.raises(InputError, match="needs herringbone gears"):
        pg.herringbone_planetary_model_from_gears(box.planetary, box.bodies, box.carrier,
                                                  box.operation, PlanetaryDynamicsOptions(),
                                                  ex, ex)
    with pytest.raises(InputError, match="driver = 'gear'"):
        pg.mesh_operations(box.planetary, OperatingPoint(10.0, 10.0, "gear"))
    with pytest.raises(InputError, match="groove_lateral_stiffness needs"):
        PlanetaryDynamicsOptions(groove_lateral_stiffness=1e9)
    text = _gears_text(4) + "[dynamics]\nplanet_bearing_stiffness_N_per_m = -1.0\n"
    with pytest.raises(InputError, match=r"dynamics.planet_bearing_stiffness_N_per_m = -1 N/m "
                                         r"is outside the allowed range \[0, 1e\+14\] N/m"):
        gearbox_from_text(text)
    with pytest.raises(InputError, match="'dofs' is not known"):
        gearbox_from_text(_gears_text(4) + '[dynamics]\ndofs = "torsional"\n')
    with pytest.raises(InputError, match="'sun_load_side' is not known"):
        gearbox_from_text(open("workflows/configs/spur_pair_assembly_errors.toml").read()
                          .replace("damping_ratio = 0.07", 'damping_ratio = 0.07\n'
                                   'sun_load_side = "R"'))


def test_modes_command_on_the_wind_turbine_gearbox_file(tmp_path, capsys):
    """``gearpipe modes`` builds the herringbone model from the file's gears (8(N+3) DOF less
    the ties of ring, carrier and planet halves) and writes its modes: the rigid rotation
    first, then the mode families of Lin and Parker and axial modes."""
    from pipeline.cli import main

    assert main(["modes", WIND, "--out", str(tmp_path), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    f = np.array(summary["frequencies_Hz"])
    assert summary["coordinates"] == 8 * 7 and summary["independent_dofs"] == 8 * 7 - 6 * 4
    assert f.size == 8 * 7 - 6 * 4 and np.all(np.diff(f) >= -1e-9)
    assert f[0] < 1e-6 and f[2] > 10.0
    assert {"rotational", "translational", "planet"} <= set(summary["kinds"])
    assert (tmp_path / "modes.csv").exists() and (tmp_path / "mode_shapes.png").exists()
