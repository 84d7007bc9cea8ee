"""Strict reading of one TOML table: known keys, checked types, units to SI.

A table is described by :class:`Key` entries (the key as written in the file,
the input field it sets, its type, its unit from the key's suffix). Reading a
table refuses unknown keys (suggesting the nearest known one), values of the
wrong type (``internal = "false"`` is a string, not a boolean) and returns the
values converted to SI under the field names of the stage's input dataclass.

Ranges live with the input dataclasses (one place, SI). When a dataclass
refuses a value, :func:`restated` re-raises the error in the words of the file:
the key as written, the value in the file's unit and the allowed range in that
unit, e.g. ``pinion.pressure_angle_deg = 60 deg is outside the allowed range
(0, 35] deg`` (keys are shown as dotted TOML paths, which name them exactly).
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Callable, Collection, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from pipeline.config.units import DIMENSIONLESS, Unit, unit_of_key
from pipeline.validation import InputError

MAX_NAME_CHARS = 80
"""Longest free-text value (a name, a label) a file may give: it has to fit a figure title."""
MAX_TEXT_CHARS = 2000
"""Longest free-text value of a description."""

KINDS = ("number", "integer", "boolean", "string", "numbers", "number_or_string")
_KIND_TEXT = {
    "number": "a number",
    "integer": "a whole number",
    "boolean": "true or false (without quotes)",
    "string": "a string in quotes",
    "numbers": "a list of numbers",
    "number_or_string": "a number or a string",
}


@dataclass(frozen=True)
class Key:
    """One key of a table.

    Attributes
    ----------
    name : the key as written in the file; its unit is its suffix (:mod:`.units`).
    field : the input field it sets (default: the name without the unit suffix).
    kind : one of :data:`KINDS`.
    choices : allowed strings (``kind`` "string" or "number_or_string").
    length : exact list length (``kind`` "numbers"), or ``None`` for any length.
    required : the table must give it.
    help : one line for the docs.
    max_chars : longest string allowed (``kind`` "string" or "number_or_string").
    """

    name: str
    kind: str = "number"
    field: str | None = None
    choices: tuple[str, ...] = ()
    length: int | None = None
    required: bool = False
    help: str = ""
    max_chars: int = MAX_NAME_CHARS

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"Key {self.name!r}: kind {self.kind!r} is not one of {KINDS}")

    @property
    def unit(self) -> Unit:
        return unit_of_key(self.name)

    @property
    def target(self) -> str:
        """The input field this key sets."""
        if self.field is not None:
            return self.field
        suffix = self.unit.suffix
        return self.name[: -len(suffix) - 1] if suffix else self.name


def where_text(where: str) -> str:
    """``[pinion]``-style label of a table path (empty for the top level)."""
    return f"[{where}]" if where else "top level"


def _key_text(where: str, key: str) -> str:
    """A key as a dotted TOML path (``pinion.teeth``): valid TOML that names it exactly."""
    return f"{where}.{key}" if where else key


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _show(v: Any) -> str:
    """A value as the user wrote it (TOML-like), shortened."""
    if isinstance(v, bool):
        text = "true" if v else "false"
    elif isinstance(v, str):
        text = '"' + v + '"'
    elif isinstance(v, Mapping):
        text = "a table"
    else:
        text = repr(v)
    return text if len(text) <= 60 else text[:57] + "..."


def _convert(key: Key, where: str, v: Any) -> Any:
    """Type-check one value and convert it to SI."""
    bad = InputError(f"{_key_text(where, key.name)} = {_show(v)}: expected "
                     f"{_KIND_TEXT[key.kind]}")
    u = key.unit
    if key.kind == "number":
        if not _is_number(v):
            raise bad
        if not math.isfinite(float(v)):
            raise InputError(f"{_key_text(where, key.name)} = {_show(v)}: must be finite")
        return u.to_si(float(v))
    if key.kind == "integer":
        if isinstance(v, float) and math.isfinite(v) and v == int(v):
            v = int(v)
        if not isinstance(v, int) or isinstance(v, bool):
            raise bad
        return v
    if key.kind == "boolean":
        if not isinstance(v, bool):
            raise bad
        return v
    if key.kind == "numbers":
        if not isinstance(v, list) or not all(_is_number(x) for x in v):
            raise bad
        if key.length is not None and len(v) != key.length:
            raise InputError(f"{_key_text(where, key.name)} = {_show(v)}: expected "
                             f"{key.length} numbers, got {len(v)}")
        for x in v:
            if not math.isfinite(float(x)):
                raise InputError(f"{_key_text(where, key.name)} = {_show(v)}: must be finite")
        return tuple(u.to_si(float(x)) for x in v)
    if key.kind == "number_or_string" and _is_number(v):
        if not math.isfinite(float(v)):
            raise InputError(f"{_key_text(where, key.name)} = {_show(v)}: must be finite")
        return u.to_si(float(v))
    if not isinstance(v, str):
        raise bad
    check_text(_key_text(where, key.name), v, key.max_chars)
    if key.choices and v not in key.choices:
        raise InputError(f"{_key_text(where, key.name)} = {_show(v)} is not one of "
                         f"{', '.join(map(repr, key.choices))}")
    return v


def check_text(key: str, value: str, max_chars: int) -> str:
    """``value`` if it has at most ``max_chars`` characters, else a one-line
    :class:`InputError` naming ``key`` (as written) and both lengths; refused at load, so
    that no stage or figure sees a megabyte of label."""
    if len(value) > max_chars:
        raise InputError(f"{key} = {_show(value)} is {len(value)} characters long; at most "
                         f"{max_chars} are allowed")
    return value


def unknown(name: str, known: Sequence[str], what: str) -> InputError:
    """Error for an unknown key or table, with the closest known name."""
    close = difflib.get_close_matches(name, list(known), n=1, cutoff=0.6)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    return InputError(f"{what} {name!r} is not known{hint}; allowed: "
                      f"{', '.join(sorted(known))}")


def read_table(table: Any, keys: Sequence[Key], where: str,
               subtables: Sequence[str] = ()) -> dict[str, Any]:
    """Check a parsed TOML table against ``keys`` and return ``{field: SI value}``.

    Parameters
    ----------
    table : the parsed table (must be a mapping).
    keys : the keys it may hold.
    where : its path in the file (``"pinion"``, ``"pinion.material"``), for messages.
    subtables : names of nested tables it may hold; they are left out of the result.
    """
    if not isinstance(table, Mapping):
        raise InputError(f"{where} = {_show(table)}: expected a table [{where}]")
    by_name = {k.name: k for k in keys}
    out: dict[str, Any] = {}
    for name, v in table.items():
        if name in subtables:
            if not isinstance(v, Mapping):
                raise InputError(f"{_key_text(where, name)} = {_show(v)}: expected a table "
                                 f"[{where}.{name}]")
            continue
        if name not in by_name:
            raise unknown(name, list(by_name) + list(subtables),
                          f"{where_text(where)} key")
        key = by_name[name]
        if key.target in out:
            other = next(k.name for k in keys if k.target == key.target and k.name in table
                         and k.name != name)
            raise InputError(f"{_key_text(where, name)} and {_key_text(where, other)} set the "
                             "same value: give only one")
        out[key.target] = _convert(key, where, v)
    for k in keys:
        if k.required and k.name not in table:
            raise InputError(f"{where_text(where)} needs the key {k.name!r}"
                             + (f" ({k.help})" if k.help else ""))
    return out


_INDEX = re.compile(r"^(.*?)(\[(\d+)\])?$")


def _stem(key: Key) -> str:
    suffix = key.unit.suffix
    return key.name[: -len(suffix) - 1] if suffix else key.name


def _restate(exc: InputError, where: str, keys: Sequence[Key],
             present: Collection[str]) -> InputError | None:
    """The error of a range check on a dataclass field, in the file's key and unit."""
    if exc.field is None or exc.bounds is None:
        return None
    m = _INDEX.match(exc.field.rsplit(".", 1)[-1])
    base, index = m.group(1), m.group(3)
    matches = [k for k in keys if base in (k.target, _stem(k))]
    key = next((k for k in matches if k.name in present), matches[0] if matches else None)
    if key is None:
        return None
    u = key.unit if key.unit is not DIMENSIONLESS else DIMENSIONLESS
    lo, hi, lo_open, hi_open = exc.bounds

    def show(x: float) -> str:
        return f"{u.from_si(x):.6g}" if math.isfinite(x) else ("-inf" if x < 0 else "inf")

    label = u.label and f" {u.label}"
    name = key.name + (f"[{index}]" if index is not None else "")
    return InputError(
        f"{_key_text(where, name)} = {show(exc.value)}{label} is outside the allowed range "
        f"{'(' if lo_open else '['}{show(lo)}, {show(hi)}{')' if hi_open else ']'}{label}",
        field=exc.field, value=exc.value, bounds=exc.bounds)


@contextmanager
def restated(where: str, keys: Sequence[Key], present: Collection[str] = ()) -> Iterator[None]:
    """Re-raise range errors of the input dataclasses built inside in the file's terms.

    ``present`` are the keys the table gave (they win when two keys set one field).
    Errors the keys of ``where`` cannot explain are prefixed with the table name.
    """
    try:
        yield
    except InputError as exc:
        again = _restate(exc, where, keys, present)
        if again is not None:
            raise again from None
        text = str(exc)
        if where and not text.startswith("["):
            raise InputError(f"{where_text(where)}: {text}", field=exc.field, value=exc.value,
                             bounds=exc.bounds) from None
        raise


def build(factory: Callable[..., Any], table: Any, keys: Sequence[Key], where: str,
          subtables: Sequence[str] = (), **extra: Any) -> Any:
    """``factory(**read_table(...), **extra)`` with its errors in the file's terms."""
    values = read_table(table, keys, where, subtables)
    with restated(where, keys, table):
        return factory(**values, **extra)
