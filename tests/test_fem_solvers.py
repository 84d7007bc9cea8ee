"""Sparse SPD solvers: every method gives the same displacements on a 3D problem."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import MeshTet

from pipeline.fem.linear_static import build_model, solve_static
from pipeline.fem.solvers import (
    DirectSolver,
    cholespy_available,
    cholmod_available,
    factorize_spd,
    sparse_cholesky,
)
from pipeline.geometry.gear import Material
from pipeline.validation import InputError


@pytest.fixture(scope="module")
def bar():
    """A clamped 3D bar, P2, with three load cases (axial, lateral, torsion-like)."""
    mesh = MeshTet.init_tensor(np.linspace(0, 1, 9), np.linspace(0, 0.1, 3),
                               np.linspace(0, 0.1, 3))
    model = build_model(mesh, Material(), order=2)
    clamp = model.basis.get_dofs(lambda x: x[0] < 1e-12).flatten()
    tip = model.basis.get_dofs(lambda x: x[0] > 1 - 1e-12).flatten()
    F = np.zeros((model.n_dof, 3))
    for k in range(3):
        F[tip[tip % 3 == k], k] = 1.0
    return model, clamp, F


def test_factor_once_many_rhs_and_methods_agree(bar):
    model, clamp, F = bar
    ref = solve_static(model, F, clamp, solver=DirectSolver("splu"))
    assert ref.method == "splu"
    # Equilibrium: reactions balance the applied load in every case.
    np.testing.assert_allclose(ref.reactions.sum(axis=0), -F.sum(axis=0), rtol=1e-9)
    for method, available in (("cholmod", cholmod_available()),
                              ("cholespy", cholespy_available())):
        if available:
            ch = solve_static(model, F, clamp, solver=DirectSolver(method))
            assert ch.method == method
            np.testing.assert_allclose(ch.displacements, ref.displacements, rtol=0,
                                       atol=1e-10 * np.abs(ref.displacements).max())
    auto = solve_static(model, F, clamp)
    assert auto.method == (sparse_cholesky() or "splu")


def test_cholespy_is_installed_and_solves_many_rhs():
    """cholespy is a dependency: "auto" must find a sparse Cholesky on every install.

    A 1D Laplacian with a known inverse column checks (n, k) right-hand sides.
    """
    assert cholespy_available()
    n = 50
    A = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tocsr()
    f = factorize_spd(A, "cholespy")
    B = np.eye(n)[:, [0, n // 2, n - 1]]
    X = f.solve(B)
    i = np.arange(1, n + 1)[:, None]
    j = np.array([1, n // 2 + 1, n])[None, :]
    exact = np.minimum(i, j) * (n + 1 - np.maximum(i, j)) / (n + 1)  # (A^-1)_ij
    np.testing.assert_allclose(X, exact, rtol=1e-12)
    assert f.method == "cholespy" and X.shape == B.shape


def test_bad_inputs(bar):
    """Unknown methods and wrong shapes raise InputError."""
    model, clamp, F = bar
    with pytest.raises(InputError, match="solver.method"):
        factorize_spd(model.stiffness, "mumps")
    with pytest.raises(InputError, match="rows"):
        solve_static(model, F[:-1], clamp)
