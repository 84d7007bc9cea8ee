"""Tolerances of ISO 1328-1:1995 for an accuracy grade: the deviations the load factors of
ISO 6336-1 (K_v, K_Halpha, K_Hbeta) are computed from.

ISO 6336-1 and ISO/TR 6336-30 use the 1995 grades (the 2013 edition's tolerance classes
give other values). Grade 5 formulas, in um with ``m_n``, ``d`` and ``b`` in mm:

* single pitch ``f_pt = 0.3 (m_n + 0.4 sqrt(d)) + 4``; cumulative ``F_p = 0.3 m_n + 1.25
  sqrt(d) + 7``;
* profile: total ``F_alpha = 3.2 sqrt(m_n) + 0.22 sqrt(d) + 0.7``, form ``f_falpha = 2.5
  sqrt(m_n) + 0.17 sqrt(d) + 0.5``, slope ``f_Halpha = 2 sqrt(m_n) + 0.14 sqrt(d) + 0.5``;
* helix: total ``F_beta = 0.1 sqrt(d) + 0.63 sqrt(b) + 4.2``, form and slope ``f_fbeta =
  f_Hbeta = 0.07 sqrt(d) + 0.45 sqrt(b) + 3``;

evaluated at the geometric mean of the size range each of ``m_n``, ``d`` and ``b`` falls in
(:data:`RANGES`, upper limits included), multiplied by ``2^((Q - 5) / 2)`` for grade
``Q``, and rounded: to 1 um from 10 um, to 0.5 um from 5 um, to 0.1 um below. The base
pitch deviation of ISO 6336-1 is ``f_pb = f_pt cos(alpha_t)`` (to 0.1 um).

Checked against the tolerances KISSsoft prints for the eight gears of the NREL 5 MW
reference gearbox (``tests/test_rating_accuracy.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.validation import InputError, check_int_range

RANGES = {
    "d": (5.0, 20.0, 50.0, 125.0, 280.0, 560.0, 1000.0, 1600.0, 2500.0, 4000.0, 6000.0,
          8000.0, 10000.0),
    "m_n": (0.5, 2.0, 3.5, 6.0, 10.0, 16.0, 25.0, 40.0, 70.0),
    "b": (4.0, 10.0, 20.0, 40.0, 80.0, 160.0, 250.0, 400.0, 650.0, 1000.0),
}
"""Size ranges of ISO 1328-1:1995 (mm): a value in ``(lo, hi]`` takes ``sqrt(lo hi)``."""


def range_mean(value_mm: float, name: str) -> float:
    """Geometric mean of the ISO 1328-1 range (mm) that ``value_mm`` lies in."""
    limits = RANGES[name]
    for lo, hi in zip(limits[:-1], limits[1:], strict=True):
        if lo < value_mm <= hi or (value_mm == lo == limits[0]):
            return math.sqrt(lo * hi)
    raise InputError(f"ISO 1328-1: {name} = {value_mm:.6g} mm is outside the standard's range "
                     f"[{limits[0]:g}, {limits[-1]:g}] mm")


def rounded(value_um: float) -> float:
    """ISO 1328-1 rounding: to 1 um from 10 um, to 0.5 um from 5 um, else to 0.1 um."""
    step = 1.0 if value_um >= 10.0 else 0.5 if value_um >= 5.0 else 0.1
    return round(value_um / step) * step


@dataclass(frozen=True)
class Tolerances:
    """Tolerances of one gear for its accuracy grade, m (ISO 1328-1:1995 symbols)."""

    grade: int
    f_pt: float
    f_pb: float
    F_p: float
    F_alpha: float
    f_falpha: float
    f_Halpha: float
    F_beta: float
    f_fbeta: float
    f_Hbeta: float


def tolerances(grade: int, module: float, diameter: float, face_width: float,
               transverse_pressure_angle: float) -> Tolerances:
    """ISO 1328-1:1995 tolerances of grade ``grade`` (0..12) for the normal module,
    reference diameter and face width (m); ``f_pb`` with the transverse pressure angle
    (rad)."""
    check_int_range("rating.accuracy_grade", grade, 0, 12)
    m = range_mean(module * 1e3, "m_n")
    d = math.sqrt(range_mean(diameter * 1e3, "d"))
    b = math.sqrt(range_mean(face_width * 1e3, "b"))
    k = 2.0 ** ((grade - 5) / 2.0)
    sm = math.sqrt(m)

    def tol(grade5_um: float) -> float:
        return rounded(grade5_um * k)

    f_pt = tol(0.3 * (m + 0.4 * d) + 4.0)
    f_pb = round(f_pt * math.cos(transverse_pressure_angle), 1)
    f_hb = tol(0.07 * d + 0.45 * b + 3.0)
    um = 1e-6
    return Tolerances(grade, f_pt * um, f_pb * um, tol(0.3 * m + 1.25 * d + 7.0) * um,
                      tol(3.2 * sm + 0.22 * d + 0.7) * um, tol(2.5 * sm + 0.17 * d + 0.5) * um,
                      tol(2.0 * sm + 0.14 * d + 0.5) * um, tol(0.1 * d + 0.63 * b + 4.2) * um,
                      f_hb * um, f_hb * um)
