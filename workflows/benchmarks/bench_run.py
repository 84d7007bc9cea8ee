"""Benchmark: ``gearpipe run`` on the assembly-error paper's pair with FE-enriched excitation.

Targets: cold (empty cache: FE meshes, FE tables of both gears, loaded contact,
dynamics, all figures) under 15 s; warm with one dynamics option changed (the FE
tables and the contact cycle come from the cache) under 3 s, on 2 cores.

Each run is a fresh ``gearpipe run`` process (imports included, as a user sees it), in
one session side by side: cold, warm with the same file, warm with the mesh damping
ratio changed. Prints the wall time, the step breakdown the run records in its
``summary.json`` (geometry, stiffness, contact with FE build, dynamic model, modes,
response, sweep, writing), the rest (interpreter start, imports, run record) and the
peak resident memory of the process, its CPU time (with its children: figures are
drawn in forked processes; CPU time is what a busy machine does not inflate), and the
load average at the start; writes results/benchmarks/run.json.

    python workflows/benchmarks/bench_run.py [--compliance fe2d|fe3d|analytical]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(HERE / "workflows"))

from child_runs import print_steps, timed_child  # noqa: E402
from default_case import DEFAULT  # noqa: E402

from pipeline.io import write_json  # noqa: E402
from pipeline.provenance import library_versions  # noqa: E402


def one_run(config: Path, out: Path, cache: Path) -> dict:
    """``gearpipe run`` in a child process (:func:`child_runs.timed_child`)."""
    return timed_child([sys.executable, "-m", "pipeline.cli", "run", str(config), "--out",
                        str(out), "--cache-dir", str(cache), "--json"],
                       out / "summary.json", key="timing")


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--compliance", default="fe2d", choices=("analytical", "fe2d", "fe3d"))
    args = ap.parse_args(argv)
    text = DEFAULT.replace('compliance = "fe2d"', f'compliance = "{args.compliance}"')
    figures = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        cfg = tmp / "default_case.toml"
        cfg.write_text(text, encoding="utf-8")
        changed = tmp / "default_case_damping.toml"
        changed.write_text(text.replace("damping_ratio = 0.07", "damping_ratio = 0.08"),
                           encoding="utf-8")
        figures["cold"] = one_run(cfg, tmp / "cold", tmp / "cache")
        figures["warm"] = one_run(cfg, tmp / "warm", tmp / "cache")
        figures["warm_dynamics_changed"] = one_run(changed, tmp / "warm2", tmp / "cache")
    cold = figures["cold"]["wall_s"]
    load = os.getloadavg()[0]
    print(f"gearpipe run, {args.compliance} compliance, {os.cpu_count()} CPUs, load average "
          f"{load:.1f} (targets: cold < 15 s, warm with a dynamics change < 3 s)")
    for name, f in figures.items():
        rss = f"{f['peak_rss_MB']:.0f} MB" if f["peak_rss_MB"] else "n/a"
        print(f"  {name:24s} {f['wall_s']:6.2f} s  ({f['wall_s'] / cold:5.3f} of cold), "
              f"CPU {f['cpu_s']:6.2f} s, peak RSS {rss}")
        print_steps(f)
    result = {"compliance": args.compliance, "figures": figures, "cpus": os.cpu_count(),
              "load_average": load,
              "versions": library_versions()}
    out = HERE / "results" / "benchmarks"
    write_json(out / "run.json", result)
    print(f"written to {out / 'run.json'}")
    return result


if __name__ == "__main__":
    main(sys.argv[1:])
