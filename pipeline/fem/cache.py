"""On-disk cache of generated meshes (and other FE results), keyed by a content hash of their
inputs.

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
from typing import Any, TypeVar

import numpy as np

from pipeline.fem.gmsh_session import TetMeshData
from pipeline.io import atomic_write, content_hash

T = TypeVar("T")

# Bump when the stored layout or the meshing code changes what a key produces.
CACHE_FORMAT = 2


def default_cache_dir() -> Path:
    """``meshes/`` at the top of the repository (git-ignored)."""
    return Path(__file__).resolve().parents[2] / "meshes"


def mesh_key(kind: str, inputs: Mapping[str, Any]) -> str:
    """File stem ``<kind>-<hash>`` for a mesh built from ``inputs`` (any JSON-able data)."""
    return f"{kind}-{content_hash({'kind': kind, 'format': CACHE_FORMAT, 'inputs': inputs})}"


def save_arrays(path: str | Path, arrays: Mapping[str, Any]) -> Path:
    """Write named arrays to ``path`` (.npz) atomically."""
    return atomic_write(path, lambda tmp: np.savez(tmp, **arrays))


def load_arrays(path: str | Path) -> dict[str, np.ndarray]:
    """Read all arrays of an .npz file written by :func:`save_arrays`."""
    # our own file handle: np.load leaves its handle open when the archive is truncated
    with open(path, "rb") as fh, np.load(fh) as z:
        return {k: z[k] for k in z.files}


def save_tet_mesh(path: str | Path, data: TetMeshData) -> Path:
    """Write ``data`` to ``path`` (.npz) atomically."""
    arrays = {"points": data.points, "cells": data.cells}
    arrays.update({f"surface:{k}": v for k, v in data.surfaces.items()})
    arrays.update({f"volume:{k}": v for k, v in data.volumes.items()})
    return save_arrays(path, arrays)


def load_tet_mesh(path: str | Path) -> TetMeshData:
    """Read a mesh written by :func:`save_tet_mesh`."""
    z = load_arrays(path)
    surfaces = {k.split(":", 1)[1]: v for k, v in z.items() if k.startswith("surface:")}
    volumes = {k.split(":", 1)[1]: v for k, v in z.items() if k.startswith("volume:")}
    return TetMeshData(z["points"], z["cells"], surfaces, volumes)


def cached_file(
    kind: str, inputs: Mapping[str, Any], build: Callable[[], T],
    load: Callable[[Path], T], save: Callable[[Path, T], object],
    cache_dir: str | Path | None = None, enabled: bool = True,
) -> tuple[T, Path | None, bool]:
    """Return the cached result for ``inputs`` or build, store and return it.

    Parameters
    ----------
    kind : short name of the result family (part of the file name).
    inputs : everything the result depends on (geometry in m, settings).
    build : called on a cache miss; returns the result.
    load, save : read / atomically write the result at a path (.npz).
    cache_dir : folder of the cache (default :func:`default_cache_dir`).
    enabled : False builds without reading or writing the cache.

    Returns
    -------
    (result, path of the cache file or None, True if it was read from the cache)
    """
    if not enabled:
        return build(), None, False
    path = Path(cache_dir or default_cache_dir()) / f"{mesh_key(kind, inputs)}.npz"
    if path.is_file():
        try:
            return load(path), path, True
        except (OSError, ValueError, KeyError, zipfile.BadZipFile):
            pass  # unreadable (e.g. truncated by a full disk): rebuild below
    data = build()
    save(path, data)
    return data, path, False


def cached_tet_mesh(
    kind: str, inputs: Mapping[str, Any], build: Callable[[], TetMeshData],
    cache_dir: str | Path | None = None, enabled: bool = True,
) -> tuple[TetMeshData, Path | None, bool]:
    """:func:`cached_file` for meshes: (mesh, cache path or None, True if read from it)."""
    return cached_file(kind, inputs, build, load_tet_mesh, save_tet_mesh, cache_dir, enabled)
