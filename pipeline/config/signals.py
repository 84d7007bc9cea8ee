"""A periodic stiffness table (``[dynamics.mesh_stiffness]``) -> :class:`PeriodicSignal`.

``kind`` chooses the shape (keys in :data:`pipeline.config.tables.SIGNAL`):
"rectangular" (single/double contact levels), "contact_line" (ISO 6336-like
contact-line length), "harmonic" (Fourier series), "constant" and "csv" (one
column of a CSV file holding one mesh period; a relative path is relative to
the gearbox file).
"""

from __future__ import annotations

import csv
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.config.schema import Key, read_table, restated, unknown
from pipeline.config.tables import SIGNAL, SIGNAL_KINDS
from pipeline.signals import MIN_SAMPLES, PeriodicSignal
from pipeline.validation import InputError, check_range


def signal_from_table(table: Mapping[str, Any], where: str, base: Path | None) -> PeriodicSignal:
    """Build the signal of a stiffness table at ``where`` (N/m over one mesh period)."""
    if not isinstance(table, Mapping):
        raise InputError(f"{where}: expected a table [{where}]")
    kind = table.get("kind", "constant")
    if not isinstance(kind, str) or kind not in SIGNAL_KINDS:
        raise InputError(f"{where}.kind = {kind!r} is not one of "
                         f"{', '.join(map(repr, SIGNAL_KINDS))}")
    keys = SIGNAL[kind] + (Key("kind", "string", choices=SIGNAL_KINDS),)
    try:
        kw = read_table(table, keys, where)
    except InputError as exc:
        raise InputError(f"{exc} (for kind = {kind!r})") from None
    kw.pop("kind", None)
    if kind == "harmonic" and "phases" in kw and len(kw["phases"]) != len(kw["amplitudes"]):
        raise InputError(f"{where}.phases_rad = {list(table['phases_rad'])}: expected "
                         f"{len(kw['amplitudes'])} numbers (one per amplitude), got "
                         f"{len(kw['phases'])}")
    signal = _build(kind, kw, where, keys, table, base)
    if np.any(signal.values <= 0.0):
        raise InputError(f"{where}: the {kind} stiffness falls to "
                         f"{signal.values.min():.6g} N/m; a mesh stiffness must be > 0 N/m "
                         "everywhere")
    return signal


def _build(kind: str, kw: dict[str, Any], where: str, keys, table, base) -> PeriodicSignal:
    from pipeline.dynamics.excitation import (
        MAX_MESH_STIFFNESS,
        contact_line_stiffness,
        harmonic_signal,
        rectangular_mesh_stiffness,
    )

    with restated(where, keys, table):
        if kind == "rectangular":
            return rectangular_mesh_stiffness(**kw)
        if kind == "contact_line":
            return contact_line_stiffness(**kw)
        if kind == "harmonic":
            return harmonic_signal(**kw)
        if kind == "constant":
            value = check_range("value", kw["value"], 0.0, MAX_MESH_STIFFNESS, lo_open=True,
                                unit="N/m")
            return PeriodicSignal(np.full(8, float(value)))
    return _csv_signal(kw, where, base)


def csv_path(path: str, base: Path | None) -> Path:
    """The file of a ``kind = "csv"`` table: a relative ``path`` is relative to ``base``
    (the folder of the gearbox file)."""
    p = Path(path)
    return base / p if base is not None and not p.is_absolute() else p


def referenced_files(document: Mapping[str, Any], base: Path | None,
                     where: str = "") -> dict[str, Path]:
    """The files a parsed gearbox document points to, by the dotted key of their ``path``."""
    out: dict[str, Path] = {}
    for key, value in document.items():
        name = f"{where}{key}"
        if isinstance(value, Mapping):
            if value.get("kind") == "csv" and isinstance(value.get("path"), str):
                out[f"{name}.path"] = csv_path(value["path"], base)
            if isinstance(value.get("topography_csv"), str):  # [<gear>.modifications]
                out[f"{name}.topography_csv"] = csv_path(value["topography_csv"], base)
            out.update(referenced_files(value, base, f"{name}."))
    return out


def csv_rows(path: Path, shown: str, hint: str, comments: bool = False) -> list[list[str]]:
    """The rows of the CSV file ``path`` (with ``comments``: lines starting with ``#`` and
    empty lines left out); a missing, unreadable or non-UTF-8 file is one line starting with
    ``shown`` (the key as the file gave it) and, for a missing one, ending with ``hint``."""
    problem = path_problem(path)
    if problem is not None:
        raise InputError(f"{shown} {problem}; {hint}")
    try:
        with path.open(encoding="utf-8", newline="") as f:
            rows = list(csv.reader(f))
    except OSError as exc:
        raise InputError(f"{shown} cannot be read ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise InputError(f"{shown} is not a UTF-8 text file (a CSV table is)") from None
    if comments:
        rows = [r for r in rows if r and not r[0].lstrip().startswith("#")]
    return rows


def path_problem(path: Path) -> str | None:
    """Why ``path`` cannot be read as a data file, or ``None``: missing, a folder, or not a
    regular file (a device such as ``/dev/zero``, a pipe, a socket: reading one may never
    end)."""
    if not path.exists():
        return "does not exist"
    if path.is_dir():
        return "is a folder, not a file"
    if not path.is_file():
        return "is not a regular file (a device, pipe or socket)"
    return None


def _csv_signal(kw: dict[str, Any], where: str, base: Path | None) -> PeriodicSignal:
    path = csv_path(kw["path"], base)
    key = f'{where}.path = "{path}"'
    rows = csv_rows(path, key, "give a CSV file with one mesh period of stiffness values "
                    "(N/m) in a column")
    names = [n.strip() for n in rows[0]] if rows else []
    col = kw.get("column", names[-1] if names else "")
    if col not in names:
        raise unknown(col, names, f"{where}.column")
    j = names.index(col)
    values = []
    for line, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        cell = row[j].strip() if j < len(row) else ""
        try:
            values.append(float(cell))
        except ValueError:
            raise InputError(f"{key}: line {line}, column {col!r} holds {cell!r}, not a "
                             "number") from None
    if len(values) < MIN_SAMPLES or not np.all(np.isfinite(values)):
        raise InputError(f"{key}: column {col!r} holds {len(values)} values; one mesh period "
                         f"needs at least {MIN_SAMPLES} finite values")
    return PeriodicSignal(np.asarray(values))
