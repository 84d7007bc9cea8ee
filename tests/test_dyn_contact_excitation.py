"""Mesh excitation from the loaded tooth contact (pipeline.dynamics.contact_excitation).

The ladder:

* exact: with the linear local contact and perfect flanks the loaded contact is the slice
  method itself (every slice loaded, k = sum 1/G_ii), so the contact excitation equals the
  stiffness stage's k, K_f, KT_f1, KT_f2, and e = x_s - P/k vanishes (round-off);
* exact: the zero-speed limit of the pair model (static equilibrium at every phase)
  reproduces the contact analysis' static transmission error x_s and load P at every
  position, for the spur pair of the assembly-error paper and the helical pair of Yang et
  al. (2026), lateral-torsional and torsional (round-off); the angular transmission error
  carries the bearing deflection 2 P / k_b on top;
* exact by hand: friction coefficients of single-contact positions (one loaded point at
  s: K_f = lam mu k, KT_f1 = lam mu k s, KT_f2 = -lam mu k (T1T2 - s)); the EHL coefficient
  there equals the stiffness stage's (the one pair carries the whole load either way);
  with friction the static mesh force follows the torque balance with the friction
  moments, which the contact analysis' P = T / r_b leaves out;
* convergence: the harmonic balance at 1e-3 of the lowest natural frequency tends to the
  contact values at first order in 1/H (the sampled signals are continuous but ramp over
  one sample interval where a tooth pair enters or leaves: Fourier coefficients ~ 1/h^2);
* independent solution: the DTE of the assembly-error paper's pair at its operating speed,
  analytical and contact excitation, against a scipy DOP853 integration of the paper's
  equations (tests/test_dyn_spur_dte.py, 1e-6 at H = 200);
* regression: that DTE at H = 40, analytical vs contact excitation.
"""

import dataclasses
import math

import numpy as np
import pytest

from pipeline.config import gearbox_from_text, load_gearbox
from pipeline.contact import analyse_contact, analytical_compliance
from pipeline.contact.options import ContactOptions
from pipeline.dynamics.analysis import analyse_modes
from pipeline.dynamics.contact_excitation import (
    excitation_from_contact,
    point_friction_coefficients,
)
from pipeline.dynamics.harmonic_balance import harmonic_balance
from pipeline.dynamics.mesh_input import (
    EXCITATION_SAMPLES,
    excitation_from_stiffness,
    tooth_pair_jumps,
)
from pipeline.dynamics.models.spur_pair import spur_pair_model
from pipeline.dynamics.options import PairDynamicsOptions
from pipeline.dynamics.quasi_static import quasi_static_response
from pipeline.stiffness.mesh import FrictionModel, PairModel, friction_coefficients, mesh_stiffness
from pipeline.validation import InputError

CONFIGS = "workflows/configs/"
CASES = {"spur": ("spur_pair_assembly_errors.toml", 1),
         "helical": ("traction_helical_pair.toml", 8)}
POSITIONS = 60


def _case(name: str, mu: float = 0.0, local: str = "weber", kind: str = "constant",
          tip_contact: bool = True):
    """(gearbox, actual pair, contact cycle, friction model) of a case: analytical slices."""
    path, slices = CASES[name]
    box = load_gearbox(CONFIGS + path)
    pair = box.actual_pair
    friction = FrictionModel(mu=mu, kind=kind)
    stiffness = dataclasses.replace(box.stiffness, friction="ehl" if kind == "ehl" else mu)
    opts = ContactOptions(positions=POSITIONS, slices=slices, local_contact=local,
                          tip_contact=tip_contact)
    model = PairModel.build(pair)
    source = analytical_compliance(pair, box.operation, opts, stiffness, model=model)
    return box, pair, analyse_contact(source, box.operation, opts), friction, model


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    return (request.param, *_case(request.param))


def _model(box, pair, excitation, dofs="lateral_torsional", friction=False, operation=None):
    options = dataclasses.replace(box.dynamics or PairDynamicsOptions(), dofs=dofs,
                                  friction=friction)
    return spur_pair_model(pair, (box.bodies["pinion"], box.bodies["gear"]),
                           operation or box.operation, options, excitation)


@pytest.mark.parametrize("name", list(CASES))
def test_linear_contact_equals_the_stiffness_stage(name):
    """Linear local contact, perfect flanks, mu = 0.05, contact on the nominal path: the same
    k, K_f, KT_f1, KT_f2 as the potential-energy stiffness on the same positions and slices,
    and e = 0 (round-off: the contact solve and the sums differ in summation order only)."""
    box, pair, cycle, friction, model = _case(name, mu=0.05, local="linear", tip_contact=False)
    ex = excitation_from_contact(cycle, pair, box.operation, friction)
    ref = excitation_from_stiffness(mesh_stiffness(model, POSITIONS, CASES[name][1], friction,
                                                   box.operation))
    for field in ("stiffness", "friction_stiffness", "friction_torque_pinion",
                  "friction_torque_gear"):
        got, want = getattr(ex, field).values, getattr(ref, field).values
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12 * np.abs(want).max())
    assert np.abs(ex.transmission_error.values).max() < 1e-12 * cycle.transmission_error.max()
    assert ex.mesh_period == pytest.approx(ref.mesh_period, rel=1e-14)
    assert ex.source == "contact" and ex.load == cycle.load


@pytest.mark.parametrize("dofs", ["lateral_torsional", "torsional"])
def test_static_limit_reproduces_contact_te_and_load(case, dofs):
    """Zero speed: delta = x_s and F = P at every contact position (rel. 1e-10: a 2- or
    6-unknown solve with stiffnesses 1e8-1e9 N/m). The angular TE r_bp theta_p - r_bg
    theta_g exceeds delta by the bearings' deflection 2 P / k_b (lateral-torsional). The
    spur excitation on the nominal path is resampled at EXCITATION_SAMPLES phases (its jumps
    resolved), which hold the contact positions; between them the force is P as well. With
    tip corners touching (both cases here) it keeps the contact positions."""
    name, box, pair, cycle, friction, _ = case
    ex = excitation_from_contact(cycle, pair, box.operation, friction)
    r = quasi_static_response(_model(box, pair, ex, dofs).assembly().assemble())
    tip = (cycle.point_load[cycle.point_corner > 0] > 0).any()
    assert r.time.size == (EXCITATION_SAMPLES if name == "spur" and not tip else POSITIONS)
    at_positions = slice(None, None, r.time.size // POSITIONS)
    x, P = cycle.transmission_error, cycle.load
    np.testing.assert_allclose(r.dte[0][at_positions], x, rtol=1e-10)
    np.testing.assert_allclose(r.mesh_force[0], P, rtol=1e-10)
    if dofs == "lateral_torsional":
        angular = (pair.pinion.base_radius * r.coordinate("pinion.theta")
                   - pair.gear.base_radius * r.coordinate("gear.theta"))
        kb = box.dynamics.bearing_stiffness if box.dynamics else 1e8
        np.testing.assert_allclose(angular[at_positions] - x, 2 * P / kb, rtol=1e-8)


def test_harmonic_balance_at_vanishing_speed_converges_to_the_contact_values(case):
    """Mesh frequency 1e-3 of the first natural frequency: DTE and mesh force at the contact
    positions tend to x_s and P as H grows, at first order or faster (fitted slope of the
    largest error against H below -0.75; measured -1.35 spur, -0.9 helical). At H = 160
    the largest DTE error is 1.9 % (spur) / 1.5 % (helical) of the TE's peak-to-peak and
    the largest force error 1.52 % / 0.11 %, at the positions next to a tooth pair
    entering or leaving (the truncated series of a jump, whose overshoot beside a resolved
    jump does not shrink with H); the median errors are below 0.05 %. A position on a jump
    (the spur pair's entry) is left out: there the series tends to the mean of the two
    sides. The inertia at this speed adds < 3 % of the 160th harmonic (its frequency is
    0.16 f_1)."""
    name, box, pair, cycle, friction, _ = case
    ex = excitation_from_contact(cycle, pair, box.operation, friction)
    f = analyse_modes(_model(box, pair, ex)).frequencies
    f_mesh = 1e-3 * f[f > 1e-6].min()
    slow = dataclasses.replace(box.operation, speed=2 * math.pi * f_mesh / pair.pinion.teeth)
    system = _model(box, pair, ex, operation=slow).assembly().assemble()
    tau = np.arange(POSITIONS) / POSITIONS
    off = ~np.isin(tau, [j.phase for j in tooth_pair_jumps(pair)])
    x, P, tau = cycle.transmission_error[off], cycle.load, tau[off]
    errors = []
    for H in (40, 80, 160):
        r = harmonic_balance(system, H).response
        dte = np.interp(tau, r.time / r.period, r.dte[0])
        force = np.interp(tau, r.time / r.period, r.mesh_force[0])
        errors.append((np.abs(dte - x) / np.ptp(x), np.abs(force / P - 1)))
    slope = np.polyfit(np.log([40, 80, 160]), np.log([e[0].max() for e in errors]), 1)[0]
    assert slope < -0.75
    dte_err, force_err = errors[-1]
    assert dte_err.max() < 0.04 and np.median(dte_err) < 5e-4
    assert force_err.max() < 0.02 and np.median(force_err) < 5e-4


def test_friction_coefficients_of_single_contact_positions_by_hand():
    """Spur pair, mu 0.05: where one tooth pair carries the load at roll coordinate s,
    K_f / k = lam mu, KT_f1 / k = lam mu s, KT_f2 / k = -lam mu (T1T2 - s) (dynamics signs,
    lam = +1 before the pitch point); the EHL coefficient there equals the stiffness stage's
    (which shares the load evenly over the contact length: the whole load on one pair).
    Contact on the nominal path (with tip contact no position of this unmodified pair has
    one pair loaded at 340 N m)."""
    box, pair, cycle, friction, _ = _case("spur", mu=0.05, tip_contact=False)
    ex = excitation_from_contact(cycle, pair, box.operation, friction)
    loaded = cycle.point_load > 0
    count = np.bincount(cycle.point_position[loaded], minlength=POSITIONS)
    single = np.flatnonzero(count == 1)
    # single contact lasts 2 - eps_alpha of the cycle (eps_alpha 1.77)
    assert abs(single.size - (2 - pair.transverse_contact_ratio) * POSITIONS) <= 1
    sel = loaded & np.isin(cycle.point_position, single)
    pos, s = cycle.point_position[sel], cycle.point_s[sel]
    lam = np.where(s < pair.s_pitch, 1.0, -1.0)
    at = pos * (EXCITATION_SAMPLES // POSITIONS)  # the excitation's samples at the positions
    k = ex.stiffness.values[at]
    np.testing.assert_allclose(ex.friction_stiffness.values[at], lam * 0.05 * k, rtol=1e-12)
    np.testing.assert_allclose(ex.friction_torque_pinion.values[at], lam * 0.05 * k * s,
                               rtol=1e-12)
    np.testing.assert_allclose(ex.friction_torque_gear.values[at],
                               -lam * 0.05 * k * (pair.t1t2 - s), rtol=1e-12)
    box, pair, cycle, ehl, _ = _case("spur", kind="ehl", tip_contact=False)
    mu = point_friction_coefficients(cycle, pair, box.operation, ehl)
    sel = (cycle.point_load > 0) & np.isin(cycle.point_position, single)
    s = cycle.point_s[sel]
    ref = friction_coefficients(pair, s[:, None, None], np.ones((s.size, 1, 1), bool), ehl,
                                box.operation, pair.face_width)[:, 0, 0]
    np.testing.assert_allclose(mu[sel], ref, rtol=1e-12)
    assert 0.01 < mu[sel].max() < 0.1


def test_friction_moments_enter_the_static_mesh_force():
    """Helical pair, mu 0.05, zero speed: the pinion's y bearing carries the loaded points'
    friction force sum lam mu F_i (points on the path of contact: a tip corner has none)
    scaled by F/P, and the mesh force is the torque balance
    of the free rotation with the friction torques a_k F (a_k = KT_fk / k), projected with
    the rotors' inertias: F = P D / (D - a_1 I_g / r_g + a_2 I_p / r_p),
    D = r_p I_g / r_g + r_g I_p / r_p. Its difference from P (0.6-1.5 %) is the friction
    moment the contact analysis' P = T / r_b leaves out."""
    box, pair, cycle, friction, _ = _case("helical", mu=0.05)
    ex = excitation_from_contact(cycle, pair, box.operation, friction)
    r = quasi_static_response(_model(box, pair, ex, friction=True).assembly().assemble())
    P, k = cycle.load, ex.stiffness.values
    lam = np.where(cycle.point_s < pair.s_pitch, 1.0, -1.0)
    on_path = cycle.point_corner == 0
    points = np.bincount(cycle.point_position, lam * 0.05 * cycle.point_load * on_path,
                         minlength=POSITIONS)
    kb = PairDynamicsOptions().bearing_stiffness
    np.testing.assert_allclose(kb * r.coordinate("pinion.y"), points * r.mesh_force[0] / P,
                               rtol=1e-9)
    a1, a2 = ex.friction_torque_pinion.values / k, ex.friction_torque_gear.values / k
    rp, rg = pair.pinion.base_radius, pair.gear.base_radius
    ip, ig = box.bodies["pinion"].inertia_, box.bodies["gear"].inertia_
    d = rp * ig / rg + rg * ip / rp
    np.testing.assert_allclose(r.mesh_force[0], P * d / (d - a1 * ig / rg + a2 * ip / rp),
                               rtol=1e-10)
    assert 0.005 < np.abs(r.mesh_force[0] / P - 1).max() < 0.02


def test_pair_dte_at_operating_speed_analytical_vs_contact():
    """The assembly-error paper's pair at 2340 rpm, harmonic balance H = 40 (regression,
    rel. 1e-3): analytical k(t) 25.0 um DTE peak-to-peak, loaded contact (tangent k(t),
    static TE, 360 positions, the tip corners touching beyond the path) 8.33 um; an
    independent time integration gives 24.9963 and 8.33545 um, 13.8636 and 13.6973 um
    mean (tests/test_dyn_spur_dte.py). On the nominal path the contact excitation gave
    35.0 um: its stiffness dropped by a quarter for the single-contact part of the cycle,
    which the corners now share (the fluctuation that excites the pair is about a third
    as large)."""
    from pipeline.dynamics.analysis import analyse_response
    from pipeline.run.runner import gearbox_dynamic_model

    base = (CONFIGS + "spur_pair_assembly_errors.toml")
    text = open(base, encoding="utf-8").read() + "[contact]\npositions = 360\n"
    out = {}
    for excitation in ("analytical", "contact"):
        box = gearbox_from_text(text.replace("damping_ratio = 0.07",
                                             f'damping_ratio = 0.07\nexcitation = "{excitation}"'))
        model = gearbox_dynamic_model(box)
        assert (model.transmission_error is not None) == (excitation == "contact")
        out[excitation] = analyse_response(model, box.dynamics.response).summary()["meshes"]
    assert out["analytical"]["mesh"]["dte_peak_to_peak_m"] == pytest.approx(24.996e-6, rel=1e-3)
    assert out["contact"]["mesh"]["dte_peak_to_peak_m"] == pytest.approx(8.3346e-6, rel=1e-3)
    assert out["contact"]["mesh"]["dte_mean_m"] == pytest.approx(13.697e-6, rel=1e-3)
    assert out["analytical"]["mesh"]["dte_mean_m"] == pytest.approx(13.864e-6, rel=1e-3)


def test_bad_inputs_are_one_line_errors(case):
    """A wrong stiffness definition, a cycle that is not one equally spaced mesh cycle of
    the pair (part of a cycle; another pair), too few positions: one-line InputErrors."""
    from pipeline.contact.ltca import loaded_mesh_cycle

    name, box, pair, cycle, friction, _ = case
    with pytest.raises(InputError, match="stiffness = 'chord' is not one of"):
        excitation_from_contact(cycle, pair, box.operation, friction, stiffness="chord")
    source = analytical_compliance(pair, box.operation, ContactOptions(slices=2))
    part = loaded_mesh_cycle(source, cycle.load, positions=pair.mesh_cycle(10)[:6])
    with pytest.raises(InputError, match="not one mesh cycle"):
        excitation_from_contact(part, pair, box.operation)
    other = dataclasses.replace(pair, centre_distance=pair.operating_centre_distance * 1.001)
    with pytest.raises(InputError, match="not one mesh cycle"):
        excitation_from_contact(cycle, other, box.operation)
    few = loaded_mesh_cycle(source, cycle.load, positions=3)
    with pytest.raises(InputError, match="3 positions.*>= 4"):
        excitation_from_contact(few, pair, box.operation)


@pytest.mark.slow
def test_fe2d_source_static_limit_and_stiffer_sector():
    """FE-enriched source (2D, a 7-tooth sector clamped at bore and cuts, 20 points per
    flank; ~5 s): the zero-speed model reproduces its x_s and P (rel. 1e-10), as for the
    analytical source. The clamped sector is stiffer than the analytical slices (mean
    tangent stiffness 4.9e8 vs 3.4e8 N/m; :mod:`pipeline.fem.influence` documents the
    sector's stiff bias), so its static TE is lower. The excitation's samples at the
    contact positions are every (samples / positions)-th (with tip contact the excitation
    keeps the contact positions)."""
    from pipeline.contact import FE2DCompliance, FE2DSettings

    box, pair, cycle, friction, _ = _case("spur")
    source = FE2DCompliance.build(pair, FE2DSettings(teeth=7, points=20))
    fe = analyse_contact(source, box.operation, ContactOptions(positions=POSITIONS))
    ex = excitation_from_contact(fe, pair, box.operation, friction)
    r = quasi_static_response(_model(box, pair, ex).assembly().assemble())
    np.testing.assert_allclose(r.dte[0][:: r.time.size // POSITIONS],
                               fe.transmission_error, rtol=1e-10)
    np.testing.assert_allclose(r.mesh_force[0], fe.load, rtol=1e-10)
    assert fe.mesh_stiffness.mean() > 1.3 * cycle.mesh_stiffness.mean()
    assert fe.transmission_error.mean() < cycle.transmission_error.mean()
