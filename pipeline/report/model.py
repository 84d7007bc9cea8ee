"""What a report holds: sections of quantities with units, figures, notes.

A :class:`MeshReport` is plain data: the HTML (:mod:`pipeline.report.html`), the JSON and
the CSV (:mod:`pipeline.report.writer`) are three renderings of it, so a number shown in
the HTML is the JSON's value printed with :func:`format_value`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

Value = float | int | str | bool | None


THOUSANDS_SEPARATOR = "\u202f"
"""Digit-group separator of the report: a narrow no-break space (SI Brochure, 9th ed. 2019,
5.4.4: groups of three digits separated by a thin space, never by a point or comma)."""


def _grouped(digits: str) -> str:
    """``"18500"`` -> ``"18 500"`` (narrow no-break spaces); numbers below 10 000 unchanged."""
    sign, digits = ("-", digits[1:]) if digits.startswith("-") else ("", digits)
    if len(digits) <= 4:
        return sign + digits
    head = len(digits) % 3 or 3
    groups = [digits[:head]] + [digits[i:i + 3] for i in range(head, len(digits), 3)]
    return sign + THOUSANDS_SEPARATOR.join(groups)


def format_value(value: Value) -> str:
    """How a value is printed in the HTML: for reading, not for copying.

    Rule (floats): 4 significant digits in plain notation for 1e-3 <= |x| < 1e9, the
    integer part grouped by three with :data:`THOUSANDS_SEPARATOR` from 10 000 on
    (``18500.0`` -> ``"18 500"``, ``0.00123`` -> ``"0.00123"``, ``3.14159`` -> ``"3.142"``);
    outside that range scientific with 4 significant digits (``1.5e-9`` -> ``"1.500e-09"``).
    Integers exactly, grouped the same way; ``bool`` as yes/no; ``None`` and NaN as an en
    dash; text as it is. The JSON keeps the full value.
    """
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "\u2013"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return _grouped(str(value))
    if isinstance(value, float):
        if value == 0.0:
            return "0"
        if math.isinf(value):
            return "\u221e" if value > 0 else "-\u221e"
        if not 1e-3 <= abs(value) < 1e9:
            return f"{value:.3e}"
        exponent = math.floor(math.log10(abs(float(f"{value:.4g}"))))
        # round to 4 significant digits first, so 99995 prints as 100 000, not 99 995
        text = f"{round(value, 3 - exponent):.{max(0, 3 - exponent)}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        whole, dot, frac = text.partition(".")
        return _grouped(whole) + dot + frac
    return str(value)


@dataclass(frozen=True)
class Quantity:
    """One row of a section table.

    Attributes
    ----------
    key : identifier, unique in its section (letters, digits, underscores).
    label : what the row is, as a reader reads it.
    values : one value per column of the section.
    unit : unit of the values ("-" for dimensionless, "" for text).
    """

    key: str
    label: str
    values: tuple[Value, ...]
    unit: str = "-"


@dataclass(frozen=True)
class Figure:
    """A figure of a section: a PNG file in the report folder and its caption."""

    file: str
    caption: str


@dataclass(frozen=True)
class Section:
    """A section of the report.

    Attributes
    ----------
    key : identifier (used in the JSON and in the HTML ``data-key`` attributes).
    title : heading.
    quantities : table rows.
    columns : table column headings (one per value of every row).
    figures : figures shown under the table.
    notes : sentences on the method (what was computed how, what is left out).
    """

    key: str
    title: str
    quantities: tuple[Quantity, ...] = ()
    columns: tuple[str, ...] = ("value",)
    figures: tuple[Figure, ...] = ()
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        keys = [q.key for q in self.quantities]
        if len(set(keys)) != len(keys):
            raise ValueError(f"report section {self.key!r}: repeated keys")
        for q in self.quantities:
            if len(q.values) != len(self.columns):
                raise ValueError(f"report section {self.key!r}: {q.key} has {len(q.values)} "
                                 f"values for {len(self.columns)} columns")

    def to_json(self) -> dict[str, Any]:
        """``{"title", "quantities": {key: {label, unit, value | values}}, ...}``."""
        rows: dict[str, Any] = {}
        for q in self.quantities:
            row: dict[str, Any] = {"label": q.label, "unit": q.unit}
            if len(self.columns) == 1:
                row["value"] = q.values[0]
            else:
                row["values"] = dict(zip(self.columns, q.values, strict=True))
            rows[q.key] = row
        return {"title": self.title, "columns": list(self.columns), "quantities": rows,
                "figures": [{"file": f.file, "caption": f.caption} for f in self.figures],
                "notes": list(self.notes)}


@dataclass(frozen=True)
class MeshReport:
    """The tooth load distribution report of one gear mesh.

    Attributes
    ----------
    title : heading of the report.
    mesh : mesh name ("mesh" for a pair, "sun_planet", "planet_ring").
    sections : in reading order; the last is the provenance.
    """

    title: str
    mesh: str
    sections: tuple[Section, ...] = field(default_factory=tuple)

    def section(self, key: str) -> Section:
        """The section with ``key`` (KeyError if absent)."""
        for s in self.sections:
            if s.key == key:
                return s
        raise KeyError(key)

    def to_json(self) -> dict[str, Any]:
        """The whole report as JSON-ready data."""
        return {"title": self.title, "mesh": self.mesh,
                "sections": {s.key: s.to_json() for s in self.sections}}

    def rows(self) -> list[tuple[str, str, str, str, str, Value]]:
        """(section, key, column, label, unit, value) of every number and text, in order."""
        out = []
        for s in self.sections:
            for q in s.quantities:
                for col, v in zip(s.columns, q.values, strict=True):
                    out.append((s.key, q.key, col, q.label, q.unit, v))
        return out
