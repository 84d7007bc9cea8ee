"""Timing a command in a fresh child process, as a user runs it (for the benchmarks).

:func:`timed_child` runs the command from the checkout with off-screen plotting and
returns its wall time, the CPU time of it and its children (figures are drawn in forked
processes; CPU time is what a busy machine does not inflate), the step breakdown it
records, the rest (interpreter start, imports, run record), its peak resident memory
and the load average when it ended. :func:`print_steps` prints that breakdown.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def export_revision(rev: str, folder: Path) -> Path:
    """The files of revision ``rev`` of this checkout's repository, in ``folder`` (for
    timing today's code beside the checkout's)."""
    folder.mkdir(parents=True)
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", rev], check=True,
                             capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", str(folder)], input=archive, check=True)
    return folder


def timed_child(command: list[str], timing_file: Path, key: str | None = None,
                root: Path = ROOT) -> dict:
    """Run ``command`` from the checkout ``root`` (its working folder and ``PYTHONPATH``;
    default: this one) and read its step timing from ``timing_file`` (JSON; under ``key``
    when given): ``wall_s``, ``cpu_s``, ``steps_s``, ``from_cache``, ``outside_steps_s``,
    ``peak_rss_MB`` (``None`` when no higher than an earlier child's), ``load_average``."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    before, cpu0 = usage.ru_maxrss, usage.ru_utime + usage.ru_stime
    t0 = time.perf_counter()
    subprocess.run(command, check=True, cwd=root, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL,
                   env={**os.environ, "PYVISTA_OFF_SCREEN": "true", "MPLBACKEND": "Agg",
                        "PYTHONPATH": str(root)})
    wall = time.perf_counter() - t0
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    peak = usage.ru_maxrss  # KiB, max over children
    timing = json.loads(timing_file.read_text())
    if key is not None:
        timing = timing[key]
    return {"wall_s": wall, "cpu_s": usage.ru_utime + usage.ru_stime - cpu0,
            "steps_s": timing["steps_s"], "from_cache": timing["from_cache"],
            "outside_steps_s": wall - timing["total_s"],
            "peak_rss_MB": peak / 1024 if peak > before else None,
            "load_average": os.getloadavg()}


def print_steps(run: dict, digits: int = 3) -> None:
    """The step breakdown of a :func:`timed_child` result, one line a step (s)."""
    for step, s in run["steps_s"].items():
        mark = "  (cache)" if step in run["from_cache"] else ""
        print(f"      {step:42s} {s:7.{digits}f} s{mark}")
    print(f"      {'interpreter, imports, run record':42s} {run['outside_steps_s']:7.{digits}f} s")
