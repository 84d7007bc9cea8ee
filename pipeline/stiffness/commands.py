"""``gearpipe stiffness CONFIG``: analytical mesh stiffness over a mesh cycle -> CSV/JSON/PNG."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from pipeline.commands_common import add_common_arguments, emit, output_dir
from pipeline.config import load_pair_config
from pipeline.io import write_csv, write_json, write_run_record
from pipeline.stiffness.analysis import PairStiffness, analyse_pair


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    parser.add_argument("--harmonics", type=int, default=10,
                        help="Fourier orders of k(t) written to the JSON (default 10)")


def stiffness_summary(res: PairStiffness, harmonics: int) -> dict:
    """Summary of a stiffness result (SI; keys carry units)."""
    fs = res.mesh.as_periodic().fourier(min(harmonics, res.mesh.total.size // 2 - 1))
    out = {
        "potential_energy": res.mesh.summary(),
        "contact_line_ISO6336": {
            "mean_N_per_m": float(res.contact_line.total.mean()),
            "max_N_per_m": float(res.contact_line.total.max()),
            "min_N_per_m": float(res.contact_line.total.min()),
        },
        "iso6336": {
            "c_prime_N_per_mm_um": res.iso.c_single * 1e-9,
            "c_gamma_alpha_N_per_mm_um": res.iso.c_gamma_alpha * 1e-9,
            "mesh_stiffness_N_per_m": res.iso.mesh_stiffness,
        },
        "transverse_contact_ratio": res.actual.transverse_contact_ratio,
        "overlap_ratio": res.actual.overlap_ratio,
        "mesh_period_s": res.mesh.mesh_period,
        "fourier_N_per_m": {"mean": fs.mean, "amplitude": fs.amplitude, "phase_rad": fs.phase},
        "sainsot_fit_range_ok": {
            "pinion": res.model.pinion.foundation.in_fit_range,
            "gear": res.model.gear.foundation.in_fit_range,
        },
    }
    if res.assembled is not None:
        out["assembly_errors"] = res.assembled.summary()
    return out


def write_stiffness(res: PairStiffness, out: Path, title: str) -> list[Path]:
    """CSV of k(t), the stiffness and friction plots; returns the files written."""
    from pipeline.viz import save
    from pipeline.viz.stiffness import plot_friction_coefficients, plot_stiffness_curves

    m = res.mesh
    deg = np.degrees(m.pinion_angle)
    cols = {
        "pinion_angle [rad]": m.pinion_angle,
        "roll_coordinate_s0 [m]": m.s0,
        "mesh_stiffness [N/m]": m.total,
        "contact_line_method [N/m]": res.contact_line.total,
        "friction_stiffness [N/m]": m.friction_stiffness,
        "friction_torque_coef_pinion [N]": m.friction_torque_pinion,
        "friction_torque_coef_gear [N]": m.friction_torque_gear,
        "contact_length [m]": m.contact_length,
    }
    files = [write_csv(out / "mesh_stiffness.csv", cols)]
    ax = plot_stiffness_curves(
        [("potential energy (this model)", deg, m.total),
         ("contact-line method (ISO 6336)", deg, res.contact_line.total)],
        title=title, pairs=m.pairs, pairs_x=deg)
    files.append(save(ax, out / "mesh_stiffness.png"))
    if np.any(m.friction_stiffness != 0):
        files.append(save(plot_friction_coefficients(deg, m.friction_stiffness,
                                                     m.friction_torque_pinion,
                                                     m.friction_torque_gear, title),
                          out / "friction_coefficients.png"))
    return files


def run(args: argparse.Namespace) -> int:
    cfg = load_pair_config(args.config)
    out = output_dir(args, "stiffness")
    res = analyse_pair(cfg)
    summary = stiffness_summary(res, args.harmonics)
    title = (
        f"{cfg.name}: z {cfg.pinion.teeth}/{cfg.gear.teeth}, "
        f"m_n {cfg.pinion.module * 1e3:g} mm, "
        f"beta {math.degrees(cfg.pinion.helix_angle):g} deg, "
        f"friction {cfg.stiffness.friction}"
    )
    files = write_stiffness(res, out, title)
    files.append(write_json(out / "mesh_stiffness.json", summary))
    write_run_record(out, cfg, files, f"gearpipe stiffness {args.config}")
    emit(args, summary, out)
    return 0
