"""Benchmark: FE influence matrices (targets from issue 3).

2D sector, the assembly-error paper gear (z 50, m 3 mm), 3 teeth, 40 flank points per tooth, the
refinement at which the single-tooth compliance is converged (< 0.1 % change to
the next refinement, tests/test_fem_influence.py): target < 30 s on 2 cores.
Side by side: one factorisation + all 120 right-hand sides vs a separate
factorise-and-solve per load (what solving each load on its own costs).
``--full`` adds the 3D helical sector (3 teeth, 20 x 20 flank grid): DOFs, peak
memory (resource.getrusage) and time; target < 10 min and < 16 GiB; and, side by side on
a coarser 3D sector, the sparse Cholesky against the p-multigrid CG (speed-up ratio).
Prints the figures and writes results/benchmarks/fe.json.
"""

from __future__ import annotations

import math
import resource
import sys
import time
from pathlib import Path

import numpy as np

from pipeline.cache.folder import Cache
from pipeline.fem.flank import active_radii, flank_points
from pipeline.fem.flank_grid import face_positions, flank_grid
from pipeline.fem.influence import constrained_dofs, influence_matrix
from pipeline.fem.linear_static import build_model
from pipeline.fem.mesh_settings import SectorSettings, SectorSettings3D
from pipeline.fem.patch_loads import patch_loads
from pipeline.fem.sector2d import sector_mesh_2d
from pipeline.fem.sector3d import section_area, sector_mesh_3d
from pipeline.fem.solvers import factorize_spd, solver_named, sparse_cholesky
from pipeline.geometry import GearSpec, Material
from pipeline.io import write_json
from pipeline.provenance import library_versions

STEEL = Material(2.0e11, 0.3, 7850.0)


def bench_2d(refinement: float = 2.0) -> dict:
    gear = GearSpec(teeth=50, module=3e-3, pressure_angle=math.radians(20), face_width=0.02,
                    bore_radius=0.021, material=STEEL)
    t0 = time.perf_counter()
    sec = sector_mesh_2d(gear, SectorSettings.for_gear(gear, 3, refinement), cache=Cache.off())
    t_mesh = time.perf_counter() - t0
    r = active_radii(gear, 40)
    pts = flank_points(gear, 3, np.repeat(np.arange(3), 40), np.tile(r, 3))
    t0 = time.perf_counter()
    G = influence_matrix(sec, pts)
    t_inf = time.perf_counter() - t0
    # separate solves: factorise and solve each load on its own
    model = build_model(sec.mesh, gear.material, kind="plane_strain")
    F = patch_loads(sec, pts, G.patch_half_width).toarray()
    fixed = np.zeros(model.n_dof, bool)
    fixed[constrained_dofs(sec, model)] = True
    free = np.flatnonzero(~fixed)
    K = model.stiffness[free][:, free]
    n_sep = 12  # time a subset, extrapolate to all loads
    t0 = time.perf_counter()
    for j in range(n_sep):
        factorize_spd(K).solve(F[free, j])
    t_sep = (time.perf_counter() - t0) / n_sep * F.shape[1]
    t_fac = G.timings["factor"] + G.timings["solve"]
    return {"case": "2D sector z50 m3 3 teeth x 40 points", "refinement": refinement,
            "dof": G.n_dof, "points": len(pts), "mesh_s": t_mesh, "influence_total_s": t_inf,
            "timings_s": G.timings, "solver": G.method,
            "one_factorisation_all_rhs_s": t_fac, "separate_solves_s_extrapolated": t_sep,
            "speedup": t_sep / t_fac, "symmetry_error": G.symmetry_error(),
            "target_s": 30.0, "meets_target": t_mesh + t_inf < 30.0}


def bench_helical_sector(refinement: float = 1.5, n_profile: int = 20, n_face: int = 20,
                         method: str = "auto", cache: bool = False) -> dict:
    """Benchmark figures of the 3D helical sector influence matrix (issue 3).

    Seed 001's gear (z 50, m_n 3 mm, alpha_n 20 deg, b 20 mm, bore 21 mm) made helical
    (beta 15 deg, right hand, an assumption: seed 001 is spur), 3 teeth, the loaded
    (right) flank of every tooth on an ``n_profile x n_face`` grid (active profile x
    face width), default patch half-width. Returns a dict of figures: DOFs, points,
    timings (s), solver, CG iterations, symmetry error, volume error, compliance
    ranges (m/N) and the rim coupling ratio.
    """
    gear = GearSpec(teeth=50, module=3e-3, pressure_angle=math.radians(20), face_width=0.02,
                    helix_angle=math.radians(15), hand="right", bore_radius=0.021,
                    material=STEEL, name="seed001-helical")
    settings = SectorSettings3D.for_gear(gear, teeth=3, refinement=refinement)
    t0 = time.perf_counter()
    sector = sector_mesh_3d(gear, settings, cache=cache)
    t_mesh = time.perf_counter() - t0
    c = 0.3 * gear.module
    pts = flank_grid(sector, [0, 1, 2], active_radii(gear, n_profile, margin=1.5 * c),
                     face_positions(sector.width, n_face, 1.5 * c))
    res = influence_matrix(sector, pts, solver=solver_named(method, dim=3))
    S = res.structural
    n1 = n_profile * n_face
    mid = n1 + (n_face // 2) * n_profile + n_profile - 1  # middle tooth, mid-face, tip
    exact = section_area(gear, 3, settings.profile_points, sector.inner_radius) * sector.width
    return {
        "case": f"3D helical sector z50 m3 b20 beta15, 3 teeth x {n_profile} x {n_face} points",
        "refinement": refinement, "dof": res.n_dof, "free_dof": res.n_free,
        "elements": int(sector.mesh.t.shape[1]), "points": len(pts),
        "mesh_s": t_mesh, "timings_s": res.timings, "solver": res.method,
        "cg_iterations": res.iterations, "symmetry_error": res.symmetry_error(),
        "volume_error": sector.volume() / exact - 1.0,
        "fe_diag_range_m_per_N": [float(np.diag(res.fe).min()), float(np.diag(res.fe).max())],
        "structural_diag_range_m_per_N": [float(np.diag(S).min()), float(np.diag(S).max())],
        "rim_coupling_ratio": float(np.abs(S[mid, :n1]).max() / S[mid, mid]),
        "patch_half_width_m": res.patch_half_width,
    }


def bench_3d() -> dict:
    t0 = time.perf_counter()
    res = bench_helical_sector()
    res["wall_s"] = time.perf_counter() - t0
    res["peak_rss_GiB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
    res["meets_target"] = res["wall_s"] < 600 and res["peak_rss_GiB"] < 16
    return res


def bench_3d_solvers(refinement: float = 0.6) -> dict:
    """Side by side on one coarser 3D sector: sparse Cholesky vs p-multigrid CG (a ratio)."""
    direct = sparse_cholesky()
    if direct is None:
        return {"skipped": "no sparse Cholesky installed"}
    runs = {m: bench_helical_sector(refinement=refinement, method=m) for m in (direct, "pmg-cg")}
    secs = {m: r["timings_s"]["factor"] + r["timings_s"]["solve"] for m, r in runs.items()}
    a, b = runs[direct]["structural_diag_range_m_per_N"], runs["pmg-cg"][
        "structural_diag_range_m_per_N"]
    return {"case": runs[direct]["case"], "refinement": refinement,
            "dof": runs[direct]["dof"], "points": runs[direct]["points"],
            f"{direct}_factor_and_solve_s": secs[direct],
            "pmg_cg_factor_and_solve_s": secs["pmg-cg"],
            "speedup": secs["pmg-cg"] / secs[direct],
            "max_rel_diff_structural_diag": float(max(abs(x / y - 1) for x, y in zip(a, b,
                                                                                    strict=True)))}


def main(full: bool = False) -> dict:
    out = {"fe_2d": bench_2d(), "versions": library_versions()}
    if full:
        out["fe_3d"] = bench_3d()
        out["fe_3d_solvers"] = bench_3d_solvers()
    for name, res in out.items():
        if name == "versions":
            continue
        print(name)
        for k, v in res.items():
            print(f"  {k:36s} {v:.4g}" if isinstance(v, float) else f"  {k:36s} {v}")
    write_json(Path("results/benchmarks/fe.json"), out)
    return out


if __name__ == "__main__":
    main("--full" in sys.argv[1:])
