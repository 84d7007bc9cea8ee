"""The README's Python API example runs as written (gearbox file -> dynamic response)."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_readme_python_example(capsys, monkeypatch):
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Python API", 1)[1]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(ROOT)
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    numbers = {k: float(v) for k, v in re.findall(r"(stiffness|TE|mode|force) ([\d.e+]+)", out)}
    # the mean analytical stiffness of this pair (tests/test_cli_workflows.py: stiffness JSON)
    # lies between ISO 6336's 14-20 N/(mm um) x 20 mm; a loaded TE of a few um; the first
    # elastic mode of the 6-DOF model is the bearing mode near 780 Hz
    assert 2.8e8 < numbers["stiffness"] < 4.0e8
    assert 1.0 < numbers["TE"] < 50.0
    assert 700.0 < numbers["mode"] < 900.0
    assert numbers["force"] > 0.0
