"""One self-contained HTML file of a :class:`~pipeline.report.model.MeshReport`.

Figures are embedded as base64 data URIs (PNG, or SVG), the style sheet is inline and
there is no script or remote resource, so the file opens offline and can be mailed as it
is. A print style sheet keeps tables and figures whole on a page and drops the contents
list, so the browser's "print to PDF" gives a clean document. Every number in a table
cell carries ``data-key="<section>.<key>[.<column>]"``, the path of its value in the
report's JSON; it is that value printed with :func:`pipeline.report.model.format_value`.
"""

from __future__ import annotations

import base64
import html
from pathlib import Path

from pipeline.report.model import MeshReport, Section, format_value

_MIME = {".png": "image/png", ".svg": "image/svg+xml"}

_CSS = """
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; font-size: 13px;
       color: #1a1a1a; margin: 24px auto; max-width: 1040px; padding: 0 16px; }
h1 { font-size: 22px; margin-bottom: 4px; }
h2 { font-size: 17px; border-bottom: 2px solid #2b5d8a; padding-bottom: 3px;
     margin-top: 28px; color: #2b5d8a; }
p.sub { color: #555; margin-top: 0; }
table { border-collapse: collapse; margin: 8px 0 12px 0; }
th, td { border: 1px solid #c9d3dd; padding: 3px 8px; text-align: left; }
th { background: #eef3f8; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.unit { color: #555; }
figure { margin: 10px 0 18px 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #e3e3e3; }
figcaption { color: #444; font-size: 12px; margin-top: 3px; }
p.note { color: #333; font-size: 12px; background: #f7f7f2; border-left: 3px solid #c8b560;
         padding: 4px 8px; }
nav ol { columns: 2; font-size: 12px; }
@media print {
  body { margin: 0; max-width: none; font-size: 10.5pt; }
  nav { display: none; }
  h2 { break-after: avoid; page-break-after: avoid; }
  table, figure { break-inside: avoid; page-break-inside: avoid; }
  a { color: inherit; text-decoration: none; }
}
@page { size: A4; margin: 14mm; }
"""


def data_uri(path: Path) -> str:
    """``data:`` URI of a PNG or SVG file."""
    mime = _MIME.get(path.suffix.lower())
    if mime is None:
        raise ValueError(f"{path.name}: only PNG and SVG figures can be embedded")
    return f"data:{mime};base64,{base64.b64encode(path.read_bytes()).decode('ascii')}"


def _table(section: Section) -> str:
    if not section.quantities:
        return ""
    multi = len(section.columns) > 1
    head = "".join(f"<th>{html.escape(c)}</th>" for c in section.columns) if multi else \
        "<th>value</th>"
    rows = []
    for q in section.quantities:
        cells = []
        for col, v in zip(section.columns, q.values, strict=True):
            key = f"{section.key}.{q.key}" + (f".{col}" if multi else "")
            cls = "num" if isinstance(v, (int, float)) and not isinstance(v, bool) else "txt"
            cells.append(f'<td class="{cls}" data-key="{html.escape(key)}">'
                         f"{html.escape(format_value(v))}</td>")
        rows.append(f"<tr><td>{html.escape(q.label)}</td>{''.join(cells)}"
                    f'<td class="unit">{html.escape(q.unit)}</td></tr>')
    return (f"<table><thead><tr><th>quantity</th>{head}<th>unit</th></tr></thead>"
            f"<tbody>{''.join(rows)}</tbody></table>")


def _section(section: Section, folder: Path) -> str:
    parts = [f'<section id="{section.key}"><h2>{html.escape(section.title)}</h2>',
             _table(section)]
    for note in section.notes:
        parts.append(f'<p class="note">{html.escape(note)}</p>')
    for fig in section.figures:
        parts.append(f'<figure><img src="{data_uri(folder / fig.file)}" '
                     f'alt="{html.escape(fig.caption)}"><figcaption>'
                     f"{html.escape(fig.caption)} ({html.escape(fig.file)})</figcaption>"
                     "</figure>")
    parts.append("</section>")
    return "\n".join(parts)


def render_html(report: MeshReport, folder: Path, subtitle: str = "") -> str:
    """The report as one HTML document; figure files are read from ``folder``."""
    toc = "".join(f'<li><a href="#{s.key}">{html.escape(s.title)}</a></li>'
                  for s in report.sections)
    body = "\n".join(_section(s, Path(folder)) for s in report.sections)
    return (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        f"<title>{html.escape(report.title)}</title>"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
        f"<style>{_CSS}</style></head><body>\n"
        f"<h1>{html.escape(report.title)}</h1><p class=\"sub\">{html.escape(subtitle)}</p>\n"
        f"<nav><ol>{toc}</ol></nav>\n{body}\n</body></html>\n"
    )
