"""Where the on-disk cache lives, whether it can be written, and the one object that says
which cache a computation uses (:class:`Cache`).

One rule for every command (``--cache-dir DIR`` overrides it):

1. the environment variable ``GEARPIPE_CACHE_DIR``, when set and not empty;
2. ``meshes/`` at the top of a source checkout (the folder beside ``pyproject.toml``,
   with its README);
3. the platform's user cache folder for an installed package:
   ``$XDG_CACHE_HOME/gearpipe``, else ``~/.cache/gearpipe``.

A folder that cannot be created or written is not an error: :func:`writable_cache_dir`
warns once (:class:`CacheWarning`, one line) and the run continues without a cache.

Every step that reads or writes the cache (meshes, FE tables, groove bodies, contact
cycles, root-stress tables, figures) takes one :class:`Cache`: the folder, or off
(``--no-cache``). The commands build it once (:meth:`Cache.for_command`).
"""

from __future__ import annotations

import os
import tempfile
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

CACHE_ENV = "GEARPIPE_CACHE_DIR"
"""Environment variable that moves the cache folder."""
_LONGEST_ENTRY = 72
"""Longest path (bytes) of a temporary entry file relative to the cache folder."""


class CacheWarning(UserWarning):
    """The cache could not be used as asked (unwritable folder, corrupt entry); the run
    continues and its numbers are unaffected."""


def source_checkout_cache() -> Path | None:
    """``meshes/`` of the source checkout this package runs from, or None when installed."""
    root = Path(__file__).resolve().parents[2]
    if (root / "pyproject.toml").is_file() and (root / "meshes").is_dir():
        return root / "meshes"
    return None


def user_cache_dir(environ: Mapping[str, str] | None = None) -> Path:
    """``$XDG_CACHE_HOME/gearpipe``, or ``~/.cache/gearpipe`` when it is unset or relative."""
    env = os.environ if environ is None else environ
    xdg = env.get("XDG_CACHE_HOME", "")
    base = Path(xdg) if xdg and Path(xdg).is_absolute() else Path.home() / ".cache"
    return base / "gearpipe"


def default_cache_dir(environ: Mapping[str, str] | None = None) -> Path:
    """The cache folder when none is given (module docstring: env var, checkout, user)."""
    env = os.environ if environ is None else environ
    if env.get(CACHE_ENV, ""):
        return Path(env[CACHE_ENV]).expanduser()
    return source_checkout_cache() or user_cache_dir(env)


def writable_cache_dir(cache_dir: str | os.PathLike | None = None) -> Path | None:
    """The cache folder (``cache_dir`` or :func:`default_cache_dir`), created, or None with
    a :class:`CacheWarning` when it cannot be created or written (read-only, a file, no
    permission): the caller then runs without writing the cache."""
    folder = Path(cache_dir) if cache_dir is not None else default_cache_dir()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        # a probe as long as the longest temporary name an entry gets
        # (figures/.fig-<24 hex>.png.tmp-<pid>-<8>.png: 66), so a folder whose path leaves
        # no room for its entries is found here, once, rather than at every entry
        fd, probe = tempfile.mkstemp(prefix=".probe." + "0" * (_LONGEST_ENTRY - 15),
                                     dir=folder)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        warnings.warn(f"cache folder {folder} cannot be written ({reason}); running without "
                      f"the cache (set --cache-dir or {CACHE_ENV} to a writable folder)",
                      CacheWarning, stacklevel=2)
        return None
    return folder


@dataclass(frozen=True)
class Cache:
    """The on-disk cache a computation reads and writes.

    Attributes
    ----------
    folder : the cache folder, or None for :func:`default_cache_dir` (looked up when an
        entry is read or written).
    enabled : False neither reads nor writes any entry (``--no-cache``).
    """

    folder: Path | None = None
    enabled: bool = True

    def __post_init__(self) -> None:
        if self.folder is not None:
            object.__setattr__(self, "folder", Path(self.folder))

    @classmethod
    def off(cls) -> Cache:
        """No cache: every result is built, nothing is read or written."""
        return cls(enabled=False)

    @classmethod
    def for_command(cls, folder: str | os.PathLike | None, disabled: bool = False) -> Cache:
        """The cache of a command: off when ``disabled`` (``--no-cache``) or when the folder
        (``folder``, else :func:`default_cache_dir`) cannot be written (one
        :class:`CacheWarning`), else that folder."""
        if disabled:
            return cls.off()
        writable = writable_cache_dir(folder)
        return cls.off() if writable is None else cls(writable)

    @property
    def root(self) -> Path:
        """The cache folder (:func:`default_cache_dir` when none was given)."""
        return self.folder if self.folder is not None else default_cache_dir()

    def subfolder(self, name: str) -> Path | None:
        """``root / name`` (e.g. ``figures``), or None when the cache is off."""
        return self.root / name if self.enabled else None


DEFAULT_CACHE = Cache()
"""The default folder (:func:`default_cache_dir`), on: the default of every ``cache``
argument."""
