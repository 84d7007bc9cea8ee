"""Figures of a run: cached by what they show, drawn side by side in forked processes.

A cached figure is copied, not redrawn; a changed argument redraws it. Figures queued
for parallel drawing come out byte-identical to those drawn in turn, and one figure
whose drawing fails is named in one error while the others are still written. The
early-started drawer gives the same files; drawings that do not pickle, or a drawer that
died, are drawn in this process instead; a block that fails ends the drawer.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from pipeline.viz.figure_cache import FigureCache
from pipeline.viz.figure_queue import FigureQueue, parallel_figures


def draw_line(y: np.ndarray, title: str) -> Figure:
    """A small figure of ``y`` (a module-level function: the cache keys its source)."""
    fig = Figure(figsize=(3, 2))
    ax = fig.subplots()
    ax.plot(y)
    ax.set_title(title)
    return fig


def draw_and_note_pid(note: Path, title: str) -> Figure:
    """A figure that also writes the drawing process's id to ``note``."""
    note.write_text(str(os.getpid()))
    return draw_line(np.arange(3.0), title)


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


@pytest.mark.parametrize("workers", [1, 2])
def test_prestarted_drawer_draws_the_same_figures(tmp_path, workers):
    serial = _figures(FigureCache().save, tmp_path / "serial")
    with parallel_figures(FigureCache(), workers, prestart=True) as figures:
        drawer = figures.queue.drawer
        assert drawer is not None and drawer.process.is_alive()
        queued = _figures(figures.save, tmp_path / "drawer")
        figures.queue.draw_all(workers)
        assert figures.queue.drawer is None  # used once
    assert not drawer.process.is_alive() and drawer.process.exitcode == 0
    for s, q in zip(serial, queued, strict=True):
        assert q.read_bytes() == s.read_bytes(), q.name


def test_the_drawer_draws_them_not_this_process(tmp_path):
    with parallel_figures(FigureCache(), 1, prestart=True) as figures:
        drawer_pid = figures.queue.drawer.process.pid
        figures.save(tmp_path / "a.png", draw_and_note_pid, tmp_path / "pid.txt", "a")
    assert int((tmp_path / "pid.txt").read_text()) == drawer_pid != os.getpid()


def test_drawings_that_do_not_pickle_are_drawn_here(tmp_path):
    scale = 2.0
    with parallel_figures(FigureCache(), 2, prestart=True) as figures:
        drawer = figures.queue.drawer
        # a local function does not pickle: the queue draws it in this process
        out = figures.save(tmp_path / "local.png", lambda y, title: draw_line(scale * y, title),
                           np.arange(3.0), "local")
    assert out.is_file() and not drawer.process.is_alive()
    assert drawer.process.exitcode == -9  # never sent anything: killed, not waited for
    expected = FigureCache().save(tmp_path / "ref.png", draw_line, 2.0 * np.arange(3.0), "local")
    assert out.read_bytes() == expected.read_bytes()


def test_a_dead_drawer_is_replaced_by_this_process(tmp_path):
    with parallel_figures(FigureCache(), 2, prestart=True) as figures:
        drawer = figures.queue.drawer
        os.kill(drawer.process.pid, signal.SIGKILL)
        drawer.process.join()
        queued = _figures(figures.save, tmp_path, n=3)
    assert all(p.is_file() for p in queued)
    assert not list(tmp_path.glob(".*"))


def test_the_drawer_names_a_failing_figure(tmp_path):
    with pytest.raises(RuntimeError, match=r"broken\.png: ValueError: cannot draw the broken"):
        with parallel_figures(FigureCache(), 2, prestart=True) as figures:
            good = _figures(figures.save, tmp_path, n=3)
            figures.save(tmp_path / "broken.png", draw_broken, np.zeros(2), "the broken one")
    assert all(p.is_file() for p in good)
    assert not (tmp_path / "broken.png").exists()


def test_a_failing_block_ends_the_drawer_without_drawing(tmp_path):
    with pytest.raises(KeyError):
        with parallel_figures(FigureCache(), 2, prestart=True) as figures:
            drawer = figures.queue.drawer
            queued = _figures(figures.save, tmp_path, n=2)
            raise KeyError("the run failed")
    assert not drawer.process.is_alive()
    assert not any(p.exists() for p in queued)


def test_a_run_with_every_figure_cached_does_not_wait_for_the_drawer(tmp_path):
    cache = FigureCache(tmp_path / "cache")
    _figures(cache.save, tmp_path / "first", n=2)
    with parallel_figures(cache, 2, prestart=True) as figures:
        drawer = figures.queue.drawer
        copied = _figures(figures.save, tmp_path / "again", n=2)  # both from the cache
        assert all(p.is_file() for p in copied) and not figures.queue.jobs
        figures.queue.draw_all()
        assert figures.queue.drawer is None
    assert not drawer.process.is_alive() and drawer.process.exitcode == -9  # killed, not used
