"""Tooth stiffness of ISO 6336-1 (method B) and the contact-line method of Yang et al. (2026),
section 3.1.

ISO 6336-1:2019, 9.3:

* theoretical single stiffness ``c'_th = 1 / q'`` with (Yang et al. 2026, eq. 33)
  ``q' = 0.04723 + 0.15551/z_n1 + 0.25791/z_n2 - 0.00635 x1 - 0.11654 x1/z_n1
  - 0.00193 x2 - 0.24188 x2/z_n2 + 0.00529 x1^2 + 0.00182 x2^2`` in mm um/N,
  z_n the virtual tooth numbers (``z_n2 = inf`` for an internal gear);
* single stiffness ``c' = c'_th C_M C_R C_B cos(beta)``, times
  ``(F_t K_A / b / 100)^0.25`` below 100 N/mm;
* mesh stiffness ``c_gamma_alpha = c' (0.75 eps_alpha + 0.25)``, and
  ``c_gamma_beta = 0.85 c_gamma_alpha``.

Gear numbering follows ISO 6336-1: gear 1 is the one with fewer virtual teeth,
``z_n1 <= z_n2``, and an internal gear is always gear 2 (``z_n2 = inf``), whatever order the
pair gives them (:func:`iso_gears`); a sun with more teeth than its planets is gear 2 of its
mesh. The basic rack factor is ``C_B = (C_B1 + C_B2) / 2`` with
``C_Bi = (1 + 0.5 (1.2 - h_fPi / m_n)) (1 - 0.02 (20 deg - alpha_n))``.

Stiffness per unit face width is N/(mm um) in the standard; here everything is
returned in SI (N/m per m of face width, i.e. N/m^2; multiply by the face width
in m for N/m). For herringbone gears every value refers to one helical half.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.validation import check_range

N_PER_MM_UM = 1e9  # 1 N/(mm um) = 1e9 N/m^2


@dataclass(frozen=True)
class IsoStiffness:
    """ISO 6336-1 stiffness values, SI.

    Attributes
    ----------
    q_prime : minimum flexibility q', m^2/N (i.e. mm um/N * 1e-9).
    c_th : theoretical single stiffness per unit face width, N/m^2.
    c_single : single stiffness c' per unit face width, N/m^2.
    c_gamma_alpha : mean mesh stiffness per unit face width, N/m^2.
    c_gamma_beta : 0.85 c_gamma_alpha, N/m^2.
    face_width : b, m.
    factors : the factors C_M, C_R, C_B, cos(beta) and the load factor used.
    gear_1 : name of the gear the standard numbers 1 (fewer virtual teeth), for reports.
    """

    q_prime: float
    c_th: float
    c_single: float
    c_gamma_alpha: float
    c_gamma_beta: float
    face_width: float
    factors: dict[str, float]
    gear_1: str = ""

    @property
    def single_pair_stiffness(self) -> float:
        """c' b, maximum single-pair stiffness, N/m."""
        return self.c_single * self.face_width

    @property
    def mesh_stiffness(self) -> float:
        """c_gamma_alpha b, mean mesh stiffness, N/m."""
        return self.c_gamma_alpha * self.face_width


def q_prime(zn1: float, zn2: float, x1: float, x2: float) -> float:
    """ISO 6336-1 eq. (98) flexibility q' in mm um/N (``zn2 = inf`` for internal gears)."""
    i1 = 1.0 / zn1
    i2 = 0.0 if math.isinf(zn2) else 1.0 / zn2
    return (0.04723 + 0.15551 * i1 + 0.25791 * i2 - 0.00635 * x1 - 0.11654 * x1 * i1
            - 0.00193 * x2 - 0.24188 * x2 * i2 + 0.00529 * x1**2 + 0.00182 * x2**2)


def iso_gears(pair: GearPair) -> tuple[GearSpec, GearSpec]:
    """ISO 6336-1's gear 1 and gear 2 of a pair: gear 1 has fewer virtual teeth (z_n1 <= z_n2;
    the pinion on a tie), an internal gear is gear 2."""
    p, g = pair.pinion, pair.gear
    if g.internal or p.equivalent_teeth <= g.equivalent_teeth:
        return p, g
    return g, p


def basic_rack_factor(gear: GearSpec) -> float:
    """C_B of one gear's basic rack: ``(1 + 0.5 (1.2 - h_fP/m_n)) (1 - 0.02 (20 - alpha_n))``,
    alpha_n in degrees."""
    return (1.0 + 0.5 * (1.2 - gear.dedendum_coef)) * (
        1.0 - 0.02 * (20.0 - math.degrees(gear.pressure_angle)))


def blank_factor_cr(rim_thickness_ratio: float | None, web_ratio: float | None) -> float:
    """C_R gear blank factor: 1 for solid discs, else ``1 + ln(b_s/b) / (5 exp(s_R / (5 m_n)))``.

    ``web_ratio`` = b_s / b (web over face width) in [0.2, 1.2]; ``rim_thickness_ratio`` =
    s_R / m_n in [1, ...]. Pass ``None`` for a solid disc.
    """
    if web_ratio is None or rim_thickness_ratio is None:
        return 1.0
    check_range("iso.web_ratio", web_ratio, 0.2, 1.2)
    check_range("iso.rim_thickness_ratio", rim_thickness_ratio, 1.0, 1e3)
    return 1.0 + math.log(web_ratio) / (5.0 * math.exp(rim_thickness_ratio / 5.0))


def iso_stiffness(
    pair: GearPair,
    tangential_load: float | None = None,
    application_factor: float = 1.0,
    c_m: float = 0.8,
    c_r: float = 1.0,
) -> IsoStiffness:
    """ISO 6336-1 method B single and mesh stiffness of a pair.

    Parameters
    ----------
    pair : the gear pair, in any order (ISO numbering by :func:`iso_gears`).
    tangential_load : F_t in N at the reference circle (for the load correction
        below 100 N/mm); ``None`` assumes at least 100 N/mm.
    application_factor : K_A (-).
    c_m : theoretical correction factor C_M (0.8 for solid discs in ISO).
    c_r : gear blank factor C_R (see :func:`blank_factor_cr`).
    """
    g1, g2 = iso_gears(pair)
    zn2 = math.inf if g2.internal else g2.equivalent_teeth
    q = q_prime(g1.equivalent_teeth, zn2, g1.profile_shift, g2.profile_shift)
    c_th = 1.0 / q
    c_b = 0.5 * (basic_rack_factor(g1) + basic_rack_factor(g2))
    p = pair.pinion
    cos_b = math.cos(p.helix_angle)
    b = pair.face_width  # one helical half for herringbone gears
    load = 1.0
    if tangential_load is not None:
        w = tangential_load * application_factor / (b * 1e3)  # N/mm
        if w < 100.0:
            load = (w / 100.0) ** 0.25
    c1 = c_th * c_m * c_r * c_b * cos_b * load
    cga = c1 * (0.75 * pair.transverse_contact_ratio + 0.25)
    return IsoStiffness(
        q_prime=q * 1e-9,
        c_th=c_th * N_PER_MM_UM,
        c_single=c1 * N_PER_MM_UM,
        c_gamma_alpha=cga * N_PER_MM_UM,
        c_gamma_beta=0.85 * cga * N_PER_MM_UM,
        face_width=b,
        factors={"C_M": c_m, "C_R": c_r, "C_B": c_b, "cos_beta": cos_b, "load": load},
        gear_1=g1.name,
    )


@dataclass(frozen=True)
class ContactLineStiffness:
    """Mesh stiffness of the contact-line method over one mesh cycle.

    Attributes
    ----------
    s0 : shape (m,), roll coordinate of the leading pair, m.
    contact_length : shape (m,), total contact line length L(t), m.
    total : shape (m,), k_m(t) = k_ym L(t), N/m.
    k_per_length : k_ym, stiffness per unit contact line length, N/m^2.
    iso : the ISO stiffness it is built on.
    """

    s0: np.ndarray
    contact_length: np.ndarray
    total: np.ndarray
    k_per_length: float
    iso: IsoStiffness


def contact_line_stiffness(pair: GearPair, positions: int = 360,
                           tangential_load: float | None = None) -> ContactLineStiffness:
    """Contact-line method (Yang et al. 2026, section 3.1): k_m(t) proportional to L(t).

    Yang et al. (2026) write ``k_ym = k_y B / L_max`` with ``k_y = (0.75 eps_alpha + 0.25) c'``;
    taken literally its mean ``k_ym <L>`` exceeds the ISO mean mesh stiffness
    ``c_gamma_alpha b`` by ``<L>/L_max`` (= eps_alpha for spur gears). We keep the
    method's premise (k proportional to contact length) and normalise it so that
    the mean over the cycle equals ISO's ``c_gamma_alpha b``:
    ``k_ym = c_gamma_alpha b / <L>``.
    """
    iso = iso_stiffness(pair, tangential_load)
    s0 = pair.mesh_cycle(positions)
    length = pair.contact_line_lengths(s0).sum(axis=1)
    k_ym = iso.mesh_stiffness / length.mean()
    return ContactLineStiffness(s0, length, k_ym * length, k_ym, iso)
