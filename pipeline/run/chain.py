"""The whole pipeline on one gearbox: geometry -> stiffness -> compliance -> contact -> dynamics.

:func:`run_pipeline` composes the stages' entry points for every mesh of a gearbox
(a pair: one mesh; a planetary set: sun-planet and planet-ring) and returns a
:class:`RunResult`; it writes nothing but the cache. The order, and what each step
takes from the one before:

1. geometry (:func:`pipeline.geometry.analysis.analyse_geometry`);
2. analytical stiffness over a mesh cycle (:func:`pipeline.stiffness.analyse_stiffness`);
3. the compliance source ``[contact] compliance`` names, with the ``[fe]`` settings
   (:func:`pipeline.contact.compliance.compliance_source`; FE meshes and tables are
   cached by content hash inside the FE stage);
4. loaded contact over one mesh cycle at the operating torque
   (:func:`pipeline.contact.analyse_contact`), cached by a content hash of everything
   it depends on (:func:`pipeline.contact.cycle_io.cycle_cache_inputs`), so a rerun
   that changes only a dynamics option reads it back instead of building the FE
   source and solving the contact again;
5. with a ``[dynamics]`` table (or a ``[lumped_model]``): the dynamic model
   (:func:`pipeline.run.dynamics.dynamic_model`), its modes, the steady response at
   the operating speed and a speed sweep (dynamic mesh forces, dynamic factor);
6. the load distribution and FE root stress of every mesh
   (:mod:`pipeline.run.distribution`) and, with ``[rating]``, the ISO 6336 rating
   (:mod:`pipeline.run.rating`).

Steps 1-2 of every mesh come before the contact of any (:func:`analytical_stages`, then
:func:`contact_stages` and :func:`coupled_stages`), and the dynamics before the load
distributions, which neither needs: :func:`pipeline.run.runner.run_stages` yields the
result after each of these groups, and ``gearpipe run`` writes each group's files and
hands its figures to the drawer while the next group computes.

For a planetary set the two meshes are one sun-planet and one planet-ring mesh (for a
herringbone set one helical half at half the load), ``[operation]`` giving the sun's torque
and speed with the ring fixed, each with its gears' flank modifications
(:meth:`~pipeline.config.gearbox.Gearbox.mesh_contact`, the contact options of a mesh that
every stage reads); with a sun's shaft or planets' pins both contacts are then
solved again together with their deflection (:mod:`pipeline.run.planetary_shafts`). The
dynamic factor is the largest over the mean mesh force.
``gearpipe modes|response|sweep`` build the dynamic model the same way.

Cached by content hash (``meshes/`` of a checkout; ``--cache-dir`` moves it,
:mod:`pipeline.cache.folder`): FE meshes and tables (gear geometry, FE settings, format),
loaded contact cycles (installed pair, operating point, contact options, friction, FE
settings, formats) and figures (drawing code, every plotted array); a rerun that changes
only a dynamics option reads the contact cycle back and redraws only the dynamics figures.
Figures not in the cache are drawn by a drawer that ``gearpipe run`` starts as it starts,
so matplotlib (0.5 s to import) loads while the stages compute; it draws each group's
figures while the next group computes, and those left at the end side by side in a
process pool forked from it (:mod:`pipeline.viz.figure_queue`); the report figures are
drawn with them
(:func:`pipeline.report.writer.prepare_reports`), and a matplotlib figure is drawn once and
cut to its tight box (:mod:`pipeline.viz.saving`). The run imports matplotlib only to draw,
and reading a gearbox file or cached FE tables imports no scikit-fem.

Measured (``workflows/benchmarks/bench_run.py``: the demo's pair with FE 2D contact and the
load distribution report, separate processes, ``OMP_NUM_THREADS=2`` as ``dev.sh`` sets it,
cold runs alternating with b847466, which drew the report figures in this process after the
others and saved each through ``savefig(bbox_inches="tight")``; 2 cores shared with other
work; every file and every number of ``summary.json`` the same). At load average 1.5-1.8,
three runs each: cold 8.2-8.5 s against 9.7-10.6 s (median ratio 0.83; the writing and
report steps 3.8 s against 5.3 s), CPU with the drawing processes 13.0-13.3 s against
13.2-14.3 s, warm with the damping ratio changed 3.7 s against 4.1 s. At load average
3.5-5.4, three runs each: cold 15.3-28.6 s against 30.9-33.5 s (median ratio 0.74), CPU
13.7-15.6 s against 15.2-16.6 s. At load average 2.6-4.1, five runs each: cold 16.3-29.6 s
against 14.9-29.7 s (median ratios 1.05 and 1.09 in two sessions), CPU 14.4-18.8 s against
12.5-18.8 s. The gain depends on the other work sharing the cores: from 17-26 % to none
within the spread of the runs. Where the CPU time of a cold run goes (one process each, same
machine): the computing process 5-6 s (imports 0.8-1.0 s, loaded contact with both FE tables
1.5 s, shafts 0.6 s, FE root stress 1.4-1.7 s, dynamics 0.45 s), the drawing processes 7-9 s
(matplotlib import 0.35 s, the 21 matplotlib figures 4-5.5 s, the pyvista load map 1.3-1.9 s
of which 0.7-1.2 s imports, each new drawing process 0.5-1.5 s more for its first figures).

Since the files of each stage are written as it ends and its figures drawn by the drawer
while the next stages compute (the report figures and those the drawer has not reached
still after the last), the demo's cold run took 0.79-0.80 of 0a4a91a's wall time with no
other job, 0.85-0.89 beside one at load average 1.3-3.2 and 0.99 at 3.1-3.6
(:mod:`pipeline.viz.figure_queue`; the stages and the drawer share the two cores, so each
stage took longer). The run is then bound by the CPU of both cores, and three cuts of it
followed: the demo's equal gears share one 2D table (:mod:`pipeline.contact.fe2d_table`),
PARDISO runs small systems on one thread (:class:`pipeline.fem.solvers._Pardiso`: the
second thread spun after every call) and the spur load map renders without
multisampling (:func:`pipeline.viz.loadmap.render_load_map`): cold 9.5 s against 20.6 s at
b847466 (median of three, ratio 0.46, CPU 16.6 against 27.5 s; b847466 ran 7.75 s the day
it was timed) and 9.9 against 13.3 s at 0a4a91a (0.74), the same files, on a day the
machine ran b847466 2.7 times slower than that.

The computing process (:func:`~pipeline.run.runner.run_pipeline` of the demo's pair, cold,
one process per run, CPU of the process and the children it waited for, one BLAS thread;
2 cores shared with other work at load average 6-9, two runs each): at 9419f53 4.5-4.6 s
(imports 0.77-0.78 s, loaded contact with both compliance tables 1.34-1.35 s, shafts
0.52-0.60 s, load distribution and root stress with its fillet table 1.39-1.46 s, two
sweeps 0.38 s); now 4.1-4.3 s (imports 0.57 s, as scipy's
interpolation and optimisation modules load where used; loaded contact 1.63-1.69 s with
those imports; shafts 0.42-0.47 s, each position's compliance once; root stress 1.08-1.23
s, the fillet table solved for the free DOFs only; sweeps 0.28-0.36 s in this process).
Building the tables side by side in forked processes was tried and left out: 0.1-0.4 s
more CPU, on shared cores slower (wall 1.15 times, load average 4.4-4.8), and MKL
PARDISO with two threads does not round alike in two processes. The run's summary is the
same bit for bit as at 9419f53 (one BLAS thread).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from pipeline.cache.entries import cached_file
from pipeline.cache.folder import Cache
from pipeline.config import Gearbox
from pipeline.contact.analysis import analyse_contact, warn_physics
from pipeline.contact.compliance import compliance_source
from pipeline.contact.cycle_io import (
    CYCLE_CODE,
    cycle_arrays,
    cycle_cache_inputs,
    cycle_from_arrays,
)
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.analysis import GeometryResult, analyse_geometry
from pipeline.geometry.assembly_errors import AssemblyErrors
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.progress import Steps
from pipeline.stiffness.analysis import StiffnessResult, analyse_stiffness
from pipeline.validation import InputError

if TYPE_CHECKING:
    from pipeline.run.herringbone import HerringboneStage
    from pipeline.run.planetary_shafts import PlanetaryMeshShafts
    from pipeline.run.revolution import RevolutionStage
    from pipeline.run.shafts import ShaftStage


@dataclass(frozen=True)
class RunOptions:
    """How to run the pipeline (not what it computes: that is the gearbox file).

    Attributes
    ----------
    full : fine settings of the dynamics (more harmonics, all sweep points).
    cache : the on-disk cache of meshes, FE tables, contact cycles and root-stress tables
        (:class:`~pipeline.cache.folder.Cache`: its folder, or off).
    show_progress : a line per step and progress bars on stderr.
    cache_cycles : keep loaded contact cycles in ``cache``; a design study
        turns it off: one file per design point would fill the cache with cycles that are
        never read again.
    label : the command the step lines name on stderr.
    """

    full: bool = False
    cache: Cache = field(default_factory=Cache)
    show_progress: bool = True
    cache_cycles: bool = True
    label: str = "gearpipe run"

    @property
    def cycle_cache(self) -> Cache:
        """Where contact cycles are kept: ``cache``, or off without ``cache_cycles``."""
        return self.cache if self.cache_cycles else Cache.off()


@dataclass(frozen=True)
class MeshCase:
    """One gear mesh of the gearbox and its load.

    Attributes
    ----------
    name : "mesh" for a pair; "sun_planet" / "planet_ring" for a planetary set.
    pair : the nominal pair (pinion = the driving member of this mesh's pair; one helical
        half of a herringbone set, loaded with half the mesh force).
    assembly_errors : centre displacements, m.
    operation : torque (N m) and speed (rad/s) of this pair's driving gear.
    """

    name: str
    pair: GearPair
    assembly_errors: AssemblyErrors
    operation: OperatingPoint


@dataclass(frozen=True)
class MeshStages:
    """What the static stages give for one mesh.

    Attributes
    ----------
    case : the mesh and its load.
    geometry : contact ratios, profiles, assembly-error geometry.
    stiffness : analytical mesh stiffness (potential energy, ISO 6336, contact lines).
    contact : loaded contact over one mesh cycle on the chosen compliance source, or
        ``None`` when it was not asked for (a dynamics command with analytical excitation).
    compliance : the source's name ("analytical", "fe2d", "fe3d").
    herringbone : the sun-planet mesh of a herringbone sun with a ``[groove]`` table: both
        halves through the groove (:class:`pipeline.run.herringbone.HerringboneStage`), or
        ``None``.
    shafts : a pair on shafts: the contact solved with their deflection
        (:class:`pipeline.run.shafts.ShaftStage`; ``contact`` is then that cycle); a
        planetary set with a sun's shaft or planets' pins: this mesh's view of both meshes
        solved together (:class:`pipeline.run.planetary_shafts.PlanetaryMeshShafts`); or
        None.
    revolution : a pair with ``[contact.errors]``: the contact through the revolution
        (:class:`pipeline.run.revolution.RevolutionStage`), or None.
    """

    case: MeshCase
    geometry: GeometryResult
    stiffness: StiffnessResult
    contact: LoadedMeshCycle | None
    compliance: str
    herringbone: HerringboneStage | None = None
    shafts: ShaftStage | PlanetaryMeshShafts | None = None
    revolution: RevolutionStage | None = None

    def summary(self) -> dict[str, Any]:
        """Contact ratios, stiffness and contact figures of this mesh (SI; keys carry units)."""
        st = self.stiffness.summary()
        out = {
            "compliance": self.compliance,
            "transverse_contact_ratio": st["transverse_contact_ratio"],
            "overlap_ratio": st["overlap_ratio"],
            "mesh_period_s": st["mesh_period_s"],
            "analytical_stiffness": st["potential_energy"],
            "iso6336_mesh_stiffness_N_per_m": st["iso6336"]["mesh_stiffness_N_per_m"],
        }
        if self.contact is not None:
            out["loaded_contact"] = self.contact.summary()
        if self.herringbone is not None:
            out["herringbone_contact"] = self.herringbone.summary()
        if self.shafts is not None:
            out["shafts"] = self.shafts.summary()
        if self.revolution is not None:
            out["revolution"] = self.revolution.summary()
        return out


def step_tag(mesh: str) -> str:
    """What a step line adds for a mesh: nothing for a pair's one mesh, ``" [<mesh>]"`` for
    each mesh of a planetary set."""
    return "" if mesh == "mesh" else f" [{mesh}]"


def mesh_cases(box: Gearbox) -> list[MeshCase]:
    """The meshes of a gearbox with their loads (a pair: one; a planetary set: two)."""
    if box.kind == "pair":
        return [MeshCase("mesh", box.pair, box.assembly_errors, box.operation)]
    if box.kind == "planetary":
        from pipeline.dynamics.models.planetary_gears import helical_half, mesh_operations

        ps = box.planetary
        ops = mesh_operations(ps, box.operation, 2 if ps.sun.herringbone else 1)
        return [MeshCase(name, helical_half(pair), AssemblyErrors(), op) for name, pair, op
                in (("sun_planet", ps.sun_planet, ops[0]), ("planet_ring", ps.planet_ring,
                                                             ops[1]))]
    raise InputError(f"{box.name}: gearpipe run needs gears in mesh (a pair or a planetary "
                     f"set); this file describes a {box.kind.replace('gear', 'single gear')}")


def loaded_contact(box: Gearbox, case: MeshCase, stiffness: StiffnessResult,
                   options: RunOptions, prebuilt: Any = None) -> tuple[LoadedMeshCycle, bool]:
    """The loaded contact cycle of one mesh, from the cache when its inputs are unchanged.

    ``prebuilt`` is an FE source of the same gears and FE settings built earlier (a design
    study builds one per geometry): its tables are used instead of building or reading them.
    Returns (cycle, True if read from the cache).
    """
    actual, contact = stiffness.actual, box.mesh_contact(case.name)
    inputs = cycle_cache_inputs(actual, case.operation, contact, box.stiffness, box.fe_source)

    def build() -> LoadedMeshCycle:
        source = compliance_source(actual, case.operation, contact, box.stiffness,
                                   box.fe_source, cache=options.cache, model=stiffness.model,
                                   show_progress=options.show_progress, prebuilt=prebuilt)
        return analyse_contact(source, case.operation, contact,
                               show_progress=options.show_progress)

    cycle, _, hit = cached_file("contactcycle", inputs, build, cycle_arrays, cycle_from_arrays,
                                code=CYCLE_CODE, cache=options.cycle_cache)
    if hit:
        warn_physics(cycle)  # a cycle solved now has warned already
    return cycle, hit


def analytical_stages(box: Gearbox, case: MeshCase, log: Steps) -> MeshStages:
    """Geometry and analytical stiffness of one mesh: its stages without the contact
    (``contact`` None; :func:`contact_stages` adds it)."""
    tag = step_tag(case.name)
    with log.step(f"geometry{tag}"):
        geometry = analyse_geometry(case.pair, case.assembly_errors)
    with log.step(f"analytical stiffness{tag}") as note:
        stiffness = analyse_stiffness(case.pair, case.operation, box.stiffness,
                                      assembly_errors=case.assembly_errors)
        note["text"] = f"mean {stiffness.mesh.mean:.4g} N/m"
    return MeshStages(case, geometry, stiffness, None, box.contact.compliance)


def contact_stages(box: Gearbox, stages: MeshStages, options: RunOptions, log: Steps,
                   prebuilt: Any = None) -> MeshStages:
    """``stages`` of :func:`analytical_stages` with the loaded contact of the mesh and what
    builds on it: the shafts' deflection, the contact through the revolution, a herringbone
    sun-planet mesh through its groove (``prebuilt``: :func:`loaded_contact`)."""
    case = stages.case
    with log.step(f"loaded contact ({box.contact.compliance}){step_tag(case.name)}",
                  announce=True) as note:
        cycle, hit = loaded_contact(box, case, stages.stiffness, options, prebuilt)
        note["cached"] = hit
        note["text"] = (f"{len(cycle)} positions, mean mesh stiffness "
                        f"{cycle.mesh_stiffness.mean():.4g} N/m")
    stages = dataclasses.replace(stages, contact=cycle)
    if box.shafts:
        from pipeline.run.shafts import shaft_stage

        sh = shaft_stage(box, stages, options, log)
        if sh is not None:  # the contact downstream is the one with the shafts' deflection
            stages = dataclasses.replace(stages, contact=sh.cycle, shafts=sh)
    if box.errors is not None:
        from pipeline.run.revolution import revolution_stage

        stages = dataclasses.replace(stages, revolution=revolution_stage(box, stages, options,
                                                                         log))
    if case.name == "sun_planet":
        from pipeline.run.herringbone import herringbone_stage

        hb = herringbone_stage(box, stages, options, log)
        if hb is not None:
            stages = dataclasses.replace(stages, herringbone=hb)
    return stages


def static_stages(box: Gearbox, case: MeshCase, options: RunOptions, log: Steps,
                  contact: bool = True, prebuilt: Any = None) -> MeshStages:
    """Geometry, analytical stiffness and (with ``contact``) loaded contact of one mesh
    (:func:`analytical_stages`, :func:`contact_stages`; ``prebuilt``:
    :func:`loaded_contact`)."""
    stages = analytical_stages(box, case, log)
    return contact_stages(box, stages, options, log, prebuilt) if contact else stages


def mesh_stages(box: Gearbox, options: RunOptions, log: Steps, contact: bool = True,
                prebuilt: Mapping[str, Any] | None = None) -> dict[str, MeshStages]:
    """The static stages of every mesh of a gearbox (none for a ``[lumped_model]``);
    ``prebuilt``: FE sources by mesh name (:func:`loaded_contact`)."""
    if box.kind == "lumped":
        return {}
    out = {case.name: static_stages(box, case, options, log, contact,
                                    None if prebuilt is None else prebuilt[case.name])
           for case in mesh_cases(box)}
    return coupled_stages(box, out, options, log) if contact else out


def coupled_stages(box: Gearbox, meshes: dict[str, MeshStages], options: RunOptions,
                   log: Steps) -> dict[str, MeshStages]:
    """``meshes`` (each with its contact) solved together where they interact: a planetary
    set with a sun's shaft or planets' pins, both contacts with their deflection
    (:mod:`pipeline.run.planetary_shafts`); else ``meshes`` as they are."""
    if box.kind == "planetary" and box.shafts:
        from pipeline.run.planetary_shafts import planetary_shaft_stage

        sh = planetary_shaft_stage(box, meshes, options, log)  # both meshes together
        if sh is not None:
            return {name: dataclasses.replace(st, contact=sh.cycles[name],
                                              shafts=sh.mesh(name))
                    for name, st in meshes.items()}
    return meshes
