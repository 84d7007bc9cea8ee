"""Benchmark: the 3D shaft superelement, cold and warm, on two straddle-mounted pinions.

Target: < 10 s cold (mesh, assembly, factorisation, condensation) on 2 cores.

* ``straddle_pinion_example``: the pinion shaft of
  ``workflows/configs/shaft_straddle_pinion.toml`` (35 mm journals, the pinion cut on its
  shaft: a 142.5 mm body 70-90 mm, integral seat; bearings at 40 and 140 mm, torque at
  0). The body is a disc: its seat's stations split only its surface, and the 35 mm
  journals' shoulder circles are refined (:mod:`pipeline.shaft.fe3d`).
* ``stepped_rigid_hub``: a 260 mm shaft, 35 mm at the coupling (torque held at 20 mm),
  40 mm bearing journals with bearings 200 mm apart (55 and 255 mm, rigid), a 45 mm body
  carrying the pinion (reference diameter 150 mm, z 50, m 3 mm) on a rigid hub 20 mm wide
  at mid-span.

Both with the default solver (``"auto"``: MKL PARDISO where installed,
:mod:`pipeline.fem.solvers`), and the straddle example once more with cholespy, the
earlier default, side by side in the same run (``straddle_pinion_example/cholespy``).

The load for the deflection printed: the demo pair's 340 N m, i.e. F_t = 2 T / d = 4533 N
and F_r = F_t tan 20 deg = 1650 N at the pitch point, moved to the axis (the tangential
force's lever is the torque).

Prints and writes to ``results/benchmarks/shaft_fe3d.json`` per case: the cold build
(empty temporary cache) with its parts (s), the warm build (read from the cache), the
unknowns and tetrahedra, the seat centre's compliance diagonal and deflection (from
``flexibility``), the bearing reactions (from ``solve``); and the import
time and the peak resident memory of the process. Timings are printed, not asserted (the
machine is shared).

Run: ``python workflows/benchmarks/bench_shaft_fe3d.py [refinement]``.
"""

from __future__ import annotations

import math
import resource
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]


def _layouts() -> dict:
    from pipeline.config import load_gearbox
    from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment

    example = load_gearbox(HERE / "configs" / "shaft_straddle_pinion.toml").shafts["pinion"][1]
    segments = (ShaftSegment(0.0, 0.04, 0.035), ShaftSegment(0.04, 0.07, 0.04),
                ShaftSegment(0.07, 0.23, 0.045), ShaftSegment(0.23, 0.26, 0.04))
    stepped = ShaftLayout(segments, 0.155, 0.02, (Bearing(0.055, axial=True), Bearing(0.255)),
                          0.02, hub="rigid", name="pinion.shaft")
    return {"straddle_pinion_example": example, "stepped_rigid_hub": stepped}


def bench_case(name: str, layout, refinement: float, solver: str = "auto") -> dict:
    """Cold and warm build of ``layout``'s superelement with ``solver``: times (s), parts,
    size, answers."""
    import numpy as np

    from pipeline.cache.folder import Cache
    from pipeline.fem.shaft_mesh import mesh_shaft
    from pipeline.shaft.fe3d import Fe3dShaft
    from pipeline.shaft.fe3d_plan import Fe3dSettings, plan_fe3d
    from pipeline.shaft.model import PointLoad

    settings = Fe3dSettings(refinement=refinement, solver=solver)
    with tempfile.TemporaryDirectory() as folder:
        cache = Cache(folder)
        t0 = time.perf_counter()
        cold = Fe3dShaft(layout, settings, cache=cache)
        t_cold = time.perf_counter() - t0
        t0 = time.perf_counter()
        warm = Fe3dShaft(layout, settings, cache=cache)
        t_warm = time.perf_counter() - t0
    assert warm.cached and not cold.cached
    tets = mesh_shaft(plan_fe3d(layout, settings).mesh).cells.shape[1]  # the same mesh again
    zg = layout.gear_position
    torque, d_ref = 340.0, 0.15
    ft = 2 * torque / d_ref
    fr = ft * math.tan(math.radians(20.0))
    load = np.array([-fr, ft, 0.0, 0.0, 0.0, torque])
    sol = warm.solve([PointLoad(zg, tuple(load[:3]), tuple(load[3:]))])
    seat = warm.flexibility(np.array([zg])) @ load  # the seat centre's motion
    se = cold.superelement
    return {"case": name, "refinement": refinement, "cold_s": t_cold, "warm_s": t_warm,
            "parts_s": dict(se.timings), "unknowns": se.n_dof, "tetrahedra_P2": int(tets),
            "solver": se.method,
            "seat_compliance_diagonal_m_per_N_rad_per_Nm": np.diag(
                warm.flexibility(np.array([zg]))).tolist(),
            "seat_deflection_um": (seat[:2] * 1e6).tolist(),
            "twist_to_coupling_mrad": float(seat[5] * 1e3),
            "bearing_reactions_N": sol.reactions[:, :2].round(1).tolist()}


def _print(r: dict) -> None:
    parts = ", ".join(f"{k} {v:.2f} s" for k, v in r["parts_s"].items())
    print(f"{r['case']}, refinement {r['refinement']:g}: {r['unknowns']} unknowns, "
          f"{r['tetrahedra_P2']} P2 tetrahedra, solver {r['solver']}")
    print(f"  cold {r['cold_s']:.2f} s ({parts}); warm {r['warm_s']:.3f} s")
    c = r["seat_compliance_diagonal_m_per_N_rad_per_Nm"]
    print("  seat compliance diagonal (u_x, u_y, u_z in m/N; theta in rad/(N m)): "
          + ", ".join(f"{v:.5e}" for v in c))
    u = r["seat_deflection_um"]
    print(f"  seat centre deflection (um): u_x {u[0]:.2f}, u_y {u[1]:.2f}; twist to the "
          f"coupling {r['twist_to_coupling_mrad']:.4f} mrad; "
          f"bearing reactions (N): {r['bearing_reactions_N']}")


def main(refinement: float = 1.0) -> dict:
    import numpy as np

    t0 = time.perf_counter()
    import pipeline.fem.linear_static  # noqa: F401  (scikit-fem, counted apart)
    import pipeline.fem.shaft_mesh  # noqa: F401  (Gmsh)
    from pipeline.io import write_json
    from pipeline.provenance import library_versions

    t_import = time.perf_counter() - t0
    layouts = _layouts()
    cases = [bench_case(name, layout, refinement) for name, layout in layouts.items()]
    cases.append(bench_case("straddle_pinion_example/cholespy",
                            layouts["straddle_pinion_example"], refinement, "cholespy"))
    for r in cases:
        _print(r)
    key = "seat_compliance_diagonal_m_per_N_rad_per_Nm"
    a, b = (np.array(c[key]) for c in (cases[0], cases[-1]))
    agreement = float(np.max(np.abs(a - b) / np.abs(b)))
    print(f"seat compliance diagonal, {cases[0]['solver']} against cholespy: largest "
          f"relative difference {agreement:.1e}")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"imports {t_import:.2f} s; peak resident memory {peak:.0f} MiB")
    out = {"cases": cases, "imports_s": t_import, "peak_rss_MiB": peak,
           "seat_compliance_relative_difference_to_cholespy": agreement,
           "versions": library_versions()}
    write_json(Path("results/benchmarks/shaft_fe3d.json"), out)
    return out


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 1.0)
