"""Seed 002 study: dynamic mesh force sweeps with groove torsional stiffness and sun axial slide.

Herringbone planetary set of seed 002 (21/37/95 teeth, m_n 15 mm, 8 deg helix,
4 planets; see pipeline.dynamics.models.seed002_case for the assumed masses and
supports), swept over mesh frequency by harmonic balance (RMS of the dynamic
mesh force, seed 002 Figs. 9-10):

* groove stiffness K_1..K_5 = 5.2e7..4.0e7 N m^2 at zero slide;
* axial slide 0, +0.5, +1 mm at K_1, and +1 mm at K_5.

Comparison with seed 002 sec. 4 (coarse run, 100 points, H = 10; a 10 Hz check
over 1000-3600 Hz gave the same peaks):

* axial slide 0 -> +1 mm at K_1: left peak RMS force falls (224.2 -> 221.2 kN),
  right rises (261.9 -> 264.4 kN), peak frequencies unchanged (1421 Hz on this
  grid, 1440 Hz at 10 Hz steps) - the paper's Fig. 10 trend, reproduced and tested;
* K_1 -> K_5: the groove (sun-half twist) natural frequency falls 3043 -> 2823 Hz
  (tested), and the left peak force falls (224.2 -> 222.0 kN), but the sweep peak
  frequencies (1440 and 2520/2690 Hz) do not move and the right peak rises
  (261.9 -> 266.0 kN). The paper (Fig. 9) reports both peak values and peak
  frequencies of both sides falling. Its mechanism is the change of the left/right
  mesh stiffness with K_j (seed 002 eqs. 14-15, Fig. 5: +9.8 % / -11.2 %); this model
  carries the groove twist only as a left/right meshing phase and a dynamic
  torsional joint, with the same mesh stiffness for every K_j, so that trend is
  NOT reproduced here.

Writes results/dynamics_herringbone_sweep/: sweep_groove.png, sweep_slide.png,
sweep_*.csv, summary.csv (main peak frequency and peak RMS force per case), run.json.

    python workflows/dynamics_herringbone_sweep.py [--full] [--out DIR]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from pipeline.dynamics.modal import modal_analysis
from pipeline.dynamics.models.seed002_case import K_J, seed002_model
from pipeline.dynamics.plots import plot_sweep
from pipeline.dynamics.sweep import mesh_force_sweep
from pipeline.io import write_csv, write_run_record

MESHES = ("s-p1L", "s-p1R")


def main_peak(sweep, mesh: str, lo: float = 200.0, hi: float = np.inf) -> tuple[float, float]:
    """(frequency Hz, RMS force N) of the largest RMS value in ``[lo, hi]`` Hz."""
    y = sweep.rms_force[sweep.mesh_names.index(mesh)]
    ok = (sweep.frequencies >= lo) & (sweep.frequencies <= hi)
    i = np.flatnonzero(ok)[np.argmax(y[ok])]
    return float(sweep.frequencies[i]), float(y[i])


def groove_mode_frequency(system) -> float:
    """Natural frequency (Hz) of the mode with the largest twist of the sun halves."""
    res = modal_analysis(system)
    a, b = res.dof_names.index("sL.theta"), res.dof_names.index("sR.theta")
    twist = np.abs(res.shapes[a] - res.shapes[b]) * np.sqrt(system.M.diagonal().max())
    return float(res.frequencies[np.argmax(twist)])


def run(full: bool = False, out: Path | None = None, executor="local") -> dict:
    out = Path(out or "results/dynamics_herringbone_sweep")
    freqs = np.linspace(10.0, 5000.0, 500 if full else 100)
    H = 20 if full else 10
    cases = {f"K{j + 1} slide 0": (kj, 0.0) for j, kj in enumerate(K_J)}
    cases.update(
        {
            "K1 slide +0.5 mm": (K_J[0], 0.5e-3),
            "K1 slide +1 mm": (K_J[0], 1e-3),
            "K5 slide +1 mm": (K_J[4], 1e-3),
        }
    )
    sweeps, groove_f = {}, {}
    for name, (kj, slide) in cases.items():
        system = seed002_model(kj, slide).assembly().assemble()
        groove_f[name] = groove_mode_frequency(system)
        sweeps[name] = mesh_force_sweep(system, freqs, n_harmonics=H, executor=executor)
    files = []
    for name, sw in sweeps.items():
        cols = {"mesh frequency [Hz]": sw.frequencies}
        for m in MESHES:
            cols[f"rms force {m} [N]"] = sw.rms_force[sw.mesh_names.index(m)]
        files.append(
            write_csv(out / f"sweep_{name.replace(' ', '_').replace('+', 'p')}.csv", cols)
        )
    groove = [f"K{j + 1} slide 0" for j in range(5)]
    slide = ["K1 slide 0", "K1 slide +0.5 mm", "K1 slide +1 mm", "K5 slide +1 mm"]
    files.append(
        plot_sweep(
            [sweeps[c] for c in groove],
            groove,
            MESHES,
            out / "sweep_groove.png",
            title="Seed 002: groove torsional stiffness K1..K5",
        )
    )
    files.append(
        plot_sweep(
            [sweeps[c] for c in slide],
            slide,
            MESHES,
            out / "sweep_slide.png",
            title="Seed 002: sun axial slide",
        )
    )
    summary = {
        "case": [],
        "groove mode [Hz]": [],
        "groove peak R [Hz]": [],
        "peak L [Hz]": [],
        "peak force L [N]": [],
        "peak R [Hz]": [],
        "peak force R [N]": [],
        "mean force L [N]": [],
        "mean force R [N]": [],
    }
    for name, sw in sweeps.items():
        fl, al = main_peak(sw, "s-p1L")
        fr, ar = main_peak(sw, "s-p1R")
        summary["case"].append(name)
        fg = groove_f[name]
        summary["groove mode [Hz]"].append(fg)
        summary["groove peak R [Hz]"].append(main_peak(sw, "s-p1R", 0.8 * fg, 1.2 * fg)[0])
        summary["peak L [Hz]"].append(fl)
        summary["peak force L [N]"].append(al)
        summary["peak R [Hz]"].append(fr)
        summary["peak force R [N]"].append(ar)
        summary["mean force L [N]"].append(sw.mean_force[sw.mesh_names.index("s-p1L"), 0])
        summary["mean force R [N]"].append(sw.mean_force[sw.mesh_names.index("s-p1R"), 0])
    cols = {k: np.array(v, dtype=float) for k, v in summary.items() if k != "case"}
    cols = {"case index [-]": np.arange(len(summary["case"]), dtype=float), **cols}
    files.append(write_csv(out / "summary.csv", cols))
    write_run_record(
        out,
        {"full": full, "n_harmonics": H, "cases": list(cases), "points": int(freqs.size)},
        files,
        "workflows/dynamics_herringbone_sweep.py",
    )
    return {"cases": summary["case"], **cols, "sweeps": sweeps}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    res = run(a.full, a.out)
    for i, c in enumerate(res["cases"]):
        print(
            f"{c:18s} groove mode {res['groove mode [Hz]'][i]:7.1f} Hz, peak near it "
            f"{res['groove peak R [Hz]'][i]:7.1f} Hz"
        )
        print(
            f"{'':18s} main peak L {res['peak L [Hz]'][i]:7.1f} Hz "
            f"({res['peak force L [N]'][i]:9.0f} N)"
            f"  R {res['peak R [Hz]'][i]:7.1f} Hz ({res['peak force R [N]'][i]:9.0f} N)"
            f"  mean L/R {res['mean force L [N]'][i]:9.0f} / {res['mean force R [N]'][i]:9.0f} N"
        )


if __name__ == "__main__":
    main()
