"""Convergence of the 3D FE tables (``compliance = "fe3d"``): mesh stiffness and TE.

The helical z 30/30 pair of ``workflows/benchmarks/bench_fe3d.py`` (m_n 3 mm, beta 15 deg,
b 12 mm, bore 30 mm) under P = 4 kN along the line of action, 30 positions over a mesh
cycle, at the default ``[fe]`` grid, with

* the default graded whole-gear model (one loaded tooth and its neighbours at the flank
  size ``m_n / (3 refinement)``, :mod:`pipeline.contact.fe3d_table`) at refinements
  0.6, 0.8, 1 (coarse default) or 0.6 .. 2 (``--full``: flank elements 1.67 .. 0.5 mm);
* the same with every tooth at the flank size (``[fe] mesh = "uniform"``, the reference of
  the grading) and the former model (every tabulated tooth loaded and fine) at the default
  refinement 1.

For each of the tangent mesh stiffness's mean, minimum and maximum and the TE p-p it fits
``q(h) = q_inf + C h^p`` through the three finest graded levels (``h`` the flank element
size) and reports the rate ``p``, the extrapolated ``q_inf`` and each case's deviation from
it (no fit, said so, when the changes do not shrink steadily).

Measured (``--full``, 2 shared cores, load ~5; the defaults of
:mod:`pipeline.fem.whole3d`: the read neighbours at 1.5 flank sizes, the teeth beyond
two rim depths left out): the graded models of 13k, 19k, 26k, 43k and 79k unknowns (one
model for both gears: mirror images) built in 2-16 s; the mesh stiffness converges at
rate 1.9 / 1.5 / 1.7 to 244.0 (mean), 205.8 (min), 264.1 (max) N/um: the default
refinement 1 is +1.12 / +1.34 / +1.11 % above the limit, refinement 2 +0.31 / +0.47 /
+0.34 %; every tooth kept and fine (268k unknowns) at refinement 1 lies 0.16 / 0.15 /
0.16 % below the graded model, the former model (every tabulated tooth loaded and fine)
0.08-0.12 % below. The TE p-p grows with refinement without a steady rate (5.57, 5.63, 5.68,
5.70, 5.72 um): refinement 1 is 0.75 % below refinement 2; every tooth fine +0.06 %, the
former model +0.12 %. (Every tooth kept, the neighbours fine, 5 m_n body cells: 23k ..
128k unknowns, rate 2.1-2.7, limits 244.2 / 206.1 / 264.6 N/um, refinement 1 +0.95 /
+1.13 / +0.90 %, every tooth fine 0.09 / 0.06 / 0.10 % below, TE p-p 5.52 .. 5.72 um.)
The default levels 0.6 .. 1 are too coarse for the fit (rates 0.06-1.4, limits off by
up to 50 %): use ``--full``
for the limit. Writes ``convergence.csv`` / ``.json`` / ``.png`` and ``run.json`` to
``results/fe3d_convergence/workflow/`` (or ``--out``). Several minutes on 2 cores
(``--full``: refinement 2 is a 79k-unknown model; the uniform reference 268k).

    python workflows/fe3d_convergence.py [--full] [--out DIR]
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from pipeline.cache.folder import Cache
from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.contact import FE3DCompliance, FE3DSettings
from pipeline.contact.fe3d_source import touching_pairs
from pipeline.contact.fe3d_table import flank_table
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.geometry import GearPair, GearSpec
from pipeline.io import write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.provenance import write_run_record

KPIS = (("k_mean", "mesh stiffness mean", "N/um", 1e-6),
        ("k_min", "mesh stiffness min", "N/um", 1e-6),
        ("k_max", "mesh stiffness max", "N/um", 1e-6),
        ("te_pp", "TE peak to peak", "um", 1e6))
LOAD_N = 4000.0
COARSE = (0.6, 0.8, 1.0)
FULL = (0.6, 0.8, 1.0, 1.4, 2.0)


def bench_pair() -> GearPair:
    """The helical z 30/30 pair of bench_fe3d.py."""
    kw = dict(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.03,
              face_width=12e-3, helix_angle=math.radians(15))
    return GearPair(GearSpec(hand="right", name="pinion", **kw),
                    GearSpec(hand="left", name="gear", **kw))


def case(pair: GearPair, settings: FE3DSettings, cache: Cache, former: bool = False) -> dict:
    """KPIs (SI) of one model, its unknowns per gear and its build time (s)."""
    t0 = time.perf_counter()
    if former:  # every tabulated tooth loaded on a mesh fine on all of them
        k = touching_pairs(pair)
        tables = [flank_table(g, g.teeth, np.sort(g.teeth // 2 + sign * k), settings, cache,
                              progress=False, one_tooth=False)
                  for g, sign in ((pair.pinion, -1), (pair.gear, 1))]
        src = FE3DCompliance(pair, settings, *tables)
    else:
        src = FE3DCompliance.build(pair, settings, cache=cache)
    build = time.perf_counter() - t0
    cyc = loaded_mesh_cycle(src, LOAD_N, positions=30)
    k, te = cyc.mesh_stiffness, cyc.transmission_error
    return {"refinement": settings.refinement, "flank_size_mm": 3.0 / (3 * settings.refinement),
            "k_mean": float(k.mean()), "k_min": float(k.min()), "k_max": float(k.max()),
            "te_pp": float(np.ptp(te)), "build_s": build,
            "dof": int(src.pinion_table.info["dof"]),
            "models": 1 + int(not src.gear_table.info["cached"])}


def fit(h: np.ndarray, q: np.ndarray) -> tuple[float, float]:
    """Rate ``p`` and limit ``q_inf`` of ``q = q_inf + C h^p`` through three levels
    (``h`` descending): the ratio of successive differences fixes ``p``."""
    d1, d2 = q[0] - q[1], q[1] - q[2]
    if d1 * d2 <= 0:
        return math.nan, math.nan

    def gap(p: float) -> float:
        return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - d1 / d2

    if gap(0.05) * gap(8.0) > 0:  # the differences do not shrink like a power of h
        return math.nan, math.nan
    p = brentq(gap, 0.05, 8.0)
    c = d2 / (h[1] ** p - h[2] ** p)
    return p, float(q[2] - c * h[2] ** p)


def run(out: Path, levels: tuple[float, ...]) -> dict:
    """The study at refinements ``levels`` (ascending), written to ``out``."""
    pair = bench_pair()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        cache = Cache(tmp)
        for r in levels:
            rows.append({"model": "graded", **case(pair, FE3DSettings(refinement=r), cache)})
            print(f"graded, refinement {r:g}: {rows[-1]['models']} model(s) of "
                  f"{rows[-1]['dof']} unknowns, {rows[-1]['build_s']:.1f} s", file=sys.stderr)
        default = FE3DSettings()
        rows.append({"model": "uniform", **case(pair, replace(default, mesh="uniform"), cache)})
        rows.append({"model": "former", **case(pair, default, cache, former=True)})
    graded = [r for r in rows if r["model"] == "graded"]
    h = np.array([r["flank_size_mm"] for r in graded[-3:]])
    limits = {}
    for key, *_ in KPIS:
        p, q_inf = fit(h, np.array([r[key] for r in graded[-3:]]))
        fitted = math.isfinite(q_inf)  # else the changes do not shrink like a power of h
        limits[key] = {"rate": p if fitted else None, "limit": q_inf if fitted else None}
        for r in rows:
            r[f"{key}_vs_limit_percent"] = 100 * (r[key] / q_inf - 1) if fitted else None
    summary = {"pair": "helical z 30/30, m_n 3 mm, beta 15 deg, b 12 mm (bench_fe3d)",
               "load_N": LOAD_N, "cases": rows, "fit": limits}
    files = [write_json(out / "convergence.json", summary),
             write_csv(out / "convergence.csv", _csv_rows(rows))]
    _figure(rows, limits, out / "convergence.png")
    write_run_record(out, {"refinements": list(levels), "load_N": LOAD_N,
                           "settings": "FE3DSettings() defaults"},
                     [*files, out / "convergence.png"], "workflows/fe3d_convergence.py")
    return summary


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--full", action="store_true", help=f"refinements {FULL}, not {COARSE}")
    ap.add_argument("--out", type=Path, default=None, help="default: results/<script>/workflow")
    args = ap.parse_args(argv)
    args.out = workflow_dir(__file__, args.out)
    with staged_output(args.out) as out:
        summary = run(out, FULL if args.full else COARSE)
    for key, *_ in KPIS:
        f = summary["fit"][key]
        if f["limit"] is None:
            print(f"{key}: no power-law fit (the changes do not shrink steadily); "
                  + ", ".join(f"{r['model']} {r['refinement']:g} {r[key]:.6g}"
                              for r in summary["cases"]))
            continue
        print(f"{key}: rate {f['rate']:.2f}, limit {f['limit']:.6g}; " + ", ".join(
            f"{r['model']} {r['refinement']:g} {r[key + '_vs_limit_percent']:+.2f} %"
            for r in summary["cases"]))
    print(f"written to {args.out}/")
    return summary


def _csv_rows(rows: list[dict]) -> dict[str, list]:
    names = {"refinement": "refinement", "flank_size_mm": "flank_element_mm",
             "dof": "unknowns_per_model", "models": "models_solved",
             "build_s": "tables_build_s",
             "k_mean": "mesh_stiffness_mean_N_per_m", "k_min": "mesh_stiffness_min_N_per_m",
             "k_max": "mesh_stiffness_max_N_per_m", "te_pp": "te_peak_to_peak_m"}
    columns = {"model": [r["model"] for r in rows]}
    columns.update({v: [r[k] for r in rows] for k, v in names.items()})
    columns.update({f"{k}_vs_limit_percent": [math.nan if r[f"{k}_vs_limit_percent"] is None
                                              else r[f"{k}_vs_limit_percent"] for r in rows]
                    for k, *_ in KPIS})
    return columns


def _figure(rows: list[dict], limits: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    graded = [r for r in rows if r["model"] == "graded"]
    h = np.array([r["flank_size_mm"] for r in graded])
    for key, label, _, scale in KPIS:
        ax = axes[0] if key.startswith("k_") else axes[1]
        line, = ax.plot(h, [r[key] * scale for r in graded], "o-",
                        label=label.replace("mesh stiffness ", ""))
        for model, marker in (("uniform", "s"), ("former", "^")):
            r = next(x for x in rows if x["model"] == model)
            ax.plot(r["flank_size_mm"], r[key] * scale, marker, color=line.get_color(),
                    mfc="none", ms=9)
        if limits[key]["limit"] is not None:
            ax.axhline(limits[key]["limit"] * scale, color=line.get_color(), lw=0.8, ls=":")
    axes[0].set_ylabel("tangent mesh stiffness (N/um)")
    axes[1].set_ylabel("TE peak to peak (um)")
    axes[0].legend(title="graded mesh", fontsize=8, loc="lower left", bbox_to_anchor=(0.02, 0.2))
    note = "squares: every tooth fine; triangles: every tabulated tooth loaded"
    axes[0].set_title(f"dotted: extrapolated limit\n{note}", fontsize=9)
    te = limits["te_pp"]["limit"] is not None
    axes[1].set_title(("dotted: extrapolated limit" if te else
                       "no steady rate (not extrapolated)") + f"\n{note}", fontsize=9)
    for ax in axes:
        ax.set_xlabel("flank element size (mm)")
        ax.invert_xaxis()
        ax.grid(alpha=0.3)
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
