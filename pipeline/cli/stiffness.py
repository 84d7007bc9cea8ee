"""``gearpipe stiffness CONFIG``: analytical mesh stiffness over a mesh cycle -> CSV/JSON/PNG."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from pipeline.cli.common import add_common_arguments, emit, load, output_dir, record
from pipeline.io import write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.stiffness.analysis import StiffnessResult, analyse_stiffness
from pipeline.validation import check_int_range
from pipeline.viz.figure_cache import NO_CACHE, FigureCache


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    parser.add_argument("--harmonics", type=int, default=10,
                        help="Fourier orders of k(t) written to the JSON (default 10)")


def write_stiffness(res: StiffnessResult, out: Path, title: str, prefix: str = "",
                    figures: FigureCache = NO_CACHE) -> list[Path]:
    """CSV of k(t), the stiffness and friction plots (file names start with ``prefix``);
    returns the files written."""
    from pipeline.viz.stiffness import plot_friction_coefficients, plot_stiffness_curves

    m = res.mesh
    deg = np.degrees(m.pinion_angle)
    files = [write_csv(out / f"{prefix}mesh_stiffness.csv", res.columns())]
    files.append(figures.save(
        out / f"{prefix}mesh_stiffness.png", plot_stiffness_curves,
        [("potential energy (this model)", deg, m.total),
         ("contact-line method (ISO 6336)", deg, res.contact_line.total)],
        title=title, pairs=m.pairs, pairs_x=deg))
    if np.any(m.friction_stiffness != 0):
        files.append(figures.save(out / f"{prefix}friction_coefficients.png",
                                  plot_friction_coefficients, deg, m.friction_stiffness,
                                  m.friction_torque_pinion, m.friction_torque_gear, title))
    return files


def run(args: argparse.Namespace) -> int:
    check_int_range("--harmonics", args.harmonics, 1, 1000)
    box = load(args)
    pair = box.require_pair()
    target = output_dir(args, "stiffness")
    res = analyse_stiffness(pair, box.operation, box.stiffness,
                            assembly_errors=box.assembly_errors)
    summary = res.summary(args.harmonics)
    title = (f"{box.name}: z {pair.pinion.teeth}/{pair.gear.teeth}, "
             f"m_n {pair.pinion.module * 1e3:g} mm, "
             f"beta {math.degrees(pair.pinion.helix_angle):g} deg, "
             f"friction {box.stiffness.friction}")
    with staged_output(target) as out:
        files = write_stiffness(res, out, title)
        files.append(write_json(out / "mesh_stiffness.json", summary))
        record(out, args, box, files)
    emit(args, summary, target)
    return 0
