"""``gearpipe geometry CONFIG``: tooth profiles, contact ratios and line of action of a pair."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from pipeline.commands_common import add_common_arguments, emit, load, output_dir
from pipeline.geometry.analysis import GeometryResult, analyse_geometry
from pipeline.io import write_json, write_run_record


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)


def write_geometry(res: GeometryResult, out: Path, prefix: str = "") -> list[Path]:
    """Line of action (nominal and, with assembly errors, installed), contact lines of a
    helical pair and the tooth profiles (PNG, names start with ``prefix``)."""
    from matplotlib.figure import Figure

    from pipeline.viz import save
    from pipeline.viz.geometry import plot_contact_lines, plot_line_of_action, plot_profile

    pair, ap = res.pair, res.assembled
    files = [save(plot_line_of_action(pair), out / f"{prefix}line_of_action.png")]
    if ap is not None:
        files.append(save(plot_line_of_action(ap.actual, title="with assembly errors: "
                          f"eps_alpha = {ap.actual.transverse_contact_ratio:.4f}, alpha_wt = "
                          f"{math.degrees(ap.actual.operating_pressure_angle):.4f} deg"),
                          out / f"{prefix}line_of_action_actual.png"))
    if pair.pinion.is_helical:
        files.append(save(plot_contact_lines(pair), out / f"{prefix}contact_lines.png"))
    fig = Figure(figsize=(9, 8))
    axes = fig.subplots(2, 1)
    for ax, g, prof in zip(axes, (pair.pinion, pair.gear), res.profiles, strict=True):
        plot_profile(prof, ax=ax)
        ax.set_title(f"{g.name}: z = {g.teeth}, undercut = {prof.undercut}")
    files.append(save(fig, out / f"{prefix}tooth_profiles.png"))
    return files


def run(args: argparse.Namespace) -> int:
    box = load(args)
    res = analyse_geometry(box.require_pair(), box.assembly_errors)
    out = output_dir(args, "geometry")
    files = write_geometry(res, out)
    summary = res.summary()
    files.append(write_json(out / "geometry.json", summary))
    write_run_record(out, box.to_dict(), files, f"gearpipe geometry {args.config}")
    emit(args, summary, out)
    return 0
