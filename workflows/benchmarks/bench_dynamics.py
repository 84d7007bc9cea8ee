"""Benchmarks of the dynamic solvers (figures printed and written to results/benchmarks/).

1. Spur pair (the assembly-error paper, 6 DOF): 200 mesh periods of time response (target < 1 s).
2. Herringbone planetary (Xu et al. 2020 case, 4 planets, 56 DOF): a 500-point harmonic
   balance sweep over 0-5000 Hz on all cores (target < 60 s on 2 cores).
3. Harmonic-balance sweep against a time-integration sweep (continuation) at the
   same points: accuracy ladders of both against the exact Floquet steady state of
   the finest segment model, and the speed-up at equal accuracy.

    python workflows/benchmarks/bench_dynamics.py [--points 500]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

from pipeline.dynamics.excitation import rectangular_mesh_stiffness
from pipeline.dynamics.integrate import integrate
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.dynamics.models.wind_turbine_planetary import wind_turbine_herringbone_model
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
    model = wind_turbine_herringbone_model(half_coupling=(5e10, 5e10, 5e10, 5e10))
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


def _timed_sweep(s, f, ref, **kw) -> dict:
    t = time.perf_counter()
    sw = mesh_force_sweep(s, f, executor=None, **kw)
    dt = time.perf_counter() - t
    err = np.abs(sw.rms_force - ref.rms_force).max() / np.abs(ref.rms_force).max()
    return {"s_per_point": dt / f.size, "max_rel_error_rms_force": float(err)}


def bench_hb_vs_time(points: int = 6) -> dict:
    """Accuracy ladders of both sweeps against the exact Floquet orbit (1440 segments).

    Harmonic balance at H = 10, 20, 40; time integration (exact propagator per
    segment, continuation from the previous point, steady state at tol 1e-6) at 180,
    360, 720 segments per mesh period. "Equal accuracy": for each HB level, the
    cheapest time-integration level whose error is not larger; the speed-up is the
    ratio of their times per point (serial, one BLAS thread).
    """
    model = wind_turbine_herringbone_model(half_coupling=(5e10, 5e10, 5e10, 5e10))
    s = model.assembly().assemble()
    f = np.linspace(300.0, 4800.0, points)
    ref = mesh_force_sweep(s, f, method="floquet", segments=1440, executor=None)
    hb = {H: _timed_sweep(s, f, ref, n_harmonics=H) for H in (10, 20, 40)}
    ti = {
        n: _timed_sweep(s, f, ref, method="time", segments=n, tol=1e-6, max_periods=50000)
        for n in (180, 360, 720)
    }
    out = {"points": points, "hb": {f"H{k}": v for k, v in hb.items()}}
    out["time"] = {f"{k}seg": v for k, v in ti.items()}
    out["equal_accuracy"] = {}
    for H, h in hb.items():
        ok = [
            (v["s_per_point"], n)
            for n, v in ti.items()
            if v["max_rel_error_rms_force"] <= h["max_rel_error_rms_force"]
        ]
        if ok:
            t_ti, n = min(ok)
            out["equal_accuracy"][f"H{H}"] = {
                "time_segments": n,
                "speedup_hb_over_time": t_ti / h["s_per_point"],
            }
        else:
            out["equal_accuracy"][f"H{H}"] = {"time_segments": None, "speedup_hb_over_time": None}
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=500)
    a = ap.parse_args()
    # serial parts: one BLAS thread (two threads on two busy cores oversubscribe badly)
    with threadpool_limits(limits=1):
        spur = bench_spur()
        hb_vs_time = bench_hb_vs_time()
    res = {
        "spur": spur,
        "herringbone_sweep": bench_sweep(a.points),
        "hb_vs_time": hb_vs_time,
        "note": "2 cores shared with other jobs: timings are upper bounds",
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
    for group in ("hb", "time"):
        for k, v in hv[group].items():
            print(
                f"  {group} {k}: {v['s_per_point'] * 1e3:.1f} ms/point, "
                f"max rel. error of RMS force {v['max_rel_error_rms_force']:.2e}"
            )
    for k, v in hv["equal_accuracy"].items():
        if v["time_segments"] is None:
            print(f"  HB {k}: no time-integration level in the ladder is as accurate")
        else:
            print(
                f"  HB {k} vs time integration at {v['time_segments']} segments "
                f"(error <= HB's): speed-up {v['speedup_hb_over_time']:.0f}x per point"
            )


if __name__ == "__main__":
    main()
