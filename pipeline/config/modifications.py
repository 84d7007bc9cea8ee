"""``[<gear>.modifications]`` -> each gear's flank modifications.

A gear pair's ``[pinion.modifications]`` and ``[gear.modifications]``, a planetary set's
``[sun.modifications]``, ``[planet.modifications]`` and ``[ring.modifications]`` hold each
gear's modifications in the file's units (keys in
:data:`~pipeline.config.tables.GEAR_MODIFICATIONS`, model in
:mod:`pipeline.contact.modifications`; which mesh takes which table:
:meth:`pipeline.config.gearbox.Gearbox.mesh_contact`). A planet's table applies to both of
its flanks, the one meshing with the sun and the one meshing with the ring, each measured
from its own start of active profile in its own mesh and with face 1 on the side of the
sun's first face. A ring's tip is at its smaller diameter (its tip relief starts there and
runs outwards). ``[contact]``'s tip relief, crowning and slope keys are the short form of
the same model: one or the other, not both. A ``topography_csv`` is a
UTF-8 CSV file (a relative path is relative to the gearbox file) with a header naming its
columns and units: ``face_position_mm``, either ``roll_length_mm`` or ``diameter_mm``, and
``deviation_um`` (material removed), one row per grid point of a full grid (any order;
lines starting with ``#`` are comments).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.config import tables as T
from pipeline.config.schema import read_table, restated
from pipeline.config.signals import csv_path, csv_rows
from pipeline.contact.modifications import (
    GearModification,
    LeadModification,
    ProfileModification,
    Topography,
)
from pipeline.validation import InputError

TABLE = "modifications"
PROFILE = {"tip_relief": "tip_relief", "tip_relief_length": "tip_relief_length",
           "tip_relief_diameter": "tip_relief_diameter", "tip_relief_shape": "tip_relief_shape",
           "root_relief": "root_relief", "root_relief_length": "root_relief_length",
           "root_relief_diameter": "root_relief_diameter",
           "root_relief_shape": "root_relief_shape", "profile_crowning": "crowning",
           "profile_slope": "slope"}
LEAD = {"lead_crowning": "crowning", "helix_slope": "slope",
        "end_relief_face1": "end_relief_face1",
        "end_relief_face1_length": "end_relief_face1_length",
        "end_relief_face2": "end_relief_face2",
        "end_relief_face2_length": "end_relief_face2_length",
        "end_relief_shape": "end_relief_shape"}
"""Each key's field -> the field of the profile / lead dataclass it sets."""
SHORT_FORM = ("tip_relief_pinion_um", "tip_relief_length_pinion_mm", "tip_relief_gear_um",
              "tip_relief_length_gear_mm", "relief_shape", "crowning_um", "slope_deviation_um")
"""``[contact]`` keys that are the short form of the gears' modifications."""
COLUMNS = ("face_position_mm", "deviation_um")
PROFILE_COLUMNS = {"roll_length_mm": "roll_length", "diameter_mm": "diameter"}


def gear_modifications(doc: Mapping[str, Any], role: str,
                       base: Path | None) -> GearModification | None:
    """The modifications of ``[role.modifications]`` (None without the table)."""
    gear_table = doc.get(role)
    if not isinstance(gear_table, Mapping) or TABLE not in gear_table:
        return None
    where = f"{role}.{TABLE}"
    table = gear_table[TABLE]
    values = read_table(table, T.GEAR_MODIFICATIONS, where)
    short = [k for k in SHORT_FORM if k in doc.get("contact", {})]
    if short:
        tables = ("[pinion.modifications] and [gear.modifications]"
                  if role in ("pinion", "gear") else "[sun.modifications], "
                  "[planet.modifications] and [ring.modifications]")
        raise InputError(f"contact.{short[0]} is the short form of {tables}: give it in "
                         f"[{where}] instead (the file has both)")
    path = values.pop("topography_csv", None)
    with restated(where, T.GEAR_MODIFICATIONS, table):
        profile = ProfileModification(**{PROFILE[k]: values.pop(k) for k in list(values)
                                         if k in PROFILE})
        lead = LeadModification(**{LEAD[k]: values.pop(k) for k in list(values) if k in LEAD})
        grid = None if path is None else read_topography(csv_path(path, base),
                                                         f"{where}.topography_csv")
        return GearModification(profile=profile, lead=lead, topography=grid, **values)


def read_topography(path: Path, key: str) -> Topography:
    """A topography grid from a CSV file (module docstring); ``key`` names it in messages."""
    shown = f'{key} = "{path}"'
    rows = csv_rows(path, shown, "give a CSV file with columns face_position_mm, "
                    "roll_length_mm (or diameter_mm), deviation_um", comments=True)
    names = [n.strip() for n in rows[0]] if rows else []
    axis = [n for n in names if n in PROFILE_COLUMNS]
    if any(c not in names for c in COLUMNS) or len(axis) != 1:
        raise InputError(f"{shown}: the header {','.join(names) or '(none)'} must name "
                         "face_position_mm, one of roll_length_mm or diameter_mm, and "
                         "deviation_um")
    cols = [names.index(c) for c in (COLUMNS[0], axis[0], COLUMNS[1])]
    data = np.empty((len(rows) - 1, 3))
    for i, row in enumerate(rows[1:]):
        for j, c in enumerate(cols):
            cell = row[c].strip() if c < len(row) else ""
            try:
                data[i, j] = float(cell)
            except ValueError:
                raise InputError(f"{shown}: row {i + 1}, column {names[c]} holds {cell!r}, not "
                                 "a number") from None
    face, profile = np.unique(data[:, 0]), np.unique(data[:, 1])
    grid = np.full((face.size, profile.size), np.nan)
    grid[np.searchsorted(face, data[:, 0]), np.searchsorted(profile, data[:, 1])] = data[:, 2]
    if data.shape[0] != face.size * profile.size or np.isnan(grid).any():
        raise InputError(f"{shown}: {data.shape[0]} rows are not a full grid of the "
                         f"{face.size} face positions x {profile.size} {axis[0]} values they "
                         "name (one row per grid point, each once)")
    return Topography(face * 1e-3, profile * 1e-3, grid * 1e-6, PROFILE_COLUMNS[axis[0]],
                      f'{key} "{path.name}"')
