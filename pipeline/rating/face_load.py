"""Face load factor K_Hbeta of ISO 6336-1, method C (ISO 6336-1:2006, 7.5 and 7.6).

SI inside (m, N, Pa); the standard writes its formulas in N, mm, um and N/(mm um), and
each dimensional constant is converted on the line that uses it. Equation numbers are
those of ISO 6336-1:2006.

* Mean line load ``F_m / b`` with ``F_m = F_t K_A K_gamma K_v`` (the caller's; N/m).
* Component of the equivalent misalignment from the pinion and its shaft bending and
  twisting (7.5.2.4.1), Eq. (57) for spur and single helical gears::

      f_sh = F_m/b 0.023 [|B* + K' l s / d1^2 (d1 / d_sh)^4 - 0.3| + 0.3] (b / d1)^2

  (um with N/mm and mm), Eq. (58) for double helical gears with 0.046 and ``b_B`` (the
  width of one helix, here ``b / 2``) in the last factor. ``l`` the bearing span, ``s``
  the pinion's offset from mid-span, ``d_sh`` the shaft's outside diameter for bending,
  ``d1`` the pinion's reference diameter; ``K'`` of Figure 13 by arrangement a-e
  (:data:`ARRANGEMENTS`), the stiffened value when the pinion body stiffens the shaft
  (``d1 / d_sh >= 1.15`` and the pinion integral with it or firmly fixed; not for a
  pinion sliding on a feather key or a normal shrink fit). ``B* = 1`` (1.5 double
  helical) for one power path; with ``k`` per cent of the power through this mesh ``B* =
  1 + 2 (100 - k) / k`` (``0.5 + (200 - k) / k`` double helical). Valid for ``s / l <=
  0.3``, a steel shaft of constant diameter with a bore under half of it (else a warning).
* What Eq. (57) assumes, against the beam shaft of :mod:`pipeline.shaft` (rigid bearings,
  the face's uniform load, the misalignment as the rise of the least-squares line through
  the gap in the plane of action; ``tests/test_shaft_iso_fsh.py``): the bracket's ``-0.3``
  and ``+0.3`` leave ``0.7 x 0.023 = 0.0161`` um mm/N to cancel, which is a body of
  diameter ``d1`` twisted by its own face load and read at the reference circle, ``4 / (pi
  G)`` = 0.01607 (the beam reads it along the line of action: ``cos(alpha)`` of it); the
  other 0.3 stays whatever the bending does (a pinion at mid-span bows symmetrically and
  tilts by nothing). The ``K'`` term is a shaft of ``d_sh`` bent by the face's load at ``s``
  from mid-span, ``F s (l^2 - 4 s^2) / (6 E I l)``: the unstiffened 0.8 is its small-``s``
  slope to 5 %, without the ``1 - 4 (s / l)^2`` (0.64 at ``s / l = 0.3``). Figure 13's
  ``a`` and ``b`` differ in sign only: bending tilts the face the way torsion does (load
  at the face end nearest the torque, ``K' > 0``) when the pinion sits off-centre towards
  the torque's end. The stiffened ``K'`` takes 40 % off, where a body of ``1.5 d_sh`` over
  ``b = l / 10`` takes 13 % (an infinitely stiff one 15 %). Read as an overhung pinion
  (``K'`` the same with and without stiffening, ``s`` its overhang), ``c``'s ``1.33 l s``
  falls below the beam's ``s (2 l + 3 s) / 6`` (1.3 to 1.5 at ``s / l`` 0.1 to 0.2); ``d``
  and ``e`` hold more than one pinion on a plain shaft (the figure's sketches were not at
  hand). Computed over ISO for a plain shaft of ``d1``: 0.66 at ``s = 0``, 0.87 to 0.60 for
  ``a``, ``b`` at ``s / l`` 0.05 to 0.3: Eq. (57) errs on the safe side between the
  bearings, not for an overhung or a stiffened pinion.
* Mesh misalignment from manufacture ``f_ma``: given, or from the helix slope deviations
  ``f_Hbeta`` of the two gears (ISO 1328-1 tolerances, :mod:`.accuracy`) as their root sum
  of squares (``"rss"``) or the larger (``"larger"``) (:data:`F_MA_RULES`).
* Initial equivalent misalignment, Eq. (52) without a proven contact pattern ``F_betax =
  1.33 B1 f_sh + B2 f_ma``, Eq. (53) with a proven favourable one ``F_betax = |1.33 B1
  f_sh - f_Hbeta5|`` (``f_Hbeta5`` the grade 5 helix slope tolerance); ``B1``, ``B2`` of
  Table 8 by helix modification (:data:`HELIX_MODIFICATIONS`); at least ``F_betax,min =
  max(0.005 F_m/b, 0.5 f_Hbeta)`` (Eq. 55, 56; um with N/mm, ``f_Hbeta`` the larger of
  the two gears').
* Running-in allowance ``y_beta`` (Eq. 44-48) per gear (:data:`RUNNING_IN`):
  ``"through_hardened"`` (St, V, GGG perl./bai., GTS perl.) ``320 / sigma_Hlim F_betax``,
  at most ``25600 / sigma_Hlim`` um for ``5 < v <= 10`` m/s and ``12800 / sigma_Hlim`` um
  above; ``"cast_iron"`` (GG, GGG ferr.) ``0.55 F_betax``, at most 45 um and 22 um;
  ``"hardened"`` (Eh, IF, NT, NV) ``0.15 F_betax``, at most 6 um; never more than
  ``F_betax``; a pair of two materials takes the mean of the two gears' values.
  ``F_betay = F_betax - y_beta`` (Eq. 43).
* ``c_gamma_beta = 0.85 c_gamma_alpha`` of method B, taken from
  :func:`pipeline.stiffness.iso6336.iso_stiffness`.
* ``F_betay c_gamma_beta / (2 F_m/b) < 1``: ``K_Hbeta = 1 + F_betay c_gamma_beta / (2 F_m /
  b)`` (Eq. 41), the contact spans the face, ``b_cal / b = 0.5 + (F_m / b) / (F_betay
  c_gamma_beta)`` (Eq. 42); otherwise ``K_Hbeta = sqrt(2 F_betay c_gamma_beta / (F_m / b))
  >= 2`` (Eq. 39), ``b_cal / b = sqrt(2 (F_m / b) / (F_betay c_gamma_beta))`` (Eq. 40).
  Both branches and their slopes meet at ``K_Hbeta = 2``.
* ``K_Fbeta`` from ``K_Hbeta`` by :func:`pipeline.rating.bending.face_load_factor` (7.6;
  the face width of one helix for double helical gears).

Sources: the standard's text was not at hand; the formulas follow public transcriptions
that agree where they overlap (a C# implementation of ISO 6336-1:2006 with its equation
numbers, the MATLAB ISO 6336 classes of Rebouças' Drivetrain, python-gearbox) and DIN
3990-11's equations of the same form. No published example of the whole chain was found:
KISSsoft's reports of the NREL 5 MW gearbox fix K_Hbeta by hand (their ``c_gamma_beta``
15.837 = 0.85 x 18.632 is checked), and ISO/TR 6336-30's example 1 prints K_Hbeta 1.16,
which this gives (1.1596) for a pinion at mid-span with ``f_ma`` the root sum of squares,
inputs the example's shaft data (not available) cannot confirm. The rest is checked
against hand calculations in the standard's units (``tests/test_rating_face_load.py``).
Sources differ on ``f_ma`` (root sum of squares in the MATLAB and python transcriptions,
the larger ``f_Hbeta`` in DIN 3990), on the 6 um cap of ``y_beta`` for hardened gears
(DIN 3990 and one transcription; not in the C# one) and on ``f_Hbeta5`` against
``f_Hbeta6`` in Eq. (53) (a python-gearbox fork cites an erratum for grade 6).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

from pipeline.rating.bending import face_load_factor
from pipeline.validation import InputError, InputWarning, check_choice, check_range

ARRANGEMENTS: dict[str, tuple[float, float]] = {
    "a": (0.48, 0.80),
    "b": (-0.48, -0.80),
    "c": (1.33, 1.33),
    "d": (-0.36, -0.60),
    "e": (-0.60, -1.00),
}
"""``K'`` of ISO 6336-1 Figure 13 per arrangement: (with stiffening, without)."""

HELIX_MODIFICATIONS: dict[str, tuple[float, float]] = {
    "none": (1.0, 1.0),
    "central_crowning": (1.0, 0.5),
    "central_crowning_with_deflection": (0.5, 0.5),
    "helix_correction": (0.1, 1.0),
    "helix_correction_and_crowning": (0.1, 0.5),
    "end_relief": (0.7, 0.7),
}
"""``(B1, B2)`` of ISO 6336-1 Table 8: no modification; central crowning ``C_beta = 0.5
f_ma``; central crowning ``C_beta = 0.5 (f_ma + f_sh)``; helix correction only; helix
correction and central crowning; end relief."""

RUNNING_IN = ("hardened", "through_hardened", "cast_iron")
"""Material groups of the running-in allowance ``y_beta``: case-hardened, induction or
flame hardened, nitrided and nitrocarburized (Eh, IF, NT, NV); through-hardened and
normalized steels, pearlitic or bainitic nodular and pearlitic malleable cast iron (St, V,
GGG, GTS); grey and ferritic nodular cast iron (GG, GGG ferr.)."""

F_MA_RULES = ("rss", "larger")
"""``f_ma`` from the helix slope deviations of the two gears: their root sum of squares,
or the larger."""

STIFFENING_RATIO = 1.15
"""``d1 / d_sh`` from which the pinion body stiffens its shaft (Figure 13)."""
OFFSET_LIMIT = 0.3
"""Largest ``s / l`` of Figure 13."""

# The standard's constants in SI: 1 um mm / N = 1e-9 m^2/N.
SHAFT_COEFFICIENT = 0.023e-9  # m^2/N, Eq. (57); 0.046e-9 for double helical, Eq. (58)
MIN_MISALIGNMENT_COEFFICIENT = 0.005e-9  # m^2/N, Eq. (55)
UM = 1e-6


@dataclass(frozen=True)
class PinionShaft:
    """The pinion's shaft for ``f_sh`` (ISO 6336-1 Figure 13), SI.

    Attributes
    ----------
    span : bearing span ``l``, m (key ``span_mm``).
    offset : distance ``s`` of the pinion's mid-face from the middle of the span, m
        (``offset_mm``; ``0 <= s <= l / 2``, the standard's curves cover ``s / l <= 0.3``).
    diameter : outside diameter ``d_sh`` of the shaft for bending, m (``shaft_diameter_mm``).
    arrangement : "a" to "e" of Figure 13 (where the torque enters relative to the pinion).
    stiffening : False for a pinion that cannot stiffen its shaft (sliding on a feather
        key, a normal shrink fit), True for one integral with the shaft or firmly fixed on
        it, None (the default) for the standard's rule alone; the pinion stiffens the shaft
        when it can and ``d1 / d_sh >= 1.15`` (``stiffening``).
    bore : bore diameter of a hollow shaft, m (``bore_diameter_mm``, 0 for solid).
    where : prefix of the keys in messages (the table the user writes them in).
    """

    span: float
    offset: float
    diameter: float
    arrangement: str
    stiffening: bool | None = None
    bore: float = 0.0
    where: str = field(default="rating.pinion_shaft", compare=False, repr=False)

    def __post_init__(self) -> None:
        w = self.where
        # the largest gearbox shafts (ship and wind drives) stay well inside 20 m and 5 m
        check_range(f"{w}.span_mm", self.span * 1e3, 0.0, 20e3, lo_open=True, unit="mm")
        check_range(f"{w}.shaft_diameter_mm", self.diameter * 1e3, 0.0, 5e3,
                    lo_open=True, unit="mm")
        check_range(f"{w}.offset_mm", self.offset * 1e3, 0.0, 0.5 * self.span * 1e3,
                    unit="mm", note="from the middle of the span to a bearing, span_mm / 2")
        check_range(f"{w}.bore_diameter_mm", self.bore * 1e3, 0.0, self.diameter * 1e3,
                    hi_open=True, unit="mm", note="below shaft_diameter_mm")
        check_choice(f"{w}.arrangement", self.arrangement, tuple(ARRANGEMENTS))
        if self.stiffening is not None and not isinstance(self.stiffening, bool):
            raise InputError(f"{w}.stiffening = {self.stiffening!r} must be true or false")
        if self.offset > OFFSET_LIMIT * self.span:
            ratio = self.offset / self.span
            warnings.warn(f"{w}.offset_mm = {self.offset * 1e3:.6g} mm over span_mm = "
                          f"{self.span * 1e3:.6g} mm gives s/l = {ratio:.4g}, beyond the 0.3 of "
                          "ISO 6336-1 Figure 13: f_sh is outside the standard's validity",
                          InputWarning, stacklevel=2)
        if self.bore >= 0.5 * self.diameter:
            warnings.warn(f"{w}.bore_diameter_mm = {self.bore * 1e3:.6g} mm is at least half of "
                          f"shaft_diameter_mm = {self.diameter * 1e3:.6g} mm: ISO 6336-1 Eq. (57) "
                          "holds for smaller bores, the shaft deflects more than f_sh says",
                          InputWarning, stacklevel=2)


@dataclass(frozen=True)
class FaceLoadInputs:
    """The user's choices for K_Hbeta by method C.

    Attributes
    ----------
    shaft : the pinion shaft, or None for a pinion at mid-span (``s = 0``: the ``K'`` term
        of Eq. (57) vanishes and the shaft's dimensions do not enter).
    helix_modification : a key of :data:`HELIX_MODIFICATIONS` (``helix_modification``).
    contact_pattern_proven : True when a favourable contact pattern under load is proven
        (Eq. 53 instead of Eq. 52; ``contact_pattern_proven``).
    power_share : per cent of the power through this mesh when the pinion's power splits
        (``power_share_percent``), in (0, 100]; None: not given, one path (100) - the
        rating of a planetary set's sun-planet mesh takes 100 / planets then.
    f_ma : the mesh misalignment from manufacture, m (``f_ma_um``), or None for
        ``f_ma_rule``.
    f_ma_rule : :data:`F_MA_RULES` entry used when ``f_ma`` is None (``f_ma_rule``).
    where : prefix of the keys in messages.
    """

    shaft: PinionShaft | None = None
    helix_modification: str = "none"
    contact_pattern_proven: bool = False
    power_share: float | None = None
    f_ma: float | None = None
    f_ma_rule: str | None = None
    where: str = field(default="rating", compare=False, repr=False)

    def __post_init__(self) -> None:
        w = self.where
        check_choice(f"{w}.helix_modification", self.helix_modification,
                     tuple(HELIX_MODIFICATIONS))
        if not isinstance(self.contact_pattern_proven, bool):
            raise InputError(f"{w}.contact_pattern_proven = {self.contact_pattern_proven!r} "
                             "must be true or false")
        if self.power_share is not None:
            check_range(f"{w}.power_share_percent", self.power_share, 0.0, 100.0,
                        lo_open=True, unit="%")
        if self.f_ma is not None and self.f_ma_rule is not None:
            raise InputError(f"{w}: give f_ma_um = {self.f_ma / UM:.6g} um or f_ma_rule = "
                             f"{self.f_ma_rule!r}, not both")
        if self.contact_pattern_proven and (self.f_ma is not None or self.f_ma_rule is not None):
            raise InputError(f"{w}: f_ma_um and f_ma_rule do not enter ISO 6336-1 Eq. (53) of "
                             "a proven contact pattern (contact_pattern_proven = true); remove "
                             "them")
        if self.f_ma is not None:
            check_range(f"{w}.f_ma_um", self.f_ma / UM, 0.0, 1000.0, unit="um")
        else:
            check_choice(f"{w}.f_ma_rule", self.rule, F_MA_RULES)

    @property
    def rule(self) -> str:
        """The ``f_ma`` rule in force (``"rss"`` unless given)."""
        return self.f_ma_rule if self.f_ma_rule is not None else "rss"


@dataclass(frozen=True)
class FaceLoadFactor:
    """K_Hbeta by ISO 6336-1 method C and its intermediates (SI).

    Attributes
    ----------
    line_load : ``F_m / b``, N/m.
    b_star : ``B*`` of Eq. (57)/(58) (-).
    k_prime : ``K'`` of Figure 13 (-), 0 without a shaft.
    stiffened : whether ``K'`` is the stiffened value.
    offset_term : ``K' l s / d1^2 (d1 / d_sh)^4`` (-).
    f_sh : misalignment from the pinion and shaft deflection, Eq. (57)/(58), m.
    f_ma : misalignment from manufacture, m.
    b1, b2 : ``B1``, ``B2`` of Table 8 (-).
    f_beta_x_calculated : ``F_betax`` of Eq. (52) or (53) before its floor, m.
    f_beta_x_min : ``F_betax,min`` of Eq. (55)/(56), m.
    f_beta_x : initial equivalent misalignment ``F_betax``, m.
    y_beta : running-in allowance, Eq. (44)-(48), m.
    f_beta_y : effective equivalent misalignment ``F_betay``, Eq. (43), m.
    c_gamma_beta : mesh stiffness ``c_gamma_beta = 0.85 c_gamma_alpha`` used, N/m^2 (N/m per
        m of face width).
    load_ratio : ``F_betay c_gamma_beta / (2 F_m / b)`` (-), below 1 on Eq. (41).
    contact_width_ratio : ``b_cal / b``, Eq. (40)/(42) (-; inf without misalignment).
    k_hbeta : ``K_Hbeta`` (-).
    k_fbeta : ``K_Fbeta`` (-), 7.6.
    """

    line_load: float
    b_star: float
    k_prime: float
    stiffened: bool
    offset_term: float
    f_sh: float
    f_ma: float
    b1: float
    b2: float
    f_beta_x_calculated: float
    f_beta_x_min: float
    f_beta_x: float
    y_beta: float
    f_beta_y: float
    c_gamma_beta: float
    load_ratio: float
    contact_width_ratio: float
    k_hbeta: float
    k_fbeta: float

    @property
    def floored(self) -> bool:
        """True when ``F_betax,min`` governs."""
        return self.f_beta_x_min > self.f_beta_x_calculated

    def summary(self) -> dict[str, float]:
        """The intermediates in the standard's units, the unit in each name."""
        return {
            "F_m/b_N/mm": self.line_load * 1e-3,
            "B*": self.b_star,
            "K'": self.k_prime,
            "f_sh_um": self.f_sh / UM,
            "f_ma_um": self.f_ma / UM,
            "B1": self.b1,
            "B2": self.b2,
            "F_betax_min_um": self.f_beta_x_min / UM,
            "F_betax_um": self.f_beta_x / UM,
            "y_beta_um": self.y_beta / UM,
            "F_betay_um": self.f_beta_y / UM,
            "c_gamma_beta_N/(mm um)": self.c_gamma_beta * 1e-9,
            "b_cal/b": self.contact_width_ratio,
            "K_Hbeta": self.k_hbeta,
            "K_Fbeta": self.k_fbeta,
        }


def power_path_factor(power_share: float, double_helical: bool = False) -> float:
    """``B*`` of Eq. (57)/(58) for ``power_share`` per cent of the power through the mesh."""
    k = power_share
    return 0.5 + (200.0 - k) / k if double_helical else 1.0 + 2.0 * (100.0 - k) / k


def shaft_constant(arrangement: str, stiffened: bool) -> float:
    """``K'`` of Figure 13 for the arrangement ("a" to "e")."""
    check_choice("rating.pinion_shaft.arrangement", arrangement, tuple(ARRANGEMENTS))
    with_, without = ARRANGEMENTS[arrangement]
    return with_ if stiffened else without


def shaft_misalignment(line_load: float, face_width: float, pinion_diameter: float,
                       b_star: float, offset_term: float, double_helical: bool = False
                       ) -> float:
    """``f_sh`` (m) of Eq. (57), or Eq. (58) for double helical gears (``face_width`` both
    helices, m; ``line_load`` ``F_m / b`` in N/m; ``pinion_diameter`` ``d1`` in m)."""
    bracket = abs(b_star + offset_term - 0.3) + 0.3
    if double_helical:
        return line_load * 2.0 * SHAFT_COEFFICIENT * bracket * (
            0.5 * face_width / pinion_diameter) ** 2
    return line_load * SHAFT_COEFFICIENT * bracket * (face_width / pinion_diameter) ** 2


def gear_running_in(misalignment: float, material: str, sigma_hlim: float, velocity: float
                    ) -> float:
    """``y_beta`` (m) of one gear of ``material`` (:data:`RUNNING_IN`) and ``sigma_Hlim``
    (Pa) at the pitch line velocity (m/s) for ``F_betax`` (m)."""
    check_choice("rating.running_in_material", material, RUNNING_IN)
    if material == "hardened":
        y = min(0.15 * misalignment, 6.0 * UM)
    elif material == "cast_iron":
        y = 0.55 * misalignment
        if velocity > 10.0:
            y = min(y, 22.0 * UM)
        elif velocity > 5.0:
            y = min(y, 45.0 * UM)
    else:
        s = sigma_hlim / 1e6  # N/mm^2
        y = 320.0 / s * misalignment
        if velocity > 10.0:
            y = min(y, 12800.0 / s * UM)
        elif velocity > 5.0:
            y = min(y, 25600.0 / s * UM)
    return min(y, misalignment)


def running_in_allowance(misalignment: float,
                         materials: tuple[tuple[str, float], tuple[str, float]],
                         velocity: float) -> float:
    """The pair's ``y_beta`` (m) for ``F_betax`` (m); ``materials`` the (group, sigma_Hlim
    in Pa) of both gears: the mean of the two gears' allowances."""
    ys = [gear_running_in(misalignment, m, s, velocity) for m, s in materials]
    return 0.5 * (ys[0] + ys[1])


def face_load_from_misalignment(f_beta_y: float, c_gamma_beta: float, line_load: float
                                ) -> tuple[float, float, float]:
    """``(K_Hbeta, b_cal / b, load ratio)`` of Eq. (39)-(42) for ``F_betay`` (m),
    ``c_gamma_beta`` (N/m^2) and ``F_m / b`` (N/m)."""
    ratio = f_beta_y * c_gamma_beta / (2.0 * line_load)
    if ratio < 1.0:
        width = math.inf if ratio == 0.0 else 0.5 + 0.5 / ratio
        return 1.0 + ratio, width, ratio
    return 2.0 * math.sqrt(ratio), 1.0 / math.sqrt(ratio), ratio


def face_load_method_c(inputs: FaceLoadInputs, *, line_load: float, face_width: float,
                       pinion_diameter: float, c_gamma_beta: float,
                       helix_slope_deviations: tuple[float, float],
                       materials: tuple[tuple[str, float], tuple[str, float]],
                       velocity: float, tooth_height: float,
                       grade5_helix_slope_deviation: float | None = None,
                       double_helical: bool = False) -> FaceLoadFactor:
    """K_Hbeta and K_Fbeta of a pair by ISO 6336-1 method C.

    Parameters
    ----------
    inputs : the user's choices (shaft, helix modification, contact pattern, f_ma).
    line_load : ``F_m / b = F_t K_A K_gamma K_v / b``, N/m.
    face_width : ``b``, m (both helices of a double helical pair).
    pinion_diameter : the pinion's reference diameter ``d1``, m.
    c_gamma_beta : ``0.85 c_gamma_alpha`` of method B
        (:attr:`pipeline.stiffness.iso6336.IsoStiffness.c_gamma_beta`), N/m^2.
    helix_slope_deviations : ``f_Hbeta`` of both gears, m.
    materials : (group of :data:`RUNNING_IN`, sigma_Hlim in Pa) of both gears.
    velocity : pitch line velocity, m/s.
    tooth_height : the larger tooth depth ``h`` of the two gears (the smaller ``b / h``),
        m, for K_Fbeta.
    grade5_helix_slope_deviation : ``f_Hbeta5`` (m), the ISO 1328-1 grade 5 helix slope
        tolerance of Eq. (53), the larger of the two gears'; needed when the contact
        pattern is proven.
    double_helical : Eq. (58) and ``b_B = b / 2``.
    """
    w = inputs.where
    check_range(f"{w}: F_m/b", line_load * 1e-3, 0.0, math.inf, lo_open=True, unit="N/mm")
    check_range(f"{w}: b", face_width * 1e3, 0.0, math.inf, lo_open=True, unit="mm")
    check_range(f"{w}: d1", pinion_diameter * 1e3, 0.0, math.inf, lo_open=True, unit="mm")
    check_range(f"{w}: c_gamma_beta", c_gamma_beta * 1e-9, 0.0, math.inf, lo_open=True,
                unit="N/(mm um)")
    check_range(f"{w}: v", velocity, 0.0, math.inf, unit="m/s")
    check_range(f"{w}: h", tooth_height * 1e3, 0.0, math.inf, lo_open=True, unit="mm")
    for k, f in enumerate(helix_slope_deviations):
        check_range(f"{w}: f_Hbeta{k + 1}", f / UM, 0.0, 1000.0, unit="um")

    share = 100.0 if inputs.power_share is None else inputs.power_share
    b_star = power_path_factor(share, double_helical)
    shaft = inputs.shaft
    k_prime, stiffened, offset_term = 0.0, False, 0.0
    if shaft is not None:
        ratio = pinion_diameter / shaft.diameter
        stiffened = shaft.stiffening is not False and ratio >= STIFFENING_RATIO
        if shaft.stiffening is True and not stiffened:
            warnings.warn(f"{shaft.where}.stiffening = true has no effect: d1 / d_sh = "
                          f"{ratio:.4g} is below {STIFFENING_RATIO} (ISO 6336-1 Figure 13), the "
                          "unstiffened K' applies", InputWarning, stacklevel=2)
        k_prime = shaft_constant(shaft.arrangement, stiffened)
        offset_term = (k_prime * shaft.span * shaft.offset / pinion_diameter**2
                       * ratio**4)
    f_sh = shaft_misalignment(line_load, face_width, pinion_diameter, b_star, offset_term,
                              double_helical)

    f_hb = max(helix_slope_deviations)
    if inputs.f_ma is not None:
        f_ma = inputs.f_ma
    elif inputs.rule == "rss":
        f_ma = math.hypot(*helix_slope_deviations)
    else:
        f_ma = f_hb
    b1, b2 = HELIX_MODIFICATIONS[inputs.helix_modification]
    if inputs.contact_pattern_proven:
        if grade5_helix_slope_deviation is None:
            raise InputError(f"{w}.contact_pattern_proven = true needs the grade 5 helix "
                             "slope tolerance f_Hbeta5 of ISO 6336-1 Eq. (53)")
        check_range(f"{w}: f_Hbeta5", grade5_helix_slope_deviation / UM, 0.0, 1000.0,
                    unit="um")
        fbx_calc = abs(1.33 * b1 * f_sh - grade5_helix_slope_deviation)
    else:
        fbx_calc = 1.33 * b1 * f_sh + b2 * f_ma
    fbx_min = max(MIN_MISALIGNMENT_COEFFICIENT * line_load, 0.5 * f_hb)
    fbx = max(fbx_calc, fbx_min)
    y_beta = running_in_allowance(fbx, materials, velocity)
    fby = fbx - y_beta
    k_hbeta, width, load_ratio = face_load_from_misalignment(fby, c_gamma_beta, line_load)
    width_f = 0.5 * face_width if double_helical else face_width
    k_fbeta = face_load_factor(k_hbeta, width_f, tooth_height)
    return FaceLoadFactor(line_load, b_star, k_prime, stiffened, offset_term, f_sh, f_ma, b1,
                          b2, fbx_calc, fbx_min, fbx, y_beta, fby, c_gamma_beta, load_ratio, width,
                          k_hbeta, k_fbeta)
