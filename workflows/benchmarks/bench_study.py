"""Benchmark of design studies and of parallel harmonic-balance sweeps (printed and written
to results/benchmarks/study.json).

1. 1000 loaded-contact points of one spur geometry (the assembly-error paper's pair, FE 2D
   whole-gear tables built once and shared through Dask; 20 contact positions; tip relief
   x torque grid 40 x 25) on a LocalCluster of 2 workers, against the same study's first
   100 points serially in one process: wall times, time per point and the parallel
   efficiency (serial time per point / (workers x parallel time per point)). Target: the
   1000 points under 60 s on 2 cores.
2. The 500-point harmonic-balance sweep (H = 20) of the 56-DOF herringbone planetary
   (Xu et al. 2020 case) serially and on the local process pool: same values, the ratio.
   Target: under 5 s on 2 cores.

The machine is shared with other jobs: compare the ratios, not the absolute times.

    python workflows/benchmarks/bench_study.py [--points 1000]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from pipeline.io import write_json

ROOT = Path(__file__).resolve().parents[2]
STUDY = """
name = "bench"
base = "{base}"
[set]
"contact.compliance" = "fe2d"
"contact.positions" = 20
"contact.render" = false
"contact.tip_relief_length_pinion_mm" = 6.2
"contact.tip_relief_length_gear_mm" = 6.2
[[axes]]
keys = ["contact.tip_relief_pinion_um", "contact.tip_relief_gear_um"]
range = [0.0, 24.0]
points = {n1}
[[axes]]
key = "operation.torque_Nm"
range = [200.0, 450.0]
points = {n2}
[kpis]
names = ["te_peak_to_peak_um", "te_order1_um", "mesh_stiffness_mean_N_per_um",
         "mesh_stiffness_ripple_percent"]
"""


def bench_study(points: int) -> dict:
    from pipeline.study.execute import StudyOptions, run_study
    from pipeline.study.spec import study_from_file

    n2 = 25
    n1 = max(2, points // n2)
    tmp = Path(tempfile.mkdtemp(prefix="bench_study_"))
    base = ROOT / "workflows" / "configs" / "spur_pair_assembly_errors.toml"
    f = tmp / "bench.toml"
    f.write_text(STUDY.format(base=base, n1=n1, n2=n2))
    spec = study_from_file(f)
    t = time.perf_counter()
    table, facts = run_study(spec, tmp / "dask", StudyOptions(workers=2, show_progress=False))
    t_par = time.perf_counter() - t
    ns = 100
    f2 = tmp / "serial.toml"
    f2.write_text(STUDY.format(base=base, n1=4, n2=n2))
    t = time.perf_counter()
    run_study(study_from_file(f2), tmp / "serial", StudyOptions(workers=0, show_progress=False))
    t_ser = time.perf_counter() - t
    per_ser, per_par = t_ser / ns, t_par / table.num_rows
    return {"points": table.num_rows, "workers": facts["workers"],
            "fe_geometries": facts["fe_geometries"], "parallel_s": t_par,
            "serial_points": ns, "serial_s": t_ser, "serial_s_per_point": per_ser,
            "parallel_s_per_point": per_par,
            "parallel_efficiency": per_ser / (facts["workers"] * per_par)}


def bench_hb(points: int = 500) -> dict:
    from pipeline.dynamics.models.wind_turbine_planetary import wind_turbine_herringbone_model
    from pipeline.dynamics.sweep import mesh_force_sweep

    s = wind_turbine_herringbone_model(half_coupling=(5e10,) * 4).assembly().assemble()
    f = np.linspace(5000.0 / points, 5000.0, points)
    t = time.perf_counter()
    a = mesh_force_sweep(s, f, n_harmonics=20, executor=None)
    t_ser = time.perf_counter() - t
    t = time.perf_counter()
    b = mesh_force_sweep(s, f, n_harmonics=20, executor="local")
    t_par = time.perf_counter() - t
    return {"points": points, "dof": len(s.dof_names), "serial_s": t_ser, "parallel_s": t_par,
            "workers": os.cpu_count(), "speedup": t_ser / t_par,
            "identical": bool(np.array_equal(a.rms_force, b.rms_force))}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1000)
    a = ap.parse_args()
    load = os.getloadavg()
    hb = bench_hb()
    st = bench_study(a.points)
    res = {"study": st, "hb_sweep": hb, "load_average_1_5_15": load,
           "note": "2 cores shared with other jobs: compare ratios"}
    write_json(ROOT / "results" / "benchmarks" / "study.json", res)
    print(f"load average at start {load[0]:.2f} / {load[1]:.2f} / {load[2]:.2f}")
    print(f"HB sweep, {hb['points']} points, {hb['dof']} DOF: serial {hb['serial_s']:.2f} s, "
          f"{hb['workers']} processes {hb['parallel_s']:.2f} s ({hb['speedup']:.2f}x), "
          f"identical values: {hb['identical']}")
    print(f"study, {st['points']} loaded-contact points ({st['fe_geometries']} FE geometry): "
          f"{st['workers']} Dask workers {st['parallel_s']:.1f} s "
          f"({st['parallel_s_per_point'] * 1e3:.1f} ms/point); serial {st['serial_points']} "
          f"points {st['serial_s']:.1f} s ({st['serial_s_per_point'] * 1e3:.1f} ms/point); "
          f"parallel efficiency {st['parallel_efficiency']:.2f}")


if __name__ == "__main__":
    main()
