"""Herringbone planetary set of Xu et al. (2020): every member as two helical halves, 8(N+3) DOF.

Bodies ``sL, sR, rL, rR, cL, cR, p1L, p1R, ...`` each carry x, y, z, theta in
the carrier frame (planets in their radial/tangential frame), so gyroscopic and
centripetal terms follow (Xu et al. 2020, eq. 22). Half ``i`` of a mesh uses the
projection of Xu et al. (2020), eq. 17 with the base helix angle beta_b and the hand
``+1`` (left) or ``-1`` (right).

Left/right joints:

* sun: the relief-groove coupling. Either a torsional stiffness (N m/rad; the
  beam guess K_j / l_LR of Xu et al. (2020), eq. 1) with translational stiffnesses or
  ties, or the FE 12 x 12 matrix on ``[ux, uy, uz, rx, ry, rz]`` at O_L then
  O_R. The model has no tilting DOFs, so rx, ry are either *dropped*
  (``groove_rotations="drop"``, default: the halves are held against tilting, as
  the meshes with N planets around the sun nearly do) or removed by *static
  condensation* (``"condense"``: tilting is free and massless,
  ``K = K_aa - K_ab K_bb^-1 K_ba`` on a = (ux, uy, uz, rz) of both nodes; a
  slender groove then transmits no lateral force, the halves pivot instead).
* planets, ring, carrier: a tie (rigid, default) or a stiffness per DOF.

Axial slide of the sun (z_a, m, + towards the right/output side) shifts the
sun's toothed halves against the planets' (Xu et al. 2020, sec. 3.1): the engaged face
width of each sun mesh becomes ``b -+ z_a`` (left loses, right gains), so the
sun-mesh stiffness of each side is scaled by ``(b -+ z_a) / b`` with
``b = engaged_width`` (the contact-line length k_0 L(t) of eq. 13 is proportional
to the engaged width). The static load and the response then move in opposite
directions on the two sides while the natural frequencies barely change.
The sun's external torque acts on both halves (``sun_load_side="both"``, Xu
et al. 2020, eq. 20d) or only on the output half (``"R"``): then the left half's share
passes through the groove, which twists it and makes the two sides unequal.
Meshing phases: sun mesh n uses ``phase_sun[n]`` (+ ``phase_lr`` on the right
side, Xu et al. 2020, eq. 14d), ring mesh n ``phase_ring[n]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from pipeline.dynamics.assembly import Assembly
from pipeline.dynamics.bodies import Body, add_measures
from pipeline.dynamics.couplings import Bearing, GearMesh, Load, MatrixCoupling, Spring, Tie
from pipeline.dynamics.mesh_geometry import cylindrical_mesh_measure
from pipeline.dynamics.modal import ModalResult, classify_modes
from pipeline.dynamics.models.planetary import PlanetaryMembers, check_lumped_members
from pipeline.dynamics.reduction import rigid_body_modes
from pipeline.signals import PeriodicSignal
from pipeline.validation import (
    InputError,
    check_choice,
    check_range,
)

if TYPE_CHECKING:
    from pipeline.fem.groove.result import GrooveStiffness

HalfSignal = PeriodicSignal | tuple[PeriodicSignal, PeriodicSignal]
"""A mesh signal of both halves, or a (left, right) pair."""

SIDES = ("L", "R")
HAND = {"L": 1, "R": -1}
_KEEP_12 = [0, 1, 2, 5, 6, 7, 8, 11]  # ux, uy, uz, rz at O_L then O_R
_DROP_12 = [3, 4, 9, 10]  # rx, ry


def condense_groove_matrix(K12: np.ndarray, rotations: str = "drop") -> np.ndarray:
    """Reduce the 12 x 12 groove matrix to (x, y, z, theta) x (L, R).

    Parameters
    ----------
    K12 : (12, 12) stiffness on [ux, uy, uz, rx, ry, rz] at O_L then O_R (N/m, N, N m/rad).
    rotations : "drop" (rx = ry = 0) or "condense" (rx, ry free, statically condensed).

    Returns
    -------
    (8, 8) stiffness on [xL, yL, zL, thL, xR, yR, zR, thR].
    """
    K = np.asarray(K12, dtype=float)
    if K.shape != (12, 12):
        raise InputError(f"groove coupling matrix has shape {K.shape}; need (12, 12)")
    check_choice("groove_rotations", rotations, ("drop", "condense"))
    a, b = _KEEP_12, _DROP_12
    if rotations == "drop":
        return 0.5 * (K[np.ix_(a, a)] + K[np.ix_(a, a)].T)
    Kbb = K[np.ix_(b, b)]
    X = np.linalg.lstsq(Kbb, K[np.ix_(b, a)], rcond=1e-12)[0]
    out = K[np.ix_(a, a)] - K[np.ix_(a, b)] @ X
    return 0.5 * (out + out.T)


def _scaled_signal(k, factor: float):
    if isinstance(k, PeriodicSignal):
        return PeriodicSignal(k.values * factor, k.period)
    return float(k) * factor


@dataclass(frozen=True)
class HerringbonePlanetaryModel(PlanetaryMembers):
    """Inputs of the herringbone planetary model (totals per member; halves get half).

    Attributes
    ----------
    n_planets : N.
    mass_*, inertia_* : totals per member, kg and kg m^2 (sun, ring, carrier, planet).
    base_radius_sun, base_radius_ring, base_radius_planet, carrier_radius : m.
    pressure_angle_sun, pressure_angle_ring : transverse operating pressure angles, rad.
    base_helix_angle : beta_b, rad (0: spur halves).
    k_sun_mesh, k_ring_mesh : mesh stiffness of *one half* (normal direction), N/m,
        either one signal for both sides or a (left, right) pair.
    k_sun, k_ring, k_carrier : translational bearing stiffness (x, y) per member, N/m.
    kz_sun, kz_ring, kz_carrier : axial bearing stiffness per member, N/m.
    k_planet, kz_planet : planet bearing stiffness (radial, tangential) and axial, N/m.
    kt_sun, kt_ring, kt_carrier : torsional supports, N m/rad.
    groove : sun left/right joint: torsional stiffness (N m/rad), a (12, 12) FE matrix, or a
        :class:`pipeline.fem.groove.result.GrooveStiffness` (its ``coupling_matrix`` is used).
    groove_rotations : "drop" or "condense" for a 12 x 12 ``groove`` (module docstring).
    groove_translational : (kx, ky, kz) of the sun joint in N/m when ``groove`` is a
        scalar; ``None`` ties the translations.
    half_coupling : stiffness (kx, ky, kz, ktheta) joining the halves of planets, ring
        and carrier; ``None`` ties them rigidly.
    axial : include the z DOFs (False: planar halves, 6(N+3) DOF before ties).
    axial_slide : sun axial slide z_a, m.
    engaged_width : engaged face width b of one sun mesh, m (needed when axial_slide != 0).
    sun_load_side : "both" halves or only "R" / "L" take the sun torque.
    planet_angles, phase_sun, phase_ring : as in the planar model, shape (N,).
    phase_lr : extra phase of the right sun meshes, mesh periods (Xu et al. 2020, lambda_LR).
    damping_ratio, sun_torque, carrier_speed, mesh_period : as in the planar model.
    modal_damping_ratio : constant modal damping of Xu et al. (2020) (-), see :class:`Assembly`.
    e_sun_mesh, e_ring_mesh : transmission error of one half (normal direction, m) over one
        mesh period, one signal or a (left, right) pair, or ``None`` (perfect flanks).
    """

    base_helix_angle: float = 0.0
    k_sun_mesh: HalfSignal | float = 2.5e8
    k_ring_mesh: HalfSignal | float = 2.5e8
    kz_sun: float = 1e8
    kz_ring: float = 1e8
    kz_carrier: float = 1e8
    kz_planet: float = 1e8
    groove: float | np.ndarray | GrooveStiffness | None = None
    groove_rotations: str = "drop"
    groove_translational: tuple[float, float, float] | None = None
    half_coupling: tuple[float, float, float, float] | None = None
    axial: bool = True
    axial_slide: float = 0.0
    engaged_width: float | None = None
    sun_load_side: str = "both"
    phase_lr: float = 0.0
    e_sun_mesh: HalfSignal | None = None
    e_ring_mesh: HalfSignal | None = None

    def __post_init__(self) -> None:
        check_range("base_helix_angle", self.base_helix_angle, 0.0, math.radians(45), unit="rad")
        check_range("axial_slide", self.axial_slide, -0.05, 0.05, unit="m")
        check_range("phase_lr", self.phase_lr, -1.0, 1.0)
        check_choice("sun_load_side", self.sun_load_side, ("both", "L", "R"))
        if self.axial_slide != 0.0 and self.engaged_width is None:
            raise InputError("axial_slide needs engaged_width (face width of one sun mesh, m)")
        if self.engaged_width is not None:
            check_range("engaged_width", self.engaged_width, abs(self.axial_slide), 1.0,
                        lo_open=True, unit="m")
        if hasattr(self.groove, "coupling_matrix"):  # a GrooveStiffness from pipeline.fem
            object.__setattr__(self, "groove", np.asarray(self.groove.coupling_matrix, float))
        if self.groove is not None and np.ndim(self.groove) == 0:
            check_range("groove", float(self.groove), 0.0, 1e15, lo_open=True, unit="N m/rad")
        check_lumped_members(self, ("k_sun", "k_ring", "k_carrier", "kz_sun", "kz_ring",
                                    "kz_carrier", "k_planet", "kz_planet", "kt_sun", "kt_ring",
                                    "kt_carrier"))

    def _side(self, value, side: str):
        if isinstance(value, (tuple, list)) and len(value) == 2:
            return value[SIDES.index(side)]
        return value

    def assembly(self) -> Assembly:
        """Bodies, supports, joints, meshes and loads of the set."""
        dofs = ("x", "y", "z", "theta") if self.axial else ("x", "y", "theta")
        N = self.n_planets
        psi = self.angles
        ph_s = np.zeros(N) if self.phase_sun is None else np.array(self.phase_sun)
        ph_r = np.zeros(N) if self.phase_ring is None else np.array(self.phase_ring)
        bodies: dict[str, Body] = {}
        couplings: list[object] = []
        central = dict(
            s=(self.mass_sun, self.inertia_sun, self.k_sun, self.kz_sun, self.kt_sun),
            r=(self.mass_ring, self.inertia_ring, self.k_ring, self.kz_ring, self.kt_ring),
            c=(
                self.mass_carrier,
                self.inertia_carrier,
                self.k_carrier,
                self.kz_carrier,
                self.kt_carrier,
            ),
        )
        for key, (m, i, k, kz, kt) in central.items():
            for side in SIDES:
                name = key + side
                bodies[name] = Body(name, m / 2, i / 2, dofs, rotating_frame=True)
                stiff = {"x": k / 2, "y": k / 2, "theta": kt / 2}
                if self.axial:
                    stiff["z"] = kz / 2
                couplings.append(Bearing(name, stiff))
        for n in range(N):
            for side in SIDES:
                name = f"p{n + 1}{side}"
                bodies[name] = Body(
                    name,
                    self.mass_planet / 2,
                    self.inertia_planet / 2,
                    dofs,
                    frame_angle=float(psi[n]),
                    rotating_frame=True,
                )
        couplings += self._joints(dofs)
        for n in range(N):
            for side in SIDES:
                p, s, r, c = (
                    bodies[f"p{n + 1}{side}"],
                    bodies["s" + side],
                    bodies["r" + side],
                    bodies["c" + side],
                )
                h = HAND[side]
                sun_m = cylindrical_mesh_measure(
                    s,
                    p,
                    psi[n] - self.pressure_angle_sun + math.pi / 2,
                    self.base_radius_sun,
                    self.base_radius_planet,
                    1,
                    1,
                    self.base_helix_angle,
                    h,
                )
                ring_m = cylindrical_mesh_measure(
                    r,
                    p,
                    psi[n] + self.pressure_angle_ring + math.pi / 2,
                    self.base_radius_ring,
                    self.base_radius_planet,
                    1,
                    -1,
                    self.base_helix_angle,
                    -h,
                )
                k_sun = self._side(self.k_sun_mesh, side)
                if self.axial_slide != 0.0:
                    scale = 1.0 + (h * -1.0) * self.axial_slide / self.engaged_width
                    k_sun = _scaled_signal(k_sun, scale)
                lr = self.phase_lr if side == "R" else 0.0
                couplings += [
                    GearMesh(
                        f"s-p{n + 1}{side}",
                        sun_m,
                        k_sun,
                        self.damping_ratio,
                        phase=float(ph_s[n] + lr),
                        transmission_error=self._side(self.e_sun_mesh, side),
                    ),
                    GearMesh(
                        f"r-p{n + 1}{side}",
                        ring_m,
                        self._side(self.k_ring_mesh, side),
                        self.damping_ratio,
                        phase=float(ph_r[n]),
                        transmission_error=self._side(self.e_ring_mesh, side),
                    ),
                    Spring(
                        f"{p.name}.bearing.radial",
                        add_measures({(p.name, "x"): 1.0}, c.in_plane(psi[n], -1.0)),
                        self.k_planet / 2,
                    ),
                    Spring(
                        f"{p.name}.bearing.tangential",
                        add_measures(
                            {(p.name, "y"): 1.0},
                            c.in_plane(psi[n] + math.pi / 2, -1.0),
                            {(c.name, "theta"): -self.carrier_radius},
                        ),
                        self.k_planet / 2,
                    ),
                ]
                if self.axial:
                    couplings.append(
                        Spring(
                            f"{p.name}.bearing.axial",
                            {(p.name, "z"): 1.0, (c.name, "z"): -1.0},
                            self.kz_planet / 2,
                        )
                    )
        blist = list(bodies.values())
        loads = self._loads(blist, couplings)
        return Assembly(
            blist,
            couplings,
            loads,
            period=self.mesh_period,
            modal_damping_ratio=self.modal_damping_ratio,
            carrier_speed=self.carrier_speed,
            name=f"herringbone-planetary-{N}",
        )

    def _joints(self, dofs) -> list[object]:
        out: list[object] = []
        members = ["r", "c"] + [f"p{n + 1}" for n in range(self.n_planets)]
        for m in members:
            if self.half_coupling is None:
                out.append(Tie(m + "L", m + "R", dofs))
            else:
                k = dict(zip(("x", "y", "z", "theta"), self.half_coupling, strict=True))
                out += [
                    Spring(f"{m}.halves.{d}", {(m + "L", d): 1.0, (m + "R", d): -1.0}, k[d])
                    for d in dofs
                ]
        g = self.groove
        if g is None:
            out.append(Tie("sL", "sR", dofs))
        elif np.ndim(g) == 0:
            out.append(
                Spring("sun.groove.theta", {("sL", "theta"): 1.0, ("sR", "theta"): -1.0}, float(g))
            )
            tr = [d for d in dofs if d != "theta"]
            if self.groove_translational is None:
                out.append(Tie("sL", "sR", tuple(tr)))
            else:
                k = dict(zip(("x", "y", "z"), self.groove_translational, strict=True))
                out += [
                    Spring(f"sun.groove.{d}", {("sL", d): 1.0, ("sR", d): -1.0}, k[d]) for d in tr
                ]
        else:
            K8 = condense_groove_matrix(np.asarray(g), self.groove_rotations)
            names = [("sL", d) for d in ("x", "y", "z", "theta")] + [
                ("sR", d) for d in ("x", "y", "z", "theta")
            ]
            keep = [i for i, (_, d) in enumerate(names) if d in dofs]
            out.append(
                MatrixCoupling("sun.groove", tuple(names[i] for i in keep), K8[np.ix_(keep, keep)])
            )
        return out

    def _loads(self, bodies, couplings) -> list[Load]:
        if self.sun_torque == 0.0:
            return []
        share = {"both": (0.5, 0.5), "L": (1.0, 0.0), "R": (0.0, 1.0)}[self.sun_load_side]
        loads = [
            Load("s" + side, "theta", self.sun_torque * w)
            for side, w in zip(SIDES, share, strict=True)
            if w
        ]
        probe = Assembly(bodies, couplings, loads, period=self.mesh_period).assemble()
        R = rigid_body_modes(probe)
        if R.shape[1]:
            r = probe.basis @ R[:, 0]
            i_s, i_c = probe.index("sL.theta"), probe.index("cL.theta")
            if abs(r[i_c]) > 1e-12 * np.abs(r).max():
                tc = -self.sun_torque * r[i_s] / r[i_c]
                loads += [Load("cL", "theta", tc / 2), Load("cR", "theta", tc / 2)]
        return loads

    def classify(self, result: ModalResult) -> ModalResult:
        """Label modes by the motion of the central members (see :func:`classify_modes`)."""
        tr = [f"{b}{s}.{d}" for b in "crs" for s in SIDES for d in ("x", "y")]
        rot = [f"{b}{s}.theta" for b in "crs" for s in SIDES]
        return classify_modes(result, tr, rot)
