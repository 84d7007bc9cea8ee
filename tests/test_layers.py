"""The stage packages form a one-way import graph (the layers contract in pyproject.toml,
checked by import-linter): commands and file writers live in ``pipeline.cli`` at the top,
each stage imports only the stages below it, and the shared modules (``pipeline.io``,
``pipeline.validation``, ...) nothing above them. The check can fail: one upward import
added to a copy of the package breaks the contract."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LINT = Path(sys.executable).with_name("lint-imports")

pytestmark = pytest.mark.skipif(not LINT.is_file(),
                                reason="import-linter not installed (pip install -e .[test])")


def _lint(root: Path) -> subprocess.CompletedProcess:
    return subprocess.run([str(LINT), "--no-cache"], cwd=root, capture_output=True, text=True,
                          env={"PYTHONPATH": str(root), "PATH": "/usr/bin:/bin"}, timeout=300)


def test_the_layers_contract_is_kept():
    result = _lint(ROOT)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "1 kept, 0 broken" in result.stdout


def test_an_upward_import_breaks_it(tmp_path):
    """A copy of the package whose geometry stage imports the dynamics: refused, and the
    message names the two layers."""
    shutil.copytree(ROOT / "pipeline", tmp_path / "pipeline",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    gear = tmp_path / "pipeline" / "geometry" / "gear.py"
    gear.write_text(gear.read_text() + "\nfrom pipeline.dynamics import modal  # noqa\n")
    result = _lint(tmp_path)
    assert result.returncode != 0
    assert "pipeline.geometry is not allowed to import pipeline.dynamics" in result.stdout
