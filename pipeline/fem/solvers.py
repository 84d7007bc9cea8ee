"""Sparse symmetric positive definite solves: factorise once, solve many right-hand sides.

Methods (measured side by side on a 2-core machine when they were chosen):

* ``"cholmod"`` - supernodal sparse Cholesky from SuiteSparse through
  scikit-sparse; the default whenever it is installed. 3D P2 elasticity with
  200k DOF factorises in about 20 s and each further right-hand side costs
  milliseconds.
* ``"cholespy"`` - the same CHOLMOD Cholesky, statically linked in the ``cholespy``
  wheel (a dependency, so always there when the package is installed; scikit-sparse
  has no wheels and needs a system SuiteSparse). Taken by ``"auto"`` when
  scikit-sparse is absent. 3D P2 sector, 23.8k DOF, 1200 right-hand sides: factor and
  solves 4.6 s against 62.6 s for the p-multigrid CG (bench_fe; 114k DOF: 85 s).
* ``"splu"`` - scipy's SuperLU. Always available; fine for 2D and small 3D
  models, unusable for large 3D ones (> 600 s at 200k DOF), so it is only the
  fallback.

Every result says which method ran, so reports can state it.

MUMPS is not offered: it was measured through the ``python-mumps`` wheel, but
the only binary wheel for CPython 3.11 (python-mumps 0.0.2, manylinux2010) is
compiled against NumPy 1.x and fails on import under NumPy 2 ("numpy.core.multiarray
failed to import"); later releases (0.0.3, 0.0.4) are source-only and need a system
MUMPS to build (pip's build of 0.0.4 stops in meson). Without scikit-sparse, 3D models with
many right-hand sides use cholespy's CHOLMOD, or, without it, the p-multigrid CG of
:mod:`pipeline.fem.pmultigrid` (block right-hand sides, one set-up).

Solvers are passed in, as scikit-fem's ``solve(..., solver=...)`` takes them: a
:class:`Solver` is called once with the free-free matrix and returns a set-up
(a factor, or a preconditioner) whose ``solve`` then takes block after block of
right-hand sides. :class:`DirectSolver` factorises; :class:`~pipeline.fem.pmultigrid.PMultigridCG`
iterates. :func:`solver_named` turns a configuration string into one of them.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from importlib.util import find_spec
from typing import Protocol

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis

from pipeline.fem.pmultigrid import PMultigridCG
from pipeline.fem.settings import FACTOR_METHODS, SOLVERS
from pipeline.validation import InputError, check_choice


def cholmod_available() -> bool:
    """True when scikit-sparse (CHOLMOD) can be imported."""
    return find_spec("sksparse") is not None


def cholespy_available() -> bool:
    """True when cholespy (CHOLMOD in a self-contained wheel) can be imported."""
    return find_spec("cholespy") is not None


def sparse_cholesky() -> str | None:
    """The sparse Cholesky that "auto" uses: "cholmod", "cholespy" or None (neither)."""
    if cholmod_available():
        return "cholmod"
    return "cholespy" if cholespy_available() else None


def _cholespy_factor(A: sp.spmatrix):
    from cholespy import CholeskySolverD, MatrixType

    A = sp.csc_matrix(A)
    A.sort_indices()
    solver = CholeskySolverD(A.shape[0], A.indptr.astype(np.int32), A.indices.astype(np.int32),
                             A.data.astype(np.float64), MatrixType.CSC)

    def solve(b: np.ndarray) -> np.ndarray:
        b = np.ascontiguousarray(b, dtype=np.float64)
        x = np.empty_like(b)
        solver.solve(b, x)
        return x

    return solve


@dataclass(frozen=True, eq=False)
class SPDFactor:
    """A factorised SPD matrix A (n, n).

    Attributes
    ----------
    method : "cholmod", "cholespy" or "splu".
    n : matrix size.
    factor_seconds : wall time of the factorisation, s.
    """

    method: str
    n: int
    factor_seconds: float
    _solve: object

    def solve(self, b: np.ndarray) -> np.ndarray:
        """Solve A x = b for b of shape (n,) or (n, k); returns the same shape."""
        b = np.asarray(b, dtype=float)
        if b.shape[0] != self.n:
            raise InputError(f"right-hand side has {b.shape[0]} rows, the matrix {self.n}")
        return np.asarray(self._solve(b))

    @property
    def iterations(self) -> int:
        """0: a factorisation does not iterate."""
        return 0


class Factorization(Protocol):
    """A matrix set up for many solves: a factor, or a preconditioner and its iteration."""

    method: str
    factor_seconds: float
    iterations: int

    def solve(self, b: np.ndarray) -> np.ndarray: ...


class Solver(Protocol):
    """Sets up the free-free stiffness ``A`` of ``basis`` (``free``: its DOFs) once."""

    def __call__(self, A: sp.spmatrix, basis: Basis, free: np.ndarray) -> Factorization: ...


@dataclass(frozen=True)
class DirectSolver:
    """Factorise once (:func:`factorize_spd`); ``method`` "auto", "cholmod", "cholespy" or
    "splu"."""

    method: str = "auto"

    def __post_init__(self) -> None:
        check_choice("solver.method", self.method, FACTOR_METHODS)

    def __call__(self, A: sp.spmatrix, basis: Basis | None = None,
                 free: np.ndarray | None = None) -> SPDFactor:
        return factorize_spd(A, self.method)


def solver_named(name: str = "auto", dim: int = 3) -> Solver:
    """The solver a configuration string names (:data:`SOLVERS`).

    "auto" is the sparse Cholesky when one is installed; without it SuperLU in 2D
    (fast there) and the p-multigrid CG in 3D (SuperLU fills badly on 3D P2 elasticity).
    """
    check_choice("solver.method", name, SOLVERS)
    if name == "pmg-cg" or (name == "auto" and dim == 3 and sparse_cholesky() is None):
        return PMultigridCG()
    return DirectSolver(name)


def factorize_spd(A: sp.spmatrix, method: str = "auto") -> SPDFactor:
    """Factorise a sparse SPD matrix once for many solves.

    Parameters
    ----------
    A : (n, n) sparse symmetric positive definite matrix.
    method : "auto" (scikit-sparse's CHOLMOD if installed, else cholespy's, else
        SuperLU), "cholmod", "cholespy" or "splu".
    """
    check_choice("solver.method", method, FACTOR_METHODS)
    if method == "auto":
        method = sparse_cholesky() or "splu"
    if method == "cholmod" and not cholmod_available():
        raise InputError("solver.method = 'cholmod' but scikit-sparse is not installed")
    if method == "cholespy" and not cholespy_available():
        raise InputError("solver.method = 'cholespy' but cholespy is not installed")
    n = A.shape[0]
    t0 = time.perf_counter()
    if method == "cholmod":
        from sksparse.cholmod import cholesky

        factor = cholesky(sp.csc_matrix(A))
        solve = factor
    elif method == "cholespy":
        solve = _cholespy_factor(A)
    else:
        lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A",
                       options={"SymmetricMode": True})
        solve = lu.solve
    return SPDFactor(method=method, n=n, factor_seconds=time.perf_counter() - t0, _solve=solve)
