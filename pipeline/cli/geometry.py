"""``gearpipe geometry CONFIG``: tooth profiles, contact ratios and line of action of a pair."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from pipeline.cli.common import add_common_arguments, emit, load, output_dir, record
from pipeline.geometry.analysis import GeometryResult, analyse_geometry
from pipeline.io import write_json
from pipeline.output_folder import staged_output
from pipeline.viz.figure_cache import NO_CACHE, FigureCache


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)


def write_geometry(res: GeometryResult, out: Path, prefix: str = "",
                   figures: FigureCache = NO_CACHE, name: str = "") -> list[Path]:
    """Line of action (nominal and, with assembly errors, installed), contact lines of a
    helical pair and the tooth profiles (PNG, names start with ``prefix``; titles with
    ``name``, the case or mesh)."""
    from pipeline.viz.geometry import plot_contact_lines, plot_line_of_action, plot_profiles

    pair, ap = res.pair, res.assembled
    files = [figures.save(out / f"{prefix}line_of_action.png", plot_line_of_action, pair,
                          name=name)]
    if ap is not None:
        files.append(figures.save(
            out / f"{prefix}line_of_action_actual.png", plot_line_of_action, ap.actual,
            title="with assembly errors: "
                  f"eps_alpha = {ap.actual.transverse_contact_ratio:.4f}, alpha_wt = "
                  f"{math.degrees(ap.actual.operating_pressure_angle):.4f} deg", name=name))
    if pair.pinion.is_helical:
        files.append(figures.save(out / f"{prefix}contact_lines.png", plot_contact_lines, pair,
                                  name=name))
    files.append(figures.save(out / f"{prefix}tooth_profiles.png", plot_profiles,
                              (pair.pinion, pair.gear), res.profiles))
    return files


def run(args: argparse.Namespace) -> int:
    box = load(args)
    target = output_dir(args, "geometry")
    res = analyse_geometry(box.require_pair(), box.assembly_errors)
    summary = res.summary()
    with staged_output(target) as out:
        files = write_geometry(res, out, name=box.name)
        files.append(write_json(out / "geometry.json", summary))
        record(out, args, box, files)
    emit(args, summary, target)
    return 0
