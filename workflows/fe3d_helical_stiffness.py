"""Helical pair of Yang et al. (2026): LTCA mesh stiffness from the slice model vs the 3D FE
whole-gear influence matrices.

The traction pair of Yang et al. (2026), Table 2 (z 31/104, m_n 7.35 mm, beta 4 deg, face
130 mm assumed; workflows/configs/traction_helical_pair.toml) at its rated load is run
through the loaded tooth contact analysis (Yang et al. 2026, eqs. 27-29, local approach
eq. 24 "weber") on the same slice contact points with

* ``slice``: the analytical slice compliance (:class:`SliceCompliance`, independent
  slices, Yang et al. (2026), section 2.1-2.4);
* ``fe3d``: the 3D FE structural compliance of both *whole gears*
  (:class:`pipeline.contact.fe3d_source.FE3DCompliance`, ``body = "whole"``: all teeth,
  the body down to the 45/150 mm bores, the full face; bores clamped; mesh graded from
  the four loaded teeth), which couples the slices across the face width;
* two 2D FE references of the same whole gears
  (:class:`~pipeline.contact.fe2d_source.FE2DCompliance`, same slices, no face
  coupling): ``fe2d_strain`` (plane strain, the 3D model's sliding-ends limit) and
  ``fe2d_stress`` (plane stress, its thin-face limit).

All use the same friction-free normal loads (the config has mu = 0).

Measured (coarse default, refinement 0.6; tables cold): the 3D whole gears come out
between the 2D plane-strain and plane-stress whole gears, as the ladder of
tests/test_fem_whole3d.py says they must, and below the slice method (the numbers and why
they differ: :mod:`pipeline.contact.fe3d_source`). Cold run 6.4 min wall and 2.9 GB peak
on 2 cores shared with other jobs (245 s of CPU); the 3D tables (87k / 188k DOF) took 74 s
and 167 s (wheel: mesh 47 s, assembly 8 s, factorisation 65 s, 576 solves 39 s, near
field 7 s), the 2D references 126 s; the FE tables and meshes are cached in ``meshes/``,
so a rerun takes seconds.

Writes to results/fe3d_helical_stiffness/workflow/: stiffness.csv (per position), summary.json
(max/min/mean of every curve, % differences, DOFs, the FE timing breakdown, peak memory,
residuals), stiffness.png and run.json (inputs and their hash). Progress of the FE
builds goes to stderr.

    python workflows/fe3d_helical_stiffness.py [--full] [--out DIR]
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from dataclasses import asdict
from pathlib import Path

import numpy as np

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.config import load_gearbox
from pipeline.contact import FE2DCompliance, FE2DSettings, FE3DCompliance, FE3DSettings
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.source import SliceCompliance
from pipeline.io import write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.provenance import write_run_record
from pipeline.stiffness.mesh import FrictionModel, PairModel

HERE = Path(__file__).resolve().parent
CONFIG = HERE / "configs" / "traction_helical_pair.toml"

# 3D grid: 4 loaded teeth x radii x face points per gear = right-hand sides of one solve
COARSE = {"refinement": 0.6, "radii": 6, "face": 24, "slices": 40, "positions": 24}
FULL = {"refinement": 0.8, "radii": 8, "face": 34, "slices": 60, "positions": 60}


def _stats(k: np.ndarray) -> dict:
    return {"mean_N_per_m": float(k.mean()), "max_N_per_m": float(k.max()),
            "min_N_per_m": float(k.min()),
            "peak_to_peak_percent": float(100 * np.ptp(k) / k.mean())}


def plot(deg: np.ndarray, curves: dict, title: str):
    from matplotlib.figure import Figure

    from pipeline.viz.units import stiffness_in_plot_unit, stiffness_label

    fig = Figure(figsize=(7, 6))
    ax = fig.subplots(2, 1, sharex=True)
    for name, cyc in curves.items():
        ax[0].plot(deg, stiffness_in_plot_unit(cyc.mesh_stiffness), marker=".", label=name)
        ax[1].plot(deg, cyc.transmission_error * 1e6, marker=".", label=name)
    ax[0].set_ylabel(stiffness_label("mesh stiffness dP/dx"))
    ax[1].set_ylabel("loaded static TE [um]")
    ax[1].set_xlabel("pinion angle [deg]")
    ax[0].legend(fontsize=8)
    ax[0].set_title(title, fontsize=9)
    return fig


def run(out: Path, refinement: float, radii: int, face: int | None, slices: int, positions: int,
        cache: Cache = DEFAULT_CACHE, references: bool = True) -> dict:
    """Run the study into ``out``; ``references`` False skips the 2D FE references."""
    from pipeline.viz import save

    cfg = load_gearbox(CONFIG)
    pair = cfg.pair
    load = cfg.operation.torque / pair.pinion.base_radius
    op = cfg.operation
    sources = {"slice": SliceCompliance(PairModel.build(pair), slices, FrictionModel(mu=0.0), op)}
    settings = FE3DSettings(body="whole", refinement=refinement, points=radii, face_points=face,
                            slices=slices)
    t0 = time.perf_counter()
    sources["fe3d"] = FE3DCompliance.build(pair, settings, cache=cache,
                                         show_progress=True)
    t_build = time.perf_counter() - t0
    rss_3d = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
    t0 = time.perf_counter()
    if references:
        for kind in ("strain", "stress"):
            sources[f"fe2d_{kind}"] = FE2DCompliance.build(pair, FE2DSettings(
                teeth=None, points=12, slices=slices, kind=f"plane_{kind}"))
    t_build_2d = time.perf_counter() - t0
    cycles, t_ltca = {}, {}
    s0 = pair.mesh_cycle(positions)
    for name, src in sources.items():
        t0 = time.perf_counter()
        cycles[name] = loaded_mesh_cycle(src, load, local="weber", positions=s0,
                                         show_progress=True)
        t_ltca[name] = time.perf_counter() - t0
    k_sl, k_fe = cycles["slice"].mesh_stiffness, cycles["fe3d"].mesh_stiffness
    fe = sources["fe3d"]
    summary = {
        "load_N": load, "positions": positions, "slices": slices,
        **{n: _stats(c.mesh_stiffness) for n, c in cycles.items()},
        "mean_over_slice": {n: float(c.mesh_stiffness.mean() / k_sl.mean())
                            for n, c in cycles.items()},
        "fe3d_vs_slice_percent": {
            "mean": float(100 * (k_fe.mean() / k_sl.mean() - 1)),
            "max": float(100 * (k_fe.max() / k_sl.max() - 1)),
            "min": float(100 * (k_fe.min() / k_sl.min() - 1)),
            "pointwise_range": [float(100 * (k_fe / k_sl - 1).min()),
                                float(100 * (k_fe / k_sl - 1).max())]},
        "transmission_error_p2p_um": {n: float(np.ptp(c.transmission_error) * 1e6)
                                      for n, c in cycles.items()},
        "max_unit_load_N_per_mm": {n: float(c.max_unit_load.max() * 1e-3)
                                   for n, c in cycles.items()},
        "max_residual_m": {n: float(c.residual.max()) for n, c in cycles.items()},
        "max_load_balance_error_N": {n: float(np.abs(c.pair_loads.sum(axis=1) - load).max())
                                     for n, c in cycles.items()},
        "fe3d_model": fe.summary(),
        "fe3d_build_s": t_build,
        "fe3d_cold_build_s": fe.pinion_table.info["seconds"] + fe.gear_table.info["seconds"],
        "fe3d_timings_s": {g: getattr(fe, f"{g}_table").info["timings_s"]
                           for g in ("pinion", "gear")},
        "fe3d_peak_rss_GiB": rss_3d,
        "fe2d_build_s": t_build_2d, "ltca_s": t_ltca,
        "peak_rss_GiB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20,
    }
    deg = np.degrees(cycles["slice"].pinion_angle)
    cols = {"pinion_angle [rad]": cycles["slice"].pinion_angle, "roll_coordinate_s0 [m]": s0}
    for n, c in cycles.items():
        cols[f"{n}_mesh_stiffness [N/m]"] = c.mesh_stiffness
        cols[f"{n}_transmission_error [m]"] = c.transmission_error
        cols[f"{n}_residual [m]"] = c.residual
    files = [write_csv(out / "stiffness.csv", cols), write_json(out / "summary.json", summary)]
    dof = fe.pinion_table.info["dof"], fe.gear_table.info["dof"]
    title = (f"Yang et al. 2026 (z 31/104, beta 4 deg), P = {load / 1e3:.1f} kN, LTCA (weber): "
             f"slice vs 3D FE ({dof[0]}/{dof[1]} DOF, refinement {refinement:g})")
    labels = {"slice": "slice method (independent slices)",
              "fe3d": "3D FE, whole gears, face-coupled",
              "fe2d_strain": "2D FE, whole gears, plane strain",
              "fe2d_stress": "2D FE, whole gears, plane stress"}
    files.append(save(plot(deg, {labels[n]: c for n, c in cycles.items()}, title),
                      out / "stiffness.png"))
    write_run_record(out, {"config": str(CONFIG), "pair": cfg, "fe3d": asdict(settings),
                           "positions": positions, "local_contact": "weber"},
                     files, "workflows/fe3d_helical_stiffness.py", referenced={"config": CONFIG})
    return summary


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--full", action="store_true",
                    help=f"{FULL} instead of {COARSE}")
    ap.add_argument("--out", type=Path, default=None, help="default: results/<script>/workflow")
    args = ap.parse_args(argv)
    args.out = workflow_dir(__file__, args.out)
    with staged_output(args.out) as out:
        summary = run(out, **(FULL if args.full else COARSE))
    for name in (n for n in ("slice", "fe3d", "fe2d_strain", "fe2d_stress") if n in summary):
        row = summary[name]
        print(f"{name:11s} " + "  ".join(f"{k} {v:.4g}" for k, v in row.items()))
    print("fe3d vs slice [%]", summary["fe3d_vs_slice_percent"])
    for g, t in summary["fe3d_timings_s"].items():
        print(f"3D FE {g} (cold build): " + ", ".join(f"{k} {v:.1f} s" for k, v in t.items()))
    print(f"3D FE build {summary['fe3d_build_s']:.0f} s (cold: "
          f"{summary['fe3d_cold_build_s']:.0f} s), peak RSS "
          f"{summary['peak_rss_GiB']:.2f} GiB; written to {args.out}/")
    return summary


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
