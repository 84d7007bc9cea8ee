"""The split-torque helicopter transmission of Jin et al. (2018) (Table 2) as model inputs.

Table 2: 2000 kW (taken per engine: the two inputs are identical engines and the
branches equal), 20900 rpm input; normal modules 3.85, 3.5 and 4.4 mm (the table
prints "44"; 44 mm is no helicopter module and 4.4 mm fits the 100 mm face);
ratios 27/74 (bevel), 31/98 (split), 23/215 (confluence); pressure angles 20,
22.5, 20 deg; face widths 45, 48, 100 mm; spiral/helix angle 30 deg for the input
and confluence stages (the confluence gears are herringbone, Jin et al. 2018, sec. 5.2);
installation angles 108, 104, 150 deg.

The bevel stage's stiffness is that of its virtual (Tredgold) helical pair, z_v =
z / cos(delta), turned to the normal direction (k_n = k_t / cos^2 beta_b) because
Jin et al. (2018) projection of eq. 5 is along the tooth normal; its radii are the
pitch radii of the actual bevel gears (eq. 4 "radius of mesh points"). The stiffness and the
friction coefficients of every stage come from the pipeline's analytical stiffness
with the EHL friction of Jin et al. (2018), eq. 9 (:mod:`pipeline.dynamics.mesh_input`).

Not given by Jin et al. (2018) (assumed, stated here): masses and inertias of steel discs of
the pitch diameters and face widths; shaft torsional stiffnesses; bearing
stiffness 1e9 N/m (radial) and 5e8 N/m (axial); engine rotor inertia 0.05 kg m^2;
rotor load inertia 500 kg m^2 (it only sets the rigid-body mode); mesh damping
ratio 0.05 and modal damping 0.02; oil viscosity 0.02 Pa s.
"""

from __future__ import annotations

import math
from dataclasses import replace

from pipeline.dynamics.mesh_input import analytical_excitation
from pipeline.dynamics.models.split_torque import SplitTorqueModel, StageMesh
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.signals import PeriodicSignal
from pipeline.stiffness.mesh import FrictionModel, OperatingPoint

POWER = 2.0e6  # W per engine
INPUT_RPM = 20900.0
RHO = 7850.0
TEETH = {"input": (27, 74), "split": (31, 98), "confluence": (23, 215)}
MODULE = {"input": 3.85e-3, "split": 3.5e-3, "confluence": 4.4e-3}
PRESSURE = {"input": 20.0, "split": 22.5, "confluence": 20.0}
WIDTH = {"input": 0.045, "split": 0.048, "confluence": 0.100}
HELIX = {"input": 30.0, "split": 0.0, "confluence": 30.0}
ROUGHNESS_UM = (0.3, 0.6, 0.9)  # Jin et al. (2018), sec. 5.3


def _disc(radius: float, width: float) -> tuple[float, float]:
    m = RHO * math.pi * radius**2 * width
    return m, 0.5 * m * radius**2


def stage_pairs() -> dict[str, GearPair]:
    """Gear pairs of the three stages (the bevel stage as its virtual helical pair)."""
    pairs = {}
    delta = math.atan(TEETH["input"][0] / TEETH["input"][1])
    for st, (z1, z2) in TEETH.items():
        beta = math.radians(HELIX[st])
        common = dict(
            module=MODULE[st],
            pressure_angle=math.radians(PRESSURE[st]),
            helix_angle=beta,
            face_width=WIDTH[st],
        )
        if st == "input":
            z1, z2 = round(z1 / math.cos(delta)), round(z2 / math.cos(math.pi / 2 - delta))
        if st == "confluence":
            common.update(herringbone=True, groove_width=0.02)
        hands = ("right", "left") if beta else ("none", "none")
        r1 = z1 * MODULE[st] / math.cos(beta) / 2
        r2 = z2 * MODULE[st] / math.cos(beta) / 2
        pairs[st] = GearPair(
            GearSpec(z1, hand=hands[0], bore_radius=0.35 * r1, name=f"{st}1", **common),
            GearSpec(z2, hand=hands[1], bore_radius=0.6 * r2, name=f"{st}2", **common),
        )
    return pairs


def _speeds() -> dict[str, float]:
    """Driver speed of each stage, rad/s."""
    w = INPUT_RPM * 2 * math.pi / 60
    out = {}
    for st, (z1, z2) in TEETH.items():
        out[st] = w
        w = w * z1 / z2
    return out


def split_torque_helicopter_model(
    roughness: float = 0.6e-6,
    friction: bool = True,
    positions: int = 180,
    slices: int = 30,
    viscosity: float = 0.02,
) -> SplitTorqueModel:
    """Jin et al. (2018) split-torque model with EHL friction for a surface roughness.

    Parameters
    ----------
    roughness : composite RMS roughness S in m (Jin et al. 2018: 0.3, 0.6, 0.9 um).
    friction : include the friction force and friction torques.
    positions : samples per mesh period of each stage's stiffness.
    slices : face slices of the helical stages.
    viscosity : oil dynamic viscosity at inlet temperature, Pa s.
    """
    speeds = _speeds()
    torque = POWER / speeds["input"]
    stages = {}
    ratio_torque = torque
    for st, pair in stage_pairs().items():
        z1, z2 = TEETH[st]
        share = {"input": 1.0, "split": 0.5, "confluence": 1.0}[st]
        t1 = ratio_torque * share
        fm = FrictionModel(kind="ehl", roughness=roughness, viscosity=viscosity)
        ex = analytical_excitation(
            pair, fm if friction else None, OperatingPoint(t1, speeds[st]), positions, slices
        )
        if st == "input":
            cb = math.cos(pair.pinion.base_helix_angle) ** 2
            ex = replace(
                ex,
                **{
                    f: PeriodicSignal(getattr(ex, f).values / cb, ex.mesh_period)
                    for f in (
                        "stiffness",
                        "friction_stiffness",
                        "friction_torque_pinion",
                        "friction_torque_gear",
                    )
                },
            )
        if st == "input":  # Jin et al. 2018, eq. 4: radii of the mesh points of the bevels
            beta = math.radians(HELIX[st])
            r1, r2 = (z * MODULE[st] / (2 * math.cos(beta)) for z in (z1, z2))
        else:
            r1, r2 = pair.pinion.base_radius, pair.gear.base_radius
        stages[st] = StageMesh(
            ex,
            r1,
            r2,
            pair.operating_pressure_angle
            if st != "input"
            else pair.pinion.transverse_pressure_angle,
            speeds[st] * z1 / (2 * math.pi),
            z1,
            z2,
        )
        ratio_torque = t1 * z2 / z1
    masses, inertias = {}, {}
    for key, (st, i) in {
        "bp": ("input", 0),
        "bg": ("input", 1),
        "sp": ("split", 0),
        "gs": ("split", 1),
        "gc": ("confluence", 0),
        "o": ("confluence", 1),
    }.items():
        z = TEETH[st][i]
        r = z * MODULE[st] / math.cos(math.radians(HELIX[st])) / 2
        masses[key], inertias[key] = _disc(r, WIDTH[st])
    inertias.update({"in": 0.05, "out": 500.0})
    delta = math.atan(TEETH["input"][0] / TEETH["input"][1])
    return SplitTorqueModel(
        stages["input"],
        stages["split"],
        stages["confluence"],
        bevel_angles=(delta, math.radians(HELIX["input"]), math.radians(PRESSURE["input"])),
        masses=masses,
        inertias=inertias,
        shafts={"input": 2.0e5, "split": 5.0e6, "dual": 2.0e6, "output": 5.0e7},
        input_torque=torque,
        damping_ratio=0.05,
        modal_damping_ratio=0.02,
        friction=friction,
    )
