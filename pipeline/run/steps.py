"""Step timing and progress lines of a pipeline run.

``gearpipe run`` reports every step on stderr as it finishes (name, seconds, whether
its result came from the cache), so a user sees where the time goes; the same
records end up in the run's summary as its timing breakdown.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field


@dataclass
class StepLog:
    """Durations (s) and cache hits of the steps of one run, in order.

    Attributes
    ----------
    show : print a line per finished step on stderr.
    label : the command the lines name (``[gearpipe report] ...``).
    seconds : step name -> wall time, s.
    cached : step name -> True when its result was read from the cache.
    """

    show: bool = True
    label: str = "gearpipe run"
    seconds: dict[str, float] = field(default_factory=dict)
    cached: dict[str, bool] = field(default_factory=dict)

    @contextmanager
    def step(self, name: str, long: bool = False) -> Iterator[dict]:
        """Time the block; the block may set ``note["cached"] = True`` or ``note["text"]``.

        A ``long`` step also announces its start (its own progress bars may follow).
        """
        note: dict = {}
        if self.show and long:
            print(f"[{self.label}] {name} ...", file=sys.stderr, flush=True)
        t0 = time.perf_counter()
        yield note
        dt = time.perf_counter() - t0
        self.seconds[name] = dt
        self.cached[name] = bool(note.get("cached", False))
        if self.show:
            extra = " (from the cache)" if self.cached[name] else ""
            text = f", {note['text']}" if note.get("text") else ""
            print(f"[{self.label}] {name}: {dt:.2f} s{extra}{text}", file=sys.stderr,
                  flush=True)

    def summary(self) -> dict:
        """``{"steps_s": {...}, "from_cache": [...], "total_s": ...}``."""
        return {"steps_s": dict(self.seconds),
                "from_cache": [k for k, v in self.cached.items() if v],
                "total_s": float(sum(self.seconds.values()))}
