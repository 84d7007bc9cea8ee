"""TOML configuration -> frozen, validated SI inputs.

Config files carry their units in the key names (``module_mm``,
``pressure_angle_deg``, ``torque_Nm``, ``speed_rpm`` ...); this module is the one
place where they are converted to SI. Unknown keys are an error (a typo must
not silently fall back to a default).

A pair file looks like::

    [pinion]                      # the driving gear unless [operation] driver = "gear"
    teeth = 50
    module_mm = 3.0               # normal module
    pressure_angle_deg = 20.0     # normal pressure angle
    face_width_mm = 20.0
    bore_radius_mm = 25.0
    [pinion.material]
    youngs_modulus_GPa = 200.0
    poisson_ratio = 0.3
    density_kg_m3 = 7850.0

    [gear]
    teeth = 50
    ...

    [pair]
    centre_distance_mm = 150.0    # optional; default: from the profile shifts
    assembly_error_pinion_um = [0.0, 0.0]   # (e_x, e_y) of seed 001
    assembly_error_gear_um = [10.0, 10.0]

    [operation]
    torque_Nm = 340.0             # on the driving gear
    speed_rpm = 2340.0            # of the driving gear
    driver = "pinion"

    [stiffness]
    friction = 0.05               # constant coefficient, or "ehl" (seed 000 eq. 9)
    positions = 360               # samples per mesh cycle
    slices = 100                  # helical: slices over the face width
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pipeline.geometry.gear import GearSpec, Material
from pipeline.validation import InputError, check_choice, check_int_range, check_range

MM = 1e-3
UM = 1e-6
DEG = math.pi / 180.0
RPM = 2.0 * math.pi / 60.0

# TOML key -> (GearSpec field, factor to SI)
_GEAR_KEYS: dict[str, tuple[str, float | None]] = {
    "teeth": ("teeth", None),
    "module_mm": ("module", MM),
    "pressure_angle_deg": ("pressure_angle", DEG),
    "face_width_mm": ("face_width", MM),
    "helix_angle_deg": ("helix_angle", DEG),
    "hand": ("hand", None),
    "profile_shift": ("profile_shift", 1.0),
    "addendum_coef": ("addendum_coef", 1.0),
    "dedendum_coef": ("dedendum_coef", 1.0),
    "cutter_tip_radius_coef": ("cutter_tip_radius_coef", 1.0),
    "bore_radius_mm": ("bore_radius", MM),
    "rim_outer_radius_mm": ("bore_radius", MM),
    "internal": ("internal", None),
    "herringbone": ("herringbone", None),
    "groove_width_mm": ("groove_width", MM),
    "tip_radius_mm": ("tip_radius", MM),
    "name": ("name", None),
}
_MATERIAL_KEYS: dict[str, tuple[str, float | None]] = {
    "youngs_modulus_GPa": ("youngs_modulus", 1e9),
    "poisson_ratio": ("poisson_ratio", 1.0),
    "density_kg_m3": ("density", 1.0),
    "name": ("name", None),
}


def _convert(table: Mapping[str, Any], keys: dict, where: str) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in table.items():
        if k not in keys:
            raise InputError(
                f"[{where}] has unknown key {k!r}; allowed keys: {', '.join(sorted(keys))}"
            )
        name, factor = keys[k]
        out[name] = v if factor is None else float(v) * factor
    return out


def material_from_table(table: Mapping[str, Any], where: str = "material") -> Material:
    """Build a :class:`Material` from a TOML table (GPa, -, kg/m^3)."""
    return Material(**_convert(table, _MATERIAL_KEYS, where))


def gear_from_table(table: Mapping[str, Any], name: str) -> GearSpec:
    """Build a :class:`GearSpec` from a TOML table with unit-suffixed keys.

    ``helix_angle_deg`` sets ``hand = "right"`` unless ``hand`` is given.
    """
    table = dict(table)
    mat = table.pop("material", None)
    kw = _convert(table, _GEAR_KEYS, name)
    kw.setdefault("name", name)
    if mat is not None:
        kw["material"] = material_from_table(mat, f"{name}.material")
    if kw.get("helix_angle", 0.0) > 0 and "hand" not in kw:
        kw["hand"] = "right"
    for req in ("teeth", "module", "pressure_angle", "face_width"):
        if req not in kw:
            raise InputError(f"[{name}] is missing the required key for {req!r}")
    return GearSpec(**kw)


@dataclass(frozen=True)
class AssemblyErrors:
    """Centre displacements of seed 001 (m), in its frame: y along the nominal line of action.

    Attributes
    ----------
    pinion : (e_xp, e_yp) in m.
    gear : (e_xg, e_yg) in m.
    """

    pinion: tuple[float, float] = (0.0, 0.0)
    gear: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        for who, e in (("pinion", self.pinion), ("gear", self.gear)):
            if len(e) != 2:
                raise InputError(f"pair.assembly_error_{who}_um needs 2 values (e_x, e_y)")
            for i, v in enumerate(e):
                check_range(f"pair.assembly_error_{who}[{i}]", v, -5e-3, 5e-3, unit="m")

    @property
    def is_zero(self) -> bool:
        return not any(self.pinion) and not any(self.gear)


@dataclass(frozen=True)
class Operation:
    """Operating point of the driving gear.

    Attributes
    ----------
    torque : torque on the driving gear, N m (> 0).
    speed : speed of the driving gear, rad/s (> 0).
    driver : "pinion" or "gear".
    """

    torque: float = 100.0
    speed: float = 100.0
    driver: str = "pinion"

    def __post_init__(self) -> None:
        check_range("operation.torque_Nm", self.torque, 0.0, 1e8, lo_open=True, unit="N m")
        check_range("operation.speed", self.speed, 0.0, 1e5, lo_open=True, unit="rad/s")
        check_choice("operation.driver", self.driver, ("pinion", "gear"))


@dataclass(frozen=True)
class StiffnessOptions:
    """Options of the analytical mesh stiffness.

    Attributes
    ----------
    friction : constant friction coefficient mu (-), or the string "ehl" for the
        EHL formula of seed 000 eq. 9.
    positions : samples per mesh cycle (>= 8).
    slices : slices over the face width for helical gears (>= 1).
    foundation_correction : factor on the fillet-foundation stiffness when several
        pairs are in contact (seed 001 uses 1.1); 1 disables.
    roughness : RMS roughness S of the flanks, m (EHL friction).
    viscosity : dynamic viscosity of the oil at inlet temperature, Pa s (EHL friction).
    """

    friction: float | str = 0.0
    positions: int = 360
    slices: int = 100
    foundation_correction: float = 1.0
    roughness: float = 0.5e-6
    viscosity: float = 0.02

    def __post_init__(self) -> None:
        if isinstance(self.friction, str):
            check_choice("stiffness.friction", self.friction, ("ehl",))
        else:
            check_range("stiffness.friction", self.friction, 0.0, 0.5)
        check_int_range("stiffness.positions", self.positions, 8, 1_000_000)
        check_int_range("stiffness.slices", self.slices, 1, 10_000)
        check_range("stiffness.foundation_correction", self.foundation_correction, 0.5, 2.0)
        check_range("stiffness.roughness", self.roughness, 0.0, 1e-4, unit="m")
        check_range("stiffness.viscosity", self.viscosity, 1e-5, 10.0, unit="Pa s")


@dataclass(frozen=True)
class PairConfig:
    """A whole pair study as read from TOML (all SI)."""

    pinion: GearSpec
    gear: GearSpec
    centre_distance: float | None = None
    assembly_errors: AssemblyErrors = field(default_factory=AssemblyErrors)
    operation: Operation = field(default_factory=Operation)
    stiffness: StiffnessOptions = field(default_factory=StiffnessOptions)
    name: str = "pair"


def _section(doc: Mapping[str, Any], key: str) -> dict[str, Any]:
    v = doc.get(key, {})
    if not isinstance(v, Mapping):
        raise InputError(f"[{key}] must be a table")
    return dict(v)


def pair_config_from_dict(doc: Mapping[str, Any], name: str = "pair") -> PairConfig:
    """Build a :class:`PairConfig` from a parsed TOML document."""
    allowed = {"pinion", "gear", "pair", "operation", "stiffness", "name"}
    for k in doc:
        if k not in allowed and not isinstance(doc[k], Mapping):
            raise InputError(f"unknown top-level key {k!r}; allowed: {', '.join(sorted(allowed))}")
    if "pinion" not in doc or "gear" not in doc:
        raise InputError("a pair config needs both a [pinion] and a [gear] table")
    pinion = gear_from_table(doc["pinion"], "pinion")
    gear = gear_from_table(doc["gear"], "gear")
    p = _section(doc, "pair")
    pair_keys = {"centre_distance_mm", "assembly_error_pinion_um", "assembly_error_gear_um"}
    for k in p:
        if k not in pair_keys:
            raise InputError(
                f"[pair] has unknown key {k!r}; allowed: {', '.join(sorted(pair_keys))}"
            )
    cd = p.get("centre_distance_mm")
    errors = AssemblyErrors(
        pinion=tuple(float(v) * UM for v in p.get("assembly_error_pinion_um", (0.0, 0.0))),
        gear=tuple(float(v) * UM for v in p.get("assembly_error_gear_um", (0.0, 0.0))),
    )
    o = _section(doc, "operation")
    op_keys = {
        "torque_Nm": ("torque", 1.0),
        "speed_rpm": ("speed", RPM),
        "driver": ("driver", None),
    }
    op = Operation(**_convert(o, op_keys, "operation"))
    s = _section(doc, "stiffness")
    s_keys = {
        "friction": ("friction", None),
        "positions": ("positions", None),
        "slices": ("slices", None),
        "foundation_correction": ("foundation_correction", 1.0),
        "roughness_um": ("roughness", UM),
        "viscosity_mPas": ("viscosity", 1e-3),
    }
    st = StiffnessOptions(**_convert(s, s_keys, "stiffness"))
    return PairConfig(
        pinion=pinion,
        gear=gear,
        centre_distance=None if cd is None else float(cd) * MM,
        assembly_errors=errors,
        operation=op,
        stiffness=st,
        name=str(doc.get("name", name)),
    )


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file, with a clear error naming the file on a syntax error."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"config file {str(path)!r} does not exist")
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: {exc}") from None


def load_pair_config(path: str | Path) -> PairConfig:
    """Read a pair study from a TOML file."""
    path = Path(path)
    return pair_config_from_dict(load_toml(path), name=path.stem)
