"""Dynamic factor K_v of ISO 6336-1, method B, in every range of the resonance ratio.

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

* The other ranges (ISO 6336-1:2006, 6.5.5-6.5.7, the coefficients of its Table 8; as
  transcribed in the MATLAB ISO 6336 classes of gfsReboucas/Drivetrain, ``ISO_6336.m``):
  the main resonance ``N_S < N <= 1.15``: ``K_v = C_v1 B_p + C_v2 B_f + C_v4 B_k + 1``
  (to be avoided: a warning); the supercritical range ``N >= 1.5``: ``K_v = C_v5 B_p +
  C_v6 B_f + C_v7``; between, linear in ``N`` from the value at 1.15 to that at 1.5;
  ``C_v4 = 0.90``, ``C_v5 = 0.47``, ``C_v6 = 0.47`` for ``eps_gamma <= 2``, above
  ``C_v4 = (0.57 - 0.05 eps_gamma) / (eps_gamma - 1.44)``, ``C_v6 = 0.12 / (eps_gamma -
  1.74)``; ``C_v7 = 0.75`` up to ``eps_gamma`` 1.5, ``0.125 sin(pi (eps_gamma - 2)) +
  0.875`` to 2.5, 1 above.

Checked against KISSsoft's reports of the NREL 5 MW gearbox (``tests/test_rating_dynamic.py``,
the subcritical range; the others against hand calculations there).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from pipeline.validation import InputError, PhysicsWarning, check_choice, check_range

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
    range : "subcritical", "main resonance", "intermediate" or "supercritical".
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
    range: str = "subcritical"


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
    c = single_stiffness * 1e-9  # N/(mm um)
    bp = c * (base_pitch_deviation - pitch_allowance) * 1e6 / w
    bf = c * (form_deviation - form_allowance) * 1e6 / w
    bk = abs(1.0 - c * tip_relief * 1e6 / w)
    cv = _coefficients(total_contact_ratio)
    main = cv[1] * bp + cv[2] * bf + cv[4] * bk + 1.0
    supercritical = cv[5] * bp + cv[6] * bf + cv[7]
    if ratio <= n_s:
        name, kv = "subcritical", ratio * (cv[1] * bp + cv[2] * bf + cv[3] * bk) + 1.0
    elif ratio <= 1.15:
        name, kv = "main resonance", main
        warnings.warn(f"rating: the pinion at {speed_1:.6g} rpm runs in the main resonance "
                      f"range of ISO 6336-1 (N = {ratio:.4g}, N_S = {n_s:.4g} to 1.15), which "
                      "the standard says to avoid; K_v of that range is used", PhysicsWarning,
                      stacklevel=2)
    elif ratio < 1.5:
        name, kv = "intermediate", supercritical + (main - supercritical) * (1.5 - ratio) / 0.35
    else:
        name, kv = "supercritical", supercritical
    return DynamicFactor(reduced_mass_per_width, n_e1, ratio, pitch_allowance, form_allowance,
                         bp, bf, bk, kv, name)


def _coefficients(eg: float) -> dict[int, float]:
    """C_v1 .. C_v7 of ISO 6336-1's Table 8 for the total contact ratio ``eg``."""
    if eg <= 2.0:
        cv = {2: 0.34, 3: 0.23, 4: 0.90, 6: 0.47}
    else:
        cv = {2: 0.57 / (eg - 0.3), 3: 0.096 / (eg - 1.56),
              4: (0.57 - 0.05 * eg) / (eg - 1.44), 6: 0.12 / (eg - 1.74)}
    cv7 = 0.75 if eg <= 1.5 else 0.125 * math.sin(math.pi * (eg - 2.0)) + 0.875 if eg <= 2.5 \
        else 1.0
    return {1: 0.32, 5: 0.47, 7: cv7, **cv}
