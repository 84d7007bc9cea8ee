"""The results as tables with units: one row per compared quantity (CSV) and one nested
document per run (JSON). Values are SI; each row's ``unit`` names the unit of its
reference, value and (absolute) error and tolerance, a relative one is a fraction."""

from __future__ import annotations

import math
from typing import Any

from pipeline.verification.model import Quantity
from pipeline.verification.results import CaseResult, VerificationRun

QUANTITY_COLUMNS = ("case", "kind", "tier", "case status", "quantity", "unit",
                    "reference [SI unit of the row]", "value [SI unit of the row]",
                    "error kind", "error [-] if relative, else [SI unit of the row]",
                    "tolerance [-] if relative, else [SI unit of the row]", "passed [-]",
                    "case time [s]", "source", "tolerance reason")
"""The CSV's columns (:func:`quantity_rows`)."""


def _row(r: CaseResult, q: Quantity | None) -> list[Any]:
    source = r.outcome.source if r.outcome is not None else ""
    head = [r.id, r.kind, r.tier, r.status]
    tail = [round(r.seconds, 3), source]
    if q is None:  # a case that raised: one row carrying its message
        return head + ["(the case raised)", "", "", "", "", "", "", 0] + tail + [r.error]
    return head + [q.name, q.unit, q.reference, q.value, q.error_kind, q.error, q.tolerance,
                   int(q.passed)] + tail + [q.reason]


def quantity_rows(run: VerificationRun) -> dict[str, list[Any]]:
    """Columns (:data:`QUANTITY_COLUMNS`) of one row per quantity of every case, a case
    that raised as one row with its message."""
    rows = []
    for r in run.results:
        qs = r.outcome.quantities if r.outcome is not None else ()
        rows += [_row(r, q) for q in qs] or [_row(r, None)]
    return {name: [row[i] for row in rows] for i, name in enumerate(QUANTITY_COLUMNS)}


def _json_number(x: float) -> float | None:
    """``x``, or ``None`` (JSON null) for NaN: JSON has no NaN."""
    return None if isinstance(x, float) and math.isnan(x) else x


def quantity_document(q: Quantity) -> dict[str, Any]:
    unit, factor = q.display or (q.unit, 1.0)
    return {"name": q.name, "unit": q.unit, "reference": q.reference, "value": q.value,
            "error_kind": q.error_kind, "error": _json_number(q.error),
            "tolerance": q.tolerance,
            "passed": q.passed, "tolerance_reason": q.reason,
            "display_unit": unit, "display_factor": factor}


def case_document(r: CaseResult) -> dict[str, Any]:
    """Everything of one case (SI values, units named)."""
    doc: dict[str, Any] = {"id": r.id, "title": r.title, "kind": r.kind, "tier": r.tier,
                           "status": r.status, "time_s": r.seconds, "error": r.error}
    o = r.outcome
    if o is None:
        return doc
    doc.update(source=o.source, inputs=dict(o.inputs), notes=o.notes,
               quantities=[quantity_document(q) for q in o.quantities])
    c = o.convergence
    if c is not None:
        doc["convergence"] = {"level_name": c.level_name, "levels": list(c.levels),
                              "quantity": c.quantity, "values": list(c.values),
                              "error_name": c.error_name,
                              "errors": [_json_number(e) for e in c.errors],
                              "rate": _json_number(c.rate),
                              "expected_rate": _json_number(c.expected_rate),
                              "rate_reason": c.rate_reason}
    doc["plots"] = [{"title": p.title, "xlabel": p.xlabel, "ylabel": p.ylabel,
                     "series": [{"label": s.label, "x": [_json_number(v) for v in s.x],
                                 "y": [_json_number(v) for v in s.y]}
                                for s in p.series]} for p in o.plots]
    return doc


def run_document(run: VerificationRun) -> dict[str, Any]:
    """The run's summary and every case in full."""
    return {**{k: v for k, v in run.summary().items() if k != "results"},
            "cases_detail": [case_document(r) for r in run.results]}
