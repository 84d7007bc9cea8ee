"""On-disk cache of generated meshes (and other FE results), keyed by a content hash of their
inputs, each entry checked against a SHA-256 of its contents when it is read.

A mesh depends only on the geometry and the mesh settings, so both go into the key
(:func:`pipeline.io.content_hash`) and nothing else: labels (a gear's or its material's
``name``, :func:`unlabelled`) change no number, so an identical pinion and gear share
one entry. Any changed input gives a new file name and the stale file is simply never
read again. The folder is :func:`pipeline.fem.cache_dir.default_cache_dir` unless moved.

Entries are ``.npz`` archives written atomically (:func:`pipeline.io.atomic_write`: a
temporary file moved into place) with one more array, ``__sha256__``, the digest of
every other array's name, dtype, shape and bytes (:func:`arrays_digest`). An entry
that cannot be read back exactly (zero bytes, truncated, not an archive, a missing
field, a digest that does not match because the payload was changed) is reported once
as a :class:`CacheWarning`, deleted and rebuilt. A folder that cannot be written costs
only the saving: the result is returned uncached, with one warning.

The same entries hold FE tables, loaded contact cycles and figures (keys: what determines
them, never a gear's or material's name); ``--no-cache`` neither reads nor writes the
cache. The check costs one hash of the data: 0.46 s for a 72 MB table against 0.59 s to
read it unchecked (one run, 2 cores at load average 6.6; meshes and 2D tables are a few
MB). Checks (``tests/test_cache.py``): zero-byte, truncated, half, foreign, changed (a mesh
with its points scaled by 1.0001, which was once used silently), checksum-less, read-only
and blocked entries and folders.
"""

from __future__ import annotations

import hashlib
import os
import warnings
import zipfile
from collections.abc import Callable, Mapping
from dataclasses import asdict
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from pipeline.fem.cache_dir import CACHE_ENV, CacheWarning, default_cache_dir
from pipeline.fem.gmsh_session import TetMeshData
from pipeline.io import atomic_write, content_hash

T = TypeVar("T")

# Bump when the stored layout or the meshing code changes what a key produces.
# 3: entries carry a SHA-256 of their arrays; gear and material names left out of keys.
CACHE_FORMAT = 3
DIGEST = "__sha256__"
"""Name of the array holding the SHA-256 of an entry's other arrays."""


class CorruptEntry(ValueError):
    """A cache file that cannot be read back exactly (the message says why)."""


def mesh_key(kind: str, inputs: Mapping[str, Any]) -> str:
    """File stem ``<kind>-<hash>`` for a mesh built from ``inputs`` (any JSON-able data)."""
    return f"{kind}-{content_hash({'kind': kind, 'format': CACHE_FORMAT, 'inputs': inputs})}"


def unlabelled(gear: Any) -> dict[str, Any]:
    """A :class:`~pipeline.geometry.GearSpec` as key data without its labels (the gear's and
    its material's ``name``), which change no mesh or matrix."""
    data = asdict(gear)
    data.pop("name", None)
    data.get("material", {}).pop("name", None)
    return data


def arrays_digest(arrays: Mapping[str, Any]) -> str:
    """SHA-256 (hex) of named arrays: every name, dtype, shape and the bytes, in name order."""
    h = hashlib.sha256()
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}\0{a.dtype.str}\0{a.shape}\0".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def save_arrays(path: str | Path, arrays: Mapping[str, Any]) -> Path:
    """Write named arrays and their :func:`arrays_digest` to ``path`` (.npz) atomically."""
    arrays = {k: np.asarray(v) for k, v in arrays.items()}
    if DIGEST in arrays:
        raise ValueError(f"{DIGEST!r} is reserved for the digest of the other arrays")
    stamped = {**arrays, DIGEST: np.array(arrays_digest(arrays))}
    return atomic_write(path, lambda tmp: np.savez(tmp, **stamped))


def load_arrays(path: str | Path) -> dict[str, np.ndarray]:
    """Read the arrays of an .npz file written by :func:`save_arrays`, checked against their
    digest; :class:`CorruptEntry` when the file cannot be read back exactly."""
    try:
        # our own file handle: np.load leaves its handle open when the archive is truncated
        with open(path, "rb") as fh:
            if os.fstat(fh.fileno()).st_size == 0:
                raise CorruptEntry("the file is empty (0 bytes)")
            with np.load(fh, allow_pickle=False) as z:
                arrays = {k: z[k] for k in z.files}
    except CorruptEntry:
        raise
    except (EOFError, ValueError, KeyError, zipfile.BadZipFile, zipfile.LargeZipFile) as exc:
        raise CorruptEntry(f"not a complete archive ({type(exc).__name__}: {exc})") from exc
    stored = arrays.pop(DIGEST, None)
    if stored is None:
        raise CorruptEntry("it carries no checksum")
    if str(stored) != arrays_digest(arrays):
        raise CorruptEntry("its contents do not match their SHA-256 checksum")
    return arrays


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
    load, save : read / atomically write the result at a path (.npz); ``load`` raises
        (:class:`CorruptEntry`, ``OSError``, ``KeyError``, ``ValueError``) on a file it
        cannot read back exactly.
    cache_dir : folder of the cache (default :func:`default_cache_dir`).
    enabled : False builds without reading or writing the cache.

    Returns
    -------
    (result, path of the cache file or None when nothing was stored, True if it was read
    from the cache)
    """
    if not enabled:
        return build(), None, False
    path = Path(cache_dir or default_cache_dir()) / f"{mesh_key(kind, inputs)}.npz"
    if path.is_file():
        try:
            return load(path), path, True
        except (CorruptEntry, OSError, KeyError, ValueError) as exc:
            _discard(path, exc)
    data = build()
    try:
        save(path, data)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        warnings.warn(f"cache folder {path.parent} cannot be written ({reason}); results are "
                      f"not cached (set --cache-dir or {CACHE_ENV} to a writable folder)",
                      CacheWarning, stacklevel=2)
        return data, None, False
    return data, path, False


def _discard(path: Path, exc: BaseException) -> None:
    """Warn that the entry at ``path`` is unusable and delete it (if the folder allows)."""
    why = str(exc) if isinstance(exc, CorruptEntry) else f"{type(exc).__name__}: {exc}"
    warnings.warn(f"cache file {path} is unusable ({why}); deleted and rebuilt",
                  CacheWarning, stacklevel=3)
    try:
        path.unlink()
    except OSError:
        pass  # a read-only folder keeps the file; the rebuilt result is still returned


def cached_tet_mesh(
    kind: str, inputs: Mapping[str, Any], build: Callable[[], TetMeshData],
    cache_dir: str | Path | None = None, enabled: bool = True,
) -> tuple[TetMeshData, Path | None, bool]:
    """:func:`cached_file` for meshes: (mesh, cache path or None, True if read from it)."""
    return cached_file(kind, inputs, build, load_tet_mesh, save_tet_mesh, cache_dir, enabled)
