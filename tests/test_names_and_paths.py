"""Absurd names and paths are refused in one line before any work, never a traceback after it.

Table-driven: each row is a gearbox file or an ``--out`` folder a user might give (the
cases of a reliability audit: a 20000-level table header, which tomllib alone parses in
time quadratic in its parts (6.8 s for a 20000-part dotted key, so such keys are refused
before parsing); a 100000-character ``name``; a 300- or 250-character result folder name;
a path beyond PATH_MAX), the exit status and the words of the one-line error. Every row
runs ``gearpipe run`` with its pipeline replaced by a stage that fails the test if called,
so a refusal that comes after any stage would show; and nothing may be written. The
limits are those of Linux (NAME_MAX 255 bytes, PATH_MAX 4096 bytes, POSIX.1-2017
<limits.h>), read with ``os.pathconf`` as the code does.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

import pipeline.cli.run as run_commands
from pipeline.cli import main as cli
from pipeline.io import atomic_write_text
from pipeline.output_folder import LONGEST_FILE_NAME, OutputError, staged_output

ROOT = Path(__file__).resolve().parents[1]
SPUR = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"
NAME_MAX = os.pathconf("/tmp", "PC_NAME_MAX")
PATH_MAX = os.pathconf("/tmp", "PC_PATH_MAX")
LINES = len(SPUR.read_text().splitlines())
STAGING_EXTRA = len(".") + len(".staging-") + 7 + len("-") + 8  # .<name>.staging-<pid>-<8>
LONGEST_TEMP = len(".") + LONGEST_FILE_NAME + len(".tmp-") + 7 + len("-") + 8 + len(".parquet")


def _named(name: str) -> str:
    return re.sub(r"^name = .*$", f'name = "{name}"', SPUR.read_text(), count=1,
                  flags=re.MULTILINE)


def _deep_path(root: Path, length: int) -> Path:
    """A path under ``root`` whose absolute form is exactly ``length`` bytes (names of 200)."""
    path = root.resolve()
    while len(str(path)) + 1 + 200 < length:
        path = path / ("d" * 200)
    return path / ("e" * (length - len(str(path)) - 1))


def _not_a_stage(*args, **kwargs):
    raise AssertionError("a stage ran before the refusal")


BAD = [
    # case, gearbox text, --out under tmp_path (callable), exit status, words
    ("20000-level table header", SPUR.read_text() + "[" + ".".join(["a"] * 20000) + "]\nx = 1\n",
     None, 2, [f"line {LINES + 1}: a key or table header of more than 100 dotted parts",
               "more than 8 levels"]),
    ("9-level table header", SPUR.read_text() + "[" + ".".join(["a"] * 9) + "]\nx = 1\n",
     None, 2, ["nested too deeply at a.a.a.a.a.a.a.a", "more than 8 levels"]),
    ("20000-level array", SPUR.read_text() + "x = " + "[" * 20000 + "]" * 20000 + "\n",
     None, 2, ["nested too deeply", "more than 8 levels"]),
    ("20000-level inline table", SPUR.read_text() + "x = " + "{a = " * 20000 + "1"
     + "}" * 20000 + "\n", None, 2, ["nested too deeply", "more than 8 levels"]),
    ("20000-level dotted key", SPUR.read_text() + ".".join(["a"] * 20000) + " = 1\n", None, 2,
     [f"line {LINES + 1}: a key or table header of more than 100 dotted parts"]),
    ("7-part dotted key under [dynamics.sweep]", SPUR.read_text() + ".".join(["a"] * 7)
     + " = 1\n", None, 2, ["nested too deeply at dynamics.sweep.a.a.a.a.a.a"]),
    ("100000-character name", _named("x" * 100_000), None, 2,
     ["name = \"xxx", "is 100000 characters long", "at most 80"]),
    ("81-character gear name", SPUR.read_text().replace(
        "[pinion]\n", "[pinion]\nname = \"" + "p" * 81 + "\"\n", 1), None, 2,
     ["pinion.name = ", "is 81 characters long", "at most 80"]),
    ("2001-character description", 'description = "' + "d" * 2001 + '"\n' + SPUR.read_text(),
     None, 2, ["description = ", "is 2001 characters long", "at most 2000"]),
    ("300-character --out name", None, lambda t: t / ("c" * 300), 1,
     ["results folder name", "is 300 bytes long", f"at most {NAME_MAX - STAGING_EXTRA}"]),
    ("250-character --out name", None, lambda t: t / ("c" * 250), 1,
     ["is 250 bytes long", f"at most {NAME_MAX - STAGING_EXTRA}",
      f"adds {STAGING_EXTRA} for its staging folder"]),
    (f"{NAME_MAX - STAGING_EXTRA + 1}-character --out name", None,
     lambda t: t / ("c" * (NAME_MAX - STAGING_EXTRA + 1)), 1,
     [f"is {NAME_MAX - STAGING_EXTRA + 1} bytes long"]),
    ("300-character folder inside --out", None, lambda t: t / ("c" * 300) / "run", 1,
     ["is 300 bytes long", f"the file system allows at most {NAME_MAX}"]),
    ("--out one byte beyond PATH_MAX with the staging and temporary names", None,
     lambda t: _deep_path(t, PATH_MAX - 1 - STAGING_EXTRA - 1 - LONGEST_TEMP + 1), 1,
     ["as an absolute path", f"at most {PATH_MAX - 1 - STAGING_EXTRA - 1 - LONGEST_TEMP}"]),
]


@pytest.mark.parametrize(("case", "text", "out", "status", "words"), BAD,
                         ids=[b[0] for b in BAD])
def test_refused_in_one_line_before_any_stage(tmp_path, capsys, monkeypatch, case, text, out,
                                              status, words):
    monkeypatch.setattr(run_commands, "run_stages", _not_a_stage)
    cfg = tmp_path / "in" / "case.toml"
    cfg.parent.mkdir()
    cfg.write_text(text if text is not None else SPUR.read_text(), encoding="utf-8")
    target = out(tmp_path / "o") if out is not None else tmp_path / "o" / "run"
    before = sorted(tmp_path.rglob("*"))
    assert cli(["run", str(cfg), "--out", str(target), "--no-cache"]) == status
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("gearpipe run: error: "), err
    assert len(err[0]) < 400, err[0]
    for w in words:
        assert w in err[0], (w, err[0])
    assert sorted(tmp_path.rglob("*")) == before  # nothing written


def test_the_longest_allowed_folder_name_is_written(tmp_path, capsys):
    """A result folder name of NAME_MAX - 26 bytes (229 on Linux) is written: the staging
    folder beside it reaches exactly NAME_MAX."""
    out = tmp_path / ("c" * (NAME_MAX - STAGING_EXTRA))
    assert cli(["geometry", str(SPUR), "--out", str(out)]) == 0
    assert (out / "geometry.json").is_file() and (out / "run.json").is_file()


def test_the_longest_allowed_path_holds_the_longest_file(tmp_path):
    """At the PATH_MAX limit the check allows, the staging folder takes a file of the longest
    allowed name with the longest suffix (its temporary name included) and is swapped in."""
    allowed = PATH_MAX - 1 - STAGING_EXTRA - 1 - LONGEST_TEMP
    target = _deep_path(tmp_path, allowed)
    assert len(str(target)) == allowed
    name = "f" * (LONGEST_FILE_NAME - len(".parquet")) + ".parquet"
    with staged_output(target) as staging:
        atomic_write_text(staging / name, "x")
    assert (target / name).read_text() == "x"
    with pytest.raises(OutputError, match="as an absolute path"):
        with staged_output(_deep_path(tmp_path, allowed + 1)):
            raise AssertionError("the block ran")


CACHES = [
    ("300-character name", lambda t: t / ("c" * 300)),
    ("under a file", lambda t: t / "blocker" / "meshes"),
    # room for the folder, not for its entries' temporary names (72 bytes below it)
    ("no room for its entries", lambda t: _deep_path(t, PATH_MAX - 1 - 50)),
]


@pytest.mark.parametrize("cache", [c[1] for c in CACHES], ids=[c[0] for c in CACHES])
def test_an_unusable_cache_folder_is_one_warning_and_the_run_goes_on(tmp_path, capsys, cache):
    (tmp_path / "blocker").write_text("a file where a folder should be")
    out = tmp_path / "out"
    assert cli(["run", str(SPUR), "--out", str(out), "--cache-dir", str(cache(tmp_path))]) == 0
    err = [line for line in capsys.readouterr().err.splitlines()
           if "warning" in line and "cache" in line]
    assert len(err) == 1 and err[0].startswith("gearpipe run: warning: cache folder "), err
    assert "running without the cache" in err[0]
    assert (out / "contact_cycle.csv").is_file() and (out / "report.html").is_file()
