"""Benchmark: the 3D shaft superelement of a straddle-mounted pinion, cold and warm.

Target: < 10 s cold (mesh, assembly, factorisation, condensation) for a shaft of the demo
pair's size. The layout: a 260 mm shaft, 35 mm at the coupling (torque held at 20 mm),
40 mm bearing journals with bearings 200 mm apart (55 and 255 mm, rigid), a 45 mm body
carrying the pinion (reference diameter 150 mm, z 50, m 3 mm) on a rigid hub 20 mm wide
at mid-span. The load: the demo pair's 340 N m, i.e. F_t = 2 T / d = 4533 N and
F_r = F_t tan 20 deg = 1650 N at the pitch point, moved to the axis (the tangential
force's lever is the torque).

Prints the import time, the cold build (empty temporary cache) with its parts, the warm
build (read from the cache), the peak resident memory of the process, the unknowns and
the seat's deflection.

Run: ``python workflows/benchmarks/bench_shaft_fe3d.py [refinement]``.
"""

from __future__ import annotations

import math
import resource
import sys
import tempfile
import time


def main(refinement: float = 1.0) -> None:
    t0 = time.perf_counter()
    import pipeline.fem.linear_static  # noqa: F401  (scikit-fem, counted apart)
    import pipeline.fem.shaft_mesh  # noqa: F401  (Gmsh)
    from pipeline.cache.folder import Cache
    from pipeline.shaft.fe3d import Fe3dShaft
    from pipeline.shaft.fe3d_plan import Fe3dSettings
    from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
    from pipeline.shaft.model import PointLoad

    t_import = time.perf_counter() - t0
    segments = (ShaftSegment(0.0, 0.04, 0.035), ShaftSegment(0.04, 0.07, 0.04),
                ShaftSegment(0.07, 0.23, 0.045), ShaftSegment(0.23, 0.26, 0.04))
    layout = ShaftLayout(segments, 0.155, 0.02, (Bearing(0.055, axial=True), Bearing(0.255)),
                         0.02, hub="rigid", name="pinion.shaft")
    settings = Fe3dSettings(refinement=refinement)
    with tempfile.TemporaryDirectory() as folder:
        cache = Cache(folder)
        t0 = time.perf_counter()
        cold = Fe3dShaft(layout, settings, cache=cache)
        t_cold = time.perf_counter() - t0
        t0 = time.perf_counter()
        warm = Fe3dShaft(layout, settings, cache=cache)
        t_warm = time.perf_counter() - t0
    assert warm.cached and not cold.cached
    torque, d_ref = 340.0, 0.15
    ft = 2 * torque / d_ref
    fr = ft * math.tan(math.radians(20.0))
    sol = warm.solve([PointLoad(0.155, (-fr, ft, 0.0), (0.0, 0.0, torque))])
    seat = min(range(sol.z.size), key=lambda i: abs(sol.z[i] - 0.155))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    se = cold.superelement
    parts = ", ".join(f"{k} {v:.2f} s" for k, v in se.timings.items())
    print(f"straddle-mounted pinion shaft, refinement {refinement:g}: {se.n_dof} unknowns, "
          f"solver {se.method}")
    print(f"imports {t_import:.2f} s; cold {t_cold:.2f} s ({parts}); warm {t_warm:.3f} s")
    print(f"peak resident memory {peak:.0f} MiB")
    u = sol.displacement[seat] * 1e6
    print(f"seat deflection (um): u_x {u[0]:.2f}, u_y {u[1]:.2f}; twist to the coupling "
          f"{sol.rotation[seat, 2] * 1e3:.4f} mrad; bearing reactions (N): "
          f"{sol.reactions[:, :2].round(1).tolist()}")


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 1.0)
