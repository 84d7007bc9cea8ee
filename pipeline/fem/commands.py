"""``gearpipe fe CONFIG``: 2D sector FE of both gears -> mesh, influence matrix, compliance.

For each gear of the pair: the 2D sector mesh (``--teeth`` teeth, ``--refinement``),
the structural influence matrix of ``--points`` points per flank on every tooth
(summary: size, symmetry, timings, rim coupling), the single-tooth FE compliance
along the profile against the analytical tooth compliance (bending + shear +
axial + Sainsot foundation, :mod:`pipeline.stiffness.tooth`), PNGs of the mesh
and of the sector deformed by a unit load at the pitch radius. Writes CSV/JSON/PNG
and ``run.json`` to ``results/<config>/fe/``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from pipeline.commands_common import add_common_arguments, emit, output_dir
from pipeline.config import load_pair_config
from pipeline.fem.flank import active_radii, flank_points
from pipeline.fem.influence import constrained_dofs, influence_matrix
from pipeline.fem.linear_static import build_model, solve_static
from pipeline.fem.patch_loads import patch_loads
from pipeline.fem.sector2d import SectorSettings2D, sector_mesh_2d
from pipeline.geometry.gear import GearSpec
from pipeline.io import atomic_write, write_csv, write_json, write_run_record
from pipeline.validation import check_int_range, check_range


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    parser.add_argument("--teeth", type=int, default=5, help="teeth in the sector (default 5)")
    parser.add_argument("--points", type=int, default=40, help="points per flank (default 40)")
    parser.add_argument("--refinement", type=float, default=2.0,
                        help="mesh refinement (flank size m_n / (12 refinement); default 2)")
    parser.add_argument("--kind", choices=("plane_strain", "plane_stress"),
                        default="plane_strain", help="2D model (default plane_strain)")


def analyse_gear(gear: GearSpec, args: argparse.Namespace, out: Path, tag: str) -> tuple[dict,
                                                                                       list]:
    """Mesh, influence matrix and single-tooth comparison of one gear; returns summary, files."""
    from pipeline.fem.sector_plots import plot_compliance, plot_deformed, plot_sector_mesh
    from pipeline.stiffness.tooth import tooth_compliance, tooth_model
    from pipeline.viz.pair_plots import save

    n, mid = args.teeth, args.teeth // 2
    sec = sector_mesh_2d(gear, SectorSettings2D.for_gear(gear, n, args.refinement))
    r = active_radii(gear, args.points)
    pts = flank_points(gear, n, np.repeat(np.arange(n), r.size), np.tile(r, n))
    G = influence_matrix(sec, pts, kind=args.kind)
    S = G.structural
    diag = np.diag(S)[mid * r.size:(mid + 1) * r.size]
    an = tooth_compliance(tooth_model(gear), r)
    an_total = an.tooth + an.foundation
    files = [write_csv(out / f"{tag}_tooth_compliance.csv", {
        "radius [m]": r, "fe_structural [m^2/N]": diag,
        "fe_raw_patch [m^2/N]": np.diag(G.fe)[mid * r.size:(mid + 1) * r.size],
        "analytical_total [m^2/N]": an_total, "analytical_tooth [m^2/N]": an.tooth,
        "analytical_foundation [m^2/N]": an.foundation})]
    files.append(atomic_write(out / f"{tag}_influence_m2_per_N.npy", lambda p: np.save(p, S)))
    title = f"{gear.name}: z {gear.teeth}, m_n {gear.module * 1e3:g} mm, {n}-tooth sector"
    files.append(save(plot_sector_mesh(sec, title), out / f"{tag}_mesh.png"))
    files.append(save(plot_compliance(r, [("FE structural (" + args.kind + ")", diag),
                                          ("analytical b+s+a+foundation", an_total)], title),
                      out / f"{tag}_tooth_compliance.png"))
    # one deformed picture: 1 N/mm at the pitch radius of the middle tooth
    model = build_model(sec.mesh, gear.material, kind=args.kind)
    one = flank_points(gear, n, [mid], [gear.reference_radius])
    u = solve_static(model, 1e3 * patch_loads(sec, one, G.patch_half_width).toarray(),
                     constrained_dofs(sec, model)).displacements[:, 0]
    scale = 0.05 * gear.module / max(np.abs(u).max(), 1e-30)
    files.append(save(plot_deformed(sec, u, scale, title + ", 1 N/mm at the pitch radius"),
                      out / f"{tag}_deformed.png"))
    ratio = diag / an_total
    summary = {
        "sector_teeth": n, "nodes": sec.n_nodes, "dof": G.n_dof, "points": len(pts),
        "solver": G.method, "timings_s": G.timings, "symmetry_error": G.symmetry_error(),
        "rim_coupling_max_ratio": float(np.max(S[mid * r.size:(mid + 1) * r.size, :r.size]
                                               / diag[:, None])),
        "fe_over_analytical_min": float(ratio.min()),
        "fe_over_analytical_max": float(ratio.max()),
        "fe_compliance_pitch_m2_per_N": float(np.interp(gear.reference_radius, r, diag)),
    }
    return summary, files


def run(args: argparse.Namespace) -> int:
    check_int_range("fe.teeth", args.teeth, 1, 99)
    check_int_range("fe.points", args.points, 1, 1000)
    check_range("fe.refinement", args.refinement, 0.1, 20.0)
    cfg = load_pair_config(args.config)
    out = output_dir(args, "fe")
    summary, files = {}, []
    for tag, gear in (("pinion", cfg.pinion), ("gear", cfg.gear)):
        s, f = analyse_gear(gear, args, out, tag)
        summary[tag] = s
        files += f
    files.append(write_json(out / "fe_summary.json", summary))
    write_run_record(out, cfg, files, f"gearpipe fe {args.config}")
    emit(args, summary, out)
    return 0
