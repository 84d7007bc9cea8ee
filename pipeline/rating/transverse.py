"""Transverse load factors K_Halpha and K_Falpha of ISO 6336-1, method B.

``F_tH = F_t K_A K_gamma K_v K_Hbeta`` and the deviation ``f`` the larger of the base
pitch deviation ``f_pb`` and the profile form deviation ``f_falpha`` (each the larger of
the two gears'), less the running-in allowance ``y_alpha`` of ``f_pb``
(:func:`pipeline.rating.dynamic.running_in`):

* ``eps_gamma <= 2``: ``K_Halpha = K_Falpha = eps_gamma / 2 (0.9 + 0.4 c_gamma_alpha (f -
  y_alpha) / (F_tH / b))``;
* ``eps_gamma > 2``: ``K_Halpha = K_Falpha = 0.9 + 0.4 sqrt(2 (eps_gamma - 1) / eps_gamma)
  c_gamma_alpha (f - y_alpha) / (F_tH / b)``;
* at least 1, ``K_Halpha`` at most ``eps_gamma / (eps_alpha Z_eps^2)`` and ``K_Falpha`` at
  most ``eps_gamma / (0.25 eps_alpha + 0.75)``.

The larger of ``f_pb`` and ``f_falpha`` (rather than ``f_pb`` alone) follows ISO 6336-1:2006
as KISSsoft applies it: its report of the NREL 5 MW gearbox's parallel helical stage prints
1.069, which this reproduces, where ``f_pb`` alone gives 1.020
(``tests/test_rating_transverse.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.validation import check_range


@dataclass(frozen=True)
class TransverseLoadFactors:
    """K_Halpha, K_Falpha and the values before their limits (-)."""

    k_halpha: float
    k_falpha: float
    unlimited: float
    limit_h: float
    limit_f: float


def transverse_load_factors(*, mesh_stiffness: float, base_pitch_deviation: float,
                            form_deviation: float, allowance: float, line_load_h: float,
                            transverse_contact_ratio: float, total_contact_ratio: float,
                            contact_ratio_factor: float) -> TransverseLoadFactors:
    """K_Halpha and K_Falpha of method B (SI): ``c_gamma_alpha`` (N/m^2), ``f_pb`` and
    ``f_falpha`` (m, each the larger of the two gears'), ``y_alpha`` (m), ``F_tH / b``
    (N/m), ``eps_alpha``, ``eps_gamma`` and ``Z_eps``."""
    check_range("rating.line_load_h", line_load_h, 0.0, math.inf, lo_open=True, unit="N/m")
    deviation = max(base_pitch_deviation, form_deviation) - allowance
    term = 0.4 * mesh_stiffness * deviation / line_load_h
    eg, ea = total_contact_ratio, transverse_contact_ratio
    if eg <= 2.0:
        k = eg / 2.0 * (0.9 + term)
    else:
        k = 0.9 + math.sqrt(2.0 * (eg - 1.0) / eg) * term
    limit_h = eg / (ea * contact_ratio_factor**2)
    limit_f = eg / (0.25 * ea + 0.75)
    return TransverseLoadFactors(max(1.0, min(k, limit_h)), max(1.0, min(k, limit_f)), k,
                                 limit_h, limit_f)
