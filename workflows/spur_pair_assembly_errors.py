"""Stiffness study of the assembly-error paper: friction 0 / 0.05 / 0.1 and assembly-error
conditions 1-3.

Spur pair z 50/50, m 3 mm, 20 deg, b 20 mm, 340 N m at 2340 rpm (the assembly-error paper table).
Writes to results/spur_pair_assembly_errors/workflow/: overlay plots (PNG), the curves (CSV), a
table of max/min/mean per case (CSV + JSON) and run.json.

    python workflows/spur_pair_assembly_errors.py [--full] [--out DIR]
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
from pipeline.geometry.assembly_errors import AssemblyErrors
from pipeline.io import write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.progress import progress
from pipeline.provenance import write_run_record
from pipeline.stiffness.analysis import analyse_stiffness
from pipeline.viz import save
from pipeline.viz.stiffness import plot_stiffness_curves

HERE = Path(__file__).resolve().parent
CONFIG = HERE / "configs" / "spur_pair_assembly_errors.toml"
UM = 1e-6
CONDITIONS = {  # the assembly-error paper table: (e_xp, e_yp), (e_xg, e_yg) in um
    "condition 1 (ideal)": ((0.0, 0.0), (0.0, 0.0)),
    "condition 2 (10 um)": ((0.0, 0.0), (10.0, 10.0)),
    "condition 3 (100 um)": ((0.0, 0.0), (100.0, 100.0)),
}
FRICTION = (0.0, 0.05, 0.1)


def run(out: Path, positions: int) -> dict:
    base = load_gearbox(CONFIG)
    base = dataclasses.replace(base, stiffness=dataclasses.replace(base.stiffness,
                                                                   positions=positions))
    cases = [(f"mu = {mu}", dataclasses.replace(
        base, stiffness=dataclasses.replace(base.stiffness, friction=mu))) for mu in FRICTION]
    for name, (ep, eg) in CONDITIONS.items():
        errors = AssemblyErrors(tuple(v * UM for v in ep), tuple(v * UM for v in eg))
        cases.append((f"{name}, mu = 0", dataclasses.replace(base, assembly_errors=errors)))
    results = {}
    for name, cfg in progress(cases, "spur pair cases"):
        results[name] = analyse_stiffness(cfg.pair, cfg.operation, cfg.stiffness,
                                          assembly_errors=cfg.assembly_errors)
    table = {}
    for name, r in results.items():
        s = r.mesh.summary()
        table[name] = {
            **s,
            "transverse_contact_ratio": r.actual.transverse_contact_ratio,
            "double_contact_fraction_of_cycle": float(np.mean(np.sum(r.mesh.pairs > 0, 1) > 1)),
            "centre_distance_m": r.actual.operating_centre_distance,
        }
    ref = table["mu = 0.0"]
    for row in table.values():
        for key in ("mean", "max", "min"):
            row[f"{key}_change_vs_frictionless_ideal_percent"] = 100 * (
                row[f"{key}_N_per_m"] / ref[f"{key}_N_per_m"] - 1)
    files = [write_json(out / "summary.json", table)]
    files.append(write_csv(out / "summary.csv", {
        "case_index [-]": np.arange(len(table)),
        "mean [N/m]": [t["mean_N_per_m"] for t in table.values()],
        "max [N/m]": [t["max_N_per_m"] for t in table.values()],
        "min [N/m]": [t["min_N_per_m"] for t in table.values()],
        "contact_ratio [-]": [t["transverse_contact_ratio"] for t in table.values()],
    }))
    deg = lambda r: np.degrees(r.mesh.pinion_angle)  # noqa: E731
    fr = [(n, deg(results[n]), results[n].mesh.total) for n in results if n.startswith("mu")]
    files.append(save(plot_stiffness_curves(fr, title="Spur pair: friction (condition 1)"),
                      out / "friction.png"))
    ae = [(n, deg(results[n]), results[n].mesh.total) for n in results if n.startswith("cond")]
    files.append(save(plot_stiffness_curves(ae, title="Spur pair: assembly errors (mu = 0)"),
                      out / "assembly_errors.png"))
    cols = {"pinion_angle [rad]": results["mu = 0.0"].mesh.pinion_angle}
    for i, (n, r) in enumerate(results.items()):
        cols[f"case{i} {n} [N/m]"] = r.mesh.total
    files.append(write_csv(out / "curves.csv", cols))
    write_run_record(out, {"config": str(CONFIG), "positions": positions,
                           "cases": list(results)},
                     files, "workflows/spur_pair_assembly_errors.py",
                     referenced={"config": CONFIG})
    return table


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--full", action="store_true", help="3600 positions per mesh cycle")
    ap.add_argument("--out", type=Path, default=None, help="default: results/<script>/workflow")
    args = ap.parse_args(argv)
    target = workflow_dir(__file__, args.out)
    with staged_output(target) as out:
        table = run(out, 3600 if args.full else 360)
    for name, row in table.items():
        print(f"{name:32s} mean {row['mean_N_per_m']:.4e}  max {row['max_N_per_m']:.4e}  "
              f"min {row['min_N_per_m']:.4e} N/m  eps_a {row['transverse_contact_ratio']:.4f}")
    print(f"written to {target}/")
    return table


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
