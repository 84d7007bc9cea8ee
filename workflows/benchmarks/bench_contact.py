"""Benchmark: loaded tooth contact solve per mesh position (targets from issue 3).

Targets: < 5 ms per mesh position for a spur pair (3 tooth pairs x 5 slices),
< 50 ms for a helical pair (30 slices, ~90 loaded candidate points).

Inputs are one mesh cycle of the spur pair of the assembly-error paper (340 N m)
and the helical pair of Yang et al. (2026) (20 233 N m on the gear): contact
points, curvature radii and contact lines from :class:`pipeline.geometry.GearPair`;
initial separations
from linear tip relief and lead crowning. The compliance is a stand-in for the
FE influence coefficients that will feed the solver: per tooth pair a dense
block coupling the slices along the face with an exponential kernel (positive
definite, decay length b/4), scaled so that a uniform load sees the usual
single-pair stiffness 14 N/(mm um) per unit face width, softer at both ends of
the path. Hertz local approach by Yang et al. (2026), eq. (24).

Side by side in one run: warm-started sweep (each position from the previous),
cold starts, linear vs Hertz, and scipy's SLSQP on the same linear QP for a few
positions (accuracy cross-check and speed ratio).

Second part, the full pipeline per mesh position with the analytical slice
compliance (:class:`pipeline.contact.source.SliceCompliance`, classical tooth
model, Yang et al. (2026), eq. 24 local contact, tip relief + crowning):
:func:`pipeline.contact.ltca.loaded_mesh_cycle` timed end to end, i.e. candidate
points, G from the potential-energy method, separations, Hertz geometry and the solve.
Prints the figures and writes results/benchmarks/contact.json.
"""

from __future__ import annotations

import math
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

from pipeline.contact import HertzLineContact, solve_contact, solve_positions
from pipeline.geometry import GearPair, GearSpec, Material
from pipeline.io import write_json
from pipeline.provenance import library_versions

STEEL = Material(2.06e11, 0.3, 7850.0)
K_PER_WIDTH = 1.4e10  # single-pair mesh stiffness per unit face width, N/m^2 (14 N/(mm um))


def spur_pair() -> GearPair:
    d = math.radians
    return GearPair(*(GearSpec(teeth=50, module=3e-3, pressure_angle=d(20), face_width=0.02,
                               bore_radius=0.021, material=STEEL, name=n) for n in ("p", "g")))


def helical_pair() -> GearPair:
    kw = dict(module=7.35e-3, pressure_angle=math.radians(20), helix_angle=math.radians(4.0),
              addendum_coef=1.2, dedendum_coef=1.55, face_width=0.13, material=STEEL)
    return GearPair(GearSpec(teeth=31, hand="right", profile_shift=0.27807, bore_radius=0.045,
                             name="p", **kw),
                    GearSpec(teeth=104, hand="left", profile_shift=-0.59026, bore_radius=0.15,
                             name="g", **kw))


def mesh_cycle_case(pair: GearPair, n_slices: int, n_positions: int, load: float,
                    tip_relief: float = 15e-6, crowning: float = 5e-6):
    """G (m, n, n) m/N, eps (m, n) m, HertzLineContact (m, n), for one mesh cycle."""
    b = pair.face_width
    tb = math.tan(pair.pinion.base_helix_angle)
    z = (np.arange(n_slices) + 0.5) * b / n_slices
    s_pair, _ = pair.pair_positions(pair.mesh_cycle(n_positions))  # (m, K)
    s = s_pair[:, :, None] + z[None, None, :] * tb  # (m, K, N)
    m, K, N = s.shape
    inside = (s >= pair.s_start) & (s <= pair.s_end)
    g_a = pair.path_length
    xi = np.clip((s - pair.s_start) / g_a, 0.0, 1.0)  # 0..1 along the path
    la = 0.2
    eps = (tip_relief * (np.clip((la - xi) / la, 0, 1) + np.clip((xi - 1 + la) / la, 0, 1))
           + crowning * (2 * z / b - 1) ** 2)
    eps = np.where(inside, eps, np.inf).reshape(m, K * N)
    # per-slice compliance: pair stiffness softer at the path ends, exponential face coupling
    c_slice = n_slices / (K_PER_WIDTH * b * (1.0 - 0.35 * (2 * xi - 1) ** 2))  # (m, K, N)
    kern = np.exp(-np.abs(z[:, None] - z[None, :]) / (0.25 * b))
    kern = 0.5 * np.eye(N) + 0.5 * kern
    kern /= kern.sum(1).mean()
    G = np.zeros((m, K * N, K * N))
    for k in range(K):  # block-diagonal over tooth pairs (K <= 5)
        sl = slice(k * N, (k + 1) * N)
        c = np.sqrt(c_slice[:, k, :, None] * c_slice[:, k, None, :])
        G[:, sl, sl] = N * c * kern
    G[~np.isfinite(eps)[:, :, None] | ~np.isfinite(eps)[:, None, :]] = 0.0
    rho1, rho2 = pair.curvature_radii(np.clip(s, pair.s_start, pair.s_end))
    mod = pair.pinion.module
    hertz = HertzLineContact(
        slice_width=b / n_slices / math.cos(pair.pinion.base_helix_angle),
        radius_1=rho1.reshape(m, -1), radius_2=rho2.reshape(m, -1),
        depth_1=(0.9 - 0.4 * xi).reshape(m, -1) * mod,  # pinion: thick root first, tip last
        depth_2=(0.5 + 0.4 * xi).reshape(m, -1) * mod,
        material_1=STEEL, material_2=STEEL,
    )
    return G, eps, hertz, load


def best_of(fn, repeat: int = 5) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def slsqp(G: np.ndarray, eps: np.ndarray, P: float) -> np.ndarray:
    """Reference: scipy SLSQP on the same QP (candidate points only)."""
    idx = np.flatnonzero(np.isfinite(eps))
    Gc, ec = G[np.ix_(idx, idx)], eps[idx]
    sc = P / idx.size
    res = minimize(lambda f: 0.5 * sc * f @ Gc @ f + ec @ f, np.ones(idx.size),
                   jac=lambda f: sc * Gc @ f + ec, method="SLSQP",
                   bounds=[(0, None)] * idx.size,
                   constraints=[{"type": "eq", "fun": lambda f: f.sum() - idx.size,
                                 "jac": lambda f: np.ones_like(f)}],
                   options={"ftol": 1e-15, "maxiter": 1000})
    out = np.zeros(eps.size)
    out[idx] = res.x * sc
    return out


def run_case(name: str, pair: GearPair, n_slices: int, torque: float, n_positions: int) -> dict:
    P = torque / pair.gear.base_radius
    G, eps, hz, _ = mesh_cycle_case(pair, n_slices, n_positions, P)
    m = n_positions
    n_cand = np.isfinite(eps).sum(1)
    solve_positions(G[:3], eps[:3], P, [hz.for_position(k) for k in range(3)])  # warm-up
    t_lin = best_of(lambda: solve_positions(G, eps, P), 3) / m
    t_nl = best_of(lambda: solve_positions(G, eps, P, hz), 3) / m
    t_cold = best_of(lambda: solve_positions(G, eps, P, hz, warm_start=False), 3) / m
    sweep = solve_positions(G, eps, P, hz)
    lin = solve_positions(G, eps, P)
    tracemalloc.start()
    solve_positions(G, eps, P, hz)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    ks = list(range(0, m, max(1, m // 4)))[:4]
    t_ref, diff = 0.0, 0.0
    for k in ks:
        t = time.perf_counter()
        ref = slsqp(G[k], eps[k], P)
        t_ref += time.perf_counter() - t
        diff = max(diff, float(np.abs(ref - lin.loads[k]).max() / P))
    t_one = best_of(lambda: [solve_contact(G[k], eps[k], P) for k in ks], 3) / len(ks)
    return {
        "case": name,
        "positions": m,
        "candidate_points_per_position": [int(n_cand.min()), int(n_cand.max())],
        "loaded_points_per_position": [int(sweep.active.sum(1).min()),
                                       int(sweep.active.sum(1).max())],
        "total_load_N": P,
        "linear_per_position_s": t_lin,
        "hertz_per_position_s": t_nl,
        "hertz_cold_start_per_position_s": t_cold,
        "warm_start_speedup": t_cold / t_nl,
        "newton_iterations_max": int(sweep.newton_iterations.max()),
        "face_solves_mean": float(sweep.iterations.mean()),
        "max_residual_over_tolerance": float((sweep.residual / sweep.tolerance).max()),
        "max_load_balance_error_rel": float(np.abs(sweep.loads.sum(1) - P).max() / P),
        "mesh_stiffness_tangent_mean_N_per_m": float(sweep.mesh_stiffness_tangent.mean()),
        "hertz_lowers_stiffness_by": float(1 - sweep.mesh_stiffness_tangent.mean()
                                           / lin.mesh_stiffness_tangent.mean()),
        "slsqp_per_position_s": t_ref / len(ks),
        "active_set_linear_per_position_s": t_one,
        "speedup_vs_slsqp": t_ref / len(ks) / t_one,
        "slsqp_max_load_difference_rel_to_P": diff,
        "peak_python_memory_MB": peak / 1e6,
    }


def ltca_case(name: str, pair: GearPair, slices: int, torque: float, n_positions: int,
              coupling: float = 0.0) -> dict:
    """End-to-end loaded_mesh_cycle with the analytical slice compliance (per position)."""
    from pipeline.contact.ltca import loaded_mesh_cycle
    from pipeline.contact.separations import FlankModifications
    from pipeline.contact.source import SliceCompliance
    from pipeline.stiffness.mesh import PairModel
    from pipeline.stiffness.tooth import classical_tooth_model, hertz_compliance

    model = PairModel(pair, classical_tooth_model(pair.pinion), classical_tooth_model(pair.gear),
                      hertz_compliance(pair.pinion, pair.gear))
    src = SliceCompliance(model, slices=slices, coupling=coupling)
    L = 0.25 * pair.path_length
    mods = FlankModifications(15e-6, L, 15e-6, L, "parabolic", crowning=8e-6)
    P = torque / pair.gear.base_radius
    loaded_mesh_cycle(src, P, mods, positions=4)  # warm-up
    t_total = best_of(lambda: loaded_mesh_cycle(src, P, mods, positions=n_positions), 3)
    t_lin = best_of(lambda: loaded_mesh_cycle(src, P, mods, "linear", n_positions), 3)
    s0 = pair.mesh_cycle(n_positions)
    t_g = best_of(lambda: [src.matrix(float(s)) for s in s0], 3)
    cyc = loaded_mesh_cycle(src, P, mods, positions=n_positions)
    n = np.bincount(cyc.point_position)
    return {
        "case": name,
        "positions": n_positions,
        "candidate_points_per_position": [int(n.min()), int(n.max())],
        "total_load_N": P,
        "end_to_end_weber_per_position_s": t_total / n_positions,
        "end_to_end_linear_per_position_s": t_lin / n_positions,
        "compliance_matrix_per_position_s": t_g / n_positions,
        "newton_iterations_max": int(cyc.newton_iterations.max()),
        "max_residual_m": float(cyc.residual.max()),
        "max_residual_over_tolerance": float((cyc.residual / cyc.tolerance).max()),
        "mesh_stiffness_mean_N_per_m": float(cyc.mesh_stiffness.mean()),
        "max_unit_load_N_per_mm": float(cyc.max_unit_load.max() * 1e-3),
    }


def main(n_positions: int = 60) -> dict:
    spur = run_case("spur 50/50, 3 pairs x 5 slices", spur_pair(), 5, 340.0, n_positions)
    hel = run_case("helical 31/104, 30 slices", helical_pair(), 30, 20233.0, n_positions)
    e2e = [ltca_case("spur 50/50, slice compliance", spur_pair(), 1, 340.0, n_positions),
           ltca_case("helical 31/104, 30 slices", helical_pair(), 30, 20233.0, n_positions),
           ltca_case("helical 31/104, 30 slices, coupled (kappa 0.2)", helical_pair(), 30,
                     20233.0, n_positions, 0.2)]
    out = {"spur": spur, "helical": hel, "end_to_end_slice_compliance": e2e,
           "targets_per_position_s": {"spur": 0.005, "helical": 0.050},
           "versions": library_versions()}
    for r, target in ((spur, 5.0), (hel, 50.0)):
        print(f"{r['case']}: {r['candidate_points_per_position']} candidates, "
              f"{r['loaded_points_per_position']} loaded, P = {r['total_load_N']:.0f} N")
        print(f"  linear, warm sweep        {r['linear_per_position_s'] * 1e3:8.3f} ms/position")
        print(f"  Hertz,  warm sweep        {r['hertz_per_position_s'] * 1e3:8.3f} ms/position"
              f"   (target {target:g} ms)")
        print(f"  Hertz,  cold starts       {r['hertz_cold_start_per_position_s'] * 1e3:8.3f} "
              f"ms/position   (warm start {r['warm_start_speedup']:.2f} x faster)")
        print(f"  scipy SLSQP, same QP      {r['slsqp_per_position_s'] * 1e3:8.3f} ms/position"
              f"   (active set {r['speedup_vs_slsqp']:.0f} x faster, max load difference "
              f"{r['slsqp_max_load_difference_rel_to_P']:.1e} P)")
        print(f"  Newton iterations <= {r['newton_iterations_max']}, residual/tolerance <= "
              f"{r['max_residual_over_tolerance']:.2g}, load balance error "
              f"{r['max_load_balance_error_rel']:.1e}, peak memory "
              f"{r['peak_python_memory_MB']:.1f} MB")
        print(f"  Hertz lowers the mean tangent mesh stiffness by "
              f"{100 * r['hertz_lowers_stiffness_by']:.1f} %")
    for r, target in zip(e2e, (5.0, 50.0, 50.0), strict=True):
        print(f"{r['case']} (end to end, {r['candidate_points_per_position']} candidates): "
              f"Weber {r['end_to_end_weber_per_position_s'] * 1e3:.3f} ms/position, linear "
              f"{r['end_to_end_linear_per_position_s'] * 1e3:.3f} ms/position "
              f"(target {target:g} ms; G alone "
              f"{r['compliance_matrix_per_position_s'] * 1e3:.3f} ms), Newton <= "
              f"{r['newton_iterations_max']}, residual <= {r['max_residual_m']:.1e} m")
    path = write_json(Path("results/benchmarks/contact.json"), out)
    print(f"written to {path}")
    return out


if __name__ == "__main__":
    main(360 if "--full" in sys.argv else 60)
    sys.exit(0)
