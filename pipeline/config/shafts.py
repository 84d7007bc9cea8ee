"""``[<gear>.shaft]`` tables of a gearbox file -> :class:`~pipeline.shaft.layout.ShaftLayout`.

A gear of a pair (``[pinion.shaft]``, ``[gear.shaft]``) and the sun and planets of a
planetary set may sit on a shaft::

    [pinion.shaft]
    model = "beam"                  # or "fe3d" (pipeline.shaft)
    gear_position_mm = 120.0        # the gear's mid-face from the shaft's first end
    torque_position_mm = 0.0        # where the torque is held (a coupling)
    hub = "rigid"                   # or "integral" (a pinion cut on its shaft)
    [[pinion.shaft.segments]]       # contiguous from 0
    start_mm = 0.0
    end_mm = 240.0
    outer_diameter_mm = 50.0
    inner_diameter_mm = 0.0
    [[pinion.shaft.bearings]]
    position_mm = 20.0
    radial_stiffness_N_per_m = 5.0e8   # left out: rigid
    tilting_stiffness_Nm_per_rad = 0.0   # "rigid": clamped
    axial = true                    # exactly one bearing locates the shaft
    [pinion.shaft.material]         # left out: the gear's

A planet's ``[planet.shaft]`` is its pin (:func:`pin_layout`): ``gear_position_mm``, the
pin's ``[[segments]]``, its ``[[bearings]]`` (where the carrier's cheeks hold the pin: a
radial and tilting stiffness or rigid; one ``tilting_stiffness_Nm_per_rad = "rigid"`` bearing
alone is a cantilevered, flexpin-like pin) and ``planet_bearing_radial_stiffness_N_per_m``
(the bearing between the planet and its pin; left out: rigid). The planet turns freely on
its pin, so the pin carries no torque (``torque_position_mm`` and ``hub`` are refused) and
the planet with its bearing moves as one rigid body with the pin's seat (the bearing's
radial give, uniform across the face, adds to the approach and to the dynamics' planet
support, not to the misalignment). The sun's and the pins' positions run from the same end
of the gearbox: whether a pin's clamped cheek is at the sun's coupling end or at the other
decides whether the pin's tilt adds to the sun's twist across the face or offsets it. Every
planet has the same pin. Shafts of helical and herringbone planetary sets are refused.

The seat is the gear's face width. Both shafts' positions run the same way along the axes
(from the same end of the gearbox); ``[operation] pinion_rotation`` ("clockwise", the
default, or "counterclockwise") is the pinion's sense of rotation seen from the end the
positions grow towards: with the driver it picks the loaded flanks, which set the sense of
a helical mesh's axial force and of the shafts' twist (:mod:`pipeline.shaft.misalignment`,
The other rotation). Every refusal names the key as written, with the index
of a segment or bearing (``pinion.shaft.bearings[1].position_mm``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from pipeline.config import tables as T
from pipeline.config.schema import build, read_table, restated
from pipeline.geometry.gear import GearSpec, Material
from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
from pipeline.validation import InputError, check_range

MODELS = ("beam", "fe3d")
PIN_REFUSED = {
    "torque_position_mm": "the planet turns freely on its pin, which carries no torque",
    "hub": "the planet and its bearing move with the pin's seat as one rigid body",
}


def _rows(table: Mapping[str, Any], name: str, where: str) -> list[Mapping[str, Any]]:
    rows = table.get(name)
    if rows is None:
        raise InputError(f"{where} needs [[{where}.{name}]] tables")
    if not isinstance(rows, list) or not all(isinstance(r, Mapping) for r in rows):
        raise InputError(f"{where}.{name}: expected [[{where}.{name}]] tables, one each")
    return rows


def shaft_layout(table: Mapping[str, Any], gear: GearSpec, where: str
                 ) -> tuple[str, ShaftLayout]:
    """(model, layout) of one ``[<gear>.shaft]`` table (module docstring)."""
    plain = {k: v for k, v in table.items() if k not in ("segments", "bearings")}
    values = read_table(plain, T.SHAFT, where, subtables=("material",))
    model = values.pop("model", "beam")
    segments = tuple(build(ShaftSegment, row, T.SHAFT_SEGMENT, f"{where}.segments[{i}]")
                     for i, row in enumerate(_rows(table, "segments", where)))
    bearings = []
    for i, row in enumerate(_rows(table, "bearings", where)):
        b = read_table(row, T.SHAFT_BEARING, f"{where}.bearings[{i}]")
        b.setdefault("radial_stiffness", math.inf)
        if b.get("tilting_stiffness") == "rigid":
            b["tilting_stiffness"] = math.inf
        with restated(f"{where}.bearings[{i}]", T.SHAFT_BEARING, row):
            bearings.append(Bearing(**b))
    material = gear.material if "material" not in table else build(
        Material, table["material"], T.MATERIAL, f"{where}.material")
    if model not in MODELS:  # the schema's choices refuse it first
        raise InputError(f"{where}.model = {model!r} is not one of {MODELS}")
    with restated(where, T.SHAFT, table):
        return model, ShaftLayout(segments, seat_width=gear.face_width,
                                  bearings=tuple(bearings), material=material, name=where,
                                  **values)


def pin_layout(table: Mapping[str, Any], planet: GearSpec, where: str = "planet.shaft"
               ) -> tuple[str, ShaftLayout, float]:
    """(model, layout, planet bearing's radial stiffness N/m, ``inf`` rigid) of a planet's
    ``[planet.shaft]`` table, its pin (module docstring); the layout holds the pin against
    rotation at its axial bearing, where no torque reaches it."""
    for key, why in PIN_REFUSED.items():
        if key in table:
            raise InputError(f"{where}.{key}: {why}; leave it out")
    plain = {k: v for k, v in table.items() if k not in ("segments", "bearings")}
    values = read_table(plain, T.PLANET_PIN, where, subtables=("material",))
    k_bearing = values.pop("planet_bearing_radial_stiffness", math.inf)
    if k_bearing != math.inf:  # inf: rigid, which check_range refuses as non-finite
        check_range(f"{where}.planet_bearing_radial_stiffness_N_per_m", k_bearing, 0.0, 1e15,
                    lo_open=True, unit="N/m")
    rows = {k: v for k, v in table.items() if k not in T.PIN_ONLY}
    axial = [float(r.get("position_mm", 0.0)) for r in _rows(table, "bearings", where)
             if r.get("axial") is True]
    rows["torque_position_mm"] = axial[0] if len(axial) == 1 else float(
        _rows(table, "bearings", where)[0].get("position_mm", 0.0))
    model, layout = shaft_layout(rows, planet, where)
    return model, layout, k_bearing
