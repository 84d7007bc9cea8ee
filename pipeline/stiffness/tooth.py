"""Single-tooth compliance by the potential-energy method, on the actual tooth profile.

A normal load F at the flank point of radius R is split into a bending part
F_b and a compressive part F_a along the tooth centreline (with friction, see
:mod:`pipeline.stiffness.friction`). With the tooth a cantilever clamped at the
root circle (sections from :mod:`pipeline.stiffness.sections`):

    1/k_b = int [F_b (eta_c - eta) - F_a h_c]^2 / (E I) d eta / F^2
    1/k_s = int 1.2 F_b^2 / (G A) d eta / F^2
    1/k_a = int F_a^2 / (E A) d eta / F^2

(the assembly-error paper; Yang et al. 2026, eqs. 1-3 and 21-23), where ``eta_c`` is the load
point's centreline distance from the clamp and ``h_c`` its half thickness. The body
(fillet-foundation) term is Sainsot's (:mod:`pipeline.stiffness.foundation`) for
external gears and its refit for ring rims (:mod:`pipeline.stiffness.ring_body`) for
internal gears, applied to the resultant of normal load and friction. All compliances
here are *per unit face width* (m^2/N): divide by the face width (m) for m/N.

Internal (ring) teeth are the same cantilever turned round: the root circle is the
tooth's *largest* radius, the clamp is the chord through the points where its fillets
leave the root circle, and ``eta`` runs inwards to the tip
(:func:`pipeline.stiffness.sections.exact_sections`). The load geometry is derived in
:func:`load_geometry`; with it the integrals above hold unchanged.

The sections come from the exact profile (involute plus the trochoidal fillet cut by the
rack), so a root circle below or above the base circle is handled as it is; they are
pre-integrated once per gear, so any number of load positions costs one interpolation each.
A normal load at radius R on a ring tooth has the load angle alpha_R + psi (the ring tooth
widens towards its root) and still compresses the tooth. The Hertz term of the mesh
stiffness is the constant line-contact value of the assembly-error paper and Yang et al.
(2026). Checks: the classical model (involute clamped at the base circle), kept as a
reference, reproduces the closed-form integrals of Yang et al. (2026) to 2e-5; the
pure-involute ring tooth (Chen and Shao 2013, Liang et al. 2014) matches an independent
quadrature to 2e-5, the exact profile to 1e-4.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.gear import GearSpec
from pipeline.stiffness.foundation import (
    FoundationCoefficients,
    body_term_warnings,
    foundation_coefficients,
    foundation_compliance,
)
from pipeline.stiffness.friction import load_components
from pipeline.stiffness.ring_body import ring_coefficients
from pipeline.stiffness.sections import ToothSections, _half_angles, exact_sections
from pipeline.validation import PhysicsWarning


@dataclass(frozen=True)
class ToothModel:
    """Everything the potential-energy method needs about one gear's tooth.

    Attributes
    ----------
    gear : the gear.
    sections : tabulated sections from the clamp (root circle) to the tip.
    foundation : Sainsot coefficients of the gear body.
    root_thickness : S_f, tooth thickness at the root circle, m.
    """

    gear: GearSpec
    sections: ToothSections
    foundation: FoundationCoefficients
    root_thickness: float


@dataclass(frozen=True)
class ToothCompliance:
    """Compliance components per unit face width, m^2/N, each of the shape of the input radii."""

    bending: np.ndarray
    shear: np.ndarray
    axial: np.ndarray
    foundation: np.ndarray

    @property
    def tooth(self) -> np.ndarray:
        """Bending + shear + axial compression."""
        return self.bending + self.shear + self.axial


def tooth_model(gear: GearSpec, n_sections: int = 3000) -> ToothModel:
    """Tooth model on the exact profile (involute + fillet), clamped at the root.

    External and internal teeth alike (:func:`pipeline.stiffness.sections.exact_sections`);
    the body term is :func:`body_coefficients`.
    """
    from pipeline.geometry.profile import tooth_profile

    prof = tooth_profile(gear)
    rf = gear.root_radius
    theta_f = _root_half_angle(prof.x, prof.y, rf, gear)
    sections = exact_sections(prof, theta_f, n_sections)
    coef = body_coefficients(gear, theta_f)
    return ToothModel(gear, sections, coef, 2.0 * rf * theta_f)


def body_coefficients(gear: GearSpec, theta_f: float) -> FoundationCoefficients:
    """Body-term coefficients: Sainsot's for external gears, the ring fit for internal ones;
    a body outside Sainsot's fit is reported once as a :class:`PhysicsWarning`."""
    if gear.internal:
        return ring_coefficients(gear, theta_f)
    for text in body_term_warnings(gear.name, gear.root_radius, gear.bore_radius, theta_f):
        warnings.warn(text, PhysicsWarning, stacklevel=1)  # once per gear and process
    return foundation_coefficients(gear.root_radius, gear.bore_radius, theta_f)


def _root_half_angle(x: np.ndarray, y: np.ndarray, rf: float, gear: GearSpec) -> float:
    """theta_f: half angle of the tooth where its fillet leaves the root circle (rad)."""
    r = np.hypot(x, y)
    # A ring's root arc is exact to round-off, while the start of its circular fillet stays
    # within 1e-6 r_f of the root circle over several points (a small fillet on a large ring)
    on_root = np.abs(r - rf) <= (1e-12 if gear.internal else 1e-6) * rf
    ang = np.arctan2(np.abs(x), np.abs(y))
    if np.any(on_root):
        # the fillet end on the root circle closest to the tooth
        return float(np.min(ang[on_root]))
    return float(math.pi / gear.teeth)


def classical_tooth_model(gear: GearSpec, n_sections: int = 4000) -> ToothModel:
    """The textbook model: pure involute, no fillet.

    External teeth are clamped at the base circle (Yang et al. 2026, eqs. 11-13), internal
    teeth at the chord between their flanks' root-circle points (Chen and Shao 2013); see
    :func:`pipeline.stiffness.sections.involute_sections`. Kept as an exact reference for
    the numerical integration; the body term uses ``theta_f`` = half tooth angle at the
    clamp circle (base circle, or root circle of a ring).
    """
    from pipeline.stiffness.sections import involute_sections

    sections = involute_sections(gear, n_sections)
    clamp = gear.root_radius if gear.internal else gear.base_radius
    theta_f = float(gear.half_tooth_angle(clamp))
    coef = body_coefficients(gear, theta_f)
    return ToothModel(gear, sections, coef, 2.0 * gear.root_radius * theta_f)


def load_geometry(gear: GearSpec, contact_radius: ArrayLike) -> tuple[np.ndarray, ...]:
    """Load point geometry on the involute at radius ``R`` (m), any shape.

    Tooth frame: centre line along +y, the loaded (right) flank at x > 0, the flank point
    at polar angle ``psi`` (half tooth angle) from +y, ``e_r = (sin psi, cos psi)``,
    ``e_t = (cos psi, -sin psi)``. The involute's normal at radius R is tangent to the base
    circle, at the profile angle ``alpha = acos(r_b / R)`` to ``e_t``. External tooth
    (narrowing outwards): outward flank normal ``cos(alpha) e_t + sin(alpha) e_r``, so the
    normal load ``-F n`` has ``F cos(alpha - psi)`` along -x (bending) and
    ``F sin(alpha - psi)`` along -y, towards the root (compression). Internal tooth
    (widening outwards, root at the larger radius): outward normal
    ``cos(alpha) e_t - sin(alpha) e_r``, so ``F cos(alpha + psi)`` along -x and
    ``F sin(alpha + psi)`` along +y, again towards the root. Either way the load angle
    ``a`` (to the normal of the centre line) enters :func:`load_components` and the
    section moment is ``F_b (eta_c - eta) - F_a h_c`` with ``eta`` measured from the
    clamp towards the tip.

    Returns
    -------
    load_angle : angle between the normal load and the normal to the centreline, rad.
    h_c : half tooth thickness at the load point, m.
    y_c : centreline coordinate of the load point (from the gear centre), m.
    """
    r = np.asarray(contact_radius, dtype=float)
    psi = _half_angles(gear, r)
    alpha = np.arccos(np.clip(gear.base_radius / r, -1.0, 1.0))
    load_angle = alpha + psi if gear.internal else alpha - psi
    return load_angle, r * np.sin(psi), r * np.cos(psi)


def tooth_compliance(model: ToothModel, contact_radius: ArrayLike, mu: ArrayLike = 0.0,
                     lam: ArrayLike = 0.0) -> ToothCompliance:
    """Compliance components of one tooth loaded at radius ``R`` (m), per unit face width.

    Parameters
    ----------
    model : from :func:`tooth_model`.
    contact_radius : radius of the contact point on this gear, m, any shape.
    mu : friction coefficient (-), broadcastable.
    lam : friction direction (+1 approach, -1 recess, 0 none), broadcastable.
    """
    g = model.gear
    mat = g.material
    load_angle, h_c, y_c = load_geometry(g, contact_radius)
    fb, fa = load_components(load_angle, mu, lam)
    b2, b1, b0, a0 = model.sections.beam_integrals(model.sections.eta_of_radius(y_c))
    bending = (fb * fb * b2 - 2.0 * fb * fa * h_c * b1 + fa * fa * h_c * h_c * b0)
    bending = bending / mat.youngs_modulus
    shear = 1.2 * fb * fb * a0 / mat.shear_modulus
    axial = fa * fa * a0 / mat.youngs_modulus
    # Body: the resultant of normal load and friction, at its own angle and line.
    a_eff = np.arctan2(fa, fb)
    if g.internal:  # signed, from the clamped root chord towards the tip (ring_body)
        u_f = model.sections.clamp_radius - (y_c + h_c * np.tan(a_eff))
    else:
        u_f = np.abs(y_c - h_c * np.tan(a_eff) - g.root_radius)
    found = (fa * fa + fb * fb) * foundation_compliance(
        model.foundation, u_f, model.root_thickness, a_eff, mat.youngs_modulus
    )
    return ToothCompliance(bending, shear, axial, found)


def hertz_compliance(pinion: GearSpec, gear: GearSpec) -> float:
    """Constant Hertz compliance of a line contact per unit face width, m^2/N.

    ``1/k_h = 4 (1 - nu^2) / (pi E L)`` for equal materials (the assembly-error paper, Yang et al.
    2026 eq. 7), generalised to ``2/(pi L) [(1-nu1^2)/E1 + (1-nu2^2)/E2]``.
    """
    m1, m2 = pinion.material, gear.material
    return 2.0 / math.pi * (1.0 / m1.plane_strain_modulus + 1.0 / m2.plane_strain_modulus)
