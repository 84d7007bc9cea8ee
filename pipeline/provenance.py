"""What determines a run's numbers, written beside its outputs as ``run.json``.

A record holds the command and its arguments as given, the input files as written
(path, SHA-256, text), the parsed inputs, the options that change the numbers, the
SHA-256 of every file the inputs point to (a stiffness CSV, ...), the code revision
(``git describe`` in a checkout, the package version, and always a SHA-256 of the
package source), the versions of Python, the numerical libraries, the sparse solvers
and the BLAS, the start time, the run time and the output files. Its ``hash`` (SHA-256,
16 hex digits) covers everything that determines the numbers (the command, inputs,
options, the input and referenced files' contents, the code and the versions) and
nothing that does not (times, folders, the platform string, which libraries the run
happened to load), so two runs with the same hash computed the same thing.

The numerical libraries recorded are NumPy, SciPy, scikit-fem, Gmsh and
pypardiso/MKL/cholespy/scikit-sparse, with the sparse Cholesky used and the BLAS; a
referenced file is for example a ``kind = "csv"`` stiffness table. Every command and
workflow writes one.
Cost, measured on 2 cores shared with other jobs (load average 4-5): 85-98 ms per record
(source hash, ``git``, versions).
"""

from __future__ import annotations

import hashlib
import os
import platform
import subprocess
import sys
import time
from collections.abc import Iterable, Mapping
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path
from typing import Any, Protocol

from pipeline.io import content_hash, to_jsonable, write_json

_UNHASHED = ("platform", "sparse_cholesky", "blas")  # machine, or what the run imported
_TRACKED = ("numpy", "scipy", "scikit-fem", "gmsh", "meshio", "pyvista", "matplotlib",
            "cholespy", "scikit-sparse", "pypardiso", "mkl", "threadpoolctl")
_PACKAGE = Path(__file__).resolve().parent


class InputSource(Protocol):
    """An input file as read (:class:`pipeline.config.toml_file.InputFile`)."""

    path: Path | None
    text: str
    sha256: str


def file_sha256(path: str | os.PathLike) -> str:
    """SHA-256 (hex) of a file's bytes."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def source_sha256(package: Path = _PACKAGE) -> str:
    """SHA-256 (hex) of the package's Python source: every ``*.py`` by relative path."""
    h = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        h.update(path.relative_to(package).as_posix().encode() + b"\0")
        h.update(path.read_bytes() + b"\0")
    return h.hexdigest()


def _git(*args: str) -> str | None:
    try:
        run = subprocess.run(["git", "-C", str(_PACKAGE.parent), *args], capture_output=True,
                             text=True, timeout=10, check=False)
    except (OSError, subprocess.SubprocessError):
        return None
    if run.returncode != 0:
        return None
    return run.stdout.strip() or None


def code_revision() -> dict[str, str | None]:
    """The code that ran: package version, source SHA-256, and in a git checkout the
    commit and ``git describe --always --dirty``."""
    from pipeline import __version__

    rev: dict[str, str | None] = {"version": __version__, "source_sha256": source_sha256()}
    if (_PACKAGE.parent / ".git").exists():
        rev["git_commit"] = _git("rev-parse", "HEAD")
        rev["git_describe"] = _git("describe", "--always", "--dirty", "--tags")
    return rev


def library_versions() -> dict[str, Any]:
    """Versions of Python, the numerical libraries, the sparse solvers and the BLAS.

    ``sparse_cholesky`` is the factorisation the FE solvers use by default ("pardiso",
    "cholmod", "cholespy" or "none"; "not loaded" when the run did no FE); ``blas`` lists
    the BLAS/OpenMP libraries loaded in the process. These two depend on what the run
    imported, so they are recorded but not hashed (the package versions are).
    """
    out: dict[str, Any] = {"python": sys.version.split()[0], "platform": platform.platform()}
    for name in ("gearpipe",) + _TRACKED:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    solvers = sys.modules.get("pipeline.fem.solvers")  # importing it costs 0.5 s
    out["sparse_cholesky"] = (solvers.sparse_cholesky() or "none") if solvers else "not loaded"
    try:
        from threadpoolctl import threadpool_info

        out["blas"] = sorted({f"{i.get('internal_api')} {i.get('version')}"
                              for i in threadpool_info()})
    except ImportError:
        out["blas"] = []
    return out


def _utc(t: float) -> str:
    return datetime.fromtimestamp(t, UTC).isoformat(timespec="seconds")


def run_record(inputs: Any, outputs: Iterable[str | os.PathLike], command: str, *,
               arguments: Iterable[str] | None = None, options: Mapping[str, Any] | None = None,
               sources: Iterable[InputSource] = (),
               referenced: Mapping[str, str | os.PathLike] | None = None,
               started: float | None = None) -> dict[str, Any]:
    """The record of a run (module docstring) as a JSON-ready dictionary.

    Parameters
    ----------
    inputs : the parsed inputs (configuration as read, stage options; any JSON-able data).
    outputs : the files the run wrote (their names are listed).
    command : what ran, without paths (e.g. ``"gearpipe fe"``); part of the hash.
    arguments : the command-line arguments as given (recorded, not hashed).
    options : command-line options that change the numbers (part of the hash).
    sources : input files as read: path, raw text, SHA-256 (the SHA-256 is hashed).
    referenced : files the inputs point to, by the key that names them; their
        SHA-256 is recorded and hashed.
    started : start of the run, seconds since the epoch (default: now).
    """
    now = time.time()
    started = now if started is None else started
    files = {key: {"path": str(p), "sha256": file_sha256(p)}
             for key, p in (referenced or {}).items()}
    srcs = [{"path": None if s.path is None else str(s.path), "sha256": s.sha256,
             "text": s.text} for s in sources]
    code, versions = code_revision(), library_versions()
    determining = {
        "command": command, "inputs": inputs, "options": dict(options or {}),
        "sources": [s["sha256"] for s in srcs],
        "referenced": {k: v["sha256"] for k, v in files.items()},
        "code": code["source_sha256"],
        "versions": {k: v for k, v in versions.items() if k not in _UNHASHED},
    }
    return to_jsonable({
        "command": command,
        "arguments": list(arguments) if arguments is not None else None,
        "hash": content_hash(determining),
        "started_utc": _utc(started),
        "finished_utc": _utc(now),
        "run_time_s": round(now - started, 3),
        "code": code,
        "versions": versions,
        "sources": srcs,
        "referenced_files": files,
        "options": dict(options or {}),
        "inputs": inputs,
        "outputs": sorted({Path(o).name for o in outputs}),
    })


def write_run_record(outdir: str | os.PathLike, inputs: Any,
                     outputs: Iterable[str | os.PathLike], command: str,
                     **kwargs: Any) -> Path:
    """Write ``run.json`` (:func:`run_record`; keyword arguments as there) into ``outdir``,
    the run's last file: its outputs are ``outputs`` and whatever else the folder holds
    (so that a rerun recognises the folder as one result, :mod:`pipeline.output_folder`)."""
    outdir = Path(outdir)
    present = [p for p in os.listdir(outdir) if not p.startswith(".") and p != "run.json"]
    return write_json(outdir / "run.json",
                      run_record(inputs, [*outputs, *present], command, **kwargs))


__all__ = ["code_revision", "file_sha256", "library_versions", "run_record",
           "source_sha256", "write_run_record"]
