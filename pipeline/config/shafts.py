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
    tilting_stiffness_Nm_per_rad = 0.0
    axial = true                    # exactly one bearing locates the shaft
    [pinion.shaft.material]         # left out: the gear's

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
from pipeline.validation import InputError

MODELS = ("beam", "fe3d")


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
