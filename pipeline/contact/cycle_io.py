"""Storing a :class:`LoadedMeshCycle` on disk (.npz) and reading it back exactly.

The loaded contact cycle is the pipeline's most expensive intermediate after the FE
tables; ``gearpipe run`` caches it by a content hash of everything it depends on
(:func:`cycle_cache_inputs`). Arrays are stored bit for bit, so a cycle read back gives
identical downstream numbers.
"""

from __future__ import annotations

from dataclasses import asdict, fields
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.contact.options import ContactOptions
from pipeline.contact.results import LoadedMeshCycle
from pipeline.fem.cache import CACHE_FORMAT, load_arrays, save_arrays
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.options import StiffnessOptions

# Bump when LoadedMeshCycle's fields or the contact solver change what a key produces
# (2: a spur pair with lead crowning or slope deviation is solved with slices).
CYCLE_FORMAT = 2
_SCALARS = {"load": float, "local_contact": str}
# ContactOptions fields that only shape the outputs, not the cycle
_PRESENTATION = ("load_map_profile_points", "render")


def cycle_cache_inputs(pair: GearPair, operation: OperatingPoint, contact: ContactOptions,
                       stiffness: StiffnessOptions, fe: Any = None) -> dict[str, Any]:
    """Everything a loaded mesh cycle depends on, for its cache key.

    The installed pair (geometry, materials, centre distance), the operating point,
    the contact options that change the solve (compliance source, positions, slices,
    local contact, modifications), the friction model and foundation correction of
    ``[stiffness]``, the FE settings of an FE source and the storage formats of the FE
    tables and of the cycle itself.
    """
    opts = {k: v for k, v in asdict(contact).items() if k not in _PRESENTATION}
    return {"format": CYCLE_FORMAT, "fe_format": CACHE_FORMAT, "pair": pair,
            "operation": operation, "contact": opts, "friction": stiffness.friction_model,
            "foundation_correction": stiffness.foundation_correction, "fe": fe}


def save_cycle(path: str | Path, cycle: LoadedMeshCycle) -> Path:
    """Write ``cycle`` to ``path`` (.npz) atomically."""
    arrays = {f.name: np.asarray(getattr(cycle, f.name)) for f in fields(cycle)}
    return save_arrays(path, arrays)


def load_cycle(path: str | Path) -> LoadedMeshCycle:
    """Read a cycle written by :func:`save_cycle` (KeyError when a field is missing)."""
    z = load_arrays(path)
    kw: dict[str, Any] = {}
    for f in fields(LoadedMeshCycle):
        v = z[f.name]
        kw[f.name] = _SCALARS[f.name](v) if f.name in _SCALARS else v
    return LoadedMeshCycle(**kw)
