"""Sparse symmetric positive definite solves: factorise once, solve many right-hand sides.

Methods (measured side by side on a 2-core machine when they were chosen):

* ``"pardiso"`` - MKL PARDISO's supernodal sparse Cholesky (``mtype = 2``, METIS nested
  dissection) through pypardiso, with MKL from the ``mkl`` wheel; a dependency on x86-64
  Linux and Windows (the platforms with MKL wheels) and the default wherever it is
  installed. ``workflows/benchmarks/bench_sparse_solvers.py`` (two runs of 3 cold
  factorisations each, 2 cores shared with other jobs, load 2-6): the straddle-mounted
  shaft superelement's matrix (64.3k unknowns, 4.8M non-zeros, 42 right-hand sides)
  factorises in 2.0-3.7 s on one thread against 8.5-18.5 s with cholespy, and the block
  solves in 0.30-0.83 s against 0.73-1.31 s; the z 30 helical pinion of ``bench_fe3d``
  (43.7k unknowns, 68 right-hand sides) in 1.5-2.4 s against 4.2-7.8 s, solving at 4-8
  against 13-19 ms per right-hand side; the same pinion refined to 112k unknowns in
  5.9-12.6 s against 64-75 s. Its solutions differ from cholespy's by 1e-13 to 1e-12
  (relative), as SuperLU's do. A minimum degree ordering instead of METIS factorises the
  shaft 20-70 % slower (the pinion 20 % faster, but solves it at half the speed); 2
  threads were no faster on the shared machine (MKL takes ``OMP_NUM_THREADS``). PARDISO
  takes 25-30 % more memory than cholespy on the smaller matrices (shaft 405-411 against
  324-326 MiB; 2 % more at 112k) and MKL about 1 GB of disk. PARDISO is called
  directly (:class:`_Pardiso`, through the library pypardiso loads) on the upper
  triangle it needs, which the callers can build alone
  (:func:`pipeline.fem.linear_static.free_block`, :meth:`DirectSolver.factorize_upper`);
  MKL runs on as many threads as ``OMP_NUM_THREADS`` (or ``MKL_NUM_THREADS``) allows, by
  default every core, except for matrices below :data:`SERIAL_BELOW_NNZ` non-zeros (one
  thread: :class:`_Pardiso`). On the whole-gear 3D tables of the traction pair of Yang et al.
  (2026) (``bench_fe3d --full``; 164k and 282k unknowns, 272 right-hand sides read at
  1904 points) the factor holds 113M non-zeros (0.95 GB) for the larger gear, and the
  time is the factorisation and the block solves in about equal parts (9.5 and 11.4 s
  on one thread at 164k). Tried there and not kept: PARDISO's sparse right-hand side and
  partial solution (``iparm 31`` with the 21k loaded and read unknowns marked; answers
  equal to 1e-11) factorised in 294 s instead of 9.5 s; its single-precision factor
  (``iparm 28``) stops at a negative pivot (error -4: the stiffness is too
  ill-conditioned for a single-precision Cholesky); parallel METIS (``iparm 2 = 3``)
  gives the same factor; METIS with ``iparm 2 = 12`` or ``22`` 3 % more non-zeros and
  minimum degree 23 % more; the two-level factorisation (``iparm 24 = 1``) and the
  parallel solve (``iparm 25``) were no faster with 2 threads on the shared machine
  (load 6-9). Against pypardiso's own calls, the full free block and row-major copies of
  the blocks (``bench_fe3d --full``, 2 threads, load 0.5-1.5): both tables 30.3 s against
  33.6 s (pinion factorise 3.5 / 3.7 s, solve 2.8 / 2.9 s; gear 6.1 / 8.1 s and
  5.2 / 5.8 s), ``gearpipe contact`` 34.2 against 38.3 s, peak memory 2.0 against
  2.35 GiB, mesh stiffness and TE p-p unchanged (tables equal to 5e-14). PARDISO's
  factorisation of the larger gear (175k unknowns since) takes 770 MB (``iparm 15-17``);
  its far body is now eliminated first (:mod:`pipeline.fem.condensation`, with
  :func:`schur_complement`: PARDISO's partial factorisation, ``iparm 36 = 1``), so the
  two parts take 320 and 506 MB in turn. Out-of-core PARDISO (``iparm 60 = 2``, 500 MB
  in core) was no answer: 181 s instead of 38 s for both tables, peak 1.24 GiB.
* ``"cholmod"`` - supernodal sparse Cholesky from SuiteSparse through
  scikit-sparse; taken by ``"auto"`` without PARDISO whenever it is installed. 3D P2
  elasticity with 200k DOF factorises in about 20 s and each further right-hand side
  costs milliseconds.
* ``"cholespy"`` - the same CHOLMOD Cholesky, statically linked in the ``cholespy``
  wheel with the reference BLAS (one core; a dependency, so always there when the
  package is installed; scikit-sparse has no wheels and needs a system SuiteSparse).
  Taken by ``"auto"`` when neither is present. 3D P2 sector, 23.8k DOF, 1200
  right-hand sides: factor and solves 4.6 s against 62.6 s for the p-multigrid CG
  (bench_fe; 114k DOF: 85 s).
* ``"splu"`` - scipy's SuperLU. Always available; fine for 2D and small 3D
  models, unusable for large 3D ones (> 600 s at 200k DOF; 8-16 s and 1 GB on the
  shaft above), so it is only the fallback.

Every result says which method ran, so reports can state it.

Measured and not offered (bench_sparse_solvers, the same runs): CHOLMOD through the
cvxopt wheel (OpenBLAS; kvxopt bundles the same libraries) factorises about as fast
(shaft 1.7-4.1 s, pinion 0.9-1.8 s, 112k unknowns 6.2-7.0 s) but solves one right-hand
side at a time (45-83 ms each on the shaft against PARDISO's 7), so the tables' hundreds
of right-hand sides are slower, and cvxopt is GPL; sksparse-minimal (CHOLMOD on the
reference BLAS) factorises the shaft in 4.4-8.7 s; QDLDL (an LDL^T without supernodes)
in 29-49 s. scikit-sparse and pydiso (MKL PARDISO) have no wheels for this platform.
MUMPS: the only binary wheel of ``python-mumps`` for CPython 3.11 (0.0.2,
manylinux2010) is compiled against NumPy 1.x and fails on import under NumPy 2
("numpy.core.multiarray failed to import"); the later releases pip finds for it (0.0.3,
0.0.4) are source-only and need a system MUMPS. Without a sparse Cholesky, 3D models
with many right-hand sides use the p-multigrid CG of :mod:`pipeline.fem.pmultigrid`
(block right-hand sides, one set-up).

Solvers are passed in, as scikit-fem's ``solve(..., solver=...)`` takes them: a
:class:`Solver` is called once with the free-free matrix and returns a set-up
(a factor, or a preconditioner) whose ``solve`` then takes block after block of
right-hand sides. :class:`DirectSolver` factorises; :class:`~pipeline.fem.pmultigrid.PMultigridCG`
iterates. :func:`solver_named` turns a configuration string into one of them.
"""

from __future__ import annotations

import ctypes
import os
import sys
import time
import weakref
from dataclasses import dataclass
from importlib.util import find_spec
from pathlib import Path
from typing import Protocol

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis

from pipeline.fem.pmultigrid import PMultigridCG
from pipeline.fem.settings import FACTOR_METHODS, SOLVERS
from pipeline.validation import InputError, check_choice


def pardiso_available() -> bool:
    """True when pypardiso (MKL PARDISO, with MKL from the ``mkl`` wheel) can be imported."""
    return find_spec("pypardiso") is not None


def cholmod_available() -> bool:
    """True when scikit-sparse (CHOLMOD) can be imported."""
    return find_spec("sksparse") is not None


def cholespy_available() -> bool:
    """True when cholespy (CHOLMOD in a self-contained wheel) can be imported."""
    return find_spec("cholespy") is not None


def sparse_cholesky() -> str | None:
    """The sparse Cholesky that "auto" uses: "pardiso", "cholmod", "cholespy" or None
    (none installed)."""
    if pardiso_available():
        return "pardiso"
    if cholmod_available():
        return "cholmod"
    return "cholespy" if cholespy_available() else None


PARDISO_NOT_SPD = -4
"""PARDISO's error for a zero or negative pivot: the matrix is not positive definite."""


def _point_pypardiso_at_mkl() -> None:
    """Name the environment's MKL runtime to pypardiso (``PYPARDISO_MKL_RT``), unless set.

    Without it, every pypardiso solver object (and its import) looks for ``mkl_rt`` with
    ``find_library`` and then a recursive glob over the environment: 0.3 s each. The
    ``mkl`` wheel puts the library in the environment's ``lib`` folder.
    """
    if "PYPARDISO_MKL_RT" not in os.environ:
        found = sorted(Path(sys.prefix, "lib").glob("libmkl_rt.so*"))
        if found:
            os.environ["PYPARDISO_MKL_RT"] = str(found[0])


SERIAL_BELOW_NNZ = 700_000
"""Upper triangles of fewer non-zeros are factorised and solved on one thread
(:class:`_Pardiso`)."""


class _Pardiso:
    """One MKL PARDISO Cholesky (``mtype = 2``) of an upper triangle, called directly.

    pypardiso only loads the library (and its handle ``pt``): its own calls copy the
    matrix's index arrays (1-based) on every solve and keep a copy of the matrix to
    compare each right-hand side's with. Here the zero-based CSR arrays are passed as
    they are (``iparm 35``), once factorised only solves (phase 33) follow.

    Threads. A matrix whose upper triangle has fewer than :data:`SERIAL_BELOW_NNZ`
    non-zeros is analysed, factorised and solved on one thread (MKL's thread-local
    setting, put back after each call; every phase on the same threads: a factorisation
    on fewer threads than its analysis crashes MKL), larger ones on the threads MKL is
    given. Measured (2-core machine): the demo's 2D gear models (22k and 44k unknowns,
    0.25M and 0.50M non-zeros, 52 and 124 MFLOP by PARDISO's count) factorise in
    0.02-0.06 s after a 0.1-0.25 s analysis; on two threads the 44k model's
    factorisation and 60 block solves took 0.20-0.27 s and 0.39-0.50 s of CPU, and the
    second thread then spun for MKL's OpenMP block time (200 ms, Intel's
    ``KMP_BLOCKTIME``: 0.2 s of CPU after the last call), taken from the core that draws
    ``gearpipe run``'s figures meanwhile; on one, 0.23-0.27 s and 0.27-0.32 s of CPU,
    nothing after. The z 30 helical gear of ``bench_fe3d`` (26k unknowns in 3D, 0.91M
    non-zeros, 3539 MFLOP) factorises in 0.28-0.30 s on two threads against 0.40-0.42 s
    on one, and solves in 0.12-0.14 against 0.21-0.23 s: it keeps them. One thread also
    makes the small tables bit-reproducible (MKL's parallel reductions round differently
    from run to run).
    """

    def __init__(self, U: sp.csr_matrix):
        _point_pypardiso_at_mkl()
        from pypardiso import PyPardisoSolver

        if U.nnz >= 2**31:
            raise InputError(f"PARDISO's 32-bit interface takes < 2^31 non-zeros, the "
                             f"matrix has {U.nnz}")
        self._lib = PyPardisoSolver(mtype=2)  # the library and the handle pt only
        self.n = U.shape[0]
        self.data = np.ascontiguousarray(U.data, dtype=np.float64)
        self.indptr = np.ascontiguousarray(U.indptr, dtype=np.int32)
        self.indices = np.ascontiguousarray(U.indices, dtype=np.int32)
        self.iparm = np.zeros(64, dtype=np.int32)
        self.iparm[0] = 1  # use the parameters set here, not PARDISO's defaults
        self.iparm[1] = 2  # METIS nested dissection (bench_sparse_solvers: beats min. degree)
        self.iparm[9] = 8  # pivot perturbation 1e-8 (PARDISO's value for symmetric types)
        self.iparm[34] = 1  # zero-based indices
        self.error = 0
        self.serial = U.nnz < SERIAL_BELOW_NNZ  # every call on one thread (docstring)

    def call(self, phase: int, b: np.ndarray, perm: np.ndarray | None = None) -> np.ndarray:
        """PARDISO's ``phase`` on the right-hand sides ``b`` (n,) or (n, k); returns x
        (``perm``: PARDISO's int32 ``perm`` array, e.g. the Schur rows of ``iparm 36``)."""
        b = np.asfortranarray(b, dtype=np.float64)
        x = np.zeros_like(b)
        err = ctypes.c_int32(0)
        i32 = ctypes.POINTER(ctypes.c_int32)
        f64 = ctypes.POINTER(ctypes.c_double)
        lib = self._lib
        serial = self.serial
        before = lib.libmkl.MKL_Set_Num_Threads_Local(1) if serial else 0
        try:
            lib._mkl_pardiso(
                lib.pt.ctypes.data_as(ctypes.POINTER(lib._pt_type[0])),
                ctypes.byref(ctypes.c_int32(1)), ctypes.byref(ctypes.c_int32(1)),  # maxfct, mnum
                ctypes.byref(ctypes.c_int32(2)), ctypes.byref(ctypes.c_int32(phase)),
                ctypes.byref(ctypes.c_int32(self.n)), self.data.ctypes.data_as(f64),
                self.indptr.ctypes.data_as(i32), self.indices.ctypes.data_as(i32),
                ctypes.POINTER(ctypes.c_int32)() if perm is None else perm.ctypes.data_as(i32),
                ctypes.byref(ctypes.c_int32(1 if b.ndim == 1 else b.shape[1])),
                self.iparm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(0)),  # msglvl
                b.ctypes.data_as(f64), x.ctypes.data_as(f64), ctypes.byref(err))
        finally:
            if serial:  # back to the thread's setting before (0: the global one)
                lib.libmkl.MKL_Set_Num_Threads_Local(before)
        self.error = err.value
        return x

    def release(self) -> None:
        """Free PARDISO's memory (phase -1)."""
        self.call(-1, np.zeros(1))


def _return_free_heap() -> None:
    """Hand the C heap's free pages back to the system (glibc's ``malloc_trim``) before a
    factorisation takes its peak memory.

    Meshing and assembly leave hundreds of MB of freed but mapped small blocks: on the
    traction gear of Yang et al. (2026) the resident memory before its factorisation went
    from 0.55 to 0.28 GiB. A no-op where the C library has no ``malloc_trim``.
    """
    try:  # the process's own symbols (Windows has no such handle: TypeError)
        trim = ctypes.CDLL(None).malloc_trim
    except (AttributeError, OSError, TypeError):
        return
    trim(0)


def _pardiso_upper(A: sp.spmatrix, upper: bool) -> _Pardiso:
    """A PARDISO instance on the upper triangle of ``A`` (``A`` is that triangle if
    ``upper``), rows sorted and checked non-empty."""
    U = A.tocsr() if upper else sp.triu(A, format="csr")  # PARDISO's storage: upper by rows
    U.sort_indices()
    if not np.diff(U.indptr).all():  # PARDISO would crash on an empty row
        raise RuntimeError("PARDISO's Cholesky: the matrix has an empty row, so it is not "
                           "positive definite (a DOF in no element?)")
    return _Pardiso(U)


def _check_pardiso(solver: _Pardiso) -> None:
    """Release ``solver`` and raise if its last call failed."""
    if solver.error:
        err = solver.error
        solver.release()
        if err == PARDISO_NOT_SPD:
            raise RuntimeError("PARDISO's Cholesky met a zero or negative pivot: the matrix "
                               "is not positive definite (a body without enough supports?)")
        raise RuntimeError(f"PARDISO failed with error {err}")


def _pardiso_factor(A: sp.spmatrix, upper: bool = False):
    solver = _pardiso_upper(A, upper)
    del A  # the factor needs only its own arrays (solver.data, .indptr, .indices)
    _return_free_heap()
    solver.call(12, np.zeros(solver.n))  # analysis and numerical factorisation
    _check_pardiso(solver)

    def solve(b: np.ndarray) -> np.ndarray:
        x = solver.call(33, b)  # column-major, as PARDISO writes it (no copy)
        if solver.error:
            raise RuntimeError(f"PARDISO's solve failed with error {solver.error}")
        return x

    # PARDISO keeps its factor outside Python: free it with the last reference to solve
    weakref.finalize(solve, solver.release)
    return solve


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
    method : "pardiso", "cholmod", "cholespy" or "splu".
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
    """Factorise once (:func:`factorize_spd`); ``method`` "auto", "pardiso", "cholmod",
    "cholespy" or "splu"."""

    method: str = "auto"

    def __post_init__(self) -> None:
        check_choice("solver.method", self.method, FACTOR_METHODS)

    def __call__(self, A: sp.spmatrix, basis: Basis | None = None,
                 free: np.ndarray | None = None) -> SPDFactor:
        return factorize_spd(A, self.method)

    @property
    def upper(self) -> bool:
        """True when the method takes the upper triangle only (PARDISO): then the caller
        can hand it that alone (:meth:`factorize_upper`) and never build the full block."""
        method = sparse_cholesky() or "splu" if self.method == "auto" else self.method
        return method == "pardiso"

    def factorize_upper(self, U: sp.spmatrix) -> SPDFactor:
        """Factorise the SPD matrix whose upper triangle (diagonal included) is ``U``."""
        return factorize_spd(U, self.method, upper=True)


def solver_named(name: str = "auto", dim: int = 3) -> Solver:
    """The solver a configuration string names (:data:`SOLVERS`).

    "auto" is the sparse Cholesky when one is installed; without it SuperLU in 2D
    (fast there) and the p-multigrid CG in 3D (SuperLU fills badly on 3D P2 elasticity).
    """
    check_choice("solver.method", name, SOLVERS)
    if name == "pmg-cg" or (name == "auto" and dim == 3 and sparse_cholesky() is None):
        return PMultigridCG()
    return DirectSolver(name)


def _symmetric(U: sp.spmatrix) -> sp.csr_matrix:
    """The symmetric matrix whose upper triangle (diagonal included) is that of ``U``."""
    U = sp.triu(U, format="csr")
    return U + sp.triu(U, k=1, format="csr").T


def factorize_spd(A: sp.spmatrix, method: str = "auto", upper: bool = False) -> SPDFactor:
    """Factorise a sparse SPD matrix once for many solves.

    Parameters
    ----------
    A : (n, n) sparse symmetric positive definite matrix, or its upper triangle
        (diagonal included) if ``upper``.
    method : "auto" (MKL PARDISO's Cholesky if pypardiso is installed, else
        scikit-sparse's CHOLMOD, else cholespy's, else SuperLU), "pardiso", "cholmod",
        "cholespy" or "splu".
    upper : ``A`` holds the upper triangle only (PARDISO takes it as it is; the other
        methods get the full matrix rebuilt from it).
    """
    check_choice("solver.method", method, FACTOR_METHODS)
    if method == "auto":
        method = sparse_cholesky() or "splu"
    if method == "pardiso" and not pardiso_available():
        raise InputError("solver.method = 'pardiso' but pypardiso is not installed")
    if method == "cholmod" and not cholmod_available():
        raise InputError("solver.method = 'cholmod' but scikit-sparse is not installed")
    if method == "cholespy" and not cholespy_available():
        raise InputError("solver.method = 'cholespy' but cholespy is not installed")
    n = A.shape[0]
    t0 = time.perf_counter()
    if upper and method != "pardiso":
        A = _symmetric(A)
    if method == "pardiso":
        solve = _pardiso_factor(A, upper)
    elif method == "cholmod":
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


def schur_complement(U: sp.spmatrix, interface: np.ndarray, method: str = "auto"
                     ) -> np.ndarray:
    """Dense Schur complement ``S = K_gg - K_gi K_ii^-1 K_ig`` of an SPD matrix K on the
    unknowns ``interface`` (g; i the others), from K's upper triangle ``U``.

    Parameters
    ----------
    U : (n, n) sparse upper triangle of K, diagonal included.
    interface : (n,) boolean mask of the unknowns kept; S is ordered as they are.
    method : as :func:`factorize_spd`. PARDISO computes S within one partial
        factorisation (``iparm 36 = 1``: the interface eliminated last, S returned dense);
        the others factorise K_ii and solve for K_ig's columns in blocks.

    Returns
    -------
    (m, m) symmetric positive definite array, m = ``interface.sum()``.
    """
    check_choice("solver.method", method, FACTOR_METHODS)
    g = np.asarray(interface, dtype=bool)
    if g.shape != (U.shape[0],) or not g.any() or g.all():
        raise InputError(f"interface: a mask of the matrix's {U.shape[0]} unknowns, with some "
                         "but not all of them")
    method = sparse_cholesky() or "splu" if method == "auto" else method
    m = int(g.sum())
    if method == "pardiso" and pardiso_available():
        solver = _pardiso_upper(U, upper=True)
        solver.iparm[35] = 1  # Schur complement, returned dense in x
        _return_free_heap()
        S = solver.call(12, np.zeros(m * m), perm=g.astype(np.int32))
        _check_pardiso(solver)
        solver.release()
        return S.reshape(m, m)
    K = _symmetric(U)
    inner = ~g
    Kig = K[inner][:, g]
    S = K[g][:, g].toarray()
    factor = factorize_spd(K[inner][:, inner], method)
    for a in range(0, m, 256):
        S[:, a:a + 256] -= Kig.T @ factor.solve(Kig[:, a:a + 256].toarray())
    return 0.5 * (S + S.T)
