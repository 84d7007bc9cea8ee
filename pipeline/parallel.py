"""The process pool for parallel work inside one command, and children that end with it.

One kind of pool runs every piece of parallel work a command does in its own process
tree: the chunks of a speed sweep (:func:`pipeline.dynamics.sweep.map_chunks`) and the
figures of a run (:mod:`pipeline.viz.figure_queue`). :func:`process_pool` is a
``concurrent.futures.ProcessPoolExecutor`` whose workers

* are **forked**, so they start in milliseconds with every module this process has
  imported, and a function defined in ``__main__`` can be sent by name; ``fork`` is POSIX
  only (:func:`can_fork`): where it is missing the callers compute in this process;
* use **one BLAS thread** each (:func:`one_blas_thread`): the pool already uses every core;
* **end with this process**, kill -9 included (:func:`die_with_parent`).

Python forks the workers of a ``fork`` pool all at once, in the thread that submits the
first work (or :func:`start_workers`). A worker may fork a pool of its own (the figure
drawer forks its drawing pool once it has imported matplotlib, so that every drawing
process starts with it); each generation ends with the one that forked it. The pool is
ended by :meth:`~concurrent.futures.Executor.shutdown` (after the running work), or at
once by :func:`kill_pool`. It keeps SIGPIPE ignored while it is given work, as Python
does but Gmsh undoes: a dead worker then breaks the pool (``BrokenProcessPool``) rather
than this process (``_Pool``). Design studies (``gearpipe study``) run on
Dask's LocalCluster instead: the product's cluster for studies, whose workers Dask's
nanny starts and ends (``distributed.process``).

Why a child needs :func:`die_with_parent`: a pool worker waits for work on a queue whose
other end it holds itself, so a worker whose parent was killed by SIGKILL would wait for
ever. How it learns of the death:

* **Linux**: ``prctl(PR_SET_PDEATHSIG, SIGKILL)``; the kernel kills the child when its
  parent dies. The signal fires when the *thread* that forked the child ends, not the
  process: fork only from a thread that outlives its children (the pools here are
  created, used and ended by one thread, the one that waits for their results).
* **elsewhere** (macOS, the BSDs): a daemon thread in the child that checks every
  :data:`POLL_INTERVAL` seconds whether its parent pid has changed (the orphan is adopted
  by init or a subreaper), then kills the child; a pipe from the parent would not do, as
  any process forked later keeps a copy of the parent's end open.

Either way the parent may have died between the fork and the call; the child checks its
parent pid right after arming and ends at once if the parent is no longer the one given.

Checked by ``tests/test_child_processes.py``: each parent killed with kill -9, its children
were gone in 0.004-0.02 s and a study's LocalCluster workers in 0.6-1.8 s (measured).
"""

from __future__ import annotations

import ctypes
import multiprocessing
import os
import signal
import sys
import threading
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from typing import Any

POLL_INTERVAL = 0.2
"""Seconds between two parent checks of the portable watcher (elsewhere than Linux)."""

_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


def can_fork() -> bool:
    """Whether this platform can fork (:func:`process_pool` needs it)."""
    return "fork" in multiprocessing.get_all_start_methods()


def process_pool(workers: int | None = None, warm_up: Callable[[], None] | None = None
                 ) -> ProcessPoolExecutor:
    """A process pool: forked workers, one BLAS thread each, ending with this process.

    The workers are forked when the first work is submitted (or :func:`start_workers`), by
    the submitting thread; they end when that thread ends (Linux's parent-death signal),
    so it must be the thread that waits for the results and shuts the pool down.

    Parameters
    ----------
    workers : number of processes (default: CPU count).
    warm_up : called first in every worker (imports the work needs, for example); its
        exceptions are ignored (the work reports its own).
    """
    return _Pool(
        max_workers=workers or os.cpu_count() or 1,
        mp_context=multiprocessing.get_context("fork"),
        initializer=_start_worker,
        initargs=(os.getpid(), warm_up),
    )


def start_workers(pool: ProcessPoolExecutor) -> None:
    """Fork the workers of ``pool`` now (a fork pool forks them all with its first work)."""
    pool.submit(os.getpid)


class _Pool(ProcessPoolExecutor):
    """A ``ProcessPoolExecutor`` that keeps SIGPIPE ignored while it is given work.

    Python ignores SIGPIPE, but ``gmsh.initialize()`` restores the default action (end
    the process) behind Python's back (measured: the SIGPIPE bit of ``SigIgn`` in
    ``/proc/self/status`` is cleared after it, while ``signal.getsignal`` still says
    ignored). When a worker dies, the executor closes its end of the work queue and
    flushes the work not yet taken into it: with the default action that write into a
    pipe nobody reads ends this process (exit status -13, ``tests/test_child_processes.py``)
    instead of failing the pending work with ``BrokenProcessPool``.
    """

    def submit(self, fn, /, *args, **kwargs):
        """As :meth:`ProcessPoolExecutor.submit`, SIGPIPE ignored first (main thread only:
        Python sets signal actions there)."""
        if threading.current_thread() is threading.main_thread() and hasattr(signal,
                                                                              "SIGPIPE"):
            signal.signal(signal.SIGPIPE, signal.SIG_IGN)
        return super().submit(fn, *args, **kwargs)


def kill_pool(pool: ProcessPoolExecutor) -> None:
    """End ``pool`` now: its workers are killed, whatever they are doing, and its pending
    work cancelled (for a pool whose results are no longer wanted: a worker may be busy
    for a while, and :meth:`~concurrent.futures.Executor.shutdown` would wait for it).
    Idempotent."""
    # the executor keeps its worker processes in a private mapping (no public way to kill
    # them before Python 3.14's terminate_workers); it is None once the pool is shut down
    workers = list((getattr(pool, "_processes", None) or {}).values())
    for worker in workers:
        worker.kill()
    pool.shutdown(wait=True, cancel_futures=True)


def one_blas_thread() -> Any:
    """Context: one BLAS thread in this process (each pool worker runs with one).

    The matrices of the dynamics are small (<= a few hundred rows); a multi-threaded BLAS
    gains nothing on them and, on cores shared with other jobs, its spinning threads made
    a serial 3-point sweep of the 6-DOF pair 19x slower (15.4 s against 0.82 s, measured).
    """
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=1)


def _start_worker(parent_pid: int, warm_up: Callable[[], None] | None) -> None:
    """Pool worker initializer: end with the parent, one BLAS thread, then ``warm_up``."""
    die_with_parent(parent_pid)
    one_blas_thread()
    if warm_up is not None:
        try:
            warm_up()
        except Exception:  # noqa: BLE001 - a failing initializer would break the pool
            pass


def die_with_parent(parent_pid: int) -> None:
    """End this process with SIGKILL when the process ``parent_pid`` ends.

    Call it first in a forked child, with the parent's pid taken before the fork
    (``os.getpid()`` in the parent).

    Parameters
    ----------
    parent_pid : pid of the process that forked this one.
    """
    if not _arm_parent_death_signal():
        _start_parent_watcher(parent_pid, POLL_INTERVAL)
    if os.getppid() != parent_pid:  # the parent died before the signal was armed
        _end_now()


def _arm_parent_death_signal() -> bool:
    """``prctl(PR_SET_PDEATHSIG, SIGKILL)`` on Linux; whether it is armed."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):  # no C library symbols to call
        return False
    # int prctl(int option, unsigned long arg2, ...): full-width arguments, as the kernel
    # reads them
    prctl.argtypes = [ctypes.c_int] + [ctypes.c_ulong] * 4
    prctl.restype = ctypes.c_int
    return prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0


def _start_parent_watcher(parent_pid: int, interval: float) -> threading.Thread:
    """A daemon thread that ends this process once its parent pid is not ``parent_pid``."""

    def watch() -> None:
        while os.getppid() == parent_pid:
            time.sleep(interval)
        _end_now()

    thread = threading.Thread(target=watch, name="parent-watcher", daemon=True)
    thread.start()
    return thread


def _end_now() -> None:
    """End this process as the parent-death signal would: no clean-up, no output."""
    if hasattr(signal, "SIGKILL"):
        os.kill(os.getpid(), signal.SIGKILL)
    os._exit(1)


__all__ = ["POLL_INTERVAL", "can_fork", "die_with_parent", "kill_pool", "one_blas_thread",
           "process_pool", "start_workers"]
