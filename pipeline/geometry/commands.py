"""``gearpipe geometry CONFIG``: tooth profiles, contact ratios and line of action of a pair."""

from __future__ import annotations

import argparse
import math

from pipeline.commands_common import add_common_arguments, emit, output_dir
from pipeline.config import load_pair_config
from pipeline.geometry.assembly_errors import AssembledPair
from pipeline.geometry.pair import GearPair
from pipeline.io import write_json, write_run_record


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)


def geometry_summary(pair: GearPair) -> dict:
    """Pair and gear quantities for reports (SI, keys carry units)."""
    out = dict(pair.summary())
    for g in (pair.pinion, pair.gear):
        out[f"{g.name}_base_radius_m"] = g.base_radius
        out[f"{g.name}_tip_radius_m"] = g.tip_radius_
        out[f"{g.name}_root_radius_m"] = g.root_radius
        out[f"{g.name}_tip_thickness_m"] = g.tooth_thickness_tip
    return out


def run(args: argparse.Namespace) -> int:
    from matplotlib.figure import Figure

    from pipeline.geometry.profile import tooth_profile
    from pipeline.viz import save
    from pipeline.viz.geometry import plot_contact_lines, plot_line_of_action, plot_profile

    cfg = load_pair_config(args.config)
    out = output_dir(args, "geometry")
    pair = GearPair(cfg.pinion, cfg.gear, cfg.centre_distance)
    summary = geometry_summary(pair)
    files = [save(plot_line_of_action(pair), out / "line_of_action.png")]
    if not cfg.assembly_errors.is_zero:
        ap = AssembledPair(pair, cfg.assembly_errors)
        summary["assembly_errors"] = ap.summary()
        files.append(save(plot_line_of_action(ap.actual, title="with assembly errors: "
                          f"eps_alpha = {ap.actual.transverse_contact_ratio:.4f}, alpha_wt = "
                          f"{math.degrees(ap.actual.operating_pressure_angle):.4f} deg"),
                          out / "line_of_action_actual.png"))
    if pair.pinion.is_helical:
        files.append(save(plot_contact_lines(pair), out / "contact_lines.png"))
    fig = Figure(figsize=(9, 8))
    axes = fig.subplots(2, 1)
    for ax, g in zip(axes, (pair.pinion, pair.gear), strict=True):
        prof = tooth_profile(g)
        plot_profile(prof, ax=ax)
        ax.set_title(f"{g.name}: z = {g.teeth}, undercut = {prof.undercut}")
        summary[f"{g.name}_form_radius_m"] = prof.form_radius
        summary[f"{g.name}_undercut"] = bool(prof.undercut)
        summary[f"{g.name}_thin_tip"] = bool(prof.thin_tip)
    files.append(save(fig, out / "tooth_profiles.png"))
    files.append(write_json(out / "geometry.json", summary))
    write_run_record(out, cfg, files, f"gearpipe geometry {args.config}")
    emit(args, summary, out)
    return 0
