"""Benchmark: FE-enriched mesh stiffness over a mesh cycle, cold and warm.

The spur pair of the assembly-error paper (``workflows/configs/spur_pair_assembly_errors.toml``,
z 50/50, m 3 mm, whole gears, plane strain, 30 radii per flank, 60 mesh positions, Weber
local contact): :class:`~pipeline.contact.FE2DCompliance` on the default graded meshes
against today's uniform whole-gear model (``mesh = "uniform"``, refinement 1), each run
in a fresh Python process so that imports and the peak memory (RSS) are its own:

* cold: empty cache folder; imports, meshing (Gmsh + conversion), assembly, load
  vectors, factorisation, solves, near field, table writing and the contact cycle (the
  pair's gears are equal: one table is solved, the other read back,
  :mod:`pipeline.contact.fe2d_table`; the breakdown counts the solved ones);
* warm: the same cache folder again: imports, table loading, contact cycle.

Cold graded runs are repeated (``--repeat``, default 3) and the fastest is reported
beside the median (the machine is shared). ``--convergence`` adds the convergence
study of the uniform model (refinement 0.5, 0.7, 1, 1.4, 2; a few minutes) and fits
``k(h) = k_inf + C h^p`` to the three finest levels (``h`` = 1 / refinement), the
reference the graded default is checked against (module docstring of
:mod:`pipeline.contact.fe2d_source`). Prints the figures and writes
``results/benchmarks/fe_enriched.json`` and ``fe_enriched.csv``.

    python workflows/benchmarks/bench_fe_enriched.py [--repeat N] [--convergence]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"
OUT = ROOT / "results" / "benchmarks"
STAGES = ("mesh", "assembly", "loads", "factor", "solve", "nearfield")
UNIFORM_LEVELS = (0.5, 0.7, 1.0, 1.4, 2.0)


def run_once(settings: dict, cache_dir: str | None) -> dict:
    """One FE-enriched mesh cycle in this process (called in a child process)."""
    t0 = time.perf_counter()
    from pipeline.cache.folder import Cache
    from pipeline.config import load_gearbox
    from pipeline.contact import FE2DCompliance, FE2DSettings
    from pipeline.contact.analysis import analyse_contact
    from pipeline.contact.options import ContactOptions

    t1 = time.perf_counter()
    box = load_gearbox(CONFIG)
    fe = FE2DSettings(**settings)
    t2 = time.perf_counter()
    src = FE2DCompliance.build(box.actual_pair, fe,
                               cache=Cache.off() if cache_dir is None else Cache(cache_dir))
    t3 = time.perf_counter()
    k = analyse_contact(src, box.operation, ContactOptions(positions=60)).mesh_stiffness
    t4 = time.perf_counter()
    gears = [src.info["pinion"], src.info["gear"]]
    out = {"imports_s": t1 - t0, "config_s": t2 - t1, "tables_s": t3 - t2, "contact_s": t4 - t3,
           "total_s": t4 - t0, "cached": all(g["cached"] for g in gears),
           "dof": [g["dof"] for g in gears],
           "peak_rss_GiB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20,
           "k_mean_N_per_m": float(k.mean()), "k_min_N_per_m": float(k.min()),
           "k_max_N_per_m": float(k.max())}
    if not out["cached"]:  # the builds of this run: a table read back (an equal gear's,
        # solved a moment before) carries the timings of the build that made it
        for stage in STAGES:
            out[f"{stage}_s"] = sum(g["timings"][stage] for g in gears if not g["cached"])
        out["tables_solved"] = sum(not g["cached"] for g in gears)
    return out


def child(settings: dict, cache_dir: str | None) -> dict:
    """:func:`run_once` in a fresh interpreter; adds the interpreter's own start-up time."""
    t0 = time.perf_counter()
    cmd = [sys.executable, __file__, "--child", json.dumps(settings),
           "--cache-dir", cache_dir or ""]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    res = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, check=True, env=env)
    out = json.loads(res.stdout.strip().splitlines()[-1])
    out["process_wall_s"] = time.perf_counter() - t0
    return out


def cold_and_warm(settings: dict, repeat: int) -> dict:
    """``repeat`` cold runs (each with a new empty cache folder), then a warm one."""
    colds = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as d:
            colds.append(child(settings, d))
            warm = child(settings, d)
    best = min(colds, key=lambda r: r["total_s"])
    best["total_s_median"] = statistics.median(r["total_s"] for r in colds)
    best["process_wall_s_median"] = statistics.median(r["process_wall_s"] for r in colds)
    return {"settings": settings, "cold": best, "warm": warm}


def fit_limit(levels: list[float], values: list[float]) -> tuple[float, float]:
    """(k_inf, p) of ``k = k_inf + C h^p`` through the three finest levels (h = 1/level)."""
    (h1, k1), (h2, k2), (h3, k3) = sorted(zip(1.0 / np.asarray(levels), values, strict=True))[:3]
    r = (k3 - k2) / (k2 - k1)  # = ((h3^p - h2^p) / (h2^p - h1^p))
    p = float(np.log(r) / np.log(h3 / h2)) if h3 / h2 == h2 / h1 else _solve_p(h1, h2, h3, r)
    c = (k2 - k1) / (h2**p - h1**p)
    return float(k1 - c * h1**p), p


def _solve_p(h1: float, h2: float, h3: float, r: float) -> float:
    from scipy.optimize import brentq

    return float(brentq(lambda p: (h3**p - h2**p) / (h2**p - h1**p) - r, 0.2, 8.0))


def convergence() -> dict:
    """Uniform whole-gear model at every level of :data:`UNIFORM_LEVELS` (no cache)."""
    rows = [child({"mesh": "uniform", "refinement": r}, None) for r in UNIFORM_LEVELS]
    out = {"levels": list(UNIFORM_LEVELS), "runs": rows}
    for q in ("mean", "min", "max"):
        vals = [r[f"k_{q}_N_per_m"] for r in rows]
        k_inf, p = fit_limit(list(UNIFORM_LEVELS), vals)
        out[f"k_{q}_extrapolated_N_per_m"] = k_inf
        out[f"k_{q}_order"] = p
    return out


def print_table(res: dict) -> None:
    g, u = res["graded"], res["uniform"]
    print(f"{'':24s} {'graded (default)':>18s} {'uniform (today)':>18s} {'ratio':>8s}")
    rows = [("unknowns per gear", lambda r: r["cold"]["dof"][0]),
            ("cold tables solved", lambda r: r["cold"]["tables_solved"])]
    rows += [(f"cold {s} [s]", lambda r, s=s: r["cold"][f"{s}_s"]) for s in
             ("imports",) + STAGES + ("contact", "total")]
    rows += [("cold process wall [s]", lambda r: r["cold"]["process_wall_s"]),
             ("cold peak RSS [GiB]", lambda r: r["cold"]["peak_rss_GiB"]),
             ("warm imports [s]", lambda r: r["warm"]["imports_s"]),
             ("warm table loading [s]", lambda r: r["warm"]["tables_s"]),
             ("warm contact cycle [s]", lambda r: r["warm"]["contact_s"]),
             ("warm peak RSS [GiB]", lambda r: r["warm"]["peak_rss_GiB"]),
             ("k mean [N/m]", lambda r: r["cold"]["k_mean_N_per_m"]),
             ("k min [N/m]", lambda r: r["cold"]["k_min_N_per_m"]),
             ("k max [N/m]", lambda r: r["cold"]["k_max_N_per_m"])]
    for name, get in rows:
        a, b = get(g), get(u)
        print(f"{name:24s} {a:18.4g} {b:18.4g} {a / b:8.3f}")
    if "convergence" in res:
        c = res["convergence"]
        for q in ("mean", "min", "max"):
            ref = c[f"k_{q}_extrapolated_N_per_m"]
            print(f"k {q}: extrapolated {ref:.6g} N/m (order {c[f'k_{q}_order']:.2f}); graded "
                  f"{100 * (g['cold'][f'k_{q}_N_per_m'] / ref - 1):+.3f} %, uniform 1.0 "
                  f"{100 * (u['cold'][f'k_{q}_N_per_m'] / ref - 1):+.3f} %")


def write(res: dict) -> None:
    """JSON of everything; CSV with one row per run (cold/warm x graded/uniform)."""
    from pipeline.io import atomic_write_text, write_json
    from pipeline.provenance import library_versions

    res["versions"] = library_versions()
    write_json(OUT / "fe_enriched.json", res)
    keys = ["imports_s", *(f"{s}_s" for s in STAGES), "tables_s", "contact_s", "total_s",
            "process_wall_s", "peak_rss_GiB", "k_mean_N_per_m", "k_min_N_per_m",
            "k_max_N_per_m"]
    header = ["run", "unknowns per gear"]
    for key in keys:
        unit = "GiB" if "GiB" in key else "N/m" if "N_per_m" in key else "s"
        header.append(f"{key.removesuffix('_s').removesuffix('_GiB').removesuffix('_N_per_m')}"
                      f" [{unit}]")
    lines = [",".join(header)]
    for model in ("graded", "uniform"):
        for state in ("cold", "warm"):
            r = res[model][state]
            lines.append(",".join([f"{model} {state}", str(r["dof"][0])]
                                  + [f"{r[k]:.6g}" if k in r else "" for k in keys]))
    atomic_write_text(OUT / "fe_enriched.csv", "\n".join(lines) + "\n")


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--child", default=None, help=argparse.SUPPRESS)
    ap.add_argument("--cache-dir", default="", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child is not None:
        print(json.dumps(run_once(json.loads(args.child), args.cache_dir or None)))
        return {}
    res = {"case": "assembly-error paper spur pair, whole gears, 60 positions, 30 radii",
           "graded": cold_and_warm({}, args.repeat),
           "uniform": cold_and_warm({"mesh": "uniform", "refinement": 1.0}, 1)}
    if args.convergence:
        res["convergence"] = convergence()
    print_table(res)
    write(res)
    return res


if __name__ == "__main__":
    main()
