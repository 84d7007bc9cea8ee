"""A ``gearpipe run`` killed (SIGKILL) while it writes leaves one complete result.

The run is a subprocess that sends itself SIGKILL at an exact point: in the middle of
writing a cache file (its temporary file written, not yet renamed), after the 3rd and
the 15th file of the result folder, and in the middle of the portable two-rename swap
(previous result renamed away, new one not yet in). After each kill the output folder
holds the previous complete result (or, after the swap kill, nothing visible until the
next run puts the previous result back); the next uninterrupted run leaves no hidden
staging folder or temporary file in the results or the cache, and its files are
bit-identical to those of an uninterrupted run (``run.json`` differs in its times,
``summary.json`` in its ``timing`` section, and the report in its two clock times and
the libraries the process loaded, only).
The figures of a rerun come from the figure cache; the second case checks that figures
drawn afresh are bit-identical as well. Both are marked slow (five and three processes of
``gearpipe run``); the default suite covers the same clean-up with simulated leftovers
(``test_output_folder.py``).
"""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from gearsets import SMALL

ROOT = Path(__file__).resolve().parents[1]

# Runs gearpipe and kills itself at the point named by the first argument.
DRIVER = r"""
import os, signal, sys
import pipeline.output_folder as of

point, rest = sys.argv[1], sys.argv[2:]
replace, rename, count = os.replace, os.rename, [0]

def die():
    os.kill(os.getpid(), signal.SIGKILL)

def patched_replace(src, dst):
    if point == "cache" and "contactcycle-" in str(dst):
        die()  # the cache file's temporary is complete, its rename never happens
    replace(src, dst)
    if point.startswith("files:") and ".staging-" in str(dst):
        count[0] += 1
        if count[0] == int(point[6:]):
            die()

def patched_rename(src, dst):
    rename(src, dst)
    if point == "swap" and ".old-" in str(dst):
        die()  # the previous result is away, the new one not yet in

os.replace, os.rename = patched_replace, patched_rename
if point == "swap":
    of.exchange = lambda a, b: False  # the portable swap: two renames
from pipeline.cli import main
sys.exit(main(rest))
"""


def _gearpipe(point: str, cfg: Path, out: Path, cache: Path) -> int:
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg",
           "PYVISTA_OFF_SCREEN": "true", "OMP_NUM_THREADS": "1"}
    proc = subprocess.run([sys.executable, "-c", DRIVER, point, "run", str(cfg), "--out",
                           str(out), "--cache-dir", str(cache), "--json"],
                          env=env, capture_output=True, timeout=300, check=False)
    return proc.returncode


# the report's provenance rows that differ between two runs of the same inputs: its clock
# times, and what the process happened to load (the sparse Cholesky and the BLAS/OpenMP
# libraries: a rerun that reads its FE tables from the cache loads neither solver nor OpenMP;
# pipeline.provenance records them without hashing them for that reason)
_REPORT_TIMES = ("time_utc", "run_time", "version_sparse_cholesky", "version_blas")


def _files(folder: Path) -> dict[str, bytes]:
    """Every file's bytes, but ``run.json``, the step timings of ``summary.json`` and the
    report's clock times (written at, run time, "written in ... s") and loaded libraries."""
    files = {p.name: p.read_bytes() for p in sorted(folder.iterdir()) if p.name != "run.json"}
    summary = json.loads(files.pop("summary.json"))
    summary.pop("timing")
    files["summary.json"] = json.dumps(summary, sort_keys=True).encode()
    if "report.json" in files:
        report = json.loads(files["report.json"])
        for key in _REPORT_TIMES:
            report["sections"]["provenance"]["quantities"].pop(key)
        files["report.json"] = json.dumps(report, sort_keys=True).encode()
        rows = files["report.csv"].decode().splitlines()
        files["report.csv"] = "\n".join(
            r for r in rows if not any(r.startswith(f"provenance,{k},") for k in _REPORT_TIMES)
        ).encode()
        html = files["report.html"].decode()
        html = re.sub(r'(data-key="provenance\.(?:' + "|".join(_REPORT_TIMES) + r')">)[^<]*',
                      r"\1", html)
        files["report.html"] = re.sub(r"written in [0-9.]+ s", "", html).encode()
    return files


def _temps(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob(".*"))


@pytest.mark.slow  # 14 s of CPU in five processes; 30-55 s on the shared 2-core machine
def test_a_killed_run_leaves_one_complete_result(tmp_path):
    cfg = tmp_path / "small.toml"
    cfg.write_text(SMALL, encoding="utf-8")
    out, cache = tmp_path / "results" / "run", tmp_path / "cache"
    killed = -signal.SIGKILL

    assert _gearpipe("cache", cfg, out, cache) == killed
    assert _temps(cache) and not out.exists()  # a temporary cache file was left behind

    assert _gearpipe("none", cfg, out, cache) == 0
    assert _temps(cache) == []  # the next write into the cache removed it
    first, record = _files(out), json.loads((out / "run.json").read_text())
    assert sorted(record["outputs"]) == sorted(first)

    assert _gearpipe("files:3", cfg, out, cache) == killed
    assert _files(out) == first  # the previous complete result, untouched
    assert [p.name for p in out.parent.iterdir() if ".staging-" in p.name]

    assert _gearpipe("swap", cfg, out, cache) == killed
    assert not out.exists() and [p for p in out.parent.iterdir() if ".old-" in p.name]

    assert _gearpipe("none", cfg, out, cache) == 0
    assert sorted(os.listdir(out.parent)) == ["run"]  # no staging or old folders left
    assert _temps(out) == [] and _temps(cache) == []
    assert _files(out) == first  # bit-identical to the uninterrupted run
    again = json.loads((out / "run.json").read_text())
    assert again["hash"] == record["hash"] and again["outputs"] == record["outputs"]


@pytest.mark.slow
def test_a_killed_run_without_cache_reruns_bit_identically(tmp_path):
    """Killed after 15 files, rerun without any cache: the figures drawn afresh (matplotlib
    Agg, pyvista off-screen) are bit-identical to those of an uninterrupted run."""
    cfg = tmp_path / "small.toml"
    cfg.write_text(SMALL, encoding="utf-8")
    out, reference = tmp_path / "out", tmp_path / "reference"
    assert _gearpipe("none", cfg, reference, tmp_path / "c1") == 0
    assert _gearpipe("files:15", cfg, out, tmp_path / "c2") == -signal.SIGKILL
    assert not out.exists()
    assert _gearpipe("none", cfg, out, tmp_path / "c3") == 0
    assert _files(out) == _files(reference) and sorted(os.listdir(tmp_path)) == [
        "c1", "c2", "c3", "out", "reference", "small.toml"]


@pytest.fixture(autouse=True)
def _needs_sigkill():
    if not hasattr(signal, "SIGKILL"):
        pytest.skip("no SIGKILL on this platform")
