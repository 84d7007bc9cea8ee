"""Benchmark: the herringbone groove study (workflows/herringbone_groove_study.py), cold, warm.

Targets (issue 13): the whole study (groove FE for 7 geometries - 2 to fit, 5 for K_1..K_5 -,
the herringbone contact of 11 cases and a slide search, the Fig. 9 sweeps of 5 grooves,
6 load maps and the figures) cold under 5 minutes on 2 cores; from the cache under 30 s.

Each run is a fresh process (interpreter and imports included, as a user sees it) with
its own empty cache folder for the cold run, the same folder for the warm run. Prints
the wall time, the step breakdown the study records (``timing.json``), the rest
(interpreter, imports, run record) and the peak resident memory; writes
results/benchmarks/herringbone_study.json. The machine is shared: quote ratios and the
load average printed with the figures.

    python workflows/benchmarks/bench_herringbone_study.py
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

from child_runs import print_steps, timed_child

from pipeline.io import write_json
from pipeline.provenance import library_versions

HERE = Path(__file__).resolve().parents[2]

STUDY = HERE / "workflows" / "herringbone_groove_study.py"


def one_run(out: Path, cache: Path) -> dict:
    """The study in a child process (:func:`child_runs.timed_child`)."""
    return timed_child([sys.executable, str(STUDY), "--out", str(out), "--cache-dir",
                        str(cache)], out / "timing.json")


def main(argv: list[str] | None = None) -> dict:
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0]).parse_args(argv)
    figures = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        figures["cold"] = one_run(tmp / "cold", tmp / "cache")
        figures["warm"] = one_run(tmp / "warm", tmp / "cache")
    cold = figures["cold"]["wall_s"]
    print(f"herringbone groove study, {os.cpu_count()} CPUs (targets: cold < 300 s, "
          "warm < 30 s)")
    for name, f in figures.items():
        rss = f"{f['peak_rss_MB']:.0f} MB" if f["peak_rss_MB"] else "n/a"
        la = ", ".join(f"{x:.1f}" for x in f["load_average"])
        print(f"  {name:6s} {f['wall_s']:7.1f} s ({f['wall_s'] / cold:5.3f} of cold), "
              f"peak RSS {rss}, load average after {la}")
        print_steps(f, digits=2)
    result = {"figures": figures, "cpus": os.cpu_count(), "versions": library_versions()}
    out = HERE / "results" / "benchmarks"
    write_json(out / "herringbone_study.json", result)
    print(f"written to {out / 'herringbone_study.json'}")
    return result


if __name__ == "__main__":
    main(sys.argv[1:])
