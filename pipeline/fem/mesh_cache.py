"""Meshes in the on-disk cache (:mod:`pipeline.cache.entries`): a mesh as named arrays and
back, keyed by the gear, the settings and the source of :data:`MESH_CODE`."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.cache.entries import cached_file
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.gmsh_session import TetMeshData

MESH_CODE = ("pipeline.geometry", "pipeline.fem")
"""The code a mesh or an FE result of :mod:`pipeline.fem` depends on."""


def tet_mesh_arrays(data: TetMeshData) -> dict[str, np.ndarray]:
    """A mesh as named arrays (:func:`tet_mesh_from_arrays` reads them back)."""
    arrays = {"points": data.points, "cells": data.cells}
    arrays.update({f"surface:{k}": v for k, v in data.surfaces.items()})
    arrays.update({f"volume:{k}": v for k, v in data.volumes.items()})
    return arrays


def tet_mesh_from_arrays(z: Mapping[str, np.ndarray]) -> TetMeshData:
    """The mesh of :func:`tet_mesh_arrays`."""
    surfaces = {k.split(":", 1)[1]: v for k, v in z.items() if k.startswith("surface:")}
    volumes = {k.split(":", 1)[1]: v for k, v in z.items() if k.startswith("volume:")}
    return TetMeshData(z["points"], z["cells"], surfaces, volumes)


def cached_tet_mesh(
    kind: str, inputs: Mapping[str, Any], build: Callable[[], TetMeshData],
    cache: Cache = DEFAULT_CACHE,
) -> tuple[TetMeshData, Path | None, bool]:
    """:func:`cached_file` for meshes (code :data:`MESH_CODE`): (mesh, cache path or None,
    True if read from it)."""
    return cached_file(kind, inputs, build, tet_mesh_arrays, tet_mesh_from_arrays,
                       code=MESH_CODE, cache=cache)
