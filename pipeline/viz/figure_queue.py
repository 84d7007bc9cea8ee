"""Figures drawn side by side in a process pool once a run has queued them all.

Drawing a figure is single-threaded and costs 0.1-0.4 s of CPU (the pyvista load map about
1 s; the demo run's 22 figures, 2-core machine); a run writes ten or more.
A :class:`FigureQueue` collects the drawings a :class:`~pipeline.viz.figure_cache.FigureCache`
defers (the cached ones are copied at once) and :meth:`FigureQueue.draw_all` submits
each to a :func:`~pipeline.parallel.process_pool` (forked workers that end with the
process that forked them, kill -9 included); each worker writes its files atomically and
returns its failure, if any, as one line. ``fork`` is POSIX only: where it is missing, or
with one worker, everything is drawn in turn.

A *drawer* started early (:meth:`FigureQueue.start`, ``parallel_figures(prestart=True)``)
is a pool of one process that imports matplotlib (about 0.5 s) and warms its font cache
(:func:`warm_up`, its initializer) while this process is still computing what to draw,
so a run whose figures are not all cached does not wait for that import. A run whose
stages give the data of some figures before the last (``gearpipe run``: geometry and
stiffness before the FE contact, the contact's figures before the dynamics and the root
stress) hands them over with :meth:`~FigureQueue.send`: the drawer draws them one at a
time, itself, on the core this process leaves free while it computes; it is given the
next one only when it has drawn the last (:meth:`~FigureQueue._feed`, from the pool's
result thread), so that the end of the run finds at most one drawing begun. The drawings
it has not been given then join the rest (a run may also hand it a preparation for
drawings to come, :meth:`~FigureQueue.prepare`: ``gearpipe run`` has it import pyvista
after the geometry and stiffness figures, while the FE contact computes, when it drew
some of those, so that the load map drawn after the contact does not wait for the
import): :meth:`~FigureQueue.draw_all` submits them all
to it as one job, which forks the drawing pool from the warmed-up drawer
(:func:`draw_jobs`): every drawing process starts with matplotlib and the drawing modules
the drawer imported (for the figures it drew) imported once. Why not one pool forked from
this process at the start: each of its workers imports them itself.
Measured (``workflows/benchmarks/bench_run.py``, the demo's cold ``gearpipe run`` beside
0a4a91a, which drew every figure after the last stage; three runs each, every file and
number the same): with pyvista prepared, wall median 11.5 s against 14.2 s (0.80) and
10.9 against 13.8 s (0.79) with no other job (load average 0.6-2.3, the run's own), CPU
19.3-20.3 against 20.7-20.8 s, the load map 1.5 s of CPU against 2.3-2.7 s; before
that, beside another job using both cores, 14.5 against 17.0 s (0.85) at load average
1.3-2.9 and 12.9 against 14.5 s (0.89) at 2.4-3.2; at 3.1-3.6, when the run's processes
share about one core, 23.3 against 23.5 s (0.99): the drawer gains only where a core is
free while the stages compute.
Measured on 2 cores (warm ``gearpipe run`` of the demo with the damping ratio changed,
runs interleaved), with one worker warmed up: 13 % slower than the drawer, 0.37 s more
CPU; with every worker warmed up: 11 % slower, and the unchanged warm run 18 % slower
(two imports compete with the computing process). With the drawer forking the pool, the
runs took as long as with the hand-written drawer it replaced (median ratios 0.93-1.05).

A drawing process runs without Python's cyclic garbage collector (:func:`drawing_process`):
matplotlib makes many objects in reference cycles, and each full collection walks the
whole heap of imported modules again. Measured on the 22 figures of the demo run drawn in
one process (2-core machine, loaded): 4.5-4.8 s of CPU without it against 4.9-5.0 s with
it, for 37 MB more peak memory (519 against 482 MB); the processes end after drawing.

The figures come out the same wherever they are drawn. A drawing that does not pickle
(a local function) is drawn in the process that holds it; so are the drawings a broken
pool did not finish (a worker killed: the pool ends its other workers too), in turn.
A batch the drawer cannot take (it does not pickle, or the drawer has died) is drawn
from this process by :func:`draw_jobs`. A run with every figure cached kills the drawer
at once (:func:`~pipeline.parallel.kill_pool`) rather than wait for its warm-up.

The early drawer helps only with a free core. Measured side by side on 2 cores at load
average 1.4-1.6 (warm ``gearpipe run`` of the demo's pair, four runs each): with the
damping ratio changed 2.56-3.15 s with the drawer and 2.59-3.32 s without; with nothing
changed 2.07-2.43 s with it and 1.81-2.05 s without (its matplotlib import competes for the
core, and nothing is drawn).
"""

from __future__ import annotations

import gc
import os
import threading
from collections.abc import Callable, Iterator
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from pipeline.parallel import can_fork, kill_pool, process_pool, start_workers

if TYPE_CHECKING:
    from pipeline.viz.figure_cache import FigureCache

Job = tuple[Path, Callable[[], Path]]
"""A drawing: the PNG it writes and the call that draws and writes it."""


Sent = tuple[Path, Callable[[], Path], Future]
"""A drawing handed to the drawer by :meth:`FigureQueue.send`, with its future."""


@dataclass
class FigureQueue:
    """Drawings waiting for :meth:`draw_all`.

    Attributes
    ----------
    jobs : (PNG path, drawing thunk) in the order they were queued.
    drawer : the early-started drawer, a pool of one warmed-up process (:meth:`start`).
    handed : the drawings :meth:`send` handed over that the drawer has not been given yet.
    sent : the drawings given to the drawer, with their futures.
    preparing, prepared : the calls :meth:`prepare` handed over, not yet given to the drawer
        and given (their futures).
    """

    jobs: list[Job] = field(default_factory=list)
    drawer: ProcessPoolExecutor | None = None
    handed: list[Job] = field(default_factory=list)
    sent: list[Sent] = field(default_factory=list)
    preparing: list[Callable[[], object]] = field(default_factory=list)
    prepared: list[Future] = field(default_factory=list)
    _lock: threading.RLock = field(default_factory=threading.RLock, repr=False,
                                   compare=False)

    def add(self, path: str | Path, job: Callable[[], Path]) -> Path:
        """Queue ``job`` (draws and writes ``path``); returns ``path``."""
        self.jobs.append((Path(path), job))
        return Path(path)

    def start(self) -> None:
        """Start the drawer now (module docstring); nothing happens where ``fork`` is
        missing."""
        if self.drawer is None and can_fork():
            self.drawer = process_pool(1, warm_up)
            start_workers(self.drawer)  # forked by this thread, the one that waits for it

    def send(self) -> None:
        """Hand the drawings queued so far to the drawer, which draws them one at a time, in
        turn, while this process goes on (module docstring); without a drawer they stay
        queued for :meth:`draw_all`."""
        with self._lock:
            if self.drawer is None:
                return
            self.handed += self.jobs
            self.jobs = []
            self._feed()

    def prepare(self, call: Callable[[], object]) -> None:
        """Have the drawer run ``call`` (a module-level function: the imports of drawings to
        come, say) once it has drawn the drawings handed over before, while this process
        goes on (module docstring); nothing without a drawer. Its errors are ignored: a
        drawing that needs what it prepares reports its own."""
        with self._lock:
            if self.drawer is None:
                return
            self.preparing.append(call)
            self._feed()

    def _feed(self) -> None:
        """Give the drawer the next handed drawing, or else the next preparation, if it has
        none in hand (one at a time, so that :meth:`draw_all` finds at most one begun; the
        lock held)."""
        busy = [f for *_, f in self.sent] + self.prepared
        if self.drawer is None or any(not f.done() for f in busy):
            return
        try:
            if self.handed:
                path, job = self.handed[0]
                future = self.drawer.submit(draw_one, path, job)
                self.sent.append((path, job, future))
                self.handed.pop(0)
            elif self.preparing:
                future = self.drawer.submit(self.preparing[0])
                self.prepared.append(future)
                self.preparing.pop(0)
            else:
                return
        except (BrokenProcessPool, RuntimeError):  # it died, or is shut down: draw_all draws
            return
        future.add_done_callback(self._drawn)

    def _drawn(self, future: Future) -> None:
        """A given drawing is done (called by the pool's thread): give the next."""
        with self._lock:
            self._feed()

    def stop(self) -> None:
        """End the drawer without drawing the rest (idempotent): it is killed rather than
        waited for (it may still be importing matplotlib, or drawing a figure of a run that
        failed)."""
        with self._lock:
            drawer, self.drawer = self.drawer, None
            self.handed, self.sent, self.preparing, self.prepared = [], [], [], []
        if drawer is not None:
            kill_pool(drawer)

    def draw_all(self, workers: int | None = None, show_progress: bool = False) -> None:
        """Draw every queued figure in up to ``workers`` processes (default: CPU count):
        by the drawer if :meth:`start` started it, else from here (:func:`draw_jobs`);
        wait for those :meth:`send` handed to the drawer (the ones it has not begun are
        drawn with the rest).

        ``show_progress``: the figures written so far, on stderr once the drawing has taken a
        second (:func:`pipeline.progress.progress`; counted by their files appearing, as
        the drawings write them atomically).

        Raises
        ------
        RuntimeError : naming the figures whose drawing failed (their files not written).
        """
        with self._lock:  # the drawer is given nothing more (_feed)
            jobs, sent = self.handed + self.jobs, self.sent
            self.jobs, self.handed, self.sent, self.preparing = [], [], [], []
            for future in self.prepared:  # one it has begun is waited for with its queue
                future.cancel()
            self.prepared = []
            drawer, self.drawer = self.drawer, None
        if not jobs and not sent:  # every figure came from the cache: not waited for
            if drawer is not None:
                kill_pool(drawer)
            return
        paths = [path for path, _, _ in sent] + [path for path, _ in jobs]
        with _counting_files(paths, show_progress):
            failures = (_by_drawer(drawer, sent, jobs, workers) if drawer is not None
                        else draw_jobs(jobs, workers))
        if failures:
            raise RuntimeError("figures not written: " + "; ".join(failures))


def draw_jobs(jobs: list[Job], workers: int | None) -> list[str]:
    """Draw ``jobs`` in a pool of up to ``workers`` processes forked from this one (default:
    CPU count), or here in turn (one worker, or no ``fork``); the failures, in the order
    of ``jobs``."""
    n = min(len(jobs), workers or os.cpu_count() or 1)
    if n > 1 and can_fork():
        return _draw_in(process_pool(n, drawing_process), jobs)
    return [failure for failure in (draw_one(path, job) for path, job in jobs) if failure]


def draw_one(path: Path, job: Callable[[], Path]) -> str | None:
    """Run one drawing; its failure as one line (``<file>: <error type>: <message>``), or
    ``None``: the other figures still get drawn, and the error is named in the caller."""
    try:
        job()
    except Exception as exc:  # reported by name; the other figures still get drawn
        return f"{path.name}: {type(exc).__name__}: {exc}"
    return None


def _by_drawer(drawer: ProcessPoolExecutor, sent: list[Sent], jobs: list[Job],
               workers: int | None) -> list[str]:
    """Have the drawer draw ``jobs`` (:func:`draw_jobs` there, after the ``sent`` drawings
    it has begun; those it has not are drawn with ``jobs``), wait for all and end it; the
    failures. A sent drawing the drawer could not draw (it did not pickle, or the drawer
    died) is drawn here; so are ``jobs`` if it could not take them (they do not pickle, or
    it died: then nothing it may have written of them is trusted), by :func:`draw_jobs`."""
    began = [(path, job, future) for path, job, future in sent if not future.cancel()]
    jobs = [(path, job) for path, job, future in sent if future.cancelled()] + jobs
    batch: Future | None = None
    if jobs:
        try:
            batch = drawer.submit(draw_jobs, jobs, workers)
        except BrokenProcessPool:  # it died before
            pass
    failures: list[str | None] = []
    try:
        for path, job, future in began:
            # an exception is the drawer's, not the drawing's (draw_one catches those)
            failures.append(future.result() if future.exception() is None
                            else draw_one(path, job))
        drawn = None if batch is None or batch.exception() is not None else batch.result()
    except BaseException:  # interrupted: nothing more to wait for
        kill_pool(drawer)
        raise
    if jobs and drawn is None:
        kill_pool(drawer)
        drawn = draw_jobs(jobs, workers)
    else:
        drawer.shutdown()
    return [failure for failure in failures if failure] + (drawn or [])


def _draw_in(pool: ProcessPoolExecutor, jobs: list[Job]) -> list[str]:
    """Draw ``jobs`` in ``pool`` (shut down afterwards), and here those it could not draw
    (module docstring); the failures, in the order of ``jobs``."""
    futures: list[Future | None] = []
    try:
        for path, job in jobs:
            futures.append(pool.submit(draw_one, path, job))
    except BrokenProcessPool:  # a worker died before all drawings were sent
        futures += [None] * (len(jobs) - len(futures))
    failures = []
    broken = False
    try:
        for (path, job), future in zip(jobs, futures, strict=True):
            # an exception here is the pool's, not the drawing's (draw_one catches those):
            # the drawing did not pickle, or its worker or another one died (then its file,
            # written or not, is drawn again)
            gone = future is None or future.cancelled()
            error = None if gone else future.exception()
            if not gone and error is None:
                failures.append(future.result())
                continue
            if not broken and (gone or isinstance(error, BrokenProcessPool)):
                # the pool's other workers end before anything is drawn here: none of its
                # processes is still writing, and the temporary file one left half-written
                # is a dead process's, removed by the next write into its folder
                kill_pool(pool)
                broken = True
            failures.append(draw_one(path, job))
    except BaseException:  # interrupted: nothing more to wait for
        kill_pool(pool)
        raise
    pool.shutdown()
    return [failure for failure in failures if failure]


def warm_up() -> None:
    """Import matplotlib's figure and Agg canvas and rasterise a text once (font cache), then
    :func:`drawing_process` (the drawer forks its drawing processes from here)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(1, 1))
    fig.text(0.5, 0.5, "0.5 [um]")
    FigureCanvasAgg(fig).draw()
    drawing_process()


def drawing_process() -> None:
    """Turn off the cyclic garbage collector in this process, which only draws and then ends
    (module docstring); the objects alive now are moved out of the collector's way."""
    gc.freeze()
    gc.disable()


def _files_written(paths: list[Path], finished: threading.Event,
                   poll: float = 0.2) -> Iterator[Path]:
    """Yield each of ``paths`` not there at the start once it exists, until all are or
    ``finished`` is set (then those written by then)."""
    waiting = [p for p in paths if not p.exists()]
    while waiting:
        stop = finished.wait(poll)
        for p in [p for p in waiting if p.exists()]:
            waiting.remove(p)
            yield p
        if stop:
            return


@contextmanager
def _counting_files(paths: list[Path], enabled: bool) -> Iterator[None]:
    """Report the files of ``paths`` appearing while the block runs (a watcher thread)."""
    if not enabled:
        yield
        return
    from pipeline.progress import progress

    finished = threading.Event()

    def watch() -> None:
        for _ in progress(_files_written(paths, finished), "figures drawn", total=len(paths)):
            pass

    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    try:
        yield
    finally:
        finished.set()
        watcher.join()


@contextmanager
def parallel_figures(cache: FigureCache, workers: int | None = None, *,
                     prestart: bool = False) -> Iterator[FigureCache]:
    """``cache`` with its drawings deferred; on leaving the block they are drawn in parallel
    (or earlier, by :meth:`FigureQueue.draw_all` on ``cache.queue``).

    ``prestart`` starts the drawer on entering (module docstring): for a block that
    computes before it queues. If the block raises, the queued drawings are dropped (the
    run failed anyway) and the drawer is killed.
    """
    queue = FigureQueue()
    if prestart:
        queue.start()
    try:
        yield replace(cache, queue=queue)
        queue.draw_all(workers)
    finally:
        queue.stop()


__all__ = ["FigureQueue", "draw_jobs", "draw_one", "drawing_process", "parallel_figures",
           "warm_up"]
