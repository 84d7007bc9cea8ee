"""Catalogue of the flank modifications: the map of each kind alone on the demo pinion.

One panel per modification of :mod:`pipeline.contact.modifications`, each 10 um on the
pinion of the demo pair (z 50/50, m 3 mm, 20 deg, b 20 mm), over its active flank: tip
relief (circular arc over 5 mm of roll length), root relief (parabolic over 4 mm), profile
crowning C_alpha, profile slope f_Halpha, lead crowning C_beta, end reliefs at both faces
(linear over 4 mm), helix slope f_Hbeta and the twist S (ISO 21771 profile twist: the
profile slope runs from -S/2 at face 1 to +S/2 at face 2, so +S/4 is removed at the tip of
face 2 and at the root of face 1, -S/4 at the other two corners). Writes to
results/modification_catalogue/workflow/: ``modification_catalogue.png``, ``summary.json``
(each map's smallest and largest value and the twist's corners, um) and run.json.

    python workflows/modification_catalogue.py [--out DIR]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from pipeline.cli import run_workflow
from pipeline.cli.common import workflow_dir
from pipeline.contact.modifications import (
    GearModification,
    LeadModification,
    ProfileModification,
    modification_maps,
)
from pipeline.geometry import GearPair, GearSpec, Material
from pipeline.io import write_json
from pipeline.output_folder import staged_output
from pipeline.provenance import write_run_record
from pipeline.viz import save
from pipeline.viz.canvas import new_figure
from pipeline.viz.modifications import plot_modification_map

UM, MM = 1e-6, 1e-3
C = 10 * UM
CATALOGUE = {
    "tip relief (arc, 5 mm)": GearModification(profile=ProfileModification(
        tip_relief=C, tip_relief_length=5 * MM, tip_relief_shape="arc")),
    "root relief (parabolic, 4 mm)": GearModification(profile=ProfileModification(
        root_relief=C, root_relief_length=4 * MM, root_relief_shape="parabolic")),
    "profile crowning C_alpha": GearModification(profile=ProfileModification(crowning=C)),
    "profile slope f_Halpha": GearModification(profile=ProfileModification(slope=C)),
    "lead crowning C_beta": GearModification(lead=LeadModification(crowning=C)),
    "end reliefs (linear, 4 mm)": GearModification(lead=LeadModification(
        end_relief_face1=C, end_relief_face1_length=4 * MM, end_relief_face2=C,
        end_relief_face2_length=4 * MM)),
    "helix slope f_Hbeta": GearModification(lead=LeadModification(slope=C)),
    "twist S": GearModification(twist=C),
}
"""Each modification alone, 10 um, on the pinion."""


def demo_pair() -> GearPair:
    steel = Material(youngs_modulus=2.0e11, poisson_ratio=0.3, density=7850.0)

    def gear(name: str) -> GearSpec:
        return GearSpec(teeth=50, name=name, module=3e-3, pressure_angle=0.3490658503988659,
                        face_width=0.02, bore_radius=0.021, material=steel)
    return GearPair(gear("pinion"), gear("gear"))


def run(out: Path) -> dict:
    pair = demo_pair()
    none = GearModification()
    fig = new_figure((17.0, 7.6), "constrained")
    axes = fig.subplots(2, 4).ravel()
    summary = {}
    for ax, (name, mod) in zip(axes, CATALOGUE.items(), strict=True):
        m = modification_maps(pair, (mod, none))[0]
        plot_modification_map(m, f"{name}, 10 um", ax=ax, diameters=False)
        summary[name] = {"min_um": float(m.deviation.min() / UM),
                         "max_um": float(m.deviation.max() / UM)}
        if name == "twist S":  # (root, face 1), (tip, face 1), (root, face 2), (tip, face 2)
            w = m.deviation / UM
            summary[name]["corners_um"] = [float(w[0, 0]), float(w[0, -1]), float(w[-1, 0]),
                                           float(w[-1, -1])]
    fig.suptitle("Flank modifications of the demo pinion (z 50, m 3 mm), each alone: "
                 "material removed [um] over face position and roll length (tip up)",
                 fontsize=10)
    files = [save(fig, out / "modification_catalogue.png"),
             write_json(out / "summary.json", summary)]
    write_run_record(out, {"amount_um": C / UM}, files, "workflows/modification_catalogue.py")
    return summary


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=None, help="default: results/<script>/workflow")
    args = ap.parse_args(argv)
    args.out = workflow_dir(__file__, args.out)
    with staged_output(args.out) as out:
        summary = run(out)
    for name, row in summary.items():
        print(f"{name:32s} " + "  ".join(f"{k} {v}" for k, v in row.items()))
    print(f"written to {args.out}/")
    return summary


if __name__ == "__main__":
    sys.exit(run_workflow(__file__, main))
