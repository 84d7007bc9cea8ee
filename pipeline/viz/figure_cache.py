"""Figures cached by a hash of what they show: a rerun copies unchanged figures.

Drawing and rasterising a figure costs 0.1-0.4 s (a 3D load map about 1 s); a rerun of
``gearpipe run`` that changes only a dynamics option would spend most of its time redrawing
the same stiffness, contact and load-map figures. :meth:`FigureCache.save` keys each PNG by
the drawing function, the source of the module that defines it
(:func:`pipeline.cache.entries.code_digest`, as every cache entry), and every argument
it is drawn from (arrays by their bytes, dataclasses field by field), so a figure is
redrawn exactly when its data or its drawing code changed. An argument the key
cannot describe is an error rather than a silently stale figure. Each cached PNG carries
its key in a ``tEXt`` chunk (``gearpipe-key``, left out of the copy a run writes, so a
figure is the same file drawn or copied); a cached file that is not a whole PNG
(empty, or cut before its end chunk) or holds another key (a figure copied or moved onto
this name) is reported in one warning line and redrawn over.
"""

from __future__ import annotations

import struct
import warnings
import zlib
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any, Protocol

from pipeline.cache.entries import code_digest
from pipeline.cache.folder import Cache, CacheWarning
from pipeline.io import atomic_write, content_hash
from pipeline.viz.saving import save


class FigureSink(Protocol):
    """Where a figure not in the cache can be deferred instead of drawn at once (a
    :class:`pipeline.viz.figure_queue.FigureQueue`)."""

    def add(self, path: str | Path, job: Callable[[], Path]) -> Path:
        """Take ``job`` (draws and writes ``path``); returns ``path``."""
        ...


@dataclass(frozen=True)
class FigureCache:
    """Where cached PNGs live; ``folder=None`` draws every figure (no cache).

    Attributes
    ----------
    folder : cache folder (e.g. ``<cache>/figures``), or ``None``.
    dpi : resolution, dots per inch (part of the key).
    queue : if given, figures not in the cache are queued there instead of drawn at once
        (:func:`pipeline.viz.figure_queue.parallel_figures` draws them side by side).
    """

    folder: Path | None = None
    dpi: int = 130
    queue: FigureSink | None = field(default=None, compare=False)

    @classmethod
    def within(cls, cache: Cache) -> FigureCache:
        """Figures kept in the ``figures`` folder of ``cache`` (beside the meshes, FE tables
        and contact cycles); every figure drawn when the cache is off."""
        folder = cache.subfolder("figures")
        return cls() if folder is None else cls(folder)

    def save(self, path: str | Path, draw: Callable[..., Any], *args: Any, **kwargs: Any
             ) -> Path:
        """Write ``draw(*args, **kwargs)`` as PNG to ``path``, or copy it from the cache."""
        cached = None
        if self.folder is not None:
            key = content_hash(draw.__module__, draw.__qualname__,
                               code_digest((draw.__module__,)), self.dpi, args, kwargs)
            cached = Path(self.folder) / f"fig-{key}.png"
            if cached.is_file():
                if _whole_png(cached) and stored_key(cached) == key:
                    plain = without_key(cached.read_bytes())
                    return atomic_write(path, lambda p: Path(p).write_bytes(plain))
                warnings.warn(f"cached figure {cached} is not a whole PNG of this figure "
                              "(cut, or another figure's); redrawn", CacheWarning, stacklevel=2)
        job = partial(draw_figure, Path(path), cached, self.dpi, draw, args, kwargs,
                      cached.stem.removeprefix("fig-") if cached is not None else "")
        return job() if self.queue is None else self.queue.add(path, job)


def draw_figure(path: Path, cached: Path | None, dpi: int, draw: Callable[..., Any],
                args: tuple, kwargs: dict, key: str = "") -> Path:
    """Draw ``draw(*args, **kwargs)`` into ``path`` (PNG at ``dpi``) and keep a copy as
    ``cached``, stamped with ``key``; a module-level function, so a queued drawing
    pickles."""
    out = save(draw(*args, **kwargs), path, dpi)
    if cached is not None:
        # only the cached copy carries the key: a figure is the same file drawn or copied
        stamped = with_key(out.read_bytes(), key)
        try:
            atomic_write(cached, lambda p: Path(p).write_bytes(stamped))
        except OSError:
            pass  # a read-only or full cache only costs the next run a redraw
    return out


_KEY_WORD = b"gearpipe-key"
_HEADER_END = 8 + 4 + 4 + 13 + 4  # signature and the IHDR chunk (length, type, data, CRC)


def with_key(png: bytes, key: str) -> bytes:
    """``png`` with a ``tEXt`` chunk ``gearpipe-key: key`` after its header chunk."""
    data = _KEY_WORD + b"\0" + key.encode("ascii")
    chunk = (struct.pack(">I", len(data)) + b"tEXt" + data
             + struct.pack(">I", zlib.crc32(b"tEXt" + data)))
    return png[:_HEADER_END] + chunk + png[_HEADER_END:]


def without_key(png: bytes) -> bytes:
    """``png`` without the chunk :func:`with_key` put after its header (unchanged if none)."""
    length = struct.unpack(">I", png[_HEADER_END:_HEADER_END + 4])[0]
    chunk = png[_HEADER_END + 4:_HEADER_END + 8 + length]
    if chunk[:4] == b"tEXt" and chunk[4:].startswith(_KEY_WORD + b"\0"):
        return png[:_HEADER_END] + png[_HEADER_END + 12 + length:]
    return png


def stored_key(path: Path) -> str | None:
    """The ``gearpipe-key`` text of a PNG file (:func:`with_key`), or ``None``."""
    try:
        with open(path, "rb") as fh:
            fh.seek(len(_PNG_START))
            while True:
                head = fh.read(8)
                if len(head) < 8:
                    return None
                length, kind = struct.unpack(">I", head[:4])[0], head[4:]
                if kind in (b"IDAT", b"IEND"):
                    return None
                body = fh.read(length)
                fh.seek(4, 1)  # CRC
                if kind == b"tEXt" and body.startswith(_KEY_WORD + b"\0"):
                    return body[len(_KEY_WORD) + 1:].decode("ascii", "replace")
    except OSError:
        return None


_PNG_START = b"\x89PNG\r\n\x1a\n"
_PNG_END = b"IEND\xaeB`\x82"  # the end chunk's type and CRC, the last bytes of every PNG


def _whole_png(path: Path) -> bool:
    """True if ``path`` starts with the PNG signature and ends with the IEND chunk."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(len(_PNG_START))
            fh.seek(0, 2)
            if fh.tell() < len(_PNG_START) + len(_PNG_END):
                return False
            fh.seek(-len(_PNG_END), 2)
            return head == _PNG_START and fh.read() == _PNG_END
    except OSError:
        return False


NO_CACHE = FigureCache()
"""Draw every figure."""

__all__ = ["NO_CACHE", "FigureCache"]
