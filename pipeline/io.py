"""Writing results: atomic files and a run record beside every output.

A half-written file is never left under its final name: data go to a
temporary file in the same directory and are moved into place with
``os.replace`` (atomic on POSIX). Each run writes ``run.json`` recording its
inputs, the hash of its configuration, and the versions of the libraries used.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import sys
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import asdict, is_dataclass
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

_TRACKED = ("numpy", "scipy", "scikit-fem", "gmsh", "meshio", "pyvista", "matplotlib")


def atomic_write(path: str | os.PathLike, writer: Callable[[str], None]) -> Path:
    """Call ``writer(tmp_path)`` and move the file to ``path`` only if it succeeds."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        writer(tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


def atomic_write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    return atomic_write(path, lambda p: Path(p).write_text(text, encoding="utf-8"))


def to_jsonable(obj: Any) -> Any:
    """Convert dataclasses, numpy arrays and scalars into JSON-ready values."""
    if is_dataclass(obj) and not isinstance(obj, type):
        return to_jsonable(asdict(obj))
    if isinstance(obj, Mapping):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, Path):
        return str(obj)
    return obj


def write_json(path: str | os.PathLike, data: Any) -> Path:
    """Write ``data`` as indented JSON, atomically."""
    return atomic_write_text(path, json.dumps(to_jsonable(data), indent=2) + "\n")


def write_csv(path: str | os.PathLike, columns: Mapping[str, np.ndarray]) -> Path:
    """Write equal-length 1-D columns as CSV; put units in the column names."""
    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    header = ",".join(names)
    return atomic_write(
        path, lambda p: np.savetxt(p, data, delimiter=",", header=header, comments="", fmt="%.9g")
    )


def content_hash(data: Any) -> str:
    """SHA-256 (hex, 16 chars) of a JSON-canonical form of ``data``."""
    blob = json.dumps(to_jsonable(data), sort_keys=True, separators=(",", ":")).encode()
    return hashlib.sha256(blob).hexdigest()[:16]


def library_versions() -> dict[str, str]:
    """Versions of Python and of the numerical libraries the pipeline uses."""
    out = {"python": sys.version.split()[0], "platform": platform.platform()}
    for name in ("gearpipe",) + _TRACKED:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out


def write_run_record(
    outdir: str | os.PathLike, inputs: Any, outputs: list[str | os.PathLike], command: str
) -> Path:
    """Write ``run.json`` with inputs, their hash, versions and the output files."""
    record = {
        "command": command,
        "time_utc": datetime.now(UTC).isoformat(timespec="seconds"),
        "config_hash": content_hash(inputs),
        "inputs": to_jsonable(inputs),
        "versions": library_versions(),
        "outputs": [str(Path(o).name) for o in outputs],
    }
    return write_json(Path(outdir) / "run.json", record)
