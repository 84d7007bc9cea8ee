"""Tooth root bending strength of ISO 6336-3, method B: root stress, permissible root
stress and the safety factor S_F of each gear.

SI inside (m, N, Pa); the standard's formulas are in mm and N/mm^2 where a factor holds a
dimensional constant, converted at that line.

* Nominal root stress ``sigma_F0 = F_t / (b m_n) Y_F Y_S Y_beta Y_B Y_DT``
  (:mod:`pipeline.contact.iso_root_stress`: the form factor, stress correction factor and
  helix factor of method B, the load at the outer point of single pair contact);
* face load factor ``K_Fbeta = K_Hbeta^N_F`` with ``N_F = (b/h)^2 / (1 + b/h + (b/h)^2)``,
  ``b/h`` the face width over the tooth depth, at least 3 (ISO 6336-1:2019, 8.3.3);
* ``sigma_F = sigma_F0 K_A K_gamma K_v K_Fbeta K_Falpha``;
* ``sigma_FG = sigma_Flim Y_ST Y_NT Y_deltarelT Y_RrelT Y_X Y_M`` (``Y_ST = 2``; ``Y_M``
  0.7 for an idler such as a planet, 1 otherwise), ``sigma_FP =
  sigma_FG / S_Fmin`` and ``S_F = sigma_FG / sigma_F``, with
  - the life factor ``Y_NT`` on the material's line (:data:`LIFE_LINES`, log-log between
    the table's points, down to 0.85 at 10^10 cycles or 1.0 under optimum conditions);
  - the relative notch sensitivity ``Y_deltarelT = (1 + sqrt(rho' chi*)) / (1 + sqrt(rho'
    chi*_T))``, ``chi* = (1 + 2 q_s) / 5``, ``chi*_T = 1.2`` (the test gear's ``q_sT =
    2.5``), ``rho'`` the material's slip-layer thickness (case-hardened steel 0.0030 mm);
  - the relative surface factor ``Y_RrelT``: for steels ``1.674 - 0.529 (R_z + 1)^0.1``
    (``1 <= R_z <= 40`` um, root roughness), 1.120 below 1 um;
  - the size factor ``Y_X``: case-hardened and nitrided steels ``1.05 - 0.01 m_n`` for
    ``5 < m_n < 25`` mm (1 at or below 5, 0.8 from 25); through-hardened steels ``1.03 -
    0.006 m_n`` below 30 mm (0.85 from 30).

Limited life (fewer load cycles than the knee, 3 x 10^6, :mod:`.life`): ``Y_deltarelT``,
``Y_RrelT`` and ``Y_X`` run log-log from their endurance values at the knee to their static
values at the line's first point (10^3 cycles for case-hardened and nitrided steels, 10^4
for through-hardened ones), with the weight of ``Y_NT``'s own interpolation, so that
``sigma_FG`` runs log-log between its static and endurance values. Static values
(DIN 3990-11, section 5.6, equation 5.18 and table 5.1, as transcribed in the public
repository hanslhansl/din3990, ``din3990/din3990_11.py``; :func:`static_notch_sensitivity`):

* ``Y_deltarelT,stat``: case-hardened, induction- or flame-hardened steel ``0.44 Y_S +
  0.12``; nitrided and nitrocarburized steels ``0.20 Y_S + 0.60``; through-hardened steel
  ``(1 + 0.82 (Y_S - 1) (300 / sigma_0.2)^(1/4)) / (1 + 0.82 (300 / sigma_0.2)^(1/4))``
  (``sigma_0.2`` the 0.2 % proof stress in N/mm^2); ``Y_S`` the stress correction factor at
  the load's point (method B);
* ``Y_RrelT,stat = 1``, ``Y_X,stat = 1``.

Checked against KISSsoft's report of the NREL 5 MW reference gearbox's parallel stage
(``tests/test_rating_bending.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.contact.iso_root_stress import IsoRootStress
from pipeline.rating.life import (
    StrengthCurve,
    life_factor_on,
    limited_life_value,
    static_weight,
)
from pipeline.validation import InputError, check_choice, check_range

LIFE_LINES: dict[str, tuple[tuple[float, float], ...]] = {
    "hardened": ((1e3, 2.5), (3e6, 1.0), (1e10, 0.85)),
    "through_hardened": ((1e4, 2.5), (3e6, 1.0), (1e10, 0.85)),
    "nitrided": ((1e3, 1.6), (3e6, 1.0), (1e10, 0.85)),
    "nitrocarburized": ((1e3, 1.1), (3e6, 1.0), (1e10, 0.85)),
}
"""ISO 6336-3 life factor lines (clause 12, table): ``hardened`` Eh, IF (root);
``through_hardened`` St, V, GGG (perl., bai.), GTS (perl.); ``nitrided`` NT, NV (nitr.),
GG, GGG (ferr.); ``nitrocarburized`` NV (nitrocar.). (load cycles, Y_NT) at the table's
points."""
KNEE = 3e6
"""Endurance knee of the bending life lines, load cycles."""
SIZE_CLASSES = ("hardened", "through_hardened", "cast_iron")


def life_factor(cycles: float, line: str, optimum: bool = False) -> float:
    """``Y_NT`` at ``cycles`` load cycles on the material ``line`` (:data:`LIFE_LINES`)."""
    check_choice("rating.bending_life_line", line, tuple(LIFE_LINES))
    return life_factor_on(LIFE_LINES[line], cycles, optimum)


def static_notch_sensitivity(y_s: float, line: str, proof_stress: float | None = None
                             ) -> float:
    """``Y_deltarelT,stat`` for the stress correction factor ``Y_S`` on the material's life
    ``line``; a through-hardened steel needs its 0.2 % ``proof_stress`` (Pa)."""
    check_choice("rating.bending_life_line", line, tuple(LIFE_LINES))
    if line == "hardened":
        return 0.44 * y_s + 0.12
    if line in ("nitrided", "nitrocarburized"):
        return 0.20 * y_s + 0.60
    if proof_stress is None:
        raise InputError("rating.proof_stress is required for a through-hardened gear "
                         "below the bending endurance knee (3e+06 load cycles): it sets the "
                         "static notch sensitivity Y_deltarelT,stat")
    check_range("rating.proof_stress", proof_stress, 100e6, 2500e6, unit="Pa")
    k = 0.82 * (300e6 / proof_stress) ** 0.25
    return (1.0 + k * (y_s - 1.0)) / (1.0 + k)


def face_load_factor(k_hbeta: float, face_width: float, tooth_height: float) -> float:
    """``K_Fbeta = K_Hbeta^N_F`` for the face width and tooth height (m)."""
    check_range("rating.K_Hbeta", k_hbeta, 1.0, 10.0)
    r = max(face_width / tooth_height, 3.0)
    return k_hbeta ** (r * r / (1.0 + r + r * r))


def notch_sensitivity(q_s: float, slip_layer: float) -> float:
    """``Y_deltarelT`` for the notch parameter ``q_s`` and the slip-layer thickness ``rho'``
    (m)."""
    rho = slip_layer * 1e3  # mm
    chi = (1.0 + 2.0 * q_s) / 5.0
    return (1.0 + math.sqrt(rho * chi)) / (1.0 + math.sqrt(rho * 1.2))


def surface_factor(root_roughness: float) -> float:
    """``Y_RrelT`` of a steel root with peak-to-valley roughness ``R_z`` (m)."""
    rz = root_roughness * 1e6
    check_range("rating.root_roughness_rz", rz, 0.0, 40.0, lo_open=True, unit="um")
    return 1.120 if rz < 1.0 else 1.674 - 0.529 * (rz + 1.0) ** 0.1


def size_factor(module: float, size_class: str) -> float:
    """``Y_X`` for the normal module (m) of a ``"hardened"`` (case-hardened, nitrided),
    ``"through_hardened"`` steel or ``"cast_iron"`` (GG, GGG ferr.) gear."""
    check_choice("rating.size_class", size_class, SIZE_CLASSES)
    m = module * 1e3
    if size_class == "hardened":
        return 1.0 if m <= 5.0 else 0.8 if m >= 25.0 else 1.05 - 0.01 * m
    if size_class == "cast_iron":
        return 1.0 if m <= 5.0 else 0.7 if m >= 25.0 else 1.075 - 0.015 * m
    return 1.0 if m <= 5.0 else 0.85 if m >= 30.0 else 1.03 - 0.006 * m


@dataclass(frozen=True)
class BendingSafety:
    """Root stress, permissible root stress and safety of one gear (SI).

    Attributes
    ----------
    nominal : sigma_F0, Pa (from :class:`~pipeline.contact.iso_root_stress.IsoRootStress`).
    load_factor : K_A K_gamma K_v K_Fbeta K_Falpha (-).
    stress : sigma_F, Pa.
    life_factor, notch_factor, surface_factor, size_factor, mean_stress_factor : Y_NT,
        Y_deltarelT, Y_RrelT, Y_X, Y_M (-) at the gear's load cycles (below the knee the
        limited-life values of Y_deltarelT, Y_RrelT, Y_X).
    limit : sigma_FG, Pa; permissible : sigma_FP, Pa; safety : S_F (-).
    """

    nominal: float
    load_factor: float
    stress: float
    life_factor: float
    notch_factor: float
    surface_factor: float
    size_factor: float
    mean_stress_factor: float
    limit: float
    permissible: float
    safety: float


def _check_strength(sigma_flim: float, mean_stress_factor: float, line: str) -> None:
    check_range("rating.sigma_Flim", sigma_flim, 100e6, 1000e6, unit="Pa")
    check_range("rating.Y_M", mean_stress_factor, 0.5, 1.0)
    check_choice("rating.bending_life_line", line, tuple(LIFE_LINES))


def strength_curve(root: IsoRootStress, sigma_flim: float, line: str, slip_layer: float,
                   root_roughness: float, size_class: str, module: float,
                   optimum: bool = False, mean_stress_factor: float = 1.0,
                   proof_stress: float | None = None) -> StrengthCurve:
    """The S-N line ``sigma_FG(N)`` of a gear (arguments as :func:`bending_safety`): the
    life ``line``, ``sigma_Flim Y_ST Y_M``, the endurance product ``Y_deltarelT Y_RrelT
    Y_X`` and its static value ``Y_deltarelT,stat`` (a through-hardened gear needs its
    ``proof_stress``, Pa, for it)."""
    _check_strength(sigma_flim, mean_stress_factor, line)
    influence = (notch_sensitivity(root.q_s, slip_layer) * surface_factor(root_roughness)
                 * size_factor(module, size_class))
    return StrengthCurve(LIFE_LINES[line], sigma_flim * 2.0 * mean_stress_factor, influence,
                         static_notch_sensitivity(root.y_s, line, proof_stress), optimum)


def bending_safety(root: IsoRootStress, load_factor: float, sigma_flim: float, cycles: float,
                   line: str, slip_layer: float, root_roughness: float, size_class: str,
                   module: float, minimum_safety: float = 1.4, optimum: bool = False,
                   mean_stress_factor: float = 1.0, proof_stress: float | None = None
                   ) -> BendingSafety:
    """``sigma_F``, ``sigma_FP`` and ``S_F`` of a gear from its method-B nominal ``root``
    stress, the product ``K_A K_gamma K_v K_Fbeta K_Falpha``, its ``sigma_Flim`` (Pa, the
    test gear's, without ``Y_ST``), ``cycles`` on the life ``line``, the slip-layer
    thickness (m), the root roughness ``R_z`` (m), the size class and normal module (m);
    ``mean_stress_factor`` ``Y_M`` (1 for a pulsating load, 0.7 for an idler's
    alternating one, ISO 6336-3:2019). Below the knee ``Y_deltarelT``, ``Y_RrelT`` and
    ``Y_X`` are their limited-life values; a through-hardened gear there needs its 0.2 %
    ``proof_stress`` (Pa) for ``Y_deltarelT,stat``."""
    check_range("rating.load_factor", load_factor, 1.0, 10.0)
    check_range("rating.minimum_safety_bending", minimum_safety, 0.5, 5.0)
    _check_strength(sigma_flim, mean_stress_factor, line)
    w = static_weight(LIFE_LINES[line], cycles)
    ynt = life_factor(cycles, line, optimum)
    yd = notch_sensitivity(root.q_s, slip_layer)
    if w > 0.0:  # the static value matters only below the knee
        yd = limited_life_value(yd, static_notch_sensitivity(root.y_s, line, proof_stress), w)
    yr = limited_life_value(surface_factor(root_roughness), 1.0, w)
    yx = limited_life_value(size_factor(module, size_class), 1.0, w)
    limit = sigma_flim * 2.0 * ynt * yd * yr * yx * mean_stress_factor
    stress = root.sigma_f0 * load_factor
    return BendingSafety(root.sigma_f0, load_factor, stress, ynt, yd, yr, yx,
                         mean_stress_factor, limit, limit / minimum_safety, limit / stress)
