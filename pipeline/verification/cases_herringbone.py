"""Case of a herringbone sun-planet mesh through the sun's relief groove
(:mod:`pipeline.contact.herringbone`): the load split against springs in series.

With a linear local contact, perfect flanks and contact confined to the nominal path,
every point in mesh is loaded, so each helical half is a linear spring of its own tangent
stiffness k = 1 / c and the groove (the beam groove of Xu et al. (2020), eq. 1,
k_t = K_j / l_LR) a torsional spring of compliance c_g = N r_b^2 / k_t on the line of
action. The planet's approach is common to both halves; with a fraction f of the torque
entering on the left (right entry f = 0, left f = 1, both ends f = 1/2) the groove carries
(1 - f) P_L - f P_R and the split is exact:
P_L / P = (c_R + f c_g) / (c_L + c_R + c_g).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pipeline.verification.context import Context
from pipeline.verification.model import Outcome, Plot, Quantity, Series

CONFIG = "configs/wind_turbine_herringbone_planetary.toml"
"""The Xu et al. (2020) wind-turbine herringbone planetary stage (under ``workflows/``)."""
L_LR = 0.225
"""O_L - O_R of the wind-turbine sun, m (185 mm half + 40 mm groove)."""
K_J = 4.0e7
"""Groove torsional rigidity K_j, N m^2 / rad (k_t = K_j / l_LR)."""
POSITIONS = 8
ENTRIES = {"right": 0.0, "left": 1.0, "both": 0.5}
"""Torque entry and the fraction f of the torque entering on the left."""


def case_herringbone_springs_in_series(context: Context) -> Outcome:
    """The left half's share of the load at every position against the springs-in-series
    split, for the torque entering right, left and at both ends."""
    from pipeline.config import load_gearbox
    from pipeline.contact import analytical_compliance
    from pipeline.contact.groove_flank import GrooveFlankCoupling
    from pipeline.contact.herringbone import HerringboneOptions, herringbone_mesh_cycle
    from pipeline.dynamics.models.planetary_gears import helical_half, mesh_operations

    path = context.reference_dir.parent / CONFIG
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing (it is in a source checkout's workflows/)")
    box = load_gearbox(str(path))
    ps = box.planetary
    pair = helical_half(ps.sun_planet)
    op = mesh_operations(ps, box.operation, 1)[0]  # the whole mesh: both halves
    src = dataclasses.replace(analytical_compliance(pair, op, box.contact, box.stiffness),
                              tip_contact=False)
    P, N = op.torque / pair.pinion.base_radius, ps.n_planets
    groove = GrooveFlankCoupling.torsion(K_J / L_LR)
    cg = N * pair.pinion.base_radius**2 / groove.torsional_stiffness
    q, series = [], []
    for entry, f in ENTRIES.items():
        hb = herringbone_mesh_cycle(src, P, groove, N,
                                    options=HerringboneOptions(torque_entry=entry),
                                    local="linear", positions=POSITIONS)
        cL, cR = 1.0 / hb.left.mesh_stiffness, 1.0 / hb.right.mesh_stiffness
        expected = (cR + f * cg) / (cL + cR + cg)
        share = hb.load_left / P
        i = int(np.argmax(np.abs(share / expected - 1.0)))
        q.append(Quantity(f"left half's share P_L / P, torque entering {entry} (the position "
                          "farthest from the reference)", "-", float(expected[i]),
                          float(share[i]), "relative", 1e-9,
                          "the solver's residual bound (1e-10 of the approach); the tests "
                          "hold 1e-9"))
        k = np.arange(len(share))
        series += [Series(f"gearpipe, {entry} entry", k, share, "o"),
                   Series(f"springs in series, {entry} entry", k, expected, "-")]
    plot = Plot("Herringbone sun-planet: left half's share of the mesh load",
                "mesh position [index over one mesh cycle]", "P_L / P [-]", tuple(series))
    inputs = (("stage", "Xu et al. (2020) wind-turbine herringbone planetary "
                        f"(workflows/{CONFIG}), one sun-planet mesh"),
              ("groove", f"beam torsion k_t = K_j / l_LR, K_j = {K_J:g} N m^2/rad, "
                         f"l_LR = {L_LR * 1e3:g} mm"),
              ("contact", f"linear local contact, contact on the nominal path, {POSITIONS} "
                          "positions"))
    return Outcome("exact: the halves and the groove as springs in series (planet approach "
                   "common to both halves)", inputs, tuple(q), plots=(plot,))
