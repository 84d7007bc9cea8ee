"""Case of the mesh excitation from the loaded tooth contact
(:mod:`pipeline.dynamics.contact_excitation`) at zero speed.

The zero-speed limit of the pair model is static equilibrium at every mesh phase, so it
reproduces the contact analysis' static transmission error x_s and mesh load P at every
contact position; the angular transmission error r_bp theta_p - r_bg theta_g carries the
bearings' deflection 2 P / k_b on top (lateral-torsional model). Checked on the spur pair
of the assembly-error paper and the helical pair of Yang et al. (2026), lateral-torsional
and torsional.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Outcome, Plot, Quantity, Series

CASES = {"spur": ("configs/spur_pair_assembly_errors.toml", 1),
         "helical": ("configs/traction_helical_pair.toml", 8)}
"""The pairs (gearbox file under ``workflows/``, analytical slices across the face)."""
POSITIONS = 60
DOFS = ("lateral_torsional", "torsional")


def _contact(context: Context, path: str, slices: int):
    """(gearbox, actual pair, contact cycle, friction model): analytical slices, Weber's
    contact, tip contact on, no friction."""
    from pipeline.config import load_gearbox
    from pipeline.contact import analyse_contact, analytical_compliance
    from pipeline.contact.options import ContactOptions
    from pipeline.stiffness.mesh import FrictionModel, PairModel

    file = context.reference_dir.parent / path
    if not file.is_file():
        raise FileNotFoundError(f"{file} is missing (it is in a source checkout's workflows/)")
    box = load_gearbox(str(file))
    pair = box.actual_pair
    stiffness = dataclasses.replace(box.stiffness, friction=0.0)
    opts = ContactOptions(positions=POSITIONS, slices=slices, local_contact="weber",
                          tip_contact=True)
    source = analytical_compliance(pair, box.operation, opts, stiffness,
                                   model=PairModel.build(pair))
    return box, pair, analyse_contact(source, box.operation, opts), FrictionModel(mu=0.0)


def _worst(name, unit, ref, val, tol, reason, display=None):
    ref, val = np.ravel(ref), np.ravel(val)
    i = int(np.argmax(np.abs(val / ref - 1.0)))
    return Quantity(name, unit, ref[i], val[i], "relative", tol, reason, display)


def case_contact_excitation_zero_speed(context: Context) -> Outcome:
    """The quasi-static response to the contact excitation against the contact's TE and load
    at every position (worst position reported)."""
    from pipeline.dynamics.contact_excitation import excitation_from_contact
    from pipeline.dynamics.models.spur_pair import spur_pair_model
    from pipeline.dynamics.options import PairDynamicsOptions
    from pipeline.dynamics.quasi_static import quasi_static_response

    solve = ("a 2- or 6-unknown solve with stiffnesses 1e8-1e9 N/m: round-off (the tests "
             "hold 1e-10)")
    q, plots = [], []
    for name, (path, slices) in CASES.items():
        box, pair, cycle, friction = _contact(context, path, slices)
        ex = excitation_from_contact(cycle, pair, box.operation, friction)
        x, P = cycle.transmission_error, cycle.load
        for dofs in DOFS:
            options = dataclasses.replace(box.dynamics or PairDynamicsOptions(), dofs=dofs,
                                          friction=False)
            model = spur_pair_model(pair, (box.bodies["pinion"], box.bodies["gear"]),
                                    box.operation, options, ex)
            r = quasi_static_response(model.assembly().assemble())
            at = slice(None, None, r.time.size // POSITIONS)
            q += [_worst(f"{name}, {dofs}: dynamic TE at zero speed vs the contact's x_s",
                         "m", x, r.dte[0][at], 1e-10, solve, UM),
                  _worst(f"{name}, {dofs}: mesh force at zero speed vs the contact's P", "N",
                         np.full(r.mesh_force[0].shape, P), r.mesh_force[0], 1e-10, solve)]
            if dofs == "lateral_torsional":
                angular = (pair.pinion.base_radius * r.coordinate("pinion.theta")
                           - pair.gear.base_radius * r.coordinate("gear.theta"))
                kb = box.dynamics.bearing_stiffness if box.dynamics else 1e8
                q.append(_worst(f"{name}, {dofs}: angular TE - x_s vs the bearings' 2 P / k_b",
                                "m", np.full(x.shape, 2 * P / kb), angular[at] - x, 1e-8,
                                "the difference of two nearly equal TEs loses digits: the "
                                "tests hold 1e-8", UM))
                phase = np.arange(x.size) / x.size
                plots.append(Plot(f"{name} pair at zero speed: TE over one mesh cycle",
                                  "mesh phase [-]", "transmission error [um]",
                                  (Series("loaded contact x_s", phase, x * 1e6, "-"),
                                   Series("pair model, zero speed", phase,
                                          r.dte[0][at] * 1e6, "o"))))
    inputs = (("pairs", "workflows/configs/spur_pair_assembly_errors.toml (spur, 1 slice), "
                        "workflows/configs/traction_helical_pair.toml (helical, 8 slices)"),
              ("contact", f"analytical compliance, Weber's contact, tip contact on, "
                          f"{POSITIONS} positions, no friction"),
              ("model", "pair model, lateral-torsional and torsional, quasi-static response"))
    return Outcome("exact: static equilibrium at every phase (the zero-speed limit)", inputs,
                   tuple(q), plots=tuple(plots))
