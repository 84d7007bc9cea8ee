"""Body (rim) term of an internal gear's teeth: Sainsot's form, fitted for ring rims.

Sainsot et al. (2004) derived and fitted the body-induced deflection of a tooth on an
*external* gear body (an annulus between bore and root circle, clamped at the bore); their
h_f-dependence is dominated by the torsion of that annulus (the fitted ``0.1855 h_f^2`` of
P* against ``2 (1 + nu) h_f^2 / (4 pi) = 0.207 h_f^2`` from the annulus in torsion). A
ring tooth hangs from a rim *outside* its root circle, and its teeth are nearly a pitch
wide at the root (narrow tooth spaces), so the formula does not carry over: mapped to
``h_f = r_rim / r_f`` it is extrapolated below its fitted range (1.4 <= h_f <= 7), and
tooth + body came out 1.2-3.2 times as compliant as a 2D FE of the whole ring (from the
tip to the root of rings of 50-95 teeth, tests/test_internal_gears.py).

The literature on internal spur gear mesh stiffness treats the ring's *global* rim
deformation as a curved beam between the supports of the ring (Chen and Shao 2013),
which needs the support layout, not part of a gear description. The *local* body term
used here keeps Sainsot's form and refits it to whole-ring 2D FE, as Sainsot et al. fitted
theirs (``workflows/ring_body_fit.py --full``: 32 standard rings, 40-160 teeth, 20 and
25 deg, rims of 2.5-12 modules, plane stress, outer rim surface clamped)::

    lambda_f = cos^2(a) / (E b) [ L (u_f/S_f)^2 + M (u_f/S_f) + P ],
    P = P0 + P1 ln(t_R / S_f),

with ``t_R = r_rim - r_f`` the rim thickness, ``S_f = 2 r_f theta_f`` the tooth thickness
at the root circle and ``u_f`` the distance from the clamped root chord to where the
load line crosses the centre line (towards the tip positive). The translation term
grows like a half-plane's surface displacement against a support at depth t_R (Flamant:
``2/pi = 0.64`` per unit of ln; the fit gives 0.68); L and M are the rotation of the
tooth base under the root moment (Sainsot: L* = 6.8-6.9 and M* = 1-3 for external
bodies). Over the fit's 288 flank points, tooth (bending + shear + axial) + this body
term is within 2.9 % RMS (10.7 % max, at the root end of the thinnest rims) of the FE
flank compliance, and within 4.6 % on rings outside the fit (50 teeth; the 4.1 m_n rim of
the Xu et al. (2020) ring). Not included: bending of the rim between the ring's supports, and
a rim that is not clamped along its outer surface.
"""

from __future__ import annotations

import math

from pipeline.geometry.gear import GearSpec
from pipeline.stiffness.foundation import FoundationCoefficients
from pipeline.validation import InputError

# L, M, P0, P1 of ``workflows/ring_body_fit.py --full`` (samples: results/ring_body_fit/workflow/)
RING_TABLE = (3.3022, 1.3101, 0.69949, 0.67717)
T_OVER_S_RANGE = (0.74, 3.89)  # rim thickness over root tooth thickness in the fit
THETA_F_RANGE = (0.0189, 0.0786)  # rad
T_OVER_S_MIN = 0.5  # below it P falls towards 0: the rim bends like a beam, not covered


def ring_coefficients(gear: GearSpec, theta_f: float) -> FoundationCoefficients:
    """Body-term coefficients of an internal gear with root half angle ``theta_f`` (rad).

    Returns :class:`FoundationCoefficients` with ``P`` from the rim thickness and
    ``Q = 0``; its ``h_f`` is ``r_rim / r_f`` and ``in_fit_range`` refers to the ranges of
    the ring fit (rim thickness over root tooth thickness, theta_f).

    Raises
    ------
    InputError if the rim is thinner than half the root tooth thickness.
    """
    rf, r_rim = gear.root_radius, gear.bore_radius
    s_f = 2.0 * rf * theta_f
    ratio = (r_rim - rf) / s_f
    if ratio < T_OVER_S_MIN:
        raise InputError(
            f"{gear.name}.rim_outer_radius = {r_rim * 1e3:.6g} mm leaves a rim of "
            f"{(r_rim - rf) * 1e3:.4g} mm, outside the allowed range [{T_OVER_S_MIN} S_f, inf) = "
            f"[{T_OVER_S_MIN * s_f * 1e3:.4g}, inf) mm (S_f the root tooth thickness): the "
            "analytical ring body term does not cover rims that bend like thin beams")
    L, M, P0, P1 = RING_TABLE
    ok = (T_OVER_S_RANGE[0] <= ratio <= T_OVER_S_RANGE[1]
          and THETA_F_RANGE[0] <= theta_f <= THETA_F_RANGE[1])
    return FoundationCoefficients(L, M, P0 + P1 * math.log(ratio), 0.0, r_rim / rf, theta_f, ok)
