"""Benchmark: the 3D FE contact compliance build (whole gear bodies), cold and warm.

Default case: the helical test pair of tests/test_fem_source3d.py (z 30/30, m_n 3 mm,
beta 15 deg, b 12 mm, bore 30 mm), whole gears at refinement 1, 8 profile x 13 face
points on the 3 loaded teeth of each gear. ``--full`` adds the pair of Yang et al.
(2026) (z 31/104, m_n 7.35 mm, b 130 mm; workflows/configs/traction_helical_pair.toml)
at the fe3d workflow's coarse settings (refinement 0.6, 6 x 24 points on 4 teeth).

For each case ``FE3DCompliance.build`` runs twice on a fresh cache folder: cold (mesh,
assembly, factorisation, solves, near field; the breakdown from the tables' info) and
warm (both tables read back from the cache). Peak RSS is the process's high-water mark
after the cold build (resource.getrusage), so run the script on its own. Prints the
figures and writes results/benchmarks/fe3d.json.

    python workflows/benchmarks/bench_fe3d.py [--full]
"""

from __future__ import annotations

import math
import resource
import sys
import tempfile
import time
from pathlib import Path

from pipeline.cache.folder import Cache
from pipeline.contact import FE3DCompliance, FE3DSettings
from pipeline.geometry import GearPair, GearSpec
from pipeline.io import write_json
from pipeline.provenance import library_versions

HERE = Path(__file__).resolve().parents[1]


def _small_pair() -> GearPair:
    kw = dict(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.03,
              face_width=12e-3, helix_angle=math.radians(15))
    return GearPair(GearSpec(hand="right", name="pinion", **kw),
                    GearSpec(hand="left", name="gear", **kw))


def _yang_pair() -> GearPair:
    from pipeline.config import load_gearbox

    return load_gearbox(HERE / "configs" / "traction_helical_pair.toml").pair


def bench_case(name: str, pair: GearPair, settings: FE3DSettings) -> dict:
    """Cold and warm build of ``pair``'s 3D FE compliance: times (s), breakdown, DOFs,
    peak RSS (GiB)."""
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        cold = FE3DCompliance.build(pair, settings, cache=Cache(tmp), show_progress=True)
        t_cold = time.perf_counter() - t0
        rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
        t0 = time.perf_counter()
        warm = FE3DCompliance.build(pair, settings, cache=Cache(tmp))
        t_warm = time.perf_counter() - t0
    tables = {g: getattr(cold, f"{g}_table").info for g in ("pinion", "gear")}
    return {"case": name, "settings": settings, "cold_s": t_cold, "warm_s": t_warm,
            "warm_from_cache": all(getattr(warm, f"{g}_table").info["cached"]
                                   for g in ("pinion", "gear")),
            "peak_rss_GiB_after_cold": rss,
            **{g: {k: info[k] for k in ("model_teeth", "dof", "free_dof", "solver",
                                        "timings_s")} for g, info in tables.items()},
            "grid_points": {g: int(getattr(cold, f"{g}_table").structural.shape[0])
                            for g in ("pinion", "gear")}}


def _print(r: dict) -> None:
    print(f"{r['case']}: cold {r['cold_s']:.1f} s, warm {r['warm_s']:.2f} s "
          f"(from cache: {r['warm_from_cache']}), peak RSS {r['peak_rss_GiB_after_cold']:.2f} GiB")
    for g in ("pinion", "gear"):
        t = r[g]["timings_s"]
        print(f"  {g}: z {r[g]['model_teeth']}, {r[g]['dof']} DOF, "
              f"{r['grid_points'][g]} load cases, {r[g]['solver']}: "
              + ", ".join(f"{k} {v:.1f} s" for k, v in t.items()))


def main(full: bool = False) -> dict:
    cases = [bench_case("helical z30/30 m3 b12, whole gears, refinement 1", _small_pair(),
                        FE3DSettings(refinement=1.0, points=8))]
    if full:
        cases.append(bench_case("Yang et al. (2026) z31/104 m7.35 b130, whole gears, "
                                "refinement 0.6", _yang_pair(),
                                FE3DSettings(refinement=0.6, points=6, face_points=24)))
    for r in cases:
        _print(r)
    out = {"cases": cases, "versions": library_versions()}
    write_json(Path("results/benchmarks/fe3d.json"), out)
    return out


if __name__ == "__main__":
    main("--full" in sys.argv[1:])
