"""The gap the shafts' deflection opens across the face, in the plane of action.

Frames
------
Each gear's shaft is solved in its own *mesh frame*, right-handed: ``y`` is the direction in
which the mesh force pushes this gear's axis (along the line of action, away from the mate),
``z`` the shaft's axis (the layout's axial coordinate), ``x = y x z``, and this gear's
tangent point ``T_i`` (where the line of action touches its base circle) lies at ``x = +r_b``.
Along the roll coordinate ``s`` of :mod:`pipeline.geometry.pair` (from ``T1`` towards ``T2``)
"away from the mate" is ``-s`` for the pinion and ``+s`` for the gear: the loaded flanks
touch, so the gear pushes the pinion back along the line of action towards ``T1`` and the
pinion pushes the gear towards ``T2``. Check: the force ``F`` along ``y`` at ``x = r_b`` has the
moment ``+F r_b`` about ``+z`` on *each* gear (two external gears turn opposite ways); on
the driver (``OperatingPoint.driver``) it is the reaction to the driving torque
``P r_b,driver`` (:func:`pipeline.contact.analysis.line_of_action_load`), on the other gear
it turns it. This is the project's one loaded flank (the "right" flanks of
:mod:`pipeline.contact.fe3d_source`): the pinion, driving, turns clockwise seen from
``+z``.

The other rotation
------------------
The pinion turning the other way (or the gear driving: the torque, not the motion, picks
the flank) loads the other flanks, the mirror image of these in the plane through both
axes. Reflected in that plane (``x -> -x`` of each mesh frame) the gearbox is the one
above with every hand reversed: the gap across the face is that of the pinion of the
other hand on the loaded flank (:meth:`HelicalMesh.of` with ``reflected``), and the
shaft's motion in the real gearbox is the reflected one with ``u_x``, ``theta_y`` and
``theta_z`` (and the loads ``F_x``, ``M_y``, ``M_z``) negated
(:meth:`pipeline.shaft.model.ShaftSolution.reflected`; a round shaft on round bearings is
its own mirror image). A spur pair's gap is the same either way.

Loads
-----
The contact's line load ``w_j`` (N/m, along the transverse line of action) on face slice
``j`` of width ``dz_j`` gives the transverse force ``F_j = w_j dz_j``. On a helical flank the
force lies along the flank's normal, which is in the plane of action and perpendicular to
the contact line. The contact lines of :meth:`GearPair.contact_lines` run at ``ds / dzeta =
+tan(beta_b)`` in the contact's face coordinate ``zeta``; the normal is therefore
``(cos beta_b, -sin beta_b)`` in ``(s, zeta)`` up to its sense, and the force on the pinion,
whose transverse part is ``-F`` along ``s``, is ``F (-1, +tan beta_b)``: an axial part
``+F tan(beta_b)`` along ``+zeta`` (on the gear the opposite). Which way ``zeta`` runs
along the shaft's ``z`` the hand says: the section of a right-hand (``h = +1``) flank at
``z`` is turned by ``h tan(beta) z / r`` about ``+z``, so on the loaded flank the contact
line has ``ds / dz = -h tan(beta_b)`` (:mod:`pipeline.contact.fe3d_source`, Mapping), hence
``zeta = z`` for a left-hand pinion and ``zeta = b - z`` (the contact's face runs against
the shaft's axis) for a right-hand pinion. In each gear's mesh frame the axial force is

    F_a,j = a F_j,   a_pinion = -h_pinion tan(beta_b),   a_gear = +h_pinion tan(beta_b),

the same rule ``a = -h tan(beta_b)`` for each gear with its own hand (an external pair has
opposite hands). As a screw: a right-hand pinion turning clockwise seen from ``+z`` (its
rotation vector along ``-z``) drives the gear's teeth towards ``+z``, as a right-hand screw
turned that way drives its nut, and is pushed back towards ``-z``.

Where it acts: the contact point lies in the plane of action, ``r_b`` from the axis along
``x`` and ``d_j`` back from the tangent point towards the mate, ``(r_b, -d_j)`` in ``(x, y)``,
with ``d = s`` for the pinion (from ``T1``) and ``d = T1T2 - s`` for the gear (from ``T2``).
Taking the force ``(0, F_j, a F_j)`` at that point to the shaft's axis at ``z_j`` (``M = r
x F``), the slice loads the shaft with

* the force ``(0, F_j, a F_j)``;
* the moment ``(-a F_j d_j, -a F_j r_b, F_j r_b)``: about ``x``, the axial force's lever
  along the line of action, which tilts the shaft in the ``y``-``z`` plane (the plane of
  the gap); about ``y``, its lever ``r_b``, which tilts the shaft across the line of
  action; about ``z``, the torque.

That is ``F_j`` times the unit load ``L_j = (0, 1, a, -a d_j, -a r_b, r_b)``; a spur
pair has ``a = 0``. The slice's ``d_j`` is the cycle-mean one: the load-weighted mean of
the contact points' ``s`` in that slice over the mesh cycle (:class:`HelicalMesh`), which
makes the cycle-mean moment exact (the moment is linear in each point's load and ``s``).

Gap
---
The contact measures gaps along the transverse line of action
(:mod:`pipeline.contact.separations`; :mod:`pipeline.contact.source`: transverse loads and
approaches, ``G = G_normal / cos^2(beta_b)``). A small rigid motion ``(u, theta)`` of the
shaft's section at ``z_j`` moves the contact point by ``u + theta x (r_b, -d_j, 0)``; the
flank retreats along its unit normal ``n = cos(beta_b) (0, 1, a)`` by that motion dotted
with ``n`` (the contact point's slide along the flank changes the gap only to second
order), which is ``cos(beta_b)`` times the transverse retreat (a helicoid moved by
``delta_t`` along ``y`` moves ``delta_t cos(beta_b)`` along its normal). The transverse
retreat is thus

    delta_j = u_y + r_b theta_z + a (u_z - d_j theta_x - r_b theta_y) = L_j . (u, theta)_j,

the displacement work-conjugate to the transverse load, so ``delta = L^T C L F`` with the
shaft's flexibility ``C`` (6 per point): symmetric, and for the pair the sum over the
gears. The axial terms carry ``a = +-tan(beta_b)`` (``sin(beta_b)`` along the normal);
``u_z`` is the seat's axial give (shaft and axial bearing); the tilts ``theta_x`` (in the
plane of the gap, which shows itself in ``u_y`` changing across the face) and ``theta_y``
(across it) move the contact point axially by ``-d theta_x`` and ``-r_b theta_y``. The
displacement across the line of action, ``u_x``, changes the centre distance, a
second-order effect on the gap (left out). The gap the two shafts open at face
point ``j`` is ``g_j = delta_p,j + delta_g,j``: its variation across the face is the
misalignment in the plane of action (ISO 6336-1's ``f_sh``), its mean a rigid approach that
adds to the transmission error only.

Checks (tests/test_shaft_misalignment.py, tests/test_run_shafts.py): the loads on the two
shafts are equal and opposite in one global frame, force and moment (1e-12), with the
moments ``P r_b`` about the axes; the force is normal to :meth:`GearPair.contact_lines` in
either hand; reversing the hand reverses the axial force and the shaft's response to it
exactly, and is the gearbox turned end for end (the mirrored shaft gives the same gap to
1e-12); a rigid seat at mid-span tilts by the axial force's moment over its closed-form
tilting stiffness (1e-9, its axial terms too); ``beta_b = 0`` is the spur result bit for
bit. The demo pair at 15 deg on a straddle-mounted pinion opens 0.32 um (K_Hbeta 1.016;
the spur pair 0) through its fixed point, to 1e-9 of the closed form. The planetary
functions (block at the end; tests/test_shaft_planetary_loads.py): equally spaced sun meshes
cancel (1e-14), a planet's two forces drive the carrier with ``T_s (1 + z_r / z_s)``
(1e-12), a cantilevered pin's retreats are Roark's with the shear term (1e-9), an integral
sun's twist is ``sum T_k min(z, z_k) / (G J)`` (1e-9).

Face positions: functions here take and return the contact's face coordinate ``zeta`` (m
from the face's first end, :attr:`LoadedMeshCycle.point_z`); the shaft's face point is at
``gear_position - b / 2 + zeta``, or ``gear_position + b / 2 - zeta`` for a right-hand
pinion (:func:`seat_points`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from pipeline.geometry.pair import GearPair
from pipeline.shaft.model import PointLoad, ShaftModel, ShaftSolution
from pipeline.validation import InputError, check_choice, check_range

ROLES = ("pinion", "gear")
"""The gears in the order :func:`shaft_gap` takes their shafts."""


@dataclass(frozen=True)
class HelicalMesh:
    """What a helical mesh adds to its shafts' loads (module docstring).

    Attributes
    ----------
    base_helix_angle : beta_b, rad, in [0, 45 deg).
    pinion_hand : "right", "left" or "none" (spur; with ``beta_b = 0``).
    t1t2 : the line of action between the tangent points, ``T1T2``, m.
    roll : (n,) the cycle-mean roll coordinate ``s`` of the load in each face slice (the
        load-weighted mean of the contact points' ``s``), m, in the contact's face order.
    """

    base_helix_angle: float
    pinion_hand: str
    t1t2: float
    roll: np.ndarray

    def __post_init__(self) -> None:
        check_range("shafts: base helix angle", self.base_helix_angle, 0.0,
                    math.radians(45.0), hi_open=True, unit="rad")
        check_choice("shafts: pinion hand", self.pinion_hand, ("right", "left", "none"))
        roll = np.array(self.roll, dtype=float)
        roll.flags.writeable = False
        object.__setattr__(self, "roll", roll)

    @classmethod
    def of(cls, pair: GearPair, roll: np.ndarray, reflected: bool = False) -> HelicalMesh:
        """The mesh of an external, spur or helical (not herringbone) ``pair`` with the
        cycle-mean roll coordinates ``roll`` (m) of its face slices; ``reflected``: the
        other flanks loaded (module docstring: the pinion's hand reversed)."""
        if pair.gear.internal and pair.pinion.is_helical:
            raise InputError("shafts: the loads of a helical internal pair on its shafts are "
                             "not built; shafts take external helical pairs")
        if pair.pinion.herringbone:
            raise InputError("shafts: a herringbone pair's two halves on shafts are not built "
                             "(the contact takes one half); shafts take spur and helical pairs")
        hand = pair.pinion.hand
        if reflected:
            hand = {"right": "left", "left": "right"}.get(hand, hand)
        return cls(pair.pinion.base_helix_angle, hand, pair.t1t2, roll)

    @property
    def reversed(self) -> bool:
        """True when the contact's face coordinate runs against the shafts' axis (a
        right-hand pinion, module docstring)."""
        return self.pinion_hand == "right"

    def axial_ratio(self, role: int) -> float:
        """``a = F_a / F``: the axial force over the transverse one along the shaft's ``z``
        of gear ``role`` (0 pinion, 1 gear; module docstring), -."""
        h = {"right": 1.0, "left": -1.0, "none": 0.0}[self.pinion_hand]
        a = -h * math.tan(self.base_helix_angle)
        return a if role == 0 else -a

    def lever(self, role: int) -> np.ndarray:
        """``d`` (n,): the contact's distance from gear ``role``'s tangent point along the
        line of action (``s`` from ``T1``; ``T1T2 - s`` from ``T2``), m."""
        return self.roll if role == 0 else self.t1t2 - self.roll


@dataclass(frozen=True)
class FlankRetreat:
    """One gear's retreat across the face, along the transverse line of action.

    Attributes
    ----------
    z : (n,) the contact's face positions from the face's first end, m.
    translation : (n,) ``u_y`` of the shaft there, m.
    twist : (n,) ``r_b theta_z`` there, m.
    solution : the shaft's whole solution (deflection line, bearing reactions) in the mesh
        frame, or None.
    axial : (n,) ``a (u_z - d theta_x - r_b theta_y)`` there (a helical mesh's axial
        terms, module docstring), m; None: 0 (spur).
    """

    z: np.ndarray
    translation: np.ndarray
    twist: np.ndarray
    solution: ShaftSolution | None = None
    axial: np.ndarray | None = None

    @property
    def total(self) -> np.ndarray:
        """``delta`` (n,), m."""
        out = self.translation + self.twist
        return out if self.axial is None else out + self.axial


def unit_loads(base_radius: float, n: int, mesh: HelicalMesh | None = None,
               role: int = 0) -> np.ndarray:
    """``L`` (n, 6): each face slice's load on gear ``role``'s shaft per newton of transverse
    load, ``(0, 1, a, -a d, -a r_b, r_b)`` (N/N and N m/N; module docstring); spur (``mesh``
    None) ``a = 0``."""
    out = np.zeros((n, 6))
    out[:, 1] = 1.0
    out[:, 5] = base_radius
    if mesh is not None:
        if mesh.roll.shape != (n,):
            raise InputError(f"shaft loads: {mesh.roll.size} roll coordinates for {n} face "
                             "slices")
        a = mesh.axial_ratio(role)
        out[:, 2] = a
        out[:, 3] = -a * mesh.lever(role)
        out[:, 4] = -a * base_radius
    return out


def seat_loads(z: np.ndarray, line_load: np.ndarray, face_width: float, gear_position: float,
               base_radius: float, unit: np.ndarray | None = None) -> list[PointLoad]:
    """The mesh's load on one gear's shaft in its mesh frame (module docstring): ``z`` (n,)
    slice centres from the face's first end *along the shaft's axis* (m), ``line_load`` (n,)
    N/m; slices of equal width ``face_width / n``; ``unit`` (n, 6) the loads per newton
    (:func:`unit_loads`; None: spur)."""
    z = np.asarray(z, dtype=float)
    w = np.asarray(line_load, dtype=float)
    if z.shape != w.shape or z.ndim != 1 or z.size == 0:
        raise InputError("shaft loads: one line load per face position")
    unit = unit_loads(base_radius, z.size) if unit is None else unit
    f = unit * (w * face_width / z.size)[:, None]
    start = gear_position - 0.5 * face_width
    return [PointLoad(float(start + zj), tuple(float(v) for v in fj[:3]),
                      tuple(float(v) for v in fj[3:]))
            for zj, fj in zip(z, f, strict=True)]


def seat_points(model: ShaftModel, z: np.ndarray, mesh: HelicalMesh | None = None
                ) -> np.ndarray:
    """The shaft positions (m) of the contact's face points ``z`` (m from the face's first
    end): ``gear_position - b / 2 + z``, or ``gear_position + b / 2 - z`` when the contact's
    face runs against the shaft's axis (``mesh.reversed``, module docstring)."""
    lay = model.layout
    z = np.asarray(z, dtype=float)
    if mesh is not None and mesh.reversed:
        return lay.gear_position + 0.5 * lay.seat_width - z
    return lay.gear_position - 0.5 * lay.seat_width + z


def flank_retreat(model: ShaftModel, z: np.ndarray, line_load: np.ndarray,
                  base_radius: float, flexibility: np.ndarray | None = None,
                  mesh: HelicalMesh | None = None, role: int = 0) -> FlankRetreat:
    """The retreat of gear ``role``'s flank (0 pinion, 1 gear) across the face under the
    mesh's line load (module docstring), ``model`` the gear's shaft in its mesh frame,
    ``z`` the contact's face positions (m); ``flexibility`` its
    :meth:`~pipeline.shaft.model.ShaftModel.flexibility` at :func:`seat_points` when
    computed already (a fixed point reuses it); ``mesh`` a helical mesh (None: spur)."""
    lay = model.layout
    points = seat_points(model, z, mesh)
    w = np.asarray(line_load, dtype=float)
    unit = unit_loads(base_radius, w.size, mesh, role)
    loads = seat_loads(points - (lay.gear_position - 0.5 * lay.seat_width), w,
                       lay.seat_width, lay.gear_position, base_radius, unit)
    c = model.flexibility(points) if flexibility is None else flexibility
    f = np.concatenate([np.r_[ld.force, ld.moment] for ld in loads])
    d = (c @ f).reshape(-1, 6)
    axial = None
    if mesh is not None:
        axial = (unit[:, 2] * d[:, 2] + unit[:, 3] * d[:, 3] + unit[:, 4] * d[:, 4])
    return FlankRetreat(np.asarray(z, dtype=float), d[:, 1], base_radius * d[:, 5],
                        model.solve(loads), axial)


def shaft_gap(models: Sequence[ShaftModel | None], base_radii: Sequence[float],
              z: np.ndarray, line_load: np.ndarray, helix_angle: float = 0.0,
              flexibilities: Sequence[np.ndarray | None] | None = None,
              mesh: HelicalMesh | None = None
              ) -> tuple[np.ndarray, tuple[FlankRetreat | None, ...]]:
    """The gap (n,) the shafts of both gears open across the face (m; a gear without a
    shaft: rigid) and each gear's retreat (module docstring).

    ``models`` and ``base_radii`` in the order pinion, gear (:data:`ROLES`); ``z`` the
    contact's face positions (m) and ``line_load`` its line load there (N/m);
    ``flexibilities`` of the models at :func:`seat_points`, when computed already; ``mesh``
    the helical mesh, needed when ``helix_angle`` (rad) is not 0.
    """
    if helix_angle != 0.0 and mesh is None:
        raise InputError("shafts: a helical pair's shaft loads need its HelicalMesh (the "
                         "axial force's sense and lever)")
    if len(models) > len(ROLES):
        raise InputError(f"shafts: {len(models)} shafts for the two gears of a pair")
    flex = flexibilities or [None] * len(models)
    retreats = tuple(None if m is None else flank_retreat(m, z, line_load, rb, c, mesh, role)
                     for role, (m, rb, c) in enumerate(zip(models, base_radii, flex,
                                                           strict=True)))
    gap = np.zeros(np.shape(z))
    for r in retreats:
        if r is not None:
            gap = gap + r.total
    return gap, retreats


# Planetary sets --------------------------------------------------------------------------
#
# A sun meshes with N planets and a planet with the sun and the ring: one shaft carries
# several meshes. Each mesh m loads the shaft with its own unit loads ``L_m`` (n, 6) in the
# shaft's frame and retreats by ``L_m . (u, theta)`` (module docstring), the shaft's
# displacements ``d = C sum_m L_m F_m`` under all of them. For a spur set:
#
# * the sun in the mesh frame of its first planet's mesh (the pair sun-planet, the sun the
#   pinion): mesh n is that mesh turned by ``psi_n - psi_0`` about the sun's axis, so its
#   unit load is ``(0, 1, 0, 0, 0, r_b)`` turned by that angle (:func:`rotated_unit_loads`);
#   with equally spaced planets the forces cancel and the moments about the axis add (which
#   way the angles count changes no gap of a spur set: a round shaft's bending, mirrored
#   with the forces, and its torsion are uncoupled);
# * a planet turns freely on its pin (the planet bearing carries no torque), so a pin is
#   loaded by forces only, in a frame with ``x`` along the tangent of the planet's orbit in
#   the sense the sun pushes the planet and ``y`` radially outward from the sun's axis: the
#   sun pushes the planet along ``(cos alpha_sp, sin alpha_sp)`` (away from the sun, a
#   separating force) and the ring along ``(cos alpha_pr, -sin alpha_pr)`` (towards the
#   sun's axis), each along its transverse line of action away from its mate
#   (:func:`planet_unit_loads`). Both tangential parts point the same way: they drive the
#   carrier, whose torque ``2 a N P cos(alpha)`` is the sun's and the ring's together.


def rotated_unit_loads(unit: np.ndarray, angle: float) -> np.ndarray:
    """``unit`` (n, 6) loads ``(F, M)`` turned by ``angle`` (rad) about the shaft's axis
    ``z``: the forces' and the moments' x-y parts rotate, their z parts stay."""
    c, s = math.cos(angle), math.sin(angle)
    rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    unit = np.asarray(unit, dtype=float)
    return np.concatenate([unit[:, :3] @ rot.T, unit[:, 3:] @ rot.T], axis=1)


def planet_unit_loads(pressure_angles: tuple[float, float], n: int) -> tuple[np.ndarray,
                                                                             np.ndarray]:
    """The sun-planet and the planet-ring mesh's unit loads (n, 6) on a planet's pin per
    newton of transverse load (forces only: the planet turns freely on its pin), in the pin's
    frame (``x`` along the orbit's tangent, ``y`` radially out; block comment above);
    ``pressure_angles`` the transverse operating pressure angles of the two meshes, rad."""
    out = []
    for angle, radial in zip(pressure_angles, (1.0, -1.0), strict=True):
        u = np.zeros((n, 6))
        u[:, 0] = math.cos(angle)
        u[:, 1] = radial * math.sin(angle)
        out.append(u)
    return out[0], out[1]


def body_retreats(flexibility: np.ndarray, units: Sequence[np.ndarray],
                  forces: Sequence[np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
    """One shaft under several meshes: its displacements and each mesh's flank retreat.

    Parameters
    ----------
    flexibility : (6n, 6n) the shaft's flexibility at its ``n`` face points (m/N, rad/N m).
    units : per mesh, its unit loads (n, 6) at those points (N/N, N m/N).
    forces : per mesh, its transverse force on each face slice (n,), N.

    Returns
    -------
    (d, retreats): ``d`` (n, 6) the displacements ``C sum_m L_m F_m`` (m, rad) and, per
    mesh, its retreat ``L_m . d`` (n,), m (block comment above).
    """
    if len(units) != len(forces) or not units:
        raise InputError("shaft loads: one force row per mesh")
    f = sum(np.asarray(u, dtype=float) * np.asarray(w, dtype=float)[:, None]
            for u, w in zip(units, forces, strict=True))
    d = (np.asarray(flexibility) @ f.reshape(-1)).reshape(-1, 6)
    return d, [np.einsum("ij,ij->i", np.asarray(u, dtype=float), d) for u in units]
