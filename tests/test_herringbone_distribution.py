"""Load distribution of each helical half of a herringbone mesh
(pipeline.contact.herringbone_distribution), on the sun-planet pair of Xu et al. (2020).

Exact checks: equilibrium (the halves' shares sum to 1 and each half's line load integrates
over its face to that half's load, to the solver's tolerance); mirror symmetry (with no
groove twist both halves are the same helical contact at P / 2, so every number of the two
halves is equal and equal to the single helical half's at half the torque).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pipeline.cache.folder import Cache
from pipeline.config import load_gearbox
from pipeline.contact import analytical_compliance, loaded_mesh_cycle
from pipeline.contact.distribution import load_distribution
from pipeline.contact.groove_flank import GrooveFlankCoupling
from pipeline.contact.herringbone import HerringboneOptions, herringbone_mesh_cycle
from pipeline.contact.herringbone_distribution import herringbone_distribution
from pipeline.dynamics.models.planetary_gears import helical_half, mesh_operations
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError

CONFIG = "workflows/configs/wind_turbine_herringbone_planetary.toml"
POSITIONS = 8
KT = 5.98e7 / 0.225  # N m/rad: the FE groove's K_j over O_L - O_R (Xu et al. 2020, eq. 1)


@pytest.fixture(scope="module")
def case():
    """Helical half of the sun-planet pair, its source and the whole mesh's operating point."""
    box = load_gearbox(CONFIG)
    ps = box.planetary
    pair = helical_half(ps.sun_planet)
    op = mesh_operations(ps, box.operation, 1)[0]  # both halves: T_s / N on the sun
    src = analytical_compliance(pair, op, box.contact, box.stiffness)
    return src, pair, op, ps.n_planets


def solve(case, groove, **opts):
    src, pair, op, n = case
    cycle = herringbone_mesh_cycle(src, op.torque / pair.pinion.base_radius, groove, n,
                                   options=HerringboneOptions(**opts), positions=POSITIONS)
    return cycle, herringbone_distribution(cycle, pair, op)


def test_shares_sum_to_one_and_line_loads_integrate_to_the_half_loads(case):
    """Torque leaving at the right half through a torsion groove: P_L(t) + P_R(t) = P to
    1e-12 (the solver enforces the total load), sum_z w_h(z, t) dz = P_h(t) to 1e-12 of P
    (dz the slice widths); the right half carries more and governs."""
    _, pair, op, n = case
    cycle, hd = solve(case, GrooveFlankCoupling.torsion(KT))
    P = op.torque / pair.pinion.base_radius
    np.testing.assert_allclose(hd.left.share + hd.right.share, 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(hd.left.load + hd.right.load, P, rtol=1e-12)
    for side in ("left", "right"):
        h = hd.half(side)
        widths = np.unique(np.round(h.cycle.point_width, 15))
        assert widths.size == 1  # equal slices across the face
        d = h.distribution
        assert d.z.size * widths[0] == pytest.approx(pair.face_width, rel=1e-12)
        np.testing.assert_allclose(d.line_load.sum(axis=1) * widths[0], h.load, rtol=0,
                                   atol=1e-12 * P)
        # the tooth pairs share the half's own load P_h(t), which moves over the cycle
        assert np.ptp(h.load) > 0.05 * h.load.mean()
        np.testing.assert_allclose(d.load_share.sum(axis=1), 1.0, rtol=0, atol=1e-12)
        # the half's torque is its mean load on the sun's base radius; N of them on the sun
        assert h.operation.torque == pytest.approx(h.load.mean() * pair.pinion.base_radius,
                                                   rel=1e-12)
        assert h.sun_torque == pytest.approx(n * h.operation.torque, rel=1e-15)
        assert h.operation.speed == op.speed
    assert hd.left.operation.torque + hd.right.operation.torque == pytest.approx(op.torque,
                                                                                rel=1e-12)
    # torque leaving at the right half: the groove twists and unloads the left half
    assert hd.right.share.mean() > 0.5 > hd.left.share.mean()
    assert hd.governing == "right" and hd.line_load_ratio > 1.0
    assert hd.right.max_line_load == max(h.max_line_load for h in (hd.left, hd.right))
    s = hd.summary()
    assert s["governing"] == "right"
    assert s["left"]["load_share_mean"] + s["right"]["load_share_mean"] == pytest.approx(
        1.0, abs=1e-12)
    assert s["right"]["max_line_load_N_per_m"] == hd.right.max_line_load


@pytest.mark.parametrize("groove,entry", [(GrooveFlankCoupling.rigid(), "right"),
                                          (GrooveFlankCoupling.torsion(KT), "both")])
def test_mirror_symmetric_set_is_two_equal_halves_at_half_torque(case, groove, entry):
    """No groove twist (a rigid groove; or half the torque leaving at each half, eqs. 20d /
    21d of Xu et al. 2020, so the groove carries none): both halves give the same numbers
    to round-off, and the helical-half LTCA at T / 2 gives them too (the solver's tolerance
    1e-10 of the approach bounds the difference)."""
    src, pair, op, _ = case
    single = loaded_mesh_cycle(src, 0.5 * op.torque / pair.pinion.base_radius,
                               positions=POSITIONS)
    ref = load_distribution(single, pair, OperatingPoint(0.5 * op.torque, op.speed))
    cycle = herringbone_mesh_cycle(src, op.torque / pair.pinion.base_radius, groove,
                                   case[3], options=HerringboneOptions(torque_entry=entry),
                                   positions=POSITIONS)
    hd = herringbone_distribution(cycle, pair, op, equal_split=single)
    np.testing.assert_allclose(cycle.groove_twist, 0.0, atol=1e-15)
    L, R = hd.left.distribution, hd.right.distribution
    for d, rtol in ((R, 1e-12), (ref, 1e-10)):
        np.testing.assert_allclose(d.line_load, L.line_load, rtol=0,
                                   atol=rtol * L.line_load.max())
        for name in ("k_hbeta", "pair_load_ratio", "mean_line_load"):
            assert getattr(d, name) == pytest.approx(getattr(L, name), rel=rtol), name
        for name in ("line_load_max", "hertz_max"):
            assert getattr(d, name).value == pytest.approx(getattr(L, name).value,
                                                           rel=rtol), name
    np.testing.assert_allclose(hd.left.share, 0.5, rtol=1e-12)
    assert hd.left.operation.torque == pytest.approx(0.5 * op.torque, rel=1e-12)
    assert hd.equal_split.operation.torque == pytest.approx(0.5 * op.torque, rel=1e-12)
    np.testing.assert_allclose(hd.equal_split.share, 0.5, rtol=1e-12)
    assert hd.equal_split.distribution.k_hbeta == ref.k_hbeta
    assert hd.line_load_ratio == pytest.approx(1.0, abs=1e-12)
    for side in ("left", "right"):
        assert hd.over_equal_split(side) == pytest.approx(1.0, abs=1e-10)


def test_operating_point_must_be_the_cycles(case):
    _, pair, op, _ = case
    cycle, _ = solve(case, GrooveFlankCoupling.rigid())
    with pytest.raises(InputError, match="solved at P"):
        herringbone_distribution(cycle, pair, OperatingPoint(0.5 * op.torque, op.speed))
    with pytest.raises(InputError, match="not half the mesh load"):
        herringbone_distribution(cycle, pair, op, equal_split=dataclasses.replace(
            cycle.left, load=2.0 * cycle.left.load))


def test_mirror_symmetric_halves_have_equal_root_stress(case, tmp_path):
    """FE 2D root stress under each half's line loads (linear in them): with no groove
    twist both halves equal the helical half at T / 2, sun and planet, to 1e-10."""
    from pipeline.contact.root_stress import analyse_root_stress

    src, pair, op, n = case
    single = loaded_mesh_cycle(src, 0.5 * op.torque / pair.pinion.base_radius,
                               positions=POSITIONS)
    cycle, _ = solve(case, GrooveFlankCoupling.rigid())
    hd = herringbone_distribution(cycle, pair, op, equal_split=single)
    roots = {side: analyse_root_stress(hd.half(side).cycle, pair, hd.half(side).operation,
                                       cache=Cache(tmp_path))
             for side in ("left", "right", "equal split")}
    for gear in ("pinion", "gear"):
        ref = getattr(roots["equal split"], gear)
        for side in ("left", "right"):
            g = getattr(roots[side], gear)
            assert g.max_stress == pytest.approx(ref.max_stress, rel=1e-10), (side, gear)
            assert g.iso.sigma_f0 == pytest.approx(ref.iso.sigma_f0, rel=1e-10)
        assert ref.max_stress > 0.0
