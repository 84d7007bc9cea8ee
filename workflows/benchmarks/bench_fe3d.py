"""Benchmark: the 3D FE tables (``[contact] compliance = "fe3d"``), this checkout side by
side with a baseline revision.

Cases, each at the default ``[fe]`` settings (refinement 1, 8 profile points, face points
about one patch half-width apart):

* the helical z 30/30 pair of tests/test_fem_source3d.py (m_n 3 mm, beta 15 deg, b 12 mm,
  bore 30 mm): both gears' tables cold (fresh cache), then warm (read back), and the loaded
  contact at P = 4 kN over 30 positions (mesh stiffness mean, min, max, TE p-p);
* ``--full`` adds the pair of Yang et al. (2026) (z 31/104, m_n 7.35 mm, b 130 mm;
  workflows/configs/traction_helical_pair.toml): its tables cold, and ``gearpipe contact``
  on it with ``compliance = "fe3d"`` cold, as a user runs it (its contact.json gives the
  figures compared).

Every measurement is a fresh child process of the checkout, run with ``OMP_NUM_THREADS``
set to ``--threads`` (default 2: what MKL takes on a 2-core machine when the variable is
unset, as for a user; a parent's setting, such as one thread in a test runner, is not
inherited), timed (imports not counted for
the tables, counted for the command) with its own peak resident memory (``wait4``); the
baseline revision (``--baseline``, default the main branch before the one-tooth tables,
``b847466``) is exported with ``git archive`` and run with the same interpreter, the two
alternating (``--repeat`` rounds, the order swapped every round). Prints each run's
breakdown (mesh, assembly, factorisation, solves, near field per gear, the unknowns, whether
a table came from a mirror image's solve), the medians side by side with the ratio this
checkout / baseline and the figures' relative differences; writes
results/benchmarks/fe3d.json (``--full``: fe3d_full.json, ``--only-contact``:
fe3d_contact.json). Targets: z 30/30 tables < 5 s; traction pair tables < 20 s
and < 1 GB, ``gearpipe contact`` < 30 s; mesh stiffness and TE p-p within 0.5 % of the
baseline's. Run it alone: the machine's other jobs slow both sides, not the ratio.

    python workflows/benchmarks/bench_fe3d.py [--full] [--baseline REV | --no-baseline]
        [--repeat N] [--threads N]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(HERE / "workflows"))

from child_runs import export_revision  # noqa: E402

from pipeline.io import write_json  # noqa: E402
from pipeline.provenance import library_versions  # noqa: E402

BASELINE = "b847466"
"""The revision compared with by default (the main branch before the one-tooth tables)."""
TRACTION = HERE / "workflows" / "configs" / "traction_helical_pair.toml"
FIGURES = ("mesh_stiffness_mean_N_per_m", "mesh_stiffness_min_N_per_m",
           "mesh_stiffness_max_N_per_m", "transmission_error_peak_to_peak_m")

# The child: only calls both revisions have (FE3DCompliance.build, loaded_mesh_cycle).
TABLES = r"""
import json, math, resource, sys, time
import numpy as np
from pipeline.cache.folder import Cache
from pipeline.contact import FE3DCompliance, FE3DSettings
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.geometry import GearPair, GearSpec
case, cache = sys.argv[1], Cache(sys.argv[2])
if case == "z30":
    kw = dict(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.03,
              face_width=12e-3, helix_angle=math.radians(15))
    pair = GearPair(GearSpec(hand="right", name="pinion", **kw),
                    GearSpec(hand="left", name="gear", **kw))
else:
    from pipeline.config import load_gearbox
    pair = load_gearbox(sys.argv[3]).pair
t0 = time.perf_counter()
src = FE3DCompliance.build(pair, FE3DSettings(), cache=cache)
cold = time.perf_counter() - t0
t0 = time.perf_counter()
FE3DCompliance.build(pair, FE3DSettings(), cache=cache)
out = {"tables_cold_s": cold, "tables_warm_s": time.perf_counter() - t0,
       "peak_rss_GiB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20}
for g in ("pinion", "gear"):
    info = getattr(src, g + "_table").info
    out[g] = {"dof": info["dof"], "condensed": info.get("condensed_dof", 0),
              "cached": info["cached"], "timings_s": info["timings_s"],
              "mirrored": info.get("mirrored", False)}
if case == "z30":
    cyc = loaded_mesh_cycle(src, 4000.0, positions=30)
    k, te = cyc.mesh_stiffness, cyc.transmission_error
    out.update({"mesh_stiffness_mean_N_per_m": k.mean(), "mesh_stiffness_min_N_per_m": k.min(),
                "mesh_stiffness_max_N_per_m": k.max(),
                "transmission_error_peak_to_peak_m": float(np.ptp(te))})
print(json.dumps(out, default=float))
"""


def child(command: list[str], root: Path, logs: Path, threads: int
          ) -> tuple[float, float, str]:
    """Run ``command`` from checkout ``root`` with ``OMP_NUM_THREADS = threads``: (wall s,
    its own peak RSS in GiB, stdout).
    stdout and stderr go to files in ``logs`` (no pipe to fill); ``wait4`` reaps the child
    and gives its resource use."""
    logs.mkdir(parents=True, exist_ok=True)
    out_path, err_path = logs / "stdout.txt", logs / "stderr.txt"
    with out_path.open("w") as out, err_path.open("w") as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen(command, cwd=root, stdout=out, stderr=err,
                                env={**os.environ, "PYTHONPATH": str(root), "MPLBACKEND": "Agg",
                                     "PYVISTA_OFF_SCREEN": "true",
                                     "OMP_NUM_THREADS": str(threads)})
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t0
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode:
        raise RuntimeError(f"{' '.join(map(str, command[:4]))} failed in {root}:\n"
                           f"{err_path.read_text()[-2000:]}")
    return wall, usage.ru_maxrss / 2**20, out_path.read_text()


def tables_run(case: str, root: Path, tmp: Path, threads: int) -> dict:
    """Both gears' tables of ``case`` ("z30" or "traction") cold and warm in one child."""
    wall, rss, out = child([sys.executable, "-c", TABLES, case, str(tmp / "cache"),
                            str(TRACTION)], root, tmp / "logs", threads)
    return {**json.loads(out), "process_s": wall, "process_peak_rss_GiB": rss}


def contact_run(root: Path, tmp: Path, threads: int) -> dict:
    """``gearpipe contact`` on the traction pair with ``compliance = "fe3d"``, cold."""
    tmp.mkdir(parents=True, exist_ok=True)
    config = tmp / "traction_fe3d.toml"
    config.write_text(TRACTION.read_text(encoding="utf-8").replace(
        "[stiffness]", '[contact]\ncompliance = "fe3d"\n\n[stiffness]', 1), encoding="utf-8")
    wall, rss, _ = child([sys.executable, "-m", "pipeline.cli", "contact", str(config),
                          "--out", str(tmp / "out"), "--cache-dir", str(tmp / "cache")],
                         root, tmp / "logs", threads)
    figures = json.loads((tmp / "out" / "contact.json").read_text())
    return {"contact_s": wall, "peak_rss_GiB": rss, **{k: figures[k] for k in FIGURES}}


def _print_tables(name: str, r: dict) -> None:
    print(f"    {name}: tables cold {r['tables_cold_s']:.2f} s, warm {r['tables_warm_s']:.3f} s, "
          f"peak RSS {r['peak_rss_GiB']:.2f} GiB")
    for g in ("pinion", "gear"):
        info = r[g]
        how = ("from the pinion's mirror image" if info["mirrored"] and info["cached"]
               else "read back" if info["cached"] else "solved")
        far = (f" ({info['condensed']} of them condensed before the factorisation)"
               if info.get("condensed") else "")
        print(f"      {g}: {info['dof']} unknowns{far}, {how}: " + ", ".join(
            f"{k} {v:.2f} s" for k, v in info["timings_s"].items()))


def _median(runs: list[dict], key: str) -> float:
    return statistics.median(r[key] for r in runs)


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--full", action="store_true", help="add the traction pair (minutes)")
    ap.add_argument("--baseline", default=BASELINE, help="revision to compare with")
    ap.add_argument("--no-baseline", action="store_true", help="time this checkout only")
    ap.add_argument("--repeat", type=int, default=2, help="rounds of cold runs (z 30/30)")
    ap.add_argument("--only-contact", action="store_true",
                    help="with --full: the traction pair's gearpipe contact only")
    ap.add_argument("--threads", type=int, default=2,
                    help="OMP_NUM_THREADS of the timed children (default 2)")
    args = ap.parse_args(argv)
    if args.threads < 1:
        ap.error(f"--threads = {args.threads}: must be >= 1")
    cases = [] if args.only_contact else [("z30", "tables", args.repeat)]
    if args.full:
        cases += [] if args.only_contact else [("traction", "tables", 1)]
        cases.append(("traction", "contact", 1))
    results: dict = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        roots = {"this checkout": HERE}
        if not args.no_baseline:
            roots[f"baseline {args.baseline}"] = export_revision(args.baseline, tmp / "base")
        for case, kind, rounds in cases:
            runs: dict[str, list[dict]] = {name: [] for name in roots}
            for i in range(rounds):
                order = list(roots) if i % 2 == 0 else list(roots)[::-1]
                for name in order:
                    work = tmp / f"{case}-{kind}-{i}-{name.split()[0]}"
                    run = (tables_run(case, roots[name], work, args.threads)
                           if kind == "tables" else contact_run(roots[name], work, args.threads))
                    run["load_average"] = os.getloadavg()
                    runs[name].append(run)
                    print(f"{case} {kind}, {name}, round {i + 1}: load "
                          f"{run['load_average'][0]:.1f}", flush=True)
                    if kind == "tables":
                        _print_tables(name, run)
                    else:
                        print(f"    gearpipe contact {run['contact_s']:.1f} s, peak RSS "
                              f"{run['peak_rss_GiB']:.2f} GiB")
            results[f"{case} {kind}"] = runs
    summary = _summary(results)
    out = {"runs": results, "summary": summary, "baseline": None if args.no_baseline
           else args.baseline, "threads": args.threads, "versions": library_versions()}
    name = "fe3d" + ("_contact" if args.only_contact else "_full" if args.full else "")
    write_json(HERE / "results" / "benchmarks" / f"{name}.json", out)
    return out


def _summary(results: dict) -> dict:
    """Medians side by side, the ratio this checkout / baseline and the figures' changes."""
    summary = {}
    print("\nmedians (this checkout | baseline | ratio)")
    for label, runs in results.items():
        names = list(runs)
        key = "tables_cold_s" if label.endswith("tables") else "contact_s"
        row = {"time_s": [_median(runs[n], key) for n in names],
               "peak_rss_GiB": [_median(runs[n], "peak_rss_GiB") for n in names]}
        figures = [k for k in FIGURES if k in runs[names[0]][0]]
        if len(names) == 2:
            row["ratio"] = row["time_s"][0] / row["time_s"][1]
            row["figures_change_percent"] = {
                k: 100 * (runs[names[0]][0][k] / runs[names[1]][0][k] - 1) for k in figures}
        summary[label] = row
        print(f"  {label}: {' | '.join(f'{t:.2f} s' for t in row['time_s'])}"
              + (f" | {row['ratio']:.3f}" if "ratio" in row else "")
              + f"; peak RSS {' | '.join(f'{m:.2f}' for m in row['peak_rss_GiB'])} GiB")
        for k, v in row.get("figures_change_percent", {}).items():
            print(f"    {k}: {v:+.3f} %")
    return summary


if __name__ == "__main__":
    main()
