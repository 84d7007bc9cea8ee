"""Figures drawn side by side in forked processes once a run has queued them all.

Rasterising a figure is single-threaded and costs 0.2-1 s; a run writes ten or more.
A :class:`FigureQueue` collects the drawings a :class:`~pipeline.viz.figure_cache.FigureCache`
defers (the cached ones are copied at once) and :meth:`FigureQueue.draw_all` shares
them out round-robin between this process and ``workers - 1`` forked children. A forked
child inherits the data to draw, so nothing is pickled; each child writes its files
atomically and reports failures back through a pipe. ``fork`` is POSIX only: where it is
missing, or with one worker, everything is drawn here in turn.
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from pipeline.viz.figure_cache import FigureCache


@dataclass
class FigureQueue:
    """Drawings waiting for :meth:`draw_all`.

    Attributes
    ----------
    jobs : (PNG path, drawing thunk) in the order they were queued.
    """

    jobs: list[tuple[Path, Callable[[], Path]]] = field(default_factory=list)

    def add(self, path: str | Path, job: Callable[[], Path]) -> Path:
        """Queue ``job`` (draws and writes ``path``); returns ``path``."""
        self.jobs.append((Path(path), job))
        return Path(path)

    def draw_all(self, workers: int | None = None) -> None:
        """Draw every queued figure, in up to ``workers`` processes (default: CPU count).

        Raises
        ------
        RuntimeError : naming the figures whose drawing failed (their files not written).
        """
        jobs, self.jobs = self.jobs, []
        n = min(len(jobs), workers or os.cpu_count() or 1)
        if n <= 1 or "fork" not in multiprocessing.get_all_start_methods():
            failures = _draw(jobs)
        else:
            ctx = multiprocessing.get_context("fork")
            children = []
            for part in range(1, n):
                reader, writer = ctx.Pipe(duplex=False)
                child = ctx.Process(target=_draw_in_child, args=(jobs[part::n], writer),
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
        if failures:
            raise RuntimeError("figures not written: " + "; ".join(failures))


def _draw(jobs: list[tuple[Path, Callable[[], Path]]]) -> list[str]:
    """Run the jobs; one line per failure."""
    failures = []
    for path, job in jobs:
        try:
            job()
        except Exception as exc:  # reported by name; the other figures still get drawn
            failures.append(f"{path.name}: {type(exc).__name__}: {exc}")
    return failures


def _draw_in_child(jobs: list[tuple[Path, Callable[[], Path]]], writer) -> None:
    failures = _draw(jobs)
    writer.send(failures)
    writer.close()
    os._exit(0)  # skip the parent's atexit handlers and buffered output


@contextmanager
def parallel_figures(cache: FigureCache, workers: int | None = None
                     ) -> Iterator[FigureCache]:
    """``cache`` with its drawings deferred; on leaving the block they are drawn in parallel.

    If the block raises, the queued drawings are dropped (the run failed anyway).
    """
    queue = FigureQueue()
    yield replace(cache, queue=queue)
    queue.draw_all(workers)


__all__ = ["FigureQueue", "parallel_figures"]
