"""Case of the loaded contact through a revolution with a runout
(:mod:`pipeline.contact.revolution`): exact in the contact problem.

A pinion runout e (phase phi) is a rigid translation of the pinion's teeth: at pinion angle
theta_1 every pair on the line of action gets the same gap e sin(phi + theta_1), which the
complementarity conditions of the contact problem (Yang et al. 2026, eqs. 27-29) carry into
the approach unchanged with the same loads, and the centre distance becomes a + e cos(phi +
theta_1 - alpha_wt). Each mesh cycle of the revolution is therefore the mesh-cycle contact
of the pair at its cycle's centre distance (positions moved by the roll shift) plus the
gap, to the solvers' round-off (the approach ~1e-5 m, residual bound 1e-10 of it). The part
the centre distance adds is linear in e, and the TE's order 1 carries e. The pair: z 50/50,
m 3 mm, 20 deg, b 20 mm, 340 N m, Weber's contact model with tip contact.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Outcome, Plot, Quantity, Series

RUNOUT_M, PHASE_RAD = 10e-6, 0.3
POSITIONS = 12
"""Contact positions per mesh cycle."""
CHECKED_CYCLES = (0, 13, 37)
"""Mesh cycles rebuilt independently."""


def _spur(z: int, name: str) -> GearSpec:
    return GearSpec(teeth=z, name=name, module=3e-3, pressure_angle=math.radians(20.0),
                    face_width=0.02, bore_radius=0.021,
                    material=Material(youngs_modulus=2.0e11, poisson_ratio=0.3))


def rebuilt_runout_cycles(src, load: float, errors, positions: int, cycles,
                          modifications=None, driver: str = "pinion") -> np.ndarray:
    """TE (m), shape (len(cycles), positions), of the mesh cycles ``cycles`` of a runout
    rebuilt independently of :func:`pipeline.contact.revolution.loaded_revolution`: the
    mesh-cycle contact on the pair at the centre distance of each cycle's middle, at the
    positions moved by the roll shift, plus the common gap of the instant. Exact in the
    contact problem (module docstring; Yang et al. 2026, eqs. 27-29): ``src`` the pair's
    compliance source, ``load`` the line-of-action load (N), ``errors`` the
    :class:`~pipeline.contact.tooth_errors.ToothErrors`."""
    from pipeline.contact.ltca import loaded_mesh_cycle
    from pipeline.contact.revolution import at_centre_distance
    from pipeline.contact.tooth_errors import (
        centre_distance_change,
        centre_line_turn,
        roll_shift,
        runout_gaps,
    )

    pair = src.pair
    s0 = pair.mesh_cycle(positions)
    out = []
    for c in cycles:
        middle = c * pair.base_pitch + np.mean(s0 - s0[0])
        da = centre_distance_change(pair, errors, middle)
        turn = float(centre_line_turn(pair, errors, middle))
        moved = GearPair(pair.pinion, pair.gear,
                         centre_distance=pair.operating_centre_distance + float(da))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            cyc = loaded_mesh_cycle(at_centre_distance(src, moved), load, modifications,
                                    "weber", s0 + roll_shift(pair, moved, turn),
                                    driver=driver)
        g1, g2 = runout_gaps(pair, errors, c * pair.base_pitch + s0 - s0[0])
        out.append(cyc.transmission_error + g1 + g2)
    return np.array(out)


def case_runout_revolution(context: Context) -> Outcome:
    """A pinion runout through a revolution: each mesh cycle against the pair at its centre
    distance plus e sin(phi + theta_1), linearity of the centre-distance part, order-1
    amplitude e."""
    from pipeline.contact.analysis import analytical_compliance, line_of_action_load
    from pipeline.contact.ltca import loaded_mesh_cycle
    from pipeline.contact.options import ContactOptions
    from pipeline.contact.revolution import loaded_revolution
    from pipeline.contact.tooth_errors import GearErrors, ToothErrors
    from pipeline.operation import OperatingPoint

    operation = OperatingPoint(torque=340.0, speed=2340.0 * math.pi / 30.0)
    pair = GearPair(_spur(50, "pinion"), _spur(50, "gear"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        src = analytical_compliance(pair, operation, ContactOptions(tip_contact=True))
        load = line_of_action_load(pair, operation)
        cyc = loaded_mesh_cycle(src, load, None, "weber", POSITIONS)

    def revolution(e):
        errors = ToothErrors(GearErrors(name="pinion", eccentricity=e,
                                        eccentricity_phase=PHASE_RAD), GearErrors(name="gear"))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return loaded_revolution(src, load, errors, positions=POSITIONS), errors

    rev, errors = revolution(RUNOUT_M)
    theta = rev.contact.pinion_angle
    te = rev.transmission_error.reshape(-1, POSITIONS)
    rebuilt = rebuilt_runout_cycles(src, load, errors, POSITIONS, CHECKED_CYCLES)
    nominal = np.tile(cyc.transmission_error, te.shape[0])
    rest = rev.transmission_error - nominal - RUNOUT_M * np.sin(PHASE_RAD + theta)
    small, _ = revolution(RUNOUT_M / 10)
    rest_small = (small.transmission_error - nominal
                  - RUNOUT_M / 10 * np.sin(PHASE_RAD + theta))
    # position 0 of each cycle lies at the path's start, where the TE steps (module notes)
    inner = np.abs(rest.reshape(-1, POSITIONS)[:, 1:]).max()
    inner_small = np.abs(rest_small.reshape(-1, POSITIONS)[:, 1:]).max()
    q = (Quantity("largest difference from the rebuilt mesh cycles 0, 13, 37", "m", 0.0,
                  float(np.abs(te[list(CHECKED_CYCLES)] - rebuilt).max()), "upper_bound", 1e-14,
                  "the solvers' round-off: residual bound 1e-10 of an approach of ~1e-5 m",
                  UM),
         Quantity("centre-distance part at e / 10 over that at e", "-", 0.1,
                  inner_small / inner, "relative", 0.02,
                  "linear in e; the quadratic term is 0.9 % at e = 10 um, full load"),
         Quantity("TE order-1 amplitude", "m", RUNOUT_M, rev.spectrum().at(1.0), "relative",
                  3e-3, "the mean TE's change with the centre distance and the path-start "
                        "step's share (measured 2.4e-3 of e at full load)", UM))
    deg = np.degrees(theta)
    plot = Plot("Pinion runout 10 um: TE through a revolution", "pinion angle [deg]",
                "transmission error [um]",
                (Series("gearpipe, revolution", deg, rev.transmission_error * 1e6, "-"),
                 Series("nominal mesh cycle + e sin(phi + theta_1)", deg,
                        (nominal + RUNOUT_M * np.sin(PHASE_RAD + theta)) * 1e6, "--")))
    inputs = (("pair", "spur z 50/50, m 3 mm, 20 deg, b 20 mm, E 200 GPa"),
              ("load", "340 N m on the pinion, Weber's contact model, tip contact on"),
              ("runout", f"pinion eccentricity {RUNOUT_M * 1e6:g} um, phase {PHASE_RAD:g} rad; "
                         f"{POSITIONS} positions per mesh cycle, 50 cycles"))
    return Outcome("exact: a runout is a rigid translation of the teeth, carried unchanged "
                   "through the contact conditions (Yang et al. 2026, eqs. 27-29)", inputs, q,
                   plots=(plot,),
                   notes="Position 0 of each mesh cycle lies at the start of the path of "
                         "contact, where the TE steps (corner contact before it): it is left "
                         "out of the linearity check.")
