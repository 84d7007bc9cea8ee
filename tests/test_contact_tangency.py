"""Line contact across a rounded tip's tangency with its involute (pipeline.contact.tangency).

Ladder:
* exact: the collocation solver gives Hertz's approach difference of two radii
  (``ln(R1 / R2) / pi`` per unit load, Johnson 1985 eqs. 4.43 and 4.45 with the half-plane's
  logarithmic displacement) and Hertz's peak pressure; the correction vanishes where the
  involute's Hertz patch ends before the tangency (``xi <= -1``) and equals Hertz of the
  rounding where the rounding's patch lies past it (``xi >= 1``), solved without the
  shortcut;
* convergence: the committed table's entries are the solver's at its grid (to 1e-9), and
  the interpolation lies within 0.006 of the solver off the grid;
* the model: its tangent is the derivative of its approach; the offset of a contact point
  from the tangency against the arc of the rounding drawn by the profile; the loaded TE of
  the demo pair with 0.3 mm roundings is continuous where the contact point crosses the
  tangency (it stepped by 2.4 % within 0.01 mm of roll with the rounding's Hertz alone).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur

from pipeline.contact import tangency as T
from pipeline.contact.analysis import analytical_compliance
from pipeline.contact.hertz import HertzLineContact, effective_radius
from pipeline.contact.ltca import loaded_mesh_cycle, weber_model
from pipeline.contact.options import ContactOptions
from pipeline.geometry.pair import GearPair
from pipeline.geometry.profile import tip_rounding_arc
from pipeline.geometry.tip_contact import contact_radii_at, curvature_radii_at, tangency_offset
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError

B_I = math.sqrt(4.0 / math.pi)  # Hertz half-width for R = 1, w = 1, E* = 1


@pytest.mark.parametrize("q", [0.5, 0.01])
def test_solver_gives_hertz(q):
    """A quadratic gap of radius R on the graded grid: the approach minus that of radius 1
    is ``ln(1 / R) / pi`` (Hertz, both in the same logarithmic kernel) within 2e-4 (the
    collocation's error, 1.2e-4 here), and the peak pressure ``2 w / (pi b)`` within 0.5 %
    (the element at the centre)."""
    b = B_I * math.sqrt(q)
    edges = T._edges(-1.6 * b, 1.6 * b, 0.0, b / 40.0, b / 60.0)
    centres = 0.5 * (edges[:-1] + edges[1:])
    u, p = T.line_contact(centres**2 / (2.0 * q), edges)
    assert (u - T.hertz_approach(B_I)) * math.pi == pytest.approx(math.log(1.0 / q), abs=2e-4)
    assert p.max() == pytest.approx(2.0 / (math.pi * b), rel=5e-3)
    assert np.sum(p * np.diff(edges)) == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("q", [0.001, 0.05, 0.3])
def test_exact_limits_hold_in_the_solution(q):
    """Solved without the shortcut: no correction where the involute's Hertz patch ends at
    the tangency, Hertz of the rounding where the rounding's patch starts there (the
    involute behind it, flatter, stays open)."""
    assert T.solved_phi(q, -1.0) == pytest.approx(0.0, abs=2e-4)
    assert T.solved_phi(q, 1.0) == pytest.approx(math.log(1.0 / q), abs=2e-3)
    assert T.phi(q, -1.5) == 0.0 and T.phi(q, 1.5) == math.log(1.0 / q)
    # between the two, the correction grows steadily from the involute to the rounding
    xi = np.array([-0.9, -0.5, -0.1, 0.0, 0.01, 0.1, 0.5, 0.9])
    values = [T.phi(q, float(x)) for x in xi]
    assert np.all(np.diff(values) > 0.0)


def test_committed_table_is_the_solvers():
    """Entries of the committed table recomputed: equal to 1e-9 (same grid, same code)."""
    table = T.phi_table()
    xi = np.concatenate([T.XI_INVOLUTE, T.T_ROUNDING**2])
    for i, j in ((0, 5), (3, 21), (8, 30), (12, 44), (16, 10)):
        assert table[i, j] == pytest.approx(T.phi(float(T.Q[i]), float(xi[j])), abs=1e-9)


def test_interpolation_between_grid_points():
    """At random (q, xi) off the grid the interpolated correction lies within 0.006 of the
    solver's (the correction spans 0 .. ln(1/q), up to 9.2)."""
    rng = np.random.default_rng(7)
    q = np.exp(rng.uniform(math.log(1.5 * T.Q_MIN), 0.0, 10))
    xi = rng.uniform(-0.98, 0.98, 10)
    got, _ = T.phi_interp(q, xi)
    want = [T.phi(float(a), float(b)) for a, b in zip(q, xi, strict=True)]
    assert np.abs(got - want).max() < 6e-3
    with pytest.raises(InputError, match="outside the tabulated"):
        T.phi_interp(0.5 * T.Q_MIN, 0.0)


def _pair(rounding_mm: float = 0.3) -> GearPair:
    return GearPair(spur(50, "pinion", tip_rounding=rounding_mm * 1e-3),
                    spur(50, "gear", tip_rounding=rounding_mm * 1e-3))


def test_offset_along_the_rounding_and_the_involute():
    """``tangency_offset``: 0 at the active tip radius; on the rounding the arc length from
    the tangency measured on the profile's arc (its points, the angle at their centre) to
    1e-10 m (the arc-cosine near the tip circle); on the involute the difference of the
    involute's arc coordinates (negative); NaN for a sharp tip."""
    g = _pair().pinion
    assert float(tangency_offset(g, g.active_tip_radius)) == pytest.approx(0.0, abs=1e-15)
    x, y = tip_rounding_arc(g, 9)
    r = np.hypot(x, y)
    rho = g.tip_rounding
    centre_r = g.tip_radius_ - rho
    # the centre: on the circle r_a - rho, rho from every arc point
    c = np.array([x[-1], y[-1]]) * centre_r / r[-1]
    assert np.hypot(x - c[0], y - c[1]) == pytest.approx(rho, rel=1e-9)
    angle = np.arctan2(y - c[1], x - c[0])
    arc = rho * np.abs(angle - angle[0])
    assert tangency_offset(g, r) == pytest.approx(arc, abs=1e-10)
    rb = g.base_radius
    below = g.active_tip_radius - np.array([1e-4, 1e-3])
    assert tangency_offset(g, below) == pytest.approx(
        (below**2 - g.active_tip_radius**2) / (2 * rb), rel=1e-12)
    assert np.isnan(tangency_offset(spur(50, "pinion"), 0.07)).all()


def test_model_tangent_is_its_derivative_and_sharp_pairs_keep_weber():
    """At points around the pinion's tangency: the tangent equals the central difference
    of the approach (rel 1e-5); the approach of a point far down the flank is Weber's of
    the involute, and a pair without roundings gets plain Weber."""
    pair = _pair()
    src = analytical_compliance(pair, OperatingPoint(340.0, 2340.0), ContactOptions())
    s_end = pair.s_end
    pts = src.points(s_end - pair.base_pitch + 0.02e-3)
    model = weber_model(pair, pts)
    assert isinstance(model, T.TangencyContact)
    F = np.full(len(pts), 2000.0)
    h = 1e-3
    fd = (model.approach(F + h) - model.approach(F - h)) / (2 * h)
    assert model.tangent(F) == pytest.approx(fd, rel=1e-5)
    plain = GearPair(spur(50, "pinion"), spur(50, "gear"))
    src0 = analytical_compliance(plain, OperatingPoint(340.0, 2340.0), ContactOptions())
    assert isinstance(weber_model(plain, src0.points(plain.s_pitch)), HertzLineContact)
    mid = src.points(pair.s_pitch)
    m = weber_model(pair, mid)
    far = np.abs(mid.s - pair.s_pitch) < 0.5 * pair.base_pitch
    assert m.approach(F[: len(mid)])[far] == pytest.approx(
        m.base.approach(F[: len(mid)])[far], rel=1e-14)


def test_loaded_te_is_continuous_through_the_tangency():
    """Demo pair with 0.3 mm roundings, 100 N m, analytical slices: the loaded TE at 1 um of
    roll before and after the leaving pair's contact point crosses the pinion's tangency
    differs by less than 0.05 % (a smooth curve: its slope there is 0.5 %/10 um; the
    rounding's Hertz alone made a 2.4 % step), and 1.5 mm of roll past it the model is
    the rounding's Hertz against the gear's flank exactly (at 0.4 mm the rounding's
    contact point is only 7 um past the tangency and its 15 um patch still reaches it)."""
    pair = _pair()
    src = analytical_compliance(pair, OperatingPoint(100.0, 2340.0), ContactOptions())
    load = 100.0 / pair.pinion.base_radius
    k_end = pair.s_end - pair.base_pitch
    te = loaded_mesh_cycle(src, load, None, "weber",
                           k_end + np.array([-1e-6, 1e-6])).transmission_error
    assert abs(te[1] / te[0] - 1.0) < 5e-4
    # 1.5 mm past the tangency (the rounding's patch clear of it): its own Hertz
    pts = src.points(k_end + 1.5e-3)
    model = weber_model(pair, pts)
    i = int(np.argmax(pts.s))
    assert float(tangency_offset(pair.pinion, contact_radii_at(pair, pts.s[i:i + 1])[0])[0]) > 0
    rho1, rho2 = curvature_radii_at(pair, pts.s[i:i + 1])
    assert rho1[0] == pair.pinion.tip_rounding
    r_eff = 2.0 * effective_radius(rho1, rho2)
    b = model.base
    alone = HertzLineContact(b.slice_width[i], r_eff, r_eff, b.depth_1[i], b.depth_2[i],
                             b.material_1, b.material_2)
    f = np.array([load])
    assert model.approach(np.full(len(pts), load))[i] == pytest.approx(
        float(alone.approach(f)[0]), rel=1e-12)


def test_a_rounding_too_small_to_resolve_is_refused():
    """A rounding below 1e-4 of the flanks' effective radius is refused in one line naming
    the key, the value in mm and the smallest the model resolves."""
    pair = GearPair(spur(50, "pinion", tip_rounding=1e-7), spur(50, "gear"))
    src = analytical_compliance(pair, OperatingPoint(100.0, 2340.0), ContactOptions())
    with pytest.raises(InputError, match=r"^pinion\.tip_rounding = 0\.0001 mm is below the "
                                         r"0\.00\d+ mm the tangency contact model resolves"):
        loaded_mesh_cycle(src, 100.0 / pair.pinion.base_radius, None, "weber", 6)


def test_table_grid_is_checked_to_round_off(tmp_path, monkeypatch):
    """A table made on another grid is refused; one whose grid differs in the last bit
    (another NumPy's ``logspace``) is the same table."""
    tangency = T
    with np.load(tangency.TABLE) as z:
        arrays = dict(z)
    for shift, ok in ((1e-15, True), (1e-6, False)):
        path = tmp_path / f"table_{shift}.npz"
        np.savez(path, **{**arrays, "q": arrays["q"] * (1 + shift)})
        monkeypatch.setattr(tangency, "TABLE", path)
        tangency.phi_table.cache_clear()
        try:
            if ok:
                assert np.array_equal(tangency.phi_table(), arrays["phi"])
            else:
                with pytest.raises(RuntimeError, match="grid 'q' differs"):
                    tangency.phi_table()
        finally:
            tangency.phi_table.cache_clear()
