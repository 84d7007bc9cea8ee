"""Benchmark of an optimisation (printed with its breakdown and written to
results/benchmarks/optimise.json).

The example ``workflows/configs/tip_relief_optimise.toml``: 4 parameters (tip relief amount
and length of each gear) over 5 torques, FE 2D tables (one geometry), 20 contact positions,
differential evolution with 20 designs per generation, on a LocalCluster of 2 workers; the
optimum's ``gearpipe run`` is not part of it. ``--maxiter`` overrides the example's
generations. Target: under 60 s on 2 cores.

Breakdown: reading and checking the file (the bounds' gearboxes), starting and closing the
LocalCluster alone, the optimisation (evaluations x torques points), the serial time per
point of the same evaluations in this process (20 points), from which the parallel
efficiency. The machine is shared with other jobs (the load average is printed).

    python workflows/benchmarks/bench_optimise.py [--maxiter N]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import time
import warnings
from pathlib import Path

from pipeline.io import write_json

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "workflows" / "configs" / "tip_relief_optimise.toml"


def bench(maxiter: int | None, workers: int = 2) -> dict:
    from pipeline.study.evaluate import build_fe_tables, evaluate_point
    from pipeline.study.execute import StudyOptions, dask_client
    from pipeline.study.kpis import select_kpis
    from pipeline.study.optimise import optimise_from_file, run_optimisation

    t = time.perf_counter()
    spec = optimise_from_file(EXAMPLE)
    t_read = time.perf_counter() - t
    if maxiter is not None:
        spec = dataclasses.replace(spec, maxiter=maxiter)
    t = time.perf_counter()
    with dask_client(None, workers):
        pass
    t_cluster = time.perf_counter() - t
    t = time.perf_counter()
    res = run_optimisation(spec, StudyOptions(workers=workers, show_progress=False))
    t_opt = time.perf_counter() - t
    points = res.evaluations * len(spec.torques_Nm)
    # serial time per point: the first 4 designs of the record at every torque
    kpis = select_kpis(spec.kpi_names, False)
    docs = [spec.point_document({p.label: h[p.label] for p in spec.parameters}, tq)
            for h in res.history[:4] for tq in spec.torques_Nm]
    fe = build_fe_tables(docs[0])
    t = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for d in docs:
            evaluate_point(d, fe, kpis=kpis)
    per_serial = (time.perf_counter() - t) / len(docs)
    per_par = (t_opt - t_cluster) / points
    return {"file": str(EXAMPLE.relative_to(ROOT)), "parameters": len(spec.parameters),
            "torques": len(spec.torques_Nm), "generations": res.generations,
            "evaluations": res.evaluations, "points": points, "read_check_s": t_read,
            "cluster_start_close_s": t_cluster, "optimisation_s": t_opt,
            "parallel_s_per_point": per_par, "serial_s_per_point": per_serial,
            "parallel_efficiency": per_serial / (workers * per_par),
            "objective": res.objective, "optimum": res.best, "feasible": res.feasible}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--maxiter", type=int, default=None)
    a = ap.parse_args()
    load = os.getloadavg()
    res = bench(a.maxiter)
    res["load_average_1_5_15"] = load
    res["target"] = "4 parameters over 5 torques under 60 s on 2 cores"
    write_json(ROOT / "results" / "benchmarks" / "optimise.json", res)
    print(f"load average at start {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}")
    print(f"read and check {res['read_check_s']:.2f} s, LocalCluster start + close alone "
          f"{res['cluster_start_close_s']:.2f} s")
    print(f"optimisation: {res['parameters']} parameters x {res['torques']} torques, "
          f"{res['evaluations']} evaluations ({res['generations']} generations, "
          f"{res['points']} points) {res['optimisation_s']:.1f} s; "
          f"{res['parallel_s_per_point'] * 1e3:.0f} ms/point on 2 workers, "
          f"{res['serial_s_per_point'] * 1e3:.0f} ms/point serially, parallel efficiency "
          f"{res['parallel_efficiency']:.2f}")
    print(f"optimum {res['optimum']}: weighted TE p-p {res['objective']:.4g} um "
          f"(feasible: {res['feasible']})")


if __name__ == "__main__":
    main()
