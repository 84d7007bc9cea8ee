"""Mesh excitation from the loaded tooth contact: k(t), static transmission error, friction.

The loaded tooth contact analysis (:func:`pipeline.contact.analyse_contact`, any
compliance source: analytical slices, FE 2D, FE 3D) gives over one mesh cycle, at the
load P along the transverse line of action, the loaded static transmission error x_s
(the approach of the flanks along the line of action, gear centres fixed), the mesh
stiffness (tangent k_t = dP/dx_s, secant, pointwise) and the load F_i of every loaded
point. :func:`excitation_from_contact` turns them into the
:class:`~pipeline.dynamics.mesh_input.MeshExcitation` of one mesh.

Method
------
* **Stiffness.** The dynamic model linearises the mesh force about the static state:
  ``F = k(t) (delta - e(t))``. The tangent stiffness k_t is that linearisation (a small
  dynamic approach changes the load by k_t times it), so it is the default;
  ``stiffness="secant"`` or ``"pointwise"`` use the other definitions of
  :mod:`pipeline.contact.results`.
* **Transmission error.** The displacement excitation is chosen so that the static
  state of the linearised law is the contact analysis' state:
  ``e(t) = x_s(t) - P / k(t)``, hence ``k (x_s - e) = P`` exactly at every position.
  With the secant stiffness this is the unloaded transmission error x_0 = min eps
  (the approach where the first point touches); with the tangent stiffness it is the
  point where the tangent to the load-approach curve meets P = 0, which differs
  from x_0 by the nonlinearity of the local (Hertz) approach. Both reproduce the
  static state; they differ in how the mesh answers a dynamic change of load.
* **Friction** (Jin et al. 2018, eqs. 15-17, signs of :mod:`pipeline.stiffness.friction`
  and :func:`pipeline.dynamics.mesh_input.friction_signals`): the friction force of the
  loaded points is ``sum_i lam_i mu_i F_i`` and the friction torques
  ``sum_i lam_i mu_i F_i rho_k,i`` (arms rho_1 = s, rho_2 = |rho_2(s)| of
  :meth:`GearPair.curvature_radii`), with ``lam`` of
  :func:`pipeline.stiffness.friction.friction_direction` and ``mu`` a constant or the
  EHL coefficient (Jin et al. 2018, eq. 9) at each point's own Hertz pressure from its
  unit load F_i / w_i (the stiffness stage shares the load evenly instead). They
  follow the mesh force: ``K_f = k sum lam mu F_i / P``, ``KT_fk = k sum lam mu F_i rho_k / P``,
  so that ``K_f (delta - e)`` is the loaded points' friction force at the static state
  and scales with the mesh force around it (the load shares of the static state). As in
  the stiffness stage, mu multiplies the transverse load (the normal load of a helical
  flank is ``F / cos(beta_b)``: 0.2 % more for the helical pair of Yang et al. 2026).

Static limit (the consistency the tests check): at vanishing speed the inertia and
damping forces vanish, the gear rotations balance the torques, ``F r_b1 = T_1``, so the
mesh force is P; the mesh law then gives ``delta = e + P / k = x_s``. ``delta`` is the
dynamic transmission error of :class:`~pipeline.dynamics.results.Response`, the mesh
compression between the gear centres as they are displaced
(``x_p - x_g + r_bp theta_p - r_bg theta_g`` in the lateral-torsional pair): the bearings
deflect the centres under the mesh force (``x_p - x_g = -2 P / k_b``), which shifts the
*angular* transmission error ``r_bp theta_p - r_bg theta_g`` by ``+2 P / k_b`` but changes
neither delta nor F. The contact analysis holds the centres (the FE sources: the bores)
fixed, so its x_s is the model's delta. With friction torques in the model the torque
balance carries the friction moments as well (the contact analysis takes
``P = T / r_b`` without them), so the static mesh force differs from P by a fraction
of order ``mu rho / r_b`` (0.6-1.5 % on the helical pair of Yang et al. 2026 at mu = 0.05).

What the mesh stiffness contains, and what the dynamic model must not count again
---------------------------------------------------------------------------------
* Analytical slices (:class:`~pipeline.contact.source.SliceCompliance`): tooth bending,
  shear and axial compression of both teeth, the fillet-foundation (gear body) term of
  Sainsot et al. (2004) (a body of the gear's bore radius), and the local Hertz approach
  that the contact solver adds.
* FE 2D/3D (:class:`~pipeline.contact.FE2DCompliance`, :class:`~pipeline.contact.FE3DCompliance`):
  everything between the loaded flank and the *bore* of each gear, which the FE holds
  fixed (the outer rim of a ring gear): tooth bending, shear and axial compression,
  fillet and foundation, the rim and web, the body's torsion between bore and root,
  and the coupling of the teeth in contact through the body (and, in 3D, across the
  face); the Hertz near field is removed from the FE and the contact solver adds the
  local approach (Yang et al. 2026, eq. 24). A sector with clamped cuts is stiffer than
  the whole gear (:mod:`pipeline.fem.influence`).

The dynamic models treat each gear body as rigid from its bore outwards (its mass and
polar moment, :class:`~pipeline.geometry.body.GearBody`) and attach bearings, shafts and
supports at the bore. Nothing of the above is therefore counted twice, provided that:
the bearing stiffnesses are those of the bearings and housing alone (the FE's fixed
bore excludes any bore motion, and the model's bearing springs move the rigid bore:
in series, not overlapping); a torsional shaft (split-torque model) is the shaft
between its seats, without the gear body, whose torsion from bore to root is already
in the mesh stiffness; a ring gear's support is that of the housing or splines outside
its rim. The one overlap the models keep is the relief-groove coupling of a
herringbone sun (:mod:`pipeline.fem.groove`): it is the twist between the rigid fits of
the two halves' outer surfaces, which includes some torsion of each half's own body that
the FE mesh stiffness of that half also contains (small when the groove is slender).

Checks: at zero speed the model has the contact analysis' load P and its static TE x_s as
DTE to 1e-10 on the spur pair of the assembly-error paper and the helical pair of Yang et
al. (2026); the harmonic balance at 1e-3 of the first natural frequency converges to it at
first order in 1/H (3 % of the TE's peak-to-peak at H = 160 next to a tooth pair entering
or leaving, < 0.05 % elsewhere). With the linear local contact and perfect flanks the
excitation equals the analytical one exactly. Measured on the pair of the assembly-error
paper at 2340 rpm: DTE 25.0 um peak-to-peak with the analytical k(t) (the nominal path's);
with the loaded contact, whose tip corners touch beyond the path, 8.3 um (analytical
slices, Weber local approach, 360 positions) and 11.2 um (whole-gear FE 2D, 40 positions);
confined to the nominal path the loaded contact gave 35.0 um;
``workflows/excitation_comparison.py`` compares the excitations over a speed range.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.contact.results import LoadedMeshCycle
from pipeline.dynamics.mesh_input import MeshExcitation, friction_signals, with_resolved_jumps
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.signals import PeriodicSignal
from pipeline.stiffness.friction import (
    ehl_friction_coefficient,
    friction_direction,
    hertz_line_pressure,
)
from pipeline.stiffness.mesh import FrictionModel
from pipeline.validation import InputError, check_choice

STIFFNESS_DEFINITIONS = ("tangent", "secant", "pointwise")


def pinion_speed(pair: GearPair, operation: OperatingPoint) -> float:
    """Pinion speed, rad/s, from the driver's speed."""
    return operation.speed if operation.driver == "pinion" else operation.speed * pair.gear_ratio


def point_friction_coefficients(
    cycle: LoadedMeshCycle,
    pair: GearPair,
    operation: OperatingPoint,
    friction: FrictionModel,
) -> np.ndarray:
    """Friction coefficient mu (-) of every candidate point of the cycle, shape (n_total,).

    Constant ``friction.mu``, or the EHL regression (Jin et al. 2018, eq. 9) at each loaded
    point's maximum Hertz pressure from its unit load ``F_i / w_i`` (N/m of contact line),
    its slide-to-roll ratio and entraining velocity at the pinion speed of ``operation``.
    Unloaded points get 0 (they carry no friction force).
    """
    loaded = cycle.point_load > 0.0
    if friction.kind == "constant":
        return np.where(loaded, friction.mu, 0.0)
    s = cycle.point_s[loaded]
    u1, u2 = pair.rolling_velocities(s, pinion_speed(pair, operation))
    rho1, rho2 = pair.curvature_radii(s)
    r_eff = np.abs(rho1 * rho2 / (rho1 + rho2))
    e_prime = 2.0 / (1.0 / pair.pinion.material.plane_strain_modulus
                     + 1.0 / pair.gear.material.plane_strain_modulus)
    ph = hertz_line_pressure(cycle.point_unit_load[loaded], r_eff, e_prime)
    mu = np.zeros(cycle.point_load.size)
    mu[loaded] = ehl_friction_coefficient(2.0 * (u1 - u2) / (u1 + u2), ph, u1 + u2,
                                          friction.viscosity, r_eff, friction.roughness)
    return mu


def _check_cycle(cycle: LoadedMeshCycle, pair: GearPair) -> None:
    m = len(cycle)
    if m < 4:
        raise InputError(f"contact cycle has {m} positions; a mesh excitation needs >= 4 "
                         "(contact.positions)")
    if not pair.is_mesh_cycle(cycle.s0):
        raise InputError("the contact cycle is not one mesh cycle of equally spaced positions "
                         "of this pair (pair.mesh_cycle): a mesh excitation needs "
                         "analyse_contact(..., positions=<number>) on the same pair")


def excitation_from_contact(
    cycle: LoadedMeshCycle,
    pair: GearPair,
    operation: OperatingPoint,
    friction: FrictionModel | None = None,
    *,
    stiffness: str = "tangent",
) -> MeshExcitation:
    """The mesh excitation of one mesh from its loaded tooth contact (module docstring).

    Parameters
    ----------
    cycle : loaded contact over one mesh cycle of ``pair`` (equally spaced positions,
        >= 4) at the load P of ``operation``, from any compliance source.
    pair : the pair the cycle was computed on (the actual pair, after assembly errors).
    operation : driver and its speed (rad/s): mesh period, friction direction, EHL
        velocities. Its torque is already in ``cycle.load``.
    friction : the friction model the compliance source used (constant mu or EHL), or
        ``None`` for no friction terms.
    stiffness : "tangent" (default, k_t = dP/dx_s), "secant" or "pointwise".

    Returns
    -------
    MeshExcitation with ``source = "contact"``, ``load = cycle.load`` (N), k (N/m),
    e = x_s - P / k (m), K_f (N/m), KT_f1, KT_f2 (N m/m) sampled at the cycle's positions;
    for a spur pair at ``max(positions, EXCITATION_SAMPLES)`` phases with the jumps where
    tooth pairs enter and leave at their exact phases
    (:func:`~pipeline.dynamics.mesh_input.with_resolved_jumps`) when contact is confined
    to the path. Where tip corners touch beyond it, the signals change where the corners
    close and open, at phases the load sets, and are kept at the cycle's positions (demo
    pair, 2340 rpm: the dynamic factor at 60 positions is then within 0.02 % of 360 and 720
    positions; resolving the nominal phases moved it by -0.3 %, interpolating to 360
    phases by -0.3 %). Friction acts on the path only (no
    friction force at a tip corner).
    """
    check_choice("stiffness", stiffness, STIFFNESS_DEFINITIONS)
    _check_cycle(cycle, pair)
    load = cycle.load
    k = {"tangent": cycle.mesh_stiffness, "secant": cycle.mesh_stiffness_secant,
         "pointwise": cycle.mesh_stiffness_pointwise}[stiffness]
    if not np.all(np.isfinite(k)) or np.any(k <= 0.0):
        bad = int(np.argmin(np.where(np.isfinite(k), k, -np.inf)))
        raise InputError(f"contact cycle: the {stiffness} mesh stiffness at position {bad} is "
                         f"{k[bad]:.6g} N/m; a mesh excitation needs k > 0 everywhere")
    period = 2.0 * math.pi / (pinion_speed(pair, operation) * pair.pinion.teeth)
    m = len(cycle)
    if friction is None:
        friction = FrictionModel(mu=0.0)
    mu = point_friction_coefficients(cycle, pair, operation, friction)
    lam = friction_direction(cycle.point_s, pair.s_pitch, operation.driver)
    rho1, rho2 = pair.curvature_radii(cycle.point_s)
    force = np.where(cycle.point_corner == 0, lam * mu * cycle.point_load, 0.0)  # N

    def per_position(values: np.ndarray) -> np.ndarray:
        return np.bincount(cycle.point_position, weights=values, minlength=m)

    kf, kt1, kt2 = friction_signals(per_position(force) * k / load,
                                    per_position(force * rho1) * k / load,
                                    per_position(force * np.abs(rho2)) * k / load, period)
    excitation = MeshExcitation(
        stiffness=PeriodicSignal(k, period),
        friction_stiffness=kf,
        friction_torque_pinion=kt1,
        friction_torque_gear=kt2,
        mesh_period=period,
        tooth_model=f"contact ({cycle.local_contact} local contact)",
        transmission_error=PeriodicSignal(cycle.transmission_error - load / k, period),
        load=load,
        source="contact",
    )
    if np.any(cycle.point_load[cycle.point_corner > 0] > 0.0):
        return excitation
    return with_resolved_jumps(excitation, pair)
