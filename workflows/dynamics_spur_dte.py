"""DTE study of the assembly-error paper: spur pair base case, three assembly-error conditions,
friction 0/0.05/0.1.

The 6-DOF lateral-torsional model of the assembly-error paper (z 50/50, m 3 mm, 20 deg, b 20 mm,
340 N m, 2340 rpm; gears and operation from workflows/configs/spur_pair_assembly_errors.toml)
is solved for its steady periodic response by harmonic balance. The mesh
excitation is the pipeline's analytical (potential-energy) mesh stiffness of the
*actual* pair (centres displaced by the assembly-error paper assembly errors,
pipeline.geometry.assembly_errors) with Jin et al. (2018) friction stiffness and
friction torque coefficients for the friction coefficient
(pipeline.dynamics.mesh_input).

The paper gives no DTE values, only trends in words, and this model does not reproduce
them: its DTE peak-to-peak rises with the friction and with the assembly error in every
case. The base case's 23.83 um (condition 1, mu = 0) is checked against an independent
time integration, its quasi-static limit and its convergence in the harmonics and
positions in tests/test_dyn_spur_dte.py.

Writes results/dynamics_spur_dte/workflow/: dte_friction.png, dte_conditions.png (DTE and
mesh force over one mesh period), spectrum_friction.png, spectrum_conditions.png,
summary.csv (DTE peak-to-peak, mean, RMS mesh force, first DTE harmonics per case),
run.json.

    python workflows/dynamics_spur_dte.py [--full] [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.config import load_gearbox
from pipeline.dynamics.harmonic_balance import harmonic_balance
from pipeline.dynamics.mesh_input import analytical_excitation
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.geometry.assembly_errors import AssembledPair, AssemblyErrors
from pipeline.geometry.pair import GearPair
from pipeline.io import write_csv
from pipeline.output_folder import staged_output
from pipeline.provenance import write_run_record
from pipeline.stiffness.mesh import FrictionModel
from pipeline.viz import save
from pipeline.viz.dynamics import plot_spectrum, plot_time_history

CONFIG = Path(__file__).resolve().parent / "configs" / "spur_pair_assembly_errors.toml"
# (e_xp, e_yp), (e_xg, e_yg) in um, the assembly-error paper table of conditions
CONDITIONS = {
    1: ((0.0, 0.0), (0.0, 0.0)),
    2: ((0.0, 0.0), (10.0, 10.0)),
    3: ((0.0, 0.0), (100.0, 100.0)),
}
FRICTIONS = (0.0, 0.05, 0.1)


def actual_pair(condition: int) -> GearPair:
    """The assembly-error paper pair with the centres of one assembly condition."""
    cfg = load_gearbox(CONFIG)
    nominal = GearPair(cfg.pinion, cfg.gear)
    ep, eg = CONDITIONS[condition]
    if not any(ep + eg):
        return nominal
    return AssembledPair(
        nominal, AssemblyErrors(tuple(v * 1e-6 for v in ep), tuple(v * 1e-6 for v in eg))
    ).actual


def model_for(condition: int, mu: float, positions: int = 360) -> tuple[SpurPairModel, GearPair]:
    """The assembly-error paper 6-DOF model driven by the analytical stiffness of one case."""
    cfg = load_gearbox(CONFIG)
    pair = actual_pair(condition)
    op = cfg.operation
    ex = analytical_excitation(pair, FrictionModel(mu), op, positions)
    fr = ex if mu else None
    model = SpurPairModel(
        ex.stiffness,
        pinion_teeth=cfg.pinion.teeth,
        base_radius_pinion=cfg.pinion.base_radius,
        base_radius_gear=cfg.gear.base_radius,
        torque=cfg.operation.torque,
        speed=cfg.operation.speed,
        friction_stiffness=fr and fr.friction_stiffness,
        friction_torque_pinion=fr and fr.friction_torque_pinion,
        friction_torque_gear=fr and fr.friction_torque_gear,
    )
    return model, pair


def run(full: bool = False, out: Path | None = None) -> dict:
    out = workflow_dir(__file__, out, check=False)  # a staging folder, or new
    H = 60 if full else 25
    rows = {
        "condition [-]": [],
        "friction [-]": [],
        "contact ratio [-]": [],
        "dte peak-to-peak [m]": [],
        "dte mean [m]": [],
        "rms mesh force [N]": [],
        "dte harmonic 1 [m]": [],
        "dte harmonic 2 [m]": [],
        "dte harmonic 3 [m]": [],
    }
    responses, labels = [], []
    for cond in CONDITIONS:
        for mu in FRICTIONS:
            model, pair = model_for(cond, mu, 720 if full else 360)
            hr = harmonic_balance(model.assembly().assemble(), H)
            r = hr.response
            rows["condition [-]"].append(cond)
            rows["friction [-]"].append(mu)
            rows["contact ratio [-]"].append(pair.transverse_contact_ratio)
            rows["dte peak-to-peak [m]"].append(r.peak_to_peak_dte()[0])
            rows["dte mean [m]"].append(r.dte[0, r.steady_slice()].mean())
            rows["rms mesh force [N]"].append(r.rms_mesh_force()[0])
            for o in (1, 2, 3):
                rows[f"dte harmonic {o} [m]"].append(hr.dte_amplitude[0, o])
            responses.append(r)
            labels.append(f"cond {cond}, mu {mu}")
    cols = {k: np.array(v, dtype=float) for k, v in rows.items()}
    files = [write_csv(out / "summary.csv", cols)]
    base = [i for i, lab in enumerate(labels) if lab.startswith("cond 1")]
    mu05 = [i for i, lab in enumerate(labels) if lab.endswith("mu 0.05")]
    files.append(
        save(
            plot_time_history(
                [responses[i] for i in base],
                [labels[i] for i in base],
                title="Spur pair, condition 1: DTE and mesh force, friction 0 / 0.05 / 0.1",
            ),
            out / "dte_friction.png",
        )
    )
    files.append(
        save(
            plot_time_history(
                [responses[i] for i in mu05],
                [labels[i] for i in mu05],
                title="Spur pair, mu = 0.05: DTE and mesh force, assembly-error conditions",
            ),
            out / "dte_conditions.png",
        )
    )
    files.append(
        save(
            plot_spectrum(
                [responses[i] for i in base],
                [labels[i] for i in base],
                title="Spur pair, condition 1: DTE spectrum, friction 0 / 0.05 / 0.1",
            ),
            out / "spectrum_friction.png",
        )
    )
    files.append(
        save(
            plot_spectrum(
                [responses[i] for i in mu05],
                [labels[i] for i in mu05],
                title="Spur pair, mu = 0.05: DTE spectrum, assembly-error conditions",
            ),
            out / "spectrum_conditions.png",
        )
    )
    write_run_record(
        out,
        {"full": full, "n_harmonics": H, "stiffness": "analytical"},
        files,
        "workflows/dynamics_spur_dte.py",
        referenced={"config": CONFIG},
    )
    return cols


def main(argv: list[str] | None = None) -> dict:
    """Command-line entry: ``[--full] [--out DIR]``; returns the result table."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--out", default=None, help="default: results/<script>/workflow")
    a = ap.parse_args(argv)
    with staged_output(workflow_dir(__file__, a.out)) as out:
        cols = run(a.full, out)
    for i in range(len(cols["condition [-]"])):
        print(
            f"condition {int(cols['condition [-]'][i])}  mu {cols['friction [-]'][i]:.2f}  "
            f"eps {cols['contact ratio [-]'][i]:.4f}  "
            f"DTE p-p {cols['dte peak-to-peak [m]'][i] * 1e6:7.3f} um  "
            f"RMS force {cols['rms mesh force [N]'][i]:8.1f} N"
        )
    return cols


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
