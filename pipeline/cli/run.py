"""``gearpipe run CONFIG``: every stage the gearbox file asks for, into one results folder.

Runs :func:`pipeline.run.runner.run_pipeline` and writes, to ``results/<file stem>/run/``
(or ``--out``): per mesh the geometry (``line_of_action.png``, ``tooth_profiles.png``),
the analytical stiffness (``mesh_stiffness.csv/png``), the loaded
contact cycle on the chosen compliance source (``contact_cycle.csv/png``,
``contact_points.csv``) and its load maps (``load_map_2d.png``, ``load_map.vtu``,
``load_map.png``) - prefixed by the mesh name for a planetary set; gears on shafts add
their deflection lines (``shaft_deflection.csv``) and the misalignment across the face
(``shaft_face.csv``); a pair with ``[contact.errors]`` the contact through the revolution
(``revolution_te.csv/png``, ``revolution_spectrum.csv/png``,
``revolution_worst_pair.png``, ``revolution_worst_pair_load_map.png``;
:mod:`pipeline.cli.revolution_files`); a herringbone sun with a
``[groove]`` table adds ``sun_planet_herringbone.csv`` and the left/right sun-flank load
maps ``sun_planet_herringbone_load_map_{left,right}.png/.vtu`` - then the dynamics
(``modes.csv``, ``mode_shapes.png``, ``time_history.csv/png``, ``dte_spectrum.csv/png``,
``sweep.csv/png``), the load distribution report of every mesh (``report.html``,
``report.json``, ``report.csv``; :mod:`pipeline.report`), one ``summary.json`` and
``run.json``. The figures of the reports are drawn with the others, side by side
(:mod:`pipeline.viz.figure_queue`), and the reports written once they are. Each step
prints a line with its time on stderr; FE tables and contact cycles come from the cache
when their inputs are unchanged (``--no-cache`` recomputes them, ``--cache-dir`` moves the
cache).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from pipeline.cli.common import (
    add_cache_arguments,
    add_common_arguments,
    command_cache,
    emit,
    load,
    output_dir,
    record,
)
from pipeline.io import write_json
from pipeline.output_folder import mesh_label, mesh_prefix, staged_output
from pipeline.run.chain import MeshStages, RunOptions
from pipeline.run.runner import RunResult, run_pipeline
from pipeline.viz.figure_cache import NO_CACHE, FigureCache
from pipeline.viz.figure_queue import parallel_figures


def figure_cache(options: RunOptions) -> FigureCache:
    """Figures cached beside the FE tables and contact cycles (none with ``--no-cache``)."""
    return FigureCache.within(options.cache)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    parser.add_argument("--full", action="store_true",
                        help="fine dynamics settings (more harmonics, all sweep points)")
    add_cache_arguments(parser)


def _write_mesh(name: str, st: MeshStages, box, out: Path, prefix: str,
                figures: FigureCache) -> list[Path]:
    from pipeline.cli.contact import contact_title, write_contact
    from pipeline.cli.geometry import write_geometry
    from pipeline.cli.stiffness import write_stiffness
    from pipeline.stiffness.mesh import stiffness_at

    pair = st.stiffness.actual
    title = (f"{name}: z {pair.pinion.teeth}/{pair.gear.teeth}"
             f"{' internal' if pair.gear.internal else ''}, m_n {pair.pinion.module * 1e3:g} mm, "
             f"beta {math.degrees(pair.pinion.helix_angle):g} deg")
    files = write_geometry(st.geometry, out, prefix, figures, name)
    files += write_stiffness(st.stiffness, out, title, prefix, figures)
    model, opts = st.stiffness.model, box.mesh_contact(st.case.name)
    ref = stiffness_at(model, st.contact.s0, opts.slices, box.stiffness.friction_model,
                       st.case.operation, box.stiffness.foundation_correction)
    files += write_contact(st.contact, pair, opts, ref.total,
                           contact_title(name, st.contact, pair, opts), out, prefix, figures,
                           box.mesh_gears(st.case.name))
    if st.shafts is not None:
        from pipeline.io import write_csv

        files += [write_csv(out / f"{prefix}shaft_deflection.csv",
                            st.shafts.deflection_columns()),
                  write_csv(out / f"{prefix}shaft_face.csv", st.shafts.face_columns())]
    if st.revolution is not None:
        from pipeline.cli.revolution_files import write_revolution

        files += write_revolution(st.revolution, st.contact, pair, opts, title, out, prefix,
                                  figures)
    if st.herringbone is not None:
        from pipeline.cli.herringbone_files import write_herringbone

        files += write_herringbone(st.herringbone, out, prefix, figures,
                                   opts.load_map_profile_points, opts.render)
    return files


def write_run(result: RunResult, out: Path, full: bool = False,
              figures: FigureCache = NO_CACHE) -> list[Path]:
    """All files of a run (module docstring); returns them."""
    from pipeline.cli.dynamics_files import write_modes, write_response, write_sweep
    from pipeline.dynamics.layout import model_layout

    box = result.gearbox
    files: list[Path] = []
    for name, st in result.meshes.items():
        files += _write_mesh(mesh_label(box.name, name), st, box, out, mesh_prefix(name),
                             figures)
    dyn = result.dynamics
    if dyn is not None:
        files += write_modes(dyn.modes, out, model_layout(dyn.model), figures, box.name)
        files += write_response(dyn.response, out, box.name, figures, dyn.operating)
        files += write_sweep(dyn.sweep, out, box.name, figures,
                             natural_frequencies=dyn.modes.frequencies,
                             operating=dyn.operating)
    return files


def run(args: argparse.Namespace, command: str = "run") -> int:
    """``gearpipe run`` (and ``gearpipe report``, the same files in ``results/<stem>/report``)."""
    box = load(args)
    target = output_dir(args, command)
    options = RunOptions(full=args.full, cache=command_cache(args),
                         show_progress=not args.json, label=f"gearpipe {command}")
    # the drawer imports matplotlib while the stages compute (pipeline.viz.figure_queue)
    with parallel_figures(figure_cache(options), prestart=True) as figures:
        result = run_pipeline(box, options)
        with staged_output(target) as out:
            with result.log.step("writing tables and figures", announce=True):
                files = write_run(result, out, args.full, figures)
                reports = []
                if result.meshes:  # the report figures are drawn with the others
                    from pipeline.report.writer import prepare_reports

                    reports = prepare_reports(result, out, figures,
                                              command=f"gearpipe {command} {args.config}",
                                              written=files)
                figures.queue.draw_all(show_progress=options.show_progress)
            if reports:  # the reports embed the figures drawn above: after them
                with result.log.step("load distribution reports", announce=True):
                    for report in reports:
                        files += report.write(out)
            summary = result.summary()
            files.append(write_json(out / "summary.json", summary))
            record(out, args, box, files)
    emit(args, summary, target)
    return 0
