"""Benchmark: ``gearpipe run`` on the demo's pair, this checkout side by side with a baseline.

Targets: cold (empty cache: FE meshes, FE tables of both gears, loaded contact,
dynamics, all figures and the report) under 4 s; warm with one dynamics option changed
(the FE tables and the contact cycle come from the cache) under 3 s, on 2 cores.

Each run is a fresh ``gearpipe run`` process (imports included, as a user sees it). The
baseline revision (``--baseline``, default ``b847466``) is exported with ``git archive``
into a temporary folder and run with the same interpreter; cold runs of both alternate
(``--repeat`` of each, the order swapped every round, each with a fresh cache folder),
then each side runs warm with the same file and warm with the mesh damping ratio changed.
Prints per run the wall time, the step breakdown the run records in its ``summary.json``
(geometry, stiffness, contact with FE build, shafts, load distribution, dynamics, writing,
reports), the rest (interpreter start, imports, run record), the CPU time of the process
and its children (figures are drawn in forked processes; CPU time is what a busy machine
does not inflate), the peak resident memory and the load average; then the medians side by
side with the ratio this checkout / baseline, and whether both wrote the same files and
the same numbers (``summary.json`` apart from its timing). Writes
results/benchmarks/run.json.

    python workflows/benchmarks/bench_run.py [--compliance fe2d|fe3d|analytical]
        [--baseline REV | --no-baseline] [--repeat N]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(HERE / "workflows"))

from child_runs import export_revision, print_steps, timed_child  # noqa: E402
from default_case import DEFAULT  # noqa: E402

from pipeline.io import write_json  # noqa: E402
from pipeline.provenance import library_versions  # noqa: E402

BASELINE = "b847466"
"""The revision the run is compared with by default (the main branch before the writing side
was made faster)."""


def one_run(config: Path, out: Path, cache: Path, root: Path = HERE) -> dict:
    """``gearpipe run`` of the checkout ``root`` in a child process
    (:func:`child_runs.timed_child`)."""
    return timed_child([sys.executable, "-m", "pipeline.cli", "run", str(config), "--out",
                        str(out), "--cache-dir", str(cache), "--json"],
                       out / "summary.json", key="timing", root=root)


def _without_timing(summary: dict) -> dict:
    return {k: v for k, v in summary.items() if k != "timing"}


def same_output(a: Path, b: Path) -> dict:
    """Whether two run folders hold the same files and ``summary.json`` the same numbers
    (apart from its ``timing``)."""
    files_a, files_b = (sorted(p.name for p in f.iterdir()) for f in (a, b))
    sums = [_without_timing(json.loads((f / "summary.json").read_text())) for f in (a, b)]
    return {"same_files": files_a == files_b,
            "only_in_this_checkout": sorted(set(files_a) - set(files_b)),
            "only_in_baseline": sorted(set(files_b) - set(files_a)),
            "same_summary_numbers": sums[0] == sums[1]}


def _median(runs: list[dict], key: str) -> float:
    return statistics.median(r[key] for r in runs)


def _print_run(name: str, f: dict, cold: float) -> None:
    rss = f"{f['peak_rss_MB']:.0f} MB" if f["peak_rss_MB"] else "n/a"
    print(f"  {name:28s} {f['wall_s']:6.2f} s  ({f['wall_s'] / cold:5.3f} of cold), "
          f"CPU {f['cpu_s']:6.2f} s, peak RSS {rss}, load average "
          f"{f['load_average'][0]:.1f}")
    print_steps(f)


def _print_side_by_side(sides: dict[str, list[dict]]) -> None:
    """Median cold wall and CPU time and the median of every step, side by side."""
    names = list(sides)
    print(f"  {'cold, median of ' + str(len(sides[names[0]])):42s} "
          + " ".join(f"{n:>14s}" for n in names) + "   ratio")
    for key, label in (("wall_s", "wall"), ("cpu_s", "CPU (with children)"),
                       ("outside_steps_s", "interpreter, imports, run record")):
        vals = [_median(sides[n], key) for n in names]
        ratio = f"   {vals[0] / vals[1]:5.3f}" if len(vals) == 2 and vals[1] else ""
        print(f"  {label:42s} " + " ".join(f"{v:12.3f} s" for v in vals) + ratio)
    steps: list[str] = []
    for runs in sides.values():
        steps += [s for s in runs[0]["steps_s"] if s not in steps]
    for step in steps:
        vals = [statistics.median(r["steps_s"].get(step, 0.0) for r in sides[n])
                for n in names]
        print(f"  {step:42s} " + " ".join(f"{v:12.3f} s" for v in vals))


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--compliance", default="fe2d", choices=("analytical", "fe2d", "fe3d"))
    ap.add_argument("--baseline", default=BASELINE,
                    help=f"revision to run side by side (default: {BASELINE})")
    ap.add_argument("--no-baseline", action="store_true", help="time this checkout only")
    ap.add_argument("--repeat", type=int, default=3, help="cold runs of each (default: 3)")
    args = ap.parse_args(argv)
    if args.repeat < 1:
        ap.error(f"--repeat: {args.repeat} runs; at least 1")
    text = DEFAULT.replace('compliance = "fe2d"', f'compliance = "{args.compliance}"')
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        roots = {"this checkout": HERE}
        if not args.no_baseline:
            roots[f"baseline {args.baseline}"] = export_revision(args.baseline,
                                                                 tmp / "baseline")
        cfg = tmp / "default_case.toml"
        cfg.write_text(text, encoding="utf-8")
        changed = tmp / "default_case_damping.toml"
        changed.write_text(text.replace("damping_ratio = 0.07", "damping_ratio = 0.08"),
                           encoding="utf-8")
        cold: dict[str, list[dict]] = {name: [] for name in roots}
        order = list(roots)
        for i in range(args.repeat):
            for name in (order if i % 2 == 0 else order[::-1]):
                side = f"s{order.index(name)}"
                cold[name].append(one_run(cfg, tmp / f"{side}-cold{i}",
                                          tmp / f"{side}-cache{i}", roots[name]))
        warm: dict[str, dict[str, dict]] = {}
        for name, root in roots.items():
            side, last = f"s{order.index(name)}", args.repeat - 1
            cache = tmp / f"{side}-cache{last}"
            warm[name] = {"warm": one_run(cfg, tmp / f"{side}-warm", cache, root),
                          "warm_dynamics_changed": one_run(changed, tmp / f"{side}-warm2",
                                                           cache, root)}
        compared = (same_output(tmp / "s0-cold0", tmp / "s1-cold0")
                    if len(roots) == 2 else None)
    load = os.getloadavg()
    print(f"gearpipe run, {args.compliance} compliance, {os.cpu_count()} CPUs, load average "
          f"{load[0]:.1f} {load[1]:.1f} {load[2]:.1f} at the end (targets: cold < 4 s, warm "
          "with a dynamics change < 3 s)")
    for name in roots:
        print(f"{name}:")
        c = _median(cold[name], "wall_s")
        for i, f in enumerate(cold[name]):
            _print_run(f"cold {i + 1}", f, c)
        for w, f in warm[name].items():
            _print_run(w, f, c)
    _print_side_by_side(cold)
    if compared is not None:
        print(f"  same files: {compared['same_files']}, same numbers in summary.json: "
              f"{compared['same_summary_numbers']}")
    result = {"compliance": args.compliance, "cpus": os.cpu_count(), "load_average": load,
              "baseline": None if args.no_baseline else args.baseline,
              "cold": cold, "warm": warm, "compared_with_baseline": compared,
              "median_cold_wall_s": {n: _median(r, "wall_s") for n, r in cold.items()},
              "versions": library_versions()}
    out = HERE / "results" / "benchmarks"
    write_json(out / "run.json", result)
    print(f"written to {out / 'run.json'}")
    return result


if __name__ == "__main__":
    main(sys.argv[1:])
