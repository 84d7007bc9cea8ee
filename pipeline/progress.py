"""Progress reporting for long runs on stderr: :func:`progress` (iterations, wraps tqdm) and
:class:`Steps` (named steps, their wall times).

Both say nothing about work that ends within :data:`REPORT_AFTER` seconds (but a step its
caller announces at once): a run of short steps prints only its commands' own lines, and a
bar or step line appears only where the user would otherwise wait in silence.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from typing import TypeVar

T = TypeVar("T")

REPORT_AFTER = 1.0
"""Seconds a loop or step must run before it is reported on stderr."""


def progress(
    items: Iterable[T], desc: str, total: int | None = None, enabled: bool = True, *,
    after: float = REPORT_AFTER,
) -> Iterator[T]:
    """Iterate over ``items``, with a progress bar on stderr once the loop has run ``after``
    seconds.

    A loop that ends sooner prints nothing (tqdm's ``delay``); a longer one shows its bar
    from the first item that ends after ``after`` seconds, redrawn at most every ``after``
    seconds, and clears it at the end. When stderr is not a terminal (captured output) there
    is no bar, only one whole line at the end of a loop that took ``after`` seconds. Nothing
    is printed when ``enabled`` is False, and nothing is ever written to stdout (``--json``
    output stays clean).

    Parameters
    ----------
    items : what to iterate over.
    desc : label of the bar.
    total : number of items, when ``items`` has no ``len``.
    enabled : show the bar at all.
    after : seconds before the bar appears, > 0.
    """
    if not enabled:
        yield from items
        return
    if not sys.stderr.isatty():  # captured: no redrawn bar, one whole line at the end
        t0, n = time.perf_counter(), 0
        for item in items:
            n += 1
            yield item
        dt = time.perf_counter() - t0
        if dt >= after:
            print(f"{desc}: {n} done in {dt:.1f} s", file=sys.stderr, flush=True)
        return
    from tqdm import tqdm

    yield from tqdm(items, desc=desc, total=total, file=sys.stderr, delay=after,
                    mininterval=after, leave=False)


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

    def __init__(self, label: str, enabled: bool = True, after: float = REPORT_AFTER,
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
