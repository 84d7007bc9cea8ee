"""The full-revolution section of a mesh report: the loaded contact with each tooth's
errors through the hunting cycle or a revolution (:mod:`pipeline.contact.revolution`)."""

from __future__ import annotations

import math
from typing import Any

from pipeline.report.content import quantity
from pipeline.report.model import Figure, Section

FIGURES = (
    ("revolution_te.png", "Loaded static transmission error over the span, beside the "
     "error-free mesh cycle repeated and the runouts' gap"),
    ("revolution_spectrum.png", "Its amplitude spectrum against the order per pinion "
     "revolution: mesh orders n z1 and the sidebands and ghost orders of the errors"),
    ("revolution_worst_pair.png", "The tooth pair with the largest Hertz pressure along the "
     "path, against the range of every other pair"),
    ("revolution_worst_pair_load_map.png", "Load map of that tooth pair: unit load over the "
     "face and the pinion's contact radius through its passage"),
)


def revolution_figures(names: set[str], prefix: str) -> list[Figure]:
    """The revolution's figures among the run's files ``names``
    (:mod:`pipeline.cli.revolution_files`)."""
    return [Figure(f"{prefix}{file}", caption) for file, caption in FIGURES
            if f"{prefix}{file}" in names]


def _errors_rows(errors: Any) -> list:
    rows = []
    for who in ("pinion", "gear"):
        g = getattr(errors, who)
        if g.pitch_deviations:
            dev = [abs(v) for v in g.pitch_deviations]
            rows.append(quantity(f"{who}_f_pt_max", f"{who}: largest single pitch deviation "
                                 "|f_pt|", "um", max(dev) * 1e6))
        if g.eccentricity:
            rows.append(quantity(f"{who}_eccentricity", f"{who}: eccentricity e (phase "
                                 f"{math.degrees(g.eccentricity_phase):.4g} deg)", "um",
                                 g.eccentricity * 1e6))
    return rows


def revolution_section(stage: Any, figures: list[Figure]) -> Section:
    """The :class:`pipeline.run.revolution.RevolutionStage` of a pair with its figures."""
    s = stage.summary()
    worst = s["worst_pair"]
    sideband = s["largest_sideband_order"]
    rows = [
        *_errors_rows(stage.errors),
        quantity("span", f"span ({s['span']}): mesh cycles x positions", "",
                 f"{s['mesh_cycles']} x {s['positions'] // s['mesh_cycles']}"),
        quantity("te_peak_to_peak", "transmission error over the span, peak to peak", "um",
                 s["transmission_error_peak_to_peak_m"] * 1e6),
        quantity("first_order", "amplitude at order 1 (once per pinion revolution)", "um",
                 s["first_order_amplitude_m"] * 1e6),
        quantity("mesh_order", "amplitude at the mesh order z1", "um",
                 s["mesh_order_amplitude_m"] * 1e6),
        quantity("largest_sideband", "largest sideband (order >= z1 / 2, not a mesh order)",
                 "um", s["largest_sideband_amplitude_m"] * 1e6),
        quantity("largest_sideband_order", "... at order per pinion revolution", "-",
                 None if sideband != sideband else sideband),
        quantity("worst_pair", "worst tooth pair (pinion tooth / gear tooth)", "",
                 f"{worst['pinion_tooth']} / {worst['gear_tooth']}"),
        quantity("worst_pressure", "its largest Hertz pressure", "MPa",
                 worst["pressure_Pa"] * 1e-6),
    ]
    notes = (
        "Every tooth pair carries the gap of its two teeth's cumulative pitch deviations "
        "(F_p = sum of f_pt, ISO 1328-1, along the line of action F_p cos alpha_t) and of "
        "both eccentricities at the instant (e sin(phi + theta) of each gear, the same for "
        "every pair on the line of action); teeth are numbered in the order they come into "
        "mesh, tooth 0 of both gears forming the first pair.",
        "A runout also moves the eccentric gear's centre: each mesh cycle is solved on the "
        "pair at the centre distance of its middle (a + e_1 cos(phi_1 + theta_1 - alpha_wt) "
        "- e_2 cos(phi_2 + theta_2 + alpha_wt)), "
        "whose pressure angle, path of contact and contact ratio differ, at positions moved "
        "by the turn of the base tangent point T1 (the changed pressure angle and the turned "
        "line of centres). That modulates the mesh harmonics once per revolution: sidebands "
        "at the mesh orders +- 1 (checked against the linear estimate from two mesh cycles "
        "at a +- 1 um). Pitch deviations differ from pair to pair and redistribute the load.",
        "The other sections, and the dynamics excited by the contact, use the mesh cycle "
        "without these errors.",
    )
    return Section("revolution", "Full revolution with tooth errors", tuple(rows),
                   figures=tuple(figures), notes=notes)
