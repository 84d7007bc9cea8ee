"""Tooth cross-sections along the centreline, pre-integrated for the potential-energy method.

The tooth is a cantilever along its centreline, clamped at ``eta = 0`` (the root
circle for the exact profile; the base circle for the classical model) with
half-thickness ``h(eta)`` at distance ``eta`` (m) along the centreline towards
the tip. For a unit face width the section has area ``A = 2 h`` and second
moment ``I = (2 h)^3 / 12``.

The bending energy of a load at ``eta_c`` needs ``int_0^eta_c (eta_c - eta)^k / I``
for k = 0, 1, 2. Expanding the binomial, these are combinations of the
cumulative integrals ``J_k(eta) = int_0^eta eta'^k / I d eta'`` which are
tabulated once per gear; any number of load positions then costs one
interpolation each (fully vectorised). ``A0(eta) = int_0^eta 1/A`` serves the
shear and axial-compression terms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.profile import ToothProfile


@dataclass(frozen=True)
class ToothSections:
    """Tabulated tooth sections for a unit face width.

    Attributes
    ----------
    eta : shape (n,), distance along the centreline from the clamped section, m.
    half_thickness : shape (n,), h(eta) in m.
    J0, J1, J2 : shape (n,), cumulative ``int eta^k / I`` in m^-3, m^-2, m^-1 (unit width).
    A0 : shape (n,), cumulative ``int 1 / A`` (unit width), dimensionless.
    clamp_radius : radius of the clamped section, m (root or base circle).
    internal : True for an internal gear (the centreline points inwards).
    """

    eta: np.ndarray
    half_thickness: np.ndarray
    J0: np.ndarray
    J1: np.ndarray
    J2: np.ndarray
    A0: np.ndarray
    clamp_radius: float
    internal: bool = False

    @classmethod
    def from_half_thickness(
        cls, eta: np.ndarray, h: np.ndarray, clamp_radius: float, internal: bool = False
    ) -> ToothSections:
        """Integrate a tabulated ``h(eta)`` (cumulative trapezoid, both arrays shape (n,))."""
        eta = np.asarray(eta, dtype=float)
        h = np.asarray(h, dtype=float)
        if np.any(np.diff(eta) <= 0) or eta[0] != 0.0:
            raise ValueError("ToothSections: eta must start at 0 and increase strictly")
        if np.any(h <= 0):
            raise ValueError("ToothSections: half thickness must be positive on the tooth")
        inv_i = 12.0 / (2.0 * h) ** 3
        inv_a = 1.0 / (2.0 * h)

        def cum(f: np.ndarray) -> np.ndarray:
            return np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(eta))])

        return cls(eta, h, cum(inv_i), cum(eta * inv_i), cum(eta**2 * inv_i), cum(inv_a),
                   float(clamp_radius), internal)

    def eta_of_radius(self, y: ArrayLike) -> np.ndarray:
        """Centreline distance from the clamp for a centreline coordinate ``y`` (m from centre)."""
        y = np.asarray(y, dtype=float)
        return self.clamp_radius - y if self.internal else y - self.clamp_radius

    def beam_integrals(self, eta_c: ArrayLike) -> tuple[np.ndarray, ...]:
        """Integrals for a load at ``eta_c`` (any shape), unit face width.

        Returns
        -------
        b2 : ``int_0^eta_c (eta_c - eta)^2 / I``, m^-1
        b1 : ``int_0^eta_c (eta_c - eta) / I``, m^-2
        b0 : ``int_0^eta_c 1 / I``, m^-3
        a0 : ``int_0^eta_c 1 / A``, dimensionless
        """
        e = np.asarray(eta_c, dtype=float)
        top = self.eta[-1] * (1 + 1e-9) + 1e-12
        if np.any(e < -1e-12) or np.any(e > top):
            raise ValueError(
                f"load point outside the tooth: centreline distance {float(np.max(e)):.6g} m or "
                f"{float(np.min(e)):.6g} m is outside [0, {self.eta[-1]:.6g}] m"
            )
        j0 = np.interp(e, self.eta, self.J0)
        j1 = np.interp(e, self.eta, self.J1)
        j2 = np.interp(e, self.eta, self.J2)
        a0 = np.interp(e, self.eta, self.A0)
        return e * e * j0 - 2.0 * e * j1 + j2, e * j0 - j1, j0, a0


def _graded(n: int) -> np.ndarray:
    """n points on [0, 1], clustered towards 0 where the section changes fastest."""
    u = np.linspace(0.0, 1.0, n)
    return u**1.5


def involute_sections(gear: GearSpec, n: int = 4000) -> ToothSections:
    """Sections of the classical model: the pure involute, sections normal to the centreline.

    External gears (the textbook model behind the closed-form integrals of Yang et al.
    (2026), eqs. 11-13): the tooth is cut off at the base circle and clamped there.
    Internal gears (the ring tooth of Chen and Shao (2013) and Liang et al. (2014)): the
    involute runs from the tip circle out to the root circle, and the tooth is clamped at
    the chord through the two root-circle points of its flanks, at the centreline
    distance ``r_f cos(psi_f)`` from the gear centre (``psi_f`` the half tooth angle on
    the root circle). Used as an exact reference for the numerical integration; the
    pipeline's default uses the exact profile (:func:`exact_sections`).
    """
    r0, r1 = (gear.base_radius, gear.tip_radius_) if not gear.internal else (
        gear.root_radius, gear.tip_radius_)
    psi_0 = gear.half_tooth_angle(r0)  # half angle at the clamp (Yang et al.: alpha_2)
    r = r0 + (r1 - r0) * _graded(n)
    psi = _half_angles(gear, r)
    x = r * np.sin(psi)
    y = r * np.cos(psi)
    y0 = r0 * math.cos(psi_0)
    # y(r) is monotonic on the involute for tooth shapes of interest (checked by ToothSections)
    eta = np.abs(y - y0)
    order = np.argsort(eta)
    return ToothSections.from_half_thickness(eta[order], x[order], clamp_radius=y0,
                                             internal=gear.internal)


def exact_sections(profile: ToothProfile, theta_f: float, n: int = 3000) -> ToothSections:
    """Sections of the exact tooth profile (involute + fillet), clamped at the root.

    External gears: the clamp is the section at the root radius ``r_f`` on the centreline
    and the sections run up to the tip corner.

    Internal gears: the tooth hangs from the rim (the root circle is its *largest*
    radius) and points inwards. It is clamped at the chord through the two points where
    its fillets leave the root circle, at ``y_0 = r_f cos(theta_f)`` from the gear centre;
    the sections run inwards to the tip corner, and their half thickness is read on the
    part of the flank that falls monotonically from the top of the fillet to the tip
    (above that top a horizontal cut lies in the rim, not in the tooth). Between the
    tip corners and the tip circle on the centreline (``r_a`` vs ``r_a cos(psi_a)``,
    0.16 % of the tooth height for 60 teeth) the two tip horns are counted as one section
    of the flank's width, as the external model counts the tip cap.

    Parameters
    ----------
    profile : the exact profile (:func:`pipeline.geometry.profile.tooth_profile`).
    theta_f : half angle of the tooth where its fillet leaves the root circle, rad.
    n : tabulated sections, graded towards the clamp.
    """
    gear = profile.gear
    rf = gear.root_radius
    u = _graded(n)
    if not gear.internal:
        y = rf + (float(np.max(profile.y)) - rf) * u
        h = np.asarray(profile.half_thickness(y), dtype=float)
        keep = h > 0
        return ToothSections.from_half_thickness(y[keep] - rf, h[keep], clamp_radius=rf)
    y0 = rf * math.cos(theta_f)
    y = y0 - (y0 - float(profile.y[-1])) * u
    y[-1] = profile.y[-1]  # the tip corner exactly (round-off would put it off the flank)
    h = np.asarray(profile.half_thickness(y), dtype=float)
    return ToothSections.from_half_thickness(y0 - y, h, clamp_radius=y0, internal=True)


def _half_angles(gear: GearSpec, r: np.ndarray) -> np.ndarray:
    """Vectorised half tooth angle on the involute at radii ``r`` (rad)."""
    from pipeline.geometry.involute import inv

    at = gear.transverse_pressure_angle
    a = np.arccos(np.clip(gear.base_radius / r, -1.0, 1.0))
    psi_ref = gear.reference_tooth_thickness / (2.0 * gear.reference_radius)
    if gear.internal:  # the ring tooth widens towards its root (GearSpec.half_tooth_angle)
        return psi_ref + inv(a) - inv(at)
    return psi_ref + inv(at) - inv(a)
