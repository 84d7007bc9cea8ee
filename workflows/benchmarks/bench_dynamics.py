"""Benchmarks of the dynamic solvers (figures printed and written to results/benchmarks/).

1. Spur pair (seed 001, 6 DOF): 200 mesh periods of time response (target < 1 s).
2. Herringbone planetary (seed 002 case, 4 planets, 56 DOF): a 500-point harmonic
   balance sweep over 0-5000 Hz on all cores (target < 60 s on 2 cores).
3. Harmonic-balance sweep against a time-integration sweep (continuation) at the
   same points: time per point and error of each against the exact Floquet
   steady state of the finest segment model.

    python workflows/benchmarks/bench_dynamics.py [--points 500]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

from pipeline.dynamics.excitation import rectangular_mesh_stiffness
from pipeline.dynamics.integrate import integrate
from pipeline.dynamics.models.seed002_case import seed002_model
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.dynamics.sweep import mesh_force_sweep
from pipeline.io import write_json


def bench_spur() -> dict:
    s = SpurPairModel(rectangular_mesh_stiffness(2.3e8, 3.9e8, 1.73, 360)).assembly().assemble()
    integrate(s, 2)  # warm-up (imports)
    t = time.perf_counter()
    r = integrate(s, 200)
    dt = time.perf_counter() - t
    return {"spur_200_periods_s": dt, "samples": int(r.time.size)}


def bench_sweep(points: int) -> dict:
    model = seed002_model(half_coupling=(5e10, 5e10, 5e10, 5e10))
    s = model.assembly().assemble()
    f = np.linspace(5000.0 / points, 5000.0, points)
    t = time.perf_counter()
    sw = mesh_force_sweep(s, f, n_harmonics=20, executor="local")
    dt = time.perf_counter() - t
    return {
        "hb_sweep_points": points,
        "hb_sweep_s": dt,
        "dof": len(s.dof_names),
        "independent_dof": s.n,
        "workers": os.cpu_count(),
        "main_peak_Hz": float(sw.peaks("s-p1L", 1)[0]),
    }


def bench_hb_vs_time() -> dict:
    s = seed002_model(half_coupling=(5e10, 5e10, 5e10, 5e10)).assembly().assemble()
    f = np.linspace(300.0, 4800.0, 8)
    ref = mesh_force_sweep(s, f, method="floquet", segments=1440, executor=None)
    out = {}
    for label, kw in (
        ("hb_H20", dict(method="harmonic_balance", n_harmonics=20)),
        ("time_180seg", dict(method="time", segments=180, tol=1e-6, max_periods=50000)),
    ):
        t = time.perf_counter()
        sw = mesh_force_sweep(s, f, executor=None, **kw)
        dt = time.perf_counter() - t
        err = np.abs(sw.rms_force - ref.rms_force).max() / np.abs(ref.rms_force).max()
        out[label] = {"s_per_point": dt / f.size, "max_rel_error_rms_force": float(err)}
    out["speedup_hb_over_time_per_point"] = (
        out["time_180seg"]["s_per_point"] / out["hb_H20"]["s_per_point"]
    )
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=500)
    a = ap.parse_args()
    res = {
        "spur": bench_spur(),
        "herringbone_sweep": bench_sweep(a.points),
        "hb_vs_time": bench_hb_vs_time(),
    }
    write_json(Path("results/benchmarks/dynamics.json"), res)
    sp, hs, hv = res["spur"], res["herringbone_sweep"], res["hb_vs_time"]
    print(
        f"spur pair, 200 mesh periods ({sp['samples']} samples): {sp['spur_200_periods_s']:.3f} s"
    )
    print(
        f"herringbone {hs['dof']} DOF ({hs['independent_dof']} independent), "
        f"{hs['hb_sweep_points']}-point HB sweep on {hs['workers']} cores: "
        f"{hs['hb_sweep_s']:.1f} s"
    )
    for k in ("hb_H20", "time_180seg"):
        print(
            f"  {k}: {hv[k]['s_per_point'] * 1e3:.1f} ms/point, "
            f"max rel. error of RMS force {hv[k]['max_rel_error_rms_force']:.2e}"
        )
    print(
        f"  speed-up of the HB sweep over the time-integration sweep: "
        f"{hv['speedup_hb_over_time_per_point']:.1f}x per point"
    )


if __name__ == "__main__":
    main()
