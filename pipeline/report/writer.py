"""Writing the reports of a run: per gear mesh one HTML file, its JSON and its CSV.

:func:`write_reports` takes a :class:`~pipeline.run.runner.RunResult` and the folder the
run's stage outputs were written to (:func:`pipeline.cli.run.write_run`): it renders the
load distribution and tooth root stress the run computed for every mesh
(:mod:`pipeline.run.distribution`; it computes nothing itself), draws the report's own
figures (:mod:`pipeline.viz.distribution`), embeds them and the
stage figures it finds in the folder, and writes, per mesh (prefix ``<mesh>_`` for a
planetary set) the files below. :func:`prepare_reports` does it in two steps for a run
that queues its figures (``gearpipe run``): the reports assembled and their figures queued
beside the stage figures, then :meth:`PendingReport.write` once they are all drawn.

* ``report.html`` - the self-contained report (:mod:`pipeline.report.html`); the
  sun-planet mesh of a herringbone set solved through its groove gets a section with both
  halves (:mod:`pipeline.report.herringbone_section`), a pair with ``[contact.errors]`` one
  on the contact through the revolution (:mod:`pipeline.report.revolution_section`);
* ``report.json`` - every number of it, by section and key, with labels and units;
* ``report.csv`` - the same numbers as rows ``section,key,column,quantity,value,unit``;
* ``report_cycle.csv`` - per mesh position: TE, mesh stiffness, load factors, load
  shares, root stress maxima; ``report_face.csv`` - line load over the face;
* ``rating_local.csv`` - with a rating: the local pitting safety of both flanks on the
  (roll coordinate, face position) grid, and the FE root stress along the face with the
  local bending safety (:meth:`pipeline.rating.local_safety.LocalSafety.columns`).
"""

from __future__ import annotations

import csv
import dataclasses
import fnmatch
import io
import math
import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.contact.distribution import LoadDistribution
from pipeline.io import atomic_write_text, write_csv, write_json
from pipeline.output_folder import mesh_label, mesh_prefix
from pipeline.report import content
from pipeline.report.dynamics_section import dynamics_meshes_section, dynamics_section
from pipeline.report.html import render_html
from pipeline.report.model import Figure, MeshReport
from pipeline.report.provenance import provenance
from pipeline.viz.figure_cache import NO_CACHE, FigureCache

# stage figures embedded when the run wrote them: (file, caption, section); every other
# ``load_map*.png`` of the mesh is embedded too, under its file name
STAGE_FIGURES = (
    ("tooth_profiles.png", "Tooth profiles (involute and trochoidal fillet)", "geometry"),
    ("load_map.png", "Tooth-surface load map", "load_maps"),
    ("load_map_2d.png", "Unit load p [N/mm] over face position b_z and pinion contact "
     "radius (envelope over the mesh cycle)", "load_maps"),
    ("sweep.png", "RMS dynamic mesh force over mesh frequency (the first planet's sun "
     "meshes of a planetary set), with the operating mesh frequency, its harmonics and the "
     "natural frequencies marked", "dynamics"),
    ("dte_spectrum.png", "Dynamic transmission error spectrum", "dynamics"),
    ("harmonics.png", "Harmonic contributions of the response", "dynamics"),
)


def present_files(out: Path, written: Iterable[str | Path] | None = None) -> set[str]:
    """The names of the files in ``out`` and of ``written`` (files a run wrote or queued for
    drawing there: a figure handed to a drawer is embedded once it is drawn)."""
    return {p.name for p in out.iterdir()} | {Path(p).name for p in written or ()}


def _stage_figures(names: set[str], prefix: str, mesh_level: bool
                   ) -> dict[str, list[Figure]]:
    found: dict[str, list[Figure]] = {}
    for name, caption, section in STAGE_FIGURES:
        file = (prefix if mesh_level and section != "dynamics" else "") + name
        if file in names:
            found.setdefault(section, []).append(Figure(file, caption))
    if mesh_level:
        known = {f.file for f in found.get("load_maps", [])}
        for file in sorted(fnmatch.filter(names, f"{prefix}load_map*.png")):
            if file not in known:
                found.setdefault("load_maps", []).append(Figure(
                    file, "Load map: " + file[len(prefix):-len(".png")].replace("_", " ")))
    return found


def _planetary_mesh(box: Any, name: str, st: Any) -> content.PlanetaryMesh | None:
    """How a planetary set's mesh ``name`` is loaded and turns (None for a pair)."""
    if box.kind != "planetary":
        return None
    from pipeline.geometry.planetary_speeds import planetary_speeds

    ps = box.planetary
    return content.PlanetaryMesh(name, box.operation.torque, ps.n_planets,
                                 ps.sun.herringbone,
                                 st.herringbone is not None,
                                 planetary_speeds(ps, box.operation.speed))


def _herringbone_section(st: Any, planetary: content.PlanetaryMesh, halves: Any,
                         half_roots: dict[str, Any], names: set[str], prefix: str, fig
                         ) -> Any:
    """The herringbone section with its figures: the halves' line loads and the existing
    load maps of both helical halves."""
    from pipeline.report.herringbone_section import herringbone_section
    from pipeline.viz.herringbone import plot_half_line_loads

    stage = st.herringbone
    shares = " / ".join(f"{100 * halves.half(s).share.mean():.1f} %" for s in ("left", "right"))
    figs = [fig("report_herringbone_line_load.png",
                "Line load over the face of each helical half (left / right, from the contact "
                "through the groove) and of one half at an equal split",
                plot_half_line_loads, halves,
                f"herringbone sun-planet: load left / right {shares}; sun "
                f"{planetary.sun_torque:.6g} N m at {planetary.speeds.sun * content.RPM:.4g} "
                "rpm")]
    for side in ("left", "right"):
        file = f"{prefix}herringbone_load_map_{side}.png"
        if file in names:
            figs.append(Figure(file, f"Unit load over the sun and planet flanks of the {side} "
                                     "helical half (contact through the groove)"))
    return herringbone_section(halves, half_roots, planetary.speeds, stage.cycle,
                               stage.groove.equivalent_Kj, sun_torque=planetary.sun_torque,
                               figures=figs)


def _modification_figures(contact: Any, pair: Any, gears: tuple[str, str], fig,
                          title: str) -> list[Figure]:
    """The flanks' modification maps of a mesh whose gears are modified (none otherwise),
    each named by its gear table ``gears`` (pinion, gear of the mesh)."""
    from pipeline.contact.modifications import modification_maps
    from pipeline.viz.modifications import plot_modification_maps

    flanks = contact.modifications.flanks
    if all(m.is_zero for m in flanks):
        return []
    drawn = [(dataclasses.replace(m, role=role), internal) for m, mod, role, internal in zip(
        modification_maps(pair, flanks), flanks, gears, (False, pair.gear.internal),
        strict=True) if not mod.is_zero]  # an unmodified flank has no map to show
    return [fig("report_modifications.png", "Modification map of each modified flank: "
                "material removed [um] over face position and roll length",
                plot_modification_maps, [m for m, _ in drawn], f"{title}: flank modifications",
                [i for _, i in drawn])]


def mesh_report(result: Any, name: str, out: Path, figures: FigureCache, *, title: str,
                command: str, dist: LoadDistribution, root_stress: Any = None,
                halves: Any = None, half_roots: Mapping[str, Any] | None = None,
                names: set[str] | None = None) -> MeshReport:
    """Draw (or queue, :class:`~pipeline.viz.figure_cache.FigureCache`) the report figures
    of mesh ``name`` into ``out`` and assemble its report from its load distribution
    ``dist``; ``halves``
    (:class:`~pipeline.contact.herringbone_distribution.HerringboneDistribution`) and
    ``half_roots`` (root stress by column) add the herringbone section; ``names``: the
    stage figures there are to embed (:func:`present_files`; default: the files in
    ``out``)."""
    from pipeline.viz import distribution as viz

    st = result.meshes[name]
    box = result.gearbox
    prefix = mesh_prefix(name)
    actual, op = st.stiffness.actual, st.case.operation
    names = present_files(out) if names is None else names
    stage = _stage_figures(names, prefix, True)

    def fig(file: str, caption: str, fn, *args) -> Figure:
        figures.save(out / f"{prefix}{file}", fn, *args)
        return Figure(f"{prefix}{file}", caption)

    k_fig = fig("report_stiffness.png", "Mesh stiffness over one mesh cycle",
                viz.plot_stiffness_comparison, actual, st.stiffness.mesh.s0,
                st.stiffness.mesh.total, st.contact, st.stiffness.iso.mesh_stiffness,
                st.compliance, title)
    te_fig = fig("report_transmission_error.png", "Loaded static transmission error, its mesh "
                 "orders and the load sharing", viz.plot_transmission_error, actual, dist,
                 st.contact.s0, title)
    w_fig = fig("report_line_load.png", "Line load over the face width",
                viz.plot_line_load, dist, title)
    p_fig = fig("report_contact_pressure.png", "Hertz contact pressure over both flanks",
                viz.plot_contact_pressure, st.contact, dist, actual, title)
    planetary = _planetary_mesh(box, name, st)
    contact, gears = box.mesh_contact(name), box.mesh_gears(name)
    sections = [
        content.operation_section(actual, op, contact, st.compliance, dist, planetary),
        content.geometry_section(st.geometry, actual, stage.get("geometry", [])),
        content.pair_section(actual, st.stiffness.nominal),
        content.modifications_section(contact, st.case.assembly_errors,
                                      st.stiffness.assembled,
                                      _modification_figures(contact, actual, gears, fig, title),
                                      gears),
        content.stiffness_section(st.stiffness, dist, st.compliance, [k_fig]),
        content.transmission_error_section(dist, [te_fig]),
        content.load_distribution_section(dist, actual, [w_fig], contact.modifications),
        content.contact_pressure_section(dist, [p_fig]),
    ]
    if root_stress is not None:
        from pipeline.report.root_section import root_stress_section

        r_fig = fig("report_root_stress.png", "Largest principal stress along the fillets",
                    viz.plot_root_stress, root_stress.curves(), title)
        peak = st.contact.tip_contact_peak()
        sections.append(root_stress_section(root_stress, [r_fig],
                                            0.0 if peak is None else peak["share"]))
    if st.shafts is not None:
        sections.append(_shaft_section(box, st, dist, actual, op, fig, title))
    if st.revolution is not None:
        from pipeline.report.revolution_section import revolution_figures, revolution_section

        sections.append(revolution_section(st.revolution, revolution_figures(names, prefix)))
    if halves is not None:
        sections.append(_herringbone_section(st, planetary, halves, half_roots or {}, names,
                                             prefix, fig))
    if stage.get("load_maps"):
        sections.append(content.figures_section("load_maps", "Tooth-surface load maps",
                                                stage["load_maps"]))
    if result.dynamics is not None:
        dyn = _stage_figures(names, prefix, False).get("dynamics", [])
        summary = result.dynamics.summary()
        sections.append(dynamics_section(summary))
        sections.append(dynamics_meshes_section(summary, name, dyn))
        if result.dynamics.without_shafts is not None:
            sections.append(_shaft_dynamics_section(result.dynamics, summary, name, fig,
                                                    title))
    if result.rating is not None:
        sections += _rating_sections(result.rating, name, fig, title, actual.gear.internal)
    run_s = result.log.summary()["total_s"]
    src = box.source
    record = provenance(box.to_dict(), file_sha256=src.sha256 if src else None,
                        command=command, run_seconds=run_s)
    sections.append(content.provenance_section(record))
    return MeshReport(title, name, tuple(sections))


def _shaft_section(box: Any, st: Any, dist: LoadDistribution, pair: Any, op: Any, fig,
                   title: str):
    """The shafts section of a pair on shafts with its figure."""
    from pipeline.contact.distribution import load_distribution
    from pipeline.report.shaft_section import shaft_section
    from pipeline.viz.shafts import plot_shaft_deflection

    stage = st.shafts
    rigid = load_distribution(stage.rigid, pair, op)
    if box.kind == "planetary":
        return _planetary_shaft_section(box, st, rigid, dist, fig, title)
    shafts = []
    for role, r in zip(("pinion", "gear"), stage.retreats, strict=True):
        if r is None or r.solution is None:
            continue
        lay = box.shafts[role][1]
        shafts.append((role, r.solution.z, r.solution.displacement[:, 1], lay.seat,
                       np.array([b.position for b in lay.bearings])))
    rigid_w = np.interp(stage.z, rigid.z, rigid.cycle_mean) if rigid.z.size > 1 \
        else np.full(stage.z.size, float(rigid.cycle_mean.mean()))
    f = fig("report_shafts.png", "The shafts' deflection along the line of action and the line "
            "load across the face with and without it", plot_shaft_deflection, shafts,
            stage.z, rigid_w, np.interp(stage.z, dist.z, dist.cycle_mean), stage.gap, title,
            stage.mesh is not None and stage.mesh.reversed)
    return shaft_section(stage, rigid.k_hbeta, dist.k_hbeta, [f],
                         {role: spec[0] for role, spec in box.shafts.items()})


def _shaft_dynamics_section(dynamics: Any, summary: Mapping[str, Any], name: str, fig,
                            title: str):
    """The dynamics with and without the shafts, with the figure of both sweeps for this
    report's mesh (a planetary set's: its first planet's)."""
    from pipeline.dynamics.mesh_names import planet_meshes
    from pipeline.report.shaft_section import shaft_dynamics_section
    from pipeline.viz.shafts import plot_shaft_dynamics

    sweep, rigid = dynamics.sweep, dynamics.without_shafts
    meshes = planet_meshes(sweep.mesh_names, name).get("", {})
    shown = meshes[min(meshes)] if meshes else sweep.mesh_names[0]
    i = sweep.mesh_names.index(shown)
    tag = "" if shown == "mesh" else f" (mesh {shown})"
    f = fig("report_shaft_dynamics.png", f"Dynamic factor over mesh frequency{tag} with and "
            "without the shafts, with the natural frequencies of each",
            plot_shaft_dynamics, sweep.frequencies, sweep.dynamic_factor[i],
            rigid.sweep.dynamic_factor[i], summary["natural_frequencies_Hz"],
            summary["without_shafts"]["natural_frequencies_Hz"],
            dynamics.operating.mesh_frequency, title + tag)
    return shaft_dynamics_section(summary, [f])


def _planetary_shaft_section(box: Any, st: Any, rigid: LoadDistribution,
                             dist: LoadDistribution, fig, title: str):
    """The shafts section of one mesh of a planetary set with its figure."""
    from pipeline.report.shaft_section import planetary_shaft_section
    from pipeline.viz.shafts import plot_planetary_shaft_deflection

    stage = st.shafts
    role = {"sun": ("sun", "bearings"), "planet pin": ("planet", "supports in the carrier")}
    shafts = []
    for name, z, line in stage.deflection_lines():
        lay = box.shafts[role[name][0]][1]
        shafts.append((name, z, line, lay.seat, np.array([b.position for b in lay.bearings]),
                       role[name][1]))
    f = fig("report_shafts.png", "The sun's and the planet pin's retreat along this mesh's "
            "line of action and the line load across the face with and without it",
            plot_planetary_shaft_deflection, shafts, stage.z,
            np.interp(stage.z, rigid.z, rigid.cycle_mean),
            np.interp(stage.z, dist.z, dist.cycle_mean), stage.gap, title)
    return planetary_shaft_section(stage, [f])


def _rating_sections(stage: Any, name: str, fig, title: str, internal: bool) -> list:
    """The rating's sections of mesh ``name`` of rating ``stage`` with their figures: the
    load factors, both gears' safety factors and the local safety over the flank;
    ``internal``: the mesh's second gear is a ring."""
    from pipeline.report.rating_section import (
        rating_load_section,
        rating_local_section,
        rating_section,
    )
    from pipeline.viz.rating import (
        plot_local_pitting_safety,
        plot_root_stress_along_face,
        plot_safety_factors,
    )

    m = stage.meshes[name]
    r = m.rating
    s_f = [math.nan if b is None else b.safety for b in r.bending]
    f = fig("report_rating.png", "ISO 6336 safety factors of both gears against the required "
            "minimum", plot_safety_factors, list(m.gears), [p.safety for p in r.pitting], s_f,
            stage.minimum_pitting, stage.minimum_bending, title)
    sections = [rating_load_section(m), rating_section(m, [f])]
    if m.local is None:
        return sections
    local = [fig("report_rating_local_pitting.png", "Local pitting safety S_H,loc over both "
                 "flanks (loaded contact), the required S_Hmin as a contour line",
                 plot_local_pitting_safety, m.local, m.minimum_pitting, internal, title)]
    if m.local.bending is not None:
        local.append(fig("report_rating_root_face.png", "FE root stress along the face and "
                         "the local bending safety S_F,loc", plot_root_stress_along_face,
                         m.local, m.minimum_bending, title))
    return [*sections, rating_local_section(m, local)]


def _csv_text(report: MeshReport) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["section", "key", "column", "quantity", "value", "unit"])
    for section, key, column, label, unit, value in report.rows():
        w.writerow([section, key, column, label, "" if value is None else value, unit])
    return buf.getvalue()


def write_mesh_report(report: MeshReport, dist: LoadDistribution, out: Path, prefix: str,
                      subtitle: str, root_stress: Any = None, local: Any = None) -> list[Path]:
    """The HTML, JSON and CSV files of one mesh report (module docstring); ``local``: the
    rating's :class:`~pipeline.rating.local_safety.LocalSafety`, or None."""
    cycle_cols = dist.columns()
    if root_stress is not None:
        cycle_cols.update(root_stress.cycle_columns())
    extra = [] if local is None else [write_csv(out / f"{prefix}rating_local.csv",
                                                local.columns())]
    return [
        atomic_write_text(out / f"{prefix}report.html", render_html(report, out, subtitle)),
        write_json(out / f"{prefix}report.json", report.to_json()),
        atomic_write_text(out / f"{prefix}report.csv", _csv_text(report)),
        write_csv(out / f"{prefix}report_cycle.csv", cycle_cols),
        write_csv(out / f"{prefix}report_face.csv", dist.face_columns()),
        *extra,
    ]


@dataclasses.dataclass(frozen=True)
class PendingReport:
    """A mesh report assembled with its figures drawn or queued; :meth:`write` writes its
    files (module docstring) once the figures are drawn (the HTML embeds them).

    Attributes
    ----------
    report : the report.
    distribution : its load distribution.
    prefix : its files' prefix (``<mesh>_`` for a planetary set).
    subtitle : the HTML's subtitle up to the time it took.
    root_stress : its root stress, or None.
    local : the rating's local safety, or None.
    started : ``time.perf_counter()`` when its assembly began.
    """

    report: MeshReport
    distribution: LoadDistribution
    prefix: str
    subtitle: str
    root_stress: Any
    local: Any
    started: float

    def write(self, out: Path) -> list[Path]:
        """The report's files in ``out`` (its figures must be there)."""
        subtitle = f"{self.subtitle}; written in {time.perf_counter() - self.started:.1f} s"
        return write_mesh_report(self.report, self.distribution, out, self.prefix, subtitle,
                                 self.root_stress, self.local)


def write_reports(result: Any, out: Path, figures: FigureCache = NO_CACHE, *,
                  command: str = "gearpipe run", show_progress: bool = False) -> list[Path]:
    """Reports of every gear mesh of ``result`` with a load distribution
    (``result.distributions``, :mod:`pipeline.run.distribution`) into ``out`` (module
    docstring); returns the files. A run without gear meshes (a lumped model) has none.
    With ``show_progress`` a mesh whose report takes over a second gets a line on stderr.
    ``figures`` must draw at once (no queue); a run that queues its figures uses
    :func:`prepare_reports`."""
    from pipeline.progress import Steps

    files: list[Path] = []
    steps = Steps(result.log.label, enabled=show_progress)
    for name, stage in result.distributions.items():
        with steps.step(f"report of {name.replace('_', '-')}"):
            files += _prepare_one(result, name, stage, out, figures, command).write(out)
    return files


def prepare_reports(result: Any, out: Path, figures: FigureCache, *, command: str,
                    written: Iterable[str | Path] = ()) -> list[PendingReport]:
    """The reports of :func:`write_reports`, their figures queued on ``figures`` (or drawn)
    beside the stage figures ``written`` (or queued) into ``out``; write each with
    :meth:`PendingReport.write` once the figures are drawn."""
    names = present_files(out, written)
    return [_prepare_one(result, name, stage, out, figures, command, names)
            for name, stage in result.distributions.items()]


def _prepare_one(result: Any, name: str, stage: Any, out: Path, figures: FigureCache,
                 command: str, names: set[str] | None = None) -> PendingReport:
    """The report of one mesh (:func:`write_reports`) from its
    :class:`~pipeline.run.distribution.DistributionStage`."""
    box = result.gearbox
    st = result.meshes[name]
    t0 = time.perf_counter()
    prefix = mesh_prefix(name)
    pair = st.stiffness.actual
    title = (f"{mesh_label(box.name, name)}: z {pair.pinion.teeth}/{pair.gear.teeth}, m_n "
             f"{pair.pinion.module * 1e3:g} mm, beta "
             f"{math.degrees(pair.pinion.helix_angle):g} deg")
    report = mesh_report(result, name, out, figures, title=title, command=command,
                         dist=stage.distribution, root_stress=stage.root_stress,
                         halves=stage.halves, half_roots=stage.half_roots, names=names)
    subtitle = (f"Tooth load distribution report - {st.compliance} compliance, "
                f"{len(st.contact)} mesh positions")
    local = None if result.rating is None else result.rating.meshes[name].local
    return PendingReport(report, stage.distribution, prefix, subtitle, stage.root_stress,
                         local, t0)
