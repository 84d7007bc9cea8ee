"""One gear: the frozen, validated input and the radii and angles derived from it.

Conventions (ISO 21771):

* ``module`` is the *normal* module m_n, ``pressure_angle`` the normal
  pressure angle alpha_n, ``helix_angle`` beta >= 0 with ``hand`` giving its sense.
* Profile shift ``x`` follows ISO 21771 for internal gears too (the formulas with
  negative tooth count): tooth thickness on the reference circle is
  ``s = m_t (pi/2 + 2 x tan alpha_t)`` for both kinds, and for an internal gear
  the tip radius is ``r - m_n (h_a* + x)`` and the root radius ``r + m_n (h_f* - x)``.
* For a herringbone gear ``face_width`` is the toothed width of *both* helical
  halves together; ``groove_width`` is the relief groove between them, so each
  half is ``face_width / 2`` wide and the body is ``face_width + groove_width``.

Everything is SI: m, rad, Pa, kg/m^3.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

from pipeline.validation import (
    InputError,
    check_choice,
    check_int_range,
    check_range,
)

HANDS = ("right", "left", "none")
MIN_FACE_MODULES, MAX_FACE_MODULES = 0.5, 250.0
MAX_ROUNDING_MODULES = 0.3
"""Largest tip rounding over m_n (an edge break; larger roundings are tip shortening)."""
"""Allowed face width range in normal modules."""


@dataclass(frozen=True)
class Material:
    """Linear-elastic isotropic gear material.

    Attributes
    ----------
    youngs_modulus : E in Pa.
    poisson_ratio : nu (-), in (-1, 0.5).
    density : rho in kg/m^3.
    name : label used in reports.
    """

    youngs_modulus: float = 2.06e11
    poisson_ratio: float = 0.3
    density: float = 7850.0
    name: str = "steel"

    def __post_init__(self) -> None:
        check_range("material.youngs_modulus", self.youngs_modulus, 1e6, 1e13, unit="Pa")
        check_range("material.poisson_ratio", self.poisson_ratio, -1.0, 0.5, lo_open=True,
                    hi_open=True)
        check_range("material.density", self.density, 1.0, 1e5, unit="kg/m^3")

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def plane_strain_modulus(self) -> float:
        """E' = E / (1 - nu^2) in Pa (used by Hertz line contact and plane strain)."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)


@dataclass(frozen=True)
class GearSpec:
    """A spur, helical or herringbone gear, external or internal (ring).

    Attributes
    ----------
    teeth : number of teeth z (>= 5 external, >= 10 internal).
    module : normal module m_n in m.
    pressure_angle : normal pressure angle alpha_n in rad, in (0, 35 deg].
    face_width : toothed face width b in m (both halves for a herringbone gear),
        0.5 to 250 normal modules.
    helix_angle : beta in rad, in [0, 45 deg).
    hand : "right", "left" or "none" (spur).
    profile_shift : x (-), ISO 21771 sign convention.
    addendum_coef : h_a* (-), tip height over m_n (reference profile), default 1.
    dedendum_coef : h_f* (-), root depth over m_n, default 1.25.
    cutter_tip_radius_coef : rho_a0* (-), tip radius of the rack cutter over m_n.
        Determines the trochoidal fillet (internal gears: the circular root fillet).
        Default (``None``): ISO 53 profile A's 0.38, or the largest radius that fits
        the rack tooth space when that is smaller (e.g. 0.318 at 25 deg with
        h_f* = 1.25); for an internal gear also at most the largest fillet that fits
        its own tooth space at the root (:attr:`ring_fillet_limit`, e.g. 0.287 for
        95 teeth at 25 deg).
    bore_radius : radius of the bore in m for an external gear (0 for a solid
        disc); for an internal gear the *outer* radius of the ring rim.
    internal : True for an internal (ring) gear.
    herringbone : True for two opposite-hand helical halves.
    groove_width : relief groove width between herringbone halves in m.
    tip_radius : optional tip radius in m overriding the one from h_a* and x
        (e.g. after tip shortening).
    tip_rounding : radius of the rounded edge between the flank and the tip land, m, in
        [0, 0.3 m_n] (0: a sharp corner; external gears only). The involute ends where the
        rounding touches it, at :attr:`active_tip_radius`, which ends the path of contact;
        beyond it the rounding touches the mate (:mod:`pipeline.geometry.tip_contact`).
    material : :class:`Material`.
    name : label used in reports.
    """

    teeth: int
    module: float
    pressure_angle: float
    face_width: float
    helix_angle: float = 0.0
    hand: str = "none"
    profile_shift: float = 0.0
    addendum_coef: float = 1.0
    dedendum_coef: float = 1.25
    cutter_tip_radius_coef: float | None = None
    bore_radius: float = 0.0
    internal: bool = False
    herringbone: bool = False
    groove_width: float = 0.0
    tip_radius: float | None = None
    tip_rounding: float = 0.0
    material: Material = field(default_factory=Material)
    name: str = "gear"

    def __post_init__(self) -> None:
        p = self.name
        check_int_range(f"{p}.teeth", self.teeth, 10 if self.internal else 5, 100000)
        check_range(f"{p}.module", self.module, 1e-5, 1.0, unit="m")
        check_range(f"{p}.pressure_angle", self.pressure_angle, 0.0, math.radians(35.0),
                    lo_open=True, unit="rad")
        # b / m_n from 0.5 (thinner and the FE bodies degenerate: a groove model of a
        # 0.001 mm wide gear was singular) to 250 (b / m_n is 6-40 in practice)
        check_range(f"{p}.face_width", self.face_width, MIN_FACE_MODULES * self.module,
                    MAX_FACE_MODULES * self.module, unit="m")
        check_range(f"{p}.helix_angle", self.helix_angle, 0.0, math.radians(45.0),
                    hi_open=True, unit="rad")
        check_choice(f"{p}.hand", self.hand, HANDS)
        if (self.helix_angle > 0) != (self.hand != "none"):
            raise InputError(
                f"{p}.hand = {self.hand!r} does not match {p}.helix_angle = "
                f"{self.helix_angle:.6g} rad: use 'none' exactly when the helix angle is 0"
            )
        check_range(f"{p}.profile_shift", self.profile_shift, -1.5, 1.5)
        check_range(f"{p}.addendum_coef", self.addendum_coef, 0.3, 2.0)
        check_range(f"{p}.dedendum_coef", self.dedendum_coef, self.addendum_coef, 2.5)
        if self.internal and self.root_radius <= self.base_radius:
            raise InputError(
                f"{p}: the root circle of the internal gear (radius {self.root_radius * 1e3:.6g} "
                f"mm) lies inside its base circle ({self.base_radius * 1e3:.6g} mm), where no "
                f"involute exists; lower {p}.profile_shift = {self.profile_shift:.6g} or raise "
                f"{p}.dedendum_coef = {self.dedendum_coef:.6g}"
            )
        if self.internal and self.half_tooth_angle(self.root_radius) >= math.pi / self.teeth:
            raise InputError(
                f"{p}: the tooth spaces of the internal gear close before its root circle "
                f"(root radius {self.root_radius * 1e3:.6g} mm); reduce {p}.dedendum_coef = "
                f"{self.dedendum_coef} or raise {p}.profile_shift = {self.profile_shift}"
            )
        # before the fillet limits below, which are evaluated at the tip radius
        if self.tip_radius is not None:
            lo, hi = (self.base_radius, self.reference_radius + 2 * self.module) if not \
                self.internal else (self.reference_radius - 2 * self.module, self.root_radius)
            check_range(f"{p}.tip_radius", self.tip_radius, lo, hi, unit="m")
        check_range(f"{p}.tip_rounding", self.tip_rounding, 0.0,
                    MAX_ROUNDING_MODULES * self.module, unit="m")
        if self.tip_rounding > 0.0 and self.internal:
            raise InputError(f"{p}.tip_rounding = {self.tip_rounding:.6g} m: a rounded tip of "
                             "an internal gear is not modelled; leave it 0 (a sharp corner)")
        if self.cutter_tip_radius_coef is None:
            object.__setattr__(self, "cutter_tip_radius_coef",
                               min(0.38, self.max_cutter_tip_radius_coef))
        check_range(f"{p}.cutter_tip_radius_coef", self.cutter_tip_radius_coef, 0.0,
                    self.max_cutter_tip_radius_coef)
        check_range(f"{p}.groove_width", self.groove_width, 0.0, 10.0, unit="m")
        if self.herringbone and self.helix_angle == 0:
            raise InputError(f"{p}.herringbone = true needs {p}.helix_angle > 0")
        if not self.herringbone and self.groove_width > 0:
            raise InputError(f"{p}.groove_width = {self.groove_width:.6g} m needs {p}.herringbone "
                             "= true: the relief groove separates a herringbone gear's halves")
        if self.internal:
            check_range(f"{p}.bore_radius", self.bore_radius, self.root_radius * 1.0001,
                        self.root_radius * 10, unit="m (outer rim radius of the ring)")
            if self.tip_radius_ <= self.base_radius:
                raise InputError(
                    f"{p}: internal gear tip radius {self.tip_radius_ * 1e3:.6g} mm must exceed "
                    f"the base radius {self.base_radius * 1e3:.6g} mm (more teeth or a smaller "
                    "pressure angle)"
                )
        else:
            check_range(f"{p}.bore_radius", self.bore_radius, 0.0, self.root_radius * 0.98,
                        unit="m")
        if self.tooth_thickness_tip <= 0 and not self.internal:
            raise InputError(
                f"{p}: the tooth is pointed below its tip (tip thickness "
                f"{self.tooth_thickness_tip * 1e3:.4g} mm); reduce {p}.profile_shift = "
                f"{self.profile_shift} or {p}.addendum_coef = {self.addendum_coef}"
            )

    # ---- basic derived quantities -------------------------------------------------------
    @property
    def max_cutter_tip_radius_coef(self) -> float:
        """Largest cutter tip radius (over m_n) that fits the tooth space.

        The rack tooth space (ISO 53) for every gear; for an internal gear also the ring's
        own tooth space at its root, which is narrower than the rack's (see
        :attr:`ring_fillet_limit`).
        """
        a = self.pressure_angle
        e = math.pi / 4 - self.dedendum_coef * math.tan(a)  # half space width at tip line / m
        rack = max(0.0, e * math.cos(a) / (1.0 - math.sin(a)))
        return min(rack, self.ring_fillet_limit / self.module) if self.internal else rack

    @cached_property
    def ring_fillet_limit(self) -> float:
        """Internal gears: the largest root fillet radius that fits the tooth space, m.

        The ring's fillet is the arc of radius rho tangent to the root circle (centre at
        ``r_f - rho``) and to the involute (:mod:`pipeline.geometry.profile`). Tangent to the
        involute at radius R, its centre lies on the involute's normal, the line tangent to
        the base circle, ``rho`` from the flank towards the base tangent point; so
        ``r_b^2 + (r_b tan a_R - rho)^2 = (r_f - rho)^2``, i.e.
        ``rho(R) = (r_f^2 - R^2) / (2 (r_f - r_b tan a_R))``, and the centre's polar angle
        from the tooth centre line is ``psi(R) + a_R - atan(tan a_R - rho / r_b)``. The
        fillet fits while that angle is at most ``pi / z`` (the middle of the space; at the
        limit the two fillets of a space meet on the root circle). ``inf`` for external gears.
        """
        if not self.internal:
            return math.inf
        rb, rf = self.base_radius, self.root_radius
        half_space = math.pi / self.teeth

        def rho(r: float) -> float:
            return (rf * rf - r * r) / (2.0 * (rf - math.sqrt(r * r - rb * rb)))

        def excess(r: float) -> float:
            t = math.sqrt(r * r - rb * rb) / rb
            return self.half_tooth_angle(r) + math.atan(t) - math.atan(t - rho(r) / rb) \
                - half_space

        lo, hi = max(self.tip_radius_, rb * (1.0 + 1e-12)), rf
        if excess(hi) >= 0.0:
            return 0.0  # the spaces close before the root circle (refused in __post_init__)
        if excess(lo) <= 0.0:
            return rho(lo)
        for _ in range(80):  # bisection: the centre moves into the space as R falls
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if excess(mid) > 0.0 else (lo, mid)
        return rho(hi)

    @cached_property
    def transverse_module(self) -> float:
        """m_t = m_n / cos(beta) in m."""
        return self.module / math.cos(self.helix_angle)

    @cached_property
    def transverse_pressure_angle(self) -> float:
        """alpha_t = atan(tan(alpha_n) / cos(beta)) in rad."""
        return math.atan(math.tan(self.pressure_angle) / math.cos(self.helix_angle))

    @cached_property
    def base_helix_angle(self) -> float:
        """beta_b = asin(sin(beta) cos(alpha_n)) in rad."""
        return math.asin(math.sin(self.helix_angle) * math.cos(self.pressure_angle))

    @cached_property
    def reference_radius(self) -> float:
        """r = z m_t / 2 in m."""
        return self.teeth * self.transverse_module / 2.0

    @cached_property
    def base_radius(self) -> float:
        """r_b = r cos(alpha_t) in m."""
        return self.reference_radius * math.cos(self.transverse_pressure_angle)

    @cached_property
    def tip_radius_(self) -> float:
        """Tip radius r_a in m (the override if given)."""
        if self.tip_radius is not None:
            return self.tip_radius
        h = self.module * (self.addendum_coef + self.profile_shift)
        return self.reference_radius - h if self.internal else self.reference_radius + h

    @cached_property
    def active_tip_radius(self) -> float:
        """Radius where the involute ends, m: the tip radius, or with a tip rounding rho the
        radius where the rounding touches the involute. The rounding's centre lies rho inside
        the flank, on the circle ``r_a - rho`` and on the involute's normal at the tangency
        point, so the roll length there is ``rho + sqrt((r_a - rho)^2 - r_b^2)``."""
        rho = self.tip_rounding
        if rho == 0.0:
            return self.tip_radius_
        rb = self.base_radius
        roll = rho + math.sqrt((self.tip_radius_ - rho) ** 2 - rb * rb)
        return math.hypot(rb, roll)

    @cached_property
    def root_radius(self) -> float:
        """Root radius r_f in m (generated by the rack with h_f* and x)."""
        h = self.module * (self.dedendum_coef - self.profile_shift)
        return self.reference_radius + h if self.internal else self.reference_radius - h

    @cached_property
    def transverse_base_pitch(self) -> float:
        """p_bt = 2 pi r_b / z in m."""
        return 2.0 * math.pi * self.base_radius / self.teeth

    @cached_property
    def normal_base_pitch(self) -> float:
        """p_bn = pi m_n cos(alpha_n) in m."""
        return math.pi * self.module * math.cos(self.pressure_angle)

    @cached_property
    def reference_tooth_thickness(self) -> float:
        """Transverse arc tooth thickness on the reference circle s_t in m."""
        return self.transverse_module * (
            math.pi / 2 + 2.0 * self.profile_shift * math.tan(self.pressure_angle)
        )

    def half_tooth_angle(self, r: float) -> float:
        """Half the angular tooth thickness at radius ``r`` on the involute (rad).

        For an internal gear this is half the angular width of the *tooth* (the
        metal between two spaces), which is the space of an external gear: it
        grows with the radius (the ring tooth is widest at its root).
        """
        from pipeline.geometry.involute import inv

        at = self.transverse_pressure_angle
        a = math.acos(min(1.0, self.base_radius / r))
        psi_ref = self.reference_tooth_thickness / (2.0 * self.reference_radius)
        if self.internal:
            return psi_ref + inv(a) - inv(at)
        return psi_ref + inv(at) - inv(a)

    @cached_property
    def tooth_thickness_tip(self) -> float:
        """Transverse arc tooth thickness on the tip circle in m (<= 0: pointed)."""
        r = self.tip_radius_
        return 2.0 * r * float(self.half_tooth_angle(r))

    @property
    def is_helical(self) -> bool:
        return self.helix_angle > 0.0

    @property
    def half_width(self) -> float:
        """Face width of one helical half (herringbone) or the whole face width, m."""
        return self.face_width / 2.0 if self.herringbone else self.face_width

    @property
    def equivalent_teeth(self) -> float:
        """Virtual (equivalent spur) tooth count z_n = z / (cos^2 beta_b cos beta) (ISO 6336)."""
        return self.teeth / (math.cos(self.base_helix_angle) ** 2 * math.cos(self.helix_angle))
