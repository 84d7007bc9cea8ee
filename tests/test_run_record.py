"""``run.json`` tells runs apart: its hash covers everything that determines the numbers.

Cases from the reliability audit: two ``gearpipe fe`` option sets that shared a hash,
and a stiffness table the gearbox file points to whose contents changed the modes but
not the hash. The record also keeps the file as written, the code revision, the solver
versions and the times, none of which (but the code) enter the hash.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from pipeline.cli import main as cli
from pipeline.provenance import run_record

CONFIG = Path(__file__).resolve().parents[1] / "workflows" / "configs" / \
    "spur_pair_assembly_errors.toml"


def record(folder: Path) -> dict:
    return json.loads((folder / "run.json").read_text(encoding="utf-8"))


class _Sector:
    """Stands in for the FE of one gear: the record is what is tested here."""

    def summary(self) -> dict:
        return {"points": 1}


@pytest.mark.parametrize(("a", "b"), [
    (["--refinement", "0.5", "--points", "5"],
     ["--refinement", "1", "--points", "6", "--kind", "plane_stress"]),
    (["--teeth", "3"], ["--teeth", "4"]),
    ([], ["--kind", "plane_stress"]),
])
def test_fe_options_give_different_hashes(tmp_path, monkeypatch, a, b):
    import pipeline.cli.fem as fe

    monkeypatch.setattr(fe, "analyse_sector", lambda gear, opts, **cache: _Sector())
    monkeypatch.setattr(fe, "write_gear", lambda res, out, tag: [])
    hashes = []
    for i, extra in enumerate((a, b, a)):
        out = tmp_path / f"out{i}"
        assert cli(["fe", str(CONFIG), "--out", str(out), *extra]) == 0
        hashes.append(record(out)["hash"])
        assert record(out)["options"] == {
            "kind": None, "points": None, "refinement": None, "teeth": None,
            **{k[2:]: (v if k == "--kind" else float(v) if k == "--refinement" else int(v))
               for k, v in zip(extra[::2], extra[1::2], strict=True)}}
    assert hashes[0] != hashes[1] and hashes[0] == hashes[2]


def _with_table(tmp_path: Path, values: np.ndarray) -> Path:
    np.savetxt(tmp_path / "k.csv", values, header="k [N/m]", comments="")
    cfg = tmp_path / "pair.toml"
    cfg.write_text(CONFIG.read_text().replace("positions = 360", "positions = 60")
                   + '\n[dynamics.mesh_stiffness]\nkind = "csv"\npath = "k.csv"\n')
    return cfg


def test_a_changed_referenced_file_changes_the_hash(tmp_path):
    k = 3.5e8 + 0.4e8 * np.cos(np.linspace(0, 2 * np.pi, 64, endpoint=False))
    runs = {}
    for name, values in (("first", k), ("same", k), ("doubled", 2 * k)):
        cfg = _with_table(tmp_path, values)
        out = tmp_path / name
        assert cli(["modes", str(cfg), "--out", str(out)]) == 0
        runs[name] = (record(out), np.loadtxt(out / "modes.csv", delimiter=",", skiprows=1))
    (first, m1), (same, m2), (doubled, m3) = runs.values()
    assert first["hash"] == same["hash"] != doubled["hash"]
    np.testing.assert_array_equal(m1, m2)
    assert not np.allclose(m1, m3)  # the doubled table changed the numbers
    assert first["versions"]["sparse_cholesky"] in ("pardiso", "cholmod", "cholespy")  # did FE
    ref = first["referenced_files"]["dynamics.mesh_stiffness.path"]
    assert ref["path"] == str(tmp_path / "k.csv") and re.fullmatch(r"[0-9a-f]{64}", ref["sha256"])
    assert ref["sha256"] != doubled["referenced_files"]["dynamics.mesh_stiffness.path"]["sha256"]


def test_the_record_keeps_the_file_code_solvers_and_times(tmp_path):
    out = tmp_path / "out"
    assert cli(["geometry", str(CONFIG), "--out", str(out)]) == 0
    rec = record(out)
    assert rec["command"] == "gearpipe geometry"
    assert rec["arguments"] == ["geometry", str(CONFIG), "--out", str(out)]
    (src,) = rec["sources"]
    assert src["text"] == CONFIG.read_text(encoding="utf-8") and src["path"] == str(CONFIG)
    assert re.fullmatch(r"[0-9a-f]{64}", rec["code"]["source_sha256"])
    assert rec["code"]["version"]
    if "git_commit" in rec["code"]:
        assert re.fullmatch(r"[0-9a-f]{40}", rec["code"]["git_commit"])
    versions = rec["versions"]
    assert versions["cholespy"] != "not installed" and versions["numpy"]
    # "not loaded" when nothing in the process did FE (other tests in this process may have)
    assert versions["sparse_cholesky"] in ("not loaded", "pardiso", "cholmod", "cholespy")
    assert versions["blas"]
    assert rec["started_utc"] <= rec["finished_utc"] and 0 <= rec["run_time_s"] < 600
    assert sorted(rec["outputs"]) == sorted(p.name for p in out.iterdir() if p.name != "run.json")
    assert re.fullmatch(r"[0-9a-f]{16}", rec["hash"])


def test_times_and_folders_do_not_enter_the_hash_but_everything_else_does():
    base = dict(inputs={"a": 1}, outputs=["x.csv"], command="gearpipe x")
    h = run_record(**base, started=0.0)["hash"]
    assert run_record(**base, started=1e9, arguments=["--out", "elsewhere"])["hash"] == h
    assert run_record(**{**base, "outputs": ["y.csv"]})["hash"] == h
    assert run_record(**{**base, "inputs": {"a": 2}})["hash"] != h
    assert run_record(**{**base, "command": "gearpipe y"})["hash"] != h
    assert run_record(**base, options={"full": True})["hash"] != h
