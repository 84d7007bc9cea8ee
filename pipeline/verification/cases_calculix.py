"""The FE-enriched loaded contact of the demo spur pair against an independent CalculiX
plane-strain contact model (``workflows/reference/calculix_spur_contact.py``; its
committed results ``demo_pair_reference.json``).

The reference shares nothing with the project's FE but the tooth profile and the
boundary conditions: its own Gmsh meshes of both whole gears (CPE6, 0.1 mm on the contact
flanks), surface-to-surface penalty contact on every flank and tip land, the pinion's bore
turned rigidly, the gear's bore fixed; 24 positions over a mesh cycle at 100 and 340 N m,
each torque bracketed by two of four load steps 4 % apart. Like for like, the project's
loaded TE is taken at the torque and its mesh stiffness as the secant over the same two
load steps (``bracket_torque_Nm``), as the reference defines it. Its mesh convergence (0.2 /
0.1 / 0.05 mm, the reference module's docstring) puts the committed 0.1 mm mesh within
about 0.15 % of the converged TE and stiffness where no corner carries load.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from pipeline.verification.context import Context
from pipeline.verification.model import N_PER_UM, UM, Outcome, Plot, Quantity, Series

REFERENCE_FILE = "demo_pair_reference.json"

DEMO_PAIR_TEXT = """\
name = "reference"
[pinion]
teeth = 50
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 20.0
bore_radius_mm = 21.0
[gear]
teeth = 50
module_mm = 3.0
pressure_angle_deg = 20.0
face_width_mm = 20.0
bore_radius_mm = 21.0
[operation]
torque_Nm = 340.0
speed_rpm = 2340.0
[contact]
compliance = "fe2d"
"""
"""The demo pair (z 50/50, m 3 mm, 20 deg, b 20 mm, bores 21 mm) with the FE-enriched
contact, frictionless as the reference; the reference's ``pair`` entry is checked against
it."""

TOLERANCES = {"te": 0.015, "k": 0.015, "k_closing": 0.025, "k_nominal": 0.016, "k_mean": 2e-3,
              "te_ptp": 1e-2}
"""Relative tolerances (module docstring; the reasons are stated with each quantity)."""
CLOSING_SHARE = 0.03
"""A tip corner carrying a positive share of P below this closes between the reference's
two load steps: the secant straddles the kink of T(theta)."""


def load_reference(context: Context, name: str = REFERENCE_FILE) -> dict:
    """The committed reference data (JSON, SI units; keys name their units)."""
    path = Path(context.reference_dir) / name
    if not path.is_file():
        raise FileNotFoundError(f"the CalculiX reference data {path} are missing (they are "
                                "committed in a source checkout's workflows/reference/)")
    return json.loads(path.read_text())


def _gearpipe(reference: dict, context: Context, tip_contact: bool,
              entries: list[dict]) -> tuple[np.ndarray, np.ndarray, object]:
    """The project's loaded TE (m) and secant mesh stiffness (N/m), shape (torques,
    positions), at the reference's positions and load steps; and the pair."""
    from pipeline.config.gearbox import gearbox_from_text
    from pipeline.contact.compliance import compliance_source
    from pipeline.contact.ltca import loaded_mesh_cycle

    text = DEMO_PAIR_TEXT + ("" if tip_contact else "tip_contact = false\n")
    box = gearbox_from_text(text, name="reference")
    src = compliance_source(box.pair, box.operation, box.contact, box.stiffness, box.fe_source,
                            cache=context.cache)
    rb1 = box.pair.pinion.base_radius
    torques = reference["torques_Nm"]
    te = np.empty((len(torques), len(entries)))
    k = np.empty_like(te)

    def loaded_te(torque: float, s0: float) -> float:
        cyc = loaded_mesh_cycle(src, torque / rb1, box.contact.modifications,
                                box.contact.local_contact, positions=np.array([s0]))
        return float(cyc.transmission_error[0])

    for i, e in enumerate(entries):
        for t, T in enumerate(torques):
            lo, hi = e["torques"][t]["bracket_torque_Nm"]
            te[t, i] = loaded_te(T, e["s0_m"])
            k[t, i] = (hi - lo) / rb1 / (loaded_te(hi, e["s0_m"]) - loaded_te(lo, e["s0_m"]))
    return te, k, box.pair


def _check_pair(reference: dict, pair) -> None:
    ref = reference["pair"]
    if ref["teeth"] != [pair.pinion.teeth, pair.gear.teeth] or not np.isclose(
            ref["base_pitch_m"], pair.base_pitch, rtol=1e-12, atol=0.0):
        raise ValueError("the reference data are not of the demo pair (teeth "
                         f"{ref['teeth']}, base pitch {ref['base_pitch_m']} m)")


def _compare(context: Context, run: str) -> Outcome:
    reference = load_reference(context)
    entries = reference["runs"][run]
    te_g, k_g, pair = _gearpipe(reference, context, run == "full", entries)
    _check_pair(reference, pair)
    torques = reference["torques_Nm"]
    rb1 = pair.pinion.base_radius
    te_r = np.array([[e["torques"][t]["transmission_error_m"] for e in entries]
                     for t in range(len(torques))])
    k_r = np.array([[e["torques"][t]["mesh_stiffness_N_per_m"] for e in entries]
                    for t in range(len(torques))])
    closing = np.array([[0.0 < sum(ld for ld, b in zip(e["torques"][t]["pair_load_N"],
                                                        e["torques"][t]["pair_beyond_path"],
                                                        strict=True) if b)
                         < CLOSING_SHARE * T / rb1 for e in entries]
                        for t, T in enumerate(torques)])
    s0 = np.array([e["s0_m"] for e in entries])
    te_why = ("the largest difference measured when the reference was committed is 1.23 % "
              "(position 0, 100 N m, the start of the path); the reference's 0.1 mm mesh is "
              "within about 0.15 % of its converged TE")
    k_why = ("secant over the reference's load steps; measured at most 1.46 % (position 18); "
             "the reference mesh is within about 0.15 % of its converged stiffness")
    closing_why = ("a tip corner closes between the reference's two load steps, the secant "
                   "straddles the kink of T(theta) (measured -2.3 %; at the reference's own "
                   "rotations the torques agree within 0.25 %)")
    if run == "nominal":
        te_why = "contact on the nominal path in both models; measured at most 1.3 %"
        k_why = "measured at most 1.5 %, at the ends of the path (the tests hold 1.6 %)"
    q = []
    for t, T in enumerate(torques):
        for i in range(len(entries)):
            q.append(Quantity(f"loaded TE, {T:g} N m, position {i}", "m", te_r[t, i],
                              te_g[t, i], "relative", TOLERANCES["te"], te_why, UM))
            near = closing[t, i] and run == "full"
            q.append(Quantity(f"mesh stiffness, {T:g} N m, position {i}"
                              + (" (tip corner closing)" if near else ""), "N/m", k_r[t, i],
                              k_g[t, i], "relative",
                              TOLERANCES["k_closing"] if near else
                              TOLERANCES["k_nominal" if run == "nominal" else "k"],
                              closing_why if near else k_why, N_PER_UM))
    if run == "full":
        q.append(Quantity("mean mesh stiffness over the cycle, 340 N m", "N/m", k_r[1].mean(),
                          k_g[1].mean(), "relative", TOLERANCES["k_mean"],
                          "the mean over 24 positions averages the local differences "
                          "(measured 302.8 against 302.5 N/um)", N_PER_UM))
        q.append(Quantity("loaded TE peak to peak, 340 N m", "m", np.ptp(te_r[1]),
                          np.ptp(te_g[1]), "relative", TOLERANCES["te_ptp"],
                          "a difference of two TE values, each within 1.5 % (measured "
                          "4.886 against 4.865 um)", UM))
    x = (s0 - pair.s_start) / pair.base_pitch
    plots = tuple(
        Plot(f"{what} against CalculiX ({'every flank' if run == 'full' else 'nominal path'}"
             " contact)", "position in the mesh cycle (s0 - s_start) / p_b [-]",
             f"{what} [{unit}]",
             tuple(s for t, T in enumerate(torques) for s in (
                 Series(f"CalculiX, {T:g} N m", x, ref[t] * scale, f"C{t}o"),
                 Series(f"gearpipe FE 2D, {T:g} N m", x, got[t] * scale, f"C{t}-x"))))
        for what, unit, ref, got, scale in (("loaded TE", "um", te_r, te_g, 1e6),
                                            ("mesh stiffness", "N/um", k_r, k_g, 1e-6)))
    diff = tuple(Series(f"{what}, {T:g} N m", x, 100 * (got[t] / ref[t] - 1.0), style)
                 for what, ref, got, style in (("TE", te_r, te_g, "-o"), ("k", k_r, k_g, "--x"))
                 for t, T in enumerate(torques))
    bands = {"TE and k": TOLERANCES["te"]} if run == "full" else \
        {"TE": TOLERANCES["te"], "k": TOLERANCES["k_nominal"]}
    for name, tol in bands.items():
        diff += (Series(f"tolerance of {name}, +-{100 * tol:g} %", (0.0, 1.0, np.nan, 0.0, 1.0),
                        (100 * tol, 100 * tol, np.nan, -100 * tol, -100 * tol),
                        "k:" if name != "k" else "k-."),)
    t_c, i_c = np.nonzero(closing) if run == "full" else ((), ())
    if len(i_c):
        diff += (Series(f"k where a tip corner closes (+-{100 * TOLERANCES['k_closing']:g} %)",
                        x[i_c], 100 * (k_g[t_c, i_c] / k_r[t_c, i_c] - 1.0), "ks"),)
    plots += (Plot("gearpipe / CalculiX - 1 at every position and torque",
                   "position in the mesh cycle (s0 - s_start) / p_b [-]", "difference [%]",
                   diff),)
    prov = reference["provenance"]
    inputs = (("pair", "demo pair: z 50/50, m 3 mm, 20 deg, b 20 mm, bores 42 mm, "
                       "frictionless"),
              ("torques", ", ".join(f"{T:g}" for T in torques) + " N m"),
              ("positions", f"{len(entries)} over one mesh cycle"),
              ("reference model", f"CalculiX {prov['calculix_version']}, {prov['elements']}, "
                                  f"{prov['contact']}, 0.1 mm on the contact flanks, "
                                  f"{prov['mesh']['pinion_nodes']} nodes per gear"),
              ("gearpipe", "[contact] compliance = \"fe2d\" (whole gears, graded), Weber "
                           "local contact" + ("" if run == "full" else
                                              ", tip_contact = false")))
    return Outcome("independent CalculiX plane-strain contact model, "
                   f"workflows/reference/{REFERENCE_FILE} (run \"{run}\", "
                   f"{prov['date_utc']})", inputs, tuple(q), plots=plots,
                   notes="The stiffness is the secant over the reference's two load steps "
                         "bracketing each torque, as the reference defines it.")


def case_calculix_demo_pair(context: Context) -> Outcome:
    """Loaded TE and mesh stiffness of the demo pair, contact on every flank and tip
    corner, at all 24 positions and both torques, against CalculiX."""
    return _compare(context, "full")


def case_calculix_demo_pair_nominal(context: Context) -> Outcome:
    """The control: contact confined to the nominal path in both models
    (``tip_contact = false`` against the reference's nominal run)."""
    return _compare(context, "nominal")
