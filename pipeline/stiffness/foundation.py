"""Fillet-foundation (gear body) compliance of Sainsot, Velex & Duverger (2004).

    lambda_f = cos^2(alpha_m) / (E L)
               * [ L* (u_f/S_f)^2 + M* (u_f/S_f) + P* (1 + Q* tan^2 alpha_m) ]

(J. Mech. Des. 126, 748-752; Yang et al. 2026, eq. 16), with the coefficients from the
fitted polynomials (Yang et al. 2026, eq. 17)

    X*(h_f, theta_f) = A/theta_f^2 + B h_f^2 + C h_f/theta_f + D/theta_f + E h_f + F,

``h_f = r_f / r_int`` (root radius over bore radius), ``theta_f`` the half angle
of the tooth at the root circle, ``S_f = 2 r_f theta_f`` the tooth thickness at
the root circle, ``u_f`` the distance along the centreline from the root circle
to where the load line crosses it, and ``alpha_m`` the load angle.

The extracted text of Table 1 of Yang et al. (2026) lost the minus signs; the signs below are
those of the original paper (Table 1 of Sainsot et al. 2004). The fit was made
for 1.4 <= h_f <= 7 and 0.01 <= theta_f <= 0.12 rad.

Bores outside the fit. Sainsot's body is an annulus clamped at its bore, and the h_f
dependence of P* is that annulus in torsion (``0.1855 h_f^2``, against
``2 (1 + nu) h_f^2 / (4 pi)`` for a plane annulus; :mod:`.ring_body`), which grows
without bound as the bore closes: extrapolated, the seed 001 pair's mesh stiffness fell
from 3.76e8 N/m (21 mm bore, h_f 3.4) to 2.03e8 (10 mm), 7.3e7 (5 mm) and 8.6e6 (2 mm),
while a solid gear, with no bore to be clamped at, was given the fit's upper end,
2.07e8. The material inside ``r_f / 7`` is the shaft seat, whose torsion belongs to
the shaft, not to the tooth foundation; so a small bore is treated as the solid gear
is, and both ends of the fit the same way: ``h_f`` is held at the nearest end of
[1.4, 7] (a rim thinner than ``h_f = 1.4`` also bends like a ring, which the fit does
not contain, so the polynomial's softening towards ``h_f = 1`` is not trusted either).
The mesh stiffness is then continuous and monotonic in the bore, and a bore -> 0 tends
to the solid gear (tests/test_stiffness_body_term.py): the seed 001 pair's mean mesh
stiffness is 2.07e8 N/m for a solid gear and any bore up to r_f / 7 = 10.2 mm, rising
continuously and monotonically to 3.76e8 at the 21 mm bore. :func:`foundation_coefficients`
reports a geometry outside the fit (``in_fit_range``) and
:func:`body_term_warnings` says what was done, in one line.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

# rows L*, M*, P*, Q*; columns A, B, C, D, E, F (Sainsot et al. 2004, Table 1)
SAINSOT_TABLE = np.array(
    [
        [-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045],
        [60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086],
        [-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236],
        [-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904],
    ]
)
H_F_RANGE = (1.4, 7.0)
THETA_F_RANGE = (0.01, 0.12)


@dataclass(frozen=True)
class FoundationCoefficients:
    """Sainsot coefficients L*, M*, P*, Q* for one gear body (dimensionless).

    ``h_f`` is the value used, within the fit (module docstring); ``in_fit_range`` is
    False when the gear's own (r_f / r_int, theta_f) lies outside the fitted domain (a
    solid disc counts as inside: it is the fit's upper end by definition).
    """

    L: float
    M: float
    P: float
    Q: float
    h_f: float
    theta_f: float
    in_fit_range: bool


def sainsot_polynomials(h_f: ArrayLike, theta_f: ArrayLike) -> np.ndarray:
    """Evaluate L*, M*, P*, Q*; returns shape (4, ...) for broadcast inputs."""
    h = np.asarray(h_f, dtype=float)
    t = np.asarray(theta_f, dtype=float)
    basis = np.stack(np.broadcast_arrays(1 / t**2, h**2, h / t, 1 / t, h, np.ones_like(h * t)))
    return np.tensordot(SAINSOT_TABLE, basis, axes=(1, 0))


def foundation_coefficients(root_radius: float, body_radius: float, theta_f: float
                            ) -> FoundationCoefficients:
    """Coefficients for an external gear with root radius ``r_f`` and bore radius ``r_int`` (m).

    Sainsot's fit is for external gear bodies; ring gears have their own body term
    (:mod:`pipeline.stiffness.ring_body`).
    """
    lo, hi = H_F_RANGE
    if body_radius <= 0:
        ratio = hi  # solid disc: held at the fit's upper end (module docstring)
    else:
        ratio = max(root_radius, body_radius) / min(root_radius, body_radius)
    h_f = min(max(ratio, lo), hi)
    L, M, P, Q = sainsot_polynomials(h_f, theta_f)
    ok = lo <= ratio <= hi and THETA_F_RANGE[0] <= theta_f <= THETA_F_RANGE[1]
    return FoundationCoefficients(float(L), float(M), float(P), float(Q), h_f, theta_f, ok)


def body_term_warnings(name: str, root_radius: float, bore_radius: float,
                       theta_f: float) -> list[str]:
    """One line per way an external gear's body lies outside Sainsot's fit (none for a
    solid disc or a bore within it). Lengths in m, ``theta_f`` in rad."""
    lo, hi = H_F_RANGE
    out = []
    if bore_radius > 0:
        ratio = root_radius / bore_radius
        if ratio > hi:
            out.append(f"{name}: bore radius {bore_radius * 1e3:.4g} mm is below r_f / 7 = "
                       f"{root_radius / hi * 1e3:.4g} mm, the smallest bore of Sainsot's body "
                       f"term; its body is treated as a solid gear's (h_f = 7)")
        elif ratio < lo:
            out.append(f"{name}: rim from bore {bore_radius * 1e3:.4g} mm to root "
                       f"{root_radius * 1e3:.4g} mm is thinner than Sainsot's fit (h_f = "
                       f"{ratio:.3g} < 1.4); body term held at h_f = 1.4 (rim bending not "
                       f"included: the body is more compliant than computed)")
    if not THETA_F_RANGE[0] <= theta_f <= THETA_F_RANGE[1]:
        out.append(f"{name}: root half angle theta_f = {theta_f:.4g} rad is outside Sainsot's "
                   f"fit [{THETA_F_RANGE[0]}, {THETA_F_RANGE[1]}] rad; body term extrapolated")
    return out


def foundation_compliance(
    coef: FoundationCoefficients,
    u_f: ArrayLike,
    s_f: float,
    load_angle: ArrayLike,
    youngs_modulus: float,
) -> np.ndarray:
    """Body compliance per unit face width, m/N * m (divide by the face width in m).

    Parameters
    ----------
    u_f : distance from the root circle to the load line's crossing of the centreline, m.
    s_f : tooth thickness at the root circle, m.
    load_angle : alpha_m, angle between the load and the normal to the centreline, rad.
    youngs_modulus : E in Pa.
    """
    ratio = np.asarray(u_f, dtype=float) / s_f
    a = np.asarray(load_angle, dtype=float)
    bracket = coef.L * ratio**2 + coef.M * ratio + coef.P * (1.0 + coef.Q * np.tan(a) ** 2)
    return np.cos(a) ** 2 / youngs_modulus * bracket
