"""Run a selection of cases: each timed, an exception caught as the case's failure with
its one-line message, a line per case handed to ``report`` (the command prints it on
stderr)."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

from pipeline.verification.catalogue import Case
from pipeline.verification.context import Context
from pipeline.verification.results import CaseResult, VerificationRun


def one_line(exc: BaseException) -> str:
    """``"Type: first line of the message"``."""
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else 'no detail'}"


def run_case(case: Case, context: Context) -> CaseResult:
    """Run one case; an exception becomes a failed result with its one-line message."""
    start = time.perf_counter()
    try:
        outcome, error = case.function(context), ""
    except Exception as exc:  # a case that raises is a failed case, the run goes on
        outcome, error = None, one_line(exc)
    return CaseResult(case.id, case.title, case.kind, case.tier, outcome,
                      time.perf_counter() - start, error)


def run_cases(cases: Sequence[Case], context: Context,
              report: Callable[[str], None] | None = None) -> VerificationRun:
    """Run ``cases`` in order; ``report`` receives a line as each starts and its summary
    line (:meth:`CaseResult.summary_line`) as it ends."""
    results = []
    for i, case in enumerate(cases, 1):
        if report is not None:
            report(f"[{i}/{len(cases)}] {case.id} ...")
        result = run_case(case, context)
        if report is not None:
            report(f"[{i}/{len(cases)}] {result.summary_line()}")
        results.append(result)
    return VerificationRun(tuple(results))
