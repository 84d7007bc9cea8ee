"""Reading a TOML input file safely: every way a file can be unreadable is one line.

Refused with a one-line :class:`~pipeline.validation.InputError` naming the file:
a missing file or a folder, an unreadable file, a file over 10 MB, binary data
(NUL bytes), a UTF-8 byte-order mark, text that is not UTF-8 (with the line and
the offending byte), TOML syntax errors (with tomllib's line and column), and
tables or arrays nested deeper than :data:`MAX_DEPTH` (a dotted key or table header of
more than 100 parts before parsing, since tomllib takes quadratic time on it).
"""

from __future__ import annotations

import hashlib
import sys
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pipeline.validation import InputError

MAX_BYTES = 10_000_000
MAX_DEPTH = 8
_BOM = b"\xef\xbb\xbf"


@dataclass(frozen=True)
class InputFile:
    """A parsed input file.

    Attributes
    ----------
    path : where it was read from (``None`` for a document built in Python).
    text : the file as written (UTF-8).
    document : the parsed TOML (nested dicts and lists).
    sha256 : hex digest of the raw bytes.
    """

    path: Path | None
    text: str
    document: dict[str, Any]
    sha256: str


_KEY_CHARS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_- \t.[")
_MAX_KEY_PARTS = 100
"""A dotted key or table header with more parts than this is refused before parsing:
tomllib takes time quadratic in the parts (0.6 s for 8000, 6.8 s for 20000)."""


def _key_parts(line: str) -> int:
    """Parts of the dotted key or table header that ``line`` starts with (0 if it is not
    one: the key must end in ``=`` or the header in ``]``, with only key characters and
    quoted names before it)."""
    dots, quote, escaped = 0, "", False
    for ch in line.lstrip():
        if quote:
            if escaped:
                escaped = False
            elif ch == "\\" and quote == '"':
                escaped = True
            elif ch == quote:
                quote = ""
        elif ch in "\"'":
            quote = ch
        elif ch == ".":
            dots += 1
        elif ch in "=]":
            return dots + 1
        elif ch not in _KEY_CHARS:
            return 0
    return 0


def _long_key_line(text: str) -> int | None:
    """The number of the first line whose key or header has more than
    :data:`_MAX_KEY_PARTS` parts, or None (lines with fewer dots are skipped at C speed)."""
    for number, line in enumerate(text.split("\n"), 1):
        if line.count(".") >= _MAX_KEY_PARTS and _key_parts(line) > _MAX_KEY_PARTS:
            return number
    return None


def _too_deep(doc: Mapping[str, Any]) -> str | None:
    """Where the first table or array nested deeper than :data:`MAX_DEPTH` levels starts
    (a dotted path, ``a.b[0]``, shortened), or None. Iterative and stopping at the limit:
    a 20000-level table header costs a few steps and no recursion."""
    stack: list[tuple[Any, str, int]] = [(doc, "", 1)]
    while stack:
        value, path, level = stack.pop()
        items = ((f"{path}.{k}" if path else str(k), x) for k, x in value.items()) \
            if isinstance(value, Mapping) else \
            ((f"{path}[{i}]", x) for i, x in enumerate(value))
        for where, x in items:
            if isinstance(x, (Mapping, list)):
                if level + 1 > MAX_DEPTH:
                    return where if len(where) <= 80 else where[:77] + "..."
                stack.append((x, where, level + 1))
    return None


def parse_toml(data: bytes, name: str) -> dict[str, Any]:
    """Decode and parse TOML bytes; ``name`` labels the messages (usually the path)."""
    if data.startswith(_BOM):
        raise InputError(f"{name}: starts with a UTF-8 byte-order mark (BOM); save it as UTF-8 "
                         "without BOM")
    if b"\x00" in data:
        raise InputError(f"{name}: contains binary data (NUL bytes); an input file is TOML text")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise InputError(f"{name}: line {line} is not UTF-8 text (byte 0x{data[exc.start]:02x}); "
                         "save the file as UTF-8") from None
    long_key = _long_key_line(text)
    if long_key is not None:
        raise InputError(f"{name}: line {long_key}: a key or table header of more than "
                         f"{_MAX_KEY_PARTS} dotted parts; tables or arrays nested too deeply "
                         f"(more than {MAX_DEPTH} levels)")
    limit = sys.getrecursionlimit()
    try:
        sys.setrecursionlimit(max(limit, 2000))
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{name}: TOML syntax error: {exc}") from None
    except RecursionError:
        raise InputError(f"{name}: tables or arrays nested too deeply (more than "
                         f"{MAX_DEPTH} levels)") from None
    finally:
        sys.setrecursionlimit(limit)
    deep = _too_deep(doc)
    if deep is not None:
        raise InputError(f"{name}: tables or arrays nested too deeply at {deep} (more than "
                         f"{MAX_DEPTH} levels)")
    return doc


def read_input_file(path: str | Path) -> InputFile:
    """Read and parse a TOML input file (see the module docstring for what is refused)."""
    path = Path(path)
    if not path.exists():
        raise InputError(f"input file {str(path)!r} does not exist")
    if not path.is_file():
        raise InputError(f"input file {str(path)!r} is not a file")
    try:
        size = path.stat().st_size
        if size > MAX_BYTES:
            raise InputError(f"{path}: {size} bytes is larger than an input file can be "
                             f"({MAX_BYTES} bytes)")
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot be read ({exc.strerror})") from None
    return parse_input(data, str(path), path)


def parse_input(data: bytes, name: str, path: Path | None = None) -> InputFile:
    """Parse the bytes of an input file into an :class:`InputFile` (``name`` labels errors)."""
    doc = parse_toml(data, name)
    return InputFile(path, data.decode("utf-8"), doc, hashlib.sha256(data).hexdigest())
