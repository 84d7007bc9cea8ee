"""Nominal tooth root stress of ISO 6336-3 (method B): external gears cut by a rack,
internal gears cut by a pinion-type cutter.

Both kinds share the virtual spur gear, the load point, the bending arm and the two factors
(ISO 6336-3:2019, 6.2; tooth counts, diameters and ``z_n`` of an internal gear carry ISO's
negative sign); they differ in the critical section (:class:`RootSection`), the chord
``s_Fn`` between the points where the fillet's tangent makes 30 deg (external) or 60 deg
(internal) with the tooth centre line, the fillet radius ``rho_F`` there, and the diameter
``d_sFn`` through those points.

Shared (no protuberance, ``s_pr = 0``):

* virtual spur gear: ``z_n = z / (cos^2 beta_b cos beta)``, ``d_n = m_n z_n``,
  ``d_bn = d_n cos(alpha_n)``, ``d_an = d_n + d_a - d``;
* the load acts at the outer point of single pair contact of the virtual gear,
  ``d_en = 2 sgn(z) sqrt((sqrt(d_an^2 - d_bn^2)/2 - sgn(z) p_bn (eps_alpha_n - 1))^2 +
  d_bn^2/4)`` with ``eps_alpha_n = eps_alpha / cos^2(beta_b)`` and ``p_bn = pi m_n
  cos(alpha_n)``; for a high-contact-ratio pair (``eps_alpha_n >= 2``) the same formula, as
  ISO keeps it, gives the outer point of double pair contact (the inner point of triple pair
  contact, one ``p_bn (eps_alpha_n - 1) >= p_bn`` from the tip), still with the whole
  ``F_t`` on one tooth: the tooth there shares the load with one other pair, so sigma_F0
  stays above a loaded tooth contact's stress (:attr:`IsoRootStress.high_contact_ratio`);
  ``alpha_en = acos(d_bn / d_en)``, ``gamma_e = (pi/2 + 2 x tan(alpha_n)) / z_n +
  inv(alpha_n) - inv(alpha_en)``, ``alpha_Fen = alpha_en - gamma_e`` (the load angle);
* bending arm: the distance along the tooth centre line from the chord to the point where
  the load line crosses it, ``h_Fe = y_e - y_F`` with ``y_e = (cos(gamma_e) - sin(gamma_e)
  tan(alpha_Fen)) d_en / 2`` and ``y_F = sgn(z) sqrt(d_sFn^2 - s_Fn^2) / 2``
  (:attr:`RootSection.height`; for an internal gear both are negative and the chord lies
  further from the axis than the load);
* ``Y_F = 6 (h_Fe / m_n) cos(alpha_Fen) / ((s_Fn / m_n)^2 cos(alpha_n))``,
  ``Y_S = (1.2 + 0.13 L) q_s^(1 / (1.21 + 2.3 / L))`` with ``L = s_Fn / h_Fe``,
  ``q_s = s_Fn / (2 rho_F)`` (ISO: valid for 1 <= q_s < 8);
* helix factor ``Y_beta = 1 - eps_beta beta / 120 deg`` (``eps_beta`` at most 1, ``beta`` at
  most 30 deg); rim factor ``Y_B = 1`` (solid rim) and deep tooth factor ``Y_DT = 1``
  are taken as 1 and the result says so (ISO 6336-3:2019 clause 10: ``Y_DT = 1`` for
  ``eps_alpha_n <= 2.05`` or an ISO tolerance class above 4, below 1 only for a finer class,
  which the gearbox file does not give);
* nominal root stress ``sigma_F0 = F_t / (b m_n) Y_F Y_S Y_beta Y_B Y_DT``, ``F_t`` the
  nominal tangential load at the reference circle.

External gear, rack cutter (:func:`rack_root_section`, ISO 6336-3:2019, 6.2, the 30 deg
tangent): ``E = pi/4 m_n - h_fP tan(alpha_n) - (1 - sin(alpha_n)) rho_fP / cos(alpha_n)``,
``G = rho_fP / m_n - h_fP / m_n + x``, ``H = 2 / z_n (pi/2 - E / m_n) - pi/3``, ``theta =
2 G / z_n tan(theta) - H`` (fixed point from ``pi/6``); ``s_Fn / m_n = z_n sin(pi/3 - theta)
+ sqrt(3) (G / cos(theta) - rho_fP / m_n)``, ``rho_F / m_n = rho_fP / m_n + 2 G^2 /
(cos(theta) (z_n cos^2(theta) - 2 G))``, ``y_F / m_n = (z_n cos(pi/3 - theta) + G /
cos(theta) - rho_fP / m_n) / 2``. The same geometry is checked against the exact generated
profile of :mod:`pipeline.geometry.profile` in ``tests/test_root_stress.py``.

Internal gear, pinion-type cutter (:func:`shaper_root_section`, the 60 deg tangent of ISO
6336-3 on the fillet the cutter generates; exact generation in the virtual spur gear's
plane, the cutter's virtual tooth count ``z_0n = z_0 / (cos^2 beta_b cos beta)``):

* cutting mesh at zero backlash (ISO 21771 with signed counts): ``inv(alpha_w0) =
  inv(alpha_n) + 2 tan(alpha_n) (x_0 + x) / (z_0n + z_n)``, ``a_0 = m_n (|z_n| - z_0n)/2
  cos(alpha_n) / cos(alpha_w0)``, cutting pitch radii ``r_w0 = a_0 z_0n / (|z_n| - z_0n)``
  (cutter) and ``r_w = r_w0 + a_0`` (ring);
* the cutter's tip circle reaches the ring's root circle, ``r_a0 = r_fn - a_0`` with the
  virtual ring's ``r_fn = |d_n + d_f - d| / 2`` (as KISSsoft sizes the cutter), unless its
  addendum is given (``r_a0 = m_n (z_0n/2 + h_a0* + x_0)``); the centre M of its tip
  rounding lies ``rho_a0`` inside the tip circle and ``rho_a0`` inside its involute flank,
  at roll length ``sqrt((r_a0 - rho_a0)^2 - r_b0^2) + rho_a0`` of the flank point it
  touches;
* the cutter rolls its pitch circle inside the ring's: with its centre at angle ``psi``
  about the ring's axis it has turned ``psi (|z_n| / z_0n - 1)`` about its own; the normal
  of the generated surface passes through the pitch point C (Willis), so the rounding cuts
  the point ``E = M + rho_a0 (M - C) / |M - C|`` while that normal lies between the tip
  circle's and the flank's on the rounding (the flank's end gives the root form diameter
  ``d_Ff``);
* the 60 deg tangent point is where that normal makes 30 deg with the ring tooth's centre
  line (nearest the root when the fillet has several); ``s_Fn`` is twice its distance from
  the centre line, ``d_sFn = -2 |E|``; the fillet is the offset by ``rho_a0`` of M's path
  and shares its centre of curvature ``M + n_M / kappa`` (``kappa = M' x M'' / |M'|^3``,
  ``n_M`` the path's left normal, the derivatives in ``psi`` in closed form), so
  ``rho_F = |rho_a0 (n . n_M) - 1 / kappa|``.

Checked against a simulated cutter sweeping out the ring and against the rack tooth a huge
ring and cutter tend to; the cutter's ``d_Ff`` is KISSsoft's (1987.879 and 2662.682 mm
for the NREL 5 MW rings). This exact generation is not ISO 6336-3:2006's approximation for
internal gears (its Eq. (11) virtual fillet radius, (16) and (19), whose text is not at
hand): KISSsoft 03/2017 ("roF and sFn according to ISO 6336-3:2007-04-01") prints s_Fn
56.76 mm, rho_F 8.78 mm (z -93, z_0 30) and 129.40 mm, 22.24 mm (z -56, z_0 36) where the
exact generation gives 57.53, 7.78 and 132.15, 13.57 mm (sigma_F0 3.6 % and 18 % above
KISSsoft's); its load point, bending arm and factors from its printed section are
reproduced (``tests/test_iso_root_stress_internal.py``). A helical ring is generated in
its virtual spur gear's plane by the cutter's virtual spur gear, by analogy with ISO's
virtual gear (not checked against a reference).

``load_diameter`` moves the load, e.g. to the tip (``d_en = d_an``, ISO's tip-load factors
``Y_Fa``, ``Y_Sa``); ``section`` imposes a critical section (e.g. a printed one).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.involute import inv, inv_inverse
from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError, check_int_range, check_range

EXTERNAL_TANGENT = math.radians(30.0)
"""Angle between the critical section's fillet tangent and the tooth centre line, external."""
INTERNAL_TANGENT = math.radians(60.0)
"""The same for an internal gear (ISO 6336-3)."""
MIN_TEETH_DIFFERENCE = 10
"""Smallest ``|z| - z_0`` of a ring and its pinion-type cutter accepted."""


@dataclass(frozen=True)
class ShaperCutter:
    """Pinion-type cutter that generates an internal gear.

    Attributes
    ----------
    teeth : z_0 (whole number, 8 to ``|z| - 10`` of the ring it cuts).
    profile_shift : x_0 (-), in [-1, 1]; default 0.
    tip_radius_coef : rho_a0* = rho_a0 / m_n (-), its tip rounding; ``None`` (default): the
        ring's basic rack fillet ``cutter_tip_radius_coef`` (rho_fP*).
    addendum_coef : h_a0* = h_a0 / m_n (-), its addendum (its tip radius ``m_n (z_0 / 2 +
        h_a0* + x_0)``); ``None`` (default): the addendum that cuts the ring's root circle
        (its ``root_radius``) at the cutting centre distance, as KISSsoft sizes the cutter.
    name : key prefix in error messages: its fields are named ``<name>_teeth``,
        ``<name>_profile_shift``, ... (``rating.ring.cutter`` gives the gearbox file's keys
        ``rating.ring.cutter_teeth``, ...).
    """

    teeth: int
    profile_shift: float = 0.0
    tip_radius_coef: float | None = None
    addendum_coef: float | None = None
    name: str = "cutter"

    def __post_init__(self) -> None:
        p = self.name
        check_int_range(f"{p}_teeth", self.teeth, 8, 100000)
        check_range(f"{p}_profile_shift", self.profile_shift, -1.0, 1.0)
        if self.tip_radius_coef is not None:
            check_range(f"{p}_tip_radius_coef", self.tip_radius_coef, 0.0, 0.6)
        if self.addendum_coef is not None:
            check_range(f"{p}_addendum_coef", self.addendum_coef, 0.5, 2.5)


@dataclass(frozen=True)
class RootSection:
    """Critical root section of a tooth of the virtual spur gear (SI).

    Attributes
    ----------
    chord : s_Fn, m.
    fillet_radius : rho_F at the critical points, m.
    diameter : d_sFn = 2 x the radius of the critical points, m; negative for an internal
        gear (ISO's signed diameters).
    tangent_angle : angle between the fillet's tangent there and the tooth centre line,
        rad (30 deg external, 60 deg internal).
    theta : ISO's theta of the rack construction (rad), or None (pinion-type cutter).
    form_diameter : d_Ff, where the generated fillet meets the involute, m, signed as
        ``diameter`` (pinion-type cutter), or None (rack construction).
    """

    chord: float
    fillet_radius: float
    diameter: float
    tangent_angle: float
    theta: float | None = None
    form_diameter: float | None = None

    def __post_init__(self) -> None:
        check_range("section.chord", self.chord, 0.0, math.inf, lo_open=True, unit="m")
        check_range("section.fillet_radius", self.fillet_radius, 0.0, math.inf, lo_open=True,
                    unit="m")
        if not abs(self.diameter) > self.chord:
            raise InputError(f"section.diameter = {self.diameter:.6g} m: its magnitude must "
                             f"exceed the chord section.chord = {self.chord:.6g} m")
        check_range("section.tangent_angle", self.tangent_angle, 0.0, math.pi / 2.0,
                    lo_open=True, hi_open=True, unit="rad")

    @property
    def height(self) -> float:
        """y_F: signed distance of the chord from the gear axis along the centre line, m."""
        y = math.sqrt((self.diameter / 2.0) ** 2 - (self.chord / 2.0) ** 2)
        return math.copysign(y, self.diameter)


@dataclass(frozen=True)
class IsoRootStress:
    """ISO 6336-3 method B nominal root stress of one gear (SI).

    Attributes
    ----------
    sigma_f0 : nominal tooth root stress sigma_F0, Pa.
    tangential_load : F_t at the reference circle, N; face_width : b, m.
    y_f, y_s, y_beta, y_b, y_dt : the factors (-).
    s_fn : tooth root chord at the critical section, m.
    rho_f : fillet radius at the critical section, m.
    h_fe : bending moment arm, m.
    load_diameter : d_en of the virtual spur gear where the load acts, m (negative for an
        internal gear).
    load_angle : alpha_Fen, rad.
    theta : ISO's theta of the rack construction, rad, or None (internal gear).
    virtual_teeth : z_n (-), negative for an internal gear.
    q_s : notch parameter s_Fn / (2 rho_F) (-); in_range : 1 <= q_s < 8.
    virtual_contact_ratio : eps_alpha_n = eps_alpha / cos^2(beta_b) (-).
    section : the critical section (:class:`RootSection`).
    cutter : the pinion-type cutter of an internal gear, or None.
    """

    sigma_f0: float
    tangential_load: float
    face_width: float
    y_f: float
    y_s: float
    y_beta: float
    y_b: float
    y_dt: float
    s_fn: float
    rho_f: float
    h_fe: float
    load_diameter: float
    load_angle: float
    theta: float | None
    virtual_teeth: float
    q_s: float
    in_range: bool
    virtual_contact_ratio: float
    section: RootSection
    cutter: ShaperCutter | None = None

    @property
    def high_contact_ratio(self) -> bool:
        """eps_alpha_n >= 2: ISO's load point is the outer point of double pair contact,
        carrying the whole F_t (module docstring)."""
        return self.virtual_contact_ratio >= 2.0

    def summary(self) -> dict[str, float | bool]:
        """Factors and stress (SI; keys carry units)."""
        return {"sigma_F0_Pa": self.sigma_f0, "Y_F": self.y_f, "Y_S": self.y_s,
                "Y_beta": self.y_beta, "Y_B": self.y_b, "Y_DT": self.y_dt,
                "s_Fn_m": self.s_fn, "rho_F_m": self.rho_f, "h_Fe_m": self.h_fe,
                "load_diameter_m": self.load_diameter, "q_s": self.q_s,
                "q_s_in_range": self.in_range,
                "eps_alpha_n": self.virtual_contact_ratio,
                "d_sFn_m": self.section.diameter}


def _theta(g: float, h: float, zn: float) -> float:
    """Fixed point of ``theta = 2 G / z_n tan(theta) - H`` from pi/6 (converges quickly)."""
    th = math.pi / 6.0
    for _ in range(200):
        new = 2.0 * g / zn * math.tan(th) - h
        if abs(new - th) < 1e-14:
            return new
        th = new
    raise InputError(f"ISO 6336-3: the 30 deg tangent iteration did not converge (G = {g:.4g}, "
                     f"z_n = {zn:.4g})")


def helix_factor(overlap_ratio: float, helix_angle: float) -> float:
    """Y_beta = 1 - eps_beta beta / 120 deg, eps_beta <= 1 and beta <= 30 deg (-)."""
    eb = min(overlap_ratio, 1.0)
    beta = min(math.degrees(helix_angle), 30.0)
    return 1.0 - eb * beta / 120.0


def virtual_teeth(gear: GearSpec) -> float:
    """z_n = z / (cos^2 beta_b cos beta), negative for an internal gear (-)."""
    return -gear.equivalent_teeth if gear.internal else gear.equivalent_teeth


def rack_root_section(gear: GearSpec) -> RootSection:
    """The 30 deg tangent section of an external gear cut by its rack (module docstring):
    h_fP = dedendum_coef m_n, rho_fP = cutter_tip_radius_coef m_n."""
    if gear.internal:
        raise InputError(f"{gear.name}: the rack construction is for external gears; an "
                         "internal gear's section comes from its pinion-type cutter")
    mn, an, x = gear.module, gear.pressure_angle, gear.profile_shift
    h_fp = gear.dedendum_coef * mn
    rho_fp = gear.cutter_tip_radius_coef * mn
    zn = virtual_teeth(gear)
    e = math.pi / 4.0 * mn - h_fp * math.tan(an) - (1.0 - math.sin(an)) * rho_fp / math.cos(an)
    g = rho_fp / mn - h_fp / mn + x
    h = 2.0 / zn * (math.pi / 2.0 - e / mn) - math.pi / 3.0
    th = _theta(g, h, zn)
    s_fn = mn * (zn * math.sin(math.pi / 3.0 - th) + math.sqrt(3.0) * (g / math.cos(th)
                                                                      - rho_fp / mn))
    rho_f = mn * (rho_fp / mn + 2.0 * g * g / (math.cos(th) * (zn * math.cos(th) ** 2
                                                               - 2.0 * g)))
    y_f = mn / 2.0 * (zn * math.cos(math.pi / 3.0 - th) + g / math.cos(th) - rho_fp / mn)
    return RootSection(s_fn, rho_f, 2.0 * math.hypot(y_f, s_fn / 2.0), EXTERNAL_TANGENT, th)


@dataclass(frozen=True)
class _Shaping:
    """The cutting mesh of a ring and its cutter in the virtual gear's plane (SI).

    The ring's axis is the origin, the tooth space being cut is centred on +y at
    ``psi = 0``; the cutter's tooth in it is centred on its own +y axis, and ``rounding``
    is the centre M of the rounding on the cutter flank facing +x, in the cutter's frame."""

    centre_distance: float
    ratio: float
    pitch_radius: float
    rounding: np.ndarray
    rho: float
    tip_normal: float
    flank_normal: float

    def rounding_path(self, psi: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """M and its first two derivatives in psi, in the ring's frame."""
        s, c = math.sin(psi), math.cos(psi)
        w = self.ratio - 1.0  # the cutter's turn per unit psi
        cb, sb = math.cos(w * psi), math.sin(w * psi)
        m0 = self.rounding
        rot = np.array([cb * m0[0] - sb * m0[1], sb * m0[0] + cb * m0[1]])
        quarter = np.array([-rot[1], rot[0]])
        a0 = self.centre_distance
        centre = a0 * np.array([s, c])
        return (centre + rot, a0 * np.array([c, -s]) + w * quarter,
                -centre - w * w * rot)

    def cut_normal(self, psi: float) -> tuple[np.ndarray, np.ndarray, float]:
        """(M, unit normal from the pitch point through M, its angle on the cutter from the
        cutter tooth's centre line towards +x), in the ring's frame."""
        m, _, _ = self.rounding_path(psi)
        pitch = self.pitch_radius * np.array([math.sin(psi), math.cos(psi)])
        n = (m - pitch) / np.linalg.norm(m - pitch)
        turn = (self.ratio - 1.0) * psi
        on_cutter = math.atan2(n[0], n[1]) + turn
        return m, n, on_cutter


def _shaping(gear: GearSpec, cutter: ShaperCutter) -> _Shaping:
    """The cutting mesh of ``gear`` (internal) and ``cutter``, validated (module docstring)."""
    mn, an = gear.module, gear.pressure_angle
    zn = gear.equivalent_teeth
    scale = zn / gear.teeth
    p = cutter.name
    check_int_range(f"{p}_teeth", cutter.teeth, 8, gear.teeth - MIN_TEETH_DIFFERENCE)
    z0 = cutter.teeth * scale
    x0 = cutter.profile_shift
    rho = mn * (gear.cutter_tip_radius_coef if cutter.tip_radius_coef is None
                else cutter.tip_radius_coef)
    inv_w = float(inv(an)) + 2.0 * math.tan(an) * (x0 + gear.profile_shift) / (z0 - zn)
    if inv_w <= 0.0:
        raise InputError(f"{p}: no cutting mesh (inv(alpha_w0) = {inv_w:.4g}); raise "
                         f"{p}_profile_shift = {x0:.6g} or lower the ring's profile shift")
    aw = float(inv_inverse(inv_w))
    a0 = mn * (zn - z0) / 2.0 * math.cos(an) / math.cos(aw)
    r0 = mn * z0 / 2.0
    rb0 = r0 * math.cos(an)
    if cutter.addendum_coef is None:  # the cutter reaches the ring's root circle
        ra0 = mn * zn / 2.0 + gear.root_radius - gear.reference_radius - a0
        if ra0 <= r0:
            raise InputError(f"{p}: reaching the root circle of {gear.name} needs a cutter "
                             f"addendum of {(ra0 - r0) * 1e3:.6g} mm; give {p}_addendum_coef")
    else:
        ra0 = r0 + mn * (cutter.addendum_coef + x0)
    rm = ra0 - rho
    if rm <= rb0:
        raise InputError(f"{p}: the tip rounding {rho * 1e3:.6g} mm reaches below the "
                         f"cutter's base circle; lower {p}_tip_radius_coef")
    roll = math.sqrt(rm * rm - rb0 * rb0) + rho  # of the flank point the rounding touches
    rt = math.hypot(rb0, roll)
    at = math.acos(rb0 / rt)
    half = (math.pi / 2.0 + 2.0 * x0 * math.tan(an)) / z0 + float(inv(an)) - float(inv(at))
    flank_normal = half + math.pi / 2.0 - at  # the flank's outward normal, from the centre line
    touch = rt * np.array([math.sin(half), math.cos(half)])
    m0 = touch - rho * np.array([math.sin(flank_normal), math.cos(flank_normal)])
    if m0[0] < 0.0:
        raise InputError(f"{p}: the tip rounding {rho * 1e3:.6g} mm does not fit on the "
                         f"cutter tooth (its tip is too narrow); lower {p}_tip_radius_coef or "
                         f"{p}_addendum_coef")
    return _Shaping(a0, zn / z0, a0 + a0 * z0 / (zn - z0), m0, rho,
                    math.atan2(m0[0], m0[1]), flank_normal)


def _bracket(f, start: float, step: float, limit: float) -> tuple[float, float] | None:
    """First interval from ``start`` in steps of ``step`` where ``f`` changes sign."""
    a, fa = start, f(start)
    while abs(a - start) < limit:
        b = a + step
        fb = f(b)
        if fa * fb <= 0.0:
            return (a, b)
        a, fa = b, fb
    return None


def shaper_root_section(gear: GearSpec, cutter: ShaperCutter) -> RootSection:
    """The 60 deg tangent section of an internal gear generated by ``cutter`` (module
    docstring): exact generation in the virtual spur gear's plane."""
    if not gear.internal:
        raise InputError(f"{gear.name}: the pinion-type cutter's construction is for internal "
                         "gears; an external gear's section comes from its rack")
    sh = _shaping(gear, cutter)
    zn = gear.equivalent_teeth
    centre_line = np.array([math.sin(math.pi / zn), math.cos(math.pi / zn)])
    pitch = 2.0 * math.pi / zn
    step = pitch / 400.0

    def beyond(psi: float, target: float) -> float:
        return sh.cut_normal(psi)[2] - target

    # the rounding cuts from where its normal is the tip circle's to where it is the flank's
    tip = _bracket(lambda p: beyond(p, sh.tip_normal), 0.0, step, pitch)
    if tip is None:  # the normal at psi = 0 may already lie past the tip circle's
        tip = _bracket(lambda p: beyond(p, sh.tip_normal), 0.0, -step, pitch)
    flank = _bracket(lambda p: beyond(p, sh.flank_normal), 0.0, -step, 2.0 * pitch)
    if tip is None or flank is None:
        raise InputError(f"{gear.name}: the tip rounding of {cutter.name} does not "
                         "generate a fillet (no cutting between its tip and flank)")
    from scipy.optimize import brentq  # 0.5 s to import: internal gears only

    psi_tip = brentq(lambda p: beyond(p, sh.tip_normal), *tip, xtol=1e-15)
    psi_flank = brentq(lambda p: beyond(p, sh.flank_normal), *flank, xtol=1e-15)
    sine = math.sin(INTERNAL_TANGENT)  # |normal . centre line| at the 60 deg tangent

    def tilt(psi: float) -> float:
        return abs(float(sh.cut_normal(psi)[1] @ centre_line)) - sine

    span = psi_flank - psi_tip
    where = _bracket(tilt, psi_tip, span / 400.0, abs(span) * (1.0 + 1e-9))
    if where is None:
        raise InputError(f"{gear.name}: no 60 deg tangent on the fillet {cutter.name} "
                         "generates (it lies on the involute)")
    psi = brentq(tilt, *where, xtol=1e-15)
    m, n, _ = sh.cut_normal(psi)
    point = m + sh.rho * n
    _, d1, d2 = sh.rounding_path(psi)
    speed = float(np.linalg.norm(d1))
    left = np.array([-d1[1], d1[0]]) / speed
    # the fillet, M's path offset by rho along n, shares the path's centre of curvature
    # M + left / kappa (kappa = M' x M'' / |M'|^3, signed)
    kappa = float(d1[0] * d2[1] - d1[1] * d2[0]) / speed**3
    rho_f = abs(sh.rho * float(n @ left) - 1.0 / kappa)
    chord = 2.0 * abs(float(point[0] * centre_line[1] - point[1] * centre_line[0]))
    diameter = -2.0 * float(np.linalg.norm(point))
    m, n, _ = sh.cut_normal(psi_flank)
    form = -2.0 * float(np.linalg.norm(m + sh.rho * n))
    return RootSection(chord, rho_f, diameter, INTERNAL_TANGENT, form_diameter=form)


def _load_point(gear: GearSpec, pair: GearPair, zn: float,
                load_diameter: float | None) -> tuple[float, float, float, float]:
    """(d_en, alpha_Fen, y_e, eps_alpha_n) of the virtual gear (module docstring, SI)."""
    mn, an, x = gear.module, gear.pressure_angle, gear.profile_shift
    sign = -1.0 if gear.internal else 1.0
    dn = mn * zn
    dbn = dn * math.cos(an)
    dan = dn + sign * 2.0 * (gear.tip_radius_ - gear.reference_radius)
    ean = pair.transverse_contact_ratio / math.cos(gear.base_helix_angle) ** 2
    if load_diameter is None:
        pbn = math.pi * mn * math.cos(an)
        roll = math.sqrt(dan**2 - dbn**2) / 2.0 - sign * pbn * (ean - 1.0)
        den = sign * 2.0 * math.sqrt(roll**2 + dbn**2 / 4.0)
    else:
        den = float(load_diameter)
        if gear.internal:  # from the tip inwards to the root circle
            dfn = dn - 2.0 * (gear.root_radius - gear.reference_radius)
            inside = dfn < den <= dan * (1.0 - 1e-12)
            span = f"[{dan * 1e3:.6g}, {dfn * 1e3:.6g})"
        else:
            inside = dbn < den <= dan * (1.0 + 1e-12)
            span = f"({dbn * 1e3:.6g}, {dan * 1e3:.6g}]"
        if not inside:
            raise InputError(f"ISO 6336-3: load diameter {den * 1e3:.6g} mm is outside the "
                             f"involute of the virtual gear {span} mm")
    aen = math.acos(dbn / den)
    ge = (math.pi / 2.0 + 2.0 * x * math.tan(an)) / zn + float(inv(an)) - float(inv(aen))
    afen = aen - ge
    y_e = (math.cos(ge) - math.sin(ge) * math.tan(afen)) * den / 2.0
    return den, afen, y_e, ean


def iso_root_stress(gear: GearSpec, pair: GearPair, tangential_load: float, *,
                    load_diameter: float | None = None, cutter: ShaperCutter | None = None,
                    section: RootSection | None = None) -> IsoRootStress:
    """ISO 6336-3 method B nominal root stress of ``gear`` in ``pair`` (module docstring).

    Parameters
    ----------
    gear : ``pair.pinion`` or ``pair.gear``; an external gear is generated by its rack
        cutter (h_fP = dedendum_coef m_n, rho_fP = cutter_tip_radius_coef m_n), an internal
        one by ``cutter``.
    pair : the pair (transverse contact ratio and overlap ratio).
    tangential_load : F_t at the reference circle, N (> 0).
    load_diameter : d_en of the virtual spur gear where the load acts, m (negative for an
        internal gear); default the outer point of single pair contact; ``d_an`` puts it
        at the tip.
    cutter : the pinion-type cutter of an internal gear (required for one, refused for an
        external gear).
    section : a critical section to use instead of the generated one (e.g. a printed one;
        its diameter's sign must be the gear's).
    """
    if not tangential_load > 0.0:
        raise InputError(f"ISO 6336-3: tangential load {tangential_load:.6g} N must be > 0 N")
    if cutter is not None and not gear.internal:
        raise InputError(f"{gear.name}: a pinion-type cutter is modelled for internal gears "
                         "only; an external gear is cut by its rack (leave cutter unset)")
    if cutter is not None and section is not None:
        raise InputError(f"{gear.name}: give the cutter that generates the root section or "
                         "the section itself, not both")
    if section is None:
        if gear.internal and cutter is None:
            raise InputError(f"{gear.name}: an internal gear's root section needs its "
                             "pinion-type cutter (cutter=ShaperCutter(teeth=z_0))")
        section = shaper_root_section(gear, cutter) if gear.internal \
            else rack_root_section(gear)
    elif (section.diameter < 0.0) != gear.internal:
        raise InputError(f"{gear.name}: the section's diameter {section.diameter * 1e3:.6g} mm "
                         "must be negative exactly for an internal gear")
    zn = virtual_teeth(gear)
    den, afen, y_e, ean = _load_point(gear, pair, zn, load_diameter)
    mn, s_fn, rho_f = gear.module, section.chord, section.fillet_radius
    h_fe = y_e - section.height
    if not h_fe > 0.0:
        raise InputError(f"{gear.name}: the load line crosses the tooth centre line "
                         f"{-h_fe * 1e3:.6g} mm beyond the critical section (bending arm <= 0); "
                         "move the load diameter towards the tip")
    y_f = 6.0 * (h_fe / mn) * math.cos(afen) / ((s_fn / mn) ** 2 * math.cos(gear.pressure_angle))
    L = s_fn / h_fe
    qs = s_fn / (2.0 * rho_f)
    y_s = (1.2 + 0.13 * L) * qs ** (1.0 / (1.21 + 2.3 / L))
    y_beta = helix_factor(pair.overlap_ratio, gear.helix_angle)
    b = pair.face_width
    sigma = tangential_load / (b * mn) * y_f * y_s * y_beta
    return IsoRootStress(sigma, float(tangential_load), b, y_f, y_s, y_beta, 1.0, 1.0, s_fn,
                         rho_f, h_fe, den, afen, section.theta, zn, qs, bool(1.0 <= qs < 8.0),
                         ean, section, cutter if gear.internal else None)
