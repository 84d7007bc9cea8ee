"""The results of a run: one :class:`CaseResult` per case (the catalogue's description,
what the case returned, its time, the message of what it raised) and the run's
:class:`VerificationRun` with its totals."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from pipeline.verification.display import format_error, format_tolerance
from pipeline.verification.model import Outcome, Quantity


@dataclass(frozen=True)
class CaseResult:
    """One case run: the catalogue's description, its outcome (``None`` when it raised),
    the time it took and the one-line message of what it raised.

    Attributes
    ----------
    id, title, kind, tier : from the catalogue (:class:`.catalogue.Case`).
    outcome : what the case function returned, or ``None``.
    seconds : wall time of the case, s.
    error : ``"ExceptionType: message"`` (one line) when the case raised, else ``""``.
    """

    id: str
    title: str
    kind: str
    tier: str
    outcome: Outcome | None
    seconds: float
    error: str = ""

    @property
    def passed(self) -> bool:
        """No exception, at least one quantity, every quantity within its tolerance."""
        return (not self.error and self.outcome is not None and bool(self.outcome.quantities)
                and all(q.passed for q in self.outcome.quantities))

    @property
    def status(self) -> str:
        """``"pass"``, ``"fail"`` or ``"error"`` (the case raised)."""
        return "error" if self.error else ("pass" if self.passed else "fail")

    @property
    def worst(self) -> Quantity | None:
        """The quantity furthest outside (or least inside) its tolerance."""
        if self.outcome is None or not self.outcome.quantities:
            return None
        return max(self.outcome.quantities, key=_margin)

    def summary_line(self) -> str:
        """One line: status, id, time and the worst quantity's error against its
        tolerance (or the error message)."""
        head = f"{self.status.upper():5s} {self.id} ({self.seconds:.1f} s)"
        if self.error:
            return f"{head}: {self.error}"
        q = self.worst
        if q is None:
            return f"{head}: no quantity compared"
        return f"{head}: {q.name} {format_error(q)} (tolerance {format_tolerance(q)})"


@dataclass(frozen=True)
class VerificationRun:
    """The results of a run of cases, in the catalogue's order."""

    results: tuple[CaseResult, ...] = field(default_factory=tuple)

    @property
    def passed(self) -> bool:
        return bool(self.results) and all(r.passed for r in self.results)

    @property
    def counts(self) -> dict[str, int]:
        """Number of cases per status."""
        out = {"pass": 0, "fail": 0, "error": 0}
        for r in self.results:
            out[r.status] += 1
        return out

    @property
    def seconds(self) -> float:
        return float(sum(r.seconds for r in self.results))

    def summary(self) -> dict:
        """Totals and one entry per case (id, kind, status, time, worst error)."""
        cases = []
        for r in self.results:
            q = r.worst
            cases.append({"id": r.id, "kind": r.kind, "tier": r.tier, "status": r.status,
                          "seconds": r.seconds, "error": r.error,
                          "worst": None if q is None else {
                              "quantity": q.name,
                              "error": q.error if math.isfinite(q.error) else None,
                              "error_kind": q.error_kind, "tolerance": q.tolerance}})
        return {"cases": len(self.results), **self.counts, "passed": self.passed,
                "seconds": self.seconds, "results": cases}


def _margin(q: Quantity) -> float:
    """How far the error uses up its tolerance (> 1: outside)."""
    e = q.error
    if not math.isfinite(e):
        return math.inf
    if q.error_kind == "lower_bound":
        used = -e
    elif q.error_kind == "upper_bound":
        used = e
    else:
        used = abs(e)
    return used / q.tolerance if q.tolerance > 0 else (math.inf if used > 0 else 0.0)
