"""Six-DOF lateral-torsional spur pair of the assembly-error paper.

Coordinates ``pinion.x, pinion.y, pinion.theta, gear.x, gear.y, gear.theta``;
x lies along the line of action, each gear's theta is positive in its own
sense of rotation (the gear turns opposite to the pinion), so the dynamic
transmission error is ``delta = x_p - x_g + r_bp theta_p - r_bg theta_g``
(the assembly-error paper) and the mesh force ``F = k(t) (delta - e) + c delta'`` with
``c = 2 zeta sqrt(k_mean m_e)``, ``m_e = 1 / (r_bp^2 / I_p + r_bg^2 / I_g)``.
The pinion carries the input torque T_p, the gear the balancing load
``T_g = T_p r_bg / r_bp``.

With drive inertias (gears on shafts, :mod:`pipeline.shaft`): a ``drive`` body (the motor's
rotor, theta only, turning with the pinion) is tied to the pinion by its shaft's torsional
stiffness between the seat and the torque point, and takes T_p; a ``load`` body (the driven
machine, turning with the gear) is tied to the gear the same way and takes -T_g. The
two-inertia frequency of such a shaft is ``sqrt(k_t (J_1 + J_2) / (J_1 J_2)) / 2 pi``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.dynamics.assembly import Assembly
from pipeline.dynamics.bodies import Body
from pipeline.dynamics.couplings import Bearing, FrictionLoad, GearMesh, Load, TorsionalShaft
from pipeline.dynamics.mesh_geometry import cylindrical_mesh_measure, friction_direction_measure
from pipeline.dynamics.mesh_input import MeshExcitation
from pipeline.dynamics.models.planetary import MAX_SPEED, MAX_TORQUE, check_body_range
from pipeline.dynamics.options import PairDynamicsOptions
from pipeline.geometry.body import GearBody
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_int_range, check_range


@dataclass(frozen=True)
class SpurPairModel:
    """Inputs of the spur pair of the assembly-error paper (defaults: its Table of base
    parameters).

    Attributes
    ----------
    mesh_stiffness : k(tau) over one mesh period, N/m.
    pinion_teeth : z_p (sets the mesh frequency z_p n_p / 60).
    base_radius_pinion, base_radius_gear : m.
    mass_pinion, mass_gear : kg.
    inertia_pinion, inertia_gear : kg m^2.
    bearing_stiffness : N/m in x and y for both gears.
    gear_bearing_stiffness : N/m in x and y of the gear alone (its shaft's support at the
        seat), or None for ``bearing_stiffness``; ``bearing_stiffness`` is then the
        pinion's.
    bearing_damping : N s/m in x and y.
    damping_ratio : mesh damping ratio zeta.
    torque : input torque on the pinion, N m.
    speed : pinion speed, rad/s.
    transmission_error : e(tau) in m, or ``None``.
    friction_stiffness : K_f(tau) in N/m (Jin et al. 2018, eq. 16), or ``None``.
    friction_torque_pinion, friction_torque_gear : K_Tf(tau) in N m/m, or ``None``.
    torsional_only : keep only the two rotations (2-inertia model).
    t1t2 : length of the line of action between the base circles' tangent points T1 T2,
        m; places the gear in mode-shape drawings only (``None``: not known, the base
        circles of an external pair are drawn touching).
    gear_internal : the gear is an internal gear (a ring): in mode-shape drawings its base
        circle encloses the pinion's, its centre on the pinion's side of the line of action,
        and it turns the pinion's way. The equations are those of the external pair: each
        rotation is measured in its gear's own sense of rotation, in which both base
        tangent points move the same way along the line of action.
    inertia_drive, kt_drive : the motor behind the pinion's shaft, kg m^2, and the shaft's
        torsional stiffness between it and the pinion, N m/rad; both None: the input
        torque acts on the pinion.
    inertia_load, kt_load : the driven machine behind the gear's shaft and its shaft's
        torsional stiffness, likewise.
    """

    mesh_stiffness: PeriodicSignal
    pinion_teeth: int = 50
    base_radius_pinion: float = 0.075 * math.cos(math.radians(20.0))
    base_radius_gear: float = 0.075 * math.cos(math.radians(20.0))
    mass_pinion: float = 2.52
    mass_gear: float = 2.52
    inertia_pinion: float = 7.4e-3
    inertia_gear: float = 7.4e-3
    bearing_stiffness: float = 1.0e8
    gear_bearing_stiffness: float | None = None
    bearing_damping: float = 100.0
    damping_ratio: float = 0.07
    torque: float = 340.0
    speed: float = 2340.0 * 2 * math.pi / 60
    transmission_error: PeriodicSignal | None = None
    friction_stiffness: PeriodicSignal | None = None
    friction_torque_pinion: PeriodicSignal | None = None
    friction_torque_gear: PeriodicSignal | None = None
    torsional_only: bool = False
    t1t2: float | None = None
    gear_internal: bool = False
    inertia_drive: float | None = None
    kt_drive: float | None = None
    inertia_load: float | None = None
    kt_load: float | None = None

    def __post_init__(self) -> None:
        check_int_range("pinion_teeth", self.pinion_teeth, 5, 10_000)
        for f in ("base_radius_pinion", "base_radius_gear", "mass_pinion", "mass_gear",
                  "inertia_pinion", "inertia_gear"):
            check_body_range(f, getattr(self, f))
        check_range("torque", self.torque, 0.0, MAX_TORQUE, lo_open=True, unit="N m")
        check_range("speed", self.speed, 0.0, MAX_SPEED, lo_open=True, unit="rad/s")
        check_range("bearing_stiffness", self.bearing_stiffness, 0.0, 1e14, unit="N/m")
        if self.gear_bearing_stiffness is not None:
            check_range("gear_bearing_stiffness", self.gear_bearing_stiffness, 0.0, 1e14,
                        unit="N/m")
        check_range("bearing_damping", self.bearing_damping, 0.0, 1e9, unit="N s/m")
        check_range("damping_ratio", self.damping_ratio, 0.0, 1.0)
        for name in ("drive", "load"):
            inertia, k_t = getattr(self, f"inertia_{name}"), getattr(self, f"kt_{name}")
            if inertia is not None:
                check_body_range(f"inertia_{name}", inertia)
            if k_t is not None:
                check_range(f"kt_{name}", k_t, 0.0, 1e14, lo_open=True, unit="N m/rad")
            if (inertia is None) != (k_t is None):
                raise InputError(f"inertia_{name} and kt_{name} go together: the {name} "
                                 "inertia sits behind a shaft of that torsional stiffness")

    @property
    def drive(self) -> tuple[float, float] | None:
        """(inertia kg m^2, torsional stiffness N m/rad) of the motor, or None."""
        return None if self.inertia_drive is None else (self.inertia_drive, self.kt_drive)

    @property
    def load(self) -> tuple[float, float] | None:
        """(inertia kg m^2, torsional stiffness N m/rad) of the driven machine, or None."""
        return None if self.inertia_load is None else (self.inertia_load, self.kt_load)

    @property
    def mesh_period(self) -> float:
        """T_m = 2 pi / (z_p Omega_p), s."""
        return 2 * math.pi / (self.pinion_teeth * self.speed)

    def assembly(self) -> Assembly:
        """Bodies, bearings, mesh and torques of the pair."""
        dofs = ("theta",) if self.torsional_only else ("x", "y", "theta")
        p = Body("pinion", self.mass_pinion, self.inertia_pinion, dofs)
        g = Body("gear", self.mass_gear, self.inertia_gear, dofs)
        measure = cylindrical_mesh_measure(
            p, g, 0.0, self.base_radius_pinion, self.base_radius_gear, spin1=1, spin2=-1
        )
        friction = []
        if self.friction_stiffness is not None and not self.torsional_only:
            friction.append(
                FrictionLoad(self.friction_stiffness, friction_direction_measure(p, g, 0.0))
            )
        if self.friction_torque_pinion is not None:
            friction.append(FrictionLoad(self.friction_torque_pinion, {("pinion", "theta"): 1.0}))
        if self.friction_torque_gear is not None:
            friction.append(FrictionLoad(self.friction_torque_gear, {("gear", "theta"): 1.0}))
        couplings: list[object] = [
            GearMesh(
                "mesh",
                measure,
                self.mesh_stiffness,
                self.damping_ratio,
                transmission_error=self.transmission_error,
                friction=tuple(friction),
            ),
        ]
        if not self.torsional_only:
            gear_k = (self.bearing_stiffness if self.gear_bearing_stiffness is None
                      else self.gear_bearing_stiffness)
            for b, k in (("pinion", self.bearing_stiffness), ("gear", gear_k)):
                couplings.append(
                    Bearing(
                        b,
                        {"x": k, "y": k},
                        {"x": self.bearing_damping, "y": self.bearing_damping},
                    )
                )
        bodies = [p, g]
        torque_on = {"pinion": "pinion", "gear": "gear"}
        for name, gear, given in (("drive", "pinion", self.drive), ("load", "gear", self.load)):
            if given is not None:
                bodies.append(Body(name, 0.0, given[0], ("theta",)))
                couplings.append(TorsionalShaft(name, gear, given[1]))
                torque_on[gear] = name
        loads = [
            Load(torque_on["pinion"], "theta", self.torque),
            Load(torque_on["gear"], "theta",
                 -self.torque * self.base_radius_gear / self.base_radius_pinion),
        ]
        return Assembly(tuple(bodies), couplings, loads, period=self.mesh_period,
                        name="spur-pair")


def spur_pair_model(
    pair: GearPair,
    bodies: tuple[GearBody, GearBody],
    operation: OperatingPoint,
    options: PairDynamicsOptions,
    excitation: MeshExcitation | None = None,
    supports: tuple[float | None, float | None] = (None, None),
    torsion: tuple[float | None, float | None] = (None, None),
) -> SpurPairModel:
    """The lateral-torsional (or torsional) model of a pair, everything derived from geometry.

    Parameters
    ----------
    pair : the actual pair (its base radii and the pinion's tooth count are used).
    bodies : pinion and gear bodies (mass in kg, polar moment in kg m^2, derived from the
        geometry unless overridden).
    operation : pinion torque (N m) and speed (rad/s); the pinion must drive.
    options : bearings, damping, degrees of freedom, an optional explicit k(tau).
    excitation : k(tau), the transmission error e(tau) and the friction terms of the mesh
        (from the stiffness stage, :func:`pipeline.dynamics.mesh_input.excitation_from_stiffness`,
        or the loaded contact,
        :func:`pipeline.dynamics.contact_excitation.excitation_from_contact`); needed unless
        ``options.mesh_stiffness`` is given. Its e(tau) belongs to its k(tau) (the static
        state ``k (x_s - e) = P``), so an explicit ``options.mesh_stiffness`` drops it.
    supports : the pinion's and the gear's support stiffness at the seat from their shafts
        (N/m, :mod:`pipeline.shaft`), or None for ``options.bearing_stiffness``.
    torsion : the pinion's and the gear's shaft torsional stiffness between the seat and the
        torque point (N m/rad), or None (no shaft); with ``options.drive_inertia`` /
        ``options.load_inertia`` they tie the motor and the driven machine to the gears.
    """
    if operation.driver != "pinion":
        raise InputError("operation.driver = 'gear': the pair dynamic model drives the pinion; "
                         "set [operation] driver = \"pinion\"")
    k = options.mesh_stiffness
    te = None
    if k is None:
        if excitation is None:
            raise InputError("the pair dynamic model needs a mesh excitation or an explicit "
                             "[dynamics.mesh_stiffness]")
        k, te = excitation.stiffness, excitation.transmission_error
    friction = options.friction and excitation is not None and excitation.has_friction
    pb, gb = bodies
    drives = []
    for key, inertia, k_t in (("drive_inertia_kgm2", options.drive_inertia, torsion[0]),
                              ("load_inertia_kgm2", options.load_inertia, torsion[1])):
        if inertia is not None and k_t is None:
            shaft = "pinion" if key.startswith("drive") else "gear"
            raise InputError(f"dynamics.{key} needs [{shaft}.shaft]: the torsional stiffness "
                             f"between it and the {shaft} is its shaft's")
        drives.append((inertia, None if inertia is None else k_t))
    return SpurPairModel(
        mesh_stiffness=k,
        pinion_teeth=pair.pinion.teeth,
        base_radius_pinion=pair.pinion.base_radius,
        base_radius_gear=pair.gear.base_radius,
        mass_pinion=pb.mass_,
        mass_gear=gb.mass_,
        inertia_pinion=pb.inertia_,
        inertia_gear=gb.inertia_,
        bearing_stiffness=options.bearing_stiffness if supports[0] is None else supports[0],
        gear_bearing_stiffness=supports[1] if supports[1] is not None else (
            None if supports[0] is None else options.bearing_stiffness),
        bearing_damping=options.bearing_damping,
        damping_ratio=options.damping_ratio,
        torque=operation.torque,
        speed=operation.speed,
        transmission_error=te,
        friction_stiffness=excitation.friction_stiffness if friction else None,
        friction_torque_pinion=excitation.friction_torque_pinion if friction else None,
        friction_torque_gear=excitation.friction_torque_gear if friction else None,
        torsional_only=options.dofs == "torsional",
        t1t2=pair.t1t2,
        gear_internal=pair.gear.internal,
        inertia_drive=drives[0][0],
        kt_drive=drives[0][1],
        inertia_load=drives[1][0],
        kt_load=drives[1][1],
    )
