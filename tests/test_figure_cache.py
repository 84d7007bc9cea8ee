"""Figures of a run: cached by what they show, drawn side by side in a process pool.

A cached figure is copied, not redrawn; a changed argument redraws it. Figures queued
for parallel drawing come out byte-identical to those drawn in turn, and one figure
whose drawing fails is named in one error while the others are still written. The
early-started drawer gives the same files, drawn by it or by the pool it forks, not by
this process; drawings handed to it early (``send``) are drawn by the drawer itself, one
given at a time, the rest by its pool, and a preparation handed after them runs in the
drawer once they are drawn; drawings that do not pickle, a drawer that died, or
drawings a broken pool (a worker killed while drawing) did not finish are drawn by the
process that holds them; a block that fails, or a run with every figure cached, kills the
drawer without waiting for its warm-up.
"""

from __future__ import annotations

import os
import signal
import time
from functools import partial
from pathlib import Path

import numpy as np
import psutil
import pytest
from matplotlib.figure import Figure

from pipeline.viz import figure_queue
from pipeline.viz.figure_cache import FigureCache
from pipeline.viz.figure_queue import FigureQueue, parallel_figures


def draw_line(y: np.ndarray, title: str) -> Figure:
    """A small figure of ``y`` (a module-level function: the cache keys its source)."""
    fig = Figure(figsize=(3, 2))
    ax = fig.subplots()
    ax.plot(y)
    ax.set_title(title)
    return fig


def draw_and_note_pid(note: Path, title: str, y: np.ndarray | None = None) -> Figure:
    """A figure that also writes the drawing process's id and its parent's to ``note``."""
    note.write_text(f"{os.getpid()} {os.getppid()}")
    return draw_line(np.arange(3.0) if y is None else y, title)


def draw_killing_once(mark: Path, title: str) -> Figure:
    """Kills the process drawing it, unless ``mark`` exists (it writes it first)."""
    if not mark.exists():
        mark.write_text("killed")
        os.kill(os.getpid(), signal.SIGKILL)
    return draw_line(np.arange(3.0), title)


def slow_warm_up() -> None:
    time.sleep(60)


def draw_broken(y: np.ndarray, title: str) -> Figure:
    raise ValueError(f"cannot draw {title}")


def _figures(save, tmp, n=5):
    return [save(tmp / f"f{i}.png", draw_line, np.arange(i + 3.0) ** 2, f"figure {i}")
            for i in range(n)]


def test_cache_copies_unchanged_and_redraws_changed_figures(tmp_path):
    cache = FigureCache(tmp_path / "cache")
    first = cache.save(tmp_path / "a.png", draw_line, np.arange(4.0), "a")
    assert len(list((tmp_path / "cache").glob("fig-*.png"))) == 1
    again = cache.save(tmp_path / "b.png", draw_line, np.arange(4.0), "a")
    assert again.read_bytes() == first.read_bytes()
    assert len(list((tmp_path / "cache").glob("fig-*.png"))) == 1  # a hit, nothing drawn
    cache.save(tmp_path / "c.png", draw_line, np.arange(4.0) + 1e-12, "a")
    assert len(list((tmp_path / "cache").glob("fig-*.png"))) == 2  # changed data: redrawn


@pytest.mark.parametrize("workers", [1, 2, 3])
def test_parallel_figures_equal_serial_ones(tmp_path, workers):
    serial = _figures(FigureCache().save, tmp_path / "serial")
    with parallel_figures(FigureCache(tmp_path / "cache"), workers) as figures:
        queued = _figures(figures.save, tmp_path / "parallel")
        assert not any(p.exists() for p in queued)  # drawn on leaving the block
    for s, q in zip(serial, queued, strict=True):
        assert q.read_bytes() == s.read_bytes(), q.name
    assert len(list((tmp_path / "cache").glob("fig-*.png"))) == 5


def test_a_failing_figure_is_named_and_the_others_are_written(tmp_path):
    queue = FigureQueue()
    cache = FigureCache(queue=queue)
    good = _figures(cache.save, tmp_path, n=3)
    cache.save(tmp_path / "broken.png", draw_broken, np.zeros(2), "the broken one")
    with pytest.raises(RuntimeError, match=r"broken\.png: ValueError: cannot draw the broken"):
        queue.draw_all(workers=2)
    assert all(p.is_file() for p in good)
    assert not (tmp_path / "broken.png").exists()
    assert not list(tmp_path.glob(".*"))  # no temporary files left behind


def _alive(process: psutil.Process) -> bool:
    try:
        return process.status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def _children() -> list[psutil.Process]:
    """The live child processes of this one (the drawer, or a pool's workers)."""
    return [c for c in psutil.Process().children() if _alive(c)]


def _gone(processes: list[psutil.Process]) -> bool:
    return not any(_alive(p) for p in processes)


@pytest.mark.parametrize("workers", [1, 2])
def test_prestarted_drawer_draws_the_same_figures(tmp_path, workers):
    serial = _figures(FigureCache().save, tmp_path / "serial")
    with parallel_figures(FigureCache(), workers, prestart=True) as figures:
        assert figures.queue.drawer is not None
        drawer = _children()
        assert len(drawer) == 1  # forked at the start
        queued = _figures(figures.save, tmp_path / "drawer")
        figures.queue.draw_all(workers)
        assert figures.queue.drawer is None  # used once
    assert _gone(drawer)
    for s, q in zip(serial, queued, strict=True):
        assert q.read_bytes() == s.read_bytes(), q.name


@pytest.mark.parametrize("workers", [1, 2])
def test_the_drawer_or_its_pool_draws_them_not_this_process(tmp_path, workers):
    """One worker: the drawer draws; more: a pool forked from the warmed-up drawer."""
    with parallel_figures(FigureCache(), workers, prestart=True) as figures:
        drawer = _children()[0].pid
        figures.save(tmp_path / "a.png", draw_and_note_pid, tmp_path / "a.txt", "a")
        figures.save(tmp_path / "b.png", draw_and_note_pid, tmp_path / "b.txt", "b")
    for note in ("a.txt", "b.txt"):
        pid, parent = map(int, (tmp_path / note).read_text().split())
        if workers == 1:
            assert (pid, parent) == (drawer, os.getpid())
        else:
            assert parent == drawer


def _wait_for(paths: list[Path], seconds: float = 60.0) -> None:
    deadline = time.monotonic() + seconds
    while not all(p.is_file() for p in paths) and time.monotonic() < deadline:
        time.sleep(0.01)


def test_sent_drawings_are_drawn_by_the_drawer_in_turn_and_the_rest_by_its_pool(tmp_path):
    """``send`` gives the drawer one drawing at a time (the others wait in ``handed``); it
    draws them itself, and the drawings queued after them go to the pool it forks; the
    files are the same as drawn in turn."""
    serial = [FigureCache().save(tmp_path / "serial" / f"{n}.png", draw_line,
                                 np.arange(3.0), n) for n in "abcd"]
    with parallel_figures(FigureCache(), 2, prestart=True) as figures:
        drawer = _children()[0].pid
        early = [figures.save(tmp_path / f"{n}.png", draw_and_note_pid, tmp_path / f"{n}.txt",
                              n) for n in "ab"]
        figures.queue.send()
        assert len(figures.queue.sent) == 1 and len(figures.queue.handed) == 1
        assert not figures.queue.jobs
        _wait_for(early)  # both drawn before the others are queued
        late = [figures.save(tmp_path / f"{n}.png", draw_and_note_pid, tmp_path / f"{n}.txt",
                             n) for n in "cd"]
    for n in "abcd":
        pid, parent = map(int, (tmp_path / f"{n}.txt").read_text().split())
        assert (pid, parent) == (drawer, os.getpid()) if n in "ab" else parent == drawer, n
    for s, q in zip(serial, early + late, strict=True):
        assert q.read_bytes() == s.read_bytes(), q.name


def note_pid_and_files(note: Path, folder: Path) -> None:
    """A preparation: writes its process's id and the PNG files in ``folder`` to ``note``."""
    note.write_text(f"{os.getpid()} " + " ".join(sorted(p.name for p in folder.glob("*.png"))))


def test_a_preparation_runs_in_the_drawer_after_the_drawings_handed_before(tmp_path):
    with parallel_figures(FigureCache(), 2, prestart=True) as figures:
        drawer = _children()[0].pid
        early = _figures(figures.save, tmp_path, n=2)
        figures.queue.send()
        figures.queue.prepare(partial(note_pid_and_files, tmp_path / "note.txt", tmp_path))
        _wait_for([tmp_path / "note.txt"])
    pid, *seen = (tmp_path / "note.txt").read_text().split()
    assert int(pid) == drawer and seen == [p.name for p in early]
    assert all(p.is_file() for p in early)


def test_a_failing_sent_drawing_is_named_and_one_that_does_not_pickle_drawn_here(tmp_path):
    def local(title):  # a local function does not pickle: drawn in this process
        return draw_and_note_pid(tmp_path / "pid.txt", title)

    with pytest.raises(RuntimeError, match=r"^figures not written: broken\.png: ValueError: "
                                           r"cannot draw the broken one$"):
        with parallel_figures(FigureCache(), 2, prestart=True) as figures:
            figures.save(tmp_path / "broken.png", draw_broken, np.zeros(2), "the broken one")
            here = figures.save(tmp_path / "local.png", local, "local")
            good = _figures(figures.save, tmp_path, n=2)
            figures.queue.send()
            _wait_for([good[0]])
    assert here.is_file() and all(p.is_file() for p in good)
    assert int((tmp_path / "pid.txt").read_text().split()[0]) == os.getpid()
    assert not (tmp_path / "broken.png").exists()


def test_drawings_that_do_not_pickle_are_drawn_here(tmp_path):
    scale = 2.0

    def local(y, title):  # a local function does not pickle: drawn in this process
        return draw_and_note_pid(tmp_path / "pid.txt", title, scale * y)

    with parallel_figures(FigureCache(), 2, prestart=True) as figures:
        drawer = _children()
        out = figures.save(tmp_path / "local.png", local, np.arange(3.0), "local")
        pooled = figures.save(tmp_path / "pooled.png", draw_line, np.arange(3.0), "pooled")
    assert int((tmp_path / "pid.txt").read_text().split()[0]) == os.getpid()
    assert _gone(drawer)  # the drawer could not take the batch: killed
    expected = FigureCache().save(tmp_path / "ref.png", draw_line, 2.0 * np.arange(3.0), "local")
    assert out.read_bytes() == expected.read_bytes() and pooled.is_file()


def test_a_dead_drawer_is_replaced_by_this_process(tmp_path):
    with parallel_figures(FigureCache(), 2, prestart=True) as figures:
        drawer = _children()[0]
        drawer.kill()
        # dead, but left for the pool to reap: reaping it here (psutil's wait) would take
        # the exit status the executor waits for, and its shutdown would spin for ever
        deadline = time.monotonic() + 30.0
        while _alive(drawer) and time.monotonic() < deadline:
            time.sleep(0.01)
        assert not _alive(drawer)
        queued = _figures(figures.save, tmp_path, n=3)
    assert all(p.is_file() for p in queued)
    assert not list(tmp_path.glob(".*"))


@pytest.mark.parametrize("prestart", [False, True])
def test_a_worker_killed_while_drawing_leaves_its_figures_to_its_parent(tmp_path, prestart):
    """A drawing that kills its worker (once: it leaves a mark first) breaks the pool; the
    process that forked the pool (this one, or the drawer) draws the figures not finished,
    the same as drawn in turn."""
    serial = _figures(FigureCache().save, tmp_path / "serial", n=4)
    with parallel_figures(FigureCache(), 2, prestart=prestart) as figures:
        queued = _figures(figures.save, tmp_path / "pool", n=4)
        killer = figures.save(tmp_path / "pool" / "killer.png", draw_killing_once,
                              tmp_path / "mark", "killer")
    assert (tmp_path / "mark").is_file() and killer.is_file()
    for s, q in zip(serial, queued, strict=True):
        assert q.read_bytes() == s.read_bytes(), q.name
    assert not list((tmp_path / "pool").glob(".*"))


def test_the_drawer_names_a_failing_figure(tmp_path):
    with pytest.raises(RuntimeError, match=r"^figures not written: broken\.png: ValueError: "
                                           r"cannot draw the broken one$"):
        with parallel_figures(FigureCache(), 2, prestart=True) as figures:
            good = _figures(figures.save, tmp_path, n=3)
            figures.save(tmp_path / "broken.png", draw_broken, np.zeros(2), "the broken one")
    assert all(p.is_file() for p in good)
    assert not (tmp_path / "broken.png").exists()


def test_a_failing_block_ends_the_drawer_without_drawing(tmp_path):
    with pytest.raises(KeyError):
        with parallel_figures(FigureCache(), 2, prestart=True) as figures:
            drawer = _children()
            queued = _figures(figures.save, tmp_path, n=2)
            raise KeyError("the run failed")
    assert drawer and _gone(drawer)
    assert not any(p.exists() for p in queued)


def test_a_run_with_every_figure_cached_does_not_wait_for_the_drawer(tmp_path, monkeypatch):
    """The warm-up made to take 60 s: leaving the block kills the drawer instead of
    waiting for it."""
    cache = FigureCache(tmp_path / "cache")
    _figures(cache.save, tmp_path / "first", n=2)
    monkeypatch.setattr(figure_queue, "warm_up", slow_warm_up)
    start = time.monotonic()
    with parallel_figures(cache, 2, prestart=True) as figures:
        drawer = _children()
        copied = _figures(figures.save, tmp_path / "again", n=2)  # both from the cache
        assert all(p.is_file() for p in copied) and not figures.queue.jobs
        figures.queue.draw_all()
        assert figures.queue.drawer is None
    assert time.monotonic() - start < 30 and drawer and _gone(drawer)
