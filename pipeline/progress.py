"""Progress reporting for long runs on stderr: :func:`progress` (iterations, wraps tqdm; silent
when not a terminal or disabled) and :class:`Steps` (named steps, their wall times).
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from typing import TypeVar

T = TypeVar("T")


def progress(
    items: Iterable[T], desc: str, total: int | None = None, enabled: bool = True
) -> Iterator[T]:
    """Iterate over ``items`` showing a progress bar on stderr.

    The bar appears only when ``enabled`` and stderr is a terminal, or when the
    run is long enough for tqdm to print (``mininterval``); it never writes to
    stdout, so ``--json`` output stays clean.
    """
    if not enabled:
        yield from items
        return
    from tqdm import tqdm

    yield from tqdm(items, desc=desc, total=total, file=sys.stderr, mininterval=1.0, leave=False)


class Steps:
    """Times named steps of a long computation and reports the slow ones on stderr.

    ``with steps.step("factorise"):`` announces the step once it has run for ``after``
    seconds (a timer thread; a C call that holds the GIL delays the line to its end)
    and, if it took longer than that, prints its wall time when it ends; every step's
    time is added to :attr:`timings` (s), so the caller can keep a breakdown.
    :meth:`advance` reports the progress of a counted step (blocks of solves), at most
    every ``every`` seconds.
    Nothing is printed when ``enabled`` is False; nothing is ever written to stdout.

    Parameters
    ----------
    label : prefix of every line, e.g. ``"fe3d gear"``.
    enabled : print at all.
    after : seconds a step must run before it is reported.
    every : seconds between two progress lines of one step.
    """

    def __init__(self, label: str, enabled: bool = True, after: float = 1.0,
                 every: float = 5.0) -> None:
        self.label = label
        self.enabled = enabled
        self.after = after
        self.every = every
        self.timings: dict[str, float] = {}
        self._started: dict[str, float] = {}
        self._said: dict[str, float] = {}

    def _say(self, text: str) -> None:
        if self.enabled:
            print(f"{self.label}: {text}", file=sys.stderr, flush=True)

    @contextmanager
    def step(self, name: str, announce: bool = False) -> Iterator[None]:
        """Time the ``with`` block as step ``name`` (docstring of :class:`Steps`);
        ``announce`` prints its start line at once (for a long C call that holds the GIL,
        which would hold the timer's line back until it returns)."""
        t0 = time.perf_counter()
        self._started[name] = self._said[name] = t0
        timer = threading.Timer(self.after, self._say, (f"{name} ...",))
        timer.daemon = True
        if announce:
            self._say(f"{name} ...")
        elif self.enabled:
            timer.start()
        try:
            yield
        finally:
            timer.cancel()
            dt = time.perf_counter() - t0
            self._started.pop(name, None)
            self.timings[name] = self.timings.get(name, 0.0) + dt
            if dt >= self.after:
                self._say(f"{name} done in {dt:.1f} s")

    def advance(self, name: str, done: int, total: int, unit: str = "") -> None:
        """Report ``done`` of ``total`` (``unit``) of the running step ``name`` once it has
        run for ``after`` seconds, then every ``every`` seconds."""
        t0, now = self._started.get(name), time.perf_counter()
        if t0 is not None and now - t0 >= self.after and now - self._said[name] >= self.every:
            self._said[name] = now
            self._say(f"{name} {done}/{total}{' ' + unit if unit else ''} ({now - t0:.0f} s)")
