"""Nominal tooth root stress of ISO 6336-3 (method B) for external gears cut by a rack.

ISO 6336-3:2019, 6.2 (the form factor ``Y_F`` and stress correction factor ``Y_S`` of
method B, from the basic rack and the virtual spur gear; no protuberance, ``s_pr = 0``):

* virtual spur gear: ``z_n = z / (cos^2 beta_b cos beta)``, ``d_n = m_n z_n``,
  ``d_bn = d_n cos(alpha_n)``, ``d_an = d_n + d_a - d``;
* ``E = pi/4 m_n - h_fP tan(alpha_n) - (1 - sin(alpha_n)) rho_fP / cos(alpha_n)``,
  ``G = rho_fP / m_n - h_fP / m_n + x``, ``H = 2 / z_n (pi/2 - E / m_n) - pi/3``, and
  ``theta = 2 G / z_n tan(theta) - H`` (fixed point from ``pi/6``): the 30 deg tangent;
* ``s_Fn / m_n = z_n sin(pi/3 - theta) + sqrt(3) (G / cos(theta) - rho_fP / m_n)`` (chord
  between the 30 deg tangent points), ``rho_F / m_n = rho_fP / m_n + 2 G^2 / (cos(theta)
  (z_n cos^2(theta) - 2 G))`` (fillet radius there);
* the load acts at the outer point of single pair contact of the virtual gear,
  ``d_en = 2 sqrt((sqrt(d_an^2 - d_bn^2)/2 - p_bn (eps_alpha_n - 1))^2 + d_bn^2/4)`` with
  ``eps_alpha_n = eps_alpha / cos^2(beta_b)`` and ``p_bn = pi m_n cos(alpha_n)``; for a
  high-contact-ratio pair (``eps_alpha_n >= 2``) the same formula, as ISO keeps it, gives
  the outer point of double pair contact (the inner point of triple pair contact, one
  ``p_bn (eps_alpha_n - 1) >= p_bn`` from the tip), still with the whole ``F_t`` on one
  tooth: the tooth there shares the load with one other pair, so sigma_F0 stays above a
  loaded tooth contact's stress (:attr:`IsoRootStress.high_contact_ratio`);
  ``alpha_en = acos(d_bn / d_en)``, ``gamma_e = (pi/2 + 2 x tan(alpha_n)) / z_n +
  inv(alpha_n) - inv(alpha_en)``, ``alpha_Fen = alpha_en - gamma_e`` (the load angle);
* bending arm ``h_Fe / m_n = ((cos(gamma_e) - sin(gamma_e) tan(alpha_Fen)) d_en / m_n
  - z_n cos(pi/3 - theta) - G / cos(theta) + rho_fP / m_n) / 2``;
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

``load_diameter`` moves the load, e.g. to the tip (``d_en = d_an``, ISO's tip-load factors
``Y_Fa``, ``Y_Sa``). The same geometry is checked against the exact generated profile of
:mod:`pipeline.geometry.profile` (the 30 deg tangent points, their chord and fillet
radius, the load line) in ``tests/test_root_stress.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.involute import inv
from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError


@dataclass(frozen=True)
class IsoRootStress:
    """ISO 6336-3 method B nominal root stress of one gear (SI).

    Attributes
    ----------
    sigma_f0 : nominal tooth root stress sigma_F0, Pa.
    tangential_load : F_t at the reference circle, N; face_width : b, m.
    y_f, y_s, y_beta, y_b, y_dt : the factors (-).
    s_fn : tooth root chord at the 30 deg tangents, m.
    rho_f : fillet radius at the 30 deg tangent, m.
    h_fe : bending moment arm, m.
    load_diameter : d_en of the virtual spur gear where the load acts, m.
    load_angle : alpha_Fen, rad.
    theta : angle of the 30 deg tangent construction (ISO's theta), rad.
    virtual_teeth : z_n (-).
    q_s : notch parameter s_Fn / (2 rho_F) (-); in_range : 1 <= q_s < 8.
    virtual_contact_ratio : eps_alpha_n = eps_alpha / cos^2(beta_b) (-).
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
    theta: float
    virtual_teeth: float
    q_s: float
    in_range: bool
    virtual_contact_ratio: float

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
                "eps_alpha_n": self.virtual_contact_ratio}


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


def iso_root_stress(gear: GearSpec, pair: GearPair, tangential_load: float, *,
                    load_diameter: float | None = None) -> IsoRootStress:
    """ISO 6336-3 method B nominal root stress of ``gear`` in ``pair`` (module docstring).

    Parameters
    ----------
    gear : ``pair.pinion`` or ``pair.gear`` (external, generated by its rack cutter:
        h_fP = dedendum_coef m_n, rho_fP = cutter_tip_radius_coef m_n).
    pair : the pair (transverse contact ratio and overlap ratio).
    tangential_load : F_t at the reference circle, N (> 0).
    load_diameter : d_en of the virtual spur gear where the load acts, m; default the outer
        point of single pair contact; ``d_an`` puts it at the tip.
    """
    if gear.internal:
        raise InputError(f"{gear.name}: ISO 6336-3 method B form factors are implemented for "
                         f"external gears only")
    if not tangential_load > 0.0:
        raise InputError(f"ISO 6336-3: tangential load {tangential_load:.6g} N must be > 0 N")
    mn, an, x = gear.module, gear.pressure_angle, gear.profile_shift
    h_fp = gear.dedendum_coef * mn
    rho_fp = gear.cutter_tip_radius_coef * mn
    bb = gear.base_helix_angle
    zn = gear.teeth / (math.cos(bb) ** 2 * math.cos(gear.helix_angle))
    e = math.pi / 4.0 * mn - h_fp * math.tan(an) - (1.0 - math.sin(an)) * rho_fp / math.cos(an)
    g = rho_fp / mn - h_fp / mn + x
    h = 2.0 / zn * (math.pi / 2.0 - e / mn) - math.pi / 3.0
    th = _theta(g, h, zn)
    s_fn = mn * (zn * math.sin(math.pi / 3.0 - th) + math.sqrt(3.0) * (g / math.cos(th)
                                                                      - rho_fp / mn))
    rho_f = mn * (rho_fp / mn + 2.0 * g * g / (math.cos(th) * (zn * math.cos(th) ** 2
                                                               - 2.0 * g)))
    dn = mn * zn
    dbn = dn * math.cos(an)
    dan = dn + 2.0 * gear.tip_radius_ - 2.0 * gear.reference_radius
    ean = pair.transverse_contact_ratio / math.cos(bb) ** 2
    if load_diameter is None:
        pbn = math.pi * mn * math.cos(an)
        roll = math.sqrt(dan**2 - dbn**2) / 2.0 - pbn * (ean - 1.0)
        den = 2.0 * math.sqrt(roll**2 + dbn**2 / 4.0)
    else:
        den = float(load_diameter)
        if not dbn < den <= dan * (1.0 + 1e-12):
            raise InputError(f"ISO 6336-3: load diameter {den * 1e3:.6g} mm is outside the "
                             f"involute of the virtual gear ({dbn * 1e3:.6g}, {dan * 1e3:.6g}] mm")
    aen = math.acos(dbn / den)
    ge = (math.pi / 2.0 + 2.0 * x * math.tan(an)) / zn + float(inv(an)) - float(inv(aen))
    afen = aen - ge
    h_fe = mn / 2.0 * ((math.cos(ge) - math.sin(ge) * math.tan(afen)) * den / mn
                       - zn * math.cos(math.pi / 3.0 - th) - g / math.cos(th) + rho_fp / mn)
    y_f = 6.0 * (h_fe / mn) * math.cos(afen) / ((s_fn / mn) ** 2 * math.cos(an))
    L = s_fn / h_fe
    qs = s_fn / (2.0 * rho_f)
    y_s = (1.2 + 0.13 * L) * qs ** (1.0 / (1.21 + 2.3 / L))
    y_beta = helix_factor(pair.overlap_ratio, gear.helix_angle)
    b = pair.face_width
    sigma = tangential_load / (b * mn) * y_f * y_s * y_beta
    return IsoRootStress(sigma, float(tangential_load), b, y_f, y_s, y_beta, 1.0, 1.0, s_fn,
                         rho_f, h_fe, den, afen, th, zn, qs, bool(1.0 <= qs < 8.0), ean)
