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
Any other message of a dataclass is rewritten the same way: each field it names
(``gear.module = 0.0035 m``, ``groove.mesh_size = 0.0005 m``, ``web_width``) becomes the
key of the file's table (``gear.module_mm = 3.5 mm``, ``groove.mesh_size_mm = 0.5 mm``,
``web_width_mm``), found through :class:`Scope` - the table being read, and the
other tables whose fields the dataclass may name under their own prefix (a
pair's ``pinion.`` and ``gear.``, also under a gear's own ``name``). So a
dataclass speaks of its fields in SI, once, and every message reaches the user
in the file's terms; ``tests/test_config_messages.py`` checks this for every
key of :mod:`pipeline.config.tables`.
"""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Callable, Collection, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from pipeline.config.units import DIMENSIONLESS, UNITS, Unit, unit_of_key
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


@dataclass(frozen=True)
class Scope:
    """A table whose keys an error message may name.

    Attributes
    ----------
    where : its path in the file (``"pinion"``, ``"dynamics.response"``).
    keys : its keys.
    present : the keys it gave (they win when two keys set one field).
    """

    where: str
    keys: Sequence[Key]
    present: Collection[str] = ()

    def key(self, name: str, fields_only: bool = False) -> tuple[Key, bool] | None:
        """The key a field name or key name refers to, and whether ``name`` is already the
        key as written (its value is then in the file's unit); ``fields_only``: only a key
        whose input field is ``name``."""
        for k in self.keys:
            if k.name == name and not fields_only:
                return k, True
        matches = [k for k in self.keys
                   if name == k.target or (name == _stem(k) and not fields_only)]
        if not matches:
            return None
        return next((k for k in matches if k.name in self.present), matches[0]), False


def _stem(key: Key) -> str:
    suffix = key.unit.suffix
    return key.name[: -len(suffix) - 1] if suffix else key.name


_NUMBER = r"-?(?:inf|\d+(?:\.\d*)?(?:e[+-]?\d+)?)"
_SI_LABELS = sorted({u.si for u in UNITS} - {"-"}, key=len, reverse=True)
_SI = "|".join(re.escape(label) for label in _SI_LABELS)
_MENTION = re.compile(
    r"(?<![\w.\[\]'\"])(?:(?P<prefix>[A-Za-z_]\w*(?:\.[A-Za-z_]\w*)*)\.)?"
    r"(?P<name>[A-Za-z_]\w*)(?P<index>\[\d+\])?(?![\w.(])"
    r"(?: = (?P<value>'[^']*'|\"[^\"]*\"|True|False|true|false|" + _NUMBER + r")"
    rf"(?: (?P<unit>{_SI})(?![\w/^]))?"
    r"(?P<range> is outside the allowed range (?P<lb>[\[(])(?P<lo>" + _NUMBER + r"), "
    r"(?P<hi>" + _NUMBER + r")(?P<rb>[\])])(?: (?P<runit>" + _SI + r")(?![\w/^]))?)?)?")
"""A quantity an input dataclass names in a message: ``prefix.field[i] = value unit`` with
an optional ``is outside the allowed range [lo, hi] unit`` after it."""


def _show_si(x: float, u: Unit) -> str:
    return f"{u.from_si(x):.6g}" if math.isfinite(x) else ("-inf" if x < 0 else "inf")


def _number(text: str) -> float:
    return float(text.replace("inf", "Infinity")) if "inf" in text else float(text)


def _in_file_terms(text: str, primary: Scope, scopes: Mapping[str, Scope]) -> str:
    """``text`` with every field an input dataclass names replaced by the key as written.

    A field names a key when its prefix names a table (``pinion.module``, ``gear.module``
    in a pair's message) or, without a known prefix, when it is given a value
    (``sweep.method = 'x'``, ``n_harmonics = 40``) or has an underscore (``web_width``) and
    is a field of ``primary``; values and allowed ranges in SI are shown in the key's unit.
    Other words are left alone.
    """
    aliases = {name: f"__scope{i}__" for i, name in enumerate(scopes) if not name.isidentifier()}
    for name in sorted(aliases, key=len, reverse=True):
        text = text.replace(f"{name}.", f"{aliases[name]}.")
    by_alias = {aliases.get(name, name): scope for name, scope in scopes.items()}
    back = {v: k for k, v in aliases.items()}

    def replace(m: re.Match) -> str:
        prefix, name = m.group("prefix"), m.group("name")
        scope = by_alias.get(prefix) if prefix else None
        # another prefix (a dataclass's own, "sweep.method"): a field of the table being read
        # only by its field name, so that "operation.torque" never becomes "groove.torque_Nm"
        guess = scope is None and (m.group("value") is not None or "_" in name)
        if guess:
            scope = primary
        found = scope.key(name, fields_only=guess and prefix is not None) if scope else None
        if found is None:
            whole = m.group(0)
            return f"{back[prefix]}{whole[len(prefix):]}" if prefix in back else whole
        key, as_written = found
        bare = prefix is None and m.group("value") is None
        out = (key.name if bare else _key_text(scope.where, key.name)) + (m.group("index") or "")
        value = m.group("value")
        if value is None:
            return out
        u = key.unit
        convert = not as_written and u is not DIMENSIONLESS and m.group("unit") == u.si
        label = f" {u.label}" if convert else (f" {m.group('unit')}" if m.group("unit") else "")
        if value.startswith("'"):
            value = '"' + value[1:-1] + '"'
        elif value in ("True", "False"):
            value = value.lower()
        elif convert:
            value = _show_si(_number(value), u)
        out += f" = {value}{label}"
        if m.group("range"):
            rconvert = not as_written and u is not DIMENSIONLESS and m.group("runit") == u.si
            lo, hi = m.group("lo"), m.group("hi")
            if rconvert:
                lo, hi = _show_si(_number(lo), u), _show_si(_number(hi), u)
            runit = f" {u.label}" if rconvert else (
                f" {m.group('runit')}" if m.group("runit") else "")
            out += (f" is outside the allowed range {m.group('lb')}{lo}, {hi}{m.group('rb')}"
                    f"{runit}")
        return out

    return _MENTION.sub(replace, text)


def _scopes(primary: Scope, also: Mapping[str, Scope]) -> dict[str, Scope]:
    """The tables a message may name by prefix: ``also`` and the primary table under its
    path and its last part (``dynamics.sweep`` and ``sweep``)."""
    out = dict(also)
    if primary.where:
        out.setdefault(primary.where.rsplit(".", 1)[-1], primary)
        out[primary.where] = primary
    return out


def _restate(exc: InputError, primary: Scope, scopes: Mapping[str, Scope]) -> InputError | None:
    """The error of a range check on a dataclass field, in the file's key and unit."""
    if exc.field is None or exc.bounds is None:
        return None
    m = _MENTION.fullmatch(exc.field)
    if m is None:
        return None
    prefix, base, index = m.group("prefix"), m.group("name"), m.group("index")
    scope = scopes.get(prefix) if prefix else None
    found = scope.key(base) if scope else primary.key(base, fields_only=prefix is not None)
    scope = scope or primary
    if found is None:
        return None
    key, as_written = found
    u = DIMENSIONLESS if as_written else key.unit
    lo, hi, lo_open, hi_open = exc.bounds
    label = f" {key.unit.label}" if key.unit.label else ""
    note = f" ({exc.note})" if exc.note else ""
    return InputError(
        f"{_key_text(scope.where, key.name + (index or ''))} = {_show_si(exc.value, u)}{label} "
        f"is outside the allowed range {'(' if lo_open else '['}{_show_si(lo, u)}, "
        f"{_show_si(hi, u)}{')' if hi_open else ']'}{label}{note}",
        field=exc.field, value=exc.value, bounds=exc.bounds, note=exc.note)


@contextmanager
def restated(where: str, keys: Sequence[Key], present: Collection[str] = (), *,
             also: Mapping[str, Scope] | None = None) -> Iterator[None]:
    """Re-raise the errors of the input dataclasses built inside in the file's terms.

    A range error becomes ``table.key = value unit is outside the allowed range [lo, hi]
    unit`` in the key's unit; in any other message each field the dataclass names is
    replaced by the key as written, with its value in the file's unit
    (:func:`_in_file_terms`). ``present`` are the keys the table gave (they win when two
    keys set one field); ``also`` maps the prefixes under which the dataclasses name fields
    of other tables (a pair's ``pinion.module``) to those tables. A message that does not
    begin with a key of the file is prefixed with the table name.
    """
    try:
        yield
    except InputError as exc:
        primary = Scope(where, keys, present)
        scopes = _scopes(primary, also or {})
        again = _restate(exc, primary, scopes)
        if again is not None:
            raise again from None
        text = _in_file_terms(str(exc), primary, scopes)
        for alias, scope in scopes.items():  # "pinion: ..." -> "[pinion]: ..."
            if scope.where and text.startswith(f"{alias}: "):
                text = f"{where_text(scope.where)}: {text[len(alias) + 2:]}"
                break
        named = {s.where for s in scopes.values() if s.where}
        if where and not text.startswith("[") and not any(
                text.startswith(f"{w}.") for w in named):
            text = f"{where_text(where)}: {text}"
        raise InputError(text, field=exc.field, value=exc.value, bounds=exc.bounds,
                         note=exc.note) from None


def build(factory: Callable[..., Any], table: Any, keys: Sequence[Key], where: str,
          subtables: Sequence[str] = (), **extra: Any) -> Any:
    """``factory(**read_table(...), **extra)`` with its errors in the file's terms."""
    values = read_table(table, keys, where, subtables)
    with restated(where, keys, table):
        return factory(**values, **extra)
