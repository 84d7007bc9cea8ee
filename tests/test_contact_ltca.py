"""Loaded tooth contact over a mesh cycle with the analytical slice compliance
(pipeline.contact.source / separations / ltca)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.separations import FlankModifications, initial_separations
from pipeline.contact.source import (
    ComplianceSource,
    ContactPoints,
    SliceCompliance,
    candidate_zone,
)
from pipeline.stiffness.mesh import FrictionModel, PairModel, stiffness_at
from pipeline.stiffness.tooth import classical_tooth_model, hertz_compliance
from pipeline.validation import InputError


def classical(pair) -> PairModel:
    """Tooth models of Yang et al. (2026), eqs. 11-13 (involute clamped at the base circle)."""
    return PairModel(pair, classical_tooth_model(pair.pinion), classical_tooth_model(pair.gear),
                     hertz_compliance(pair.pinion, pair.gear))


@pytest.fixture(scope="module")
def spur_model(spur_pair_z50):
    return classical(spur_pair_z50)


@pytest.fixture(scope="module")
def helical_model(helical_traction_pair):
    return classical(helical_traction_pair)


def spur_load(pair) -> float:
    return 340.0 / pair.pinion.base_radius  # the assembly-error paper: 340 N m on the pinion


@pytest.mark.parametrize("mu", [0.0, 0.1])
@pytest.mark.parametrize("case", ["spur", "helical"])
def test_ltca_reproduces_the_slice_method(case, mu, spur_model, helical_model):
    """Independent slices, constant Hertz compliance, eps = 0, contact on the nominal path
    only (the slice method's assumption, ``tip_contact=False``): every slice in the path
    is loaded, so the LTCA stiffness k = 1^T G^-1 1 = sum_i 1/G_ii must equal
    pipeline.stiffness.mesh.stiffness_at exactly (1e-12), tangent and secant, with and
    without friction (mu = 0.1, Yang et al. 2026, eqs. 19-23 sign convention)."""
    model = spur_model if case == "spur" else helical_model
    src = SliceCompliance(model, slices=30, friction=FrictionModel(mu=mu), tip_contact=False)
    assert isinstance(src, ComplianceSource)
    P = spur_load(model.pair) if case == "spur" else 6031.0 / model.pair.pinion.base_radius
    cyc = loaded_mesh_cycle(src, P, local="linear", positions=24)
    ref = stiffness_at(model, cyc.s0, slices=30, friction=FrictionModel(mu=mu)).total
    assert np.abs(cyc.mesh_stiffness / ref - 1).max() < 1e-12
    assert np.abs(cyc.mesh_stiffness_secant / ref - 1).max() < 1e-12
    assert np.abs(cyc.pair_loads.sum(axis=1) / P - 1).max() < 1e-13  # load balance
    assert np.all(cyc.residual <= cyc.tolerance)


def test_weber_local_contact_lowers_stiffness_about_ten_percent(helical_model):
    """Yang et al. (2026), section 2.3: the nonlinear local deformation (eq. 24) lowers the mesh
    stiffness of its traction pair by 'approximately 10%' at rated load (20 233 N m on
    the gear) without changing its shape. Checked on the nominal path (as the slice
    method): mean ratio in [0.85, 0.95] and the ratio varies by < 3 % over the cycle."""
    pair = helical_model.pair
    src = SliceCompliance(helical_model, slices=30, tip_contact=False)
    P = 20233.0 / pair.gear.base_radius
    weber = loaded_mesh_cycle(src, P, local="weber", positions=24)
    ref = stiffness_at(helical_model, weber.s0, slices=30).total
    ratio = weber.mesh_stiffness / ref
    assert 0.85 <= ratio.mean() <= 0.95
    assert np.ptp(ratio) < 0.03
    assert np.abs(weber.pair_loads.sum(axis=1) / P - 1).max() < 1e-13


def test_tip_relief_lowers_entry_stiffness_and_tip_load(spur_model):
    """The spur pair of the assembly-error paper, 340 N m. A linear tip relief of 30 um over 30 %
    of the path on both gears exceeds the ~15 um deflection, so at contact entry (first positions
    of the
    cycle, gear tip on the pinion root) the entering pair carries less load and the
    tangent and secant stiffness drop (first two of 40 positions); the load at the pinion
    tip (last 5 % of the path) falls below the unmodified case; the total load stays P."""
    pair = spur_model.pair
    src = SliceCompliance(spur_model, tip_contact=False)
    P = spur_load(pair)
    L = 0.3 * pair.path_length
    mods = FlankModifications(30e-6, L, 30e-6, L)
    plain = loaded_mesh_cycle(src, P, local="weber", positions=40)
    relief = loaded_mesh_cycle(src, P, mods, local="weber", positions=40)
    entry = slice(0, 2)  # the first 5 % of the cycle
    assert np.all(relief.mesh_stiffness[entry] < 0.9 * plain.mesh_stiffness[entry])
    assert np.all(relief.mesh_stiffness_secant[entry] < plain.mesh_stiffness_secant[entry])
    tip = plain.point_s > pair.s_end - 0.05 * pair.path_length
    assert relief.point_load[tip].max() < 0.5 * plain.point_load[tip].max()
    assert np.abs(relief.pair_loads.sum(axis=1) / P - 1).max() < 1e-13
    # in single-tooth contact the relief (far from the contact) changes nothing
    single = (plain.pair_loads > 0).sum(axis=1) == 1
    assert single.any()
    assert relief.mesh_stiffness[single] == pytest.approx(plain.mesh_stiffness[single], rel=1e-9)


def test_separations_are_the_stated_formulas(helical_traction_pair):
    """eps at chosen points against the closed forms of pipeline.contact.separations:
    parabolic pinion/gear tip relief, crowning C_b at both faces and 0 at mid face,
    slope deviation, pitch error of pair k = 1, +inf off the path."""
    pair = helical_traction_pair
    b, L = pair.face_width, 2e-3
    s = np.array([pair.s_end, pair.s_end - L / 2, pair.s_start, pair.s_pitch, pair.s_pitch,
                  pair.s_pitch, pair.s_end + 1e-4])
    z = np.array([b / 2, b / 2, b / 2, 0.0, b, b / 2, b / 2])
    pts = ContactPoints(s, z, [0, 0, 0, 0, 0, 1, 0], np.full(7, 1e-3))
    mods = FlankModifications(20e-6, L, 10e-6, L, "parabolic", crowning=8e-6,
                              slope_deviation=4e-6, pitch_errors=(0.0, 3e-6))
    eps = initial_separations(pair, pts, mods)
    expected = [20e-6, 20e-6 / 4, 10e-6, 8e-6 - 2e-6, 8e-6 + 2e-6, 3e-6, np.inf]
    assert eps == pytest.approx(expected, rel=1e-12, abs=1e-18)
    with pytest.raises(InputError, match="relief_length_pinion"):
        FlankModifications(tip_relief_pinion=1e-5)
    with pytest.raises(InputError, match="tip_relief_gear"):
        FlankModifications(tip_relief_gear=5e-3, relief_length_gear=1e-3)


def test_slice_coupling_structure(helical_model):
    """kappa = 0.2: G = D^1/2 (I - kappa L) D^1/2 is symmetric positive definite, its
    neighbour entries are kappa sqrt(d_i d_j) on the same tooth only, and with eps = 0
    the mesh stiffness stays within 1e-4 of independent slices (rows of I - kappa L sum
    to one, so a uniformly loaded tooth deflects as in the slice method)."""
    pair = helical_model.pair
    P = 6031.0 / pair.pinion.base_radius
    s0 = pair.mesh_cycle(8)
    free = SliceCompliance(helical_model, slices=30, tip_contact=False)
    coupled = SliceCompliance(helical_model, slices=30, coupling=0.2, tip_contact=False)
    pos = float(s0[3])
    G, d, pts = coupled.matrix(pos), free.diagonal(pos), coupled.points(pos)
    assert np.array_equal(G, G.T)
    assert np.linalg.eigvalsh(G).min() > 0
    same = pts.pair[1:] == pts.pair[:-1]
    off = np.diag(G, 1)
    assert off[same] == pytest.approx(0.2 * np.sqrt(d[1:] * d[:-1])[same], rel=1e-14)
    assert np.all(off[~same] == 0.0)
    a = loaded_mesh_cycle(free, P, local="linear", positions=s0)
    c = loaded_mesh_cycle(coupled, P, local="linear", positions=s0)
    assert np.abs(c.mesh_stiffness / a.mesh_stiffness - 1).max() < 1e-4


def test_points_follow_the_contact_lines(helical_traction_pair, helical_model):
    """Candidate points lie on s = s0 + k p_bt + z tan(beta_b) inside the candidate zone
    (the path and its tip zones), and the widths of those on the path add up to the
    contact-line lengths times cos(beta_b)."""
    pair = helical_traction_pair
    src = SliceCompliance(helical_model, slices=40)
    s0 = float(pair.mesh_cycle(7)[4])
    pts = src.points(s0)
    tb = math.tan(pair.pinion.base_helix_angle)
    assert pts.s == pytest.approx(s0 + pts.pair * pair.base_pitch + pts.z * tb, rel=1e-14)
    lo, hi = candidate_zone(pair)
    assert np.all((pts.s >= lo) & (pts.s <= hi))
    on = (pts.s >= pair.s_start) & (pts.s <= pair.s_end)
    lengths = pair.contact_line_lengths(np.array([s0]))[0] * math.cos(pair.pinion.base_helix_angle)
    widths = np.array([pts.width[on & (pts.pair == k)].sum() for k in pair.pair_indices()])
    assert np.abs(widths - lengths).max() <= pair.face_width / 40 * 2
