"""No child process outlives its parent, kill -9 of the parent included.

``pipeline.parallel.die_with_parent`` is checked on its own (a parent killed with
SIGKILL, a parent already gone before the child arms it), by Linux's parent-death signal
and by the portable watcher thread. Then each place that has children is killed while they
run, first in a small script whose children sleep for 60 s (the sweep's pool; the drawing
pool of a process, of the drawer, and of a killed drawer; a drawing pool one of whose
workers is killed, and any pool after ``gmsh.initialize()``, which sets SIGPIPE back to
its default action), then as ``gearpipe`` runs: ``gearpipe run`` during the speed sweep
(the pool workers and the early-started figure drawer), ``gearpipe run`` while the
drawer's pool draws, the drawer itself while its pool draws (slow: the run then draws
the figures itself and must succeed), and ``gearpipe study`` with its two LocalCluster
workers. Every child must be gone within :data:`GONE_WITHIN`. Without
``die_with_parent`` (measured with the hand-written pipes the pools replaced), every
case but the study and the slow one fails: the pool workers and the drawer of a run
killed in its sweep were still there 5 s later (they wait for ever), the drawing
children of a run killed while drawing 5.6 s later. Processes forked by a run carry the
run's command line, so a search for the test's output folder in every command line
finds them all, grandchildren included, once the parent is gone.
"""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import psutil
import pytest
from gearsets import SMALL

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg",
       "PYVISTA_OFF_SCREEN": "true", "OMP_NUM_THREADS": "1"}
GONE_WITHIN = 2.0  # s: measured 0.004-0.021 s on Linux; room for a loaded machine
# 1000 sweep points: the sweep runs in the process pool (50 or more) for about 0.5 s
SWEEP = SMALL.replace("points_coarse = 12", "points_coarse = 1000")

pytestmark = pytest.mark.skipif(not hasattr(os, "fork") or not hasattr(signal, "SIGKILL"),
                                reason="needs fork and SIGKILL")


def _alive(process: psutil.Process) -> bool:
    try:
        return process.status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def _wait(condition: Callable[[], bool], timeout: float) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(0.01)
    return condition()


def _marked(marker: str) -> list[psutil.Process]:
    """Live processes whose command line contains ``marker``, this one excepted."""
    found = []
    for process in psutil.process_iter():
        try:
            if process.pid != os.getpid() and marker in " ".join(process.cmdline()):
                found.append(process)
        except psutil.Error:  # ended or not ours to read
            continue
    return [p for p in found if _alive(p)]


def _kill_all(processes: list[psutil.Process]) -> None:
    for process in processes:
        try:
            process.kill()
        except psutil.Error:
            pass


def _gearpipe(tmp_path: Path, *args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "pipeline.cli", *args], env=ENV, cwd=tmp_path,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def _forked_children(process: psutil.Process) -> list[psutil.Process]:
    """The live children that were forked by ``process`` (they share its command line)."""
    try:
        line = process.cmdline()
        return [c for c in process.children() if _alive(c) and c.cmdline() == line]
    except psutil.Error:
        return []


def _run(tmp_path: Path) -> tuple[subprocess.Popen, str]:
    """``gearpipe run`` of the sweep config; its marker (the output folder)."""
    cfg = tmp_path / "sweep.toml"
    cfg.write_text(SWEEP, encoding="utf-8")
    out = tmp_path / "out"
    return _gearpipe(tmp_path, "run", str(cfg), "--out", str(out), "--cache-dir",
                     str(tmp_path / "cache"), "--json"), str(out)


# --- the helper itself --------------------------------------------------------------------

# Forks a child that arms die_with_parent and sleeps; prints the child's pid; sleeps.
MIDDLE = r"""
import os, sys, time
import pipeline.parallel as cp
if sys.argv[1] == "watcher":
    cp._arm_parent_death_signal = lambda: False  # the portable path, as elsewhere than Linux
else:  # the signal alone: no watcher to fall back on
    cp._start_parent_watcher = lambda *args: sys.exit("parent-death signal not armed")
parent = os.getpid()
pid = os.fork()
if pid == 0:
    cp.die_with_parent(parent)
    time.sleep(60)
    os._exit(0)
print(pid, flush=True)
time.sleep(60)
"""

PATHS = ["signal", "watcher"]


@pytest.mark.parametrize("path", PATHS)
def test_a_child_ends_when_its_parent_is_killed(path):
    if path == "signal" and not sys.platform.startswith("linux"):
        pytest.skip("the parent-death signal is Linux only")
    middle = subprocess.Popen([sys.executable, "-c", MIDDLE, path], env=ENV,
                              stdout=subprocess.PIPE, text=True)
    child = None
    try:
        child = psutil.Process(int(middle.stdout.readline()))
        time.sleep(0.5)  # the child has armed (and, as watcher, polled a few times)
        assert _alive(child)  # it lives as long as its parent does
        middle.kill()
        middle.wait(timeout=10)
        assert _wait(lambda: not _alive(child), GONE_WITHIN)
    finally:
        middle.kill()
        middle.wait(timeout=10)
        _kill_all([child] if child else [])


@pytest.mark.parametrize("path", PATHS)
def test_a_child_whose_parent_is_already_gone_ends_at_once(path):
    """The parent given is not this process's parent (as when the parent died between the
    fork and the call): the process kills itself before going on."""
    if path == "signal" and not sys.platform.startswith("linux"):
        pytest.skip("the parent-death signal is Linux only")
    script = MIDDLE.split("parent = os.getpid()")[0] + (
        "cp.die_with_parent(os.getppid() + 1_000_000)\nprint('went on')\n")
    done = subprocess.run([sys.executable, "-c", script, path], env=ENV, capture_output=True,
                          text=True, timeout=60, check=False)
    assert done.returncode == -signal.SIGKILL and done.stdout == ""


# --- every place that has children, on its own ---------------------------------------------

# A sweep whose two pool workers sleep for 60 s.
POOL = r"""
import time
from pipeline.dynamics.sweep import map_chunks
from pipeline.parallel import process_pool
map_chunks(time.sleep, [60.0, 60.0], process_pool(2))
"""

# Three figures that take 60 s each, drawn by a pool of three forked here, or by the
# early-started drawer and the pool of three it forks (the pools pickle __main__.slow by
# name; the forked workers have it).
FIGURES = r"""
import sys, time
from pipeline.viz.figure_queue import FigureQueue

def slow():
    time.sleep(60)

queue = FigureQueue()
if sys.argv[1] == "drawer":
    queue.start()
for i in range(3):
    queue.add(f"figure{i}.png", slow)
queue.draw_all(workers=3)
"""


def _kill_and_watch(victim: psutil.Process) -> list[psutil.Process]:
    """Stop ``victim`` (it starts no more processes), list its descendants, kill it."""
    victim.suspend()
    descendants = [c for c in victim.children(recursive=True) if _alive(c)]
    victim.kill()
    return descendants


def _script(text: str, *args: str, cwd: Path) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", text, *args], env=ENV, cwd=cwd,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def test_sweep_pool_workers_end_with_their_parent(tmp_path):
    proc, watched = _script(POOL, cwd=tmp_path), []
    try:
        parent = psutil.Process(proc.pid)
        assert _wait(lambda: len(_forked_children(parent)) == 2, 60), "no pool workers seen"
        watched = _kill_and_watch(parent)
        assert len(watched) == 2
        assert _wait(lambda: not any(_alive(c) for c in watched), GONE_WITHIN), watched
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(watched)


@pytest.mark.parametrize("where", ["here", "drawer"])
def test_drawing_children_end_with_their_parent(tmp_path, where):
    """Killed while drawing: here, its pool's three workers end; with the drawer, the
    drawer and its pool's three workers end."""
    proc, watched = _script(FIGURES, where, cwd=tmp_path), []
    try:
        parent = psutil.Process(proc.pid)
        drawers = 4 if where == "drawer" else 3  # the processes it has, grandchildren included
        drawing = lambda: len([c for c in parent.children(recursive=True) if _alive(c)]) == drawers  # noqa: E731, E501
        assert _wait(drawing, 60), "no drawing children seen"
        watched = _kill_and_watch(parent)
        assert len(watched) == drawers
        assert _wait(lambda: not any(_alive(c) for c in watched), GONE_WITHIN), watched
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(watched)


def test_drawing_children_end_with_a_killed_drawer(tmp_path):
    proc, watched = _script(FIGURES, "drawer", cwd=tmp_path), []
    try:
        parent = psutil.Process(proc.pid)
        with_children = lambda: [d for d in _forked_children(parent) if len(_forked_children(d)) == 3]  # noqa: E731, E501
        assert _wait(lambda: bool(with_children()), 60), "no drawing children seen"
        watched = _kill_and_watch(with_children()[0])
        assert len(watched) == 3
        assert _wait(lambda: not any(_alive(c) for c in watched), GONE_WITHIN), watched
        assert _alive(parent)  # the process that started the drawer goes on (drawing itself)
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(watched)


def test_a_killed_pool_worker_takes_the_others_with_it(tmp_path):
    """One of the three drawing workers killed: the pool ends the other two, and the
    process that started it goes on (drawing the figures itself)."""
    proc, watched = _script(FIGURES, "here", cwd=tmp_path), []
    try:
        parent = psutil.Process(proc.pid)
        assert _wait(lambda: len(_forked_children(parent)) == 3, 60), "no pool workers seen"
        watched = _forked_children(parent)
        watched[0].kill()
        assert _wait(lambda: not any(_alive(c) for c in watched), GONE_WITHIN), watched
        assert _alive(parent)
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(watched)


# Two workers, each given a 60 s sleep with more waiting, after gmsh.initialize() has set
# SIGPIPE back to its default action; each piece of work carries 1 MB, so that the one
# queued next is still being written into the work queue's pipe (64 kB) when a worker
# dies. Prints what the pending work came to.
BROKEN = r"""
import time
import gmsh
from concurrent.futures import wait
from pipeline.parallel import process_pool

def hold(seconds, payload):
    time.sleep(seconds)

gmsh.initialize()
pool = process_pool(2)
futures = [pool.submit(hold, 60.0, bytes(1_000_000)) for _ in range(8)]
print("submitted", flush=True)
wait(futures)
print(sorted({type(f.exception()).__name__ for f in futures}), flush=True)
pool.shutdown()
"""


def test_a_killed_pool_worker_breaks_the_pool_not_its_parent(tmp_path):
    """One worker killed while work is pending, with SIGPIPE at the default action that
    gmsh.initialize() leaves: the pending work fails with BrokenProcessPool, the other
    worker ends, and the parent goes on (without the pool's guard it died of SIGPIPE,
    exit status -13, as the executor wrote the queued work into a pipe nobody reads)."""
    proc = subprocess.Popen([sys.executable, "-c", BROKEN], env=ENV, cwd=tmp_path,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    watched: list[psutil.Process] = []
    try:
        assert proc.stdout.readline() == "submitted\n"
        parent = psutil.Process(proc.pid)
        assert _wait(lambda: len(_forked_children(parent)) == 2, 60), "no pool workers seen"
        watched = _forked_children(parent)
        watched[0].kill()
        assert _wait(lambda: not any(_alive(c) for c in watched), GONE_WITHIN), watched
        assert proc.wait(timeout=30) == 0
        assert proc.stdout.read() == "['BrokenProcessPool']\n"
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(watched)


# --- gearpipe run and gearpipe study -----------------------------------------------------------

def _kill_run_when(tmp_path, seen, what: str) -> None:
    """Start ``gearpipe run``, wait until ``seen(parent)`` holds, stop the run where it is,
    kill -9 it and require every process it started gone within ``GONE_WITHIN``."""
    proc, marker = _run(tmp_path)
    try:
        parent = psutil.Process(proc.pid)
        assert _wait(lambda: seen(parent) or proc.poll() is not None, 120) and seen(parent), (
            f"no {what} seen")
        parent.suspend()  # it forks nothing more until the kill; its children go on
        assert seen(parent)
        parent.kill()
        proc.wait(timeout=10)
        assert _wait(lambda: not _marked(marker), GONE_WITHIN), _marked(marker)
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(_marked(marker))


def test_run_killed_in_its_sweep_leaves_no_process(tmp_path):
    """kill -9 of ``gearpipe run`` while its pool computes the sweep: the drawer (forked at
    the start) and the pool workers end with it."""
    # the drawer and at least one pool worker (the pool has one per core)
    _kill_run_when(tmp_path, lambda parent: len(_forked_children(parent)) >= 2, "pool")


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one core: the drawer forks no child")
def test_run_killed_while_its_drawer_draws_leaves_no_process(tmp_path):
    """kill -9 of ``gearpipe run`` while the drawer and its forked children draw."""
    _kill_run_when(tmp_path, lambda parent: any(_forked_children(c)
                                                for c in _forked_children(parent)),
                   "drawing child")


@pytest.mark.slow  # 9-11 s: the run goes on to its end
@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="one core: the drawer forks no child")
def test_drawer_killed_while_drawing_ends_its_children_and_the_run_finishes(tmp_path):
    """kill -9 of the drawer while its children draw: they end with it, and the run draws
    the figures itself and succeeds."""
    proc, marker = _run(tmp_path)
    children: list[psutil.Process] = []
    try:
        parent = psutil.Process(proc.pid)

        def drawer_with_children() -> bool:
            for drawer in _forked_children(parent):
                if _forked_children(drawer):
                    children[:] = [drawer]
                    return True
            return False

        assert _wait(lambda: drawer_with_children() or proc.poll() is not None, 120), (
            "no drawing child seen")
        assert children, "the run ended before its drawer forked"
        drawer = children[0]
        drawer.suspend()  # it forks no more children while they are listed
        children[:] = [drawer, *_forked_children(drawer)]
        drawer.kill()
        assert _wait(lambda: not any(_alive(c) for c in children), GONE_WITHIN), children
        assert proc.wait(timeout=300) == 0
        out = tmp_path / "out"
        listed = json.loads((out / "run.json").read_text(encoding="utf-8"))["outputs"]
        pngs = [name for name in listed if name.endswith(".png")]
        assert {"sweep.png", "mode_shapes.png", "mesh_stiffness.png"} <= set(pngs)
        assert all((out / name).stat().st_size > 1000 for name in pngs)
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(children + _marked(marker))


STUDY = """\
name = "torque"
base = "sweep.toml"
[[axes]]
keys = ["operation.torque_Nm"]
range = [100.0, 400.0]
points = 200
[kpis]
names = ["te_peak_to_peak_um", "mesh_stiffness_mean_N_per_um"]
[execution]
batch_points = 2
"""


def test_study_killed_with_its_local_cluster_leaves_no_process(tmp_path):
    """kill -9 of ``gearpipe study`` while its two LocalCluster workers compute: they (and
    multiprocessing's resource tracker) end with it."""
    (tmp_path / "sweep.toml").write_text(SMALL, encoding="utf-8")
    (tmp_path / "study.toml").write_text(STUDY, encoding="utf-8")
    proc = _gearpipe(tmp_path, "study", "study.toml", "--out", str(tmp_path / "out"),
                     "--workers", "2")
    children: list[psutil.Process] = []
    try:
        parent = psutil.Process(proc.pid)

        def workers() -> bool:
            try:
                children[:] = [c for c in parent.children(recursive=True) if _alive(c)]
                lines = [" ".join(c.cmdline()) for c in children]
            except psutil.Error:
                return False
            return sum("--multiprocessing-fork" in line for line in lines) >= 2

        assert _wait(lambda: workers() or proc.poll() is not None, 120) and workers(), (
            "no LocalCluster workers seen")
        parent.suspend()  # it starts no more processes while they are listed
        children[:] = [c for c in parent.children(recursive=True) if _alive(c)]
        parent.kill()
        proc.wait(timeout=10)
        assert _wait(lambda: not any(_alive(c) for c in children), 10.0), children
    finally:
        proc.kill()
        proc.wait(timeout=10)
        _kill_all(children)
