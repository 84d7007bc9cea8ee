"""Stiffness study of Yang et al. (2026): helical slice method with friction, and the contact-line
method.

Traction pair of Yang et al. (2026), Table 2 (z 31/104, m_n 7.35 mm, beta 4 deg, a 495 mm,
face width assumed 130 mm) at its rated load (20,233 N m on the wheel).
Writes to results/helical_slice_stiffness/workflow/: mesh stiffness without/with friction
(mu 0.05 and EHL), the single-tooth-pair stiffness along its engagement, the
contact-line (ISO 6336) comparison, a summary table and run.json.

    python workflows/helical_slice_stiffness.py [--full] [--out DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

import numpy as np

from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.config import load_gearbox
from pipeline.io import write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.progress import progress
from pipeline.provenance import write_run_record
from pipeline.stiffness.analysis import analyse_stiffness
from pipeline.stiffness.mesh import PairModel
from pipeline.viz import save
from pipeline.viz.stiffness import plot_stiffness_curves

HERE = Path(__file__).resolve().parent
CONFIG = HERE / "configs" / "traction_helical_pair.toml"


def single_pair_curve(res) -> tuple[np.ndarray, np.ndarray]:
    """Stiffness of one tooth pair through its whole engagement (N/m) vs its z=0 roll coordinate.

    Follows pair index k over consecutive mesh cycles; shape (n,) each.
    """
    m = res.mesh
    pair = res.actual
    ks = pair.pair_indices()
    s_list, k_list = [], []
    for j, k in enumerate(ks):
        s_list.append(m.s0 + k * pair.base_pitch)
        k_list.append(m.pairs[:, j])
    s = np.concatenate(s_list)
    k = np.concatenate(k_list)
    order = np.argsort(s)
    s, k = s[order], k[order]
    keep = k > 0
    return s[keep], k[keep]


def run(out: Path, positions: int, slices: int) -> dict:
    base = load_gearbox(CONFIG)
    base = dataclasses.replace(base, stiffness=dataclasses.replace(
        base.stiffness, positions=positions, slices=slices))
    variants = {"mu = 0": 0.0, "mu = 0.05": 0.05, "EHL friction": "ehl"}
    model = None
    results = {}
    for name, mu in progress(list(variants.items()), "Yang et al. 2026 cases"):
        cfg = dataclasses.replace(base, stiffness=dataclasses.replace(base.stiffness, friction=mu))
        r = analyse_stiffness(cfg.pair, cfg.operation, cfg.stiffness,
                              assembly_errors=cfg.assembly_errors, model=model)
        model = r.model if isinstance(r.model, PairModel) else None
        results[name] = r
    r0 = results["mu = 0"]
    table = {name: r.mesh.summary() for name, r in results.items()}
    table["contact-line method (ISO 6336)"] = {
        "mean_N_per_m": float(r0.contact_line.total.mean()),
        "max_N_per_m": float(r0.contact_line.total.max()),
        "min_N_per_m": float(r0.contact_line.total.min()),
        "peak_to_peak_percent": float(100 * np.ptp(r0.contact_line.total)
                                      / r0.contact_line.total.mean()),
    }
    table["potential_energy_over_contact_line_mean"] = {
        "ratio": r0.mesh.mean / float(r0.contact_line.total.mean())}
    deg = np.degrees(r0.mesh.pinion_angle)
    files = [write_json(out / "summary.json", table)]
    files.append(save(plot_stiffness_curves(
        [(n, deg, r.mesh.total) for n, r in results.items()],
        title="Yang et al. (2026): slice potential-energy method with friction"),
        out / "friction.png"))
    files.append(save(plot_stiffness_curves(
        [("slice potential energy (mu = 0)", deg, r0.mesh.total),
         ("contact-line method (ISO 6336)", deg, r0.contact_line.total)],
        title="Yang et al. (2026): slice method vs contact-line method"),
        out / "contact_line.png"))
    curves = []
    for name in ("mu = 0", "mu = 0.05"):
        s, k = single_pair_curve(results[name])
        curves.append((name, s * 1e3, k))
    files.append(save(plot_stiffness_curves(
        curves, xlabel="roll coordinate of the pair at z = 0 [mm]",
        title="Yang et al. (2026): single tooth pair stiffness through its engagement"),
        out / "single_pair.png"))
    cols = {"pinion_angle [rad]": r0.mesh.pinion_angle,
            "contact_line_method [N/m]": r0.contact_line.total}
    for n, r in results.items():
        cols[f"{n} [N/m]"] = r.mesh.total
    files.append(write_csv(out / "curves.csv", cols))
    write_run_record(out, {"config": str(CONFIG), "positions": positions, "slices": slices},
                     files, "workflows/helical_slice_stiffness.py", referenced={"config": CONFIG})
    return table


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--full", action="store_true", help="720 positions x 200 slices")
    ap.add_argument("--out", type=Path, default=None, help="default: results/<script>/workflow")
    args = ap.parse_args(argv)
    args.out = workflow_dir(__file__, args.out)
    with staged_output(args.out) as out:
        table = run(out, *((720, 200) if args.full else (360, 100)))
    for name, row in table.items():
        print(f"{name:34s} " + "  ".join(f"{k} {v:.4g}" for k, v in row.items()))
    print(f"written to {args.out}/")
    return table


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
