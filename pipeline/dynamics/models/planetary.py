"""Planar planetary set of Lin and Parker (1999): 3 DOF per body in the carrier frame.

Bodies: carrier ``c``, ring ``r``, sun ``s`` (x, y, theta in the frame rotating
with the carrier) and planets ``p1..pN`` (radial x, tangential y, theta; frame
turned by the planet angle psi_n). Theta are absolute rotation angles in rad
relative to the carrier frame (Lin and Parker use ``u = r theta``; the
eigenvalues are the same).

Meshes (transverse pressure angles alpha_s, alpha_r; psi_sn = psi_n - alpha_s,
psi_rn = psi_n + alpha_r), derived in :mod:`pipeline.dynamics.mesh_geometry`::

    delta_sn = -x_s sin psi_sn + y_s cos psi_sn - x_n sin a_s - y_n cos a_s + r_s th_s + r_p th_n
    delta_rn = -x_r sin psi_rn + y_r cos psi_rn + x_n sin a_r - y_n cos a_r + r_r th_r - r_p th_n

Planet bearings tie each planet centre to the carrier point at radius r_c
(radial and tangential springs k_p). Mesh phases: sun mesh n uses
``k_sp(tau - phase_sun[n])`` and ring mesh n ``k_rp(tau - phase_ring[n])``
(Xu et al. 2020, eqs. 14-15: phase_ring = lambda_rn + lambda_rs); pass them from
:mod:`pipeline.geometry.planetary` or give them explicitly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.dynamics.assembly import Assembly
from pipeline.dynamics.bodies import Body, add_measures
from pipeline.dynamics.couplings import Bearing, GearMesh, Load, Spring, TorsionalShaft
from pipeline.dynamics.mesh_geometry import cylindrical_mesh_measure
from pipeline.dynamics.modal import ModalResult, classify_modes
from pipeline.dynamics.reduction import rigid_body_modes
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_int_range, check_range

MAX_TORQUE = 1e8
"""Largest torque magnitude of a lumped model, N m (as :class:`~pipeline.operation.
OperatingPoint`)."""
MAX_SPEED = 1e5
"""Largest speed magnitude of a lumped model, rad/s (as :class:`~pipeline.operation.
OperatingPoint`)."""
MAX_RADIUS = 10.0
"""Largest radius of a lumped model's member, m."""
_BODY_LIMITS = (("mass_", 1e7, "kg"), ("inertia_", 1e7, "kg m^2"),
                ("base_radius_", MAX_RADIUS, "m"), ("carrier_radius", MAX_RADIUS, "m"),
                ("mesh_period", 1e3, "s"))
"""Upper bounds of a lumped model's body quantities by field-name prefix (those of
:class:`~pipeline.geometry.body.GearBody` for masses and inertias; 10 m radii; a mesh
frequency of at least 1e-3 Hz)."""


def check_body_range(name: str, value: float) -> float:
    """A lumped model's mass, inertia, radius or mesh period: positive and below its bound
    (:data:`_BODY_LIMITS`), SI."""
    hi, unit = next((h, u) for p, h, u in _BODY_LIMITS if name.startswith(p))
    return check_range(name, value, 0.0, hi, lo_open=True, unit=unit)


def check_planet_layout(model) -> None:
    """Refuse planets that coincide or overlap and a ring or sun that cannot reach them.

    Neighbouring planet centres must be further apart than two planet base radii; the
    ring's base radius must exceed the carrier radius and the sun's must stay below it.
    """
    check_body_range("carrier_radius", model.carrier_radius)
    check_range("base_radius_ring", model.base_radius_ring, model.carrier_radius, MAX_RADIUS,
                lo_open=True, unit="m")
    check_range("base_radius_sun", model.base_radius_sun, 0.0, model.carrier_radius,
                lo_open=True, hi_open=True, unit="m")
    psi = np.sort(np.mod(model.angles, 2 * math.pi))
    if psi.size > 1:
        gaps = np.diff(np.concatenate([psi, [psi[0] + 2 * math.pi]]))
        chord = 2 * model.carrier_radius * math.sin(gaps.min() / 2)
        if chord <= 2 * model.base_radius_planet:
            raise InputError(
                f"planets overlap: neighbouring planet centres are {chord * 1e3:.4g} mm apart, "
                f"less than two planet base radii ({2e3 * model.base_radius_planet:.4g} mm); "
                "check planet_angles and n_planets")


def check_lumped_members(model, stiffnesses: tuple[str, ...]) -> None:
    """The checks a planetary lumped model shares: masses, inertias, planet radius and mesh
    period positive and bounded (:func:`check_body_range`), torque and speed bounded,
    ``stiffnesses`` (N/m or N m/rad) in [0, 1e15], transverse pressure angles in (0, 90)
    deg, planet angles within one turn either way, mesh phases within one mesh period
    either way, damping ratios in [0, 1], and the layout (:func:`check_planet_layout`).
    Per-planet tuples are stored as tuples of floats."""
    n = check_int_range("n_planets", model.n_planets, 1, 64)
    for f in ("mass_sun", "mass_ring", "mass_carrier", "mass_planet", "inertia_sun",
              "inertia_ring", "inertia_carrier", "inertia_planet", "base_radius_planet",
              "mesh_period"):
        check_body_range(f, getattr(model, f))
    check_range("sun_torque", model.sun_torque, -MAX_TORQUE, MAX_TORQUE, unit="N m")
    check_range("carrier_speed", model.carrier_speed, -MAX_SPEED, MAX_SPEED, unit="rad/s")
    for f in stiffnesses:
        check_range(f, getattr(model, f), 0.0, 1e15)
    for f in ("pressure_angle_sun", "pressure_angle_ring"):
        check_range(f, getattr(model, f), 0.0, math.pi / 2, lo_open=True, hi_open=True,
                    unit="rad")
    for f, bound, unit in (("planet_angles", 2 * math.pi, "rad"), ("phase_sun", 1.0, ""),
                           ("phase_ring", 1.0, "")):
        v = getattr(model, f)
        if v is not None:
            v = tuple(float(a) for a in np.atleast_1d(v))
            if len(v) != n:
                raise InputError(f"{f} has {len(v)} entries: give one per planet "
                                 f"(n_planets = {n})")
            for i, a in enumerate(v):
                check_range(f"{f}[{i}]", a, -bound, bound, unit=unit)
            object.__setattr__(model, f, v)
    for f in ("damping_ratio", "modal_damping_ratio"):
        check_range(f, getattr(model, f), 0.0, 1.0)
    check_planet_layout(model)


@dataclass(frozen=True)
class PlanetaryMembers:
    """What the planar and the herringbone planetary models share (defaults: Lin and Parker
    1999 Table 1): the members, their supports, the planets' layout and phases, damping,
    load and speed. Checked by :func:`check_lumped_members` in each model.

    Attributes
    ----------
    n_planets : N >= 1.
    mass_sun, mass_ring, mass_carrier, mass_planet : kg.
    inertia_sun, inertia_ring, inertia_carrier, inertia_planet : kg m^2.
    base_radius_sun, base_radius_ring, base_radius_planet : m.
    carrier_radius : radius of the planet centres r_c, m.
    pressure_angle_sun, pressure_angle_ring : transverse operating pressure angles, rad.
    k_sun, k_ring, k_carrier : translational bearing stiffness of the central members, N/m.
    k_planet : planet bearing stiffness (radial and tangential), N/m.
    kt_sun, kt_ring, kt_carrier : torsional support stiffness, N m/rad.
    planet_angles : shape (N,), psi_n in rad (default equally spaced, psi_1 = 0).
    phase_sun, phase_ring : shape (N,), mesh phases in mesh periods (default zeros).
    damping_ratio : mesh damping ratio.
    modal_damping_ratio : constant modal damping (-), see :class:`Assembly` (default none).
    sun_torque : torque on the sun, N m (the carrier takes the balancing torque when
        the sun-carrier path has a rigid-body mode; otherwise it reacts on the supports).
    carrier_speed : Omega_c, rad/s.
    mesh_period : T_m in s.
    """

    n_planets: int = 4
    mass_sun: float = 0.4
    mass_ring: float = 2.35
    mass_carrier: float = 5.43
    mass_planet: float = 0.66
    inertia_sun: float = 0.39 * 0.0387**2
    inertia_ring: float = 3.00 * 0.1375**2
    inertia_carrier: float = 6.29 * 0.0884**2
    inertia_planet: float = 0.61 * 0.05015**2
    base_radius_sun: float = 0.0387
    base_radius_ring: float = 0.1375
    base_radius_planet: float = 0.05015
    carrier_radius: float = 0.0884
    pressure_angle_sun: float = math.radians(24.6)
    pressure_angle_ring: float = math.radians(24.6)
    k_sun: float = 1e8
    k_ring: float = 1e8
    k_carrier: float = 1e8
    k_planet: float = 1e8
    kt_sun: float = 0.0
    kt_ring: float = 1e9 * 0.1375**2
    kt_carrier: float = 0.0
    planet_angles: tuple[float, ...] | None = None
    phase_sun: tuple[float, ...] | None = None
    phase_ring: tuple[float, ...] | None = None
    damping_ratio: float = 0.0
    modal_damping_ratio: float = 0.0
    sun_torque: float = 0.0
    carrier_speed: float = 0.0
    mesh_period: float = 1e-3

    @property
    def angles(self) -> np.ndarray:
        """Planet angles psi_n, shape (N,), rad."""
        if self.planet_angles is not None:
            return np.array(self.planet_angles)
        return 2 * np.pi * np.arange(self.n_planets) / self.n_planets

    def planet_names(self) -> list[str]:
        return [f"p{i + 1}" for i in range(self.n_planets)]


@dataclass(frozen=True)
class PlanetaryModel(PlanetaryMembers):
    """Inputs of the planar planetary model (defaults: Lin and Parker 1999 Table 1): the
    members of :class:`PlanetaryMembers` and its meshes.

    Attributes
    ----------
    k_sun_mesh, k_ring_mesh : mesh stiffness (N/m), constant or over one mesh period.
    e_sun_mesh, e_ring_mesh : transmission error e(tau) of every sun-planet / ring-planet
        mesh over one mesh period (m, shifted by the mesh phases like the stiffness), or
        ``None`` (perfect flanks).
    inertia_drive, kt_drive : a motor behind the sun's shaft, kg m^2, tied to the sun by the
        shaft's torsional stiffness, N m/rad (body ``drive``, its rotation only; it takes
        ``sun_torque``); both None: the torque acts on the sun.
    """

    k_sun_mesh: PeriodicSignal | float = 5e8
    k_ring_mesh: PeriodicSignal | float = 5e8
    e_sun_mesh: PeriodicSignal | None = None
    e_ring_mesh: PeriodicSignal | None = None
    inertia_drive: float | None = None
    kt_drive: float | None = None

    def __post_init__(self) -> None:
        check_lumped_members(self, ("k_sun", "k_ring", "k_carrier", "k_planet", "kt_sun",
                                    "kt_ring", "kt_carrier"))
        if self.inertia_drive is not None:
            check_body_range("inertia_drive", self.inertia_drive)
        if self.kt_drive is not None:
            check_range("kt_drive", self.kt_drive, 0.0, 1e14, lo_open=True, unit="N m/rad")
        if (self.inertia_drive is None) != (self.kt_drive is None):
            raise InputError("inertia_drive and kt_drive go together: the drive inertia sits "
                             "behind a shaft of that torsional stiffness")

    def assembly(self) -> Assembly:
        """Bodies, bearings, meshes and loads of the set."""
        central = dict(
            c=(self.mass_carrier, self.inertia_carrier),
            r=(self.mass_ring, self.inertia_ring),
            s=(self.mass_sun, self.inertia_sun),
        )
        bodies = [
            Body(k, m, i, ("x", "y", "theta"), rotating_frame=True)
            for k, (m, i) in central.items()
        ]
        psi = self.angles
        ph_s = np.zeros(self.n_planets) if self.phase_sun is None else np.array(self.phase_sun)
        ph_r = np.zeros(self.n_planets) if self.phase_ring is None else np.array(self.phase_ring)
        c, r, s = bodies
        couplings: list[object] = [
            Bearing("c", {"x": self.k_carrier, "y": self.k_carrier, "theta": self.kt_carrier}),
            Bearing("r", {"x": self.k_ring, "y": self.k_ring, "theta": self.kt_ring}),
            Bearing("s", {"x": self.k_sun, "y": self.k_sun, "theta": self.kt_sun}),
        ]
        for n, name in enumerate(self.planet_names()):
            p = Body(
                name,
                self.mass_planet,
                self.inertia_planet,
                ("x", "y", "theta"),
                frame_angle=float(psi[n]),
                rotating_frame=True,
            )
            bodies.append(p)
            a_s, a_r = self.pressure_angle_sun, self.pressure_angle_ring
            sun_m = cylindrical_mesh_measure(
                s,
                p,
                psi[n] - a_s + math.pi / 2,
                self.base_radius_sun,
                self.base_radius_planet,
                1,
                1,
            )
            ring_m = cylindrical_mesh_measure(
                r,
                p,
                psi[n] + a_r + math.pi / 2,
                self.base_radius_ring,
                self.base_radius_planet,
                1,
                -1,
            )
            couplings += [
                GearMesh(
                    f"s-{name}", sun_m, self.k_sun_mesh, self.damping_ratio, phase=float(ph_s[n]),
                    transmission_error=self.e_sun_mesh,
                ),
                GearMesh(
                    f"r-{name}", ring_m, self.k_ring_mesh, self.damping_ratio,
                    phase=float(ph_r[n]), transmission_error=self.e_ring_mesh,
                ),
                Spring(
                    f"{name}.bearing.radial",
                    add_measures({(name, "x"): 1.0}, c.in_plane(psi[n], -1.0)),
                    self.k_planet,
                ),
                Spring(
                    f"{name}.bearing.tangential",
                    add_measures(
                        {(name, "y"): 1.0},
                        c.in_plane(psi[n] + math.pi / 2, -1.0),
                        {("c", "theta"): -self.carrier_radius},
                    ),
                    self.k_planet,
                ),
            ]
        driven = "s"
        if self.inertia_drive is not None:
            bodies.append(Body("drive", 0.0, self.inertia_drive, ("theta",),
                               rotating_frame=True))
            couplings.append(TorsionalShaft("drive", "s", self.kt_drive))
            driven = "drive"
        loads = self._loads(bodies, couplings, driven)
        return Assembly(
            bodies,
            couplings,
            loads,
            period=self.mesh_period,
            carrier_speed=self.carrier_speed,
            modal_damping_ratio=self.modal_damping_ratio,
            name=f"planetary-{self.n_planets}",
        )

    def _loads(self, bodies, couplings, driven: str = "s") -> list[Load]:
        """The sun torque on body ``driven`` (the sun or the motor behind its shaft) and, when
        the drive path turns freely, its balance on the carrier."""
        if self.sun_torque == 0.0:
            return []
        loads = [Load(driven, "theta", self.sun_torque)]
        probe = Assembly(bodies, couplings, loads, period=self.mesh_period).assemble()
        R = rigid_body_modes(probe)
        if R.shape[1]:
            i_s, i_c = probe.index(f"{driven}.theta"), probe.index("c.theta")
            r = probe.basis @ R[:, 0]
            if abs(r[i_c]) > 1e-12 * np.abs(r).max():
                loads.append(Load("c", "theta", -self.sun_torque * r[i_s] / r[i_c]))
        return loads

    def classify(self, result: ModalResult) -> ModalResult:
        """Label modes rotational / translational / planet (Lin and Parker 1999)."""
        return classify_modes(
            result, [f"{b}.{d}" for b in "crs" for d in "xy"], [f"{b}.theta" for b in "crs"]
        )
