"""Sweep the relief groove of Xu et al. (2020) sun gear: torsional stiffness vs width and depth.

For every groove width and groove bottom diameter the 3D P2 model of the sun body
(root-cylinder halves, distributed coupling unless the config says otherwise)
gives k_t between O_L and O_R and K_j = k_t l_LR. Writes to results/groove_sweep/workflow/:
``groove_sweep.csv``, ``groove_sweep.png`` (k_t and K_j against the groove width,
one curve per bottom diameter, with the paper's 4.0e7 - 5.2e7 N m^2 band),
``twist.png`` (the configured case under its sun torque) and ``run.json``.

Xu et al. (2020)'s sun, compared (``configs/wind_turbine_sun_groove.toml``). The paper
gives z 21, m_n 15 mm, 25 deg, 8 deg helix, a 185 mm half width and a 40 mm groove, and K_j
= 5.2e7 N m^2 from G I_j - the G J of a solid round section of 286 mm, i.e. about the root
cylinder (280.6 mm). Assumed here (not in the paper): solid body (no bore), groove bottom
270 mm, a 240 mm x 340 mm shaft on the output side (from l_RT), E 206 GPa / nu 0.3. The FE
gives K_j = 5.98e7 N m^2 (+15 %); real teeth instead of the root cylinder add 0.6 %; a
rigid coupling 83 %. The FE value is higher than the root cylinder's G J because the mesh
torque enters along each half (effective length b/3 of each half instead of b/2 in a beam
between the half centres), lower than that ideal because of the groove section and its
shoulders. A groove bottom of 250 mm gives 5.1e7, inside the paper's 4.0-5.2e7 range.

    python workflows/groove_sweep.py            # coarse: 3 x 3 cases, h = 40 mm
    python workflows/groove_sweep.py --full     # 6 x 4 cases, h = 25 mm
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pipeline.cli import run_workflow  # noqa: E402
from pipeline.cli.common import workflow_dir  # noqa: E402
from pipeline.config import load_gearbox  # noqa: E402
from pipeline.fem.groove.study import analyse_groove  # noqa: E402
from pipeline.io import write_csv  # noqa: E402
from pipeline.output_folder import staged_output  # noqa: E402
from pipeline.progress import progress  # noqa: E402
from pipeline.provenance import write_run_record  # noqa: E402
from pipeline.viz import save  # noqa: E402

CONFIG = ROOT / "workflows" / "configs" / "wind_turbine_sun_groove.toml"


def sweep(config: Path, widths_mm, diameters_mm, mesh_size_mm: float, show_progress=True):
    """k_t (N m/rad) and K_j (N m^2) on the grid; arrays of shape (n_diameters, n_widths)."""
    base = load_gearbox(config).groove
    kt = np.zeros((len(diameters_mm), len(widths_mm)))
    kj = np.zeros_like(kt)
    dofs = np.zeros_like(kt, dtype=int)
    cases = [(i, j) for i in range(len(diameters_mm)) for j in range(len(widths_mm))]
    for i, j in progress(cases, "groove sweep", enabled=show_progress):
        gear = dataclasses.replace(base.gear, groove_width=widths_mm[j] * 1e-3)
        spec = dataclasses.replace(base, gear=gear, groove_bottom_diameter=diameters_mm[i] * 1e-3,
                                   mesh_size=mesh_size_mm * 1e-3)
        res = analyse_groove(spec).result
        kt[i, j], kj[i, j], dofs[i, j] = res.torsional_stiffness, res.equivalent_Kj, res.n_dof
    return base, kt, kj, dofs


def plot(path: Path, widths_mm, diameters_mm, kt, kj, base) -> Path:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 4.2), constrained_layout=True)
    a1, a2 = fig.subplots(1, 2)
    for i, d in enumerate(diameters_mm):
        a1.plot(widths_mm, kt[i] / 1e6, "o-", label=f"groove bottom {d:g} mm")
        a2.plot(widths_mm, kj[i] / 1e7, "o-", label=f"groove bottom {d:g} mm")
    a2.axhspan(4.0, 5.2, color="0.85", zorder=0, label="Xu et al. 2020 range 4.0-5.2e7")
    a1.set(xlabel="groove width g [mm]", ylabel="k_t between O_L and O_R [MN m/rad]",
           title="torsional stiffness of the sun body")
    a2.set(xlabel="groove width g [mm]", ylabel="K_j = k_t l_LR [1e7 N m^2]",
           title="equivalent rigidity (l_LR = b/2 + g)")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle(f"{base.gear.name}: z = {base.gear.teeth}, m_n = {base.gear.module * 1e3:g} mm, "
                 f"halves {base.gear.half_width * 1e3:g} mm; {base.teeth_model}, "
                 f"{base.coupling} coupling, P2 FE", fontsize=10)
    return save(fig, path)


def main(argv: list[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="finer mesh, denser grid")
    parser.add_argument("--config", type=Path, default=CONFIG)
    parser.add_argument("--out", type=Path, default=None,
                        help="default: results/<script>/workflow")
    parser.add_argument("--no-picture", action="store_true", help="skip the pyvista picture")
    args = parser.parse_args(argv)
    args.out = workflow_dir(__file__, args.out)
    if args.full:
        widths, diameters, h = [20, 30, 40, 50, 60, 80], [230, 240, 250, 260, 270], 25.0
    else:
        widths, diameters, h = [20, 40, 60], [250, 260, 270], 40.0
    base, kt, kj, dofs = sweep(args.config, widths, diameters, h)
    with staged_output(args.out) as out:
        W, D = np.meshgrid(widths, diameters)
        files = [write_csv(out / "groove_sweep.csv", {
            "groove width [mm]": W.ravel(), "groove bottom diameter [mm]": D.ravel(),
            "k_t [N m/rad]": kt.ravel(), "K_j [N m^2]": kj.ravel(), "n_dof": dofs.ravel()}),
            plot(out / "groove_sweep.png", widths, diameters, kt, kj, base)]
        if not args.no_picture:
            from pipeline.viz.groove import render_twisted_body

            a = analyse_groove(dataclasses.replace(base, mesh_size=h * 1e-3))
            files.append(save(render_twisted_body(a, base.sun_torque or 1e5), out / "twist.png"))
        write_run_record(out, {"config": dataclasses.asdict(base), "widths_mm": widths,
                               "diameters_mm": diameters, "mesh_size_mm": h}, files,
                         "workflows/groove_sweep.py" + (" --full" if args.full else ""),
                         referenced={"config": CONFIG})
    i40 = widths.index(40) if 40 in widths else 0
    i270 = diameters.index(270) if 270 in diameters else 0
    print(f"k_t(g = {widths[i40]} mm, d = {diameters[i270]} mm) = {kt[i270, i40]:.4e} N m/rad, "
          f"K_j = {kj[i270, i40]:.4e} N m^2; written to {out}")
    return {"widths": widths, "diameters": diameters, "kt": kt, "kj": kj}


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
