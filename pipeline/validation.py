"""Input validation at the point where values enter the pipeline.

Every error names the field, the value and the allowed range, so that a user
reading a traceback from a TOML file knows which line to change.
"""

from __future__ import annotations

import math


class InputError(ValueError):
    """A user-supplied value is outside its allowed range or inconsistent.

    Range errors raised by :func:`check_range` also carry the checked ``field``
    (as named by the input dataclass), the ``value`` and the bounds in the unit
    of the check (SI), and the ``note`` saying where bounds that depend on other inputs
    come from, so that :mod:`pipeline.config` can restate them in the key and unit the
    user wrote in the input file.
    """

    def __init__(self, message: str, *, field: str | None = None,
                 value: float | None = None, bounds: tuple | None = None,
                 note: str = "") -> None:
        super().__init__(message)
        self.field = field
        self.value = value
        self.bounds = bounds  # (lo, hi, lo_open, hi_open)
        self.note = note


class PhysicsWarning(UserWarning):
    """A result that is computed correctly but outside what the model or the design is
    meant for (e.g. one tooth pair carrying the whole load at a time, a correlation used
    beyond its fitted range); the message gives the value."""


class InputWarning(UserWarning):
    """An input that is accepted but in part has no effect on any result (e.g. pitch errors
    for tooth pairs that never mesh in the analysed mesh cycle); the message names the key
    as written, the unused values in the file's unit and why they are unused."""


def _fmt(v: float) -> str:
    return f"{v:.6g}" if isinstance(v, float) else repr(v)


def check_range(
    field: str,
    value: float,
    lo: float = -math.inf,
    hi: float = math.inf,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
    note: str = "",
) -> float:
    """Return ``value`` if it lies in the interval, else raise :class:`InputError`.

    Parameters
    ----------
    field : name of the input as the user knows it (e.g. ``"pinion.teeth"``).
    value : the value given.
    lo, hi : interval bounds; ``lo_open``/``hi_open`` exclude the bound.
    unit : unit shown in the message (the unit of ``value`` as passed, SI inside).
    note : where the bounds come from when other inputs set them (``"the path of
        contact"``), shown in brackets after the range.
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{field} = {value!r} is not a number") from None
    if not math.isfinite(v):
        raise InputError(f"{field} = {value!r} must be finite")
    below = v <= lo if lo_open else v < lo
    above = v >= hi if hi_open else v > hi
    if below or above:
        lb = "(" if lo_open else "["
        rb = ")" if hi_open else "]"
        u = f" {unit}" if unit else ""
        raise InputError(
            f"{field} = {_fmt(v)}{u} is outside the allowed range "
            f"{lb}{_fmt(lo)}, {_fmt(hi)}{rb}{u}" + (f" ({note})" if note else ""),
            field=field, value=v, bounds=(lo, hi, lo_open, hi_open), note=note,
        )
    return value


def check_positive(field: str, value: float, unit: str = "") -> float:
    """Shorthand for a strictly positive finite value."""
    return check_range(field, value, 0.0, math.inf, lo_open=True, unit=unit)


def check_int_range(field: str, value: int, lo: int, hi: int | None = None) -> int:
    """Check an integer count (e.g. number of teeth) lies in ``[lo, hi]``."""
    try:
        whole = not isinstance(value, bool) and int(value) == value
    except (TypeError, ValueError, OverflowError):
        whole = False
    if not whole:
        raise InputError(f"{field} = {value!r} must be a whole number")
    return int(check_range(field, int(value), lo, math.inf if hi is None else hi))


def check_choice(field: str, value: str, allowed: tuple[str, ...]) -> str:
    """Check a string option is one of ``allowed``."""
    if value not in allowed:
        raise InputError(f"{field} = {value!r} is not one of {', '.join(map(repr, allowed))}")
    return value
