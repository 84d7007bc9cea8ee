"""Herringbone sun-planet loaded contact through the groove (pipeline.contact.herringbone).

The ladder: a rigid groove is two independent helical contacts at half the load (to the
solver's tolerance); with a linear local contact the split has a closed form (halves and
groove as springs); equilibrium at every position; the directions of Xu et al. (2020),
Figs. 5 and 8 with the torque at either end; the FE 12 x 12 condensed to the flank DOFs.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pipeline.config import load_gearbox
from pipeline.contact import analytical_compliance, loaded_mesh_cycle
from pipeline.contact.groove_flank import GrooveFlankCoupling
from pipeline.contact.herringbone import HerringboneOptions, herringbone_mesh_cycle
from pipeline.contact.herringbone_results import herringbone_arrays, herringbone_from_arrays
from pipeline.dynamics.models.planetary_gears import helical_half, mesh_operations
from pipeline.validation import InputError

CONFIG = "workflows/configs/wind_turbine_herringbone_planetary.toml"
L_LR = 0.225  # m, O_L - O_R of the wind-turbine sun (185 mm half + 40 mm groove)
POSITIONS = 8


@pytest.fixture(scope="module")
def case():
    """One helical half of the Xu et al. (2020) sun-planet pair, its source and mesh load."""
    box = load_gearbox(CONFIG)
    ps = box.planetary
    pair = helical_half(ps.sun_planet)
    op = mesh_operations(ps, box.operation, 1)[0]  # whole mesh: both halves
    src = analytical_compliance(pair, op, box.contact, box.stiffness)
    return src, op.torque / pair.pinion.base_radius, ps.n_planets, box.operation.torque


@pytest.fixture(scope="module")
def nominal(case):
    """The same case with contact confined to the nominal path: every point in mesh is
    loaded, so linear local contact makes each half a linear spring (a tip corner closes
    a gap under load and is not one)."""
    src, *rest = case
    return (dataclasses.replace(src, tip_contact=False), *rest)


def torsion(Kj: float) -> GrooveFlankCoupling:
    """The beam groove of Xu et al. (2020), eq. 1: k_t = K_j / l_LR."""
    return GrooveFlankCoupling.torsion(Kj / L_LR)


def run(case, groove, local="weber", **opts):
    src, P, N, _ = case
    return herringbone_mesh_cycle(src, P, groove, N, options=HerringboneOptions(**opts),
                                  local=local, positions=POSITIONS)


def test_rigid_groove_is_two_helical_contacts_at_half_load(case):
    """Both halves carry P/2 and equal the helical-half LTCA at P/2: loads to 1e-9 of the
    largest, approaches to 1e-12 m, mesh stiffness to 1e-9 (the solver's residual bound is
    1e-10 of the approach)."""
    src, P, _, _ = case
    hb = run(case, GrooveFlankCoupling.rigid())
    ref = loaded_mesh_cycle(src, P / 2, positions=POSITIONS)
    for half in (hb.left, hb.right):
        np.testing.assert_allclose(half.point_load, ref.point_load, rtol=0,
                                   atol=1e-9 * ref.point_load.max())
        np.testing.assert_allclose(half.transmission_error, ref.transmission_error, rtol=0,
                                   atol=1e-12)
        np.testing.assert_allclose(half.mesh_stiffness, ref.mesh_stiffness, rtol=1e-9)
    np.testing.assert_allclose(hb.load_left, P / 2, rtol=1e-12)
    assert np.all(hb.groove_twist == 0.0)


def test_stiff_groove_converges_to_rigid(case):
    """The split's departure from 1/2 falls like 1/k_t (first order)."""
    dev = [abs(run(case, torsion(kj)).load_left.mean() / case[1] - 0.5) for kj in (1e9, 1e10)]
    assert dev[0] > 0.0
    assert dev[1] / dev[0] == pytest.approx(0.1, rel=0.02)


@pytest.mark.parametrize("entry", ["right", "left", "both"])
def test_linear_contact_split_is_springs_in_series(nominal, entry):
    """Linear local contact, perfect flanks, contact on the path: every point in mesh is
    loaded, so each half is a linear spring k_h (its own tangent stiffness) and the split is
    exact: right entry P_L / P = c_R / (c_L + c_g + c_R), c = 1/k, c_g = N r_b^2 / k_t
    (+ axial)."""
    src, P, N, _ = nominal
    g = torsion(4.0e7)
    hb = run(nominal, g, local="linear", torque_entry=entry)
    cL = 1 / hb.left.mesh_stiffness
    cR = 1 / hb.right.mesh_stiffness
    cg = N * src.pair.pinion.base_radius**2 / g.torsional_stiffness
    f = {"right": 0.0, "left": 1.0, "both": 0.5}[entry]
    # the groove carries M = (1-f) P_L - f P_R (per r_b) and moves the left flanks back by
    # (1-f) cg M, the right by -f cg M; equal planet approach:
    # cL P_L + (1-f) cg M = cR P_R - f cg M  =>  P_L (cL + (1-f) cg) = P_R (cR + f cg)
    expected = (cR + f * cg) / (cL + cR + cg)
    np.testing.assert_allclose(hb.load_left / P, expected, rtol=1e-9)
    assert np.all(hb.left.residual <= hb.left.tolerance)


def test_equilibrium_every_position(case):
    """Torque, groove twist = torque through the groove / k_t, approaches consistent."""
    src, P, N, T_s = case
    g = torsion(5.2e7)
    rb = src.pair.pinion.base_radius
    t = math.tan(src.pair.pinion.base_helix_angle)
    hb = run(case, g)
    np.testing.assert_allclose((hb.load_left + hb.load_right) * rb * N, T_s, rtol=1e-12)
    np.testing.assert_allclose(hb.groove_torque, N * rb * hb.load_left, rtol=1e-12)
    np.testing.assert_allclose(hb.groove_twist, hb.groove_torque / g.torsional_stiffness,
                               rtol=1e-12)
    # the planet's approach: left flanks + groove twist, right flanks
    np.testing.assert_allclose(hb.approach, hb.left.transmission_error + rb * hb.groove_twist,
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(hb.approach, hb.right.transmission_error, rtol=0, atol=1e-12)
    assert np.all(hb.sun_axial_position == 0.0)
    # free sun: the axial forces t P_L and t P_R of the halves balance
    free = run(case, g, sun_axial="free")
    np.testing.assert_allclose(free.load_left, free.load_right, rtol=1e-12)
    np.testing.assert_allclose(free.approach, free.left.transmission_error
                               + rb * free.groove_twist + t * free.sun_axial_position,
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(free.approach, free.right.transmission_error
                               - t * free.sun_axial_position, rtol=0, atol=1e-12)
    # to balance, the sun moves so that the left flanks make up the groove twist
    np.testing.assert_allclose(2 * t * free.sun_axial_position, -rb * free.groove_twist,
                               rtol=1e-9)


def test_axial_support_stiffness(case):
    """A finite axial support lets the sun move by N t (P_L - P_R) / k_a from its slide."""
    src, P, N, _ = case
    t = math.tan(src.pair.pinion.base_helix_angle)
    hb = run(case, torsion(5.2e7), axial_slide=20e-6, axial_support_stiffness=1e9)
    np.testing.assert_allclose(hb.sun_axial_position,
                               20e-6 + N * t * (hb.load_left - hb.load_right) / 1e9, rtol=1e-12)


def test_directions_of_fig5_and_fig8(case):
    """Torque leaving at the right (Xu et al.'s O_T): the left half, behind the groove, loses
    load, stiffness and peak unit load as K_j falls - the opposite of Xu et al. (2020), Fig. 5
    and 8; with the torque at the left the paper's direction follows. A slide to the right
    unloads the left half (Fig. 8e, f)."""
    kjs = (5.2e7, 4.6e7, 4.0e7)
    right = [run(case, torsion(k)) for k in kjs]
    left = [run(case, torsion(k), torque_entry="left") for k in kjs]
    for hbs, sign in ((right, -1), (left, +1)):
        share = np.array([h.load_left.mean() for h in hbs])
        kL = np.array([h.left.mesh_stiffness.mean() for h in hbs])
        kR = np.array([h.right.mesh_stiffness.mean() for h in hbs])
        pL = np.array([h.left.max_unit_load.max() for h in hbs])
        assert np.all(sign * np.diff(share) > 0)
        assert np.all(sign * np.diff(kL) > 0) and np.all(-sign * np.diff(kR) > 0)
        assert np.all(sign * np.diff(pL) > 0)
    slid = run(case, torsion(5.2e7), axial_slide=10e-6)
    assert slid.load_left.mean() < right[0].load_left.mean()
    assert slid.right.max_unit_load.max() > right[0].right.max_unit_load.max()


def test_fe_matrix_condensation():
    """A 12 x 12 of a torsion spring, an axial spring and a laterally stiff joint condenses
    to diag(1/k_t, 1/k_a); lateral-tilt terms drop out."""
    kt, ka, kl = 2.66e8, 5.6e10, 2.7e10
    K = np.zeros((12, 12))
    for i, k in ((5, kt), (2, ka), (0, kl), (1, kl), (3, 6e8), (4, 6e8)):
        K[np.ix_([i, i + 6], [i, i + 6])] += k * np.array([[1, -1], [-1, 1]])
    K[np.ix_([0, 4, 6, 10], [0, 4, 6, 10])] += 3e9 * np.array(
        [[0, 1, 0, 1], [1, 0, -1, 0], [0, -1, 0, -1], [1, 0, -1, 0]]) * 0.01
    c = GrooveFlankCoupling.from_matrix(K)
    np.testing.assert_allclose(c.compliance, np.diag([1 / kt, 1 / ka]), rtol=1e-9, atol=1e-22)
    assert c.torsional_stiffness == pytest.approx(kt, rel=1e-9)
    assert GrooveFlankCoupling.rigid().torsional_stiffness == math.inf


def test_arrays_round_trip(case):
    """The cycle as the cache stores it (one set of named arrays, both halves in it) and
    back: bit for bit."""
    hb = run(case, torsion(4.9e7))
    back = herringbone_from_arrays(herringbone_arrays(hb))
    np.testing.assert_array_equal(back.load_left, hb.load_left)
    np.testing.assert_array_equal(back.right.point_unit_load, hb.right.point_unit_load)
    assert back.torque_entry == hb.torque_entry and back.n_planets == hb.n_planets
    assert back.summary() == hb.summary()


@pytest.mark.parametrize("kwargs, match", [
    (dict(torque_entry="middle"), "herringbone.torque_entry"),
    (dict(sun_axial="floating"), "herringbone.sun_axial"),
    (dict(axial_slide=0.2), r"herringbone.axial_slide = 0.2 m is outside"),
    (dict(axial_support_stiffness=-1.0), r"axial_support_stiffness = -1 N/m"),
    (dict(sun_axial="free", axial_slide=1e-3), "an axial slide applies to a held sun"),
])
def test_invalid_options(kwargs, match):
    with pytest.raises(InputError, match=match):
        HerringboneOptions(**kwargs)


def test_invalid_inputs(case):
    src, P, N, _ = case
    with pytest.raises(InputError, match="groove coupling matrix has shape"):
        GrooveFlankCoupling.from_matrix(np.eye(6))
    with pytest.raises(InputError, match="not positive semidefinite"):
        GrooveFlankCoupling(np.diag([1.0, -1.0]))
    with pytest.raises(InputError, match="groove torsional stiffness"):
        GrooveFlankCoupling.torsion(0.0)
    with pytest.raises(InputError, match="contact.load"):
        herringbone_mesh_cycle(src, -1.0, GrooveFlankCoupling.rigid(), N)
    with pytest.raises(InputError, match="planetary.planets"):
        herringbone_mesh_cycle(src, P, GrooveFlankCoupling.rigid(), 0)


def test_gearbox_table():
    """``[herringbone]`` in the file's units; refused where it does not apply."""
    from pipeline.config import gearbox_from_text

    text = open(CONFIG, encoding="utf-8").read()
    box = load_gearbox(CONFIG)
    assert box.herringbone == HerringboneOptions(axial_support_stiffness=1e9)
    box = gearbox_from_text(text.replace("axial_slide_mm = 0.0", "axial_slide_mm = 0.5"))
    assert box.herringbone.axial_slide == pytest.approx(0.5e-3)
    for old, new, match in (
        ("axial_slide_mm = 0.0", "axial_slide_mm = 80.0",
         r"herringbone.axial_slide_mm = 80 mm is outside the allowed range \[-50, 50\] mm"),
        ("axial_support_stiffness_N_per_m = 1.0e9", "axial_support_stiffness_N_per_m = -5.0",
         r"axial_support_stiffness_N_per_m = -5 N/m is outside the allowed range \(0, inf\]"),
        ('torque_entry = "right"', 'torque_entry = "middle"', "not one of 'right', 'left'"),
        ('torque_entry = "right"', 'torque_entri = "left"', "did you mean 'torque_entry'"),
        ("[groove] ", "[groovx] ", "table"),
    ):
        with pytest.raises(InputError, match=match):
            gearbox_from_text(text.replace(old, new, 1))
    head, tail = text.split("\n[groove]", 1)
    without_groove = head + "\n[herringbone]" + tail.split("\n[herringbone]", 1)[1]
    with pytest.raises(InputError, match=r"\[herringbone\] applies to a planetary set"):
        gearbox_from_text(without_groove)


def test_series_stiffness_is_the_half_with_the_groove(nominal):
    """Linear contact on the path, torque right: the left half in series with N r_b^2 / k_t
    carries the left load at the planet approach: P_L = k_series,L x, P_R = k_series,R x
    (right has nothing in series)."""
    src, P, N, _ = nominal
    g = torsion(4.0e7)
    hb = run(nominal, g, local="linear")
    np.testing.assert_allclose(hb.series_mesh_stiffness("left") * hb.approach, hb.load_left,
                               rtol=1e-9)
    np.testing.assert_allclose(hb.series_mesh_stiffness("right"), hb.right.mesh_stiffness,
                               rtol=1e-15)


@pytest.mark.parametrize("axial", ["held", "free"])
def test_whole_mesh_stiffness_linear(nominal, axial):
    """Linear local contact, perfect flanks, contact on the path: the mesh is linear and
    homogeneous in the load, so its tangent stiffness is P over the planet's approach, held
    or free."""
    hb = run(nominal, torsion(4.6e7), local="linear", sun_axial=axial)
    np.testing.assert_allclose(hb.mesh_stiffness, hb.load / hb.approach, rtol=1e-9)


@pytest.mark.parametrize("sun_axial", ["held", "free"])
def test_load_beyond_the_tip_zone_is_refused(case, sun_axial):
    """A load whose elastic approach passes the 200 um tip zone of the candidate points is
    refused naming the position, as in a single mesh: the corners beyond the zone would
    be missing from the solution. The case's own load is far inside it."""
    src, P, N, _ = case
    one = herringbone_mesh_cycle(src, P, GrooveFlankCoupling.rigid(), N, positions=1,
                                 options=HerringboneOptions(sun_axial=sun_axial))
    approach = float(one.approach[0])
    assert 0.0 < approach < 100e-6
    with pytest.raises(InputError, match=r"mesh position 0 .*elastic approach .* um reaches "
                                         r"the 200 um tip zone"):
        herringbone_mesh_cycle(src, 300e-6 / approach * P, GrooveFlankCoupling.rigid(), N,
                               positions=1, options=HerringboneOptions(sun_axial=sun_axial))
