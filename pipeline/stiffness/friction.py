"""Tooth-flank friction: the one place where its sign convention is written.

Sign convention (assembly-error paper, Yang et al. 2026, Jin et al. 2018)
-------------------------------------------------------------------------
``lam = +1`` in the *approach* (contact before the pitch point in time), ``-1``
in the *recess*, ``0`` exactly at the pitch point, where sliding vanishes and
there is no friction. With the pinion driving, approach is ``s < s_pitch``.

* Tooth loading (Yang et al. 2026, eqs. 19-20): in the approach the friction force on
  either flank points towards that tooth's root (away from the pitch point on the
  driver, towards it on the driven gear), so with ``F_f = mu F``

      F_b = F (cos a - lam mu sin a)      (bending, normal to the centreline)
      F_a = F (sin a + lam mu cos a)      (compression, along the centreline)

  where ``a`` is the load angle. Friction therefore *stiffens* the teeth in the
  approach and softens them in the recess (Yang et al. 2026, figs. 6-7). The assembly-error
  paper prints the opposite pairing of signs; its text and Yang et al. (2026) agree on the physics
  used here.
* Internal pairs keep the convention. Both gears turn the same way and the base tangent
  points T1, T2 lie on the same side of the contact (``rho2 = -(s + T1T2)``), so the
  surface speeds along the common tangent are ``u1 = w1 s`` and ``u2 = w2 (s + T1T2)`` in
  the same direction and ``u1 - u2 = (w1 - w2)(s - s_pitch)``, negative in the approach as
  in an external pair. Friction on the pinion then points towards its root, and its
  reaction on the ring towards the ring's root (the ring's radius grows along it, its
  centre lying on the pinion's side): the ring tooth, loaded at angle ``alpha + psi``
  (:func:`pipeline.stiffness.tooth.load_geometry`), is compressed more and bent less in
  the approach, with the same ``lam``. Checked from rigid-body kinematics in
  tests/test_internal_gears.py.
* Friction stiffness and torque coefficients (Jin et al. 2018, eqs. 15-17):
  ``K_f = lam mu k`` is positive when the friction force on the pinion points in
  the approach direction of sliding, and ``KT_f,i = lam mu k rho_i`` is positive
  when the friction torque on gear i acts with the driving torque (driver) or with
  the load torque (driven gear), as Jin et al. (2018) describe for the approach.

Friction coefficient
--------------------
Either a constant, or the EHL regression of Xu, Kahraman et al. (2007) used in
Jin et al. (2018), eq. 9 (Table 1 coefficients):

    mu = exp(f) P_h^b2 |SR|^b3 V_e^b6 nu_0^b7 R^b8
    f  = b1 + b4 |SR| P_h log10(nu_0) + b5 exp(-|SR| P_h log10(nu_0)) + b9 exp(S)

with P_h the maximum Hertz pressure in GPa, SR = 2 (u1 - u2)/(u1 + u2) the
slide-to-roll ratio, V_e = u1 + u2 the entraining velocity in m/s, nu_0 the
dynamic viscosity at inlet temperature in mPa s (cP), R the effective radius of
curvature in m and S the RMS roughness in um. These are the regression's own
units; :func:`ehl_friction_coefficient` takes SI and converts.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from pipeline.validation import InputError, check_range

EHL_B = np.array([-8.916465, 1.03303, 1.036077, -0.354068, 2.812084, -0.100601, 0.752755,
                  -0.390958, 0.620305])


def friction_direction(s: ArrayLike, s_pitch: float, driver: str = "pinion") -> np.ndarray:
    """``lam``: +1 in approach, -1 in recess, 0 at the pitch point (any shape of ``s``, m)."""
    d = np.sign(np.asarray(s, dtype=float) - s_pitch)
    return -d if driver == "pinion" else d


def load_components(load_angle: ArrayLike, mu: ArrayLike, lam: ArrayLike
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Bending and compressive parts (F_b/F, F_a/F) of a unit normal load with friction."""
    a = np.asarray(load_angle, dtype=float)
    m = np.asarray(mu, dtype=float) * np.asarray(lam, dtype=float)
    return np.cos(a) - m * np.sin(a), np.sin(a) + m * np.cos(a)


def ehl_friction_coefficient(
    slide_roll_ratio: ArrayLike,
    hertz_pressure: ArrayLike,
    entraining_velocity: ArrayLike,
    viscosity: float,
    effective_radius: ArrayLike,
    roughness: float,
) -> np.ndarray:
    """EHL friction coefficient of Xu et al. (2007), Jin et al. (2018), eq. 9.

    Parameters
    ----------
    slide_roll_ratio : SR = 2 (u1 - u2) / (u1 + u2) (-), any shape.
    hertz_pressure : maximum Hertz pressure P_h, Pa.
    entraining_velocity : V_e = u1 + u2, m/s (> 0).
    viscosity : dynamic viscosity of the oil at inlet temperature, Pa s.
    effective_radius : R = rho1 rho2 / (rho1 + rho2), m.
    roughness : composite RMS roughness S, m.

    Returns
    -------
    mu : friction coefficient (-), zero where SR = 0 (pure rolling at the pitch point).
    """
    check_range("viscosity", viscosity, 1e-5, 10.0, unit="Pa s")
    check_range("roughness", roughness, 0.0, 1e-4, unit="m")
    b = EHL_B
    sr = np.abs(np.asarray(slide_roll_ratio, dtype=float))
    ph = np.asarray(hertz_pressure, dtype=float) * 1e-9
    ve = np.asarray(entraining_velocity, dtype=float)
    r = np.asarray(effective_radius, dtype=float)
    if np.any(ve <= 0) or np.any(r <= 0) or np.any(ph < 0):
        raise InputError("EHL friction needs entraining velocity > 0, radius > 0, pressure >= 0")
    nu0 = viscosity * 1e3  # mPa s
    s_um = roughness * 1e6
    x = sr * ph * np.log10(nu0)
    f = b[0] + b[3] * x + b[4] * np.exp(-x) + b[8] * np.exp(s_um)
    return np.exp(f) * ph ** b[1] * sr ** b[2] * ve ** b[5] * nu0 ** b[6] * r ** b[7]


def hertz_line_pressure(load_per_length: ArrayLike, effective_radius: ArrayLike,
                        plane_strain_modulus: float) -> np.ndarray:
    """Maximum Hertz pressure of a line contact, Pa.

    ``p0 = sqrt(w E* / (pi R))`` with ``w`` the load per unit length (N/m), ``R``
    the effective radius (m) and ``E* = E / (2 (1 - nu^2))`` for two equal
    materials, i.e. half the plane-strain modulus ``E / (1 - nu^2)`` passed here
    (Johnson, Contact Mechanics, eq. 4.45).
    """
    e_star = 0.5 * plane_strain_modulus
    w = np.asarray(load_per_length, dtype=float)
    return np.sqrt(np.maximum(w, 0.0) * e_star / (np.pi * np.asarray(effective_radius)))
