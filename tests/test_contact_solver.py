"""Complementarity solver of one mesh position (pipeline.contact.complementarity)."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.contact import (
    ContactConvergenceError,
    HertzLineContact,
    LinearLocalCompliance,
    solve_contact,
)
from pipeline.geometry import Material
from pipeline.validation import InputError

STEEL = Material(youngs_modulus=2.0e11, poisson_ratio=0.3)


def test_two_springs_one_and_two_in_contact():
    """Two independent springs c1, c2 with the second one a gap e behind.

    By hand: while c1 P < e only spring 1 carries load, x = c1 P, k = 1/c1;
    beyond, x = (P + e/c2) / (1/c1 + 1/c2), F1 = x/c1, F2 = (x - e)/c2, k = 1/c1 + 1/c2.
    """
    c1, c2, e = 2e-9, 4e-9, 5e-6
    G = np.diag([c1, c2])
    eps = np.array([0.0, e])
    P = 1000.0  # c1 P = 2 um < e
    sol = solve_contact(G, eps, P)
    assert sol.loads == pytest.approx([P, 0.0], abs=1e-9 * P)
    assert sol.approach == pytest.approx(c1 * P, rel=1e-12)
    assert sol.mesh_stiffness_tangent == pytest.approx(1 / c1, rel=1e-12)
    assert sol.gap[1] == pytest.approx(e - c1 * P, rel=1e-12)
    P = 5000.0  # c1 P = 10 um > e
    x = (P + e / c2) / (1 / c1 + 1 / c2)
    sol = solve_contact(G, eps, P)
    assert sol.approach == pytest.approx(x, rel=1e-12)
    assert sol.loads == pytest.approx([x / c1, (x - e) / c2], rel=1e-12)
    assert sol.mesh_stiffness_tangent == pytest.approx(1 / c1 + 1 / c2, rel=1e-12)
    assert sol.mesh_stiffness_secant == pytest.approx(P / x, rel=1e-12)
    assert sol.residual <= sol.tolerance


def test_three_coupled_points_by_hand():
    """Points 1, 2 coupled (G = [[a, b], [b, a]]) share P equally by symmetry,
    so x = (a + b) P / 2 and k = 2 / (a + b); point 3 (compliance c, gap 1 mm) stays open
    with gap eps3 - x."""
    a, b, c = 3e-9, 1e-9, 2e-9
    G = np.array([[a, b, 0.0], [b, a, 0.0], [0.0, 0.0, c]])
    eps = np.array([0.0, 0.0, 1e-3])
    P = 2000.0
    sol = solve_contact(G, eps, P)
    assert sol.loads == pytest.approx([P / 2, P / 2, 0.0], rel=1e-12, abs=1e-9)
    assert sol.approach == pytest.approx((a + b) * P / 2, rel=1e-12)
    assert sol.mesh_stiffness_tangent == pytest.approx(2 / (a + b), rel=1e-12)
    assert sol.gap[2] == pytest.approx(1e-3 - (a + b) * P / 2, rel=1e-12)


def _kkt(G, eps, P, sol, local=None):
    """Max violations of: F >= 0, sum F = P, gap >= 0, gap = 0 where F > 0 (relative)."""
    F = sol.loads
    u = np.zeros_like(F) if local is None else local.approach(F)
    gap = G @ F + u + eps - sol.approach
    scale = np.max(sol.approach - eps[F > 0])
    return {
        "negative_load": max(0.0, -F.min()) / P,
        "balance": abs(F.sum() - P) / P,
        "penetration": max(0.0, -gap.min()) / scale,
        "open_loaded_gap": np.abs(gap[F > 0]).max() / scale,
    }


@pytest.mark.parametrize("seed", range(6))
def test_random_spd_kkt_linear_and_hertz(seed):
    """Random SPD G (n = 30, cond ~ 1e3) and gaps up to 20 um: the returned state
    meets the KKT conditions of eqs. 27-29 to 1e-9 relative, with and without the
    nonlinear Weber local approach; the reported residual matches an independent check."""
    rng = np.random.default_rng(seed)
    n = 30
    A = rng.standard_normal((n, n))
    G = (A @ A.T / n + 0.05 * np.eye(n)) * 5e-9
    eps = rng.uniform(0.0, 20e-6, n)
    P = 2.0e4
    hz = HertzLineContact(slice_width=np.full(n, 2e-3), radius_1=rng.uniform(0.01, 0.03, n),
                          radius_2=rng.uniform(0.01, 0.05, n), depth_1=np.full(n, 3e-3),
                          depth_2=np.full(n, 3e-3), material_1=STEEL, material_2=STEEL)
    for local in (None, hz):
        sol = solve_contact(G, eps, P, local)
        v = _kkt(G, eps, P, sol, local)
        assert all(val <= 1e-9 for val in v.values()), v
        assert sol.residual <= sol.tolerance
        assert 1 < sol.n_active < n  # a genuine contact-set problem


def test_tangent_stiffness_is_the_load_derivative():
    """k_t = dP/dx_s from the active set equals a central difference of x_s(P)
    (relative step 1e-5) with the nonlinear Hertz approach, to 1e-6."""
    rng = np.random.default_rng(7)
    n = 12
    A = rng.standard_normal((n, n))
    G = (A @ A.T / n + 0.2 * np.eye(n)) * 4e-9
    eps = rng.uniform(0.0, 3e-6, n)
    hz = HertzLineContact(np.full(n, 2e-3), np.full(n, 0.02), np.full(n, 0.03),
                          np.full(n, 3e-3), np.full(n, 3e-3), STEEL, STEEL)
    P, h = 3.0e4, 1e-5
    sol = solve_contact(G, eps, P, hz, tol=1e-13)
    lo = solve_contact(G, eps, P * (1 - h), hz, tol=1e-13)
    hi = solve_contact(G, eps, P * (1 + h), hz, tol=1e-13)
    assert np.array_equal(lo.active, hi.active)
    k_fd = 2 * h * P / (hi.approach - lo.approach)
    assert sol.mesh_stiffness_tangent == pytest.approx(k_fd, rel=1e-6)


def test_linear_local_compliance_equals_adding_it_to_G():
    """u_c = c F as a local model gives the same loads as G + diag(c) (to 1e-10 P)."""
    rng = np.random.default_rng(3)
    n = 10
    A = rng.standard_normal((n, n))
    G = (A @ A.T / n + 0.1 * np.eye(n)) * 3e-9
    c = rng.uniform(1e-10, 5e-10, n)
    eps = rng.uniform(0.0, 5e-6, n)
    a = solve_contact(G, eps, 1e4, LinearLocalCompliance(c))
    b = solve_contact(G + np.diag(c), eps, 1e4)
    assert np.abs(a.loads - b.loads).max() <= 1e-10 * 1e4
    assert a.approach == pytest.approx(b.approach, rel=1e-10)


def test_single_point_carries_everything():
    """One point in mesh (others +inf): F = P and x = G P + u_c(P) exactly."""
    hz = HertzLineContact(0.01, 0.02, 0.03, 4e-3, 4e-3, STEEL, STEEL)
    G = np.diag([5e-9, 1e-9])
    sol = solve_contact(G, [0.0, np.inf], 1500.0, _OnePoint(hz))
    assert sol.loads.tolist() == [1500.0, 0.0]
    assert sol.approach == pytest.approx(5e-9 * 1500 + float(hz.approach(1500.0)), rel=1e-12)


class _OnePoint:
    """Scalar Hertz model broadcast over two points."""

    def __init__(self, hz):
        self.hz = hz

    def approach(self, loads):
        return np.asarray(self.hz.approach(loads))

    def tangent(self, loads):
        return np.asarray(self.hz.tangent(loads))


def test_unconverged_solve_raises_naming_the_position():
    """A Newton budget of one iteration cannot meet 1e-12 on a nonlinear problem:
    ContactConvergenceError, with the position label in the message."""
    n = 8
    G = np.eye(n) * 2e-9
    hz = HertzLineContact(np.full(n, 2e-3), np.full(n, 0.02), np.full(n, 0.03),
                          np.full(n, 3e-3), np.full(n, 3e-3), STEEL, STEEL)
    eps = np.linspace(0.0, 2e-6, n)
    with pytest.raises(ContactConvergenceError, match="position 17"):
        solve_contact(G, eps, 2e4, hz, tol=1e-12, max_iter=1, label="position 17")


def test_invalid_inputs_are_named():
    """Indefinite G, negative load and NaN gaps raise InputError naming the field."""
    with pytest.raises(InputError, match="positive semidefinite"):
        solve_contact(np.array([[1e-9, 2e-9], [2e-9, 1e-9]]), [0.0, 0.0], 100.0)
    with pytest.raises(InputError, match="P"):
        solve_contact(np.eye(2) * 1e-9, [0.0, 0.0], -1.0)
    with pytest.raises(InputError, match="eps"):
        solve_contact(np.eye(2) * 1e-9, [0.0, np.nan], 1.0)
