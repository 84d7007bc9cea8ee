"""Dynamic factor K_v of ISO 6336-1, method B (the subcritical range).

SI inside; the standard's formulas in mm, um, N/mm and kg/mm are converted where written.

* Mass per unit face width of a gear reduced to its base circle (a solid or bored
  cylinder of the mean diameter ``d_m = (d_a + d_f) / 2``): ``m* = pi / 8 (d_m / d_b)^2
  d_m^2 rho (1 - q^4)``, ``q = d_i / d_m`` (:func:`gear_mass`); the pair's ``m_red = m1*
  m2* / (m1* + m2*)``; a planetary set's sun-planet mesh ``m_red = (m_sun* / N) m_pla* /
  (m_sun* / N + m_pla*)`` with ``N`` planets, its planet-ring mesh ``m_red = m_pla*``
  (:func:`reduced_mass`).
* Resonance speed of the pinion ``n_E1 = 30000 / (pi z1) sqrt(c_gamma_alpha / m_red)``
  (rpm, with N/(mm um) and kg/mm) and the resonance ratio ``N = n1 / n_E1`` (the
  speeds of a planetary mesh relative to the carrier); the subcritical range ends at
  ``N_S = 0.85`` (``0.5 + 0.35 sqrt(K_A F_t / (100 b))`` below 100 N/mm).
* Running-in allowances ``y_p`` (of the base pitch deviation ``f_pb``) and ``y_f`` (of the
  profile form deviation ``f_falpha``), each the larger of the two gears' tolerances
  (:mod:`pipeline.rating.accuracy`), per gear ``0.075 f`` (at most 3 um) for
  case-hardened and nitrided steels, ``160 / sigma_Hlim f`` for through-hardened steels
  (at most 12800 / sigma_Hlim um from 5 m/s, 6400 / sigma_Hlim from 10 m/s); a pair of
  two materials takes the mean of the two gears' values (:func:`running_in`).
* ``K_v = N K + 1``, ``K = C_v1 B_p + C_v2 B_f + C_v3 B_k`` with ``B_p = c' (f_pb -
  y_p) / (K_A F_t / b)``, ``B_f = c' (f_falpha - y_f) / (K_A F_t / b)``, ``B_k = |1 - c'
  C_a / (K_A F_t / b)|`` (``C_a`` the tip relief, or without one the running-in relief
  ``C_ay = (sigma_Hlim / 97 - 18.45)^2 / 18 + 1.5`` um, the mean of the two gears'); for
  ``1 < eps_gamma <= 2`` ``C_v1 = 0.32``, ``C_v2 = 0.34``, ``C_v3 = 0.23``, above 2
  ``C_v2 = 0.57 / (eps_gamma - 0.3)``, ``C_v3 = 0.096 / (eps_gamma - 1.56)``.

The main resonance and the supercritical range are not built: ``N > N_S`` is refused.
Checked against KISSsoft's reports of the NREL 5 MW gearbox (``tests/test_rating_dynamic.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.validation import InputError, check_choice, check_range

HARDENING = ("hardened", "through_hardened", "cast_iron")


def gear_mass(tip_diameter: float, root_diameter: float, base_diameter: float,
              inner_diameter: float, density: float) -> float:
    """``m*`` of a gear per unit face width, kg/m (diameters in m, density kg/m^3)."""
    dm = 0.5 * (tip_diameter + root_diameter)
    q = inner_diameter / dm
    if not 0.0 <= q < 1.0:
        raise InputError(f"rating: inner diameter {inner_diameter * 1e3:.6g} mm is not inside "
                         f"the mean diameter {dm * 1e3:.6g} mm")
    return math.pi / 8.0 * (dm / base_diameter) ** 2 * dm * dm * density * (1.0 - q**4)


def reduced_mass(pinion: float, wheel: float | None, mesh: str = "pair", planets: int = 1
                 ) -> float:
    """``m_red`` (kg/m) of a ``"pair"``, a ``"sun_planet"`` mesh (``pinion`` the sun,
    ``wheel`` a planet, ``planets`` of them) or a ``"planet_ring"`` mesh (``pinion`` the
    planet)."""
    check_choice("rating.mesh", mesh, ("pair", "sun_planet", "planet_ring"))
    if mesh == "planet_ring":
        return pinion
    sun = pinion / planets if mesh == "sun_planet" else pinion
    return sun * wheel / (sun + wheel)


def allowance(deviation: float, hardening: str, sigma_hlim: float, velocity: float) -> float:
    """Running-in allowance (m) of one gear for a deviation (m) on its material class
    (:data:`HARDENING`: Eh, IF, NT, NV; St, V, GGG perl., GTS; GG, GGG ferr.)."""
    check_choice("rating.hardening", hardening, HARDENING)
    if hardening == "hardened":
        return min(0.075 * deviation, 3e-6)
    if hardening == "cast_iron":
        y = 0.275 * deviation
        return min(y, 11e-6) if velocity > 10.0 else min(y, 22e-6) if velocity > 5.0 else y
    s = sigma_hlim / 1e6
    y = 160.0 / s * deviation
    if velocity > 10.0:
        return min(y, 6400.0 / s * 1e-6)
    if velocity > 5.0:
        return min(y, 12800.0 / s * 1e-6)
    return y


def running_in(deviation: float, gears: tuple[tuple[str, float], tuple[str, float]],
               velocity: float) -> float:
    """The pair's running-in allowance (m) for the deviation (m, the larger of the two
    gears'), ``gears`` the (hardening, sigma_Hlim in Pa) of both: the mean of the two."""
    ys = [allowance(deviation, h, s, velocity) for h, s in gears]
    return ys[0] if gears[0] == gears[1] else 0.5 * (ys[0] + ys[1])


def running_in_relief(sigma_hlim: float) -> float:
    """``C_ay`` (m) of a gear of ``sigma_Hlim`` (Pa) without a designed tip relief."""
    return ((sigma_hlim / 1e6 / 97.0 - 18.45) ** 2 / 18.0 + 1.5) * 1e-6


@dataclass(frozen=True)
class DynamicFactor:
    """K_v of method B and its intermediates (SI).

    Attributes
    ----------
    reduced_mass : m_red, kg/m; resonance_speed : n_E1, rpm; resonance_ratio : N (-).
    pitch_allowance, form_allowance : y_p, y_f, m.
    b_p, b_f, b_k : the non-dimensional deviation parameters (-).
    factor : K_v (-).
    """

    reduced_mass: float
    resonance_speed: float
    resonance_ratio: float
    pitch_allowance: float
    form_allowance: float
    b_p: float
    b_f: float
    b_k: float
    factor: float


def dynamic_factor(*, teeth_1: int, speed_1: float, single_stiffness: float,
                   mesh_stiffness: float, reduced_mass_per_width: float,
                   line_load: float, total_contact_ratio: float, base_pitch_deviation: float,
                   form_deviation: float, pitch_allowance: float, form_allowance: float,
                   tip_relief: float) -> DynamicFactor:
    """``K_v`` of method B in the subcritical range.

    Parameters (SI): the pinion's teeth and speed (rpm, relative to a planet carrier);
    ``c'`` and ``c_gamma_alpha`` (N/m^2); ``m_red`` (kg/m); ``K_A F_t / b`` (N/m);
    ``eps_gamma``; ``f_pb`` and ``f_falpha`` (m, the larger of the two gears'); ``y_p``,
    ``y_f`` (m); the tip relief ``C_a`` (m; :func:`running_in_relief` without one).
    """
    check_range("rating.speed", speed_1, 0.0, math.inf, lo_open=True, unit="rpm")
    n_e1 = 30.0 / (math.pi * teeth_1) * math.sqrt(mesh_stiffness / reduced_mass_per_width)
    ratio = speed_1 / n_e1
    w = line_load * 1e-3  # N/mm
    n_s = 0.85 if w >= 100.0 else 0.5 + 0.35 * math.sqrt(w / 100.0)
    if ratio > n_s:
        raise InputError(f"rating: resonance ratio N = {ratio:.4g} above the subcritical range "
                         f"(N_S = {n_s:.4g}); K_v of the main resonance and the supercritical "
                         "range is not built yet")
    c = single_stiffness * 1e-9  # N/(mm um)
    bp = c * (base_pitch_deviation - pitch_allowance) * 1e6 / w
    bf = c * (form_deviation - form_allowance) * 1e6 / w
    bk = abs(1.0 - c * tip_relief * 1e6 / w)
    eg = total_contact_ratio
    if eg <= 2.0:
        cv1, cv2, cv3 = 0.32, 0.34, 0.23
    else:
        cv1, cv2, cv3 = 0.32, 0.57 / (eg - 0.3), 0.096 / (eg - 1.56)
    k = cv1 * bp + cv2 * bf + cv3 * bk
    return DynamicFactor(reduced_mass_per_width, n_e1, ratio, pitch_allowance, form_allowance,
                         bp, bf, bk, ratio * k + 1.0)
