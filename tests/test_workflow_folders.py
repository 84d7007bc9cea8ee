"""Workflow folders and command folders never collide, and a clash is one line.

Commands write ``results/<file stem>/<command>/``; workflow scripts write
``results/<script stem>/workflow/`` (:func:`pipeline.cli.common.workflow_dir`). The
spur-pair workflow and ``gearpipe`` on its gearbox file share the stem
``spur_pair_assembly_errors``: both results live side by side, each untouched by the other.
A workflow folder holding a user's file is refused in one line (exit status 1) before the
workflow computes anything: each row replaces the workflow's first expensive step by one
that fails the test if called.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

from pipeline.cli import SUBCOMMANDS, run_workflow
from pipeline.cli import main as cli
from pipeline.cli.common import WORKFLOW_FOLDER, workflow_dir

ROOT = Path(__file__).resolve().parents[1]
WORKFLOWS = ROOT / "workflows"
SPUR = WORKFLOWS / "configs" / "spur_pair_assembly_errors.toml"


def _load(name: str):
    spec = importlib.util.spec_from_file_location(f"wf_{name}", WORKFLOWS / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _not_a_stage(*args, **kwargs):
    raise AssertionError("the workflow computed before refusing its folder")


# workflow script, the first expensive step it calls (replaced by _not_a_stage)
CLASHES = [
    ("spur_pair_assembly_errors", "run"),
    ("helical_slice_stiffness", "run"),
    ("fe3d_helical_stiffness", "run"),
    ("validate_stiffness", "run"),
    ("dynamics_spur_dte", "run"),
    ("dynamics_split_torque", "run"),
    ("dynamics_herringbone_sweep", "run"),
    ("excitation_comparison", "run_pipeline"),
    ("groove_sweep", "sweep"),
    ("ring_body_fit", "samples"),
    ("herringbone_groove_study", "fit_grooves"),
    ("tip_relief_study", "gearpipe"),
    ("modification_catalogue", "run"),
    ("fe3d_convergence", "run"),
]


def test_no_command_is_named_like_the_workflow_folder():
    assert WORKFLOW_FOLDER not in SUBCOMMANDS
    assert workflow_dir("workflows/x.py", check=False) == Path("results/x/workflow")


def test_every_writing_workflow_is_in_the_table():
    """A new workflow that writes a folder joins the table above (and so the rule)."""
    writers = {p.stem for p in WORKFLOWS.glob("*.py") if "staged_output" in p.read_text()}
    assert writers == {name for name, _ in CLASHES}


@pytest.mark.parametrize(("name", "stage"), CLASHES, ids=[c[0] for c in CLASHES])
def test_a_workflow_folder_holding_other_files_is_one_line_before_any_work(
        tmp_path, monkeypatch, capsys, name, stage):
    mod = _load(name)
    monkeypatch.setattr(mod, stage, _not_a_stage)
    monkeypatch.chdir(tmp_path)
    folder = Path("results") / name / "workflow"
    folder.mkdir(parents=True)
    (folder / "notes.txt").write_bytes(b"a user's notes\n")
    assert run_workflow(f"workflows/{name}.py", mod.main, []) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"{name}.py: error: "), err
    assert "holds files that are not one gearpipe result (notes.txt)" in err[0]
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == \
        [Path("results"), Path("results", name), folder, folder / "notes.txt"]
    assert (folder / "notes.txt").read_bytes() == b"a user's notes\n"


def test_the_study_workflow_runs_its_study_inside_its_own_folder(tmp_path, monkeypatch):
    """``gearpipe study`` writes into study/ of the workflow's staging folder; a failed
    study keeps its exit status and leaves nothing."""
    mod = _load("tip_relief_study")
    seen = []
    monkeypatch.setattr(mod, "gearpipe", lambda args: seen.append(args) or 2)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as exit_:
        mod.main([])
    assert exit_.value.code == 2
    study_out = Path(seen[0][seen[0].index("--out") + 1])
    assert study_out.name == "study"
    assert study_out.parent.name.startswith(".workflow.staging-")
    assert study_out.parent.parent == (tmp_path / "results" / "tip_relief_study").resolve()
    assert sorted(p.name for p in tmp_path.rglob("*")) == []


def test_workflow_and_command_results_of_one_stem_live_side_by_side(tmp_path, monkeypatch,
                                                                      capsys):
    """The case that used to end in a traceback: ``gearpipe`` wrote
    results/spur_pair_assembly_errors/<command>/ before the workflow ran, and after."""
    monkeypatch.chdir(tmp_path)
    assert cli(["geometry", str(SPUR)]) == 0
    before = (Path("results/spur_pair_assembly_errors/geometry/geometry.json")).read_bytes()
    mod = _load("spur_pair_assembly_errors")
    assert run_workflow("workflows/spur_pair_assembly_errors.py", mod.main, []) == 0
    assert cli(["stiffness", str(SPUR)]) == 0
    root = Path("results/spur_pair_assembly_errors")
    assert sorted(p.name for p in root.iterdir()) == ["geometry", "stiffness", "workflow"]
    assert (root / "geometry" / "geometry.json").read_bytes() == before
    assert (root / "workflow" / "friction.png").is_file()
    assert (root / "workflow" / "run.json").is_file()
    assert "error" not in capsys.readouterr().err


def test_the_script_itself_reports_a_clash_in_one_line(tmp_path):
    """Run as ``python workflows/spur_pair_assembly_errors.py``: one line, exit status 1."""
    folder = tmp_path / "results" / "spur_pair_assembly_errors" / "workflow"
    folder.mkdir(parents=True)
    (folder / "notes.txt").write_text("mine")
    proc = subprocess.run([sys.executable, str(WORKFLOWS / "spur_pair_assembly_errors.py")],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 1, proc.stderr
    assert proc.stderr.strip().splitlines() == [
        "spur_pair_assembly_errors.py: error: results/spur_pair_assembly_errors/workflow holds "
        "files that are not one gearpipe result (notes.txt); choose a new or empty folder or "
        "move them away"]
    assert (folder / "notes.txt").read_text() == "mine"
