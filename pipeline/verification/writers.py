"""The files of a verification run: ``validate.html`` (the report), ``validate.json``
(every case in full, SI) and ``validate.csv`` (one row per compared quantity, units in
the column names and the ``unit`` column)."""

from __future__ import annotations

from pathlib import Path

from pipeline.io import atomic_write_text, write_csv, write_json
from pipeline.verification.html import validation_html
from pipeline.verification.results import VerificationRun
from pipeline.verification.tables import quantity_rows, run_document

REPORT_FILES = ("validate.html", "validate.json", "validate.csv")


def write_validation(run: VerificationRun, out: Path, facts: dict[str, str]) -> list[Path]:
    """Write the three files into ``out`` (an existing folder); returns their paths."""
    return [atomic_write_text(out / "validate.html",
                              validation_html(run, "gearpipe validation report", facts)),
            write_json(out / "validate.json", run_document(run)),
            write_csv(out / "validate.csv", quantity_rows(run))]
