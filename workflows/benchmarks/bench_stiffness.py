"""Benchmark: analytical mesh stiffness over one mesh cycle (targets from issue 2).

Spur pair, 360 positions: target < 20 ms after import (tooth models built once).
Helical pair, 360 positions x 100 slices: target < 200 ms.
Side by side in one run: the vectorised evaluation vs a per-position Python loop
over the same model (the ratio is what to compare across machines).
Prints the figures and writes results/benchmarks/stiffness.json.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

from pipeline.geometry import GearPair, GearSpec, Material
from pipeline.io import write_json
from pipeline.provenance import library_versions
from pipeline.stiffness.mesh import FrictionModel, PairModel, mesh_stiffness, stiffness_at

STEEL = Material(2.0e11, 0.3, 7850.0)


def best_of(fn, repeat: int = 7) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> dict:
    d = math.radians
    spur = GearPair(*(GearSpec(teeth=50, module=3e-3, pressure_angle=d(20), face_width=0.02,
                               bore_radius=0.021, material=STEEL, name=n) for n in ("p", "g")))
    kw = dict(module=7.35e-3, pressure_angle=d(20), helix_angle=d(4.0), addendum_coef=1.2,
              dedendum_coef=1.55, face_width=0.13, material=STEEL)
    hel = GearPair(GearSpec(teeth=31, hand="right", profile_shift=0.27807, bore_radius=0.045,
                            name="p", **kw),
                   GearSpec(teeth=104, hand="left", profile_shift=-0.59026, bore_radius=0.15,
                            name="g", **kw))
    t = time.perf_counter()
    m_spur = PairModel.build(spur)
    m_hel = PairModel.build(hel)
    build = (time.perf_counter() - t) / 2
    fr = FrictionModel(mu=0.05)
    t_spur = best_of(lambda: mesh_stiffness(m_spur, 360, friction=fr))
    t_hel = best_of(lambda: mesh_stiffness(m_hel, 360, 100, friction=fr))

    # reference: the same computation one position at a time (what a loop would cost)
    def loop_spur():
        return [stiffness_at(m_spur, s0[None], friction=fr) for s0 in spur.mesh_cycle(360)]

    t_loop = best_of(loop_spur, 3)
    ref = mesh_stiffness(m_hel, 360, 1000, friction=fr).total
    err = float(np.max(np.abs(mesh_stiffness(m_hel, 360, 100, friction=fr).total - ref)) /
                ref.mean())
    out = {
        "tooth_model_build_s": build,
        "spur_360_positions_s": t_spur,
        "helical_360x100_s": t_hel,
        "spur_per_position_loop_estimate_s": t_loop,
        "vectorised_speedup_vs_loop": t_loop / t_spur,
        "helical_100_vs_1000_slices_max_rel_diff": err,
        "targets": {"spur_s": 0.020, "helical_s": 0.200},
        "versions": library_versions(),
    }
    print(f"tooth models (once per gear)    {build * 1e3:8.2f} ms")
    print(f"spur, 360 positions             {t_spur * 1e3:8.2f} ms   (target 20 ms)")
    print(f"helical, 360 x 100 slices       {t_hel * 1e3:8.2f} ms   (target 200 ms)")
    print(f"vectorised vs per-position loop {t_loop / t_spur:8.1f} x")
    print(f"helical 100 vs 1000 slices      {err * 100:8.3f} % max difference")
    path = write_json(Path("results/benchmarks/stiffness.json"), out)
    print(f"written to {path}")
    return out


if __name__ == "__main__":
    main()
    sys.exit(0)
