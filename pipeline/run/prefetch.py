"""The FE 2D tables of a run built side by side, in forked processes, as the run starts.

A cold ``gearpipe run`` with ``[contact] compliance = "fe2d"`` needs, per mesh, the
compliance tables of both gears (:func:`pipeline.contact.fe2d_table.gear_table`, before the
loaded contact) and their fillet stress tables (:func:`pipeline.fem.fillet_stress.
build_fillet_stress`, for the root stress after it). Each is one Gmsh mesh and one
factorisation, independent of the others and of the contact: built one after the other
they were half the computing (the demo's pair: 0.48-0.55 s of CPU for each compliance
table, 1.0-1.14 s for the fillet table, of 3.6-3.8 s for the whole run without the
imports; 2 cores shared with other work). :func:`prefetch_tables` lists them (the same
functions the stages call: :func:`~pipeline.contact.fe2d_table.table_jobs`,
:func:`~pipeline.contact.root_stress.fillet_settings`), leaves out those in the cache, and
builds the first (the first mesh's pinion) in this process, which would otherwise wait,
and the others in a pool of forked processes (:func:`pipeline.parallel.process_pool`, one
per core but one; a table two identical gears share is built once), each into the run's
cache, the compliance tables first: the loaded contact waits for them, and the fillet
tables are then built while the contact and the shafts are solved. The stages call the same
functions as without it, after waiting for that mesh's tables
(:meth:`TablePrefetch.wait_contact` before building its compliance source,
:meth:`TablePrefetch.wait_root` before its root stress), which they then read from the
cache. So the numbers cannot differ: the same function with the same inputs writes the
same entry, and each process runs with this process's BLAS and OpenMP thread counts (MKL
PARDISO's round-off depends on them: 7e-14 between one and two threads); the run's
summary and the entries are bit for bit those of a run that builds every table in its
stages (``tests/test_run_prefetch.py``). A table that fails in its process is built again
by its stage, which reports the error as without the prefetch.

What it gains is wall time, where cores are free; it costs CPU. On the demo's pair (one pool
process; CPU per process, 2 cores at load average 8): this process's critical path is its
imports 0.55 s, the pinion's table 0.65 s beside the pool's gear table 0.64 s, then the
contact, the shafts and the dynamics 1.1 s beside the pool's fillet table 1.11 s, then the
root stress 0.07 s: 2.4 s of CPU against 4.1-4.3 s one after the other, the wall time of
the computing on 2 otherwise idle cores. The run took 0.1-0.4 s more CPU in all (the pool
process's start, two processes' caches). On cores busy with other sessions it gained
nothing: Linux shares the CPU between sessions (autogroups) before processes, so a second
process of a run on a saturated machine only splits the run's share (the run's wall time
9.0-10.1 s against 8.3-9.1 s one after the other at load average 8, four runs each).
Nothing is prefetched with the cache off (``--no-cache``: the tables travel through it),
without fork (:func:`pipeline.parallel.can_fork`), with one core, or when every table is in
the cache already (a warm run forks nothing and imports no FE solver to find that out).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from concurrent.futures import Future, ProcessPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from functools import partial
from typing import Any

from pipeline.config import Gearbox
from pipeline.fem.settings import FE2DSettings
from pipeline.geometry.assembly_errors import assemble
from pipeline.run.chain import RunOptions, mesh_cases
from pipeline.validation import InputError

CONTACT = "contact"
"""Tables the loaded contact of a mesh waits for."""
ROOT = "root"
"""Tables the root stress of a mesh waits for."""


@dataclass(frozen=True)
class TableJob:
    """One table to build: the stage that needs it (``(mesh, CONTACT or ROOT)``), where it
    lands in the cache and the call that builds it there."""

    needed_by: tuple[str, str]
    entry: Any
    build: Callable[[], Any]


@dataclass
class TablePrefetch:
    """The tables being built (:func:`prefetch_tables`); wait for them before using them.

    Attributes
    ----------
    futures : (mesh, stage) -> the builds in the pool that stage needs.
    here : (mesh, stage) -> the builds this process makes when that stage first waits
        (this process would otherwise only wait).
    pool : the process pool, or None when nothing is built there.
    """

    futures: dict[tuple[str, str], list[Future]] = field(default_factory=dict)
    here: dict[tuple[str, str], list[Callable[[], Any]]] = field(default_factory=dict)
    pool: ProcessPoolExecutor | None = None

    def _wait(self, mesh: str, stage: str) -> None:
        for build in self.here.pop((mesh, stage), []):
            try:
                build()
            except Exception:  # noqa: BLE001 - the stage builds it again and reports why
                pass
        for f in self.futures.get((mesh, stage), []):
            f.exception()  # a failed build: the stage builds it again and reports why

    def wait_contact(self, mesh: str) -> None:
        """Wait until the compliance tables of both gears of ``mesh`` are built."""
        self._wait(mesh, CONTACT)

    def wait_root(self, mesh: str) -> None:
        """Wait until the fillet stress tables of both gears of ``mesh`` are built."""
        self._wait(mesh, ROOT)


def _with_threads(limits: list[dict], build: Callable[[], Any]) -> None:
    """``build()`` with this process's thread counts of each BLAS/OpenMP library set to
    ``limits`` (a pool worker starts with one); its result stays in the cache."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits={d["prefix"]: d["num_threads"] for d in limits}):
        build()


def _import_fe_side() -> None:
    """Import the FE side (scikit-fem, Gmsh, the assembly and solver layers) here, before
    the pool forks: this process builds a table too, and each pool process then inherits it
    instead of importing it first (0.3 s of CPU, scikit-fem most of it, that delayed its
    first table)."""
    import gmsh  # noqa: F401

    import pipeline.fem.fillet_stress  # noqa: F401
    import pipeline.fem.influence  # noqa: F401
    import pipeline.fem.patch_loads  # noqa: F401


def table_jobs(box: Gearbox, options: RunOptions) -> list[TableJob]:
    """The FE 2D tables a run of ``box`` will read or build and are not in the cache (module
    docstring); two identical gears give two jobs with one ``entry``."""
    from pipeline.contact.fe2d_table import gear_table, table_entry
    from pipeline.contact.fe2d_table import table_jobs as gear_tables
    from pipeline.contact.root_stress import fillet_settings
    from pipeline.fem.fillet_stress import build_fillet_stress, fillet_stress_entry

    fe, cache = box.fe_source, options.cache
    if not isinstance(fe, FE2DSettings) or not cache.enabled:
        return []
    fe = replace(fe, slices=None)  # the tables do not depend on the slices
    jobs: list[TableJob] = []
    for case in mesh_cases(box):
        assembled = assemble(case.pair, case.assembly_errors)
        pair = case.pair if assembled is None else assembled.actual
        tip_contact = box.mesh_contact(case.name).tip_contact
        try:
            for _, gear, teeth in gear_tables(pair, fe, tip_contact):
                jobs.append(TableJob((case.name, CONTACT), table_entry(gear, fe, teeth,
                                                                       cache=cache),
                                     partial(gear_table, gear, fe, teeth, cache=cache)))
            settings = fillet_settings(pair.pair_indices(tip_contact), fe)
            for gear in (pair.pinion, pair.gear):
                jobs.append(TableJob((case.name, ROOT), fillet_stress_entry(gear, settings,
                                                                            cache=cache),
                                     partial(build_fillet_stress, gear, settings,
                                             cache=cache)))
        except InputError:  # the stage reports it
            continue
    return [job for job in jobs if not job.entry.is_file()]


@contextmanager
def prefetch_tables(box: Gearbox, options: RunOptions) -> Iterator[TablePrefetch]:
    """Start building the tables of :func:`table_jobs` side by side (module docstring); on
    leaving, wait for them (the pool is killed at once when the run failed)."""
    from pipeline.parallel import can_fork, kill_pool, process_pool

    jobs = table_jobs(box, options) if can_fork() and (os.cpu_count() or 1) > 1 else []
    if not jobs:
        yield TablePrefetch()
        return
    from threadpoolctl import threadpool_info

    # the first table (the first mesh's pinion) is built here, the others in the pool: one
    # process fewer to start, and this one would only wait
    first = jobs[0]
    prefetch = TablePrefetch(here={first.needed_by: [first.build]})
    rest = [j for j in jobs if j.entry != first.entry]  # an identical gear's: with it
    entries = {j.entry for j in rest}
    if not entries:
        yield prefetch
        return
    limits = [d for d in threadpool_info() if d.get("num_threads")]
    _import_fe_side()
    pool = process_pool(min(len(entries), max(1, (os.cpu_count() or 1) - 1)))
    prefetch.pool = pool
    try:
        builds: dict[Any, Future] = {}
        for job in rest:  # each entry once (two identical gears share it)
            if job.entry not in builds:
                builds[job.entry] = pool.submit(_with_threads, limits, job.build)
            prefetch.futures.setdefault(job.needed_by, []).append(builds[job.entry])
        yield prefetch
    except BaseException:
        kill_pool(pool)
        raise
    pool.shutdown(wait=True)
