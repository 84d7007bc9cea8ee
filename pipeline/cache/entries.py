"""Cache entries: named arrays in ``.npz`` files, keyed by their inputs and by the code that
produces them, each checked against its key and a SHA-256 of its contents when read.

Key
---
An entry's key (:func:`entry_key`) is a content hash (:func:`pipeline.io.content_hash`) of
its kind, its inputs and the source of the code that produces it: every ``.py`` file of
the packages or modules its producer names (``code``, e.g. ``MESH_CODE`` for meshes;
:func:`code_digest`). A changed input or a changed line of that code gives a new key, so a
stale result is never read and no version number needs bumping by hand. Labels (a gear's
or its material's ``name``, :func:`unlabelled`) change no number and stay out of inputs,
so an identical pinion and gear share one entry. The folder is that of the
:class:`~pipeline.cache.folder.Cache` passed in (:func:`~pipeline.cache.folder.default_cache_dir`
unless moved).

Entries
-------
``<kind>-<key>.npz`` archives written atomically (:func:`pipeline.io.atomic_write`: a
temporary file moved into place) holding the producer's arrays (``to_arrays``), the key
(``__key__``) and the SHA-256 of every other array's name, dtype, shape and bytes
(``__sha256__``, :func:`arrays_digest`). An entry that cannot be read back exactly (zero
bytes, truncated, not an archive, a missing field, a digest that does not match because
the payload was changed) or that holds another key (an entry copied or moved onto this
name) is reported once as a :class:`CacheWarning`, deleted and rebuilt. A folder that
cannot be written costs only the saving: the result is returned uncached, with one
warning.

The same layer holds meshes, FE tables and loaded contact cycles (keys: what determines them, never
a gear's or material's name); ``--no-cache`` neither reads nor writes the cache (figures
have their own cache, :mod:`pipeline.viz.figure_cache`). The check costs one hash of the
data: 0.46 s for a 72 MB table against 0.59 s to read it unchecked (one run, 2 cores at
load average 6.6; meshes and 2D tables are a few MB). Checks (``tests/test_cache.py``):
zero-byte, truncated, half, foreign, changed (a mesh with its points scaled by 1.0001,
which was once used silently), checksum-less, moved onto another entry's name, read-only
and blocked entries and folders, and a key that follows the producing code.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import warnings
import zipfile
from collections.abc import Callable, Mapping
from dataclasses import asdict
from pathlib import Path
from typing import Any, TypeVar

import numpy as np

from pipeline.cache.folder import CACHE_ENV, DEFAULT_CACHE, Cache, CacheWarning
from pipeline.io import atomic_write, content_hash

T = TypeVar("T")

DIGEST = "__sha256__"
"""Name of the array holding the SHA-256 of an entry's other arrays."""
KEY = "__key__"
"""Name of the array holding an entry's key (:func:`entry_key`)."""

class CorruptEntry(ValueError):
    """A cache file that cannot be read back exactly (the message says why)."""


@functools.cache
def code_digest(code: tuple[str, ...]) -> str:
    """SHA-256 (hex, 16 characters) of the source of the named packages or modules: each
    name, then every ``.py`` file's path within it and its bytes, in path order. Computed
    once per process (the source does not change under a running process)."""
    h = hashlib.sha256()
    for name in sorted(set(code)):
        spec = importlib.util.find_spec(name)
        if spec is None or spec.origin is None:
            raise ValueError(f"cache key: no module or package named {name!r}")
        origin = Path(spec.origin)
        files = (sorted(origin.parent.rglob("*.py")) if spec.submodule_search_locations
                 else [origin])
        h.update(f"{name}\0".encode())
        for f in files:
            h.update(f"{f.relative_to(origin.parent).as_posix()}\0".encode())
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


def entry_key(kind: str, inputs: Mapping[str, Any], code: tuple[str, ...]) -> str:
    """Key of an entry of ``kind`` built from ``inputs`` (any JSON-able data) by ``code``
    (:func:`code_digest`)."""
    return content_hash({"kind": kind, "inputs": inputs, "code": code_digest(tuple(code))})


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


def same_arrays(arrays: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The identity conversion, for results that are named arrays already."""
    return dict(arrays)


def cached_file(
    kind: str, inputs: Mapping[str, Any], build: Callable[[], T],
    to_arrays: Callable[[T], Mapping[str, Any]], from_arrays: Callable[[dict], T], *,
    code: tuple[str, ...], cache: Cache = DEFAULT_CACHE,
) -> tuple[T, Path | None, bool]:
    """Return the cached result for ``inputs`` and ``code`` or build, store and return it.

    Parameters
    ----------
    kind : short name of the result family (part of the file name).
    inputs : everything the result depends on (geometry in m, settings).
    build : called on a cache miss; returns the result.
    to_arrays, from_arrays : the result as named arrays and back; ``from_arrays`` raises
        (``KeyError``, ``ValueError``) on arrays it cannot use.
    code : the packages or modules whose source produces the result (part of the key).
    cache : the cache to read and write (:class:`~pipeline.cache.folder.Cache`; disabled:
        build without reading or writing).

    Returns
    -------
    (result, path of the cache file or None when nothing was stored, True if it was read
    from the cache)
    """
    if not cache.enabled:
        return build(), None, False
    key = entry_key(kind, inputs, code)
    path = cache.root / f"{kind}-{key}.npz"
    if path.is_file():
        try:
            return from_arrays(_checked_arrays(path, key)), path, True
        except (CorruptEntry, OSError, KeyError, ValueError) as exc:
            _discard(path, exc)
    data = build()
    try:
        save_arrays(path, {**to_arrays(data), KEY: np.array(key)})
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        warnings.warn(f"cache folder {path.parent} cannot be written ({reason}); results are "
                      f"not cached (set --cache-dir or {CACHE_ENV} to a writable folder)",
                      CacheWarning, stacklevel=2)
        return data, None, False
    return data, path, False


def _checked_arrays(path: Path, key: str) -> dict[str, np.ndarray]:
    """The arrays of the entry at ``path`` without its key, which must be ``key``."""
    arrays = load_arrays(path)
    stored = arrays.pop(KEY, None)
    if stored is None:
        raise CorruptEntry("it carries no key")
    if str(stored) != key:
        raise CorruptEntry(f"it holds another entry (key {stored}, expected {key})")
    return arrays


def _discard(path: Path, exc: BaseException) -> None:
    """Warn that the entry at ``path`` is unusable and delete it (if the folder allows)."""
    why = str(exc) if isinstance(exc, CorruptEntry) else f"{type(exc).__name__}: {exc}"
    warnings.warn(f"cache file {path} is unusable ({why}); deleted and rebuilt",
                  CacheWarning, stacklevel=3)
    try:
        path.unlink()
    except OSError:
        pass  # a read-only folder keeps the file; the rebuilt result is still returned
