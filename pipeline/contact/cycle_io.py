"""A :class:`LoadedMeshCycle` as named arrays and back, exactly, for the cache.

The loaded contact cycle is the pipeline's most expensive intermediate after the FE
tables; ``gearpipe run`` caches it (:func:`pipeline.cache.entries.cached_file`) by everything
it depends on (:func:`cycle_cache_inputs`) and the code that computes it
(:data:`CYCLE_CODE`). Arrays are stored bit for bit, so a cycle read back gives identical
downstream numbers.
"""

from __future__ import annotations

from dataclasses import asdict, fields
from typing import Any

import numpy as np

from pipeline.contact.options import ContactOptions
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.options import StiffnessOptions

CYCLE_CODE = ("pipeline.geometry", "pipeline.stiffness", "pipeline.fem", "pipeline.contact",
              "pipeline.operation", "pipeline.signals")
"""The code a loaded contact cycle depends on (part of its cache key)."""
_SCALARS = {"load": float, "local_contact": str}
# ContactOptions fields that only shape the outputs, not the cycle
_PRESENTATION = ("load_map_profile_points", "render")


def cycle_cache_inputs(pair: GearPair, operation: OperatingPoint, contact: ContactOptions,
                       stiffness: StiffnessOptions, fe: Any = None) -> dict[str, Any]:
    """Everything a loaded mesh cycle depends on, for its cache key.

    The installed pair (geometry, materials, centre distance), the operating point,
    the contact options that change the solve (compliance source, positions, slices,
    local contact, modifications), the friction model and foundation correction of
    ``[stiffness]`` and the FE settings of an FE source.
    """
    opts = {k: v for k, v in asdict(contact).items() if k not in _PRESENTATION}
    return {"pair": pair, "operation": operation, "contact": opts,
            "friction": stiffness.friction_model,
            "foundation_correction": stiffness.foundation_correction, "fe": fe}


def cycle_arrays(cycle: LoadedMeshCycle) -> dict[str, np.ndarray]:
    """Every field of ``cycle`` as an array (:func:`cycle_from_arrays` reads them back)."""
    return {f.name: np.asarray(getattr(cycle, f.name)) for f in fields(cycle)}


def cycle_from_arrays(z: dict[str, np.ndarray]) -> LoadedMeshCycle:
    """The cycle of :func:`cycle_arrays` (KeyError when a field is missing)."""
    kw: dict[str, Any] = {}
    for f in fields(LoadedMeshCycle):
        v = z[f.name]
        kw[f.name] = _SCALARS[f.name](v) if f.name in _SCALARS else v
    return LoadedMeshCycle(**kw)
