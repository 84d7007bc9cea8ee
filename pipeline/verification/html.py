"""The validation report as one self-contained HTML page: an overview table of every case
(kind, source, status, worst error against its tolerance, time), then each case with its
source, inputs, compared quantities (reference, value, error, tolerance and its reason,
status), its convergence study and its figures (PNG embedded as base64 data URIs: the page
opens offline and prints to PDF)."""

from __future__ import annotations

import base64
import math
from html import escape

from pipeline.verification.display import format_error, format_tolerance, format_value
from pipeline.verification.figures import png_bytes
from pipeline.verification.model import KINDS, Convergence, Quantity
from pipeline.verification.results import CaseResult, VerificationRun

KIND_NAMES = {"exact": "exact solution", "published": "published value",
              "independent_fe": "independent FE model", "convergence": "convergence study"}

_STYLE = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1250px; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em;
  border-bottom: 1px solid #ccc; } h3 { font-size: 1em; }
table { border-collapse: collapse; margin: 0.5em 0; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 3px 6px; text-align: left; vertical-align: top; }
th { background: #f0f0f0; } td.num { text-align: right; white-space: nowrap; }
.pass { color: #176b1f; font-weight: bold; } .fail, .error { color: #b00; font-weight: bold; }
.small { font-size: 0.8em; color: #555; } img { max-width: 100%; margin: 0.3em 0; }
"""


def _status(status: str) -> str:
    return f'<span class="{status}">{status.upper()}</span>'


def _overview(run: VerificationRun) -> str:
    rows = []
    for r in sorted(run.results, key=lambda r: KINDS.index(r.kind)):
        q = r.worst
        worst = escape(r.error) if r.error else (
            "" if q is None else f"{escape(q.name)}: {escape(format_error(q))} "
                                 f"(tolerance {escape(format_tolerance(q))})")
        source = r.outcome.source if r.outcome is not None else ""
        rows.append(f'<tr><td><a href="#{r.id}">{r.id}</a></td><td>{KIND_NAMES[r.kind]}</td>'
                    f"<td>{escape(r.title)}</td><td>{escape(source)}</td>"
                    f"<td>{_status(r.status)}</td><td>{worst}</td>"
                    f'<td class="num">{r.seconds:.1f}</td></tr>')
    return ("<table><tr><th>case</th><th>kind</th><th>what is compared</th><th>source</th>"
            "<th>status</th><th>largest error against its tolerance</th><th>time [s]</th>"
            "</tr>" + "".join(rows) + "</table>")


def _quantities(quantities: tuple[Quantity, ...], failed: bool) -> str:
    rows = "".join(
        f"<tr><td>{escape(q.name)}</td>"
        f'<td class="num">{escape(format_value(q, q.reference))}</td>'
        f'<td class="num">{escape(format_value(q, q.value))}</td>'
        f'<td class="num">{escape(format_error(q))}</td>'
        f'<td class="num">{escape(format_tolerance(q))}</td>'
        f"<td>{_status('pass' if q.passed else 'fail')}</td>"
        f'<td class="small">{escape(q.reason)}</td></tr>' for q in quantities)
    table = ("<table><tr><th>quantity</th><th>reference</th><th>gearpipe</th><th>error</th>"
             "<th>tolerance</th><th>status</th><th>why this tolerance</th></tr>"
             f"{rows}</table>")
    if len(quantities) <= 40:
        return table
    bad = sum(not q.passed for q in quantities)
    open_ = " open" if failed else ""
    return (f"<details{open_}><summary>{len(quantities)} quantities, {bad} outside their "
            f"tolerance (click to show)</summary>{table}</details>")


def _convergence(c: Convergence) -> str:
    rows = "".join(f'<tr><td class="num">{h:.4g}</td><td class="num">{v:.8g}</td>'
                   f'<td class="num">{e:.3g}</td></tr>'
                   for h, v, e in zip(c.levels, c.values, c.errors, strict=True))
    measured = f"<b>{c.rate:.3f}</b>" if math.isfinite(c.rate) else "not formed (two levels)"
    expected = f"expected {c.expected_rate:g}" if math.isfinite(c.expected_rate) else \
        "no a-priori rate"
    return (f"<p>Measured rate {measured}; {expected}: {escape(c.rate_reason)}.</p>"
            f"<table><tr><th>{escape(c.level_name)}</th><th>{escape(c.quantity)}</th>"
            f"<th>{escape(c.error_name)}</th></tr>{rows}</table>")


def _case(r: CaseResult) -> str:
    parts = [f'<h2 id="{r.id}">{r.id}: {escape(r.title)} {_status(r.status)}</h2>',
             f'<p class="small">{KIND_NAMES[r.kind]}, {r.tier} set, {r.seconds:.1f} s</p>']
    if r.error:
        parts.append(f'<p class="error">The case raised: {escape(r.error)}</p>')
    o = r.outcome
    if o is not None:
        parts.append(f"<p><b>Source:</b> {escape(o.source)}</p>")
        if o.inputs:
            parts.append("<table><tr><th>input</th><th>value</th></tr>" + "".join(
                f"<tr><td>{escape(k)}</td><td>{escape(v)}</td></tr>" for k, v in o.inputs)
                + "</table>")
        parts.append(_quantities(o.quantities, not r.passed))
        if o.convergence is not None:
            parts.append(_convergence(o.convergence))
        for p in o.plots:
            data = base64.b64encode(png_bytes(p)).decode("ascii")
            parts.append(f'<div><img alt="{escape(p.title)}" '
                         f'src="data:image/png;base64,{data}"></div>')
        if o.notes:
            parts.append(f"<p>{escape(o.notes)}</p>")
    return "\n".join(parts)


def validation_html(run: VerificationRun, title: str, facts: dict[str, str]) -> str:
    """The report page. ``facts``: (label, text) shown under the title (the command, the
    code version, the date)."""
    counts = run.counts
    head = (f"{len(run.results)} cases: {counts['pass']} passed, {counts['fail']} failed, "
            f"{counts['error']} raised; {run.seconds:.1f} s")
    facts_html = "".join(f"<li>{escape(k)}: {escape(v)}</li>" for k, v in facts.items())
    body = "\n".join(_case(r) for r in sorted(run.results, key=lambda r: KINDS.index(r.kind)))
    return (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{escape(title)}</title><style>{_STYLE}</style></head><body>"
            f"<h1>{escape(title)}</h1><p><b>{_status('pass' if run.passed else 'fail')}"
            f" {escape(head)}</b></p><ul class=\"small\">{facts_html}</ul>"
            "<p>Each case compares what the pipeline computes with a reference: an exact "
            "solution, a published value, an independent finite-element model or, for a "
            "convergence study, the pipeline itself over refinements with its measured "
            "rate. A case passes when every quantity lies within its tolerance; each "
            "tolerance says why it is what it is. Values are shown in engineering units; "
            "the JSON and CSV files hold them in SI units.</p>"
            f"{_overview(run)}\n{body}</body></html>\n")
