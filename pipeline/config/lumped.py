"""``[lumped_model]``: a published lumped dynamic model given by its parameters.

Some references give masses, radii and stiffnesses but no tooth geometry (Lin and
Parker 1999's example planetary set). Such a model is written directly::

    [lumped_model]
    model = "planetary"            # "planetary" | "herringbone_planetary" | "spur_pair"
    n_planets = 4
    mass_sun_kg = 0.4
    base_radius_sun_mm = 38.7
    mesh_frequency_Hz = 1500.0
    phase_sun = [0.0, 0.25, 0.5, 0.75]
    [lumped_model.sun_mesh_stiffness]    # planetary; spur_pair: [lumped_model.mesh_stiffness]
    kind = "rectangular"
    ...

The keys are the fields of the model's dataclass with the unit suffix the field's
quantity takes (:data:`FIELD_UNITS`): ``mass_*`` kg, ``inertia_*`` kg m^2, radii mm,
angles deg, translational stiffness N/m, torsional N m/rad, torques N m, speeds rpm;
``mesh_frequency_Hz`` sets the mesh period. Everything the model checks on
construction (positive masses, planets that do not overlap, a ring outside the
planets) is checked here too, in the file's units.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from pipeline.config.schema import Key, read_table, restated
from pipeline.config.signals import signal_from_table
from pipeline.validation import InputError

MODELS = ("planetary", "herringbone_planetary", "spur_pair")
_SIGNALS = {"spur_pair": {"mesh_stiffness": "mesh_stiffness"},
            "planetary": {"sun_mesh_stiffness": "k_sun_mesh",
                          "ring_mesh_stiffness": "k_ring_mesh"},
            "herringbone_planetary": {"sun_mesh_stiffness": "k_sun_mesh",
                                      "ring_mesh_stiffness": "k_ring_mesh"}}
# field-name pattern -> unit suffix (first match wins)
FIELD_UNITS: tuple[tuple[str, str], ...] = (
    ("mass_", "kg"), ("inertia_", "kgm2"), ("base_radius_", "mm"), ("carrier_radius", "mm"),
    ("engaged_width", "mm"), ("axial_slide", "mm"), ("pressure_angle_", "deg"),
    ("base_helix_angle", "deg"), ("planet_angles", "deg"), ("kt_", "Nm_per_rad"),
    ("groove", "Nm_per_rad"), ("kz_", "N_per_m"), ("k_", "N_per_m"),
    ("bearing_stiffness", "N_per_m"), ("bearing_damping", "Ns_per_m"), ("sun_torque", "Nm"),
    ("torque", "Nm"), ("carrier_speed", "rpm"), ("speed", "rpm"),
)
_SKIP = {"mesh_stiffness", "k_sun_mesh", "k_ring_mesh", "transmission_error",
         "friction_stiffness", "friction_torque_pinion", "friction_torque_gear",
         "groove_translational", "half_coupling", "groove_rotations", "e_sun_mesh",
         "e_ring_mesh", "t1t2"}  # t1t2: the pair's drawing, derived from gear geometry


def _model_class(name: str):
    from pipeline.dynamics.models.herringbone_planetary import HerringbonePlanetaryModel
    from pipeline.dynamics.models.planetary import PlanetaryModel
    from pipeline.dynamics.models.spur_pair import SpurPairModel

    return {"planetary": PlanetaryModel, "herringbone_planetary": HerringbonePlanetaryModel,
            "spur_pair": SpurPairModel}[name]


def _kind(annotation: str, default: Any) -> str:
    if "tuple" in annotation:
        return "numbers"
    if annotation.startswith("bool") or isinstance(default, bool):
        return "boolean"
    if annotation.startswith("int"):
        return "integer"
    if annotation.startswith("str"):
        return "string"
    return "number"


def model_keys(cls) -> tuple[Key, ...]:
    """The file keys of a lumped model's dataclass fields (unit suffix by quantity)."""
    hints = {f.name: str(f.type) for f in dataclasses.fields(cls)}
    keys = []
    for f in dataclasses.fields(cls):
        if f.name in _SKIP:
            continue
        if f.name == "mesh_period":
            keys.append(Key("mesh_frequency_Hz", field="mesh_frequency"))
            continue
        suffix = next((u for p, u in FIELD_UNITS if f.name.startswith(p)), "")
        name = f"{f.name}_{suffix}" if suffix else f.name
        keys.append(Key(name, _kind(hints[f.name], f.default), field=f.name))
    return tuple(keys)


def lumped_model(table: Mapping[str, Any], base: Path | None) -> Any:
    """The model dataclass the ``[lumped_model]`` table describes."""
    if not isinstance(table, Mapping):
        raise InputError("[lumped_model] must be a table")
    if "model" not in table:
        raise InputError("[lumped_model] needs the key 'model' (one of "
                         f"{', '.join(map(repr, MODELS))})")
    name = table["model"]
    if name not in MODELS:
        raise InputError(f"lumped_model.model = {name!r} is not one of "
                         f"{', '.join(map(repr, MODELS))}")
    cls = _model_class(name)
    keys = model_keys(cls) + (Key("model", "string", choices=MODELS),)
    signals = _SIGNALS[name]
    values = read_table(table, keys, "lumped_model", subtables=tuple(signals))
    values.pop("model")
    if "mesh_frequency" in values:
        f = values.pop("mesh_frequency")
        if not 1e-3 <= f <= 1e6:
            raise InputError(f"lumped_model.mesh_frequency_Hz = {f:.6g} Hz is outside the "
                             "allowed range [0.001, 1e+06] Hz")
        values["mesh_period"] = 1.0 / f
    for sub, fname in signals.items():
        if sub in table:
            values[fname] = signal_from_table(table[sub], f"lumped_model.{sub}", base)
    if name == "spur_pair" and "mesh_stiffness" not in values:
        raise InputError("[lumped_model] model = 'spur_pair' needs "
                         "[lumped_model.mesh_stiffness]")
    with restated("lumped_model", keys, table):
        return cls(**values)


__all__ = ["FIELD_UNITS", "MODELS", "lumped_model", "model_keys"]
