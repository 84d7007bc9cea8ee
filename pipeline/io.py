"""Writing results: atomic, durable files with the process's permissions.

A half-written file is never left under its final name: data go to a hidden
temporary file in the same directory, are flushed to disk (``fsync``) and moved
into place with ``os.replace`` (atomic on POSIX): after a crash the name holds the
old or the new complete file, never an empty one. (The folder itself is flushed
once, when a result folder is swapped in, :mod:`pipeline.output_folder`, rather than
after every file.) Temporary files carry the writer's process id
(``.<name>.tmp-<pid>-<random><suffix>``), so the next write into the same folder
removes those a killed process left behind. Files get the permissions the
process umask gives a new file (``0o666 & ~umask``), not ``mkstemp``'s 0600.

A run's whole folder is written as a unit by :mod:`pipeline.output_folder`; its
record (``run.json``) by :mod:`pipeline.provenance`.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import os
import re
import tempfile
from collections.abc import Callable, Mapping
from dataclasses import asdict, fields, is_dataclass
from pathlib import Path
from typing import Any

import numpy as np

_TEMP = re.compile(r"^\..+\.tmp-(\d+)-[A-Za-z0-9_]{8}")


def process_umask() -> int:
    """The file-mode creation mask of this process (e.g. ``0o022``).

    Read from ``/proc/self/status`` where the kernel provides it; elsewhere by setting
    and restoring it (the only portable way, not thread-safe for that instant).
    """
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def pid_alive(pid: int) -> bool:
    """Whether process ``pid`` exists on this machine and is not a zombie."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:  # a killed child its parent has not reaped yet is dead for our purpose
        stat = Path(f"/proc/{pid}/stat").read_text()
        return stat.rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return True


def fsync_path(path: str | os.PathLike, *, directory: bool = False) -> None:
    """Flush a file (or, with ``directory``, a folder's entries) to disk."""
    flags = os.O_RDONLY | (getattr(os, "O_DIRECTORY", 0) if directory else 0)
    try:
        fd = os.open(path, flags)
    except OSError:
        if directory:  # some filesystems cannot open folders: nothing to flush there
            return
        raise
    try:
        os.fsync(fd)
    except OSError:
        if not directory:
            raise
    finally:
        os.close(fd)


def remove_stale_temps(folder: str | os.PathLike) -> list[Path]:
    """Delete temporary files in ``folder`` left by processes that no longer run."""
    removed = []
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for entry in entries:
        m = _TEMP.match(entry.name)
        if m and not pid_alive(int(m.group(1))):
            try:
                os.unlink(entry.path)
                removed.append(Path(entry.path))
            except OSError:
                pass  # another process cleaned it, or the folder is read-only
    return removed


def atomic_write(path: str | os.PathLike, writer: Callable[[str], None]) -> Path:
    """Call ``writer(tmp_path)`` and move the file to ``path`` only if it succeeds.

    The temporary file is in the same folder (hidden, with ``path``'s suffix, which
    writers such as ``np.save`` and ``savefig`` rely on); it is flushed to disk and
    given the umask's permissions before the rename. Stale temporary files of dead
    processes in the folder are removed first.

    Parameters
    ----------
    path : the file to write; its folder is created if missing.
    writer : called with the temporary file's path (a ``str``); writes the whole file.

    Returns
    -------
    Path : ``path``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temps(path.parent)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.tmp-{os.getpid()}-",
                               suffix=path.suffix, dir=path.parent)
    os.close(fd)
    try:
        writer(tmp)
        fsync_path(tmp)
        os.chmod(tmp, 0o666 & ~process_umask())
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


def csv_header(names: list[str]) -> str:
    """One CSV header line of ``names``, quoted where a name holds a comma, quote or newline
    (RFC 4180, as :func:`csv.reader` reads it back), without the line end."""
    buf = io.StringIO()
    csv.writer(buf, lineterminator="").writerow(names)
    return buf.getvalue()


def write_csv(path: str | os.PathLike, columns: Mapping[str, Any]) -> Path:
    """Write equal-length 1-D columns as CSV (RFC 4180); put units in the column names.

    Numbers are written with 9 significant digits; a column of strings (a case name,
    say) is written as text. Names and text that hold a comma, a quote or a line break
    are quoted, so :func:`csv.reader` reads back one field per column in every row.
    """
    names = list(columns)
    cols = [np.asarray(columns[n]) for n in names]
    if any(c.ndim != 1 or c.size != cols[0].size for c in cols):
        raise ValueError(f"{Path(path).name}: columns must be 1-D and of equal length, got "
                         f"shapes {[c.shape for c in cols]}")
    header = csv_header(names)
    if all(c.dtype.kind in "biuf" for c in cols):
        data = np.column_stack([c.astype(float) for c in cols]) if cols else np.empty((0, 0))
        return atomic_write(path, lambda p: np.savetxt(p, data, delimiter=",", header=header,
                                                       comments="", fmt="%.9g"))
    text = [[str(v) for v in c] if c.dtype.kind in "USO" else [f"{v:.9g}" for v in c]
            for c in cols]

    def write(tmp: str) -> None:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(names)
            w.writerows(zip(*text, strict=True))

    return atomic_write(path, write)


def _feed(h, obj: Any) -> None:
    """Feed a canonical description of ``obj`` into the hash ``h``."""
    if obj is None or isinstance(obj, (bool, int, float, str, complex)):
        h.update(f"{type(obj).__name__}:{obj!r};".encode())
    elif isinstance(obj, (np.ndarray, np.generic)):
        a = np.ascontiguousarray(obj)
        h.update(f"nd:{a.dtype.str}:{a.shape};".encode())
        h.update(a.tobytes() if a.dtype != object else repr(a.tolist()).encode())
    elif is_dataclass(obj) and not isinstance(obj, type):
        h.update(f"dc:{type(obj).__module__}.{type(obj).__qualname__}(".encode())
        for f in fields(obj):
            h.update(f"{f.name}=".encode())
            _feed(h, getattr(obj, f.name))
        h.update(b")")
    elif isinstance(obj, Mapping):
        h.update(b"{")
        for k in sorted(obj, key=str):
            _feed(h, str(k))
            _feed(h, obj[k])
        h.update(b"}")
    elif isinstance(obj, (list, tuple)):
        h.update(f"seq{len(obj)}[".encode())
        for v in obj:
            _feed(h, v)
        h.update(b"]")
    elif isinstance(obj, Path):
        _feed(h, str(obj))
    else:
        raise TypeError(f"content hash: cannot describe a value of type {type(obj).__name__}")


def content_hash(*objs: Any) -> str:
    """SHA-256 (hex, 16 characters) of a canonical description of ``objs``: scalars by type
    and repr, arrays by dtype, shape and bytes, dataclasses field by field with their
    class, mappings by sorted key, sequences in order, paths as text. Equal data give equal
    hashes; a value it cannot describe is a ``TypeError`` rather than a silent collision.
    The one hash of the project: cache keys, figure keys, run records, study points."""
    h = hashlib.sha256()
    for o in objs:
        _feed(h, o)
    return h.hexdigest()[:16]
