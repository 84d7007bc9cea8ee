"""Sparse SPD solvers: every method gives the same displacements on a 3D problem."""

from __future__ import annotations

import gc
import platform
import sys

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import MeshTet

from pipeline.fem.linear_static import (
    build_model,
    compliance_blocks,
    factorized,
    free_block,
    free_system,
    load_compliance,
    set_up,
    solve_static,
)
from pipeline.fem.solvers import (
    DirectSolver,
    cholespy_available,
    cholmod_available,
    factorize_spd,
    pardiso_available,
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
    for method, available in (("pardiso", pardiso_available()),
                              ("cholmod", cholmod_available()),
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


MKL_PLATFORM = ((sys.platform == "linux" and platform.machine() == "x86_64")
                or sys.platform == "win32")  # where pyproject installs pypardiso (MKL wheels)
needs_pardiso = pytest.mark.skipif(not MKL_PLATFORM, reason="no MKL wheels on this platform")


def _relative(x: np.ndarray, ref: np.ndarray) -> float:
    return float(np.linalg.norm(x - ref) / np.linalg.norm(ref))


@needs_pardiso
def test_pardiso_is_installed_and_is_what_auto_takes(bar):
    """pypardiso (MKL PARDISO) is a dependency: "auto" factorises with it, and its solution
    of the clamped bar's three load cases equals SuperLU's and cholespy's to 1e-10
    (relative, Frobenius norm over all cases)."""
    assert pardiso_available() and sparse_cholesky() == "pardiso"
    model, clamp, F = bar
    auto = solve_static(model, F, clamp)
    assert auto.method == "pardiso"
    for method in ("splu", "cholespy"):
        ref = solve_static(model, F, clamp, solver=DirectSolver(method)).displacements
        assert _relative(auto.displacements, ref) < 1e-10
        for k in range(F.shape[1]):  # and every load case on its own
            assert _relative(auto.displacements[:, k], ref[:, k]) < 1e-10


@needs_pardiso
def test_pardiso_reproduces_uniaxial_stress_exactly():
    """Patch test (Zienkiewicz, Taylor & Zhu, The Finite Element Method, 7th ed., 2013,
    ch. 9): a 3D block in uniaxial tension sigma_x on rollers (u_x = 0 on x = 0, u_y = 0
    on y = 0, u_z = 0 on z = 0) has the exact field u = sigma / E (x, -nu y, -nu z), which
    the P2 space holds, so the discrete solution is that field to round-off. The loads are
    K u_exact; their interior rows vanish (the field is in equilibrium), so only the x = L
    face is loaded, with a resultant sigma_x times the face area."""
    L, W, H, sigma = 0.2, 0.05, 0.03, 1e8
    mesh = MeshTet.init_tensor(np.linspace(0, L, 6), np.linspace(0, W, 3),
                               np.linspace(0, H, 3))
    mat = Material()
    model = build_model(mesh, mat, order=2)
    X = model.basis.doflocs
    comp = np.arange(model.n_dof) % 3
    scale = sigma / mat.youngs_modulus * np.array([1.0, -mat.poisson_ratio,
                                                   -mat.poisson_ratio])
    exact = scale[comp] * X[comp, np.arange(model.n_dof)]
    held = np.flatnonzero(np.isclose(X[comp, np.arange(model.n_dof)], 0.0, atol=1e-12))
    F = model.stiffness @ exact
    face = np.isclose(X[0], L) & (comp == 0)
    loaded = np.isclose(X[0], L) | np.isin(np.arange(model.n_dof), held)
    assert np.abs(F[~loaded]).max() < 1e-9 * np.abs(F).max()
    assert F[face].sum() == pytest.approx(sigma * W * H, rel=1e-12)
    F[~loaded] = 0.0
    u = solve_static(model, F, held, solver=DirectSolver("pardiso"))
    assert u.method == "pardiso"
    assert _relative(u.displacements[:, 0], exact) < 1e-10


@needs_pardiso
def test_pardiso_factors_are_exact_and_independent():
    """The 1D Laplacian tridiag(-1, 2, -1) of size n has the inverse
    (A^-1)_ij = min(i, j) (n + 1 - max(i, j)) / (n + 1) (its discrete Green's function).
    Two PARDISO factors live side by side (A and 2 A); dropping the second frees its MKL
    memory and leaves the first solving exactly."""
    n = 50
    A = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tocsr()
    i = np.arange(1, n + 1)[:, None]
    j = np.array([1, n // 2 + 1, n])[None, :]
    exact = np.minimum(i, j) * (n + 1 - np.maximum(i, j)) / (n + 1)
    B = np.eye(n)[:, [0, n // 2, n - 1]]
    first = factorize_spd(A, "pardiso")
    second = factorize_spd(2 * A, "pardiso")
    np.testing.assert_allclose(second.solve(B), exact / 2, rtol=1e-12)
    del second
    gc.collect()
    X = first.solve(B)
    np.testing.assert_allclose(X, exact, rtol=1e-12)
    np.testing.assert_allclose(first.solve(B[:, 1]), exact[:, 1], rtol=1e-12)  # one column
    assert first.method == "pardiso" and X.shape == B.shape


@needs_pardiso
def test_pardiso_runs_small_systems_on_one_thread(monkeypatch):
    """Below ``SERIAL_BELOW_NNZ`` non-zeros in the upper triangle PARDISO's analysis,
    factorisation and solves run with MKL's thread-local setting at one thread, put back
    after each call; at or above it on the threads MKL is given. The answer is the exact
    inverse either way."""
    import pipeline.fem.solvers as solvers

    n = 50
    A = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1]).tocsr()
    exact = np.arange(1, n + 1) / (n + 1)  # column n of the inverse: i / (n + 1) (above)
    seen = []
    real = solvers._Pardiso.__init__

    def spying_init(self, U):
        real(self, U)
        lib, pardiso = self._lib, self._lib._mkl_pardiso

        def spy(*args):
            seen.append(lib.libmkl.MKL_Get_Max_Threads())
            return pardiso(*args)

        lib._mkl_pardiso = spy

    monkeypatch.setattr(solvers._Pardiso, "__init__", spying_init)
    lib = solvers._Pardiso(sp.triu(A, format="csr"))._lib.libmkl
    lib.MKL_Set_Num_Threads_Local(2)  # this thread's setting, to be kept
    try:
        f = factorize_spd(A, "pardiso")
        np.testing.assert_allclose(f.solve(np.eye(n)[:, -1]), exact, rtol=1e-12)
        assert seen == [1, 1]  # analysis and factorisation, solve
        assert lib.MKL_Get_Max_Threads() == 2
        del f  # its release (phase -1) is a call too
        gc.collect()
        seen.clear()
        monkeypatch.setattr(solvers, "SERIAL_BELOW_NNZ", 10)
        f = factorize_spd(A, "pardiso")
        np.testing.assert_allclose(f.solve(np.eye(n)[:, -1]), exact, rtol=1e-12)
        assert seen == [2, 2]
    finally:
        lib.MKL_Set_Num_Threads_Local(0)


@needs_pardiso
def test_pardiso_refuses_a_matrix_that_is_not_positive_definite(bar):
    """A free-free body (six rigid-body modes) has no Cholesky factor: a one-line error."""
    model, _, _ = bar
    with pytest.raises(RuntimeError, match="not positive definite"):
        factorize_spd(model.stiffness, "pardiso")
    # a DOF in no element (an empty row) is refused before PARDISO sees it
    A = sp.diags([1.0, 0.0, 2.0]).tocsr()
    A.eliminate_zeros()
    with pytest.raises(RuntimeError, match="empty row"):
        factorize_spd(A, "pardiso")


def test_free_block_is_the_indexed_block_and_its_upper_triangle():
    """free_block(K, free) equals K[free][:, free] entry by entry (both are copies of K's
    entries: exact), with the same sparsity; upper=True equals its triu; several passes
    over the rows give the same matrix as one."""
    rng = np.random.default_rng(3)
    K = sp.random(300, 300, density=0.05, random_state=4, format="csr")
    K = (K + K.T + sp.eye(300)).tocsr()
    free = np.sort(rng.choice(300, 230, replace=False))
    ref = K[free][:, free].tocsr()
    ref.sort_indices()
    for passes in (7, 300):
        B = free_block(K, free, rows_per_pass=passes)
        assert B.shape == ref.shape and B.nnz == ref.nnz
        np.testing.assert_array_equal(B.indptr, ref.indptr)
        np.testing.assert_array_equal(B.indices, ref.indices)
        np.testing.assert_array_equal(B.data, ref.data)
        U = free_block(K, free, upper=True, rows_per_pass=passes)
        assert abs(U - sp.triu(ref)).max() == 0.0 and U.nnz == sp.triu(ref).nnz
    with pytest.raises(InputError, match="ascending"):
        free_block(K, free[::-1])


def test_upper_triangle_factors_equal_the_full_matrix_ones(bar):
    """factorize_spd(triu(A), upper=True) solves with A itself: PARDISO takes the triangle
    as it is (the same numbers as its factor of the full block: identical solutions), the
    other methods rebuild A from it. The assembled A is symmetric to round-off (1e-15 of its
    largest entry), so each method's solution of the clamped bar's three load cases equals
    its solution with the full block to 1e-10 (relative, Frobenius; the bar is
    ill-conditioned: two factorisations of it differ by up to 3e-11)."""
    model, clamp, F = bar
    fixed = np.zeros(model.n_dof, dtype=bool)
    fixed[clamp] = True
    free = np.flatnonzero(~fixed)
    A = model.stiffness[free][:, free]
    assert abs(A - A.T).max() < 1e-15 * abs(A).max()
    U = free_block(model.stiffness, free, upper=True)
    methods = ["splu", "cholespy"] + (["pardiso"] if pardiso_available() else [])
    for method in methods:
        x = factorize_spd(U, method, upper=True).solve(F[free])
        full = factorize_spd(A, method).solve(F[free])
        if method == "pardiso":
            np.testing.assert_array_equal(x, full)
        assert _relative(x, full) < 1e-10, method


def test_compliance_blocks_read_a_dense_solve(bar):
    """R^T K^-1 F by blocks of right-hand sides (column-major PARDISO blocks read column by
    column) equals the product computed here from a dense solve of the free block
    (numpy.linalg.solve) to 1e-10 (relative, max: the bar's conditioning), for blocks of 1
    and of all cases, read at other DOFs than the loaded ones; load_compliance is set_up
    then compliance_blocks, bit for bit."""
    model, clamp, F = bar
    rng = np.random.default_rng(7)
    R = sp.csc_matrix(rng.standard_normal((model.n_dof, 5)) * (rng.random((model.n_dof, 1))
                                                                < 0.05))
    Fs = sp.csc_matrix(F)
    fixed = np.zeros(model.n_dof, dtype=bool)
    fixed[clamp] = True
    free = np.flatnonzero(~fixed)
    A = model.stiffness[free][:, free].toarray()
    exact = R.toarray()[free].T @ np.linalg.solve(0.5 * (A + A.T), F[free])
    free_set, factor = set_up(model, clamp)
    np.testing.assert_array_equal(free_set, free)
    for block in (1, 3):
        C = compliance_blocks(factor, free_set, Fs, R, block=block).matrix
        assert C.shape == (5, 3)
        assert np.abs(C - exact).max() < 1e-10 * np.abs(exact).max()
    whole = load_compliance(model, Fs, clamp, read=R, block=3).matrix
    np.testing.assert_array_equal(whole, compliance_blocks(factor, free_set, Fs, R, 3).matrix)
    with pytest.raises(InputError, match="rows"):
        compliance_blocks(factor, free_set, Fs, R[:-1])


def test_free_system_factorises_without_the_model():
    """free_system's call holds the free block, not the model: a model dropped before the
    call is freed (weak reference dead), and the factor then solves bit for bit as set_up's
    (the 3D tables factorise without the full stiffness in memory)."""
    import weakref

    mesh = MeshTet.init_tensor(np.linspace(0, 1, 7), np.linspace(0, 0.1, 3),
                               np.linspace(0, 0.1, 3))
    model = build_model(mesh, Material(), order=2)
    clamp = model.dofs.get_dofs(lambda x: x[0] < 1e-12).flatten()
    F = np.zeros((model.n_dof, 1))
    F[model.dofs.get_dofs(lambda x: x[0] > 1 - 1e-12).flatten()[0::3], 0] = 1.0
    free, factor = set_up(model, clamp)
    ref = factor.solve(F[free])
    free2, factorize = free_system(model, clamp)
    alive = weakref.ref(model)
    del model
    gc.collect()
    assert alive() is None
    np.testing.assert_array_equal(free2, free)
    np.testing.assert_array_equal(factorized(factorize, free.size).solve(F[free]), ref)


def test_bad_inputs(bar):
    """Unknown methods and wrong shapes raise InputError."""
    model, clamp, F = bar
    with pytest.raises(InputError, match="solver.method"):
        factorize_spd(model.stiffness, "mumps")
    with pytest.raises(InputError, match="rows"):
        solve_static(model, F[:-1], clamp)
