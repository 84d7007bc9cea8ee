"""Running a study: every point checked first, FE tables once per geometry, batches on Dask.

:func:`run_study` checks the study file (:func:`check_study`: KPIs, ``[best]``,
``[plots]``, the size) and builds every point's gearbox before any work (an input error
is one line and nothing is written), groups the points by the geometry their FE tables depend
on (:func:`pipeline.study.evaluate.fe_geometry_key`) and runs

* on **dask.distributed** (default): a ``LocalCluster`` with one single-threaded worker
  process per core and BLAS pinned to one thread (``workers``), or the existing cluster
  at ``scheduler`` (``tcp://host:8786``) with no other change: its address is checked for
  form with the options (:func:`check_scheduler`) and connected to before anything is
  written, waiting at most :data:`CONNECT_TIMEOUT_S` (5 s), so an unreachable scheduler
  is one line and leaves no folder behind. The FE tables of each
  geometry are one task; the batches of its points take that task's future as an
  argument, so Dask ships the tables to each worker once (memory to memory, never as
  files a remote worker could not see) and no point recomputes them;
* **serially** in this process (``workers = 0``): the same batches in the same order.

Each finished batch is appended atomically to the results folder
(:class:`pipeline.study.store.StudyStore`), so a killed study resumes where it stopped.
A folder holding anything but an earlier result of the same study is refused before the
first point (:func:`pipeline.study.store.study_folder`).

Every point is the static chain of ``gearpipe run`` (geometry, analytical stiffness, the
``[contact]`` compliance source, loaded contact) and, with ``[kpis] speed_range_rpm``, a
harmonic-balance sweep of the dynamic model (:mod:`pipeline.dynamics.hb_sweep`, in chunks
on the same executors); the KPIs are read from that result. ``--resume`` reads the finished
point numbers and refuses (one line) when the manifest's base-file SHA-256, ``[set]``,
axes, sampling or KPIs differ.

Checks (``tests/test_study.py``): 2 LocalCluster workers and serial give equal tables; kill
-9 after three parts + ``--resume`` gives the table of an uninterrupted run and recomputes
none of the saved points (computed-point log per session); the tip-relief study of the
example (``workflows/configs/tip_relief_study.toml``: FE 2D, long linear relief 6.2 mm on
both gears) has its TE p-p minimum at 12.0 um (5.24 -> 0.70-0.81 um), the classic estimate
being the combined tooth deflection at the load, F / (b c_gamma_alpha) = 4824 N / (20 mm x
22.0 N/(mm um)) = 10.96 um (+10 %; tolerance 20 %). With the analytical slices the minimum
lies near 24 um: their double-contact stiffness has no body coupling
(:mod:`pipeline.contact.fe2d_source`).

Measured (``workflows/benchmarks/bench_study.py``, one run on the 2 cores with no other job
of ours, load average 1.4 at the start): 1000 FE 2D loaded-contact points (20 positions,
one FE geometry) 45.4 s on 2 Dask workers (45 ms per point) against 60 ms per point
serially (parallel efficiency 0.66; target < 60 s). Under other jobs' load (4.5-8) the same
run took 175 s: the figures need the two cores.
"""

from __future__ import annotations

import logging
import os
import sys
import uuid
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pyarrow as pa

from pipeline.cache.folder import Cache
from pipeline.output_folder import OutputError, check_target
from pipeline.parallel import one_blas_thread
from pipeline.progress import progress
from pipeline.study.evaluate import build_fe_tables, evaluate_point, fe_geometry_key
from pipeline.study.kpis import KPI, select_kpis
from pipeline.study.points import DesignPoint, axis_values, design_points
from pipeline.study.size import check_size
from pipeline.study.spec import StudySpec
from pipeline.study.store import StudyStore, study_folder, study_identity
from pipeline.validation import InputError


@dataclass(frozen=True)
class StudyOptions:
    """How to run a study (not what it computes: that is the study file).

    Attributes
    ----------
    scheduler : address of an existing Dask scheduler, or ``None`` for a LocalCluster.
    workers : LocalCluster worker processes (default: CPU count); 0 runs serially here.
    resume : continue the unfinished study in the results folder.
    cache : the FE table cache (workers on this machine share it).
    point_log : append ``"<session> <point>"`` per computed point to
        ``OUT/computed_points.log`` (workers on this machine only).
    show_progress : progress bar on stderr.
    """

    scheduler: str | None = None
    workers: int | None = None
    resume: bool = False
    cache: Cache = field(default_factory=Cache)
    point_log: bool = True
    show_progress: bool = True

    def __post_init__(self) -> None:
        if self.workers is not None and (isinstance(self.workers, bool)
                                         or not isinstance(self.workers, int)
                                         or self.workers < 0):
            raise InputError(f"--workers {self.workers}: expected 0 (serial) or more")
        if self.scheduler is not None:
            check_scheduler(self.scheduler)
            if self.workers is not None:
                raise InputError(f"--workers {self.workers} with --scheduler: the workers are "
                                 "the cluster's; give one of the two")


CONNECT_TIMEOUT_S = 5.0
"""How long a study waits for the Dask scheduler at ``--scheduler`` to answer, s."""


def check_scheduler(address: str) -> tuple[str, str, int]:
    """``(scheme, host, port)`` of a Dask scheduler address as dask.distributed reads it:
    ``tcp://host:port`` (a bare ``host:port`` is tcp), or the ``tls``, ``ws``, ``wss``
    schemes over TCP as well (not ``inproc``, which reaches only this process, nor ``ucx``,
    which needs a package gearpipe does not install); :class:`InputError` otherwise.
    Only the form is checked here (:func:`dask_client` connects)."""
    from distributed.comm.addressing import parse_host_port
    from distributed.comm.registry import backends

    schemes = [s for s in ("tcp", "tls", "ws", "wss") if s in backends]
    scheme, sep, loc = address.rpartition("://")
    scheme = scheme if sep else "tcp"
    expected = (f"--scheduler {address}: expected a Dask scheduler address tcp://host:port "
                f"(schemes {', '.join(schemes)})")
    if scheme not in schemes:
        hint = (": http:// is the dashboard's address, the scheduler's is "
                "tcp://host:8786 by default") if scheme in ("http", "https") else ""
        raise InputError(expected + hint)
    try:
        host, port = parse_host_port(loc)
    except ValueError:
        raise InputError(expected) from None
    if not host or not 1 <= port <= 65535:
        raise InputError(f"{expected}: host and a port in 1..65535")
    return scheme, host, port


@dataclass(frozen=True)
class BatchJob:
    """What every batch of a study or optimisation shares (sent with each batch): the
    KPIs, the speed range of the dynamic ones, the FE cache, the computed-point log
    (``None``: none) and the session id."""

    kpis: tuple[KPI, ...]
    speed_range_rpm: tuple[float, float] | None
    speed_points: int
    cache: Cache
    log_path: str | None
    session: str


def evaluate_batch(batch: list[tuple[int, dict]], fe: Any, job: BatchJob) -> list[dict]:
    """KPI rows ``{"point": i, KPI...: value, "error": ""}`` of a batch (one BLAS thread).

    A point the pipeline refuses (an :class:`InputError` such as a contact that does not
    converge) gets NaN KPIs and its message in ``error``; the study goes on.
    """
    rows = []
    with one_blas_thread():
        for index, doc in batch:
            try:
                row = evaluate_point(doc, fe, kpis=job.kpis, speed_range_rpm=job.speed_range_rpm,
                                     speed_points=job.speed_points, cache=job.cache)
                err = ""
            except InputError as exc:
                row, err = {k.name: float("nan") for k in job.kpis}, str(exc)
            rows.append({"point": index, **row, "error": err})
            if job.log_path:
                with open(job.log_path, "a", encoding="utf-8") as fh:
                    fh.write(f"{job.session} {index}\n")
    return rows


def fe_tables_task(doc: dict, job: BatchJob) -> Any:
    """The FE tables of a point's geometry on one BLAS thread (one task per geometry)."""
    with one_blas_thread():
        return build_fe_tables(doc, cache=job.cache)


def _arrow_type(values: list[Any]) -> pa.DataType:
    if all(isinstance(v, bool) for v in values):
        return pa.bool_()
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return pa.int64()
    if all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        return pa.float64()
    return pa.string()


def table_schema(spec: StudySpec, points: list[DesignPoint], kpis: tuple[KPI, ...]
                 ) -> pa.Schema:
    """Columns: ``point``, each axis by its first key (file units), the KPIs, ``error``."""
    fields = [pa.field("point", pa.int64())]
    for a in spec.axes:
        vals = axis_values(a) if spec.method == "grid" else [p.values[a.label] for p in points]
        fields.append(pa.field(a.label, _arrow_type(vals)))
    fields += [pa.field(k.name, pa.float64()) for k in kpis]
    fields.append(pa.field("error", pa.string()))
    return pa.schema(fields)


def check_points(spec: StudySpec, points: list[DesignPoint]) -> tuple[list[dict], list[Any]]:
    """Point documents and their FE geometry keys; the first bad point is one line."""
    from pipeline.study.evaluate import point_gearbox

    docs, keys = [], []
    for p in points:
        doc = spec.point_document(p.values)
        try:
            box = point_gearbox(doc, spec.name)
        except InputError as exc:
            vals = ", ".join(f"{k} = {v!r}" for k, v in p.values.items())
            raise InputError(f"{spec.path}: point {p.index} ({vals}): {exc}") from None
        docs.append(doc)
        keys.append(fe_geometry_key(box))
    return docs, keys


def _batches(todo: list[int], keys: list[Any], size: int) -> list[tuple[Any, list[int]]]:
    """Consecutive points of one geometry, ``size`` at most per batch."""
    groups: dict[Any, list[int]] = {}
    for i in todo:
        groups.setdefault(keys[i], []).append(i)
    return [(g, ids[j:j + size]) for g, ids in groups.items() for j in range(0, len(ids), size)]


def _connect(address: str) -> Any:
    """A client of the scheduler at ``address``, or :class:`InputError` within
    :data:`CONNECT_TIMEOUT_S` (a refused connection at once: a plain socket is tried
    first, since dask.distributed retries a refused one until its timeout; over tcp the
    socket also waits for the scheduler's greeting, since a port that accepts and never
    answers makes dask.distributed's handshake wait past its timeout)."""
    import socket

    from dask.distributed import Client

    scheme, host, port = check_scheduler(address)
    try:
        with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT_S) as probe:
            if scheme == "tcp" and not probe.recv(1):  # a scheduler greets first (handshake)
                raise ConnectionError("connection closed")
        return Client(address, timeout=f"{CONNECT_TIMEOUT_S}s")
    except Exception as exc:  # noqa: BLE001 - whatever the failure, that is no scheduler
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else \
            f"{type(exc).__name__}: {str(exc).strip()[:120]}"
        raise InputError(f"--scheduler {address}: no Dask scheduler answered ({why}; "
                         f"waited at most {CONNECT_TIMEOUT_S:g} s); start it, or leave "
                         "--scheduler out to run on this machine") from None


@contextmanager
def dask_client(scheduler: str | None, workers: int | None) -> Iterator[Any]:
    """A client of the cluster at ``scheduler``, or of a new LocalCluster (one process per
    core, one thread each, BLAS pinned to one thread), closed on exit."""
    from dask.distributed import Client, LocalCluster

    if scheduler:
        with _connect(scheduler) as client:
            yield client
        return
    one = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                      processes=True, dashboard_address=None, silence_logs=logging.ERROR,
                      env=one) as cluster, Client(cluster) as client:
        yield client


def check_study(spec: StudySpec) -> tuple[KPI, ...]:
    """The study's KPIs; first everything the study file asks that no point is needed to
    check: the KPI names, the ``[best]`` KPI and the ``[plots]`` trade-off among them, a
    speed range with a ``[dynamics]`` table, the size (:func:`pipeline.study.size.check_size`).

    Raises :class:`InputError` (one line) for the first that is wrong.
    """
    dynamics = spec.speed_range_rpm is not None
    if dynamics and "dynamics" not in spec.base.document:
        raise InputError(f"{spec.path}: kpis.speed_range_rpm needs a [dynamics] table in the "
                         f"base file {spec.base_path.name}")
    kpis = select_kpis(spec.kpis, dynamics, "rating" in spec.base.document)
    names = [k.name for k in kpis]
    asked = [("best.kpi", spec.best_kpi)] if spec.best_kpi else []
    asked += [("plots.tradeoff", k) for k in spec.tradeoff]
    for where, name in asked:
        if name not in names:
            raise InputError(f"{spec.path}: {where} = {name!r} is not a KPI of this study; "
                             f"its KPIs: {', '.join(names)}")
    if spec.best_mean_over:
        labels = [a.label for a in spec.axes]
        if spec.best_mean_over not in labels:
            raise InputError(f"{spec.path}: best.mean_over = {spec.best_mean_over!r} is not an "
                             f"axis of this study; its axes: {', '.join(labels)}")
        if spec.method != "grid" or len(labels) < 2:
            raise InputError(f"{spec.path}: best.mean_over needs a grid of two axes or more "
                             "(the mean is taken over one axis at each value of the others)")
    if len(set(spec.tradeoff)) == 1:
        raise InputError(f"{spec.path}: plots.tradeoff = {list(spec.tradeoff)!r}: expected two "
                         "different KPIs")
    check_size(spec)
    return kpis


def run_study(spec: StudySpec, out: Path, options: StudyOptions | None = None, *,
              tables: Path | None = None) -> tuple[pa.Table, dict[str, Any]]:
    """Evaluate every point of ``spec`` into ``out`` (module docstring).

    ``out`` gets the manifest, part files and point log (:mod:`pipeline.study.store`),
    ``tables`` (default: ``out``) ``study.parquet`` and ``study.csv``. Returns the table
    (ordered by point number) and run facts: points, computed now, distinct FE
    geometries, workers, session id.

    Nothing is written before the study file (:func:`check_study`), every point's gearbox
    (:func:`check_points`) and ``out`` are checked and the scheduler at
    ``options.scheduler`` has answered.

    Raises
    ------
    InputError : a bad study file or point, an unfinished study without ``resume``, no
        scheduler at ``options.scheduler``.
    OutputError : ``out`` holds files that are not a result of this study, or cannot be
        written.
    """
    options = options or StudyOptions()
    kpis = check_study(spec)
    points = design_points(spec)
    docs, keys = check_points(spec, points)
    check_target(out, study_folder(spec))
    if Path(out).is_dir() and not os.access(out, os.W_OK | os.X_OK):
        raise OutputError(f"{out} is not writable, so the study cannot be written there; "
                          "give --out another folder")
    with ExitStack() as stack:
        client = (stack.enter_context(dask_client(options.scheduler, None))
                  if options.scheduler else None)
        store = StudyStore(out, table_schema(spec, points, kpis),
                           study_identity(spec, [k.name for k in kpis]), spec.name)
        done = store.open(options.resume, len(points))
        todo = [p.index for p in points if p.index not in done]
        session = uuid.uuid4().hex[:8]
        job = BatchJob(kpis, spec.speed_range_rpm, spec.speed_points, options.cache,
                   str(Path(out).resolve() / "computed_points.log")
                   if options.point_log and client is None else None, session)
        nw = (os.cpu_count() or 1) if options.workers is None else options.workers
        size = spec.batch_points or max(1, min(32, len(todo) // (8 * max(nw, 1)) or 1))
        batches = _batches(todo, keys, size)

        def finish(rows: list[dict]) -> None:
            for r in rows:
                r.update(points[r["point"]].values)
            store.append(rows, session)

        bar = progress(range(len(todo)), f"study {spec.name}", total=len(todo),
                       enabled=options.show_progress and bool(todo))
        ticks = iter(bar)
        if options.workers == 0:
            fe_cache: dict[Any, Any] = {}
            for g, ids in batches:
                if g is not None and g not in fe_cache:
                    fe_cache[g] = fe_tables_task(docs[ids[0]], job)
                rows = evaluate_batch([(i, docs[i]) for i in ids], fe_cache.get(g), job)
                finish(rows)
                for _ in rows:
                    next(ticks, None)
        elif batches:
            from dask.distributed import as_completed

            if client is None:
                client = stack.enter_context(dask_client(None, options.workers))
            nw = len(client.scheduler_info().get("workers", {})) or nw
            fe_futures = {g: client.submit(fe_tables_task, docs[ids[0]], job, key=f"fe-tables-{g}")
                          for g, ids in batches if g is not None}
            futures = [client.submit(evaluate_batch, [(i, docs[i]) for i in ids],
                                     fe_futures.get(g), job, key=f"batch-{session}-{ids[0]}")
                       for g, ids in batches]
            for fut in as_completed(futures):
                rows = fut.result()
                finish(rows)
                for _ in rows:
                    next(ticks, None)
        for _ in ticks:
            pass
    table, _ = store.write_table(tables)
    if table.num_rows != len(points):  # pragma: no cover - would be a bug
        print(f"study: {table.num_rows} of {len(points)} points in the table", file=sys.stderr)
    facts = {"points": len(points), "computed_now": len(todo), "resumed": options.resume,
             "fe_geometries": len({k for k in keys if k is not None}),
             "workers": 0 if options.workers == 0 else nw, "session": session,
             "scheduler": options.scheduler or ("serial" if options.workers == 0
                                                else "LocalCluster")}
    return table, facts
