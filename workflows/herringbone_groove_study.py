"""Xu et al. (2020)'s groove study from geometry: groove FE -> contact of both halves -> dynamics.

The 1.5 MW herringbone planetary stage of ``configs/wind_turbine_herringbone_planetary.toml``
(sun 21, planet 37, ring 95 teeth, m_n 15 mm, 25 deg, 8 deg helix, 4 planets, 185 mm sun
halves, 40 mm groove):

1. Groove geometries spanning the paper's K_j = 4.0-5.2e7 N m^2 by 3D FE
   (:mod:`pipeline.fem.groove`): the groove bottom diameter d is the design variable;
   two FE runs fit ``l_LR / K_j = a + b / d^4`` (halves in series with the groove
   section), which gives d for each of the paper's K_1..K_5, and each d is then run
   through the FE (the K_j reported are the FE's, within a few % of the targets).
2. The herringbone sun-planet contact of each groove (:mod:`pipeline.contact.herringbone`,
   ``[herringbone]``: torque leaving at the right half as at the paper's O_T, sun held on
   its 1e9 N/m axial bearing), plus the +1 mm slide at K_1 (Fig. 8e-f), the slide that
   gives the paper's Fig. 8e change, the torque entering at the left (paper's direction)
   and T/2 on each half (the paper's eqs. 20d / 21d).
3. The six Fig. 8 load maps (left/right sun flank at K_1, K_5, K_1 + 1 mm slide; one
   colour scale; PNG + VTU).
4. Fig. 5: each half's mesh stiffness over the cycle per K_j and the change of its maximum.
5. Fig. 9: RMS dynamic mesh force of s-p1L / s-p1R against mesh frequency for each
   groove, the herringbone planetary model excited left/right by these contacts and
   joined by the same FE groove matrix.
6. ``comparison.csv``: every compared quantity beside the paper's value.

Assumptions (not in the paper): solid sun, groove bottom as the K_j variable, 240 x 340 mm
output shaft, E 206 GPa, nu 0.3 (as in the config); analytical slice compliance of the
helical halves (``[contact]``); planets rigid, in phase and axially located in the contact
(the dynamic model phases them, eq. 10); the masses and supports of the config.

Measured (the loaded contact with its default tip contact: the sun's tip corners touch
beyond the path of contact at 54 of 60 positions, carrying up to 9 % of a half's load).
``gearpipe run`` on the wind-turbine file (148 kN m, analytical slices with the Weber local
approach, sun on its 1e9 N/m axial bearing): a half's own mesh stiffness is 2.1-2.2 GN/m on
average (compliance 4.6e-10 m/N), the project's groove (K_j = 5.98e7 N m^2) adds N r_b^2 /
k_t = 3.1e-10 m/N in series with the left half, which then carries 39.6 % of the load, max
unit load 555 / 783 N/mm left / right. A free sun keeps equal halves and slides.

This study (coarse: 30 positions) fits groove bottoms 253.4 / 247.2 / 241.0 / 234.8 / 228.5
mm for K_1..K_5 (FE: 5.26 / 4.95 / 4.64 / 4.33 / 4.03e7 N m^2; two fitting runs at 270 and
210 mm). From K_1 to K_5, computed [Xu et al. 2020]: left share 38.5 -> 35.9 %; max unit
load on the flanks (the path of contact) left 542 -> 512 N/mm, -5.5 % [880 -> 940, +6.8 %],
right 795 -> 823, +3.5 % [850 -> 780, -8.3 %]; min unit load left 233 -> 219, right 399 ->
417 [260 -> 280, 270 -> 240]; own max mesh stiffness left -0.18 %, right +0.09 % [+9.79 %,
-11.23 %]; with the groove and axial support in series left -12.06 %, right +0.08 %. With
the torque entering at the left every change swaps sides: the paper's direction for the left
half, and -12.06 % for the right half with its groove next to the paper's -11.23 %.

Why they differ: (1) eqs. 20d / 21d of the paper apply T_D/2 to each half, so its groove
carries no static torque when the halves share equally and cannot shift load by twisting
(``torque_entry = "both"`` gives equal halves here, tested); the paper's left/right
stiffness change is stated, not derived. With the torque leaving at one end, the far half
sits behind a spring of 70-95 % of its own mesh compliance and loses load as K_j falls. (2)
A half's own mesh stiffness barely depends on its load (the local approach is only weakly
nonlinear, the contact lines do not move), so the ~11 % change appears only for the half's
mesh with the groove in series - what a model with the groove inside k_0Ls (eq. 14) calls
the mesh stiffness. (3) A +1 mm slide moves the flanks by tan(beta_b) z = 0.127 mm along
the line of action, three times the mesh deflection: the left half lifts off entirely
(right max 1488 N/mm) [790 / 940 N/mm]; the paper's -10.2 % of the left maximum is reached
at a 0.084 mm slide, so its slide acts an order weaker than the helix geometry gives.

Fig. 9 with the computed excitation (120 speeds, H = 10, peaks refined on a 4 Hz grid): the
main peak is at 1084 Hz (s-p1L) / 1093 Hz (s-p1R) with the masses derived from the gears
and the config's supports [~1440 Hz]; from K_1 to K_5 it moves -0.9 / +1.0 Hz and its RMS
force falls on the left (146.3 -> 142.1 kN) and rises on the right (188.7 -> 194.0 kN) with
each half's static load [both fall "very obviously"]; the groove's twist mode (3000-3250
Hz, a step in the sweeps) falls with K_j.

Speed (``workflows/benchmarks/bench_herringbone_study.py``, fresh processes, 2 cores shared
with other jobs at a load average of 6): cold 150 s (7 groove FE runs 8-18 s each, 81 s in
all; 10 herringbone contact cases and the slide search 4.9 s; 6 load maps 13 s; Fig. 9
sweeps 39 s; imports 6 s), 0.88 GB peak; warm 8.3 s (0.055 of cold: the groove FE results,
contacts, sweeps and figures come from the cache by content hash). ``--full`` (60
positions, 400 speeds, H = 20, peaks on a 1 Hz grid; 205 s with the groove FE cached) gives
the same contact figures to four digits and the Fig. 9 peaks within 0.4 Hz and 0.3 %.
``gearpipe run`` on the wind-turbine file adds the groove FE (7-18 s cold, then cached) and
the herringbone contact (0.3 s) to its static stages.

    python workflows/herringbone_groove_study.py [--full] [--out DIR] [--no-cache]
                                                 [--cache-dir DIR]
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import sys
from pathlib import Path

import numpy as np

from pipeline.cache.entries import cached_file
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.config import load_gearbox
from pipeline.contact.groove_flank import GrooveFlankCoupling
from pipeline.contact.herringbone_maps import (
    half_load_maps,
    half_pair,
    loaded_range,
    write_half_vtus,
)
from pipeline.dynamics.herringbone_excitation import excitation_from_herringbone
from pipeline.dynamics.models.planetary_gears import (
    herringbone_planetary_model_from_gears,
    mesh_operations,
)
from pipeline.dynamics.peaks import refined_peak
from pipeline.dynamics.sweep import SweepResult, mesh_force_sweep
from pipeline.io import atomic_write, write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.progress import Steps
from pipeline.provenance import write_run_record
from pipeline.run.chain import RunOptions, mesh_cases, static_stages
from pipeline.run.dynamics import mesh_excitation
from pipeline.run.herringbone import TORQUE_SIDE, cached_groove, cached_herringbone_cycle
from pipeline.viz.figure_cache import FigureCache

CONFIG = Path(__file__).parent / "configs" / "wind_turbine_herringbone_planetary.toml"
PAPER_KJ = (5.2e7, 4.9e7, 4.6e7, 4.3e7, 4.0e7)  # N m^2, K_1..K_5 (sec. 3.1)
FIT_DIAMETERS = (0.270, 0.210)  # m, groove bottoms of the two fitting FE runs
MESHES = ("s-p1L", "s-p1R")
# Xu et al. (2020), Fig. 8: (max, min) unit load in N/mm of (left, right) sun flank
PAPER_FIG8 = {"K1": ((880, 260), (850, 270)), "K5": ((940, 280), (780, 240)),
              "K1 slide +1 mm": ((790, 250), (940, 280))}


def fit_grooves(spec, log, cache):
    """Groove bottoms for the paper's K_1..K_5 and their FE results (module docstring)."""
    fits = []
    for d in FIT_DIAMETERS:
        with log.step(f"groove FE d = {d * 1e3:.0f} mm", announce=True) as note:
            g, note["cached"] = cached_groove(dataclasses.replace(spec, groove_bottom_diameter=d),
                                              cache=cache)
            note["text"] = f"K_j = {g.equivalent_Kj:.4g} N m^2"
        fits.append((d, g))
    (d0, g0), (d1, g1) = fits
    b = (g0.l_LR / g0.equivalent_Kj - g1.l_LR / g1.equivalent_Kj) / (d0**-4 - d1**-4)
    a = g0.l_LR / g0.equivalent_Kj - b * d0**-4
    grooves = []
    for kj in PAPER_KJ:
        d = float((b / (g0.l_LR / kj - a)) ** 0.25)
        with log.step(f"groove FE d = {d * 1e3:.1f} mm", announce=True) as note:
            g, note["cached"] = cached_groove(dataclasses.replace(spec, groove_bottom_diameter=d),
                                              cache=cache)
            note["text"] = f"K_j = {g.equivalent_Kj:.4g} N m^2 (target {kj:.3g})"
        grooves.append((d, g))
    return grooves, fits[0]


def contact(box, groove, hb, positions, cache):
    """Herringbone contact of the sun-planet mesh with groove result ``groove``."""
    ps = box.planetary
    pair = mesh_cases(box)[0].pair
    op = mesh_operations(ps, box.operation, 1)[0]
    cyc, hit = cached_herringbone_cycle(
        pair, op, GrooveFlankCoupling.from_matrix(groove.coupling_matrix), ps.n_planets,
        dataclasses.replace(box.mesh_contact("sun_planet"), positions=positions),
        box.stiffness, hb, cache=cache)
    return cyc, pair, op, hit


def slide_matching(box, groove, target, positions, cache, ref_max):
    """Slide (m) at which the left half's max unit load falls by ``target`` (secant)."""
    def change(z):
        hb = dataclasses.replace(box.herringbone, axial_slide=z)
        c = contact(box, groove, hb, positions, cache)[0]
        return c.left.max_unit_load.max() / ref_max - 1.0

    z0, z1 = 0.0, 20e-6
    f0, f1 = 0.0, change(z1)
    for _ in range(4):
        z0, z1, f0 = z1, z1 + (target - f1) * (z1 - z0) / (f1 - f0), f1
        f1 = change(z1)
        if abs(f1 - target) < 1e-3:
            break
    return z1, f1


def write_table(path: Path, rows: list[tuple]) -> Path:
    """comparison.csv: figure, quantity, unit, Xu et al. (2020), computed, note."""
    def write(p):
        with open(p, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(["figure", "quantity", "unit", "Xu et al. (2020)", "computed", "note"])
            for r in rows:
                w.writerow([r[0], r[1], r[2], r[3], f"{r[4]:.4g}" if isinstance(r[4], float)
                            else r[4], r[5] if len(r) > 5 else ""])
    return atomic_write(path, write)


def run(full: bool = False, out: Path | None = None, cache: Cache = DEFAULT_CACHE,
        executor=None, show_progress: bool = True) -> dict:
    """The study (module docstring); returns the comparison rows, cases, grooves, sweeps,
    peaks, the step timing (s) and the files written."""
    target = workflow_dir(__file__, out)  # refused now, not after the study
    log = Steps("herringbone groove study", enabled=show_progress, every_step=True)
    figures = FigureCache.within(cache)
    with log.step("gearbox file"):
        box = load_gearbox(CONFIG)
    positions = 60 if full else 30
    grooves, own = fit_grooves(box.groove, log, cache)
    hb = box.herringbone
    cases = {f"K{j + 1}": (g, hb) for j, (_, g) in enumerate(grooves)}
    cases["K1 slide +1 mm"] = (grooves[0][1], dataclasses.replace(hb, axial_slide=1e-3))
    cases["K1 torque left"] = (grooves[0][1], dataclasses.replace(hb, torque_entry="left"))
    cases["K5 torque left"] = (grooves[-1][1], dataclasses.replace(hb, torque_entry="left"))
    cases["K5 torque both"] = (grooves[-1][1], dataclasses.replace(hb, torque_entry="both"))
    cases["own groove"] = (own[1], hb)
    cyc = {}
    with log.step("herringbone contact", announce=True) as note:
        hits = []
        for name, (g, h) in cases.items():
            cyc[name], pair, op, hit = contact(box, g, h, positions, cache)
            hits.append(hit)
        ref_max = cyc["K1"].left.max_unit_load.max()
        z_match, _ = slide_matching(box, grooves[0][1], 790 / 880 - 1, positions, cache, ref_max)
        cases["K1 slide matching Fig. 8e"] = (grooves[0][1],
                                              dataclasses.replace(hb, axial_slide=z_match))
        cyc["K1 slide matching Fig. 8e"] = contact(box, grooves[0][1],
                                                   cases["K1 slide matching Fig. 8e"][1],
                                                   positions, cache)[0]
        note["cached"] = all(hits)
        note["text"] = f"{len(cyc)} cases, {positions} positions"
    with staged_output(target) as out:  # the folder holds one complete study
        files = []
        with log.step("load maps (Fig. 8)", announce=True):
            from pipeline.viz.loadmap import render_load_map

            maps = {k: half_load_maps(cyc[k], pair, box.contact.load_map_profile_points)
                    for k in PAPER_FIG8}
            # one colour scale for the four groove maps, one for the slide pair
            top = {k: max(maps[c][s].unit_load.max() for c in group for s in maps[c]) * 1e-3
                   for group in (("K1", "K5"), ("K1 slide +1 mm",)) for k in group}
            for k, m in maps.items():
                stem = "fig8_" + k.replace(" ", "_").replace("+", "p")
                files += write_half_vtus(m, pair, out, stem)
                for s in ("left", "right"):
                    lo, hi = loaded_range(m[s])
                    title = (f"Xu et al. (2020) Fig. 8, {k}: {s} sun flank, max {hi * 1e-3:.0f} / "
                             f"min {lo * 1e-3:.0f} N/mm")
                    files.append(figures.save(out / f"{stem}_{s}.png", render_load_map,
                                              half_pair(pair, s), m[s], title, clim=(0.0, top[k])))
        with log.step("Fig. 5 figure"):
            from pipeline.viz.herringbone import plot_groove_mesh_stiffness

            kjs = np.array([g.equivalent_Kj for _, g in grooves])
            k = {s: np.array([cyc[f"K{j + 1}"].half(s).mesh_stiffness for j in range(5)])
                 for s in ("left", "right")}
            ks = {s: np.array([cyc[f"K{j + 1}"].series_mesh_stiffness(s) for j in range(5)])
                  for s in ("left", "right")}
            files.append(figures.save(
                out / "fig5_mesh_stiffness.png", plot_groove_mesh_stiffness, kjs, k["left"],
                k["right"], ks["left"], ks["right"],
                title="Herringbone sun-planet mesh stiffness against the groove's FE stiffness "
                      "(cf. Xu et al. 2020, Fig. 5)"))
        sweeps, peaks = fig9_sweeps(box, grooves, cyc, pair, op, full, executor, log, cache)
        with log.step("Fig. 9 figure"):
            from pipeline.viz.dynamics import plot_sweep

            files.append(figures.save(
                out / "fig9_sweep.png", plot_sweep, list(sweeps.values()),
                [f"{k}: K_j = {g.equivalent_Kj / 1e7:.2f}e7 N m^2" for k, (_, g) in
                 zip(sweeps, grooves, strict=True)], MESHES,
                title="RMS dynamic mesh force, FE groove + herringbone contact (cf. Xu et al. "
                      "2020, Fig. 9)"))
        rows, cols = comparison(cyc, maps, grooves, peaks, z_match)
        files.append(write_table(out / "comparison.csv", rows))
        files.append(write_csv(out / "cases.csv", cols))
        files.append(write_json(out / "timing.json", log.summary()))
        write_run_record(out, {"config": str(CONFIG), "full": full, "positions": positions,
                               "groove_bottoms_m": [d for d, _ in grooves]}, files,
                         "workflows/herringbone_groove_study.py", referenced={"config": CONFIG})
    return {"rows": rows, "cases": cyc, "grooves": grooves, "sweeps": sweeps, "peaks": peaks,
            "timing": log.summary(), "slide_match": z_match,
            "files": [target / Path(f).relative_to(out) for f in files]}


SWEEP_CODE = ("pipeline.dynamics", "pipeline.signals")
"""The code a sweep depends on (part of its cache key)."""


def _sweep_arrays(sw: SweepResult) -> dict[str, np.ndarray]:
    return {f.name: np.asarray(getattr(sw, f.name)) for f in dataclasses.fields(sw)}


def _sweep_from_arrays(z: dict[str, np.ndarray]) -> SweepResult:
    return SweepResult(**{**{k: z[k] for k in z}, "mesh_names": tuple(z["mesh_names"].tolist()),
                          "method": str(z["method"])})


def cached_sweep(model, freqs, H, executor, cache) -> tuple[SweepResult, bool]:
    """RMS mesh force sweep of ``model``, cached by a hash of the model and the grid."""
    inputs = {"model": model, "frequencies": freqs, "n_harmonics": H}
    sw, _, hit = cached_file(
        "hbsweep", inputs, lambda: mesh_force_sweep(model.assembly().assemble(), freqs,
                                                    n_harmonics=H, executor=executor),
        _sweep_arrays, _sweep_from_arrays, code=SWEEP_CODE, cache=cache)
    return sw, hit


def fig9_sweeps(box, grooves, cyc, pair, op, full, executor, log, cache):
    """RMS mesh force sweeps of the herringbone model per groove (Fig. 9), and the main
    peak of each side refined on a fine grid around the K_1 peak: (sweeps, peaks) with
    peaks[K][mesh] = (frequency Hz, RMS force N)."""
    freqs = np.linspace(20.0, 5000.0, 400 if full else 120)
    H = 20 if full else 10
    ring_case = mesh_cases(box)[1]
    with log.step("planet-ring contact"):
        ring_stage = static_stages(box, ring_case, RunOptions(cache=cache,
                                                              show_progress=False),
                                   Steps("", enabled=False))
        ring = mesh_excitation(ring_stage, box.stiffness.friction_model, "contact")
    sweeps, peaks, hits = {}, {}, []
    with log.step("Fig. 9 sweeps", announce=True) as note:
        models = {}
        for j, (_, g) in enumerate(grooves):
            exc = excitation_from_herringbone(cyc[f"K{j + 1}"], pair, op)
            models[f"K{j + 1}"] = herringbone_planetary_model_from_gears(
                box.planetary, box.bodies, box.carrier, box.operation, box.dynamics, exc, ring,
                groove=g, sun_load_side=TORQUE_SIDE[box.herringbone.torque_entry])
            sweeps[f"K{j + 1}"], hit = cached_sweep(models[f"K{j + 1}"], freqs, H, executor,
                                                    cache)
            hits.append(hit)
        step, half = (1.0, 60.0) if full else (4.0, 40.0)
        for m in MESHES:
            f0 = main_peak(sweeps["K1"], m)[0]
            fine = np.arange(f0 - half, f0 + half + step / 2, step)
            for k, model in models.items():
                sw, hit = cached_sweep(model, fine, H, executor, cache)
                hits.append(hit)
                pk = refined_peak(fine, sw.rms_force[sw.mesh_names.index(m)])
                peaks.setdefault(k, {})[m] = (pk.frequency, pk.value)
        note["cached"] = all(hits)
        note["text"] = f"{len(sweeps)} x ({freqs.size} + 2 x {fine.size}) speeds, H = {H}"
    return sweeps, peaks


def main_peak(sw, mesh: str, lo: float = 200.0, hi: float = 5000.0) -> tuple[float, float]:
    """(frequency Hz, RMS force N) of the largest RMS mesh force in [lo, hi] Hz."""
    y = sw.rms_force[sw.mesh_names.index(mesh)]
    ok = np.flatnonzero((sw.frequencies >= lo) & (sw.frequencies <= hi))
    i = ok[np.argmax(y[ok])]
    return float(sw.frequencies[i]), float(y[i])


def comparison(cyc, maps, grooves, peaks, z_match):
    """Rows of comparison.csv and the per-case columns of cases.csv."""
    rows = []
    for j, (d, g) in enumerate(grooves):
        rows.append(("sec. 3.1", f"K_{j + 1}: groove K_j (FE, bottom {d * 1e3:.1f} mm)",
                     "N m^2", f"{PAPER_KJ[j]:.3g}", float(g.equivalent_Kj)))
    k1, k5 = cyc["K1"], cyc["K5"]
    for side, paper in (("left", "+9.79"), ("right", "-11.23")):
        ch = k5.half(side).mesh_stiffness.max() / k1.half(side).mesh_stiffness.max() - 1
        rows.append(("Fig. 5", f"{side} max. mesh stiffness change K_1 -> K_5", "%", paper,
                     float(100 * ch), "torque leaving at the right half"))
        for case, note in (("", "torque leaving at the right half"),
                           (" torque left", "torque entering at the left half")):
            a, b = cyc[f"K1{case}"], cyc[f"K5{case}"]
            if case:
                ch = b.half(side).mesh_stiffness.max() / a.half(side).mesh_stiffness.max() - 1
                rows.append(("Fig. 5", f"{side} max. mesh stiffness change K_1 -> K_5,{case}",
                             "%", paper, float(100 * ch), note))
            ch = b.series_mesh_stiffness(side).max() / a.series_mesh_stiffness(side).max() - 1
            rows.append(("Fig. 5", f"{side} max. stiffness with groove, K_1 -> K_5{case}",
                         "%", paper, float(100 * ch), note))
        sl = (cyc["K1 slide +1 mm"].half(side).mesh_stiffness.max()
              - k1.half(side).mesh_stiffness.max())
        rows.append(("Fig. 6", f"{side} max. mesh stiffness change with +1 mm slide at K_1",
                     "N/m", "-6.30e7" if side == "left" else "+1.11e8", float(sl)))
    for case, paper in PAPER_FIG8.items():
        for s, (pmax, pmin) in zip(("left", "right"), paper, strict=True):
            lo, hi = loaded_range(maps[case][s])
            rows.append(("Fig. 8", f"{case}: {s} max unit load", "N/mm", pmax, hi * 1e-3))
            rows.append(("Fig. 8", f"{case}: {s} min unit load", "N/mm", pmin, lo * 1e-3))
    for s, paper in (("left", "+6.82"), ("right", "-8.34")):
        ch = loaded_range(maps["K5"][s])[1] / loaded_range(maps["K1"][s])[1] - 1
        rows.append(("Fig. 8", f"{s} max unit load change K_1 -> K_5", "%", paper,
                     float(100 * ch)))
    rows.append(("Fig. 8e", "slide giving the paper's left max unit load change (-10.2 %)",
                 "mm", "1", float(z_match * 1e3), "sun on its 1e9 N/m axial bearing"))
    for s in ("left", "right"):
        rows.append(("loads", f"K_1: {s} share of the mesh load", "-", "~0.5 (Fig. 8)",
                     float(k1.half_load(s).mean() / k1.load)))
    both = cyc["K5 torque both"]
    rows.append(("eq. 20d", "K_5, T/2 on each half as the paper's model: left share", "-",
                 "-", float(both.load_left.mean() / both.load),
                 "the groove carries no static torque: no shift"))
    for m in MESHES:
        f = [peaks[f"K{j + 1}"][m][0] for j in range(5)]
        a = [peaks[f"K{j + 1}"][m][1] / 1e3 for j in range(5)]
        rows.append(("Fig. 9", f"{m} main peak frequency K_1..K_5", "Hz", "~1440, falls",
                     " / ".join(f"{v:.1f}" for v in f)))
        rows.append(("Fig. 9", f"{m} main peak RMS force K_1..K_5", "kN", "falls",
                     " / ".join(f"{v:.1f}" for v in a)))
    names = list(cyc)
    cols = {"case index [-]": np.arange(len(names), dtype=float)}
    for s in ("left", "right"):
        cols[f"load share {s} [-]"] = np.array([cyc[n].half_load(s).mean() / cyc[n].load
                                                for n in names])
        cols[f"max mesh stiffness {s} [N/m]"] = np.array(
            [cyc[n].half(s).mesh_stiffness.max() for n in names])
        cols[f"max unit load {s} [N/mm]"] = np.array(
            [cyc[n].half(s).max_unit_load.max() * 1e-3 for n in names])
    cols["groove twist mean [rad]"] = np.array([cyc[n].groove_twist.mean() for n in names])
    cols["sun axial position mean [m]"] = np.array([cyc[n].sun_axial_position.mean()
                                                    for n in names])
    return rows, cols


def main(argv: list[str] | None = None) -> dict:
    """Command-line entry (module docstring); prints the comparison and the timing."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--out", default=None, help="default: results/<script>/workflow")
    ap.add_argument("--no-cache", action="store_true")
    ap.add_argument("--cache-dir", default=None, help="cache folder (default meshes/)")
    a = ap.parse_args(argv)
    res = run(a.full, a.out, cache=Cache.for_command(a.cache_dir, disabled=a.no_cache))
    print(f"{'figure':8s} {'quantity':62s} {'unit':6s} {'paper':>14s} {'computed':>14s}")
    for r in res["rows"]:
        v = f"{r[4]:.4g}" if isinstance(r[4], float) else str(r[4])
        print(f"{r[0]:8s} {r[1]:62s} {r[2]:6s} {str(r[3]):>14s} {v:>14s}")
    t = res["timing"]
    print(f"total {t['total_s']:.1f} s; from the cache: {', '.join(t['from_cache']) or '-'}")
    return res


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
