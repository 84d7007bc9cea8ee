"""Body (rim) term of ring-gear teeth: fit of Sainsot et al. (2004)'s form to whole-ring 2D FE.

Sainsot et al. (2004) fitted their body-term coefficients L*, M*, P*, Q* for *external*
gear bodies (an annulus between bore and root circle). A ring tooth hangs from a rim
outside its root circle, clamped at the rim's outer surface, and that formula does not
carry over: mapped to h_f = r_rim / r_f it is extrapolated far below its fitted range
(h_f >= 1.4), and tooth + body compliance came out 1.15-4.5 times the FE's on the
coarse set of rings below (FE / analytical 0.22-0.87). This study does for rings what
Sainsot et al. did for external bodies: the same functional form,

    lambda_f E / cos^2(a) = L (u_f/S_f)^2 + M (u_f/S_f) + P0 + P1 ln(t_R / S_f),

fitted to the body compliance of whole 2D rings (P2 triangles, plane stress, outer rim
surface clamped, Hertz near field removed): the FE flank compliance minus the analytical
tooth compliance (bending + shear + axial of :func:`pipeline.stiffness.tooth.tooth_model`),
``t_R`` the rim thickness below the root circle, ``S_f`` the tooth thickness at the root
and ``u_f`` the distance from the clamped root chord to where the load line crosses the
centre line. L and M play Sainsot's roles (rotation of the tooth base under the root
moment); the translation term grows like ``ln(t_R / S_f)``, as the displacement of a
half-plane under a surface load measured against a support at depth t_R does (the
Flamant solution: 2/pi = 0.64 in plane stress; the fit gives 0.68). Sainsot's Q* (the
weight of the load's radial component) is left out: fitted freely it went to its bound 0.

Writes ``results/ring_body_fit/workflow/``: the samples (CSV), the coefficients and residuals
(JSON), run.json. The coefficients in :data:`pipeline.stiffness.foundation.RING_TABLE`
come from ``--full``.

    python workflows/ring_body_fit.py            # coarse: 8 rings, refinement 0.5
    python workflows/ring_body_fit.py --full     # 32 rings, refinement 1.0 (about 5 min)
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pipeline.cli import run_workflow  # noqa: E402
from pipeline.cli.common import workflow_dir  # noqa: E402
from pipeline.contact.fe2d_source import gear_table  # noqa: E402
from pipeline.fem.settings import FE2DSettings  # noqa: E402
from pipeline.geometry.gear import GearSpec, Material  # noqa: E402
from pipeline.io import write_csv, write_json  # noqa: E402
from pipeline.output_folder import staged_output  # noqa: E402
from pipeline.progress import progress  # noqa: E402
from pipeline.provenance import write_run_record  # noqa: E402
from pipeline.stiffness.tooth import load_geometry, tooth_compliance, tooth_model  # noqa: E402

STEEL = Material(youngs_modulus=2.0e11, poisson_ratio=0.3, density=7850.0)
MODULE = 3e-3  # per-unit-width compliances of similar 2D bodies do not depend on size


def ring(z: int, alpha_deg: float, rim_modules: float) -> GearSpec:
    """A standard ring (h_a* 1, h_f* 1.25, x 0) with a rim ``rim_modules`` m_n below its root."""
    rf = z * MODULE / 2 + 1.25 * MODULE
    return GearSpec(teeth=z, module=MODULE, pressure_angle=math.radians(alpha_deg),
                    face_width=0.02, internal=True, bore_radius=rf + rim_modules * MODULE,
                    material=STEEL, name=f"ring{z}")


def samples(cases, refinement: float, radii: int, show_progress: bool = True) -> dict:
    """FE flank compliance at ``radii`` points of each ring, with the analytical columns."""
    cols: dict[str, list] = {k: [] for k in ("teeth", "alpha_n_deg", "rim_over_m", "radius_m",
                                             "fe_m2_per_N")}
    for z, a, t in progress(cases, "ring FE", enabled=show_progress):
        g = ring(z, a, t)
        tab, _ = gear_table(g, FE2DSettings(teeth=None, points=radii, refinement=refinement,
                                            kind="plane_stress"), np.array([0]))
        r = tab.points.radius
        for k, v in (("teeth", z), ("alpha_n_deg", a), ("rim_over_m", t), ("radius_m", r),
                     ("fe_m2_per_N", np.diag(tab.structural))):
            cols[k].append(np.broadcast_to(v, r.shape).astype(float))
    return with_analytical({k: np.concatenate(v) for k, v in cols.items()})


def with_analytical(data: dict) -> dict:
    """Add the analytical tooth compliance and the body-term variables to FE samples."""
    out = {k: data[k] for k in ("teeth", "alpha_n_deg", "rim_over_m", "radius_m",
                                "fe_m2_per_N")}
    extra: dict[str, list] = {k: [] for k in ("tooth_m2_per_N", "load_angle_rad", "u_over_S",
                                              "t_over_S", "theta_f_rad")}
    keys = np.column_stack([data["teeth"], data["alpha_n_deg"], data["rim_over_m"]])
    _, first = np.unique(keys, axis=0, return_index=True)
    order = np.sort(first)
    for i, j in zip(order, np.r_[order[1:], len(keys)], strict=True):
        g = ring(int(keys[i, 0]), float(keys[i, 1]), float(keys[i, 2]))
        r = data["radius_m"][i:j]
        model = tooth_model(g)
        la, h_c, y_c = load_geometry(g, r)
        u = (model.sections.clamp_radius - (y_c + h_c * np.tan(la))) / model.root_thickness
        for k, v in (("tooth_m2_per_N", tooth_compliance(model, r).tooth),
                     ("load_angle_rad", la), ("u_over_S", u),
                     ("t_over_S", (g.bore_radius - g.root_radius) / model.root_thickness),
                     ("theta_f_rad", model.foundation.theta_f)):
            extra[k].append(np.broadcast_to(v, r.shape).astype(float))
    return out | {k: np.concatenate(v) for k, v in extra.items()}


def fit(data: dict) -> dict:
    """Least squares of the body compliance on (u/S)^2, u/S, 1, ln(t/S), weighted so that
    the residual is the relative error of the total (tooth + body) compliance."""
    c2 = np.cos(data["load_angle_rad"]) ** 2 / STEEL.youngs_modulus
    u, lt = data["u_over_S"], np.log(data["t_over_S"])
    w = c2 / data["fe_m2_per_N"]
    basis = np.column_stack([u * u, u, np.ones_like(u), lt])
    body = data["fe_m2_per_N"] - data["tooth_m2_per_N"]
    coef = np.linalg.lstsq(basis * w[:, None], body / data["fe_m2_per_N"], rcond=None)[0]
    total_err = (data["tooth_m2_per_N"] + (basis @ coef) * c2) / data["fe_m2_per_N"] - 1.0
    L, M, P0, P1 = (float(c) for c in coef)
    return {"L": L, "M": M, "P0": P0, "P1": P1,
            "total_compliance_error_max": float(np.max(np.abs(total_err))),
            "total_compliance_error_rms": float(np.sqrt(np.mean(total_err**2))),
            "samples": int(u.size),
            "t_over_S_range": [float(data["t_over_S"].min()), float(data["t_over_S"].max())],
            "theta_f_range": [float(data["theta_f_rad"].min()), float(data["theta_f_rad"].max())],
            "u_over_S_range": [float(u.min()), float(u.max())]}


def read_samples(path: Path) -> dict:
    """Samples written by an earlier run (``samples.csv``), to refit without the FE."""
    import csv

    with path.open() as f:
        rows = list(csv.DictReader(f))
    return {k.split(" [")[0]: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", action="store_true", help="32 rings at refinement 1.0")
    ap.add_argument("--out", type=Path, default=None, help="default: results/<script>/workflow")
    ap.add_argument("--samples", type=Path, help="refit the FE samples of an earlier run "
                    "(samples.csv) with the current analytical tooth model")
    args = ap.parse_args(argv)
    args.out = workflow_dir(__file__, args.out)
    if args.samples is not None:  # the FE columns of an earlier run, analytical ones anew
        data = with_analytical(read_samples(args.samples))
        result, inputs = fit(data), {"samples": str(args.samples)}
    else:
        if args.full:
            cases = [(z, a, t) for z in (40, 60, 100, 160) for a in (20.0, 25.0)
                     for t in (2.5, 4.0, 7.0, 12.0)]
            refinement, radii = 1.0, 9
        else:
            cases = [(z, a, t) for z in (60, 100) for a in (20.0, 25.0) for t in (3.0, 8.0)]
            refinement, radii = 0.5, 7
        data = samples(cases, refinement, radii)
        result = fit(data)
        result.update(refinement=refinement, cases=len(cases))
        inputs = {"cases": cases, "refinement": refinement, "radii": radii}
    with staged_output(args.out) as out:
        files = [write_csv(out / "samples.csv", data),
                 write_json(out / "fit.json", result)]
        write_run_record(out, inputs, files, "python workflows/ring_body_fit.py "
                         + " ".join(argv if argv is not None else sys.argv[1:]))
    for k, v in result.items():
        print(f"{k}: {v}")
    return 0


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
