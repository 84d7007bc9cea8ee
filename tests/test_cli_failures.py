"""Bad inputs and failed solves end in one line, never a traceback or a hang.

Table-driven: each row is a gearbox file edited the way a user might get it wrong (values
from a reliability audit of the command line), the command, and the words the one-line
error must contain: the key as written, the value in the file's unit, the allowed range
or the estimate that refuses it. Each runs in well under a second: refusals come before
any mesh or solve.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from pipeline.cli import main as cli

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "workflows" / "configs"
SPUR = CONFIGS / "spur_pair_assembly_errors.toml"
GROOVE = CONFIGS / "wind_turbine_sun_groove.toml"
LUMPED = CONFIGS / "lin_parker_planetary.toml"


def _edit(path: Path, pattern: str, value: str) -> str:
    text, n = re.subn(pattern, value, path.read_text(), count=1, flags=re.MULTILINE)
    assert n == 1, pattern
    return text


BAD = [
    ("face width 1e12 mm", "stiffness", SPUR, r"^face_width_mm = .*$", "face_width_mm = 1e12",
     ["pinion.face_width_mm = 1e+12 mm", "[1.5, 750] mm"]),
    ("groove face width 0.001 mm", "groove", GROOVE, r"^face_width_mm = .*$",
     "face_width_mm = 0.001", ["gear.face_width_mm = 0.001 mm", "[7.5, 3750] mm"]),
    ("groove mesh 0.5 mm", "groove", GROOVE, r"^mesh_size_mm = .*$", "mesh_size_mm = 0.5",
     ["billion unknowns", "GiB", "limit is 800 thousand", "groove.mesh_size_mm (now 0.5 mm)"]),
    ("10000 contact slices", "contact", SPUR, r"^\[dynamics\]", "[contact]\nslices = 10000\n"
     "[dynamics]", ["contact.slices = 10000", "[1, 1000]"]),
    ("100000 contact positions", "contact", SPUR, r"^\[dynamics\]",
     "[contact]\npositions = 100000\n[dynamics]", ["contact.positions = 100000", "[2, 10000]"]),
    ("fe 1000 points on 99 teeth", "fe", SPUR, r"^\[dynamics\]",
     "[fe]\npoints = 1000\nteeth = 99\n[dynamics]",
     ["fe.points x fe.teeth = 1000 x 99 = 99000 flank points", "limit is 8000 points"]),
    ("zero mesh frequency", "modes", LUMPED, r"^mesh_frequency_Hz = .*$",
     "mesh_frequency_Hz = 0", ["lumped_model.mesh_frequency_Hz = 0 Hz", "[0.001, 1e+06] Hz"]),
]


@pytest.mark.parametrize(("case", "command", "base", "pattern", "value", "words"), BAD,
                         ids=[b[0] for b in BAD])
def test_bad_input_is_one_line(tmp_path, capsys, case, command, base, pattern, value, words):
    cfg = tmp_path / "bad.toml"
    cfg.write_text(_edit(base, pattern, value))
    out = tmp_path / "out"
    assert cli([command, str(cfg), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"gearpipe {command}: error: "), err
    for w in words:
        assert w in err[0], (w, err[0])
    assert not any(out.glob("*.csv"))


def _raise(exc: BaseException):
    def run(*args, **kwargs):
        raise exc
    return run


def test_failed_contact_solve_is_one_line(tmp_path, capsys, monkeypatch):
    import pipeline.cli.contact as commands
    from pipeline.contact.complementarity import ContactConvergenceError

    monkeypatch.setattr(commands, "analyse_contact", _raise(ContactConvergenceError(
        "position 0.25 of the mesh cycle: residual 3e-4 after 200 iterations")))
    assert cli(["contact", str(SPUR), "--out", str(tmp_path)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["gearpipe contact: error: the computation failed (ContactConvergenceError: "
                   "position 0.25 of the mesh cycle: residual 3e-4 after 200 iterations)"]


def test_singular_model_is_one_line(tmp_path, capsys, monkeypatch):
    from numpy.linalg import LinAlgError

    import pipeline.cli.groove as command

    monkeypatch.setattr(command, "analyse_groove", _raise(LinAlgError("Singular matrix")))
    assert cli(["groove", str(GROOVE), "--out", str(tmp_path)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["gearpipe groove: error: the computation failed (LinAlgError: Singular "
                   "matrix)"]


def test_unwritable_cache_is_one_warning_line_and_the_run_goes_on(tmp_path, capsys):
    blocker = tmp_path / "cache"
    blocker.write_text("a file where the cache folder should be")
    out = tmp_path / "out"
    args = ["fe", str(SPUR), "--out", str(out), "--teeth", "3", "--points", "4",
            "--refinement", "0.5", "--cache-dir", str(blocker / "meshes")]
    assert cli(args) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert len(err) == 1 and err[0].startswith("gearpipe fe: warning: cache folder "), err
    assert "running without the cache" in err[0]
    assert (out / "fe_summary.json").is_file()
