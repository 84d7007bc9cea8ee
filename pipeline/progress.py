"""Progress reporting for long runs on stderr: :func:`progress` (iterations, wraps tqdm) and
:class:`Steps` (named steps, their wall times).

Both say nothing about work that ends within :data:`REPORT_AFTER` seconds (but a step its
caller announces at once, and the step list of a run, which names every step as it ends):
a bar or step line appears only where the user would otherwise wait in silence.
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
    """Times named steps of a computation and reports them on stderr: the one step timer of
    the project (a run's steps, FE phases, the reports).

    ``with steps.step("factorise") as note:`` times the block and adds its wall time to
    :attr:`timings` (s); the block may set ``note["cached"] = True`` (its result came from
    the cache) or ``note["text"]`` (a short result). A step is announced,
    ``[label] name ...``, at once with ``announce`` (for a long C call that holds the GIL,
    which would hold a timer's line back), else once it has run ``after`` seconds (a timer
    thread); it ends with ``[label] name: 1.23 s (from the cache), text`` when it took
    ``after`` seconds or more, or always with ``every_step`` (a run's step list).
    :meth:`advance` reports the progress of a counted step, at most every ``every`` seconds.
    Nothing is printed when ``enabled`` is False; nothing is ever written to stdout.

    Parameters
    ----------
    label : the name in brackets on every line, e.g. ``"gearpipe run"``, ``"fe3d gear"``.
    enabled : print at all.
    after : seconds a step must run before it is reported (a run's list: announced).
    every : seconds between two progress lines of one step.
    every_step : report every step when it ends, however short.
    """

    def __init__(self, label: str, enabled: bool = True, after: float = REPORT_AFTER,
                 every: float = 5.0, every_step: bool = False) -> None:
        self.label = label
        self.enabled = enabled
        self.after = after
        self.every = every
        self.every_step = every_step
        self.timings: dict[str, float] = {}
        self.cached: dict[str, bool] = {}
        self._started: dict[str, float] = {}
        self._said: dict[str, float] = {}

    def _say(self, text: str) -> None:
        if self.enabled:
            print(f"[{self.label}] {text}", file=sys.stderr, flush=True)

    @contextmanager
    def step(self, name: str, announce: bool = False) -> Iterator[dict]:
        """Time the ``with`` block as step ``name`` (class docstring); yields the note."""
        note: dict = {}
        t0 = time.perf_counter()
        self._started[name] = self._said[name] = t0
        timer = threading.Timer(self.after, self._say, (f"{name} ...",))
        timer.daemon = True
        if announce:
            self._say(f"{name} ...")
        elif self.enabled:
            timer.start()
        try:
            yield note
        finally:
            timer.cancel()
            dt = time.perf_counter() - t0
            self._started.pop(name, None)
            self.timings[name] = self.timings.get(name, 0.0) + dt
            self.cached[name] = bool(note.get("cached", False))
            if self.every_step or dt >= self.after:
                extra = " (from the cache)" if self.cached[name] else ""
                text = f", {note['text']}" if note.get("text") else ""
                self._say(f"{name}: {dt:.2f} s{extra}{text}")

    def advance(self, name: str, done: int, total: int, unit: str = "") -> None:
        """Report ``done`` of ``total`` (``unit``) of the running step ``name`` once it has
        run for ``after`` seconds, then every ``every`` seconds."""
        t0, now = self._started.get(name), time.perf_counter()
        if t0 is not None and now - t0 >= self.after and now - self._said[name] >= self.every:
            self._said[name] = now
            self._say(f"{name} {done}/{total}{' ' + unit if unit else ''} ({now - t0:.0f} s)")

    def summary(self) -> dict:
        """``{"steps_s": {name: s}, "from_cache": [names], "total_s": s}``."""
        return {"steps_s": dict(self.timings),
                "from_cache": [k for k, v in self.cached.items() if v],
                "total_s": float(sum(self.timings.values()))}
