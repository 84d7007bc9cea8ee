"""``[rating]`` of a gearbox file -> :class:`~pipeline.rating.options.RatingOptions`.

The mesh-wide keys (:data:`~pipeline.config.tables.RATING`) and one ``[rating.<gear>]``
table per gear (:data:`~pipeline.config.tables.RATING_GEAR`). A gear's allowable stress
numbers come from its ISO 6336-5 material (``material``, ``quality`` and the surface
hardness on the scale of the material's lines; :mod:`pipeline.rating.materials`), or are
given (``sigma_Hlim_MPa``, ``sigma_Flim_MPa``): a value given replaces the table's, and the
keys that would then select nothing (quality, hardness, core hardness) are refused. The
material also sets the gear's classes (running-in, life lines, size factor). A kind whose
lines are constant (case-hardened, nitrided) needs no hardness.

Where K_Hbeta comes from (``face_load_factor``) when the file does not say: a pair whose
pinion or gear sits on a shaft (``[pinion.shaft]``, ``[gear.shaft]``) takes the loaded
contact's, which the run solves with the shafts' deflection (:mod:`pipeline.run.shafts`),
as a system-deflection rating (KISSsoft, MASTA) takes the shaft model's; every other file
takes ISO 6336-1 method C's. The rating shows the other sources beside the one used, so a
``[rating.pinion_shaft]`` (method C's own picture of the pinion's shaft) next to a
``[pinion.shaft]`` is shown as method C's K_Hbeta beside the system's, not used.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from typing import Any

from pipeline.config import tables as T
from pipeline.config.schema import build, read_table, restated
from pipeline.contact.iso_root_stress import ShaperCutter
from pipeline.rating.face_load import FaceLoadInputs, PinionShaft
from pipeline.rating.materials import (
    MATERIALS,
    QUALITIES,
    hardness_range,
    material_kind,
    material_limits,
)
from pipeline.rating.options import GearRatingOptions, RatingOptions, oil_grade_viscosity
from pipeline.rating.spectrum import BIN_KEYS, LoadSpectrum
from pipeline.validation import InputError

_TABLE_KEYS = ("quality", "surface_hardness_HV", "surface_hardness_HBW", "core_hardness",
               "pitting_permitted")


def _hardness(table: Mapping[str, Any], kind: str, quality: str, where: str
              ) -> tuple[float, str]:
    """(hardness, scale) as given, or the range's low end for constant lines."""
    for scale in ("HV", "HBW"):
        if f"surface_hardness_{scale}" in table:
            return table[f"surface_hardness_{scale}"], scale
    lo, hi, scale = hardness_range(kind, quality, where=where)
    mat = MATERIALS[kind]
    i = QUALITIES.index(quality)
    if mat.contact[i].slope == 0.0 and mat.bending[i].slope == 0.0:
        return lo, scale  # neither line depends on it
    raise InputError(f"{where}.surface_hardness_{scale} is needed: ISO 6336-5's {kind} "
                     f"{quality} lines depend on it (allowed {lo:g} to {hi:g} {scale})")


NOTCH_CLASS = {"Eh": "hardened", "IF": "hardened", "V": "through_hardened",
               "V (cast)": "through_hardened", "GTS (perl.)": "through_hardened",
               "GGG (perl., bai.)": "through_hardened"}
"""The root's slip-layer class of ISO 6336-5's kinds by symbol (the others: not built)."""
CUTTER_KEYS = {"cutter_teeth": "teeth", "cutter_profile_shift": "profile_shift",
               "cutter_tip_radius_coef": "tip_radius_coef",
               "cutter_addendum_coef": "addendum_coef"}


def _cutter(values: dict[str, Any], table: Mapping[str, Any], where: str, internal: bool
            ) -> ShaperCutter | None:
    given = {CUTTER_KEYS[k]: table[k] for k in CUTTER_KEYS if k in table}
    for k in CUTTER_KEYS:
        values.pop(k, None)
    if not given:
        return None
    if not internal:
        raise InputError(f"{where}.{next(k for k in CUTTER_KEYS if k in table)} applies to an "
                         "internal gear (its pinion-type cutter); this gear is external")
    if "teeth" not in given:
        raise InputError(f"{where}.cutter_teeth is needed with the cutter's other keys")
    return ShaperCutter(**given, name=f"{where}.cutter")


def gear_rating(table: Mapping[str, Any], where: str, internal: bool = False
                ) -> GearRatingOptions:
    """One ``[rating.<gear>]`` table (module docstring); ``internal``: the gear is internal
    (the cutter keys apply)."""
    values = read_table(table, T.RATING_GEAR, where)
    cutter = _cutter(values, table, where, internal)
    kind = values.pop("material", "case_hardened")
    for k in ("quality", "surface_hardness", "core_hardness", "pitting_permitted"):
        values.pop(k, None)  # read from the table as written: they select a row
    material_kind(kind, where=where)  # an unknown kind: the allowed names
    quality = table.get("quality", "MQ")
    given = [k for k in ("sigma_Hlim_MPa", "sigma_Flim_MPa") if k in table]
    if len(given) == 2:
        extra = [k for k in _TABLE_KEYS[:-1] if k in table]
        if extra:
            raise InputError(f"{where}.{extra[0]} selects ISO 6336-5's numbers, but "
                             f"{where}.sigma_Hlim_MPa and sigma_Flim_MPa are both given")
        hardness, scale = hardness_range(kind, quality, where=where)[::2]  # classes only
    else:
        hardness, scale = _hardness(table, kind, quality, where)
    typed = any(f"surface_hardness_{s}" in table for s in ("HV", "HBW"))
    limits = material_limits(kind, quality, hardness, scale, where=where,
                             core_hardness=table.get("core_hardness"),
                             pitting_permitted=table.get("pitting_permitted", False))
    values.setdefault("sigma_hlim", limits.sigma_hlim)
    values.setdefault("sigma_flim", limits.sigma_flim)
    source = limits.source if typed else (
        f"ISO 6336-5:2016 Table 1, {kind} ({limits.symbol}) {quality}: rows "
        f"{limits.contact_row} (sigma_Hlim) and {limits.bending_row} (sigma_Flim)")
    source = source if not given else (
        f"{', '.join(given)} given; classes of {kind} ({limits.symbol})" if len(given) == 2
        else f"{source}; {given[0]} given")
    with restated(where, T.RATING_GEAR, table):
        return GearRatingOptions(
            **values, material=source, running_in=limits.running_in,
            pitting_line=limits.pitting_life_line, bending_line=limits.bending_life_line,
            size_class=limits.bending_size_class, notch_class=NOTCH_CLASS.get(limits.symbol),
            cutter=cutter)


def rating_options(doc: Mapping[str, Any], kind: str, roles: tuple[str, ...],
                   internal: frozenset[str] = frozenset()) -> RatingOptions | None:
    """``[rating]`` with a ``[rating.<gear>]`` table per gear (``roles``) it names; the oil
    by ``oil_grade`` or ``oil_viscosity_40_mm2_per_s``, not both. None without the table."""
    if "rating" not in doc:
        return None
    if kind not in ("pair", "planetary"):
        raise InputError(f"[rating] rates gears in mesh; this file describes no mesh "
                         f"({kind})")
    table = dict(doc["rating"])
    spectrum = _spectrum(table.pop("spectrum", None))
    values = read_table(table, T.RATING, "rating",
                        subtables=(*roles, "method_c", "pinion_shaft"))
    if "life_h" in table and "life_cycles" in table:
        raise InputError("rating.life_h and rating.life_cycles both give the required life; "
                         "keep one")
    grade = values.pop("oil_grade", None)
    if grade is not None:
        if "viscosity_40" in values:
            raise InputError("rating.oil_grade and rating.oil_viscosity_40_mm2_per_s both give "
                             "the oil's viscosity; keep one")
        values["viscosity_40"] = oil_grade_viscosity(grade)
    if kind == "pair" and values.get("load_sharing") is not None:
        raise InputError(f"rating.load_sharing = {table['load_sharing']!r} applies to a "
                         "planetary set (K_gamma of its planets); a pair carries all the load")
    if "face_load_factor" not in table and kind == "pair" and on_shafts(doc, roles):
        values["face_load_factor"] = "contact"
    gears = {role: gear_rating(table[role], f"rating.{role}", role in internal)
             for role in roles if role in table}
    shaft = None
    if "pinion_shaft" in table:
        shaft = build(functools.partial(PinionShaft, where="rating.pinion_shaft"),
                      table["pinion_shaft"], T.RATING_PINION_SHAFT, "rating.pinion_shaft")
    method_c = build(functools.partial(FaceLoadInputs, where="rating.method_c"),
                     table.get("method_c", {}), T.RATING_METHOD_C, "rating.method_c",
                     shaft=shaft)
    with restated("rating", T.RATING, table):
        return RatingOptions(**values, gears=gears, method_c=method_c, spectrum=spectrum)


def on_shafts(doc: Mapping[str, Any], roles: tuple[str, ...]) -> bool:
    """True when a gear of ``roles`` sits on a shaft (a ``[<gear>.shaft]`` table)."""
    return any(isinstance(doc.get(r), Mapping) and "shaft" in doc[r] for r in roles)


def _spectrum(rows: Any) -> LoadSpectrum | None:
    """``[[rating.spectrum]]`` rows (``torque_Nm``, ``speed_rpm``, ``duration_h``)."""
    if rows is None:
        return None
    if not isinstance(rows, list) or not all(isinstance(r, Mapping) for r in rows):
        raise InputError("rating.spectrum: expected [[rating.spectrum]] tables, one per bin, "
                         f"with {', '.join(BIN_KEYS)}")
    return LoadSpectrum.from_rows(rows)
