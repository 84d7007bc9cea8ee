"""``gearpipe contact CONFIG``: loaded tooth contact over a mesh cycle -> CSV/JSON/PNG/VTU.

Reads the same TOML as ``gearpipe stiffness`` plus an optional ``[contact]``
table (:mod:`pipeline.contact.options`). The compliance is the analytical slice
compliance (the optimised slice method of Yang et al. 2026 with ``local_contact = "weber"``);
writes per-position results, per-point unit loads, the load map (PNG + VTU),
a summary JSON and ``run.json`` to ``results/<config>/contact/``.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from pipeline.commands_common import add_common_arguments, emit, output_dir
from pipeline.config import PairConfig, load_pair_config, load_toml
from pipeline.contact.loadmap import flank_load_map, write_load_map_vtu
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.options import ContactOptions, contact_options_from_table
from pipeline.contact.results import LoadedMeshCycle
from pipeline.contact.source import SliceCompliance
from pipeline.geometry.assembly_errors import AssembledPair
from pipeline.geometry.pair import GearPair
from pipeline.io import write_csv, write_json, write_run_record
from pipeline.stiffness.analysis import friction_model
from pipeline.stiffness.mesh import OperatingPoint, PairModel, stiffness_at
from pipeline.stiffness.tooth import classical_tooth_model, hertz_compliance


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    parser.add_argument("--tooth-model", choices=("exact", "classical"), default="exact",
                        help="exact profile with fillet (default) or the classical involute "
                             "clamped at the base circle (Yang et al. 2026, eqs. 11-13)")


def build_source(cfg: PairConfig, opts: ContactOptions, tooth_model: str = "exact"
                 ) -> tuple[SliceCompliance, GearPair, AssembledPair | None]:
    """Slice compliance source of the *actual* pair (after assembly errors)."""
    nominal = GearPair(cfg.pinion, cfg.gear, cfg.centre_distance)
    errors = cfg.assembly_errors
    assembled = None if errors.is_zero else AssembledPair(nominal, errors)
    actual = nominal if assembled is None else assembled.actual
    if tooth_model == "classical":
        model = PairModel(actual, classical_tooth_model(actual.pinion),
                          classical_tooth_model(actual.gear),
                          hertz_compliance(actual.pinion, actual.gear))
    else:
        model = PairModel.build(actual)
    op = OperatingPoint(cfg.operation.torque, cfg.operation.speed, cfg.operation.driver)
    src = SliceCompliance(model, opts.slices, friction_model(cfg), op,
                          cfg.stiffness.foundation_correction, opts.slice_coupling)
    return src, actual, assembled


def line_of_action_load(cfg: PairConfig, pair: GearPair) -> float:
    """P = driving torque / driver's base radius, N (transverse line of action)."""
    driver = pair.pinion if cfg.operation.driver == "pinion" else pair.gear
    return cfg.operation.torque / driver.base_radius


def write_cycle(cyc: LoadedMeshCycle, out: Path) -> list[Path]:
    cols = {
        "pinion_angle [rad]": cyc.pinion_angle,
        "roll_coordinate_s0 [m]": cyc.s0,
        "transmission_error [m]": cyc.transmission_error,
        "mesh_stiffness_tangent [N/m]": cyc.mesh_stiffness,
        "mesh_stiffness_secant [N/m]": cyc.mesh_stiffness_secant,
        "mesh_stiffness_pointwise [N/m]": cyc.mesh_stiffness_pointwise,
        "max_unit_load [N/mm]": cyc.max_unit_load * 1e-3,
        "residual [m]": cyc.residual,
    }
    for j, k in enumerate(cyc.pair_index):
        cols[f"load_share_pair_{k} [-]"] = cyc.load_share[:, j]
    pts = {
        "position [-]": cyc.point_position,
        "roll_coordinate_s [m]": cyc.point_s,
        "face_position_z [m]": cyc.point_z,
        "tooth_pair [-]": cyc.point_pair,
        "slice_width [m]": cyc.point_width,
        "load [N]": cyc.point_load,
        "unit_load [N/mm]": cyc.point_unit_load * 1e-3,
        "initial_separation [m]": cyc.point_separation,
        "contact_deformation [m]": cyc.point_contact_deformation,
    }
    return [write_csv(out / "contact_cycle.csv", cols), write_csv(out / "contact_points.csv", pts)]


def run(args: argparse.Namespace) -> int:
    from pipeline.viz import save
    from pipeline.viz.contact import plot_contact_cycle
    from pipeline.viz.loadmap import plot_load_map_2d, render_load_map

    cfg = load_pair_config(args.config)
    opts = contact_options_from_table(load_toml(args.config).get("contact"))
    out = output_dir(args, "contact")
    src, pair, assembled = build_source(cfg, opts, args.tooth_model)
    load = line_of_action_load(cfg, pair)
    cyc = loaded_mesh_cycle(src, load, opts.modifications, opts.local_contact, opts.positions,
                            show_progress=True)
    ref = stiffness_at(src.model, cyc.s0, opts.slices, src.friction, src.operating,
                       cfg.stiffness.foundation_correction)
    title = (f"{cfg.name}: P = {load:.0f} N, local contact {opts.local_contact}, "
             f"beta {math.degrees(cfg.pinion.helix_angle):g} deg")
    files = write_cycle(cyc, out)
    files.append(save(plot_contact_cycle(cyc, ref.total, title), out / "contact_cycle.png"))
    lm = flank_load_map(cyc, pair, opts.load_map_profile_points)
    files.append(save(plot_load_map_2d(lm, title), out / "load_map_2d.png"))
    files.append(write_load_map_vtu(pair, lm, out / "load_map.vtu"))
    if opts.render:
        files.append(save(render_load_map(pair, lm, title), out / "load_map.png"))
    summary = {
        **cyc.summary(),
        "slice_method_mean_N_per_m": ref.mean,
        "ltca_over_slice_method_mean": float(cyc.mesh_stiffness.mean() / ref.mean),
        "transmission_error_peak_to_peak_urad": float(np.ptp(cyc.transmission_error)
                                                      / pair.pinion.base_radius * 1e6),
        "max_unit_load_N_per_mm": float(cyc.max_unit_load.max() * 1e-3),
        "positions": len(cyc),
        "local_contact": opts.local_contact,
    }
    if assembled is not None:
        summary["assembly_errors"] = assembled.summary()
    files.append(write_json(out / "contact.json", summary))
    write_run_record(out, {"pair": cfg, "contact": opts, "tooth_model": args.tooth_model},
                     files, f"gearpipe contact {args.config}")
    emit(args, summary, out)
    return 0
