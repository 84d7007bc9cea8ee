"""Left and right sun-planet mesh excitation of a herringbone set from its loaded contact.

:func:`pipeline.contact.herringbone.herringbone_mesh_cycle` solves both helical halves of
a sun-planet mesh together through the sun's relief groove. Each half h then has, over
the mesh cycle, its own load P_h(t), its own flank approach x_h(t) (static transmission
error along the transverse line of action) and its own tangent mesh stiffness
k_h = dP_h/dx_h (teeth and local contact of that half only). As in
:mod:`pipeline.dynamics.contact_excitation`, the displacement excitation is chosen so
that the linearised mesh law gives the contact's static state:
``e_h(t) = x_h(t) - P_h(t) / k_h(t)``, hence ``k_h (x_h - e_h) = P_h``. Unlike a single
helical pair, P_h varies over the cycle (the split between the halves moves with the
contact lines), so it is taken per position.

What the dynamic model must hold itself: the groove (the twist of the halves is a DOF
joined by the groove stiffness, so the herringbone model gets the same FE 12 x 12), the
planet's and the sun's supports, and where the sun torque acts (``torque_entry``). The
static twist between the halves is in each half's x_h, so the right meshes get no extra
phase lambda_LR (Xu et al. 2020, eq. 11): in the contact both halves sit at the same
mesh position of the planet and the twist moves the flanks, not the contact lines (its
phase, z_s phi / 2 pi, is 2e-3 of a mesh period for the wind-turbine sun).
Friction terms are not formed (the planetary models do not apply them).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.contact.herringbone_results import SIDES, HerringboneCycle
from pipeline.dynamics.mesh_input import MeshExcitation
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError


def excitation_from_herringbone(
    cycle: HerringboneCycle, pair: GearPair, operation: OperatingPoint
) -> tuple[MeshExcitation, MeshExcitation]:
    """(left, right) mesh excitation of one herringbone sun-planet mesh (module docstring).

    Parameters
    ----------
    cycle : the herringbone contact over one mesh cycle of ``pair`` (equally spaced
        positions, >= 4).
    pair : the helical-half pair it was computed on (sun = pinion).
    operation : the sun's speed relative to the carrier (rad/s) as the pinion speed
        (``mesh_operations``): sets the mesh period.

    Returns
    -------
    (left, right) :class:`MeshExcitation` along the transverse line of action: k_h (N/m),
    e_h = x_h - P_h / k_h (m), ``load`` the half's mean load (N), ``source = "contact"``.

    Raises
    ------
    InputError when a half is unloaded somewhere (k_h = 0: the linearised model does not
    hold; a slide or a groove that lifts a half off needs the contact itself).
    """
    m = len(cycle)
    if m < 4:
        raise InputError(f"herringbone contact has {m} positions; a mesh excitation needs >= 4 "
                         "(contact.positions)")
    if not np.allclose(cycle.left.s0, pair.mesh_cycle(m), rtol=0.0, atol=1e-9 * pair.base_pitch):
        raise InputError("the herringbone contact is not one mesh cycle of equally spaced "
                         "positions of this pair (pair.mesh_cycle)")
    speed = operation.speed if operation.driver == "pinion" else operation.speed * pair.gear_ratio
    period = 2.0 * math.pi / (abs(speed) * pair.pinion.teeth)
    out = []
    for side in SIDES:
        half, load = cycle.half(side), cycle.half_load(side)
        k = half.mesh_stiffness
        if np.any(k <= 0.0):
            i = int(np.argmin(k))
            raise InputError(f"herringbone contact: the {side} half carries {load[i]:.6g} N at "
                             f"position {i} (mesh stiffness {k[i]:.6g} N/m); a linearised mesh "
                             "excitation needs both halves loaded at every position")
        zero = PeriodicSignal(np.zeros(m), period)
        out.append(MeshExcitation(
            stiffness=PeriodicSignal(k, period),
            friction_stiffness=zero, friction_torque_pinion=zero, friction_torque_gear=zero,
            mesh_period=period,
            tooth_model=f"herringbone contact, {side} half ({half.local_contact} local contact)",
            transmission_error=PeriodicSignal(half.transmission_error - load / k, period),
            load=float(load.mean()),
            source="contact",
        ))
    return out[0], out[1]
