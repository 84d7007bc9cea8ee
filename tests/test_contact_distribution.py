"""Load distribution quantities (pipeline.contact.distribution) against closed forms.

* K_Hbeta is exactly 1 under a load spread evenly over the face;
* a spur pair of uniform mesh stiffness with a helix slope deviation carries a linear line
  load: K_Hbeta = 1 + f_Hb c_bar (1/2 - 1/(2 N)) / (P / b) on N slices (ISO 6336-1's
  1 + f_Hb c_gamma / (2 F_m / b) as N -> inf), and sqrt(2 f_Hb c / (P / b)) once part of the
  face lifts off;
* the Hertz pressure at the pitch point in single contact equals ISO 6336-2's
  Z_H Z_E sqrt(F_t / (d_1 b) (u + 1) / u) (the closed-form line contact written with the
  gear data);
* mesh-order amplitudes of a sum of sinusoids; failure paths.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur
from helpers import UniformSlices

from pipeline.contact import analyse_contact, analytical_compliance
from pipeline.contact.distribution import load_distribution, mesh_order_amplitudes
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.options import ContactOptions
from pipeline.contact.separations import FlankModifications
from pipeline.geometry import GearPair
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError, PhysicsWarning


@pytest.fixture(scope="module")
def pair() -> GearPair:
    return GearPair(spur(30, "pinion"), spur(45, "gear"))


def _pairs_in_contact(pair: GearPair, s0: np.ndarray) -> np.ndarray:
    _, inside = pair.pair_positions(s0)
    return inside.sum(axis=1)


def _cycle(pair, slices, c0, torque, slope, positions=24):
    op = OperatingPoint(torque=torque, speed=100.0)
    load = torque / pair.pinion.base_radius
    cyc = loaded_mesh_cycle(UniformSlices(pair, slices, c0), load,
                            FlankModifications(slope_deviation=slope), "none", positions)
    return cyc, op


def test_uniform_load_gives_exactly_one(pair):
    cyc, op = _cycle(pair, 20, 1.4e10, 300.0, 0.0)
    dist = load_distribution(cyc, pair, op)
    assert dist.k_hbeta == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(dist.k_hbeta_position, 1.0, atol=1e-12)
    np.testing.assert_allclose(dist.envelope, cyc.load / pair.face_width, rtol=1e-12)
    assert dist.slices_across_face == 20


def test_linear_load_from_slope_deviation_closed_form(pair):
    """Whole face loaded at every position: w(z) = P/b - n c0 f (z/b - 1/2)."""
    c0, f, slices, torque = 1.4e10, 10e-6, 40, 300.0
    cyc, op = _cycle(pair, slices, c0, torque, f)
    dist = load_distribution(cyc, pair, op)
    n = _pairs_in_contact(pair, cyc.s0)  # tooth pairs in contact, from the geometry alone
    w_m = cyc.load / pair.face_width
    edge = 0.5 - 0.5 / slices  # distance of the outer slice centre from mid face over b
    assert np.all(n * c0 * f * edge < w_m)  # the whole face carries load: linear regime
    np.testing.assert_allclose(dist.k_hbeta_position, 1.0 + n * c0 * f * edge / w_m, rtol=1e-9)
    expected = 1.0 + n.mean() * c0 * f * edge / w_m
    assert dist.k_hbeta == pytest.approx(expected, rel=1e-9)
    assert dist.k_hbeta > 1.2  # a real effect, not a value near 1
    # the continuous ISO 6336-1 form is the limit: within (1/N) of it
    iso = 1.0 + n.mean() * c0 * f / (2 * w_m)
    assert dist.k_hbeta == pytest.approx(iso, rel=1.0 / slices)
    # the heavier end is z = 0 (the gap opens towards z = b)
    assert dist.envelope[0] == pytest.approx(dist.envelope.max())


def test_partial_face_contact_closed_form(pair):
    """Single contact with part of the face unloaded: K = sqrt(2 f c / (P / b))."""
    c0, f, slices, torque = 1.4e10, 60e-6, 400, 200.0
    cyc, op = _cycle(pair, slices, c0, torque, f)
    dist = load_distribution(cyc, pair, op)
    n = _pairs_in_contact(pair, cyc.s0)
    w_m = cyc.load / pair.face_width
    k_iso = np.sqrt(2.0 * f * n * c0 / w_m)
    assert np.all(k_iso > 2.0)  # ISO's second regime at every position
    np.testing.assert_allclose(dist.k_hbeta_position, k_iso, rtol=2.0 / slices)


def test_transverse_factor_single_and_equal_sharing(pair):
    cyc, op = _cycle(pair, 4, 1.4e10, 300.0, 0.0)
    dist = load_distribution(cyc, pair, op)
    # uniform stiffness: the pairs share in proportion to their contact lengths
    np.testing.assert_allclose(dist.pair_load_ratio_position, 1.0, rtol=1e-9)
    np.testing.assert_allclose(dist.load_share.sum(axis=1), 1.0, rtol=1e-12)
    # a pitch error on pair 1 shifts the load to the other pair in double contact
    cyc2 = loaded_mesh_cycle(UniformSlices(pair, 4, 1.4e10), cyc.load,
                             FlankModifications(pitch_errors=(0.0, 3e-6)), "none", 24)
    d2 = load_distribution(cyc2, pair, op)
    n = _pairs_in_contact(pair, cyc2.s0)
    # in double contact the pair with the error carries x = P / (2 c b) - 3 um / 2 less
    c_b = 1.4e10 * pair.face_width
    share = 0.5 + 0.5 * 3e-6 * c_b / cyc.load
    double = n == 2
    assert double.any()
    np.testing.assert_allclose(d2.pair_load_ratio_position[double], 2 * share, rtol=1e-9)
    np.testing.assert_allclose(d2.pair_load_ratio_position[~double], 1.0, rtol=1e-12)


def test_hertz_pressure_at_pitch_point_matches_iso_6336_2(pair):
    """Single contact at the pitch point: p_H = Z_H Z_E sqrt(F_t / (d_1 b) (u + 1) / u)
    (ISO's nominal contact: on the path only, so no tip corner shares the load)."""
    torque = 300.0
    op = OperatingPoint(torque=torque, speed=100.0)
    src = analytical_compliance(pair, op, ContactOptions(tip_contact=False))
    k = int((pair.s_pitch - pair.s_start) // pair.base_pitch)  # this pair on the pitch point
    s0 = pair.s_pitch - k * pair.base_pitch
    assert pair.s_start <= s0 < pair.s_start + pair.base_pitch
    cyc = loaded_mesh_cycle(src, torque / pair.pinion.base_radius, None, "weber", [s0])
    assert _pairs_in_contact(pair, cyc.s0)[0] == 1
    dist = load_distribution(cyc, pair, op)
    p1, g = pair.pinion, pair.gear
    e_star = 1.0 / ((1 - p1.material.poisson_ratio**2) / p1.material.youngs_modulus
                    + (1 - g.material.poisson_ratio**2) / g.material.youngs_modulus)
    z_e = math.sqrt(e_star / math.pi)
    a_wt = pair.operating_pressure_angle
    a_t = p1.transverse_pressure_angle
    z_h = math.sqrt(2.0 * math.cos(a_wt) / (math.cos(a_t) ** 2 * math.sin(a_wt)))
    f_t = torque / p1.reference_radius
    u = pair.gear_ratio
    p_iso = z_h * z_e * math.sqrt(f_t / (2 * p1.reference_radius * pair.face_width)
                                  * (u + 1) / u)
    assert dist.hertz_max.value == pytest.approx(p_iso, rel=1e-9)
    assert dist.hertz_max.s == pytest.approx(pair.s_pitch, rel=1e-12)
    assert 2 * dist.hertz_max.pinion_radius == pytest.approx(
        2 * pair.operating_pitch_radii[0], rel=1e-12)


def test_spur_pair_with_crowning_is_sliced(pair):
    """Lead crowning C_b on a spur pair: the analytical compliance of ``ContactOptions`` cuts
    the face into ``slices`` (one slice would hide it), and with linear local contact the line
    load is P/b + k (g_mean - g(z)) / b, g(z) = C_b (2 z / b - 1)^2: on N (even) slices
    K_Hbeta(s0) = 1 + k(s0) C_b ((1 - 1/N^2) / 3 - 1/N^2) / P, k the mesh stiffness of the
    stiffness stage at s0 (contact on the nominal path, as that stage). Without modifications
    the same options give one slice."""
    from pipeline.stiffness.mesh import stiffness_at

    op = OperatingPoint(torque=300.0, speed=100.0)
    c_b, n = 8e-6, 20
    opts = ContactOptions(positions=12, slices=n, local_contact="linear", tip_contact=False,
                          modifications=FlankModifications(crowning=c_b))
    src = analytical_compliance(pair, op, opts)
    assert src.slices == n and opts.face_slices(pair) == n
    assert ContactOptions(slices=n).face_slices(pair) == 1
    with pytest.warns(PhysicsWarning, match="contact.slices = 1 cannot resolve"):
        ContactOptions(slices=1, modifications=FlankModifications(crowning=c_b))
    cyc = analyse_contact(src, op, opts)
    dist = load_distribution(cyc, pair, op)
    k = stiffness_at(src.model, cyc.s0, n, src.friction, src.operating).total
    shape = (1.0 - 1.0 / n**2) / 3.0 - 1.0 / n**2
    assert np.all(k * c_b * (1.0 - shape) < cyc.load)  # the face ends stay loaded
    np.testing.assert_allclose(dist.k_hbeta_position, 1.0 + k * c_b * shape / cyc.load,
                               rtol=1e-9)
    assert dist.k_hbeta > 1.1
    i = np.argmax(dist.cycle_mean)  # the crown carries the most, symmetric about mid face
    assert abs(dist.z[i] - pair.face_width / 2) < pair.face_width / n
    np.testing.assert_allclose(dist.cycle_mean, dist.cycle_mean[::-1], rtol=1e-9)


def test_helical_pair_even_load_near_one(helical_traction_pair):
    """Perfect helical flanks: the cycle-mean line load is even to the sampling of the cycle."""
    pair = helical_traction_pair
    op = OperatingPoint(torque=2000.0, speed=100.0)
    opts = ContactOptions(positions=40, slices=20)
    cyc = analyse_contact(analytical_compliance(pair, op, opts), op, opts)
    dist = load_distribution(cyc, pair, op)
    assert 1.0 <= dist.k_hbeta < 1.01  # 1.0086 at 40 positions, 1.0040 at 80: -> 1 like 1/m
    assert dist.k_hbeta_position.max() > dist.k_hbeta  # the transverse sharing moves in time
    assert dist.te_peak_to_peak > 0 and np.isfinite(dist.te_orders).all()
    s = dist.summary()
    assert s["K_Hbeta"] == dist.k_hbeta
    assert s["transmission_error_peak_to_peak_rad"] == pytest.approx(
        np.ptp(cyc.transmission_error) / pair.pinion.base_radius)


def test_mesh_order_amplitudes_exact():
    t = np.arange(32) / 32
    v = 1.0 + 0.3 * np.cos(2 * np.pi * t + 0.2) + 0.05 * np.sin(2 * np.pi * 7 * t)
    a = mesh_order_amplitudes(v)
    np.testing.assert_allclose(a[[0, 6]], [0.3, 0.05], rtol=1e-12)
    np.testing.assert_allclose(np.delete(a, [0, 6]), 0.0, atol=1e-14)
    short = mesh_order_amplitudes(v[::2], 10)  # 16 samples: orders 8.. unresolved
    assert np.isnan(short[7:]).all() and np.isfinite(short[:7]).all()


def test_wrong_operating_point_is_refused(pair):
    cyc, op = _cycle(pair, 4, 1.4e10, 300.0, 0.0, positions=6)
    with pytest.raises(InputError, match="solved at P = .* N, the operating point gives"):
        load_distribution(cyc, pair, OperatingPoint(torque=301.0, speed=100.0))
    other = GearPair(spur(31, "pinion"), spur(45, "gear"))
    with pytest.raises(InputError):
        load_distribution(cyc, other, op)
