"""The results folder of a study: finished points appended atomically, resumable.

Layout of ``OUT/``:

* ``manifest.json`` - what the numbers depend on (SHA-256 of the base file, the study's
  ``[set]``, ``[[axes]]``, ``[sampling]`` and ``[kpis]`` tables, the KPI columns) and
  its hash; written before any point.
* ``parts/part-<first point>-<session>.parquet`` - the rows of one finished batch, each
  written atomically (temporary file + rename), so a study killed at any moment keeps
  every batch that had finished and nothing half-written.
* ``study.parquet``, ``study.csv`` - every point, ordered by point number, when the study
  is complete.

Resuming (``--resume``) reads the finished point numbers from the part files and refuses
with one line when the manifest's hash differs from the study file's (base file, axes,
fixed changes, sampling or KPIs changed).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import pyarrow as pa
import pyarrow.csv as pcsv
import pyarrow.parquet as pq

from pipeline.io import atomic_write, content_hash, write_json
from pipeline.study.spec import StudySpec
from pipeline.validation import InputError


def study_identity(spec: StudySpec, kpi_names: Sequence[str]) -> dict[str, Any]:
    """Everything a study's numbers depend on (for the manifest and the resume check)."""
    doc = spec.document
    return {"base_sha256": spec.base.sha256, "set": doc.get("set", {}),
            "axes": doc.get("axes", []), "sampling": doc.get("sampling", {}),
            "kpis": doc.get("kpis", {}), "kpi_columns": list(kpi_names)}


class StudyStore:
    """The results folder of one study (module docstring).

    Parameters
    ----------
    out : the folder.
    schema : the table's columns (point number, axes in file units, KPIs, error text).
    identity : :func:`study_identity` of the study.
    """

    def __init__(self, out: Path, schema: pa.Schema, identity: dict[str, Any]) -> None:
        self.out = Path(out)
        self.parts = self.out / "parts"
        self.schema = schema
        self.identity = identity
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
        write_json(manifest, {"hash": self.hash, "identity": self.identity, "points": total})
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

    def write_table(self) -> tuple[pa.Table, list[Path]]:
        """``study.parquet`` and ``study.csv`` of every finished point; returns them."""
        t = self.table()
        pq_path = atomic_write(self.out / "study.parquet", lambda tmp: pq.write_table(t, tmp))
        csv_path = atomic_write(self.out / "study.csv", lambda tmp: pcsv.write_csv(t, tmp))
        return t, [pq_path, csv_path]
