"""Planetary models from the gearbox description: gears, bodies, carrier, operating point.

Builds the planar Lin and Parker (1999) model (:class:`PlanetaryModel`) or, for a
herringbone set, the model of Xu et al. (2020) (:class:`HerringbonePlanetaryModel`)
from a :class:`~pipeline.geometry.planetary.PlanetarySet`:

* masses and polar moments from the gear bodies (:class:`~pipeline.geometry.body.GearBody`,
  exact toothed sections, bores, rim, relief groove) and the carrier;
* base radii, the transverse operating pressure angles of the sun-planet and planet-ring
  pairs, the base helix angle, the carrier radius (the sun-planet centre distance) and
  the planet angles from the gears;
* meshing phases from :class:`PlanetarySet` (Xu et al. 2020, eqs. 10a-c): its phases are
  referenced to pitch-point crossings, the mesh signals of the pipeline start with the
  leading tooth pair at the start of contact, so sun mesh n is delayed by
  ``lambda_sn - o_sp`` and ring mesh n by ``lambda_rn + lambda_rs - o_pr`` mesh periods,
  ``o`` the fraction of a mesh period from the start of contact to the pitch point
  (:meth:`PlanetarySet.start_of_contact_offsets`);
* the mesh excitation of one sun-planet and one planet-ring mesh (k(t), e(t); see
  :mod:`pipeline.dynamics.mesh_input`), the same for every planet up to its phase.

Operating point: ``operation`` gives the torque (N m) and speed (rad/s) of the sun, which
drives (``driver = "pinion"``, the sun being the pinion of the sun-planet pair), with the
ring fixed: the carrier turns at ``omega_s z_s / (z_s + z_r)``, the mesh period is
``2 pi / ((omega_s - omega_c) z_s)`` (Xu et al. 2020, eq. 7) and each planet carries
``P = T_s / (N r_b,sun)`` along both of its lines of action (:func:`mesh_operations`
gives the operating points of one sun-planet and one planet-ring mesh for their
contact or stiffness analyses).

Frames and directions: the planar model is transverse, so for helical gears it takes
the transverse k(t) and e(t) and neglects the axial forces. The herringbone model works
along the flank normal with ``beta_b`` (Xu et al. 2020, eq. 17); one half of each mesh is
the helical pair of :func:`helical_half` at half the load, and its transverse signals
are turned normal by :func:`normal_excitation`. Friction terms of the excitation are not
applied in the planetary models (the line-of-action friction of Jin et al. 2018 is
written for fixed-axis pairs here). The left/right sun-mesh excitation of a herringbone
sun through its groove comes from the contact of both halves
(:mod:`pipeline.dynamics.herringbone_excitation`, passed as a (left, right) pair); the
published Fig. 5 percentages of Xu et al. (2020) are only a comparison
(:mod:`pipeline.dynamics.models.groove_mesh`). Not modelled: a stagger of the herringbone
halves.

``gearpipe modes|response|sweep`` on a planetary file build these models. Supports, groove
and damping are ``[dynamics]`` keys (``sun_bearing_stiffness_N_per_m``,
``ring_torsional_stiffness_Nm_per_rad``, ``groove_torsional_stiffness_Nm_per_rad``, ...:
``wind_turbine_herringbone_planetary.toml`` lists them; a sun on its shaft and planets on
pins give the sun's and the planets' bearing stiffness instead,
:func:`pipeline.run.planetary_shafts.support_stiffness`); with a ``[groove]`` table and
``excitation = "contact"`` the groove is its FE and a typed groove stiffness is refused.
Checks: a z 40/20/80 set at 24.6 deg with Lin and Parker's parameters has their Table 2;
``wind_turbine_herringbone_planetary.toml`` with the hand-built model's parameters has its
frequencies to round-off.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Protocol

import numpy as np

from pipeline.dynamics.mesh_input import MeshExcitation
from pipeline.dynamics.models.herringbone_planetary import HerringbonePlanetaryModel
from pipeline.dynamics.models.planetary import PlanetaryModel
from pipeline.dynamics.options import PlanetaryDynamicsOptions
from pipeline.geometry.body import GearBody
from pipeline.geometry.pair import GearPair
from pipeline.geometry.planetary import PlanetarySet, dec
from pipeline.operation import OperatingPoint
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError

if TYPE_CHECKING:
    from pipeline.fem.groove.result import GrooveStiffness

ROLES = ("sun", "planet", "ring")
LIN_PARKER_RING_SUPPORT = 1.0e9  # N/m at the ring's base circle (Lin and Parker 1999, Table 1)


class RigidBody(Protocol):
    """Mass (kg) and polar moment of inertia (kg m^2) of a body, e.g. the carrier."""

    mass: float
    inertia: float


def carrier_speed(planetary: PlanetarySet, operation: OperatingPoint) -> float:
    """Carrier speed omega_c = omega_s z_s / (z_s + z_r), rad/s (ring fixed, sun speed given)."""
    zs, zr = planetary.sun.teeth, planetary.ring.teeth
    return operation.speed * zs / (zs + zr)


def mesh_operations(planetary: PlanetarySet, operation: OperatingPoint, halves: int = 1
                    ) -> tuple[OperatingPoint, OperatingPoint]:
    """Operating points of one sun-planet and one planet-ring mesh (or one helical half).

    Parameters
    ----------
    planetary : the set.
    operation : sun torque (N m) and sun speed (rad/s), ring fixed, sun driving.
    halves : 1, or 2 for one half of a herringbone mesh (half the load).

    Returns
    -------
    (sun-planet, planet-ring) :class:`OperatingPoint`, each with the torque and speed of its
    pinion (the sun, the planet) relative to the carrier: the load along each line of
    action is ``T_s / (halves N r_b,sun)``.
    """
    _check_driver(operation)
    sp, pr = planetary.sun_planet, planetary.planet_ring
    relative = operation.speed - carrier_speed(planetary, operation)  # sun, carrier frame
    load = operation.torque / (halves * planetary.n_planets * sp.pinion.base_radius)
    return (OperatingPoint(load * sp.pinion.base_radius, relative, "pinion"),
            OperatingPoint(load * pr.pinion.base_radius,
                           relative * planetary.sun.teeth / planetary.planet.teeth, "pinion"))


def helical_half(pair: GearPair) -> GearPair:
    """One helical half of a herringbone pair as a helical pair (face width of one half)."""
    if not pair.pinion.herringbone:
        return pair

    def half(g):
        return dataclasses.replace(g, face_width=g.half_width, herringbone=False,
                                   groove_width=0.0)

    return GearPair(half(pair.pinion), half(pair.gear), pair.centre_distance)


def normal_excitation(excitation: MeshExcitation, base_helix_angle: float) -> MeshExcitation:
    """Transverse mesh signals -> along the flank normal (Xu et al. 2020, eq. 17).

    With ``delta_n = delta_t cos(beta_b)`` and ``F_n = F_t / cos(beta_b)``: ``k_n = k_t /
    cos^2(beta_b)``, ``e_n = e_t cos(beta_b)``, friction coefficients over ``cos(beta_b)``.
    """
    c = math.cos(base_helix_angle)

    def scaled(sig, factor):
        return None if sig is None else PeriodicSignal(sig.values * factor, sig.period)

    return dataclasses.replace(
        excitation,
        stiffness=scaled(excitation.stiffness, 1.0 / c**2),
        transmission_error=scaled(excitation.transmission_error, c),
        friction_stiffness=scaled(excitation.friction_stiffness, 1.0 / c),
        friction_torque_pinion=scaled(excitation.friction_torque_pinion, 1.0 / c),
        friction_torque_gear=scaled(excitation.friction_torque_gear, 1.0 / c),
    )


def mesh_phases(planetary: PlanetarySet) -> tuple[np.ndarray, np.ndarray]:
    """Delays (mesh periods, shape (N,) each, in [0, 1)) of the sun and ring meshes whose
    signals start at the start of contact (module docstring)."""
    o_sp, o_pr = planetary.start_of_contact_offsets()
    return (dec(planetary.sun_phases - o_sp),
            dec(planetary.ring_phases + planetary.ring_sun_phase - o_pr))


def _check_driver(operation: OperatingPoint) -> None:
    if operation.driver != "pinion":
        raise InputError("operation.driver = 'gear': the planetary models take the sun's "
                         "torque and speed with the ring fixed; set [operation] driver = "
                         "\"pinion\" (the sun) and give the sun's torque and speed")


def _common(planetary: PlanetarySet, bodies: Mapping[str, GearBody], carrier: RigidBody,
            operation: OperatingPoint, options: PlanetaryDynamicsOptions) -> dict:
    _check_driver(operation)
    missing = [r for r in ROLES if r not in bodies]
    if missing:
        raise InputError(f"planetary model: no gear body for {', '.join(missing)}")
    sun, planet, ring = (bodies[r] for r in ROLES)
    sp, pr = planetary.sun_planet, planetary.planet_ring
    phase_sun, phase_ring = mesh_phases(planetary)
    omega_c = carrier_speed(planetary, operation)
    kt_ring = options.ring_torsional_stiffness
    if kt_ring is None:
        kt_ring = LIN_PARKER_RING_SUPPORT * planetary.ring.base_radius**2
    return dict(
        n_planets=planetary.n_planets,
        mass_sun=sun.mass_, mass_planet=planet.mass_, mass_ring=ring.mass_,
        mass_carrier=carrier.mass,
        inertia_sun=sun.inertia_, inertia_planet=planet.inertia_, inertia_ring=ring.inertia_,
        inertia_carrier=carrier.inertia,
        base_radius_sun=planetary.sun.base_radius,
        base_radius_planet=planetary.planet.base_radius,
        base_radius_ring=planetary.ring.base_radius,
        carrier_radius=planetary.carrier_radius,
        pressure_angle_sun=sp.operating_pressure_angle,
        pressure_angle_ring=pr.operating_pressure_angle,
        k_sun=options.sun_bearing_stiffness, k_ring=options.ring_bearing_stiffness,
        k_carrier=options.carrier_bearing_stiffness, k_planet=options.planet_bearing_stiffness,
        kt_sun=options.sun_torsional_stiffness, kt_ring=kt_ring,
        kt_carrier=options.carrier_torsional_stiffness,
        planet_angles=tuple(planetary.angles),
        phase_sun=tuple(phase_sun), phase_ring=tuple(phase_ring),
        damping_ratio=options.damping_ratio,
        modal_damping_ratio=options.modal_damping_ratio,
        sun_torque=operation.torque,
        carrier_speed=omega_c,
        mesh_period=planetary.mesh_period(operation.speed, omega_c),
    )


def planetary_model_from_gears(
    planetary: PlanetarySet,
    bodies: Mapping[str, GearBody],
    carrier: RigidBody,
    operation: OperatingPoint,
    options: PlanetaryDynamicsOptions,
    sun_excitation: MeshExcitation,
    ring_excitation: MeshExcitation,
    drive_torsion: float | None = None,
) -> PlanetaryModel:
    """The planar planetary model (Lin and Parker 1999) of a set, derived from its gears.

    Parameters
    ----------
    planetary : sun, planet, ring, planet angles and phases.
    bodies : gear bodies by role "sun", "planet", "ring" (kg, kg m^2).
    carrier : the carrier's mass (kg) and polar moment (kg m^2).
    operation : sun torque (N m) and speed (rad/s), ring fixed, sun driving.
    options : supports, damping (the herringbone-only options must not be given).
    sun_excitation, ring_excitation : k(tau) (N/m) and e(tau) (m) of one sun-planet and one
        planet-ring mesh along the transverse line of action, signals starting at the
        start of contact (e.g. from :func:`mesh_operations` and the contact analysis).
    drive_torsion : the sun shaft's torsional stiffness between its seat and its torque
        point, N m/rad (:mod:`pipeline.shaft`), tying ``options.drive_inertia`` (the motor)
        to the sun; None: no shaft.
    """
    if options.drive_inertia is not None and drive_torsion is None:
        raise InputError("dynamics.drive_inertia_kgm2 needs [sun.shaft]: the torsional "
                         "stiffness between it and the sun is its shaft's")
    if options.herringbone_keys:
        raise InputError(f"dynamics.{options.herringbone_keys[0]} applies to a herringbone "
                         "set; this planetary set has no herringbone gears")
    return PlanetaryModel(
        **_common(planetary, bodies, carrier, operation, options),
        k_sun_mesh=sun_excitation.stiffness, k_ring_mesh=ring_excitation.stiffness,
        e_sun_mesh=sun_excitation.transmission_error,
        e_ring_mesh=ring_excitation.transmission_error,
        inertia_drive=options.drive_inertia,
        kt_drive=None if options.drive_inertia is None else drive_torsion,
    )


def herringbone_planetary_model_from_gears(
    planetary: PlanetarySet,
    bodies: Mapping[str, GearBody],
    carrier: RigidBody,
    operation: OperatingPoint,
    options: PlanetaryDynamicsOptions,
    sun_excitation: MeshExcitation | tuple[MeshExcitation, MeshExcitation],
    ring_excitation: MeshExcitation,
    *,
    groove: float | np.ndarray | GrooveStiffness | None = None,
    sun_load_side: str | None = None,
) -> HerringbonePlanetaryModel:
    """The herringbone planetary model (Xu et al. 2020, 8(N+3) DOF) of a set, from its gears.

    Parameters as for :func:`planetary_model_from_gears`; the excitations are those of one
    helical half (:func:`helical_half` at half the load, transverse line of action) and are
    turned normal here (:func:`normal_excitation`). ``sun_excitation`` may be a (left,
    right) pair, one per half (the herringbone contact through the groove,
    :func:`pipeline.dynamics.herringbone_excitation.excitation_from_herringbone`): the
    static twist of the halves is then in their transmission errors and the right sun
    meshes get no twist phase. Otherwise the sun's halves are joined by the groove options
    (Xu et al. 2020, eq. 1: a torsional spring; the right sun meshes then lag by the twist
    phase lambda_LR = dec(z_s T_s / (2 pi k_groove)), eq. 11, as in
    :func:`pipeline.dynamics.models.wind_turbine_planetary.wind_turbine_herringbone_model`)
    or tied; planet, ring and carrier halves are tied. ``groove`` (a
    :class:`~pipeline.fem.groove.result.GrooveStiffness` or its 12 x 12 matrix) replaces
    the groove options by the FE coupling; ``sun_load_side`` ("both", "L", "R") replaces
    the option of that name.
    """
    if not planetary.sun.herringbone:
        raise InputError("the herringbone planetary model needs herringbone gears "
                         "(herringbone = true in [sun], [planet] and [ring])")
    beta_b = planetary.sun.base_helix_angle
    per_side = isinstance(sun_excitation, tuple)
    sun_n = [normal_excitation(e, beta_b) for e in (sun_excitation if per_side
                                                    else (sun_excitation,))]
    ring_n = normal_excitation(ring_excitation, beta_b)
    k_groove = options.groove_torsional_stiffness if groove is None else groove
    lateral = options.groove_lateral_stiffness if groove is None else None
    phase_lr = 0.0
    if not per_side and k_groove is not None:
        k_t = getattr(k_groove, "torsional_stiffness", k_groove)
        if np.ndim(k_t) == 0:
            phase_lr = planetary.left_right_phase(operation.torque / float(k_t))
    common = _common(planetary, bodies, carrier, operation, options)

    def axial(value, member):
        return common[f"k_{member}"] if value is None else value

    def sides(name):
        values = tuple(getattr(e, name) for e in sun_n)
        return values if per_side else values[0]

    return HerringbonePlanetaryModel(
        **common,
        base_helix_angle=beta_b,
        k_sun_mesh=sides("stiffness"), k_ring_mesh=ring_n.stiffness,
        e_sun_mesh=sides("transmission_error"), e_ring_mesh=ring_n.transmission_error,
        kz_sun=axial(options.sun_axial_stiffness, "sun"),
        kz_ring=axial(options.ring_axial_stiffness, "ring"),
        kz_carrier=axial(options.carrier_axial_stiffness, "carrier"),
        kz_planet=axial(options.planet_axial_stiffness, "planet"),
        groove=k_groove,
        groove_translational=None if lateral is None else (lateral, lateral, lateral),
        sun_load_side=sun_load_side or options.sun_load_side,
        phase_lr=phase_lr,
    )
