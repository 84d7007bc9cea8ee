"""Cases of the loads the meshes put on the shafts (:mod:`pipeline.shaft.misalignment`):
the statics of a helical pair's two shafts and a planet's cantilevered pin.

* A helical mesh's slice loads on the pinion and on the gear, each in its own mesh frame,
  taken to one global frame (the pinion's axis at the origin, the line of action along -y,
  the gear's axis at (r_b1 + r_b2, -T1T2), its frame turned 180 deg about z) are equal and
  opposite (Newton's third law: zero net force and moment), the moment about each axis is
  P r_b of that gear, the pinion's axial force -h tan(beta_b) P (h = +1 right hand) and the
  transverse loads sum to P.
* A pin clamped at one end, the planet's rigid seat beyond a free length a: the seat's
  deflection and tilt are those of a Timoshenko cantilever loaded at its end by the
  resultant F and the moment F b / 2 (Roark, 8th ed., Table 8.1 cases 1a and 3a, with the
  shear term F a / (kappa G A), kappa Cowper's 1966):
  v(a) = F a^3 / 3EI + F a / kGA + M a^2 / 2EI, theta(a) = F a^2 / 2EI + M a / EI.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.geometry.gear import Material
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Outcome, Quantity

SLICES = 10
FACE = 0.020
"""Face width b of the helical mesh, m."""
RB1, RB2, T1T2 = 0.0705, 0.1410, 0.0548
"""Base radii of pinion and gear and the line of action's length T1T2, m."""
BETA_B = math.radians(14.0)
ROLL = np.linspace(0.0262, 0.0285, SLICES)
"""Cycle-mean roll coordinate per slice, m."""
W_SLOPED = np.linspace(2.0e5, 2.6e5, SLICES)
"""Line load per slice, N/m (a slope across the face)."""
ROUND_OFF = "round-off (the tests hold 1e-12 of the load P, or of P r_b2 for moments)"


def global_loads(loads, frame_sign: float, origin: tuple[float, float], start: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Forces (n, 3) in N and moments about the global origin (n, 3) in N m of the seat
    ``loads`` (:class:`pipeline.shaft.model.PointLoad`) given in a mesh frame whose x
    and y are the pinion frame's times ``frame_sign`` (the gear's: -1, turned 180 deg about
    z), its axis at ``origin`` (x, y) in m and its face's first end at shaft position
    ``start`` (m): the rigid-body statics that Newton's third law is checked in (module
    docstring)."""
    rot = np.diag([frame_sign, frame_sign, 1.0])
    f = np.array([ld.force for ld in loads]) @ rot
    m = np.array([ld.moment for ld in loads]) @ rot
    pos = np.array([[origin[0], origin[1], ld.z - start] for ld in loads])
    return f, m + np.cross(pos, f)


def _helical_statics(hand: str) -> list[Quantity]:
    from pipeline.shaft.misalignment import HelicalMesh, seat_loads, unit_loads

    mesh = HelicalMesh(BETA_B, hand, T1T2, ROLL)
    z = (np.arange(SLICES) + 0.5) * FACE / SLICES
    p = float(W_SLOPED.sum() * FACE / SLICES)
    h = 1.0 if hand == "right" else -1.0
    lp = seat_loads(z, W_SLOPED, FACE, 0.15, RB1, unit_loads(RB1, SLICES, mesh, 0))
    lg = seat_loads(z, W_SLOPED, FACE, 0.40, RB2, unit_loads(RB2, SLICES, mesh, 1))
    fp, mp = global_loads(lp, 1.0, (0.0, 0.0), 0.15 - FACE / 2)
    fg, mg = global_loads(lg, -1.0, (RB1 + RB2, -T1T2), 0.40 - FACE / 2)
    rel = "round-off; the tests hold 1e-12"
    return [
        Quantity(f"{hand} hand: largest component of pinion + gear force", "N", 0.0,
                 float(np.abs(fp.sum(0) + fg.sum(0)).max()), "absolute", 1e-12 * p, ROUND_OFF),
        Quantity(f"{hand} hand: largest component of pinion + gear moment", "N m", 0.0,
                 float(np.abs(mp.sum(0) + mg.sum(0)).max()), "absolute", 1e-12 * p * RB2,
                 ROUND_OFF),
        Quantity(f"{hand} hand: pinion torque P r_b1", "N m", p * RB1,
                 sum(ld.moment[2] for ld in lp), "relative", 1e-12, rel),
        Quantity(f"{hand} hand: gear torque P r_b2", "N m", p * RB2,
                 sum(ld.moment[2] for ld in lg), "relative", 1e-12, rel),
        Quantity(f"{hand} hand: pinion axial force -h tan(beta_b) P", "N",
                 -h * math.tan(BETA_B) * p, float(fp.sum(0)[2]), "relative", 1e-12, rel),
        Quantity(f"{hand} hand: pinion transverse force P", "N", p, float(fp.sum(0)[1]),
                 "relative", 1e-12, rel)]


def case_helical_mesh_statics(context: Context) -> Outcome:
    """A helical mesh's loads on both shafts: equal and opposite, the torques, the axial
    force, for both hands."""
    q = _helical_statics("right") + _helical_statics("left")
    inputs = (("mesh", f"helical, beta_b {math.degrees(BETA_B):g} deg, r_b1 {RB1 * 1e3:g} mm, "
                       f"r_b2 {RB2 * 1e3:g} mm, T1T2 {T1T2 * 1e3:g} mm, b {FACE * 1e3:g} mm"),
              ("load", f"{SLICES} slices, line load 200 to 260 N/mm across the face "
                       f"(P = {W_SLOPED.sum() * FACE / SLICES:g} N)"),
              ("seats", "pinion at 150 mm, gear at 400 mm on their shafts"))
    return Outcome("statics: Newton's third law and the torques of a helical pair", inputs,
                   tuple(q))


def case_cantilevered_pin(context: Context) -> Outcome:
    """A planet's seat on a cantilevered pin under both meshes: deflections, retreats and
    tilt against Roark's Timoshenko cantilever."""
    from pipeline.shaft.beam import BeamShaft
    from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
    from pipeline.shaft.misalignment import body_retreats, planet_unit_loads
    from pipeline.shaft.timoshenko import shear_coefficient

    mat = Material()
    a, b, tail, d, n = 0.015, 0.030, 0.005, 0.035, 10
    lay = ShaftLayout(segments=(ShaftSegment(0.0, a + b + tail, d),), gear_position=a + b / 2,
                      seat_width=b, bearings=(Bearing(0.0, tilting_stiffness=math.inf,
                                                      axial=True),),
                      torque_position=0.0, hub="rigid", material=mat)
    ei = mat.youngs_modulus * math.pi / 64 * d**4
    kga = (float(shear_coefficient(mat.poisson_ratio, d, 0.0)) * mat.shear_modulus
           * math.pi / 4 * d**2)
    points = lay.gear_position + (np.arange(n) + 0.5) * b / n - b / 2
    model = BeamShaft(lay, extra_nodes=tuple(points))
    alpha = math.radians(20.0)
    units = planet_unit_loads((alpha, alpha), n)
    w = (74e3, 60e3)
    disp, ret = body_retreats(model.flexibility(points), units,
                              [np.full(n, wi * b / n) for wi in w])
    resultant = sum(u[0, :2] * wi * b for u, wi in zip(units, w, strict=True))
    v_a = resultant * (a**3 / (3 * ei) + a / kga + (b / 2) * a**2 / (2 * ei))
    t_a = resultant * (a**2 / (2 * ei) + (b / 2) * a / ei)
    u = v_a[None, :] + np.outer(points - a, t_a)
    reason = ("the beam element is exact for end loads: round-off (the tests hold 1e-9, "
              "the flexibility's solve)")

    def worst(name, unit, ref, val, display=None):
        ref, val = np.ravel(ref), np.ravel(val)
        i = int(np.argmax(np.abs(val / ref - 1.0)))
        return Quantity(name, unit, ref[i], val[i], "relative", 1e-9, reason, display)

    q = [worst("seat deflection (x, y) at the face points, worst", "m", u, disp[:, :2], UM)]
    q += [worst(f"retreat along mesh {k + 1}, worst face point", "m", u @ unit[0, :2], r, UM)
          for k, (unit, r) in enumerate(zip(units, ret, strict=True))]
    q.append(worst("seat tilt (theta_x, theta_y) = z x theta(a), worse component", "rad",
                   [-t_a[1], t_a[0]], disp[0, 3:5]))
    inputs = (("pin", f"solid, d {d * 1e3:g} mm, clamped at 0, E {mat.youngs_modulus:g} Pa, "
                      f"nu {mat.poisson_ratio:g}"),
              ("seat", f"rigid, from {a * 1e3:g} to {(a + b) * 1e3:g} mm, a free "
                       f"{tail * 1e3:g} mm stub beyond"),
              ("loads", "sun-planet and planet-ring meshes at 20 deg, uniform 74 and 60 N/mm, "
                        f"{n} face points"))
    return Outcome("Roark's Formulas for Stress and Strain, 8th ed., Table 8.1 cases 1a and "
                   "3a, with the shear term F a / (kappa G A) (Cowper 1966)", inputs, tuple(q))
