"""The results folder of a study: finished points appended atomically, resumable.

Layout of ``OUT/``:

* ``manifest.json`` - the study's name and what the numbers depend on (SHA-256 of the base
  file, the study's ``[set]``, ``[[axes]]``, ``[sampling]`` and ``[kpis]`` tables, the KPI
  columns) and its hash; written before any point.
* ``parts/part-<first point>-<session>.parquet`` - the rows of one finished batch, each
  written atomically (temporary file + rename), so a study killed at any moment keeps
  every batch that had finished and nothing half-written.
* ``computed_points.log`` - ``<session> <point>`` per computed point (workers on this
  machine).
* ``study.parquet``, ``study.csv`` - every point, ordered by point number, when the study
  is complete.

Resuming (``--resume``) reads the finished point numbers from the part files and refuses
with one line when the manifest's hash differs from the study file's (base file, axes,
fixed changes, sampling or KPIs changed).

Which folder a study may write (:func:`study_folder`; the check, message and swap are every
command's, :mod:`pipeline.output_folder`): a new or empty one, or an earlier result of the
same study. The same study is a ``manifest.json`` naming it: the study file's ``name``, by
default its stem, so an edited study file replaces its earlier result as any command's
rerun does (a manifest written before the name was recorded counts when its base file,
``[set]``, axes and sampling are this study's). Beside the manifest the folder holds either
nothing but the files above (``parts/`` holding part files only: an unfinished study, or
what :func:`~pipeline.study.execute.run_study` writes when called as a library) or a
``run.json`` of ``gearpipe study`` listing every file. A folder holding anything else (a
user's files, another command's result, another study's) is refused before any point is
computed.
"""

from __future__ import annotations

import json
import os
import shutil
from collections.abc import Sequence
from functools import partial
from pathlib import Path
from typing import Any

import pyarrow as pa
import pyarrow.csv as pcsv
import pyarrow.parquet as pq

from pipeline.io import atomic_write, content_hash, fsync_path, write_json
from pipeline.output_folder import (
    FolderRule,
    folder_entries,
    read_json_object,
    read_record,
    record_outputs,
    unlisted,
)
from pipeline.study.spec import StudySpec
from pipeline.validation import InputError


def study_identity(spec: StudySpec, kpi_names: Sequence[str]) -> dict[str, Any]:
    """Everything a study's numbers depend on (for the manifest and the resume check)."""
    doc = spec.document
    out = {"base_sha256": spec.base.sha256, "set": doc.get("set", {}),
           "axes": doc.get("axes", []), "sampling": doc.get("sampling", {}),
           "kpis": doc.get("kpis", {}), "kpi_columns": list(kpi_names)}
    if spec.kind != "study":  # a Harris map: its axes are these tables
        out.update(kind=spec.kind, variants=doc.get("variants", []),
                   torque=doc.get("torque", {}))
    return out


# what a study's working folder holds (module docstring); with the tables, what run_study
# leaves when called as a library
WORK_FILES = ("manifest.json", "parts", "computed_points.log")
TABLE_FILES = ("study.parquet", "study.csv")


def _is_part(name: str) -> bool:
    """A part file, or the temporary file of one being written."""
    return name.startswith(("part-", ".part-")) and name.endswith(".parquet")


def _manifest(folder: Path) -> dict | None:
    return read_json_object(folder / "manifest.json")


def _same_study(manifest: dict, spec: StudySpec) -> bool:
    if "study" in manifest:
        return manifest["study"] == spec.name
    # written before the name was recorded: compare what the numbers depend on
    old = manifest.get("identity")
    now = json.loads(json.dumps(study_identity(spec, ())))
    keys = ("base_sha256", "set", "axes", "sampling")
    return isinstance(old, dict) and all(old.get(k) == now[k] for k in keys)


def _not_of_study(folder: Path, spec: StudySpec) -> list[str]:
    """Entries of ``folder`` that are not part of a result of ``spec`` (module docstring)."""
    entries = folder_entries(folder)
    manifest = _manifest(folder) if entries else None
    if manifest is None or not _same_study(manifest, spec):
        return entries
    record = read_record(folder)
    if record is not None and str(record.get("command", "")).startswith("gearpipe study"):
        return unlisted(entries, record_outputs(record))
    foreign = unlisted(entries, {*WORK_FILES, *TABLE_FILES})
    if (folder / "parts").is_dir():
        foreign += [f"parts/{e}" for e in folder_entries(folder / "parts") if not _is_part(e)]
    return foreign


def study_folder(spec: StudySpec) -> FolderRule:
    """The folders ``spec`` may write into: new, empty, or an earlier result of the same
    study, finished or not (module docstring)."""
    return FolderRule(f"a result of the study {spec.name!r}", partial(_not_of_study, spec=spec))


def is_complete(folder: Path) -> bool:
    """``folder`` (accepted by :func:`study_folder`) holds a finished study's result."""
    return (Path(folder) / "run.json").is_file()


def link_work_files(work: Path, folder: Path) -> list[Path]:
    """Hard-link the manifest, part files and point log of the study in ``work`` into
    ``folder`` (copies where the filesystem has no hard links); returns them.

    Part files are written once and never changed, so the result folder and the working
    folder it replaces may share them.
    """
    work, folder = Path(work), Path(folder)
    (folder / "parts").mkdir(exist_ok=True)
    names = [n for n in WORK_FILES if n != "parts" and (work / n).is_file()]
    names += [f"parts/{e}" for e in folder_entries(work / "parts")
              if _is_part(e) and not e.startswith(".")]
    for name in names:
        try:
            os.link(work / name, folder / name)
        except OSError:
            shutil.copy2(work / name, folder / name)
    fsync_path(folder / "parts", directory=True)
    return [folder / n for n in names if "/" not in n] + [folder / "parts"]


class StudyStore:
    """The results folder of one study (module docstring).

    Parameters
    ----------
    out : the folder.
    schema : the table's columns (point number, axes in file units, KPIs, error text).
    identity : :func:`study_identity` of the study.
    study : the study's name (recorded in the manifest: :func:`study_folder`).
    """

    def __init__(self, out: Path, schema: pa.Schema, identity: dict[str, Any],
                 study: str) -> None:
        self.out = Path(out)
        self.parts = self.out / "parts"
        self.schema = schema
        self.identity = identity
        self.study = study
        self.hash = content_hash(identity)

    def open(self, resume: bool, total: int) -> set[int]:
        """Prepare the folder; returns the point numbers already finished (resume only).

        Without ``resume`` an unfinished study in the folder is refused (it would be lost);
        a finished one is replaced.
        """
        manifest = self.out / "manifest.json"
        old = json.loads(manifest.read_text()) if manifest.is_file() else None
        done = self.finished() if old is not None else set()
        if resume:
            if old is None:
                raise InputError(f"--resume: {self.out} holds no study to resume")
            if old.get("hash") != self.hash:
                changed = [k for k in self.identity if old.get("identity", {}).get(k)
                           != json.loads(json.dumps(self.identity[k]))]
                raise InputError(f"--resume: the study in {self.out} was run with another "
                                 f"{' and '.join(changed) or 'study file'}; its "
                                 "results cannot be continued (run without --resume into a "
                                 "new --out folder)")
            return done
        if old is not None and len(done) < old.get("points", total):
            raise InputError(f"{self.out} holds an unfinished study ({len(done)} of "
                             f"{old.get('points', total)} points): continue it with --resume, "
                             "or choose another --out folder")
        for p in self.parts.glob("part-*.parquet") if self.parts.is_dir() else ():
            p.unlink()
        for name in ("study.parquet", "study.csv"):
            (self.out / name).unlink(missing_ok=True)
        self.parts.mkdir(parents=True, exist_ok=True)
        write_json(manifest, {"study": self.study, "hash": self.hash,
                              "identity": self.identity, "points": total})
        return set()

    def finished(self) -> set[int]:
        """Point numbers in the finished part files."""
        if not self.parts.is_dir():
            return set()
        out: set[int] = set()
        for p in sorted(self.parts.glob("part-*.parquet")):
            out.update(pq.read_table(p, columns=["point"]).column("point").to_pylist())
        return out

    def append(self, rows: list[dict[str, Any]], session: str) -> Path:
        """Write the rows of one finished batch as a part file, atomically."""
        table = pa.Table.from_pylist(rows, schema=self.schema)
        first = min(r["point"] for r in rows)
        path = self.parts / f"part-{first:07d}-{session}.parquet"
        return atomic_write(path, lambda tmp: pq.write_table(table, tmp))

    def table(self) -> pa.Table:
        """All finished rows ordered by point number (a point in two parts counts once)."""
        parts = sorted(self.parts.glob("part-*.parquet"))
        if not parts:
            return self.schema.empty_table()
        t = pa.concat_tables([pq.read_table(p, schema=self.schema) for p in parts])
        t = t.sort_by("point")
        pts = t.column("point").to_pylist()
        keep = [i for i, p in enumerate(pts) if i == 0 or pts[i - 1] != p]
        return t.take(keep)

    def write_table(self, folder: Path | None = None) -> tuple[pa.Table, list[Path]]:
        """``study.parquet`` and ``study.csv`` of every finished point in ``folder``
        (default: the study's folder); returns the table and the files."""
        folder = self.out if folder is None else Path(folder)
        t = self.table()
        pq_path = atomic_write(folder / "study.parquet", lambda tmp: pq.write_table(t, tmp))
        csv_path = atomic_write(folder / "study.csv", lambda tmp: pcsv.write_csv(t, tmp))
        return t, [pq_path, csv_path]
