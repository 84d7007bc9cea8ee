"""TOML -> :class:`GrooveSpec`: a ``[gear]`` table (see :mod:`pipeline.config`) and ``[groove]``.

Example (``workflows/configs/seed002_sun_groove.toml``)::

    [gear]                         # the herringbone sun gear
    teeth = 21
    module_mm = 15.0
    pressure_angle_deg = 25.0
    helix_angle_deg = 8.0
    face_width_mm = 370.0          # both toothed halves together
    herringbone = true
    groove_width_mm = 40.0
    [gear.material]
    youngs_modulus_GPa = 206.0
    poisson_ratio = 0.3

    [groove]
    bottom_diameter_mm = 270.0
    shaft_length_right_mm = 340.0  # beyond the right gear face
    shaft_diameter_right_mm = 240.0
    torque_Nm = 148000.0           # sun torque for the phase shift
    mesh_size_mm = 30.0
    teeth_model = "root_cylinder"  # or "helical_teeth"
    coupling = "distributed"       # or "rigid", "tooth_forces"
    planets = 4                    # planets loading the sun ("tooth_forces")
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from pipeline.config import gear_from_table, load_toml
from pipeline.fem.groove.spec import GrooveSpec
from pipeline.validation import InputError

MM = 1e-3
_GROOVE_KEYS: dict[str, tuple[str, float | None]] = {
    "bottom_diameter_mm": ("groove_bottom_diameter", MM),
    "shaft_length_left_mm": ("shaft_length_left", MM),
    "shaft_length_right_mm": ("shaft_length_right", MM),
    "shaft_diameter_left_mm": ("shaft_diameter_left", MM),
    "shaft_diameter_right_mm": ("shaft_diameter_right", MM),
    "torque_Nm": ("sun_torque", 1.0),
    "mesh_size_mm": ("mesh_size", MM),
    "teeth_model": ("teeth_model", None),
    "coupling": ("coupling", None),
    "planets": ("planets", None),
}


def groove_spec_from_dict(doc: Mapping[str, Any], name: str = "groove") -> GrooveSpec:
    """Build a :class:`GrooveSpec` from a parsed TOML document (mm, N m -> SI)."""
    for k in doc:
        if k not in ("gear", "groove", "name"):
            raise InputError(f"unknown top-level key {k!r}; allowed: 'gear', 'groove', 'name'")
    if "gear" not in doc or "groove" not in doc:
        raise InputError("a groove config needs a [gear] and a [groove] table")
    gear = gear_from_table(doc["gear"], str(doc.get("name", name)))
    kw: dict[str, Any] = {}
    for k, v in doc["groove"].items():
        if k not in _GROOVE_KEYS:
            raise InputError(f"[groove] has unknown key {k!r}; allowed keys: "
                             f"{', '.join(sorted(_GROOVE_KEYS))}")
        field, factor = _GROOVE_KEYS[k]
        kw[field] = v if factor is None else float(v) * factor
    if "groove_bottom_diameter" not in kw:
        raise InputError("[groove] is missing the required key 'bottom_diameter_mm'")
    return GrooveSpec(gear=gear, **kw)


def load_groove_config(path: str | Path) -> GrooveSpec:
    """Read a groove study from a TOML file."""
    path = Path(path)
    return groove_spec_from_dict(load_toml(path), name=path.stem)
