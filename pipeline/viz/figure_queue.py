"""Figures drawn side by side in forked processes once a run has queued them all.

Rasterising a figure is single-threaded and costs 0.2-1 s; a run writes ten or more.
A :class:`FigureQueue` collects the drawings a :class:`~pipeline.viz.figure_cache.FigureCache`
defers (the cached ones are copied at once) and :meth:`FigureQueue.draw_all` shares
them out round-robin between one process and ``workers - 1`` forked children. A forked
child inherits the data to draw, so nothing is pickled; each child writes its files
atomically and reports failures back through a pipe. ``fork`` is POSIX only: where it is
missing, or with one worker, everything is drawn here in turn. Every forked process ends
with the process that forked it, kill -9 included (``pipeline.child_processes``); the
drawer and the drawing children are forked by the thread that later waits for them.

A *drawer* started early (:meth:`FigureQueue.start`, ``parallel_figures(prestart=True)``)
is a forked process that imports matplotlib (about 0.5 s) and warms its font cache while
this process is still computing what to draw, so a run whose figures are not all cached
does not wait for that import. :meth:`~FigureQueue.draw_all` then pickles the drawings to
it, and it shares them out with its own forked children as above. Drawings that cannot
be pickled, or a drawer that has died, are drawn here instead: the figures come out the
same either way.

The early drawer helps only with a free core. Measured side by side on 2 cores at load
average 1.4-1.6 (warm ``gearpipe run`` of the demo's pair, four runs each): with the
damping ratio changed 2.56-3.15 s with the drawer and 2.59-3.32 s without; with nothing
changed 2.07-2.43 s with it and 1.81-2.05 s without (its matplotlib import competes for the
core, and nothing is drawn: it is killed as soon as the run knows).
"""

from __future__ import annotations

import multiprocessing
import os
import pickle
import signal
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pipeline.child_processes import die_with_parent

if TYPE_CHECKING:
    from pipeline.viz.figure_cache import FigureCache

Job = tuple[Path, Callable[[], Path]]
"""A drawing: the PNG it writes and the call that draws and writes it."""


@dataclass
class FigureQueue:
    """Drawings waiting for :meth:`draw_all`.

    Attributes
    ----------
    jobs : (PNG path, drawing thunk) in the order they were queued.
    drawer : the early-started drawing process, if any (:meth:`start`).
    """

    jobs: list[Job] = field(default_factory=list)
    drawer: _Drawer | None = None

    def add(self, path: str | Path, job: Callable[[], Path]) -> Path:
        """Queue ``job`` (draws and writes ``path``); returns ``path``."""
        self.jobs.append((Path(path), job))
        return Path(path)

    def start(self) -> None:
        """Fork the drawer now (module docstring); nothing happens where ``fork`` is missing."""
        if self.drawer is None and _can_fork():
            self.drawer = _Drawer.start()

    def stop(self) -> None:
        """End the drawer without drawing (idempotent): it has written nothing, so it is
        killed rather than waited for (it may still be importing matplotlib)."""
        drawer, self.drawer = self.drawer, None
        if drawer is not None:
            drawer.close(kill=True)

    def draw_all(self, workers: int | None = None, show_progress: bool = False) -> None:
        """Draw every queued figure, in up to ``workers`` processes (default: CPU count).

        ``show_progress``: the figures written so far, on stderr once the drawing has taken a
        second (:func:`pipeline.progress.progress`; counted by their files appearing, as
        the drawing processes write them atomically).

        Raises
        ------
        RuntimeError : naming the figures whose drawing failed (their files not written).
        """
        jobs, self.jobs = self.jobs, []
        if not jobs:  # every figure came from the cache: the drawer is not waited for
            self.stop()
            return
        drawer, self.drawer = self.drawer, None
        with _counting_files([path for path, _ in jobs], show_progress):
            failures = drawer.draw(jobs, workers) if drawer is not None else None
            if failures is None:
                failures = _draw_parallel(jobs, workers)
        if failures:
            raise RuntimeError("figures not written: " + "; ".join(failures))


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


def _can_fork() -> bool:
    return "fork" in multiprocessing.get_all_start_methods()


def _draw(jobs: list[Job]) -> list[str]:
    """Run the jobs; one line per failure."""
    failures = []
    for path, job in jobs:
        try:
            job()
        except Exception as exc:  # reported by name; the other figures still get drawn
            failures.append(f"{path.name}: {type(exc).__name__}: {exc}")
    return failures


def _draw_in_child(parent_pid: int, jobs: list[Job], writer) -> None:
    die_with_parent(parent_pid)
    failures = _draw(jobs)
    writer.send(failures)
    writer.close()
    os._exit(0)  # skip the parent's atexit handlers and buffered output


def _draw_parallel(jobs: list[Job], workers: int | None) -> list[str]:
    """Draw ``jobs`` round-robin here and in ``workers - 1`` forked children; failures."""
    n = min(len(jobs), workers or os.cpu_count() or 1)
    if n <= 1 or not _can_fork():
        return _draw(jobs)
    ctx = multiprocessing.get_context("fork")
    children = []
    for part in range(1, n):
        reader, writer = ctx.Pipe(duplex=False)
        child = ctx.Process(target=_draw_in_child, args=(os.getpid(), jobs[part::n], writer),
                            daemon=True)
        child.start()
        writer.close()
        children.append((child, reader, jobs[part::n]))
    failures = _draw(jobs[0::n])
    for child, reader, part_jobs in children:
        try:
            failures += reader.recv()
        except EOFError:  # the child died before reporting
            failures += [f"{p.name}: drawing process ended" for p, _ in part_jobs]
        child.join()
        if child.exitcode and not failures:
            failures.append(f"drawing process exit code {child.exitcode}")
    return failures


def _warm_up() -> None:
    """Import matplotlib's figure and Agg canvas and rasterise a text once (font cache)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(1, 1))
    fig.text(0.5, 0.5, "0.5 [um]")
    FigureCanvasAgg(fig).draw()


def _serve(parent_pid: int, conn, parents_end) -> None:
    """The drawer: warm up, wait for one batch of jobs, draw it, report the failures.

    ``parents_end`` is the parent's end of the pipe, inherited through the fork: closed
    first, so that :meth:`_Drawer.close` ends ``conn.recv()``. The parent's death ends the
    drawer whatever it is doing (``die_with_parent``): the pipe alone would not, as every
    process the parent forks later (a sweep's pool) inherits the parent's end.
    """
    die_with_parent(parent_pid)
    parents_end.close()
    try:
        try:
            _warm_up()
        except Exception:  # noqa: BLE001 - the drawings report their own errors
            pass
        message: Any = conn.recv()
        if message is not None:
            jobs, workers = message
            try:
                failures: list[str] | None = _draw_parallel(jobs, workers)
            except Exception:  # noqa: BLE001 - the caller draws them itself
                failures = None
            conn.send(failures)
    except (EOFError, OSError):
        pass  # the run ended or failed without drawing
    finally:
        conn.close()
        os._exit(0)  # skip the parent's atexit handlers and buffered output


@dataclass
class _Drawer:
    """A forked drawing process and this end of its pipe."""

    process: Any
    conn: Any

    @classmethod
    def start(cls) -> _Drawer:
        ctx = multiprocessing.get_context("fork")
        ours, theirs = ctx.Pipe()
        # not a daemon: a daemon may not fork the children it draws with; it ends when this
        # end of the pipe closes (close()) or when this process dies (die_with_parent)
        process = ctx.Process(target=_serve, args=(os.getpid(), theirs, ours), daemon=False)
        process.start()
        theirs.close()
        return cls(process, ours)

    def draw(self, jobs: list[Job], workers: int | None) -> list[str] | None:
        """Have the drawer draw ``jobs``; its failures, or ``None`` if it could not (the jobs
        do not pickle, or it died): then nothing it may have written is trusted and the
        caller draws them all."""
        try:
            payload = pickle.dumps((jobs, workers), protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:  # noqa: BLE001 - any argument that does not pickle: draw here
            self.close(kill=True)
            return None
        try:
            if not self.process.is_alive():
                return None
            with _broken_pipe_as_error():
                self.conn.send_bytes(payload)
            return self.conn.recv()
        except (EOFError, OSError):
            return None
        finally:
            self.close()

    def close(self, kill: bool = False) -> None:
        """Close the pipe and end the process (at once with ``kill``, else after its reply)."""
        try:
            self.conn.close()
        finally:
            if kill:
                self.process.kill()
            self.process.join(timeout=None if kill else 5)
            if self.process.is_alive():
                self.process.kill()
                self.process.join()


@contextmanager
def _broken_pipe_as_error() -> Iterator[None]:
    """Writing to a drawer that has died raises BrokenPipeError rather than killing this
    process with SIGPIPE (Python ignores SIGPIPE, but a library may have restored it)."""
    if (not hasattr(signal, "SIGPIPE")
            or threading.current_thread() is not threading.main_thread()):
        yield
        return
    previous = signal.signal(signal.SIGPIPE, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGPIPE, previous)


@contextmanager
def parallel_figures(cache: FigureCache, workers: int | None = None, *,
                     prestart: bool = False) -> Iterator[FigureCache]:
    """``cache`` with its drawings deferred; on leaving the block they are drawn in parallel
    (or earlier, by :meth:`FigureQueue.draw_all` on ``cache.queue``).

    ``prestart`` starts the drawer on entering (module docstring): for a block that computes
    before it queues. If the block raises, the queued drawings are dropped (the run failed
    anyway) and the drawer ends.
    """
    queue = FigureQueue()
    if prestart:
        queue.start()
    try:
        yield replace(cache, queue=queue)
        queue.draw_all(workers)
    finally:
        queue.stop()


__all__ = ["FigureQueue", "parallel_figures"]
