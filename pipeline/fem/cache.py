"""On-disk cache of generated meshes, keyed by a content hash of their inputs.

A mesh depends only on the geometry and the mesh settings, so both go into the
key (:func:`pipeline.io.content_hash`); any changed input gives a new file name
and the stale file is simply never read again. Files are written atomically
(temporary file + ``os.replace``), so a crashed or concurrent run never leaves
a half-written mesh under a final name; an unreadable file is rebuilt.
"""

from __future__ import annotations

import zipfile
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.fem.gmsh_session import TetMeshData
from pipeline.io import atomic_write, content_hash

# Bump when the stored layout or the meshing code changes what a key produces.
CACHE_FORMAT = 2


def default_cache_dir() -> Path:
    """``meshes/`` at the top of the repository (git-ignored)."""
    return Path(__file__).resolve().parents[2] / "meshes"


def mesh_key(kind: str, inputs: Mapping[str, Any]) -> str:
    """File stem ``<kind>-<hash>`` for a mesh built from ``inputs`` (any JSON-able data)."""
    return f"{kind}-{content_hash({'kind': kind, 'format': CACHE_FORMAT, 'inputs': inputs})}"


def save_tet_mesh(path: str | Path, data: TetMeshData) -> Path:
    """Write ``data`` to ``path`` (.npz) atomically."""
    arrays = {"points": data.points, "cells": data.cells}
    arrays.update({f"surface:{k}": v for k, v in data.surfaces.items()})
    arrays.update({f"volume:{k}": v for k, v in data.volumes.items()})
    return atomic_write(path, lambda tmp: np.savez(tmp, **arrays))


def load_tet_mesh(path: str | Path) -> TetMeshData:
    """Read a mesh written by :func:`save_tet_mesh`."""
    # our own file handle: np.load leaves its handle open when the archive is truncated
    with open(path, "rb") as fh, np.load(fh) as z:
        surfaces = {k.split(":", 1)[1]: z[k] for k in z.files if k.startswith("surface:")}
        volumes = {k.split(":", 1)[1]: z[k] for k in z.files if k.startswith("volume:")}
        return TetMeshData(z["points"], z["cells"], surfaces, volumes)


def cached_tet_mesh(
    kind: str, inputs: Mapping[str, Any], build: Callable[[], TetMeshData],
    cache_dir: str | Path | None = None, enabled: bool = True,
) -> tuple[TetMeshData, Path | None, bool]:
    """Return the cached mesh for ``inputs`` or build, store and return it.

    Parameters
    ----------
    kind : short name of the mesh family (part of the file name).
    inputs : everything the mesh depends on (geometry in m, mesh settings).
    build : called on a cache miss; returns the mesh.
    cache_dir : folder of the cache (default :func:`default_cache_dir`).
    enabled : False builds without reading or writing the cache.

    Returns
    -------
    (mesh, path of the cache file or None, True if it was read from the cache)
    """
    if not enabled:
        return build(), None, False
    path = Path(cache_dir or default_cache_dir()) / f"{mesh_key(kind, inputs)}.npz"
    if path.is_file():
        try:
            return load_tet_mesh(path), path, True
        except (OSError, ValueError, KeyError, zipfile.BadZipFile):
            pass  # unreadable (e.g. truncated by a full disk): rebuild below
    data = build()
    save_tet_mesh(path, data)
    return data, path, False
