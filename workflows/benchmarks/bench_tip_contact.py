"""Benchmark: the demo's FE-enriched loaded contact, cold, with and without tip contact.

Target (the tip-contact issue): the demo's FE-enriched loaded contact (2D FE tables of both
whole gears from an empty cache, then the 60-position contact cycle) under 2 s cold.
Teeth touching beyond the path of contact add a tooth to each gear's table and candidate
points in the tip zones; ``[contact] tip_contact = false`` is today's model, run side by
side in the same session for the ratio (the machine is shared).

Each run is a fresh ``gearpipe run`` of the demo (``workflows/default_case.py``) with an
empty cache, as a user sees it; the run records its step breakdown in ``summary.json``
(its ``loaded contact (fe2d)`` step holds the FE tables and the contact cycle).
``--repeat`` cold runs of each (default 2), the fastest reported beside the median.
Prints the figures with the breakdown and writes ``results/benchmarks/tip_contact.json``.

    python workflows/benchmarks/bench_tip_contact.py [--repeat N]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(HERE / "workflows"))

from bench_run import one_run  # noqa: E402
from child_runs import print_steps  # noqa: E402
from default_case import DEFAULT  # noqa: E402

from pipeline.io import write_json  # noqa: E402
from pipeline.provenance import library_versions  # noqa: E402

CONTACT_STEP = "loaded contact"
"""The run's step that builds the FE tables and solves the contact cycle (``loaded contact
(fe2d)`` in its step breakdown)."""


def _contact_seconds(run: dict) -> float:
    """Seconds of the run's loaded-contact step (FE tables and the contact cycle)."""
    steps = [s for name, s in run["steps_s"].items() if name.startswith(CONTACT_STEP)]
    if len(steps) != 1:
        raise SystemExit(f"the run's steps {sorted(run['steps_s'])} hold no single "
                         f"'{CONTACT_STEP} ...' step")
    return steps[0]


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    runs: dict[str, list[dict]] = {"tip_contact": [], "nominal_path": []}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for name, flag in (("nominal_path", "false"), ("tip_contact", "true")):
            cfg = tmp / f"{name}.toml"
            cfg.write_text(DEFAULT.replace("[contact]\n", f"[contact]\ntip_contact = {flag}\n",
                                           1), encoding="utf-8")
        for i in range(args.repeat):  # interleaved: both see the same machine load
            for name in runs:
                runs[name].append(one_run(tmp / f"{name}.toml", tmp / f"{name}{i}",
                                          tmp / f"cache_{name}{i}"))
    best = {n: min(r, key=_contact_seconds) for n, r in runs.items()}
    contact = {n: _contact_seconds(b) for n, b in best.items()}
    median = {n: statistics.median(_contact_seconds(x) for x in r) for n, r in runs.items()}
    load = os.getloadavg()[0]
    print(f"demo, FE-enriched loaded contact, cold, {os.cpu_count()} CPUs, load average "
          f"{load:.1f} (target: contact step < 2 s cold with tip contact)")
    for name, b in best.items():
        print(f"  {name:14s} contact step {contact[name]:6.3f} s (median of {args.repeat}: "
              f"{median[name]:6.3f} s), whole run {b['wall_s']:6.2f} s, CPU {b['cpu_s']:6.2f} s")
        print_steps(b)
    ratio = contact["tip_contact"] / contact["nominal_path"]
    print(f"  tip contact / nominal path, contact step: {ratio:.3f}")
    result = {"contact_step_s": contact, "contact_step_median_s": median,
              "ratio_tip_over_nominal": ratio, "best": best, "runs": runs,
              "cpus": os.cpu_count(), "load_average": load, "versions": library_versions()}
    out = HERE / "results" / "benchmarks"
    write_json(out / "tip_contact.json", result)
    print(f"written to {out / 'tip_contact.json'}")
    return result


if __name__ == "__main__":
    main(sys.argv[1:])
