"""Xu et al. (2020)'s published left/right sun-planet mesh stiffness change, as a comparison.

This is the paper's Fig. 5 taken as input data, kept to compare with the paper's own
model (``wind_turbine_herringbone_model(groove_mesh=XU2020_GROOVE_MESH)``,
``workflows/dynamics_herringbone_sweep.py``). The pipeline computes the effect instead:
the groove's FE stiffness and the loaded contact of both halves through it
(:mod:`pipeline.contact.herringbone`, :mod:`pipeline.dynamics.herringbone_excitation`,
``workflows/herringbone_groove_study.py``), for any groove the FE can analyse.

Xu et al. (2020) make the left and right sun-planet mesh stiffness
depend on the torsional stiffness K_j of the sun's relief groove:

* eq. 1: the relative twist of the sun halves is ``phi_LRj = T_s l / K_j``
  (K_j = G_j I_j in N m^2, l the torsion length in m), so ``phi_LRj ~ 1 / K_j``;
* eq. 11: the twist gives the left/right meshing phase
  ``lambda_LRj = dec(z_s phi_LRj / 2 pi)`` (already in
  :mod:`pipeline.dynamics.models.wind_turbine_planetary`);
* eq. 14: ``k_Lsn(t) = k_0Ls L(t - lambda_sn T_m)`` and
  ``k_Rsn(t) = k_0Rs L(t - (lambda_sn + lambda_LRj) T_m)``, with *side-specific*
  stiffness per unit contact-line length k_0Ls, k_0Rs; eq. 15: the ring-planet
  meshes do not depend on K_j;
* sec. 3.1 and Fig. 5: from K_1 = 5.2e7 to K_5 = 4.0e7 N m^2 the maximum left
  sun-planet mesh stiffness rises by 9.79 % and the right one falls by 11.23 %;
  the left rises and the right falls monotonically as K_j decreases.

A phase shift (eq. 11) cannot change the maximum of ``k_0 L(t)``, so in eq. 14
the change of the maximum must sit in k_0Ls and k_0Rs. The paper does not say
how k_0Ls(K_j), k_0Rs(K_j) are computed (the text points to the potential
energy of eq. 5 and the tooth load of eq. 25, without a formula). This module
therefore takes the published percentages as data and adds two assumptions:

1. The side factors are linear in the twist of eq. 1, i.e. in ``1 / K_j``:
   ``k_0is(K_j) / k_0is(K_1) = 1 + p_i (K_1 / K_j - 1) / (K_1 / K_5 - 1)``
   with ``p_L = +0.0979`` and ``p_R = -0.1123``. This reproduces the two
   published end points exactly and is monotonic in between (Fig. 5 shows
   K_2..K_4 only as curves, without numbers).
2. The reference is K_1: at K_1 both halves keep the nominal (equal) mesh
   stiffness of the case. Anchoring instead at a rigid groove (1 / K_j = 0,
   where the paper says the halves are symmetric) and extrapolating linearly
   in the twist would need ``k_L / k_R = 2.0`` at K_1, which contradicts the
   near-equal sides the paper reports at K_1 (tooth load 880 vs 850 N/mm,
   Fig. 8; load factors 1.04 vs 1.03, Fig. 7).

Outside ``[K_5, K_1]`` the paper gives no data, so the relation refuses such
values (:class:`~pipeline.validation.InputError`) rather than extrapolate.
The factors scale the whole signal k_0 L(t), hence its maximum and its mean
by the same ratio; the mean of the two sides changes by only
``(p_L + p_R) / 2 = -0.72 %`` at K_5.
"""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.validation import InputError, check_positive, check_range


@dataclass(frozen=True)
class GrooveMeshRelation:
    """Side factors of the sun-planet mesh stiffness against K_j (Xu et al. 2020, eq. 14, Fig. 5).

    Attributes
    ----------
    reference_Kj : K_1, groove torsional stiffness G I where both sides have the
        nominal mesh stiffness, N m^2.
    calibration_Kj : K_5 < K_1, where the published changes apply, N m^2.
    change_left : relative change of the maximum left sun-planet mesh stiffness
        from K_1 to K_5 (-); Xu et al. (2020): +0.0979.
    change_right : same for the right side (-); Xu et al. (2020): -0.1123.
    """

    reference_Kj: float = 5.2e7
    calibration_Kj: float = 4.0e7
    change_left: float = 0.0979
    change_right: float = -0.1123

    def __post_init__(self) -> None:
        check_positive("reference_Kj", self.reference_Kj, "N m^2")
        check_range(
            "calibration_Kj",
            self.calibration_Kj,
            0.0,
            self.reference_Kj,
            lo_open=True,
            hi_open=True,
            unit="N m^2",
        )
        for f in ("change_left", "change_right"):
            check_range(f, getattr(self, f), -1.0, 1.0, lo_open=True, hi_open=True)


XU2020_GROOVE_MESH = GrooveMeshRelation()
"""The relation with Xu et al. (2020)'s published values (K_1 = 5.2e7, K_5 = 4.0e7 N m^2)."""


@dataclass(frozen=True)
class SideFactors:
    """Sun-planet mesh stiffness of each half relative to its value at K_1.

    Attributes
    ----------
    Kj : groove torsional stiffness, N m^2.
    twist_fraction : ``(K_1 / K_j - 1) / (K_1 / K_5 - 1)``: the extra twist of eq. 1
        relative to its extra at K_5 (0 at K_1, 1 at K_5), -.
    left, right : k_0Ls(K_j) / k_0Ls(K_1) and k_0Rs(K_j) / k_0Rs(K_1), -.
    """

    Kj: float
    twist_fraction: float
    left: float
    right: float

    @property
    def mean(self) -> float:
        """(left + right) / 2, the change of the summed sun-mesh stiffness (-)."""
        return 0.5 * (self.left + self.right)


def side_factors(Kj: float, relation: GrooveMeshRelation = XU2020_GROOVE_MESH) -> SideFactors:
    """Left and right sun-planet mesh stiffness factors at groove stiffness ``Kj``.

    Parameters
    ----------
    Kj : groove torsional stiffness G I, N m^2, within
        ``[relation.calibration_Kj, relation.reference_Kj]`` (the range the paper covers).
    relation : the calibrated relation (default: Xu et al. (2020)'s published values).

    Returns
    -------
    :class:`SideFactors`; multiply the nominal sun-planet mesh stiffness signal of each
    half by ``left`` / ``right``.

    Raises
    ------
    InputError
        ``Kj`` outside the calibrated range, named as ``groove_Kj``.
    """
    lo, hi = relation.calibration_Kj, relation.reference_Kj
    try:
        check_range("groove_Kj", Kj, lo, hi, unit="N m^2")
    except InputError as e:
        raise InputError(
            f"{e} (Xu et al. 2020 give the left/right mesh stiffness change only for K_j in "
            "this range; pass groove_mesh=None for equal sides)"
        ) from None
    s = (hi / float(Kj) - 1.0) / (hi / lo - 1.0)
    return SideFactors(
        Kj=float(Kj),
        twist_fraction=s,
        left=1.0 + relation.change_left * s,
        right=1.0 + relation.change_right * s,
    )
