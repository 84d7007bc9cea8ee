"""Benchmark: sparse direct solvers side by side on the project's 3D stiffness matrices.

Matrices (captured as the project's builds hand them to their solver: the build's
``solver_named`` is replaced for the call by a recorder that keeps the matrix and the
first block of right-hand sides, then stops the build):

* ``shaft``: the free stiffness of the 3D P2 shaft superelement of
  ``workflows/configs/shaft_straddle_pinion.toml`` (pinion shaft, default ``[fe3d]``
  settings; :mod:`pipeline.shaft.fe3d`) and its 6 (n - 1) balanced load cases.
* ``tooth``: the free stiffness of the pinion of ``bench_fe3d.py``'s helical pair (z 30,
  m_n 3 mm, b 12 mm, whole gear, refinement 1; :mod:`pipeline.contact.fe3d_table`) and
  its first block of flank-patch load cases.

Candidates (each in a fresh process, so that the figures are cold and the memory is the
factorisation's own): cholespy (CHOLMOD, supernodal, reference BLAS; the project's
fallback), scipy's SuperLU (symmetric mode, MMD on A^T + A), MKL PARDISO through
pypardiso (real SPD, ``mtype = 2``; orderings METIS nested dissection and minimum degree;
1 and 2 threads) and, when installed, CHOLMOD through cvxopt (OpenBLAS), sksparse-minimal
(CHOLMOD, reference BLAS), QDLDL (LDL^T, AMD) and MUMPS (python-mumps). A candidate that
is not installed, or fails to import, is listed with the reason.

Per matrix, candidate and repeat: the factorisation's wall time (s), the solve of the
block (s, and per right-hand side), the process's extra peak resident memory over the
factorisation and solve (MiB: the peak, restarted before the factorisation, minus the
resident memory then, when the matrix, the right-hand sides and the library are loaded),
the cores used (CPU time over wall time of the factorisation: 1.0 is one busy core; below
that the process waited for a core), and the answer's agreement:
``||X - X_ref||_F / ||X_ref||_F`` against cholespy and the residual
``||A X - B||_F / ||B||_F``. Prints a table and writes
``results/benchmarks/sparse_solvers.json``. Timings are printed, not asserted (the machine
is shared); the minimum over the repeats is the figure to compare.

Run: ``python workflows/benchmarks/bench_sparse_solvers.py [--repeats N] [--large]``
(``--large`` adds the pinion refined to 1.9, 112k unknowns, with cholespy, PARDISO
and cvxopt only).
"""

from __future__ import annotations

import json
import math
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import scipy.sparse as sp

HERE = Path(__file__).resolve().parents[1]
REFERENCE = "cholespy"

# name: (package, ordering, threads); the factorisations are in _FACTOR below. The threads
# are set for PARDISO; the others run on one (reference BLAS, SuperLU, QDLDL; cvxopt's
# bundled OpenBLAS reports one thread to threadpoolctl).
CANDIDATES = {
    "cholespy": ("cholespy", "CHOLMOD default (AMD)", 1),
    "splu": ("scipy", "MMD on A^T + A", 1),
    "pardiso-metis-1": ("pypardiso", "METIS nested dissection", 1),
    "pardiso-metis-2": ("pypardiso", "METIS nested dissection", 2),
    "pardiso-md-1": ("pypardiso", "minimum degree", 1),
    "cvxopt-cholmod": ("cvxopt", "CHOLMOD default (AMD)", 1),
    "sksparse-minimal": ("sksparse_minimal", "CHOLMOD default (AMD)", 1),
    "qdldl": ("qdldl", "AMD", 1),
    "python-mumps": ("mumps", "MUMPS default (AMD/METIS)", 1),
}


# -- the matrices ----------------------------------------------------------------------

class _Captured(Exception):
    """Stops a build once its matrix and first right-hand sides are recorded."""


class _Recorder:
    """A :class:`pipeline.fem.solvers.Solver` that records instead of solving."""

    def __init__(self) -> None:
        self.A: sp.csc_matrix | None = None
        self.B: np.ndarray | None = None

    def __call__(self, A, basis=None, free=None):
        self.A = sp.csc_matrix(A)
        recorder = self

        class _Factor:
            method, factor_seconds, iterations = "recorder", 0.0, 0

            def solve(self, b):
                recorder.B = np.array(b, dtype=float)
                raise _Captured

        return _Factor()


@contextmanager
def _recording(module):
    """``module.solver_named`` returns a recorder inside the block."""
    recorder, original = _Recorder(), module.solver_named
    module.solver_named = lambda *args, **kwargs: recorder
    try:
        yield recorder
    finally:
        module.solver_named = original


def _capture(module, build: Callable) -> tuple[sp.csc_matrix, np.ndarray]:
    from pipeline.cache.folder import Cache

    with _recording(module) as rec, tempfile.TemporaryDirectory() as folder:
        try:
            build(Cache(folder))
        except _Captured:
            pass
    if rec.A is None or rec.B is None:
        raise RuntimeError("the build did not reach its solver")
    return rec.A, rec.B


def shaft_matrix() -> tuple[sp.csc_matrix, np.ndarray]:
    """The straddle-mounted pinion shaft's free stiffness (N/m) and its load cases (N)."""
    import pipeline.fem.solvers as solvers
    from pipeline.config import load_gearbox
    from pipeline.shaft.fe3d import Fe3dShaft

    layout = load_gearbox(HERE / "configs" / "shaft_straddle_pinion.toml").shafts["pinion"][1]
    return _capture(solvers, lambda cache: Fe3dShaft(layout, cache=cache))


def tooth_matrix(refinement: float = 1.0) -> tuple[sp.csc_matrix, np.ndarray]:
    """bench_fe3d's z 30 helical pinion (whole gear): free stiffness and first load block."""
    import pipeline.contact.fe3d_table as table
    from pipeline.contact import FE3DCompliance, FE3DSettings

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_fe3d import _small_pair

    settings = FE3DSettings(refinement=refinement, points=8)
    return _capture(table, lambda cache: FE3DCompliance.build(_small_pair(), settings,
                                                              cache=cache))


MATRICES = {"shaft": shaft_matrix, "tooth": tooth_matrix}
LARGE = {"tooth_refinement_1.9": lambda: tooth_matrix(1.9)}
"""``--large``: the pinion's mesh refined to about the size of the largest 3D tables
(112k unknowns), with the candidates that factorise it in seconds."""
LARGE_CANDIDATES = ("cholespy", "pardiso-metis-1", "pardiso-metis-2", "cvxopt-cholmod")


# -- the candidates (run in a child process) ---------------------------------------------

def _cholespy(A):
    from cholespy import CholeskySolverD, MatrixType

    s = CholeskySolverD(A.shape[0], A.indptr.astype(np.int32), A.indices.astype(np.int32),
                        A.data, MatrixType.CSC)

    def solve(b):
        b = np.ascontiguousarray(b)
        x = np.empty_like(b)
        s.solve(b, x)
        return x

    return solve, {}


def _splu(A):
    import scipy.sparse.linalg as spla

    lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})
    return lu.solve, {"nnz_factor": int(lu.L.nnz + lu.U.nnz)}


def _pardiso(ordering: int, threads: int):
    def factor(A):
        from pypardiso import PyPardisoSolver

        solver = PyPardisoSolver(mtype=2)  # real symmetric positive definite: Cholesky
        solver.libmkl.MKL_Set_Num_Threads(threads)
        solver.set_iparm(1, 1)  # the parameters below, not PARDISO's defaults
        solver.set_iparm(2, ordering)  # 0 minimum degree, 2 METIS
        solver.set_iparm(10, 8)
        solver.set_iparm(18, -1)  # report the factor's non-zeros
        U = sp.triu(A, format="csr")  # PARDISO's symmetric storage: upper triangle, by rows
        U.sort_indices()
        solver.factorize(U)
        info = {"nnz_factor": int(solver.get_iparm(18)),
                "pardiso_peak_MiB": max(solver.get_iparm(15),
                                        solver.get_iparm(16) + solver.get_iparm(17)) / 1024}
        return (lambda b: solver.solve(U, b)), info

    return factor


def _cvxopt(A):
    import cvxopt
    import cvxopt.cholmod as cholmod

    L = sp.tril(A, format="csc")
    L.sort_indices()
    cols = np.repeat(np.arange(L.shape[1]), np.diff(L.indptr))
    M = cvxopt.spmatrix(L.data, L.indices.astype(int), cols.astype(int), L.shape)
    cholmod.options["supernodal"] = 2
    F = cholmod.symbolic(M)
    cholmod.numeric(M, F)

    def solve(b):
        X = cvxopt.matrix(np.asfortranarray(b))
        cholmod.solve(F, X)  # one right-hand side at a time inside cvxopt
        return np.array(X)

    return solve, {}


def _sksparse_minimal(A):
    from sksparse_minimal import SparseCholesky

    factor = SparseCholesky(A)
    return (lambda b: factor.solve_A(np.ascontiguousarray(b))), {}


def _qdldl(A):
    import qdldl

    s = qdldl.Solver(sp.triu(A, format="csc"))
    return (lambda b: np.column_stack([s.solve(c) for c in b.T])), {}


def _mumps(A):
    import mumps

    ctx = mumps.Context()
    ctx.set_matrix(A, symmetric=True)
    ctx.factor()
    return ctx.solve, {}


_FACTOR = {"cholespy": _cholespy, "splu": _splu,
           "pardiso-metis-1": _pardiso(2, 1), "pardiso-metis-2": _pardiso(2, 2),
           "pardiso-md-1": _pardiso(0, 1), "cvxopt-cholmod": _cvxopt,
           "sksparse-minimal": _sksparse_minimal, "qdldl": _qdldl,
           "python-mumps": _mumps}


def _reset_peak_rss() -> None:
    """Start the process's peak resident memory afresh from its current value (Linux)."""
    try:
        Path("/proc/self/clear_refs").write_text("5")
    except OSError:
        pass  # elsewhere the peak keeps counting from the process's start


def _peak_rss_MiB() -> float:
    """The process's peak resident memory (MiB): ``VmHWM`` (Linux), else ``ru_maxrss``."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return float(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def run_one(name: str, matrix: Path, out: Path) -> dict:
    """Factorise and solve in this process; writes X to ``out`` (.npy), returns figures."""
    import importlib

    A = sp.load_npz(matrix).tocsc()
    A.sort_indices()
    B = np.load(matrix.with_suffix(".rhs.npy"))
    t0 = time.perf_counter()
    importlib.import_module(CANDIDATES[name][0])
    t_import = time.perf_counter() - t0
    _reset_peak_rss()  # (a forked child starts with its parent's peak)
    rss0 = _peak_rss_MiB()
    t0, c0 = time.perf_counter(), _cpu()
    solve, info = _FACTOR[name](A)
    t_factor, c_factor = time.perf_counter() - t0, _cpu() - c0
    t0 = time.perf_counter()
    X = np.asarray(solve(B))
    t_solve = time.perf_counter() - t0
    rss = _peak_rss_MiB()
    np.save(out, X)
    residual = np.linalg.norm(A @ X - B) / np.linalg.norm(B)
    return {"import_s": t_import, "factor_s": t_factor, "solve_s": t_solve,
            "cores_used_factor": c_factor / t_factor, "extra_peak_rss_MiB": rss - rss0,
            "residual": float(residual), **info}


# -- the parent --------------------------------------------------------------------------

def _child(name: str, matrix: Path, out: Path) -> dict:
    run = subprocess.run([sys.executable, __file__, "--one", name, str(matrix), str(out)],
                         capture_output=True, text=True, timeout=900, check=False)
    if run.returncode != 0:
        lines = (run.stderr.strip() or run.stdout.strip() or "no output").splitlines()
        return {"error": lines[-1][:200]}
    return json.loads(run.stdout.strip().splitlines()[-1])


def _available(name: str) -> str | None:
    """None when the candidate's package imports, else why not."""
    run = subprocess.run([sys.executable, "-c", f"import {CANDIDATES[name][0]}"],
                         capture_output=True, text=True, timeout=120, check=False)
    if run.returncode == 0:
        return None
    return (run.stderr.strip().splitlines() or ["import failed"])[-1][:200]


def _versions() -> dict:
    from importlib import metadata

    out = {}
    for dist in ("numpy", "scipy", "cholespy", "pypardiso", "mkl", "cvxopt",
                 "sksparse-minimal", "qdldl", "python-mumps"):
        try:
            out[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            out[dist] = "not installed"
    return out


def bench_matrix(label: str, A: sp.csc_matrix, B: np.ndarray, folder: Path,
                 repeats: int, names: tuple[str, ...] = tuple(CANDIDATES)) -> dict:
    """The candidates ``names`` (cholespy first), ``repeats`` times each, on ``A`` with
    right-hand sides ``B``."""
    path = folder / f"{label}.npz"
    sp.save_npz(path, A)
    np.save(path.with_suffix(".rhs.npy"), B)
    rows, ref = [], None
    for name in names:
        package, ordering, threads = CANDIDATES[name]
        row = {"solver": name, "package": package, "ordering": ordering,
               "threads_set": threads}
        why = _available(name)
        if why is not None:
            rows.append({**row, "unavailable": why})
            continue
        runs = [_child(name, path, folder / f"{label}-{name}.npy") for _ in range(repeats)]
        if any("error" in r for r in runs):
            rows.append({**row, "error": next(r["error"] for r in runs if "error" in r)})
            continue
        X = np.load(folder / f"{label}-{name}.npy")
        if name == REFERENCE:
            ref = X
        row["relative_difference_to_cholespy"] = (
            float(np.linalg.norm(X - ref) / np.linalg.norm(ref)) if ref is not None else None)
        row["runs"] = runs
        for key in ("factor_s", "solve_s"):
            row[f"{key}_min"] = min(r[key] for r in runs)
            row[f"{key}_max"] = max(r[key] for r in runs)
        rows.append(row)
    return {"matrix": label, "unknowns": A.shape[0], "nnz": int(A.nnz),
            "right_hand_sides": B.shape[1], "solvers": rows}


def _print(m: dict) -> None:
    print(f"\n{m['matrix']}: {m['unknowns']} unknowns, {m['nnz']} non-zeros, "
          f"{m['right_hand_sides']} right-hand sides in the block")
    print(f"  {'solver':18s} {'ordering':26s} {'factor s':>13s} {'solve s':>13s} "
          f"{'ms/rhs':>7s} {'MiB':>6s} {'cores':>5s} {'rel. diff':>9s} {'residual':>9s}")
    for r in m["solvers"]:
        if "runs" not in r:
            print(f"  {r['solver']:18s} {r.get('unavailable') or r.get('error')}")
            continue
        last = r["runs"][-1]
        diff = r["relative_difference_to_cholespy"]
        print(f"  {r['solver']:18s} {r['ordering']:26s} "
              f"{r['factor_s_min']:5.2f}-{r['factor_s_max']:<5.2f}  "
              f"{r['solve_s_min']:5.2f}-{r['solve_s_max']:<5.2f}  "
              f"{1e3 * r['solve_s_min'] / m['right_hand_sides']:7.1f} "
              f"{last['extra_peak_rss_MiB']:6.0f} {last['cores_used_factor']:5.2f} "
              f"{diff if diff is not None else math.nan:9.1e} {last['residual']:9.1e}")


def main(repeats: int = 2, large: bool = False) -> dict:
    import os

    from pipeline.io import write_json

    out = {"repeats": repeats, "load_average_1_min_at_start": os.getloadavg()[0],
           "versions": _versions(), "matrices": []}
    cases = [(label, make, tuple(CANDIDATES)) for label, make in MATRICES.items()]
    if large:
        cases += [(label, make, LARGE_CANDIDATES) for label, make in LARGE.items()]
    with tempfile.TemporaryDirectory() as tmp:
        for label, make, names in cases:
            t0 = time.perf_counter()
            A, B = make()
            print(f"{label}: captured in {time.perf_counter() - t0:.1f} s", flush=True)
            out["matrices"].append(bench_matrix(label, A, B, Path(tmp), repeats, names))
            _print(out["matrices"][-1])
    out["load_average_1_min_at_end"] = os.getloadavg()[0]
    write_json(Path("results/benchmarks/sparse_solvers.json"), out)
    return out


if __name__ == "__main__":
    if sys.argv[1:2] == ["--one"]:
        print(json.dumps(run_one(sys.argv[2], Path(sys.argv[3]), Path(sys.argv[4]))))
    else:
        args = sys.argv[1:]
        main(int(args[args.index("--repeats") + 1]) if "--repeats" in args else 2,
             "--large" in args)
