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
import dataclasses
from pathlib import Path

import numpy as np

from pipeline.commands_common import add_common_arguments, emit, load, output_dir
from pipeline.fem.flank import active_radii, flank_points
from pipeline.fem.influence import constrained_dofs, influence_matrix
from pipeline.fem.linear_static import build_model, solve_static
from pipeline.fem.options import PLANE_KINDS, SectorFEOptions
from pipeline.fem.patch_loads import patch_loads
from pipeline.fem.sector2d import SectorSettings2D, sector_mesh_2d
from pipeline.geometry.gear import GearSpec
from pipeline.io import atomic_write, write_csv, write_json, write_run_record


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    parser.add_argument("--teeth", type=int, default=None,
                        help="teeth in the sector (default: [fe] teeth, else 5)")
    parser.add_argument("--points", type=int, default=None,
                        help="points per flank (default: [fe] points, else 40)")
    parser.add_argument("--refinement", type=float, default=None,
                        help="mesh refinement, flank size m_n / (12 refinement) "
                             "(default: [fe] refinement, else 2)")
    parser.add_argument("--kind", choices=PLANE_KINDS, default=None,
                        help="2D model (default: [fe] kind, else plane_strain)")


def analyse_gear(gear: GearSpec, args: SectorFEOptions, out: Path, tag: str) -> tuple[dict,
                                                                                       list]:
    """Mesh, influence matrix and single-tooth comparison of one gear; returns summary, files."""
    from pipeline.stiffness.tooth import tooth_compliance, tooth_model
    from pipeline.viz import save
    from pipeline.viz.fem import plot_compliance, plot_deformed, plot_sector_mesh

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


def options(box_fe: SectorFEOptions, args: argparse.Namespace) -> SectorFEOptions:
    """The ``[fe]`` table with the command-line options that were given on top."""
    given = {k: getattr(args, k) for k in ("teeth", "points", "refinement", "kind")
             if getattr(args, k) is not None}
    return dataclasses.replace(box_fe, **given)


def run(args: argparse.Namespace) -> int:
    box = load(args)
    pair = box.require_pair()
    opts = options(box.fe, args)
    out = output_dir(args, "fe")
    summary, files = {}, []
    for tag, gear in (("pinion", pair.pinion), ("gear", pair.gear)):
        s, f = analyse_gear(gear, opts, out, tag)
        summary[tag] = s
        files += f
    files.append(write_json(out / "fe_summary.json", summary))
    write_run_record(out, {"gearbox": box.to_dict(), "fe": opts}, files,
                     f"gearpipe fe {args.config}")
    emit(args, summary, out)
    return 0
