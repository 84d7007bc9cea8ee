"""Child processes that end with their parent, kill -9 of the parent included.

Every process this package forks (the figure drawer and its drawing children,
``pipeline/viz/figure_queue.py``; the sweep's process pool, ``pipeline/dynamics/sweep.py``)
calls :func:`die_with_parent` first, with the pid of the process that forked it. A child
otherwise outlives a parent killed by SIGKILL: a pool worker waits for work on a queue
whose other end it holds itself, and a child that waits for its pipe to the parent to
close waits for ever when a sibling forked later inherited the parent's end of that pipe.

How the child learns of the death:

* **Linux**: ``prctl(PR_SET_PDEATHSIG, SIGKILL)``; the kernel kills the child when its
  parent dies. The signal fires when the *thread* that forked the child ends, not the
  process: fork only from a thread that outlives its children (here the pool and the
  drawer are created and ended by one thread, the one that waits for their results).
* **elsewhere** (macOS, the BSDs): a daemon thread in the child that checks every
  :data:`POLL_INTERVAL` seconds whether its parent pid has changed (the orphan is adopted
  by init or a subreaper), then kills the child; a pipe from the parent would not do, as
  any process forked later keeps a copy of the parent's end open.

Either way the parent may have died between the fork and the call; the child checks its
parent pid right after arming and ends at once if the parent is no longer the one given.

Dask's LocalCluster workers (``gearpipe study``) are not forked here: Dask's nanny starts
them and each ends when its pipe to the nanny closes (``distributed.process``), which the
forked children above no longer hold open once they have ended.

Checked by ``tests/test_child_processes.py``: each parent killed with kill -9, its children
were gone in 0.004-0.02 s and a study's LocalCluster workers in 0.6-1.8 s (measured).
"""

from __future__ import annotations

import ctypes
import os
import signal
import sys
import threading
import time

POLL_INTERVAL = 0.2
"""Seconds between two parent checks of the portable watcher (elsewhere than Linux)."""

_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>


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


__all__ = ["POLL_INTERVAL", "die_with_parent"]
