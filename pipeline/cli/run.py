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
``run.json``. The mesh files are written as soon as their stages are computed (geometry and
stiffness before the contact is solved, contact and load maps before the load
distribution and the dynamics) and, when the FE solver keeps to one thread
(:func:`solver_on_one_core`), their figures drawn by the early-started drawer while the
rest computes; the report figures are drawn with the dynamics figures, side by side,
and the reports written once they are (:mod:`pipeline.viz.figure_queue`). Each step prints
a line with
its time on stderr; FE tables and contact cycles come from the cache when their inputs
are unchanged (``--no-cache`` recomputes them, ``--cache-dir`` moves the cache).
"""

from __future__ import annotations

import argparse
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
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
from pipeline.run.chain import WRITING_STEP, MeshStages, RunOptions
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


def _mesh_title(name: str, pair) -> str:
    return (f"{name}: z {pair.pinion.teeth}/{pair.gear.teeth}"
            f"{' internal' if pair.gear.internal else ''}, m_n {pair.pinion.module * 1e3:g} mm, "
            f"beta {math.degrees(pair.pinion.helix_angle):g} deg")


def _write_static(name: str, geometry, stiffness, out: Path, prefix: str,
                  figures: FigureCache) -> list[Path]:
    """The geometry and analytical stiffness files of one mesh."""
    from pipeline.cli.geometry import write_geometry
    from pipeline.cli.stiffness import write_stiffness

    files = write_geometry(geometry, out, prefix, figures, name)
    return files + write_stiffness(stiffness, out, _mesh_title(name, stiffness.actual), prefix,
                                   figures)


def _write_contact(name: str, st: MeshStages, box, out: Path, prefix: str,
                   figures: FigureCache) -> list[Path]:
    """The loaded contact files of one mesh (with its shafts, revolution, herringbone)."""
    from pipeline.cli.contact import contact_title, write_contact
    from pipeline.stiffness.mesh import stiffness_at

    pair = st.stiffness.actual
    title = _mesh_title(name, pair)
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


def write_run(result: RunResult, out: Path, full: bool = False,
              figures: FigureCache = NO_CACHE) -> list[Path]:
    """All files of a run (module docstring) but the reports; returns them."""
    box = result.gearbox
    files: list[Path] = []
    for name, st in result.meshes.items():
        label, prefix = mesh_label(box.name, name), mesh_prefix(name)
        files += _write_static(label, st.geometry, st.stiffness, out, prefix, figures)
        files += _write_contact(label, st, box, out, prefix, figures)
    return files + _write_dynamics(result, out, figures)


def solver_on_one_core(env: Mapping[str, str]) -> bool:
    """Whether the FE steps' sparse solver (MKL PARDISO) runs on one thread: its thread
    count ``MKL_NUM_THREADS``, else ``OMP_NUM_THREADS``, is 1 (unset: one thread per
    core), or the machine has one core."""
    threads = env.get("MKL_NUM_THREADS") or env.get("OMP_NUM_THREADS") or ""
    return threads.strip() == "1" or (os.cpu_count() or 1) == 1


@dataclass
class _EarlyWriter:
    """Writes a run's mesh files as the stages hand them over
    (:func:`pipeline.run.runner.run_pipeline`' ``on_static`` and ``on_meshes``); with
    ``flush`` it hands their figures to the drawer at once, so that they are drawn while
    the next stages compute (:meth:`pipeline.viz.figure_queue.FigureQueue.flush`).

    Only when the solver keeps to one core (:func:`solver_on_one_core`): a multi-threaded
    solver's threads and the drawer would share the cores, and the FE steps, which wait
    for their slowest thread, took up to twice as long (demo pair, 2 cores,
    ``OMP_NUM_THREADS=2``: loaded contact 4.3 s against 2.5 s, root stress 4.7 s against
    1.9 s, medians of four cold runs); the figures then wait for the end, as the report's.
    """

    box: object
    out: Path
    figures: FigureCache
    flush: bool
    files: list[Path] = field(default_factory=list)

    def static(self, case, geometry, stiffness) -> None:
        self.files += _write_static(mesh_label(self.box.name, case.name), geometry, stiffness,
                                    self.out, mesh_prefix(case.name), self.figures)
        if self.flush:
            self.figures.queue.flush()

    def meshes(self, meshes: Mapping[str, MeshStages]) -> None:
        for name, st in meshes.items():
            self.files += _write_contact(mesh_label(self.box.name, name), st, self.box,
                                         self.out, mesh_prefix(name), self.figures)
        if self.flush:
            self.figures.queue.flush()


def run(args: argparse.Namespace, command: str = "run") -> int:
    """``gearpipe run`` (and ``gearpipe report``, the same files in ``results/<stem>/report``)."""
    box = load(args)
    target = output_dir(args, command)
    options = RunOptions(full=args.full, cache=command_cache(args),
                         show_progress=not args.json, label=f"gearpipe {command}")
    # the drawer imports matplotlib while the stages compute (pipeline.viz.figure_queue)
    # and draws each stage's figures while the next stages compute
    with parallel_figures(figure_cache(options), prestart=True) as figures, \
            staged_output(target) as out:
        early = _EarlyWriter(box, out, figures, solver_on_one_core(os.environ))
        result = run_pipeline(box, options, on_static=early.static, on_meshes=early.meshes)
        with result.log.step(WRITING_STEP, announce=True):
            files = early.files + _write_dynamics(result, out, figures)
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
