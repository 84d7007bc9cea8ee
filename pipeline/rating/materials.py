"""Allowable stress numbers of ISO 6336-5:2016 (method B): sigma_Hlim and sigma_Flim of a gear
material from its kind, its quality grade and its surface hardness, with the material's
class for ISO 6336-1/-2/-3 (life lines, running-in allowances, root size factor).

Table 1 of ISO 6336-5:2016 (clause 5.5) writes every line of its figures as ``sigma_lim =
A x + B`` (N/mm^2), ``x`` the surface hardness on the scale the row names (Brinell HBW or
Vickers HV), valid over the row's hardness range, for the quality grades ML (modest
demands), MQ (normal demands of an experienced manufacturer) and ME (high demands). Outside
a row's range the standard leaves the value to agreement between purchaser and
manufacturer: here a hardness outside the range is refused, never clamped, and a hardness
on the other scale is refused too (ISO 18265's conversions between HBW and HV are
approximate; the user converts knowingly).

The kinds (name as written in the gearbox file, the standard's symbol, Table 1 rows of
sigma_Hlim and sigma_Flim for ML, MQ, ME, hardness range):

* ``normalized_steel``, St: rows 1, 1, 2 and 5, 5, 6; 110-210 HBW.
* ``cast_steel``, St (cast): rows 3, 3, 4 and 7, 7, 8; 140-210 HBW.
* ``malleable_cast_iron``, GTS (perl.), black malleable: rows 9, 9, 10 and 15, 15, 16;
  135-250 HBW (ME 175-250).
* ``nodular_cast_iron_pearlitic``, GGG (perl., bai.), and ``nodular_cast_iron_ferritic``,
  GGG (ferr.): rows 11, 11, 12 and 17, 17, 18; 175-300 HBW (ME 200-300).
* ``grey_cast_iron``, GG: rows 13, 13, 14 and 19, 19, 20; 150-240 HBW (ME 175-275).
* ``through_hardened_carbon``, V, wrought carbon steel: rows 21, 22, 23 and 27, 28, 29;
  135-210 HV (sigma_Hlim), 115-215 HV (sigma_Flim).
* ``through_hardened_alloy``, V, wrought alloy steel: rows 24, 25, 26 and 30, 31, 32;
  200-360 HV (ME 200-390).
* ``through_hardened_cast_carbon``, V (cast): rows 33, 33, 34 and 37, 37, 38; 130-215 HV.
* ``through_hardened_cast_alloy``, V (cast): rows 35, 35, 36 and 39, 39, 40; 200-360 HV.
* ``case_hardened``, Eh: rows 41, 42, 43 and 44, 45 (46, 47), 48; 600-800 HV (MQ, ME
  660-800).
* ``flame_induction_hardened``, IF: rows 49, 50, 51 and 52, 53, 55; 485-615 HV (MQ, ME
  500-615; MQ sigma_Flim 500-570).
* ``nitrided``, NT (nitr.), nitriding steel: rows 56, 57, 58 and 62, 63, 64; 650-900 HV.
* ``nitrided_through_hardening``, NV (nitr.): rows 59, 60, 61 and 65, 66, 67; 450-650 HV.
* ``nitrocarburized``, NV (nitrocar.): rows 68, 69, 69 and 71, 72, 72; 300-650 HV (MQ, ME
  300-450).

A gear's hardness must lie in the ranges of both of its lines (through-hardened carbon
steel: 135-210 HV). Table 1 does not split nodular cast iron by structure, ISO 6336-1/-2/-3
do (pearlitic or bainitic with the steels, ferritic with grey cast iron): the two names take
the same lines and different classes, so the user says which. Case-hardened MQ bending has
three rows by core hardness (``core_hardness``, :data:`CORE_HARDNESS`):

* ``"25HRC_lower_hardenability"``, row 45, 425 N/mm^2: core at least 25 HRC with the lower
  hardenability; the default, the smallest of the three (KISSsoft's label "Core hardness
  >=25HRC Jominy J=12mm<HRC28" is taken to name this row, an inference from the words);
* ``"25HRC_upper_hardenability"``, row 46, 461 N/mm^2: the upper hardenability (J = 12 mm
  at least 28 HRC, by the same inference);
* ``"30HRC"``, row 47, 500 N/mm^2: core at least 30 HRC.

Rows 54 (flame or induction hardened MQ bending above 570 HV) and 70 and 73
(nitrocarburized MQ and ME above 450 HV) are not in the transcription below and are not
built: those hardnesses are refused with a note saying so (give sigma_Hlim and sigma_Flim
directly there).

The classes of each kind (:class:`MaterialKind`), as ISO 6336-1/-2/-3 group the symbols:

* pitting life line of ISO 6336-2 (:data:`pipeline.rating.pitting.LIFE_LINES`):
  ``"hardened"`` (line without pitting) for St, V, GGG (perl., bai.), GTS (perl.), Eh, IF,
  which may instead take ``"pitting_permitted"`` when some pitting is permitted (asked
  for, never assumed); ``"nitrided"`` for GG, GGG (ferr.), NT, NV (nitr.);
  ``"nitrocarburized"`` for NV (nitrocar.);
* bending life line of ISO 6336-3 (:data:`pipeline.rating.bending.LIFE_LINES`):
  ``"through_hardened"`` St, V, GGG (perl., bai.), GTS (perl.); ``"hardened"`` Eh, IF with
  the root hardened; ``"nitrided"`` NT, NV (nitr.), GG, GGG (ferr.); ``"nitrocarburized"``
  NV (nitrocar.);
* running-in allowances of ISO 6336-1 (y_p, y_f, y_beta, :func:`pipeline.rating.dynamic.
  allowance`): ``"through_hardened"`` (``160 / sigma_Hlim f``) St, V, GGG (perl., bai.),
  GTS (perl.); ``"cast_iron"`` (``0.275 f``) GG, GGG (ferr.); ``"hardened"`` (``0.075 f``)
  Eh, IF, NT, NV;
* size factor Y_X of ISO 6336-3: ``"through_hardened"`` (``1.03 - 0.006 m_n``) St, V, GGG
  (perl., bai.), GTS (perl.); ``"hardened"`` (``1.05 - 0.01 m_n``) Eh, IF, NT, NV;
  ``"cast_iron"`` (``1.075 - 0.015 m_n``, at least 0.7) GG, GGG (ferr.).

The running-in groups are also those of the transcription of ISO 6336-1 in the same C#
code as the table below, and the Y_X groups agree with public third-party quotes of ISO
6336-3's size factor table; KISSsoft's reports (below) print the running-in allowances and
Y_X of a case-hardened and a through-hardened gear that these classes reproduce. No flank
size class is given: ISO 6336-2's Z_X is 1 here (:mod:`pipeline.rating.pitting`), as
KISSsoft prints it (1.000) for case-hardened gears of module 45 mm.

``sigma_FE = Y_ST sigma_Flim`` with ``Y_ST = 2`` (ISO 6336-5, 5.3.2) is
:attr:`MaterialLimits.sigma_fe`.

Source and checks. The coefficients and ranges are the transcription of Table 1 in the
public C# code hakangunes258/mekanika, ``Services/Iso6336Material.cs``, which says it holds
the constants of ISO 6336-5:2016 Table 1 and gives each one's row number; the standard's
own text was not available, and no second public transcription of Table 1 (nor of the
figures of DIN 3990-5) was found to compare the rows with. What could be checked:

* KISSsoft Release 03/2017 A's report of the NREL 5 MW gearbox's parallel stage
  (``@NREL_5MW/stage_03.rtf`` in the public repository gfsReboucas/Drivetrain) prints for
  18CrNiMo7-6, case-hardened, "ISO 6336-5 Figure 9/10 (MQ), Core hardness >=25HRC Jominy
  J=12mm<HRC28": sigma_Hlim 1500.00 N/mm^2, which row 42 gives. Its sigma_Flim 430.00
  (sigma_FE 860.00) is none of rows 45-47 (425, 461, 500 N/mm^2); the report reads the
  standard's figures, not Table 1, possibly of an earlier edition (not resolved): a rating
  that reproduces that report gives sigma_Flim 430 directly.
* The stage 1 and 2 reports' through-hardened 34CrNiMo6 rings (MQ, printed "HBW 240",
  sigma_Hlim 700.00, sigma_Flim 290.00 N/mm^2): rows 25 and 31 give 701.2 and 293.2 N/mm^2
  at 250 HV (about 240 HBW by ISO 18265), consistent if KISSsoft converts so and rounds
  down to 10 N/mm^2; not established.
* Internal checks (``tests/test_rating_materials.py``): every row at both ends of its range
  against values worked by hand from the transcription, and ML <= MQ <= ME over the
  hardness range the three grades share, for sigma_Hlim and sigma_Flim of every kind.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

from pipeline.validation import InputError, check_choice, check_range

QUALITIES = ("ML", "MQ", "ME")
"""Material quality grades of ISO 6336-5."""

SCALES = ("HBW", "HV")
"""Hardness scales of Table 1: Brinell (tungsten carbide ball) and Vickers."""

CORE_HARDNESS = ("25HRC_lower_hardenability", "25HRC_upper_hardenability", "30HRC")
"""Core-hardness variants of case-hardened MQ bending (rows 45, 46, 47); the first is the
default."""

Y_ST = 2.0
"""Stress correction factor of the reference test gear, sigma_FE = Y_ST sigma_Flim."""


@dataclass(frozen=True)
class LimitLine:
    """One row of ISO 6336-5:2016 Table 1: ``sigma_lim = A x + B`` for ``x`` in [x_min,
    x_max].

    Attributes
    ----------
    row : the row number of Table 1.
    slope : A, N/mm^2 per hardness unit.
    intercept : B, N/mm^2.
    x_min, x_max : the row's hardness range, in the kind's scale (HBW or HV).
    """

    row: int
    slope: float
    intercept: float
    x_min: float
    x_max: float

    def value(self, hardness: float) -> float:
        """sigma_lim (Pa) at ``hardness`` (HBW or HV); the range is checked by the caller."""
        return (self.slope * hardness + self.intercept) * 1e6


Lines = tuple[LimitLine, LimitLine, LimitLine]
"""The lines of ML, MQ, ME (in :data:`QUALITIES` order)."""


@dataclass(frozen=True)
class MaterialKind:
    """A material and heat treatment of Table 1 with its classes in ISO 6336-1/-2/-3.

    Attributes
    ----------
    name : as written in the gearbox file (``"case_hardened"``).
    symbol : ISO 6336's symbol (``"Eh"``).
    description : the kind in words.
    scale : ``"HBW"`` or ``"HV"``, the hardness scale of its rows.
    contact, bending : the sigma_Hlim and sigma_Flim lines of ML, MQ, ME.
    pitting_life_line : key of :data:`pipeline.rating.pitting.LIFE_LINES` (without pitting).
    bending_life_line : key of :data:`pipeline.rating.bending.LIFE_LINES`.
    running_in : ``"hardened"``, ``"through_hardened"`` or ``"cast_iron"`` (ISO 6336-1).
    bending_size_class : Y_X line, ``"hardened"``, ``"through_hardened"`` or ``"cast_iron"``.
    core_variants : MQ bending rows by core hardness (:data:`CORE_HARDNESS` order), or
        empty; the first is the one in ``bending``.
    gap_notes : (quality, note) of the grades whose Table 1 rows above the transcribed
        range are not built.
    """

    name: str
    symbol: str
    description: str
    scale: str
    contact: Lines
    bending: Lines
    pitting_life_line: str
    bending_life_line: str
    running_in: str
    bending_size_class: str
    core_variants: tuple[LimitLine, ...] = ()
    gap_notes: tuple[tuple[str, str], ...] = ()

    @property
    def may_permit_pitting(self) -> bool:
        """Whether ISO 6336-2's line with limited pitting applies to this kind."""
        return self.pitting_life_line == "hardened"


def _lines(*rows: tuple[int, float, float, float, float]) -> Lines:
    ml, mq, me = (LimitLine(*r) for r in rows)
    return ml, mq, me


# Classes of the groups of ISO 6336-1/-2/-3 (see the module docstring):
# (pitting life line, bending life line, running-in, Y_X class)
_STEEL = ("hardened", "through_hardened", "through_hardened", "through_hardened")
_CAST_IRON = ("nitrided", "nitrided", "cast_iron", "cast_iron")
_CASE = ("hardened", "hardened", "hardened", "hardened")
_NITRIDED = ("nitrided", "nitrided", "hardened", "hardened")
_NITROCARBURIZED = ("nitrocarburized", "nitrocarburized", "hardened", "hardened")

_GGG_CONTACT = ((11, 1.434, 211.0, 175.0, 300.0), (11, 1.434, 211.0, 175.0, 300.0),
                (12, 1.500, 250.0, 200.0, 300.0))
_GGG_BENDING = ((17, 0.350, 119.0, 175.0, 300.0), (17, 0.350, 119.0, 175.0, 300.0),
                (18, 0.380, 134.0, 200.0, 300.0))

_KINDS = (
    MaterialKind(
        "normalized_steel", "St", "normalized low carbon wrought steel", "HBW",
        _lines((1, 1.000, 190.0, 110.0, 210.0), (1, 1.000, 190.0, 110.0, 210.0),
               (2, 1.520, 250.0, 110.0, 210.0)),
        _lines((5, 0.455, 69.0, 110.0, 210.0), (5, 0.455, 69.0, 110.0, 210.0),
               (6, 0.386, 147.0, 110.0, 210.0)),
        *_STEEL),
    MaterialKind(
        "cast_steel", "St (cast)", "normalized cast steel", "HBW",
        _lines((3, 0.986, 131.0, 140.0, 210.0), (3, 0.986, 131.0, 140.0, 210.0),
               (4, 1.143, 237.0, 140.0, 210.0)),
        _lines((7, 0.313, 62.0, 140.0, 210.0), (7, 0.313, 62.0, 140.0, 210.0),
               (8, 0.254, 137.0, 140.0, 210.0)),
        *_STEEL),
    MaterialKind(
        "malleable_cast_iron", "GTS (perl.)", "black malleable cast iron", "HBW",
        _lines((9, 1.371, 143.0, 135.0, 250.0), (9, 1.371, 143.0, 135.0, 250.0),
               (10, 1.333, 267.0, 175.0, 250.0)),
        _lines((15, 0.345, 77.0, 135.0, 250.0), (15, 0.345, 77.0, 135.0, 250.0),
               (16, 0.403, 128.0, 175.0, 250.0)),
        *_STEEL),
    MaterialKind(
        "nodular_cast_iron_pearlitic", "GGG (perl., bai.)",
        "nodular (spheroidal graphite) cast iron, pearlitic or bainitic", "HBW",
        _lines(*_GGG_CONTACT), _lines(*_GGG_BENDING), *_STEEL),
    MaterialKind(
        "nodular_cast_iron_ferritic", "GGG (ferr.)",
        "nodular (spheroidal graphite) cast iron, ferritic", "HBW",
        _lines(*_GGG_CONTACT), _lines(*_GGG_BENDING), *_CAST_IRON),
    MaterialKind(
        "grey_cast_iron", "GG", "grey cast iron", "HBW",
        _lines((13, 1.033, 132.0, 150.0, 240.0), (13, 1.033, 132.0, 150.0, 240.0),
               (14, 1.465, 122.0, 175.0, 275.0)),
        _lines((19, 0.256, 8.0, 150.0, 240.0), (19, 0.256, 8.0, 150.0, 240.0),
               (20, 0.200, 53.0, 175.0, 275.0)),
        *_CAST_IRON),
    MaterialKind(
        "through_hardened_carbon", "V", "through-hardened wrought carbon steel", "HV",
        _lines((21, 0.963, 283.0, 135.0, 210.0), (22, 0.925, 360.0, 135.0, 210.0),
               (23, 0.838, 432.0, 135.0, 210.0)),
        _lines((27, 0.250, 108.0, 115.0, 215.0), (28, 0.240, 163.0, 115.0, 215.0),
               (29, 0.283, 202.0, 115.0, 215.0)),
        *_STEEL),
    MaterialKind(
        "through_hardened_alloy", "V", "through-hardened wrought alloy steel", "HV",
        _lines((24, 1.313, 188.0, 200.0, 360.0), (25, 1.313, 373.0, 200.0, 360.0),
               (26, 2.213, 260.0, 200.0, 390.0)),
        _lines((30, 0.423, 104.0, 200.0, 360.0), (31, 0.425, 187.0, 200.0, 360.0),
               (32, 0.358, 231.0, 200.0, 390.0)),
        *_STEEL),
    MaterialKind(
        "through_hardened_cast_carbon", "V (cast)", "through-hardened cast carbon steel", "HV",
        _lines((33, 0.831, 300.0, 130.0, 215.0), (33, 0.831, 300.0, 130.0, 215.0),
               (34, 0.951, 345.0, 130.0, 215.0)),
        _lines((37, 0.224, 117.0, 130.0, 215.0), (37, 0.224, 117.0, 130.0, 215.0),
               (38, 0.286, 167.0, 130.0, 215.0)),
        *_STEEL),
    MaterialKind(
        "through_hardened_cast_alloy", "V (cast)", "through-hardened cast alloy steel", "HV",
        _lines((35, 1.276, 298.0, 200.0, 360.0), (35, 1.276, 298.0, 200.0, 360.0),
               (36, 1.350, 356.0, 200.0, 360.0)),
        _lines((39, 0.364, 161.0, 200.0, 360.0), (39, 0.364, 161.0, 200.0, 360.0),
               (40, 0.356, 186.0, 200.0, 360.0)),
        *_STEEL),
    MaterialKind(
        "case_hardened", "Eh", "case-hardened (carburized) wrought steel", "HV",
        _lines((41, 0.0, 1300.0, 600.0, 800.0), (42, 0.0, 1500.0, 660.0, 800.0),
               (43, 0.0, 1650.0, 660.0, 800.0)),
        _lines((44, 0.0, 312.0, 600.0, 800.0), (45, 0.0, 425.0, 660.0, 800.0),
               (48, 0.0, 525.0, 660.0, 800.0)),
        *_CASE,
        core_variants=(LimitLine(45, 0.0, 425.0, 660.0, 800.0),
                       LimitLine(46, 0.0, 461.0, 660.0, 800.0),
                       LimitLine(47, 0.0, 500.0, 660.0, 800.0))),
    MaterialKind(
        "flame_induction_hardened", "IF", "flame or induction hardened wrought or cast steel",
        "HV",
        _lines((49, 0.740, 602.0, 485.0, 615.0), (50, 0.541, 882.0, 500.0, 615.0),
               (51, 0.505, 1013.0, 500.0, 615.0)),
        _lines((52, 0.305, 76.0, 485.0, 615.0), (53, 0.138, 290.0, 500.0, 570.0),
               (55, 0.271, 237.0, 500.0, 615.0)),
        *_CASE,
        gap_notes=(("MQ", "Table 1's MQ bending row above 570 HV (row 54) is not built: "
                           "give sigma_Flim directly"),)),
    MaterialKind(
        "nitrided", "NT (nitr.)", "nitriding steel, nitrided", "HV",
        _lines((56, 0.0, 1125.0, 650.0, 900.0), (57, 0.0, 1250.0, 650.0, 900.0),
               (58, 0.0, 1450.0, 650.0, 900.0)),
        _lines((62, 0.0, 270.0, 650.0, 900.0), (63, 0.0, 420.0, 650.0, 900.0),
               (64, 0.0, 468.0, 650.0, 900.0)),
        *_NITRIDED),
    MaterialKind(
        "nitrided_through_hardening", "NV (nitr.)", "through-hardening steel, nitrided", "HV",
        _lines((59, 0.0, 788.0, 450.0, 650.0), (60, 0.0, 998.0, 450.0, 650.0),
               (61, 0.0, 1217.0, 450.0, 650.0)),
        _lines((65, 0.0, 258.0, 450.0, 650.0), (66, 0.0, 363.0, 450.0, 650.0),
               (67, 0.0, 432.0, 450.0, 650.0)),
        *_NITRIDED),
    MaterialKind(
        "nitrocarburized", "NV (nitrocar.)", "through-hardening wrought steel, nitrocarburized",
        "HV",
        _lines((68, 0.0, 650.0, 300.0, 650.0), (69, 1.167, 425.0, 300.0, 450.0),
               (69, 1.167, 425.0, 300.0, 450.0)),
        _lines((71, 0.0, 224.0, 300.0, 650.0), (72, 0.653, 94.0, 300.0, 450.0),
               (72, 0.653, 94.0, 300.0, 450.0)),
        *_NITROCARBURIZED,
        gap_notes=tuple((q, f"Table 1's {q} rows above 450 HV (rows 70 and 73) are not "
                            "built: give sigma_Hlim and sigma_Flim directly")
                        for q in ("MQ", "ME"))),
)

MATERIALS = MappingProxyType({k.name: k for k in _KINDS})
"""The kinds of ISO 6336-5:2016 Table 1 by the name a gearbox file uses (read-only)."""


@dataclass(frozen=True)
class MaterialLimits:
    """Allowable stress numbers of one gear's material and its classes (SI).

    Attributes
    ----------
    kind : the material's name (:data:`MATERIALS`); symbol : ISO 6336's symbol.
    quality : ``"ML"``, ``"MQ"`` or ``"ME"``.
    hardness : the surface hardness given, in ``hardness_scale`` (``"HBW"`` or ``"HV"``).
    sigma_hlim : sigma_Hlim, Pa.
    sigma_flim : sigma_Flim, Pa.
    contact_row, bending_row : the rows of ISO 6336-5:2016 Table 1 used.
    pitting_life_line : key of :data:`pipeline.rating.pitting.LIFE_LINES`.
    bending_life_line : key of :data:`pipeline.rating.bending.LIFE_LINES`.
    running_in : ``"hardened"``, ``"through_hardened"`` or ``"cast_iron"`` (ISO 6336-1).
    bending_size_class : Y_X line (:class:`MaterialKind`).
    """

    kind: str
    symbol: str
    quality: str
    hardness: float
    hardness_scale: str
    sigma_hlim: float
    sigma_flim: float
    contact_row: int
    bending_row: int
    pitting_life_line: str
    bending_life_line: str
    running_in: str
    bending_size_class: str

    @property
    def sigma_fe(self) -> float:
        """sigma_FE = Y_ST sigma_Flim, Pa (ISO 6336-5, 5.3.2)."""
        return Y_ST * self.sigma_flim

    @property
    def source(self) -> str:
        """Where the numbers come from, for a report line."""
        return (f"ISO 6336-5:2016 Table 1, {self.kind} ({self.symbol}) {self.quality}, "
                f"{self.hardness:g} {self.hardness_scale}: rows {self.contact_row} "
                f"(sigma_Hlim) and {self.bending_row} (sigma_Flim)")


def material_kind(name: str, *, where: str) -> MaterialKind:
    """The kind called ``name`` (``where``: the key's prefix, e.g. ``"rating.pinion"``)."""
    check_choice(f"{where}.material", name, tuple(MATERIALS))
    return MATERIALS[name]


def _bending_line(kind: MaterialKind, quality: str, core_hardness: str | None,
                  where: str) -> LimitLine:
    if core_hardness is None:
        return kind.bending[QUALITIES.index(quality)]
    if not (kind.core_variants and quality == "MQ"):
        raise InputError(
            f"{where}.core_hardness = {core_hardness!r}: ISO 6336-5 Table 1 has core-hardness "
            f"rows only for case_hardened MQ, not for {kind.name} {quality}")
    check_choice(f"{where}.core_hardness", core_hardness, CORE_HARDNESS)
    return kind.core_variants[CORE_HARDNESS.index(core_hardness)]


def _above(value: object, limit: float) -> bool:
    try:
        return float(value) > limit
    except (TypeError, ValueError):
        return False


def hardness_range(kind: str, quality: str, *, where: str) -> tuple[float, float, str]:
    """(lowest, highest, scale) of the surface hardness that both of the kind's lines of
    ``quality`` accept."""
    mat = material_kind(kind, where=where)
    check_choice(f"{where}.quality", quality, QUALITIES)
    i = QUALITIES.index(quality)
    c, b = mat.contact[i], mat.bending[i]
    return max(c.x_min, b.x_min), min(c.x_max, b.x_max), mat.scale


def material_limits(kind: str, quality: str, hardness: float, scale: str, *, where: str,
                    core_hardness: str | None = None, pitting_permitted: bool = False
                    ) -> MaterialLimits:
    """sigma_Hlim, sigma_Flim and the classes of a gear of material ``kind`` and ``quality``.

    Parameters
    ----------
    kind : a name of :data:`MATERIALS` (``"case_hardened"``).
    quality : ``"ML"``, ``"MQ"`` or ``"ME"``.
    hardness : surface hardness of the finished flank and root, on ``scale``.
    scale : ``"HV"`` or ``"HBW"``, as the user gave it (``surface_hardness_HV`` or
        ``surface_hardness_HBW``); it must be the scale of the kind's rows.
    where : prefix of the user's keys, e.g. ``"rating.pinion"``; errors name
        ``<where>.material``, ``<where>.quality``, ``<where>.surface_hardness_<scale>``,
        ``<where>.core_hardness``, ``<where>.pitting_permitted``.
    core_hardness : case-hardened MQ only: one of :data:`CORE_HARDNESS`; None takes the
        first (row 45, the smallest sigma_Flim).
    pitting_permitted : take ISO 6336-2's life line with limited pitting
        (``"pitting_permitted"``), for the kinds where it applies.

    Raises
    ------
    InputError
        Unknown kind, quality or core hardness; a hardness on the other scale; a hardness
        outside the range of the kind's lines (no clamping); a core hardness or permitted
        pitting that does not apply to the kind.
    """
    mat = material_kind(kind, where=where)
    check_choice(f"{where}.quality", quality, QUALITIES)
    if scale not in SCALES:
        raise InputError(f"{where}.surface_hardness_{scale} is not a key: the surface "
                         f"hardness is surface_hardness_HBW or surface_hardness_HV")
    key = f"{where}.surface_hardness_{scale}"
    if scale != mat.scale:
        raise InputError(
            f"{key} = {hardness!r} {scale}: ISO 6336-5 Table 1 gives the {mat.name} "
            f"({mat.symbol}) lines in {mat.scale}; give {where}.surface_hardness_{mat.scale} "
            f"(no conversion between HBW and HV is made: ISO 18265's are approximate)")
    i = QUALITIES.index(quality)
    contact = mat.contact[i]
    bending = _bending_line(mat, quality, core_hardness, where)
    lo, hi = max(contact.x_min, bending.x_min), min(contact.x_max, bending.x_max)
    note = (f"ISO 6336-5:2016 Table 1, {mat.name} {quality}: sigma_Hlim row {contact.row} "
            f"{contact.x_min:g}-{contact.x_max:g} {mat.scale}, sigma_Flim row {bending.row} "
            f"{bending.x_min:g}-{bending.x_max:g} {mat.scale}")
    gap = dict(mat.gap_notes).get(quality)
    if gap and _above(hardness, hi):
        note += "; " + gap
    check_range(key, hardness, lo, hi, unit=mat.scale, note=note)
    if pitting_permitted and not mat.may_permit_pitting:
        raise InputError(
            f"{where}.pitting_permitted = true: ISO 6336-2's life line with limited pitting "
            f"is for St, V, GGG (perl., bai.), GTS (perl.), Eh, IF; {mat.name} "
            f"({mat.symbol}) takes the {mat.pitting_life_line!r} line")
    x = float(hardness)
    return MaterialLimits(
        kind=mat.name, symbol=mat.symbol, quality=quality, hardness=x,
        hardness_scale=mat.scale, sigma_hlim=contact.value(x), sigma_flim=bending.value(x),
        contact_row=contact.row, bending_row=bending.row,
        pitting_life_line="pitting_permitted" if pitting_permitted else mat.pitting_life_line,
        bending_life_line=mat.bending_life_line, running_in=mat.running_in,
        bending_size_class=mat.bending_size_class)
