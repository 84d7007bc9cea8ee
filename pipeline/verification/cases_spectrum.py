"""Case of the load spectrum (:mod:`pipeline.rating.spectrum`): the Palmgren-Miner sum of
ISO 6336-6:2019, Annex C, Table C.2.

The example: a case-carburized pinion (ISO 6336-2's line without pitting: Z_NT 1.6 at
10^5, 1.0 at 5 x 10^7, 0.85 at 10^10), sigma_Hlim 1500 N/mm^2, Z_L 1.02, Z_v 0.943, Z_R
1.01, 35.2 rpm; 42 torque bins measured for 70 days and extrapolated to 30 years (bins 1,
2 and 45-48 carry no cycles and are left out). The printed stresses sigma_H S_H already
carry the example's safety factor, chosen so that D = 1: the safety factor found on them
is 1. They are rounded to 1 N/mm^2, and each cycles-to-failure N_i is judged within the
change 1 N/mm^2 makes on the curve plus its own printed rounding (3 digits).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.verification.context import Context
from pipeline.verification.model import Outcome, Plot, Quantity, Series

MPA = 1e6

TABLE_C2 = (
    # bin, torque kN m, time in 70 days s, cycles in 30 years, sigma_H S_H N/mm^2, Z_NT,
    # N_i, U_i
    (3, 25.4, 24, 2203, 2349, 1.61, 9.05e+04, 0.0243),
    (4, 25.3, 14, 1285, 2344, 1.61, 9.29e+04, 0.0138),
    (5, 25.3, 9, 825.9, 2344, 1.61, 9.29e+04, 0.00889),
    (6, 25.2, 14, 1285, 2340, 1.61, 9.54e+04, 0.0135),
    (7, 25.1, 28, 2570, 2335, 1.6, 9.79e+04, 0.0262),
    (8, 25, 14, 1285, 2330, 1.6, 1.01e+05, 0.0128),
    (9, 24.9, 9, 825.9, 2326, 1.6, 1.03e+05, 0.008),
    (10, 24.8, 19, 1744, 2321, 1.59, 1.06e+05, 0.0165),
    (11, 24.7, 28, 2570, 2316, 1.59, 1.09e+05, 0.0236),
    (12, 24.6, 33, 3028, 2312, 1.59, 1.12e+05, 0.0271),
    (13, 24.5, 24, 2203, 2307, 1.58, 1.15e+05, 0.0192),
    (14, 24.3, 24, 2203, 2297, 1.58, 1.21e+05, 0.0182),
    (15, 24.2, 19, 1744, 2293, 1.57, 1.25e+05, 0.014),
    (16, 24, 26, 2386, 2283, 1.57, 1.32e+05, 0.0181),
    (17, 23.8, 52, 4772, 2274, 1.56, 1.39e+05, 0.0343),
    (18, 23.6, 47, 4313, 2264, 1.55, 1.47e+05, 0.0293),
    (19, 23.3, 62, 5690, 2250, 1.54, 1.6e+05, 0.0355),
    (20, 23.1, 88, 8076, 2240, 1.54, 1.7e+05, 0.0476),
    (21, 22.8, 66, 6057, 2225, 1.53, 1.85e+05, 0.0328),
    (22, 22.5, 163, 14960, 2211, 1.52, 2.02e+05, 0.0741),
    (23, 22.1, 180, 16520, 2191, 1.5, 2.27e+05, 0.0727),
    (24, 21.8, 83, 7617, 2176, 1.49, 2.49e+05, 0.0306),
    (25, 21.4, 200, 18350, 2156, 1.48, 2.81e+05, 0.0653),
    (26, 20.9, 212, 19460, 2131, 1.46, 3.29e+05, 0.0592),
    (27, 20.5, 104, 9544, 2110, 1.45, 3.73e+05, 0.0256),
    (28, 20, 238, 21840, 2084, 1.43, 4.4e+05, 0.0497),
    (29, 19.4, 253, 23220, 2053, 1.41, 5.38e+05, 0.0432),
    (30, 18.8, 200, 18350, 2021, 1.39, 6.62e+05, 0.0277),
    (31, 18.2, 206, 18900, 1988, 1.37, 8.2e+05, 0.023),
    (32, 17.6, 297, 27260, 1955, 1.34, 1.02e+06, 0.0266),
    (33, 16.9, 316, 29000, 1916, 1.32, 1.34e+06, 0.0217),
    (34, 16.1, 334, 30650, 1870, 1.28, 1.85e+06, 0.0166),
    (35, 15.3, 352, 32300, 1823, 1.25, 2.58e+06, 0.0125),
    (36, 14.5, 274, 25150, 1785, 1.23, 3.42e+06, 0.00736),
    (37, 13.6, 286, 26250, 1742, 1.2, 4.7e+06, 0.00558),
    (38, 12.6, 404, 37080, 1693, 1.16, 6.86e+06, 0.0054),
    (39, 11.6, 429, 39370, 1643, 1.13, 1.02e+07, 0.00385),
    (40, 10.6, 449, 41210, 1593, 1.09, 1.54e+07, 0.00268),
    (41, 9.5, 468, 42950, 1534, 1.05, 2.52e+07, 0.0017),
    (42, 8.3, 303, 27810, 1467, 1.01, 4.57e+07, 0.000609),
    (43, 7.1, 176, 16150, 1398, 0.96, 1.9e+08, 8.48e-05),
    (44, 5.8, 12, 1101, 1318, 0.91, 1.31e+09, 8.42e-07),
)
"""ISO 6336-6:2019, Annex C, Table C.2 (bins 3-44), as transcribed in gfsReboucas/Drivetrain
``data/table_C2.csv`` (commit 4a88df34)."""

SPEED_RPM = 35.2
YEARS_OVER_DAYS = 30 * 365 / 70
"""The measurement's 70 days extrapolated to 30 years of 365 days."""

CHECKED_BINS = (3, 22, 43)
"""Bins whose N_i is listed on its own: above Z_NT 1.6 (the finite-life slope continued
before 10^5 cycles), on the finite-life slope, on the long-life branch."""


def _digit(value: float, digits: int) -> float:
    """Half a unit of the last of ``digits`` significant digits of ``value``."""
    return 0.5 * 10 ** (math.floor(math.log10(abs(value))) - digits + 1)


def case_iso_6336_6_annex_c(context: Context) -> Outcome:
    """Miner sum of ISO 6336-6 Annex C's Table C.2 from its printed stresses: the load
    cycles, N_i of three bins, the damage sum D and the spectrum's safety factor."""
    from pipeline.rating import pitting as P
    from pipeline.rating.life import StrengthCurve
    from pipeline.rating.spectrum import BinStress, LoadBin, LoadSpectrum, miner_damage

    product = 1.02 * 0.943 * 1.01
    curve = StrengthCurve(P.LIFE_LINES["hardened"], 1500 * MPA, product, product,
                          extend_static=True)
    spectrum = LoadSpectrum(tuple(LoadBin(t * 1e3, SPEED_RPM, s / 3600 * YEARS_OVER_DAYS)
                                  for _, t, s, *_ in TABLE_C2))
    stress = {t * 1e3: s * MPA for _, t, _s, _n, s, *_ in TABLE_C2}
    d = miner_damage(spectrum, lambda b: BinStress(stress[b.torque], curve))
    printed_cycles = np.array([row[3] for row in TABLE_C2])
    cycle_digits = np.array([_digit(n, 4) for n in printed_cycles])
    q = [Quantity("largest load-cycle error over the 42 bins, in units of the printed 4th "
                  "digit", "-", 0.0, float(np.max(np.abs(d.cycles - printed_cycles)
                                                  / (2 * cycle_digits))),
                  "upper_bound", 0.5, "every bin to its four printed digits (half a unit)")]
    for k in CHECKED_BINS:
        i = next(j for j, row in enumerate(TABLE_C2) if row[0] == k)
        s, n_i = TABLE_C2[i][4], TABLE_C2[i][6]
        slope = abs(math.log(curve.cycles_to_failure((s + 0.5) * MPA)
                             / curve.cycles_to_failure((s - 0.5) * MPA)))
        tol = slope + _digit(n_i, 3) / n_i
        q.append(Quantity(f"cycles to failure N_i, bin {k} ({s} N/mm^2)", "-", n_i,
                          float(d.cycles_to_failure[i]), "relative", tol,
                          f"the change 1 N/mm^2 of printed stress makes ({slope * 100:.2f} "
                          "%) plus N_i's 3-digit rounding"))
    q += [Quantity("damage sum D", "-", 1.0, d.total, "absolute", 3e-3,
                   "the stresses' 1 N/mm^2 rounding (2.2e-4) on the finite-life slope of "
                   "13.2; the printed U_i add up to 0.99945"),
          Quantity("spectrum safety factor S_H", "-", 1.0, d.safety, "absolute", 2.2e-4,
                   "1 N/mm^2 in the ~2300 N/mm^2 of the bins carrying the damage")]
    bins = [row[0] for row in TABLE_C2]
    plot = Plot("ISO 6336-6 Annex C, Table C.2: cycles to failure per bin", "bin [-]",
                "log10 of cycles to failure N_i [-]",
                (Series("ISO 6336-6 Table C.2", bins, np.log10([r[6] for r in TABLE_C2]), "o"),
                 Series("gearpipe", bins, np.log10(d.cycles_to_failure), "x")))
    inputs = (("material", "case carburized, sigma_Hlim 1500 N/mm^2, Z_L 1.02, Z_v 0.943, "
                           "Z_R 1.01, Z_W = Z_X = 1"),
              ("spectrum", f"42 torque bins (5.8 to 25.4 kN m) at {SPEED_RPM:g} rpm, 70 days "
                           "measured, extrapolated to 30 years"),
              ("stresses", "the table's sigma_H S_H per bin (to 1 N/mm^2)"))
    return Outcome("ISO 6336-6:2019, Annex C, Table C.2 (example calculation for the safety "
                   "factor from a load spectrum), as transcribed in gfsReboucas/Drivetrain "
                   "data/table_C2.csv", inputs, tuple(q), plots=(plot,),
                   notes="Z_NT continues the finite-life slope above 1.6 before 10^5 cycles "
                         "(bins 3-6), as the table's N_i do.")
