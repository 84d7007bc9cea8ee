"""Case of ISO 6336-1 method C's shaft deformation f_sh (Eq. 57, Figure 13 arrangements,
:func:`pipeline.rating.face_load.shaft_misalignment`) beside the beam shaft's mesh
misalignment (:mod:`pipeline.shaft.beam`, :func:`pipeline.shaft.misalignment.flank_retreat`).

A 20 deg spur pinion on a plain steel shaft of d_sh 50 mm (d1 = d_sh, ISO's own body),
rigid bearings 400 mm apart, the torque held at the shaft's first end, a uniform line load
w_t / cos(alpha) (w_t = F_m / b 300 N/mm) along the line of action over the face b 40 mm
(40 slices). The beam's misalignment is the rise across the face of the least-squares line
through the gap (bending u_y and torsion r_b theta_z in the plane of action).

* mid-span (s = 0): the bow of bending is symmetric, the tilt is the body's torsion
  r_b^2 w b^2 / (2 G J) (exact), and against ISO's f_sh the ratio is exactly
  4 cos(alpha) / (pi G 0.023 um mm/N): ISO's bracket leaves 0.7 x 0.023 um mm/N, which is a
  body of d1 twisted by its own face load read at the reference circle, 4 / (pi G); the
  beam reads it along the line of action;
* arrangements a and b (offset s from mid-span towards / away from the torque end): the
  bending tilt is Euler-Bernoulli's F s (l^2 - 4 s^2) / (6 E I l) plus shear F s / (l kappa
  G A) across the face, to 1 % (the load spread over the face against a point load, of
  order (b / l)^2); arrangement c (overhung s beyond the second bearing): F s (2 l + 3 s) /
  (6 E I) plus F / (2 kappa G A), to 2 % (the tilt changes along the face by 3 s / (2 l +
  3 s) of it per face width).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.geometry.gear import Material
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Outcome, Plot, Quantity, Series

ALPHA = math.radians(20.0)
W_T = 300e3  # F_m / b, N/m
FACE = 0.040
D_SH = 0.050
SPAN = 0.400
FIRST, SECOND = 0.050, 0.450
SLICES = 40
OFFSETS = (0.05, 0.1, 0.2, 0.3)
"""s / l of arrangements a and b."""
OVERHANG = 0.1
"""s / l of arrangement c."""


def _layout(gear_position: float, length: float):
    from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment

    return ShaftLayout((ShaftSegment(0.0, length, D_SH),), gear_position, FACE,
                       (Bearing(FIRST, axial=True), Bearing(SECOND)), 0.0, "integral",
                       Material())


def beam_misalignment(gear_position: float, length: float) -> tuple[float, float]:
    """(rise across the face of the least-squares line through the gap, that of its torsion
    part), m."""
    from pipeline.shaft.beam import BeamShaft
    from pipeline.shaft.misalignment import flank_retreat

    layout = _layout(gear_position, length)
    z = (np.arange(SLICES) + 0.5) * FACE / SLICES
    model = BeamShaft(layout, extra_nodes=tuple(gear_position - FACE / 2 + z))
    r = flank_retreat(model, z, np.full(SLICES, W_T / math.cos(ALPHA)),
                      0.5 * D_SH * math.cos(ALPHA))
    return (float(np.polyfit(z, r.total, 1)[0] * FACE),
            float(np.polyfit(z, r.twist, 1)[0] * FACE))


def _iso(arrangement: str, offset: float) -> float:
    """ISO 6336-1 Eq. (57) f_sh (m), B* = 1, unstiffened, d1 = d_sh."""
    from pipeline.rating.face_load import ARRANGEMENTS, shaft_misalignment

    x = ARRANGEMENTS[arrangement][1] * SPAN * offset / D_SH**2
    return shaft_misalignment(W_T, FACE, D_SH, 1.0, x)


def _section() -> tuple[float, float, float]:
    from pipeline.shaft.timoshenko import shear_coefficient

    kappa = float(shear_coefficient(Material().poisson_ratio, np.array(D_SH), np.array(0.0)))
    return math.pi * D_SH**4 / 64, math.pi * D_SH**2 / 4, kappa


def case_iso_6336_1_fsh_beside_beam(context: Context) -> Outcome:
    """The beam's face tilt at mid-span against the exact torsion and ISO's f_sh (the exact
    ratio 4 cos(alpha) / (pi G 0.023)); offset and overhung pinions against the closed-form
    bending, and the ratio to ISO that follows from it."""
    mat = Material()
    e, g = mat.youngs_modulus, mat.shear_modulus
    inertia, area, kappa = _section()
    force = W_T / math.cos(ALPHA) * FACE
    rb = 0.5 * D_SH * math.cos(ALPHA)
    torsion = rb**2 * force / FACE * FACE**2 / (2 * g * math.pi * D_SH**4 / 32)
    mid = (FIRST + SECOND) / 2
    beam, twist = beam_misalignment(mid, 0.5)
    q = [Quantity("mid-span face tilt (torsion r_b^2 w b^2 / (2 G J))", "m", torsion, beam,
                  "relative", 1e-7, "exact beam element; the least-squares line on 40 slices "
                                    "of a linear twist: round-off", UM),
         Quantity("mid-span computed / ISO f_sh: 4 cos(alpha) / (pi G 0.023 um mm/N)", "-",
                  4 * math.cos(ALPHA) / (math.pi * g * 0.023e-9), beam / _iso("a", 0.0),
                  "relative", 1e-6, "exact relation (module docstring): round-off")]
    ratios = {"a": [], "b": []}
    for ratio_sl in OFFSETS:
        s = ratio_sl * SPAN
        bending = FACE * (force * s * (SPAN**2 - 4 * s**2) / (6 * e * inertia * SPAN)
                          + force * s / (SPAN * kappa * g * area))
        for name, position, sign in (("a", mid - s, 1.0), ("b", mid + s, -1.0)):
            beam, twist = beam_misalignment(position, 0.5)
            iso = _iso(name, s)
            ratios[name].append(abs(beam) / iso)
            if ratio_sl in (0.05, 0.3):
                q.append(Quantity(f"bending tilt, arrangement {name}, s / l {ratio_sl:g}", "m",
                                  sign * bending, beam - twist, "relative", 1e-2,
                                  "the load spread over the face against the closed form's "
                                  "point load: of order (b / l)^2 = 1 %", UM))
    s = OVERHANG * SPAN
    beam, twist = beam_misalignment(SECOND + s, SECOND + s + FACE)
    overhung = FACE * (force * s * (2 * SPAN + 3 * s) / (6 * e * inertia)
                       + force / (2 * kappa * g * area))
    q.append(Quantity(f"bending tilt, arrangement c (overhung), s / l {OVERHANG:g}", "m",
                      overhung, beam - twist, "relative", 2e-2,
                      "the tilt changes along the face by 3 s / (2 l + 3 s) of it per face "
                      "width: the tests hold 2 %", UM))
    plot = Plot("Beam face tilt over ISO 6336-1 f_sh (unstiffened, d1 = d_sh)",
                "pinion offset from mid-span s / l [-]", "computed / ISO f_sh [-]",
                (Series("arrangement a (towards the torque end)", OFFSETS, ratios["a"]),
                 Series("arrangement b (away from it)", OFFSETS, ratios["b"])))
    inputs = (("shaft", f"solid steel, d_sh {D_SH * 1e3:g} mm, bearings at {FIRST * 1e3:g} and "
                        f"{SECOND * 1e3:g} mm (rigid), torque held at z = 0"),
              ("pinion", f"spur, alpha 20 deg, d1 = d_sh, b {FACE * 1e3:g} mm, integral"),
              ("load", f"F_m / b {W_T * 1e-3:g} N/mm, uniform over {SLICES} slices"),
              ("ISO", "Eq. (57), B* = 1, K' unstiffened: a 0.8, b -0.8, c 1.33"))
    return Outcome("ISO 6336-1:2006 (method C): Eq. (57) and Figure 13; Euler-Bernoulli "
                   "and Timoshenko beam closed forms (Timoshenko & Gere)", inputs, tuple(q),
                   plots=(plot,),
                   notes="ISO's constant K' drops the beam's 1 - 4 (s / l)^2: computed / ISO "
                         "falls from about 0.87 (a) and 0.83 (b) at s / l 0.05 to 0.62 and "
                         "0.60 at 0.3.")
