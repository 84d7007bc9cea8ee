"""Provenance of a report: what determines its numbers, and where they came from.

The configuration hash is :func:`pipeline.io.content_hash` of the gearbox inputs (the
same frozen inputs every stage received), the file hash the SHA-256 of the gearbox file's
bytes; the code revision, the library, solver and BLAS versions come from
:mod:`pipeline.provenance` (the same as ``run.json``), flattened to one text per entry.
"""

from __future__ import annotations

from datetime import UTC, datetime
from typing import Any

from pipeline.io import content_hash
from pipeline.provenance import code_revision as _code
from pipeline.provenance import library_versions


def code_revision() -> str:
    """``git describe`` of the source tree (with ``-dirty``) and its commit, else the package
    version and the SHA-256 of its source."""
    rev = _code()
    if rev.get("git_commit"):
        return f"{rev.get('git_describe') or ''} ({rev['git_commit']})".strip()
    return f"gearpipe {rev['version']}, source SHA-256 {rev['source_sha256'][:16]}"


def provenance(gearbox_inputs: Any, *, file_sha256: str | None, command: str,
               run_seconds: float) -> dict[str, Any]:
    """Provenance record of a report.

    Parameters
    ----------
    gearbox_inputs : the gearbox's inputs (``Gearbox.to_dict()``), hashed.
    file_sha256 : SHA-256 of the gearbox file, or None when built in Python.
    command : the command line that made the report.
    run_seconds : wall time of the run that computed the results, s.
    """
    versions = {k: ", ".join(v) if isinstance(v, list) else str(v)
                for k, v in library_versions().items()}
    return {"configuration_hash": content_hash(gearbox_inputs),
            "gearbox_file_sha256": file_sha256 or "built in Python",
            "code_revision": code_revision(),
            "command": command,
            "time_utc": datetime.now(UTC).isoformat(timespec="seconds"),
            "run_time_s": float(run_seconds),
            "versions": versions}
