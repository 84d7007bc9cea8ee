"""Units of the input files: one table, defined once.

Every key of a gearbox file carries its unit as a suffix (``module_mm``,
``torque_Nm``, ``speed_rpm``, ``youngs_modulus_GPa``); keys without a suffix
are dimensionless (``teeth``, ``profile_shift``, ``poisson_ratio``). This module
is the only place where those suffixes are turned into SI factors, and back
when a message shows a value in the unit the user wrote.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Unit:
    """A unit of the input files.

    Attributes
    ----------
    suffix : how it ends a key name, e.g. ``"mm"`` in ``module_mm``.
    label : how it is printed, e.g. ``"mm"``, ``"N m"``, ``"kg m^2"``.
    factor : value in SI = value in this unit * factor.
    si : the SI unit it converts to (for docs and messages).
    """

    suffix: str
    label: str
    factor: float
    si: str

    def to_si(self, value: float) -> float:
        """Value in this unit -> SI."""
        return value * self.factor

    def from_si(self, value: float) -> float:
        """SI value -> this unit."""
        return value / self.factor


DIMENSIONLESS = Unit("", "", 1.0, "-")

UNITS: tuple[Unit, ...] = (
    Unit("m", "m", 1.0, "m"),
    Unit("mm", "mm", 1e-3, "m"),
    Unit("um", "um", 1e-6, "m"),
    Unit("deg", "deg", math.pi / 180.0, "rad"),
    Unit("rad", "rad", 1.0, "rad"),
    Unit("rpm", "rpm", 2.0 * math.pi / 60.0, "rad/s"),
    Unit("rad_per_s", "rad/s", 1.0, "rad/s"),
    Unit("Hz", "Hz", 1.0, "Hz"),
    Unit("s", "s", 1.0, "s"),
    Unit("N", "N", 1.0, "N"),
    Unit("Nm", "N m", 1.0, "N m"),
    Unit("kW", "kW", 1e3, "W"),
    Unit("GPa", "GPa", 1e9, "Pa"),
    Unit("MPa", "MPa", 1e6, "Pa"),
    Unit("kg", "kg", 1.0, "kg"),
    Unit("kgm2", "kg m^2", 1.0, "kg m^2"),
    Unit("kg_m3", "kg/m^3", 1.0, "kg/m^3"),
    Unit("N_per_m", "N/m", 1.0, "N/m"),
    Unit("N_per_mm_um", "N/(mm um)", 1e9, "N/m^2"),
    Unit("Ns_per_m", "N s/m", 1.0, "N s/m"),
    Unit("Nm_per_rad", "N m/rad", 1.0, "N m/rad"),
    Unit("Nm2", "N m^2", 1.0, "N m^2"),
    Unit("mPas", "mPa s", 1e-3, "Pa s"),
    Unit("mm2_per_s", "mm^2/s", 1e-6, "m^2/s"),
    Unit("h", "h", 3600.0, "s"),
    Unit("percent", "%", 1.0, "%"),
    # hardness numbers: no SI unit, no conversion between scales (ISO 18265's are approximate)
    Unit("HV", "HV", 1.0, "HV"),
    Unit("HBW", "HBW", 1.0, "HBW"),
    Unit("HB", "HB", 1.0, "HB"),
)
_BY_SUFFIX = {u.suffix: u for u in UNITS}


def unit_of_key(key: str) -> Unit:
    """The unit a key name ends with (longest matching suffix), or :data:`DIMENSIONLESS`.

    >>> unit_of_key("module_mm").label
    'mm'
    >>> unit_of_key("bearing_stiffness_N_per_m").factor
    1.0
    """
    parts = key.split("_")
    for n in range(min(len(parts) - 1, 4), 0, -1):
        suffix = "_".join(parts[-n:])
        if suffix in _BY_SUFFIX:
            return _BY_SUFFIX[suffix]
    return DIMENSIONLESS


def unit(suffix: str) -> Unit:
    """The unit with this suffix (``"mm"``, ``"deg"``, ...); KeyError if unknown."""
    return _BY_SUFFIX[suffix]


def format_value(value: float, u: Unit) -> str:
    """``value`` (in unit ``u``) with up to 6 significant digits and the unit label."""
    text = f"{value:.6g}"
    return f"{text} {u.label}" if u.label else text


def key_label(key: str) -> str:
    """A dotted file key as an axis label: words and unit.

    >>> key_label("contact.tip_relief_pinion_um")
    'contact: tip relief pinion (um)'
    >>> key_label("pinion.teeth")
    'pinion: teeth'
    """
    table, _, name = key.rpartition(".")
    u = unit_of_key(name)
    words = name[: len(name) - len(u.suffix) - 1] if u.suffix else name
    text = words.replace("_", " ")
    text = f"{table}: {text}" if table else text
    return f"{text} ({u.label})" if u.label else text
