"""TOML configuration of a dynamics study -> model inputs and solver options (SI inside).

Keys carry their unit as a suffix, converted here and nowhere else::

    model = "spur_pair"            # "spur_pair" | "planetary" | "herringbone_planetary"
    name = "seed001-base"

    [parameters]                   # fields of the model dataclass, unit-suffixed
    pinion_teeth = 50
    mass_pinion_kg = 2.52
    inertia_pinion_kgm2 = 7.4e-3
    base_radius_pinion_mm = 70.477
    bearing_stiffness_N_per_m = 1e8
    torque_Nm = 340.0
    speed_rpm = 2340.0

    [mesh_stiffness]       # spur pair; planetary: [sun_mesh_stiffness], [ring_mesh_stiffness]
    kind = "rectangular"           # rectangular | contact_line | harmonic | constant | csv
    k_single_N_per_m = 2.0e8
    k_double_N_per_m = 3.4e8
    contact_ratio = 1.65
    samples = 360

    [solver]                       # response
    method = "harmonic_balance"    # harmonic_balance | floquet | time
    n_harmonics = 40
    segments = 720
    periods = 200

    [sweep]
    f_min_Hz = 10.0
    f_max_Hz = 5000.0
    points = 500                   # --full; the coarse default uses points_coarse
    points_coarse = 100
    method = "harmonic_balance"

Unknown keys are errors. Suffixes: _mm, _um, _deg, _rpm, _kg, _kgm2, _N_per_m,
_Ns_per_m, _Nm, _Nm_per_rad, _Hz, _s, _m (plain SI) or none for dimensionless.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.config import load_toml
from pipeline.dynamics.excitation import (
    contact_line_stiffness,
    harmonic_signal,
    rectangular_mesh_stiffness,
)
from pipeline.dynamics.models.herringbone_planetary import HerringbonePlanetaryModel
from pipeline.dynamics.models.planetary import PlanetaryModel
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_choice

RPM = 2 * math.pi / 60
_SUFFIX = {
    "_mm": 1e-3,
    "_um": 1e-6,
    "_deg": math.pi / 180,
    "_rpm": RPM,
    "_kg": 1.0,
    "_kgm2": 1.0,
    "_N_per_m": 1.0,
    "_Ns_per_m": 1.0,
    "_Nm": 1.0,
    "_Nm_per_rad": 1.0,
    "_Hz": 1.0,
    "_s": 1.0,
    "_m": 1.0,
}
MODELS = {
    "spur_pair": SpurPairModel,
    "planetary": PlanetaryModel,
    "herringbone_planetary": HerringbonePlanetaryModel,
}
# fields whose TOML name differs from the dataclass field
_RENAME = {"mesh_frequency": "mesh_period"}


def _split(key: str) -> tuple[str, float]:
    for suf in sorted(_SUFFIX, key=len, reverse=True):
        if key.endswith(suf):
            return key[: -len(suf)], _SUFFIX[suf]
    return key, 1.0


def _scaled(v: Any, f: float) -> Any:
    if isinstance(v, (list, tuple)):
        return tuple(_scaled(x, f) for x in v)
    if isinstance(v, bool) or isinstance(v, str) or f == 1.0 and isinstance(v, int):
        return v
    return float(v) * f


def signal_from_table(
    table: Mapping[str, Any], where: str, base: Path | None = None
) -> PeriodicSignal:
    """A periodic stiffness (N/m) from a ``[..._stiffness]`` table (see module doc)."""
    t = dict(table)
    kind = check_choice(
        f"{where}.kind",
        t.pop("kind", "constant"),
        ("rectangular", "contact_line", "harmonic", "constant", "csv"),
    )
    kw = {}
    for k, v in t.items():
        name, f = _split(k)
        kw[name] = _scaled(v, f)
    allowed = {
        "rectangular": {"k_single", "k_double", "contact_ratio", "samples", "start"},
        "contact_line": {"k_mean", "transverse_ratio", "overlap_ratio", "samples"},
        "harmonic": {"mean", "amplitudes", "phases", "samples"},
        "constant": {"value"},
        "csv": {"path", "column"},
    }[kind]
    for k in kw:
        if k not in allowed:
            raise InputError(
                f"[{where}] has unknown key {k!r} for kind {kind!r}; "
                f"allowed: {', '.join(sorted(allowed))}"
            )
    if kind == "rectangular":
        return rectangular_mesh_stiffness(**kw)
    if kind == "contact_line":
        return contact_line_stiffness(**kw)
    if kind == "harmonic":
        return harmonic_signal(**kw)
    if kind == "constant":
        return PeriodicSignal(np.full(8, float(kw["value"])))
    path = Path(kw["path"])
    if base is not None and not path.is_absolute():
        path = base / path
    if not path.is_file():
        raise InputError(f"[{where}].path = {str(path)!r} does not exist")
    data = np.genfromtxt(path, delimiter=",", names=True)
    col = kw.get("column", data.dtype.names[-1])
    if col not in data.dtype.names:
        raise InputError(f"[{where}].column = {col!r} is not one of {data.dtype.names}")
    return PeriodicSignal(np.asarray(data[col], dtype=float))


@dataclass(frozen=True)
class SolverOptions:
    """Response solver settings (see :mod:`pipeline.dynamics.commands`)."""

    method: str = "harmonic_balance"
    n_harmonics: int = 40
    segments: int | None = None
    periods: int = 200

    def __post_init__(self) -> None:
        check_choice("solver.method", self.method, ("harmonic_balance", "floquet", "time"))


@dataclass(frozen=True)
class SweepOptions:
    """Frequency sweep settings: mesh frequencies in Hz."""

    f_min: float = 10.0
    f_max: float = 5000.0
    points: int = 500
    points_coarse: int = 100
    method: str = "harmonic_balance"
    n_harmonics: int = 20

    def frequencies(self, full: bool) -> np.ndarray:
        """Mesh frequencies of the sweep, shape (points,), Hz."""
        return np.linspace(self.f_min, self.f_max, self.points if full else self.points_coarse)


@dataclass(frozen=True)
class DynamicsConfig:
    """A parsed study: the model inputs and the solver options."""

    model: object
    solver: SolverOptions = field(default_factory=SolverOptions)
    sweep: SweepOptions = field(default_factory=SweepOptions)
    name: str = "dynamics"
    raw: dict = field(default_factory=dict, compare=False)


def _options(cls, table: Mapping[str, Any], where: str):
    kw = {}
    names = {f.name for f in fields(cls)}
    for k, v in table.items():
        name, f = _split(k)
        if name not in names:
            raise InputError(
                f"[{where}] has unknown key {k!r}; allowed: {', '.join(sorted(names))}"
            )
        kw[name] = _scaled(v, f)
    return cls(**kw)


def config_from_dict(
    doc: Mapping[str, Any], name: str = "dynamics", base: Path | None = None
) -> DynamicsConfig:
    """Build a :class:`DynamicsConfig` from a parsed TOML document."""
    allowed = {
        "model",
        "name",
        "parameters",
        "mesh_stiffness",
        "sun_mesh_stiffness",
        "ring_mesh_stiffness",
        "solver",
        "sweep",
    }
    for k in doc:
        if k not in allowed:
            raise InputError(f"unknown top-level key {k!r}; allowed: {', '.join(sorted(allowed))}")
    model_name = check_choice("model", doc.get("model", ""), tuple(MODELS))
    cls = MODELS[model_name]
    names = {f.name for f in fields(cls)}
    kw: dict[str, Any] = {}
    for k, v in dict(doc.get("parameters", {})).items():
        fname, f = _split(k)
        fname = _RENAME.get(fname, fname)
        if fname not in names or fname in ("mesh_stiffness", "k_sun_mesh", "k_ring_mesh"):
            raise InputError(f"[parameters] has unknown key {k!r} for model {model_name!r}")
        kw[fname] = _scaled(v, f)
        if fname == "mesh_period":
            kw[fname] = 1.0 / kw[fname]
    if model_name == "spur_pair":
        if "mesh_stiffness" not in doc:
            raise InputError("a spur_pair config needs a [mesh_stiffness] table")
        kw["mesh_stiffness"] = signal_from_table(doc["mesh_stiffness"], "mesh_stiffness", base)
    else:
        for key, fname in (
            ("sun_mesh_stiffness", "k_sun_mesh"),
            ("ring_mesh_stiffness", "k_ring_mesh"),
        ):
            if key in doc:
                kw[fname] = signal_from_table(doc[key], key, base)
    model = cls(**kw)
    return DynamicsConfig(
        model=model,
        solver=_options(SolverOptions, doc.get("solver", {}), "solver"),
        sweep=_options(SweepOptions, doc.get("sweep", {}), "sweep"),
        name=str(doc.get("name", name)),
        raw=dict(doc),
    )


def load_dynamics_config(path: str | Path) -> DynamicsConfig:
    """Read a dynamics study from a TOML file (relative CSV paths are relative to it)."""
    path = Path(path)
    return config_from_dict(load_toml(path), name=path.stem, base=path.parent)
