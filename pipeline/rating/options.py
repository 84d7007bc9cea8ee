"""What a rating asks for: the ``[rating]`` table of a gearbox file, in SI.

:class:`RatingOptions` holds the mesh-wide inputs (application factor K_A, required life,
accuracy grade, lubricant, where K_Hbeta comes from, the planets' load sharing K_gamma,
the minimum safety factors) and one :class:`GearRatingOptions` per gear (``[rating.pinion]``,
``[rating.sun]``, ...: the allowable stress numbers of its material and its roughness).
Each default is a value the user may rely on and the README states:

* ``application_factor`` K_A 1.25 (ISO 6336-6:2019 Annex A: a uniform driving machine and
  a driven machine with moderate shocks);
* ``life_h`` 20 000 h; ``accuracy_grade`` 6 (ISO 1328-1:1995, both gears);
* ``oil_viscosity_40_mm2s`` 220 (ISO VG 220; ``oil_grade = "VG 220"`` gives the grade's
  mid-point viscosity, ISO 3448:1992);
* ``face_load_factor`` ``"method_c"``: K_Hbeta by ISO 6336-1 method C
  (:mod:`pipeline.rating.face_load`; ``[rating.method_c]`` its choices, default no helix
  modification and ``f_ma`` from both gears' ``f_Hbeta``; ``[rating.pinion_shaft]`` the
  pinion's or sun's shaft, default a pinion at mid-span), ``"contact"`` from the loaded
  contact's line load (the largest over the mean of the cycle-mean line load across the
  face), or a number; the other two are shown beside the one used. A pair on shafts
  (``[pinion.shaft]``, ``[gear.shaft]``) defaults to ``"contact"``: its contact is solved
  with the shafts' deflection (:mod:`pipeline.config.rating`);
* ``load_sharing`` K_gamma: 1 for a pair; for a planetary set the value for its number of
  planets (:data:`PLANET_LOAD_SHARING`), a number, or ``"computed"``: the largest planet's
  mean mesh force over the mean of all planets in the dynamic model;
* ``minimum_safety_pitting`` S_Hmin 1.0, ``minimum_safety_bending`` S_Fmin 1.4;
* per gear: ``material = "case_hardened"``, ``quality = "MQ"`` (ISO 6336-5:2016 Table 1:
  sigma_Hlim 1500 N/mm^2, sigma_Flim 425 N/mm^2 with the lower core hardness; any kind of
  :data:`pipeline.rating.materials.MATERIALS` with its surface hardness, or
  ``sigma_Hlim_MPa`` / ``sigma_Flim_MPa`` given directly), flank roughness R_z 4.8 um,
  root roughness R_z 20 um (KISSsoft's values in its ratings of the NREL 5 MW gearbox).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from pipeline.contact.iso_root_stress import ShaperCutter
from pipeline.rating.face_load import FaceLoadInputs
from pipeline.rating.spectrum import LoadSpectrum
from pipeline.validation import InputError, check_choice, check_int_range, check_range

OIL_GRADES = (2, 3, 5, 7, 10, 15, 22, 32, 46, 68, 100, 150, 220, 320, 460, 680, 1000,
              1500, 2200, 3200)
"""ISO 3448:1992 viscosity grades: ISO VG n has the mid-point kinematic viscosity n mm^2/s
at 40 deg C."""

PLANET_LOAD_SHARING = {3: 1.10, 4: 1.25, 5: 1.35, 6: 1.44, 7: 1.47}
"""K_gamma by number of planets, for a set without a flexible pin or floating member
(IEC 61400-4:2012 and ANSI/AGMA 6123-B06 application level 1, as transcribed in the
MATLAB ISO 6336 classes of gfsReboucas/Drivetrain, ``ISO_6336.m``; KISSsoft's rating of
the NREL 5 MW gearbox's second stage uses 1.10 for its three planets)."""

FACE_LOAD_SOURCES = ("method_c", "contact")
"""Where K_Hbeta may come from besides a number: ISO 6336-1 method C, the loaded contact's
line load."""

def oil_grade_viscosity(grade: str) -> float:
    """Kinematic viscosity at 40 deg C (m^2/s) of an ISO VG grade written ``"VG 220"``,
    ``"VG220"`` or ``"ISO VG 220"``."""
    text = grade.upper().replace("ISO", "").replace(" ", "")
    number = text[2:] if text.startswith("VG") else ""
    if not number.isdigit() or int(number) not in OIL_GRADES:
        raise InputError(f'rating.oil_grade = "{grade}" is not one of '
                         + ", ".join(f"'VG {g}'" for g in OIL_GRADES) + " (ISO 3448 grades)")
    return int(number) * 1e-6


@dataclass(frozen=True)
class GearRatingOptions:
    """One gear's rating inputs (``[rating.<gear>]``), its material resolved (SI).

    Attributes
    ----------
    sigma_hlim : allowable contact stress number sigma_Hlim, Pa.
    sigma_flim : nominal bending stress number sigma_Flim (the test gear's, without Y_ST), Pa.
    material : where they come from: ISO 6336-5's row (:attr:`MaterialLimits.source
        <pipeline.rating.materials.MaterialLimits.source>`) or "given".
    running_in : ISO 6336-1 running-in class, "hardened" (Eh, IF, NT, NV),
        "through_hardened" (St, V, GGG perl., GTS) or "cast_iron" (GG, GGG ferr.).
    pitting_line, bending_line : ISO 6336-2 and -3 life lines.
    size_class : ISO 6336-3 size factor class.
    hardness_hb : Brinell hardness (HBW) of a through-hardened gear, for the work hardening
        factor Z_W against a hardened mate; None elsewhere.
    notch_class : the root's slip-layer class ("hardened": Eh, IF; "through_hardened": V,
        GTS, GGG perl.; None: not built, the gear is not rated in bending).
    proof_stress : 0.2 % proof stress of a through-hardened gear, Pa, or None.
    cutter : the pinion-type cutter of an internal gear
        (:class:`~pipeline.contact.iso_root_stress.ShaperCutter`), or None.
    flank_roughness, root_roughness : mean peak-to-valley roughness R_z, m.
    """

    sigma_hlim: float = 1500e6
    sigma_flim: float = 425e6
    material: str = "ISO 6336-5:2016 Table 1, case_hardened (Eh) MQ: rows 42 and 45"
    running_in: str = "hardened"
    pitting_line: str = "hardened"
    bending_line: str = "hardened"
    size_class: str = "hardened"
    hardness_hb: float | None = None
    notch_class: str | None = "hardened"
    proof_stress: float | None = None
    cutter: ShaperCutter | None = None
    flank_roughness: float = 4.8e-6
    root_roughness: float = 20e-6

    def __post_init__(self) -> None:
        check_range("sigma_hlim", self.sigma_hlim, 200e6, 2500e6, unit="Pa")
        check_range("sigma_flim", self.sigma_flim, 50e6, 1000e6, unit="Pa")
        check_range("flank_roughness", self.flank_roughness, 0.0, 100e-6, lo_open=True,
                    unit="m")
        check_range("root_roughness", self.root_roughness, 0.0, 100e-6, lo_open=True,
                    unit="m")
        if self.hardness_hb is not None:
            if self.running_in != "through_hardened":
                raise InputError("hardness_HB applies to a through-hardened gear only (its "
                                 "work hardening factor Z_W against a hardened mate)")
            check_range("hardness_hb", self.hardness_hb, 100.0, 600.0)
        if self.proof_stress is not None:
            if self.notch_class != "through_hardened":
                raise InputError("proof_stress_MPa applies to a through-hardened steel (the "
                                 "slip layer of its root), not to this gear's material")
            check_range("proof_stress", self.proof_stress, 500e6, 1000e6, unit="Pa")


@dataclass(frozen=True)
class RatingOptions:
    """The ``[rating]`` table (SI): the mesh-wide inputs and each gear's.

    Attributes
    ----------
    application_factor : K_A (-), [1, 5].
    life : required life, s, (0, 1e7 h].
    life_cycles : the required life as load cycles of the driving gear (``[operation]``'s),
        or None; given, it sets the life at the operating speed (``life_h`` then refused).
    accuracy_grade : ISO 1328-1:1995 accuracy grade of every gear, 1 .. 12.
    viscosity_40 : kinematic viscosity of the oil at 40 deg C, m^2/s.
    face_load_factor : "method_c", "contact" (K_Hbeta from the loaded contact) or a number
        >= 1.
    method_c : ISO 6336-1 method C's inputs (computed for every mesh, shown beside a K_Hbeta
        from elsewhere).
    load_sharing : K_gamma: a number >= 1, "computed" (planetary sets with dynamics), or
        None for the default (1; a planetary set's :data:`PLANET_LOAD_SHARING`).
    minimum_safety_pitting, minimum_safety_bending : S_Hmin, S_Fmin (-).
    gears : the gears' :class:`GearRatingOptions` by role (every gear of the gearbox).
    spectrum : a load spectrum (``[[rating.spectrum]]``: the driving gear's torque and speed
        as in ``[operation]``, and the time at them) rated by ISO 6336-6's Miner sum beside
        the constant-load rating, or None.
    """

    application_factor: float = 1.25
    life: float = 20000.0 * 3600.0
    life_cycles: float | None = None
    accuracy_grade: int = 6
    viscosity_40: float = 220e-6
    face_load_factor: str | float = "method_c"
    method_c: FaceLoadInputs = field(default_factory=FaceLoadInputs)
    load_sharing: str | float | None = None
    minimum_safety_pitting: float = 1.0
    minimum_safety_bending: float = 1.4
    gears: Mapping[str, GearRatingOptions] = field(default_factory=dict)
    spectrum: LoadSpectrum | None = None

    def __post_init__(self) -> None:
        check_range("application_factor", self.application_factor, 1.0, 5.0)
        check_range("life", self.life, 0.0, 1e7 * 3600.0, lo_open=True, unit="s")
        if self.life_cycles is not None:
            check_range("life_cycles", self.life_cycles, 1e3, 1e12)
        check_int_range("accuracy_grade", self.accuracy_grade, 1, 12)
        check_range("viscosity_40", self.viscosity_40, 1e-6, 5000e-6, unit="m^2/s")
        if isinstance(self.face_load_factor, str):
            check_choice("face_load_factor", self.face_load_factor, FACE_LOAD_SOURCES)
        else:
            check_range("face_load_factor", self.face_load_factor, 1.0, 10.0)
        if isinstance(self.load_sharing, str):
            check_choice("load_sharing", self.load_sharing, ("computed",))
        elif self.load_sharing is not None:
            check_range("load_sharing", self.load_sharing, 1.0, 3.0)
        check_range("minimum_safety_pitting", self.minimum_safety_pitting, 0.5, 5.0)
        check_range("minimum_safety_bending", self.minimum_safety_bending, 0.5, 5.0)

    def life_hours(self, driver_speed: float) -> float:
        """The required life, h: ``life``, or ``life_cycles`` at the driving gear's
        ``driver_speed`` (rad/s)."""
        if self.life_cycles is None:
            return self.life / 3600.0
        return self.life_cycles / (driver_speed * 30.0 / math.pi * 60.0)

    def gear(self, role: str) -> GearRatingOptions:
        """The options of the gear ``role`` (its defaults when the file gave none)."""
        return self.gears.get(role, GearRatingOptions())


def planet_load_sharing(planets: int) -> float:
    """The default K_gamma of a planetary set with ``planets`` planets
    (:data:`PLANET_LOAD_SHARING`); other counts need ``rating.load_sharing``."""
    if planets not in PLANET_LOAD_SHARING:
        raise InputError(f"rating.load_sharing: no default K_gamma for {planets} planets "
                         f"(the table covers {min(PLANET_LOAD_SHARING)} to "
                         f"{max(PLANET_LOAD_SHARING)}); give rating.load_sharing")
    return PLANET_LOAD_SHARING[planets]
