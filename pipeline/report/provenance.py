"""Provenance of a report: what determines its numbers, and where they came from.

The configuration hash is :func:`pipeline.io.content_hash` of the gearbox inputs (the
same frozen inputs every stage received), the file hash the SHA-256 of the gearbox file's
bytes; the code revision is the git commit of the source tree the package runs from (with
``+modified`` when its tracked files differ from that commit), or "not a git checkout";
library and solver versions from :func:`pipeline.io.library_versions` and the sparse
direct solvers that are importable.
"""

from __future__ import annotations

import subprocess
from datetime import UTC, datetime
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Any

from pipeline.io import content_hash, library_versions

_SOLVERS = ("scikit-sparse", "cholespy", "python-mumps", "pyamg")


@lru_cache(maxsize=1)
def code_revision() -> str:
    """Git commit of the package's source tree (``+modified`` if dirty), or a note why not."""
    root = Path(__file__).resolve().parents[2]
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                              text=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain",
                                "--untracked-files=no"], capture_output=True, text=True,
                               timeout=10, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "not a git checkout"
    return f"{head}{'+modified' if dirty else ''}"


def solver_versions() -> dict[str, str]:
    """Versions of the sparse solver packages (or "not installed")."""
    out = {}
    for name in _SOLVERS:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out


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
    return {"configuration_hash": content_hash(gearbox_inputs),
            "gearbox_file_sha256": file_sha256 or "built in Python",
            "code_revision": code_revision(),
            "command": command,
            "time_utc": datetime.now(UTC).isoformat(timespec="seconds"),
            "run_time_s": float(run_seconds),
            "versions": {**library_versions(), **solver_versions()}}
