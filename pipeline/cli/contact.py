"""``gearpipe contact CONFIG``: loaded tooth contact over a mesh cycle -> CSV/JSON/PNG/VTU.

Composes :func:`pipeline.contact.compliance.compliance_source` (the source ``[contact]
compliance`` names: analytical slices, FE 2D or FE 3D with the ``[fe]`` settings) and
:func:`pipeline.contact.analyse_contact` on the gearbox file's pair, ``[operation]``,
``[stiffness]`` and ``[contact]`` tables; writes per-position results, per-point unit
loads, the load map (PNG + VTU), a summary JSON and ``run.json`` to
``results/<file stem>/contact/``.
"""

from __future__ import annotations

import argparse
import math
import warnings
from pathlib import Path

import numpy as np

from pipeline.cli.common import (
    add_cache_arguments,
    add_common_arguments,
    command_cache,
    emit,
    load,
    output_dir,
    record,
)
from pipeline.contact.analysis import TOOTH_MODELS, analyse_contact, analytical_compliance
from pipeline.contact.compliance import compliance_source
from pipeline.contact.loadmap import flank_load_map, write_load_map_vtu
from pipeline.contact.options import ContactOptions
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.pair import GearPair
from pipeline.io import write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.stiffness.mesh import stiffness_at
from pipeline.validation import InputWarning
from pipeline.viz.figure_cache import NO_CACHE, FigureCache


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    add_cache_arguments(parser)
    parser.add_argument("--tooth-model", choices=TOOTH_MODELS, default="exact",
                        help="exact profile with fillet (default) or the classical involute "
                             "clamped at the base circle (Yang et al. 2026, eqs. 11-13)")


def write_contact(cyc: LoadedMeshCycle, pair: GearPair, opts: ContactOptions,
                  k_slice: np.ndarray, title: str, out: Path, prefix: str = "",
                  figures: FigureCache = NO_CACHE,
                  gears: tuple[str, str] = ("pinion", "gear")) -> list[Path]:
    """Cycle and point CSVs, the cycle plot (against the slice method's ``k_slice``, N/m)
    and the load maps (2D PNG, VTU and, with ``opts.render``, the pyvista PNG); ``gears``
    names the mesh's gears in the titles' modifications."""
    from pipeline.viz.contact import plot_contact_cycle
    from pipeline.viz.loadmap import load_map_title, plot_load_map_2d, render_load_map

    lm = flank_load_map(cyc, pair, opts.load_map_profile_points)
    map_title = load_map_title(title, opts.modifications.describe(gears))
    # the longest drawing (1-3 s of CPU) queued first: a drawer that draws while the run goes
    # on (pipeline.viz.figure_queue) begins with it
    rendered = [figures.save(out / f"{prefix}load_map.png", render_load_map, pair, lm,
                             map_title)] if opts.render else []
    files = [write_csv(out / f"{prefix}contact_cycle.csv", cyc.columns()),
             write_csv(out / f"{prefix}contact_points.csv", cyc.point_columns()),
             figures.save(out / f"{prefix}contact_cycle.png", plot_contact_cycle, cyc, k_slice,
                          title)]
    files.append(figures.save(out / f"{prefix}load_map_2d.png", plot_load_map_2d, lm,
                              map_title))
    files.append(write_load_map_vtu(pair, lm, out / f"{prefix}load_map.vtu"))
    return files + rendered


def contact_title(name: str, cyc: LoadedMeshCycle, pair: GearPair, opts: ContactOptions) -> str:
    """Plot title: gearbox (a line of its own: a name may be 80 characters long), load,
    compliance, local contact model, helix angle."""
    return (f"{name}\nP = {cyc.load:.0f} N, {opts.compliance} compliance, local contact "
            f"{opts.local_contact}, beta {math.degrees(pair.pinion.helix_angle):g} deg")


def run(args: argparse.Namespace) -> int:
    box = load(args)
    if box.errors is not None:
        warnings.warn("[contact.errors] acts in gearpipe run (the contact through the "
                      "revolution); gearpipe contact solves one mesh cycle without them",
                      InputWarning, stacklevel=2)
    pair, opts = box.actual_pair, box.contact
    target = output_dir(args, "contact")
    slices = analytical_compliance(pair, box.operation, opts, box.stiffness,
                                   tooth_model=args.tooth_model)
    cache = command_cache(args)
    src = compliance_source(pair, box.operation, opts, box.stiffness, box.fe_source,
                            model=slices.model, cache=cache, show_progress=True)
    cyc = analyse_contact(src, box.operation, opts, show_progress=True)
    ref = stiffness_at(slices.model, cyc.s0, opts.slices, slices.friction, slices.operating,
                       box.stiffness.foundation_correction)
    summary = {
        **cyc.summary(),
        "slice_method_mean_N_per_m": ref.mean,
        "ltca_over_slice_method_mean": float(cyc.mesh_stiffness.mean() / ref.mean),
        "transmission_error_peak_to_peak_urad": float(np.ptp(cyc.transmission_error)
                                                      / pair.pinion.base_radius * 1e6),
        "max_unit_load_N_per_mm": float(cyc.max_unit_load.max() * 1e-3),
        "positions": len(cyc),
        "local_contact": opts.local_contact,
        "compliance": opts.compliance,
    }
    if box.assembled is not None:
        summary["assembly_errors"] = box.assembled.summary()
    with staged_output(target) as out:
        files = write_contact(cyc, pair, opts, ref.total,
                              contact_title(box.name, cyc, pair, opts), out)
        files.append(write_json(out / "contact.json", summary))
        record(out, args, box, files)
    emit(args, summary, target)
    return 0
