"""Tip relief study on the assembly-error paper's pair: gearpipe study on a LocalCluster.

Runs ``workflows/configs/tip_relief_study.toml`` (linear long tip relief 0-24 um on both
gears x torque 255/340/425 N m, FE 2D whole-gear tables built once and shared by every
point, dynamics excited by the loaded contact over 500-6000 rpm) and prints where the TE
peak-to-peak is smallest at each torque beside the classic estimate, the combined tooth
deflection at that load F / (b c_gamma_alpha) (ISO 6336-1; 10.96 um at 340 N m).
``--full`` doubles the relief grid (1 um steps).

Writes results/tip_relief_study/workflow/ as a unit: study/ (everything ``gearpipe study`` writes:
study.parquet/csv, sensitivity.png, tradeoff.png, best_point/), optimum.csv and run.json.

    python workflows/tip_relief_study.py [--full] [--workers N] [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

from pipeline.cli import main as gearpipe
from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.config import load_gearbox
from pipeline.io import write_csv
from pipeline.output_folder import staged_output
from pipeline.provenance import write_run_record
from pipeline.stiffness.analysis import analyse_stiffness

ROOT = Path(__file__).resolve().parent
STUDY = ROOT / "configs" / "tip_relief_study.toml"


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--out", type=Path, default=None, help="default: results/<script>/workflow")
    a = ap.parse_args(argv)
    a.out = workflow_dir(__file__, a.out)
    study = STUDY
    if a.full:
        study = Path(tempfile.mkdtemp()) / STUDY.name
        study.write_text(STUDY.read_text().replace("points = 13", "points = 25")
                         .replace('base = "', f'base = "{STUDY.parent}/'))
    with staged_output(a.out) as out:  # the study's own folder is study/
        args = ["study", str(study), "--out", str(out / "study")]
        if a.workers is not None:
            args += ["--workers", str(a.workers)]
        status = gearpipe(args)
        if status:  # its one-line error is printed; nothing of this run is kept
            raise SystemExit(status)
        rows = optimum_rows(out / "study" / "study.parquet")
        files = [out / "study", write_csv(out / "optimum.csv",
                                          {k: np.array(v) for k, v in rows.items()})]
        write_run_record(out, {"study": str(study), "full": a.full, "workers": a.workers},
                         files, "workflows/tip_relief_study.py", referenced={"study": study})


def optimum_rows(table: Path) -> dict[str, list[float]]:
    """Per torque: the relief of the smallest TE p-p and the classic estimate (printed)."""
    import pyarrow.parquet as pq

    t = pq.read_table(table).to_pydict()
    box = load_gearbox(ROOT / "configs" / "spur_pair_assembly_errors.toml")
    c_gamma = analyse_stiffness(box.pair, box.operation, box.stiffness).summary()["iso6336"][
        "c_gamma_alpha_N_per_mm_um"]
    rows: dict[str, list[float]] = {"torque [N m]": [], "best relief [um]": [],
                                    "TE p-p there [um]": [], "F / (b c_gamma) [um]": []}
    x, T = np.array(t["contact.tip_relief_pinion_um"]), np.array(t["operation.torque_Nm"])
    y = np.array(t["te_peak_to_peak_um"])
    for torque in np.unique(T):
        m = T == torque
        i = np.argmin(y[m])
        F = torque / box.pair.pinion.base_radius
        est = F / (c_gamma * box.pinion.face_width * 1e3)
        for k, v in zip(rows, (torque, x[m][i], y[m][i], est), strict=True):
            rows[k].append(v)
        print(f"{torque:6.0f} N m: TE p-p smallest {y[m][i]:.2f} um at {x[m][i]:.1f} um relief; "
              f"F / (b c_gamma_alpha) = {est:.2f} um")
    return rows

if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
