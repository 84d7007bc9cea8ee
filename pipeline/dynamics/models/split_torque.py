"""Split-torque double-power-input transmission of Jin et al. (2018) (40 DOF).

Two identical branches ``L`` and ``R`` (one engine each) meet at one output gear:

* input stage: engine rotor ``in{b}`` (theta) - input shaft - bevel pinion ``bp{b}``
  (x, y, z, theta) meshing with the bevel gear ``bg{b}`` (x, y, z, theta);
* split-torque stage: the split pinion ``sp{b}`` on the bevel-gear shaft (translations
  tied to ``bg{b}``, torsion shaft between them) drives the split gears ``g1s{b}``,
  ``g2s{b}`` (x, y, theta);
* torque-confluence stage: each split gear sits on a dual-gear shaft with the
  confluence pinion ``g1{b}``, ``g2{b}`` (translations tied, torsion shaft), which
  drive the output gear ``o`` (x, y, theta); the rotor load ``out`` (theta) hangs on
  the output shaft.

That is 1 + 4 + 4 + 1 + 2 x 4 = 18 DOF per branch plus 4 at the output: 40, as in
Jin et al. (2018), eq. 1. The bevel mesh uses the projection of Jin et al. (2018), eqs. 4-5
(direction cosines P_x, P_y, P_z from the pitch-cone, spiral and pressure angles) in the
shafts' own frames; the parallel-axis meshes use
:func:`pipeline.dynamics.mesh_geometry.cylindrical_mesh_measure` with every theta
counter-clockwise in the common frame. Each mesh carries its stiffness and the
Jin et al. (2018) friction force and friction torques (eqs. 15-17).

Jin et al. (2018) state the installation angles (108, 104, 150 deg) without a figure we can
read; we take them as the angle between the two split gears seen from the split
pinion, between the two confluence pinions of a branch seen from the output gear,
and between the two branches' bisectors at the output gear. Only the directions
of the lines of action enter the lumped model.

The three stages mesh at incommensurate frequencies. :meth:`SplitTorqueModel.stage_system`
returns the system in which only one stage's coefficients vary (period: that stage's
mesh period), the others held at their means; the Fourier series method of Jin et al. (2018)
superposes the stage responses (:func:`pipeline.dynamics.multirate.superpose_stages`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pipeline.dynamics.assembly import Assembly
from pipeline.dynamics.bodies import Body
from pipeline.dynamics.couplings import Bearing, FrictionLoad, GearMesh, Load, Tie, TorsionalShaft
from pipeline.dynamics.mesh_geometry import cylindrical_mesh_measure, friction_direction_measure
from pipeline.dynamics.mesh_input import MeshExcitation
from pipeline.dynamics.reduction import rigid_body_modes
from pipeline.dynamics.system import LinearPeriodicSystem
from pipeline.geometry.planetary import dec
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_choice, check_positive, check_range

BRANCHES = ("L", "R")
STAGES = ("input", "split", "confluence")


@dataclass(frozen=True)
class StageMesh:
    """Geometry and excitation of one stage's meshes (SI).

    Attributes
    ----------
    excitation : stiffness and friction coefficients over one mesh period (N/m, N m/m).
    base_radius_driver, base_radius_driven : m.
    pressure_angle : transverse operating pressure angle, rad.
    mesh_frequency : Hz at the operating speed.
    teeth_driver, teeth_driven : tooth counts (meshing phases).
    """

    excitation: MeshExcitation
    base_radius_driver: float
    base_radius_driven: float
    pressure_angle: float
    mesh_frequency: float
    teeth_driver: int
    teeth_driven: int

    def __post_init__(self) -> None:
        check_range("mesh_frequency", self.mesh_frequency, 1e-3, 1e6, unit="Hz")


@dataclass(frozen=True)
class SplitTorqueModel:
    """Inputs of the split-torque model of Jin et al. (2018).

    Attributes
    ----------
    input_stage, split_stage, confluence_stage : :class:`StageMesh` of each stage.
    bevel_angles : (pitch-cone delta, spiral beta, normal pressure alpha) of the bevel
        pinion, rad (Jin et al. 2018, eq. 5).
    masses : kg per body kind: "bp", "bg", "sp", "gs" (split gear), "gc" (confluence
        pinion), "o".
    inertias : kg m^2 per body kind, plus "in" (engine rotor) and "out" (rotor load).
    shafts : torsional stiffness N m/rad: "input", "split", "dual", "output".
    bearing_stiffness, axial_stiffness : N/m for all supports.
    installation_angles : (split, confluence, branch) angles in rad (module docstring).
    input_torque : N m per engine on ``in{b}``.
    damping_ratio : mesh damping ratio; modal_damping_ratio : constant modal damping.
    friction : include the friction terms.
    """

    input_stage: StageMesh
    split_stage: StageMesh
    confluence_stage: StageMesh
    bevel_angles: tuple[float, float, float]
    masses: dict = field(default_factory=dict)
    inertias: dict = field(default_factory=dict)
    shafts: dict = field(default_factory=dict)
    bearing_stiffness: float = 1e9
    axial_stiffness: float = 5e8
    installation_angles: tuple[float, float, float] = (
        math.radians(108),
        math.radians(104),
        math.radians(150),
    )
    input_torque: float = 457.0
    damping_ratio: float = 0.05
    modal_damping_ratio: float = 0.0
    friction: bool = True

    def __post_init__(self) -> None:
        for key in ("bp", "bg", "sp", "gs", "gc", "o"):
            check_positive(f"masses[{key!r}]", self.masses.get(key, 0.0), "kg")
        for key in ("in", "bp", "bg", "sp", "gs", "gc", "o", "out"):
            check_positive(f"inertias[{key!r}]", self.inertias.get(key, 0.0), "kg m^2")
        for key in ("input", "split", "dual", "output"):
            check_positive(f"shafts[{key!r}]", self.shafts.get(key, 0.0), "N m/rad")
        check_positive("bearing_stiffness", self.bearing_stiffness, "N/m")
        check_positive("axial_stiffness", self.axial_stiffness, "N/m")
        check_positive("input_torque", self.input_torque, "N m")
        for i, a in enumerate(self.bevel_angles):
            check_range(f"bevel_angles[{i}]", a, 0.0, math.pi / 2, unit="rad")

    def stage(self, name: str) -> StageMesh:
        """The :class:`StageMesh` of "input", "split" or "confluence"."""
        check_choice("stage", name, STAGES)
        return {
            "input": self.input_stage,
            "split": self.split_stage,
            "confluence": self.confluence_stage,
        }[name]

    def assembly(self, varying: str | None = None) -> Assembly:
        """Bodies, supports, shafts, meshes and torques.

        Parameters
        ----------
        varying : the stage whose coefficients vary in time (its mesh period is the
            system period); the other stages use their mean values. ``None``: the
            split stage varies and the period is its mesh period.
        """
        varying = varying or "split"
        check_choice("varying", varying, STAGES)
        m, inertia = self.masses, self.inertias
        bodies: list[Body] = [
            Body("o", m["o"], inertia["o"], ("x", "y", "theta")),
            Body("out", inertia=inertia["out"], dofs=("theta",)),
        ]
        couplings: list[object] = [
            Bearing("o", {"x": self.bearing_stiffness, "y": self.bearing_stiffness}),
            TorsionalShaft("o", "out", self.shafts["output"]),
        ]
        a_s, a_c, a_b = self.installation_angles
        for b in BRANCHES:
            bisector = math.pi / 2 + (a_b / 2 if b == "L" else -a_b / 2)
            bodies += [
                Body(f"in{b}", inertia=inertia["in"], dofs=("theta",)),
                Body(f"bp{b}", m["bp"], inertia["bp"], ("x", "y", "z", "theta")),
                Body(f"bg{b}", m["bg"], inertia["bg"], ("x", "y", "z", "theta")),
                Body(f"sp{b}", m["sp"], inertia["sp"], ("x", "y", "z", "theta")),
            ]
            couplings += [
                TorsionalShaft(f"in{b}", f"bp{b}", self.shafts["input"]),
                TorsionalShaft(f"bg{b}", f"sp{b}", self.shafts["split"]),
                Tie(f"bg{b}", f"sp{b}", ("x", "y", "z")),
            ]
            for name in (f"bp{b}", f"bg{b}"):
                couplings.append(
                    Bearing(
                        name,
                        {
                            "x": self.bearing_stiffness,
                            "y": self.bearing_stiffness,
                            "z": self.axial_stiffness,
                        },
                    )
                )
            couplings.append(self._bevel_mesh(b, varying == "input"))
            for j, sgn in ((1, 1.0), (2, -1.0)):
                gs, gc = f"g{j}s{b}", f"g{j}{b}"
                bodies += [
                    Body(gs, m["gs"], inertia["gs"], ("x", "y", "theta")),
                    Body(gc, m["gc"], inertia["gc"], ("x", "y", "theta")),
                ]
                couplings += [
                    TorsionalShaft(gs, gc, self.shafts["dual"]),
                    Tie(gs, gc, ("x", "y")),
                    Bearing(gs, {"x": self.bearing_stiffness, "y": self.bearing_stiffness}),
                ]
                # split gear j seen from the split pinion, away from the output gear
                gamma_s = bisector + sgn * a_s / 2
                # meshing phases: the teeth of the common gear between the two contacts
                # (the same rule as the planet phases of Xu et al. 2020, eq. 10)
                ph_s = float(
                    dec(self.split_stage.teeth_driver * (sgn - 1) / 2 * a_s / (2 * math.pi))
                )
                couplings.append(
                    self._parallel_mesh(
                        f"split{j}{b}",
                        _find(bodies, f"sp{b}"),
                        _find(bodies, gs),
                        gamma_s,
                        self.split_stage,
                        ccw_driver=True,
                        varying=varying == "split",
                        phase=ph_s,
                    )
                )
                # confluence pinion j seen from the output gear
                gamma_c = bisector + sgn * a_c / 2
                ph_c = float(
                    dec(
                        self.confluence_stage.teeth_driven
                        * (gamma_c - math.pi / 2)
                        / (2 * math.pi)
                    )
                )
                couplings.append(
                    self._parallel_mesh(
                        f"conf{j}{b}",
                        _find(bodies, gc),
                        _find(bodies, "o"),
                        gamma_c + math.pi,
                        self.confluence_stage,
                        ccw_driver=False,
                        varying=varying == "confluence",
                        phase=ph_c,
                    )
                )
        loads = [Load(f"in{b}", "theta", self.input_torque) for b in BRANCHES]
        probe = Assembly(bodies, couplings, loads).assemble()
        R = rigid_body_modes(probe)
        if R.shape[1] != 1:
            raise InputError(f"the split-torque layout has {R.shape[1]} rigid-body modes; need 1")
        r = probe.basis @ R[:, 0]
        t_in = sum(r[probe.index(f"in{b}.theta")] for b in BRANCHES) * self.input_torque
        loads.append(Load("out", "theta", -t_in / r[probe.index("out.theta")]))
        period = 1.0 / self.stage(varying).mesh_frequency
        return Assembly(
            bodies,
            couplings,
            loads,
            period=period,
            name=f"split-torque-{varying}",
            modal_damping_ratio=self.modal_damping_ratio,
        )

    def stage_system(self, stage: str) -> LinearPeriodicSystem:
        """Assembled system in which only ``stage`` varies (period: its mesh period)."""
        return self.assembly(stage).assemble()

    def _signals(self, st: StageMesh, varying: bool):
        ex = st.excitation
        sig = [
            ex.stiffness,
            ex.friction_stiffness,
            ex.friction_torque_pinion,
            ex.friction_torque_gear,
        ]
        if not varying:
            sig = [PeriodicSignal(np.full(4, s.mean())) for s in sig]
        return sig

    def _friction(
        self, sig, pattern_force, driver: str, driven: str, spin: float, driven_spin: float
    ):
        """Friction loads; ``spin``, ``driven_spin``: sign of each gear's own sense on theta."""
        if not self.friction or not self.stage_has_friction(sig):
            return ()
        k, kf, kt1, kt2 = sig
        out = [
            FrictionLoad(kt1, {(driver, "theta"): spin}),
            FrictionLoad(kt2, {(driven, "theta"): driven_spin}),
        ]
        if pattern_force is not None and np.abs(kf.values).max() > 0:
            out.insert(0, FrictionLoad(kf, pattern_force))
        return tuple(out)

    @staticmethod
    def stage_has_friction(sig) -> bool:
        return any(np.abs(s.values).max() > 0 for s in sig[1:])

    def _parallel_mesh(
        self,
        name,
        driver: Body,
        driven: Body,
        gamma: float,
        st: StageMesh,
        ccw_driver: bool,
        varying: bool,
        phase: float,
    ) -> GearMesh:
        a = st.pressure_angle
        if ccw_driver:
            d, spin = gamma - a + math.pi / 2, 1
        else:
            d, spin = gamma + a - math.pi / 2, -1
        measure = cylindrical_mesh_measure(
            driver, driven, d, st.base_radius_driver, st.base_radius_driven, spin, spin
        )
        sig = self._signals(st, varying)
        n_line = d if spin > 0 else d + math.pi  # profile normal mirrors with the flank
        fr = self._friction(
            sig,
            friction_direction_measure(driver, driven, n_line),
            driver.name,
            driven.name,
            spin,
            -spin,
        )
        return GearMesh(name, measure, sig[0], self.damping_ratio, phase=phase, friction=fr)

    def _bevel_mesh(self, b: str, varying: bool) -> GearMesh:
        delta, beta, alpha = self.bevel_angles
        px = math.sin(delta) * math.sin(beta) * math.cos(alpha) + math.cos(delta) * math.sin(alpha)
        py = math.cos(beta) * math.cos(alpha)
        pz = math.cos(delta) * math.sin(beta) * math.cos(alpha) - math.sin(delta) * math.sin(alpha)
        st = self.input_stage
        p, g = f"bp{b}", f"bg{b}"
        # Jin et al. (2018), eq. 4 with compression positive and each theta in its own driving
        # sense
        measure = {
            (p, "x"): -px,
            (g, "x"): -px,
            (p, "z"): pz,
            (g, "z"): pz,
            (p, "y"): py,
            (g, "y"): py,
            (p, "theta"): st.base_radius_driver * py,
            (g, "theta"): -st.base_radius_driven * py,
        }
        sig = self._signals(st, varying)
        fr = self._friction(sig, None, p, g, 1, 1)
        return GearMesh(f"bevel{b}", measure, sig[0], self.damping_ratio, friction=fr)


def _find(bodies: list[Body], name: str) -> Body:
    for body in bodies:
        if body.name == name:
            return body
    raise InputError(f"no body named {name!r}")
