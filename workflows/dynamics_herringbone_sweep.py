"""Study of Xu et al. (2020): dynamic mesh force sweeps with groove torsional stiffness and sun
axial slide.

Herringbone planetary set of Xu et al. (2020) (21/37/95 teeth, m_n 15 mm, 8 deg helix,
4 planets; see pipeline.dynamics.models.wind_turbine_planetary for the assumed masses and
supports), swept over mesh frequency by harmonic balance (RMS of the dynamic
mesh force, Xu et al. (2020), Figs. 9-10):

* groove stiffness K_1..K_5 = 5.2e7..4.0e7 N m^2 at zero slide;
* axial slide 0, +0.5, +1 mm at K_1, and +1 mm at K_5.

This is the paper's model as published, a comparison: the groove stiffness enters
twice (Xu et al. 2020, eqs. 1, 11, 14-15): as the twist phase lambda_LR of the right
sun meshes and through the left/right sun-planet mesh stiffness, which changes by
+9.79 % / -11.23 % from K_1 to K_5 (sec. 3.1, Fig. 5; the published percentages as
input data, :mod:`pipeline.dynamics.models.groove_mesh`, linear in the twist 1/K_j,
equal sides at K_1). The computed effect (the groove FE and the contact of both halves
through it) is ``workflows/herringbone_groove_study.py``. The groove study tracks the
two peak regions of Fig. 9 on fine grids (2 Hz coarse, 0.5 Hz ``--full``; parabola-refined peaks),
once with that relation and once with equal sides.

Comparison with Xu et al. (2020), sec. 4 (coarse run: 100 points, H = 10, fine grids 2 Hz):

* K_1 -> K_5, main peak (paper: "near 1440 Hz"): s-p1L 1436.4 -> 1430.0 Hz,
  s-p1R 1440.4 -> 1436.4 Hz, falling monotonically - the paper's direction
  (Fig. 9), tested. With equal sides the peaks stay put (L -0.5 Hz, R +0.3 Hz):
  the shift comes from eq. 14's stiffness change, not from the groove spring.
  The shift is small (-0.3 to -0.45 %) because the peak sits on the sun-mesh
  translational mode pair (1489 Hz undamped; 80 % of its strain energy in the
  sun meshes, none in the groove), and the paper's percentages change the summed
  left + right sun-mesh stiffness by only -0.72 %, i.e. about -0.36 % in
  frequency for a mode held equally by both sides' sun meshes (a mode held by
  the right meshes alone could fall by up to 5.8 %, but the halves are
  symmetric at K_1, so the peak modes are shared). The paper gives no peak
  frequency per K_j, only that they "decrease very obviously".
* K_1 -> K_5, peak values: s-p1L rises (227 -> 246 kN), s-p1R falls
  (266 -> 254 kN); the paper has both falling - not reproduced.
* Second region (paper: "near 2500 Hz"): s-p1L 2521.2 -> 2520.2 Hz (falls by
  1 Hz), s-p1R 2692.3 -> 2694.2 Hz (rises) - not reproduced on the right side.
* The groove (sun-half twist) mode falls 3043 -> 2827 Hz but gives no sweep
  peak: it is a rotational mode, and with z_s / N = 21 / 4 the sequential
  planet phasing lets only mesh harmonics h = 4, 8, ... excite rotational modes.
* Axial slide 0 -> +1 mm at K_1: left peak RMS force falls (224.2 -> 221.2 kN),
  right rises (261.9 -> 264.4 kN), peak frequencies unchanged - the paper's
  Fig. 10 trend, reproduced and tested (K_1 has equal sides, so unchanged by
  the groove relation).

Writes results/dynamics_herringbone_sweep/workflow/: sweep_groove.png, sweep_slide.png,
sweep_*.csv (per case and shown mesh: RMS, max, mean, alternating RMS force in N, dynamic
factor), summary.csv (main peak frequency and peak RMS force per case on the
sweep grid), groove_peaks.csv (per K_j: side factors, refined peak frequencies and
forces of both regions, equal-sides peaks, mesh/groove mode frequencies and strain
energy shares), sweep_groove_peak1.png / sweep_groove_peak2.png (RMS force vs mesh
frequency per K_j around each peak region), run.json.

    python workflows/dynamics_herringbone_sweep.py [--full] [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.dynamics.modal import conservative_mean_stiffness, modal_analysis
from pipeline.dynamics.models.groove_mesh import XU2020_GROOVE_MESH, side_factors
from pipeline.dynamics.models.wind_turbine_planetary import (
    K_J,
    L_TORSION,
    wind_turbine_herringbone_model,
)
from pipeline.dynamics.peaks import refined_peak
from pipeline.dynamics.sweep import mesh_force_sweep
from pipeline.io import write_csv
from pipeline.output_folder import staged_output
from pipeline.provenance import write_run_record
from pipeline.viz import save
from pipeline.viz.dynamics import plot_sweep

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


def mode_energy_shares(system, kj: float, lo: float, hi: float) -> tuple[float, float, float]:
    """Mode in ``[lo, hi]`` Hz with the largest sun-mesh strain energy, and its shares.

    Returns
    -------
    (frequency Hz, sun-mesh share, groove share): strain energy in the mean sun-planet
    mesh stiffnesses and in the groove spring ``K_j / L_TORSION`` as fractions of the
    mode's total strain energy (mean, conservative stiffness).
    """
    res = modal_analysis(system)
    phi = np.linalg.lstsq(system.basis, res.shapes, rcond=None)[0]  # reduced coordinates
    K = conservative_mean_stiffness(system)
    total = np.einsum("im,ij,jm->m", phi, K, phi)
    sun = sum(t.signal.mean() * (t.v @ phi) ** 2 for t in system.terms if t.name.startswith("s-p"))
    a, b = res.dof_names.index("sL.theta"), res.dof_names.index("sR.theta")
    groove = kj / L_TORSION * (res.shapes[a] - res.shapes[b]) ** 2
    ok = np.flatnonzero((res.frequencies >= lo) & (res.frequencies <= hi))
    i = ok[np.argmax(sun[ok] / total[ok])]
    return float(res.frequencies[i]), float(sun[i] / total[i]), float(groove[i] / total[i])


def groove_peak_study(coarse: dict, full: bool, H: int, executor) -> tuple[dict, dict, dict]:
    """Peak frequencies per K_j on fine grids around the two peak regions of Xu et al. (2020), Fig.
    9.

    Peak 1 is the main peak (Xu et al. 2020: near 1440 Hz), peak 2 the next region (near
    2500 Hz). Each K_j is run with the K_j-dependent left/right mesh stiffness (the
    model) and with equal sides (``groove_mesh=None``, the earlier model), to separate
    the effect of eq. 14's stiffness change from that of the groove spring and phase.

    Returns
    -------
    (table columns, fine sweeps of peak 1 per K, fine sweeps of peak 2 per K).
    """
    sw1 = coarse["K1 slide 0"]
    p1 = [main_peak(sw1, m, 1000.0, 2000.0)[0] for m in MESHES]
    p2 = [main_peak(sw1, m, 2200.0, 3000.0)[0] for m in MESHES]
    step = 0.5 if full else 2.0
    grid1 = np.arange(min(p1) - 50.0, max(p1) + 50.0 + step / 2, step)
    grid2 = np.arange(min(p2) - 50.0, max(p2) + 50.0 + step / 2, 2 * step)
    cols: dict[str, list] = {}
    fine1, fine2 = {}, {}

    def put(key, value):
        cols.setdefault(key, []).append(value)

    for j, kj in enumerate(K_J):
        sf = side_factors(kj)
        put("K_j [N m^2]", kj)
        put("k factor L [-]", sf.left)
        put("k factor R [-]", sf.right)
        for tag, rel in (("", XU2020_GROOVE_MESH), (" equal sides", None)):
            kw = {"groove_mesh": rel}
            system = wind_turbine_herringbone_model(kj, **kw).assembly().assemble()
            a = mesh_force_sweep(system, grid1, n_harmonics=H, executor=executor)
            if not tag:  # the second region only with the model's relation
                b = mesh_force_sweep(system, grid2, n_harmonics=H, executor=executor)
                fine1[f"K{j + 1}"], fine2[f"K{j + 1}"] = a, b
                fm, sun, gr = mode_energy_shares(system, kj, 1200.0, 1800.0)
                put("mesh mode [Hz]", fm)
                put("mesh mode sun-mesh energy [-]", sun)
                put("mesh mode groove energy [-]", gr)
                put("groove mode [Hz]", groove_mode_frequency(system))
            for m in MESHES:
                side = m[-1]
                pk1 = refined_peak(a.frequencies, a.rms_force[a.mesh_names.index(m)])
                put(f"peak1 {side}{tag} [Hz]", pk1.frequency)
                if not tag:
                    pk2 = refined_peak(b.frequencies, b.rms_force[b.mesh_names.index(m)])
                    put(f"peak1 force {side} [N]", pk1.value)
                    put(f"peak2 {side} [Hz]", pk2.frequency)
                    put(f"peak2 force {side} [N]", pk2.value)
                    put(f"peak at window edge {side} [-]", float(pk1.at_edge or pk2.at_edge))
    return {k: np.array(v, dtype=float) for k, v in cols.items()}, fine1, fine2


def run(full: bool = False, out: Path | None = None, executor="local") -> dict:
    out = workflow_dir(__file__, out, check=False)  # a staging folder, or new
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
        system = wind_turbine_herringbone_model(kj, slide, groove_mesh=XU2020_GROOVE_MESH
                                                ).assembly().assemble()
        groove_f[name] = groove_mode_frequency(system)
        sweeps[name] = mesh_force_sweep(system, freqs, n_harmonics=H, executor=executor)
    files = []
    for name, sw in sweeps.items():
        cols = {k: v for k, v in sw.columns().items()
                if k == "mesh frequency [Hz]" or any(f" {m} [" in k for m in MESHES)}
        files.append(
            write_csv(out / f"sweep_{name.replace(' ', '_').replace('+', 'p')}.csv", cols)
        )
    groove = [f"K{j + 1} slide 0" for j in range(5)]
    slide = ["K1 slide 0", "K1 slide +0.5 mm", "K1 slide +1 mm", "K5 slide +1 mm"]
    files.append(
        save(
            plot_sweep(
                [sweeps[c] for c in groove],
                groove,
                MESHES,
                title="Xu et al. (2020): groove torsional stiffness K1..K5",
            ),
            out / "sweep_groove.png",
        )
    )
    files.append(
        save(
            plot_sweep(
                [sweeps[c] for c in slide],
                slide,
                MESHES,
                title="Xu et al. (2020): sun axial slide",
            ),
            out / "sweep_slide.png",
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
    table, fine1, fine2 = groove_peak_study(sweeps, full, H, executor)
    files.append(write_csv(out / "groove_peaks.csv", table))
    for tag, fine in (("peak1", fine1), ("peak2", fine2)):
        files.append(
            save(
                plot_sweep(
                    list(fine.values()),
                    [f"{k}: K = {kj:.2g} N m^2" for k, kj in zip(fine, K_J, strict=True)],
                    MESHES,
                    title=f"Xu et al. 2020: groove stiffness K1..K5, {tag} region "
                    "(eq. 14 mesh stiffness)",
                ),
                out / f"sweep_groove_{tag}.png",
            )
        )
    write_run_record(
        out,
        {"full": full, "n_harmonics": H, "cases": list(cases), "points": int(freqs.size)},
        files,
        "workflows/dynamics_herringbone_sweep.py",
    )
    return {"cases": summary["case"], **cols, "sweeps": sweeps, "groove_peaks": table}


def main(argv: list[str] | None = None) -> dict:
    """Command-line entry: ``[--full] [--out DIR]``; returns the result table."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--out", default=None, help="default: results/<script>/workflow")
    a = ap.parse_args(argv)
    with staged_output(workflow_dir(__file__, a.out)) as out:
        res = run(a.full, out)
    t = res["groove_peaks"]
    print("K_j [N m^2]  k L/R      peak1 L / R [Hz]   (equal sides)      peak2 L / R [Hz]")
    for i, kj in enumerate(t["K_j [N m^2]"]):
        print(
            f"{kj:10.3g}  {t['k factor L [-]'][i]:.4f}/{t['k factor R [-]'][i]:.4f}"
            f"  {t['peak1 L [Hz]'][i]:7.1f} / {t['peak1 R [Hz]'][i]:7.1f}"
            f"  ({t['peak1 L equal sides [Hz]'][i]:7.1f} /"
            f" {t['peak1 R equal sides [Hz]'][i]:7.1f})"
            f"  {t['peak2 L [Hz]'][i]:7.1f} / {t['peak2 R [Hz]'][i]:7.1f}"
        )
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
    return res


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
