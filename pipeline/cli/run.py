"""``gearpipe run CONFIG``: every stage the gearbox file asks for, into one results folder.

Runs :func:`pipeline.run.runner.run_pipeline` (stage by stage) and writes, to
``results/<file stem>/run/`` (or ``--out``): per mesh the geometry (``line_of_action.png``,
``tooth_profiles.png``), the analytical stiffness (``mesh_stiffness.csv/png``), the loaded
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
``run.json``. The files of each stage are written as soon as it is done
(:func:`pipeline.run.runner.run_stages`: geometry and analytical stiffness, contact, dynamics)
and its figures handed to the drawer, which draws them while the next stages compute; the
figures of the reports are drawn with those left at the end, side by side
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
from pipeline.run.runner import RunResult, run_stages
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


def _mesh_title(name: str, st: MeshStages) -> str:
    pair = st.stiffness.actual
    return (f"{name}: z {pair.pinion.teeth}/{pair.gear.teeth}"
            f"{' internal' if pair.gear.internal else ''}, m_n {pair.pinion.module * 1e3:g} mm, "
            f"beta {math.degrees(pair.pinion.helix_angle):g} deg")


def _write_analytical(name: str, st: MeshStages, out: Path, prefix: str,
                      figures: FigureCache) -> list[Path]:
    """The geometry and analytical stiffness files of one mesh."""
    from pipeline.cli.geometry import write_geometry
    from pipeline.cli.stiffness import write_stiffness

    files = write_geometry(st.geometry, out, prefix, figures, name)
    return files + write_stiffness(st.stiffness, out, _mesh_title(name, st), prefix, figures)


def _write_contact(name: str, st: MeshStages, box, out: Path, prefix: str,
                   figures: FigureCache) -> list[Path]:
    """The loaded contact files of one mesh and those of the stages built on it (shafts,
    revolution, herringbone halves)."""
    from pipeline.cli.contact import contact_title, write_contact
    from pipeline.stiffness.mesh import stiffness_at

    pair, title = st.stiffness.actual, _mesh_title(name, st)
    model, opts = st.stiffness.model, box.mesh_contact(st.case.name)
    ref = stiffness_at(model, st.contact.s0, opts.slices, box.stiffness.friction_model,
                       st.case.operation, box.stiffness.foundation_correction)
    files = write_contact(st.contact, pair, opts, ref.total,
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


def _write_dynamics(result: RunResult, out: Path, figures: FigureCache) -> list[Path]:
    """The dynamics files of a run (none without dynamics)."""
    from pipeline.cli.dynamics_files import write_modes, write_response, write_sweep
    from pipeline.dynamics.layout import model_layout

    dyn, name = result.dynamics, result.gearbox.name
    if dyn is None:
        return []
    return [*write_modes(dyn.modes, out, model_layout(dyn.model), figures, name),
            *write_response(dyn.response, out, name, figures, dyn.operating),
            *write_sweep(dyn.sweep, out, name, figures,
                         natural_frequencies=dyn.modes.frequencies, operating=dyn.operating)]


def write_stage(stage: str, result: RunResult, out: Path, figures: FigureCache = NO_CACHE
                ) -> dict[str, list[Path]]:
    """The files of one stage of :func:`pipeline.run.runner.run_stages` (``"analytical"``,
    ``"contact"``, ``"dynamics"``; the other stages write none here): by mesh name, the
    dynamics' under ``""``."""
    box = result.gearbox
    if stage == "dynamics":
        return {"": _write_dynamics(result, out, figures)}
    write = {"analytical": lambda label, st, prefix: _write_analytical(label, st, out, prefix,
                                                                       figures),
             "contact": lambda label, st, prefix: _write_contact(label, st, box, out, prefix,
                                                                 figures)}.get(stage)
    if write is None:
        return {}
    return {name: write(mesh_label(box.name, name), st, mesh_prefix(name))
            for name, st in result.meshes.items()}


def _in_order(written: dict[str, dict[str, list[Path]]]) -> list[Path]:
    """The files of :func:`write_stage` by stage, in the order of :func:`write_run`: each
    mesh's (its stages in turn), then the dynamics'."""
    meshes = [name for part in written.values() for name in part if name]
    return [p for name in dict.fromkeys([*meshes, ""]) for part in written.values()
            for p in part.get(name, [])]


def write_run(result: RunResult, out: Path, full: bool = False,
              figures: FigureCache = NO_CACHE) -> list[Path]:
    """All files of a run (module docstring); returns them."""
    return _in_order({stage: write_stage(stage, result, out, figures)
                      for stage in ("analytical", "contact", "dynamics")})


def run(args: argparse.Namespace, command: str = "run") -> int:
    """``gearpipe run`` (and ``gearpipe report``, the same files in ``results/<stem>/report``)."""
    box = load(args)
    target = output_dir(args, command)
    options = RunOptions(full=args.full, cache=command_cache(args),
                         show_progress=not args.json, label=f"gearpipe {command}")
    # the drawer imports matplotlib while the stages compute, then draws the figures of
    # each stage while the next computes (pipeline.viz.figure_queue); if the run fails,
    # it is ended before the staging folder it draws into is removed
    with staged_output(target) as out, \
            parallel_figures(figure_cache(options), prestart=True) as figures:
        written: dict[str, dict[str, list[Path]]] = {}
        for stage, result in run_stages(box, options):
            if stage == "complete":
                break
            with result.log.step(f"writing the {stage} files"):
                written[stage] = write_stage(stage, result, out, figures)
                drawing = bool(figures.queue.jobs)
                figures.queue.send()
            if stage == "analytical" and drawing and any(
                    box.mesh_contact(name).render for name in result.meshes):
                # figures not in the cache: the load maps will likely be drawn as well;
                # the drawer imports their renderer while the FE contact computes
                from pipeline.viz.loadmap import prepare_rendering

                figures.queue.prepare(prepare_rendering)
        files = _in_order(written)
        with result.log.step("writing tables and figures", announce=True):
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
