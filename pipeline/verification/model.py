"""The case model: what one verification case compares and how it is judged.

A case compares quantities the pipeline computes with reference values: an exact solution
(``"exact"``), a published value (``"published"``: a standard's worked example, a paper's
table, a commercial code's printed report), an independent finite-element model
(``"independent_fe"``) or the pipeline's own values over a sequence of refinements
(``"convergence"``: the levels, the measured rate and what the theory expects of it).
Every compared quantity carries its unit, its reference, the project's value, how the
error is measured and the tolerance with the reason for it; the case passes when every
quantity is within its tolerance and nothing raised.

Values are SI (the unit says which); :mod:`.display` shows them in engineering units where
a quantity names its display unit. The results of a run are in :mod:`.results`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

KINDS = ("exact", "published", "independent_fe", "convergence")
"""The kinds of case, in the order the report lists them."""

ERROR_KINDS = ("relative", "absolute", "lower_bound", "upper_bound")
"""How a quantity's error is measured against its tolerance:

* ``relative``: ``value / reference - 1``, passes when its magnitude is at most the
  tolerance;
* ``absolute``: ``value - reference`` in the quantity's unit, likewise;
* ``lower_bound``: ``value - reference``, passes when at least ``-tolerance`` (the value
  may exceed the reference by any amount: an a-priori convergence rate that fine meshes
  beat);
* ``upper_bound``: ``value - reference``, passes when at most ``tolerance`` (a change that
  must stay below a bound).
"""


@dataclass(frozen=True)
class Quantity:
    """One compared quantity.

    Attributes
    ----------
    name : what is compared ("tip deflection u_y(L, 0)").
    unit : its unit (SI, as the values: "m", "N/m", "Hz", "-").
    reference : the reference value, in ``unit``.
    value : the project's value, in ``unit``.
    error_kind : one of :data:`ERROR_KINDS`.
    tolerance : the allowed error (a fraction for ``relative``, else in ``unit``).
    reason : why the tolerance is what it is (rounding of the printed value, a
        discretisation error of stated size, ...).
    display : (unit, factor) the report shows the values in (value in ``unit`` times
        ``factor``: ``("um", 1e6)`` for metres), default the SI unit itself.
    """

    name: str
    unit: str
    reference: float
    value: float
    error_kind: str
    tolerance: float
    reason: str
    display: tuple[str, float] | None = None

    def __post_init__(self) -> None:
        if self.error_kind not in ERROR_KINDS:
            raise ValueError(f"quantity {self.name!r}: error_kind {self.error_kind!r} is not "
                             f"one of {', '.join(ERROR_KINDS)}")
        if not self.tolerance >= 0.0:
            raise ValueError(f"quantity {self.name!r}: tolerance {self.tolerance!r} must be "
                             ">= 0")
        object.__setattr__(self, "reference", float(self.reference))
        object.__setattr__(self, "value", float(self.value))

    @property
    def error(self) -> float:
        """The error as :data:`ERROR_KINDS` defines it (a fraction for ``relative``); NaN
        when it cannot be formed (a relative error against a zero reference)."""
        if self.error_kind == "relative":
            return self.value / self.reference - 1.0 if self.reference != 0.0 else math.nan
        return self.value - self.reference

    @property
    def passed(self) -> bool:
        """Within the tolerance (a NaN error or value fails)."""
        e = self.error
        if not math.isfinite(e):
            return False
        if self.error_kind == "lower_bound":
            return e >= -self.tolerance
        if self.error_kind == "upper_bound":
            return e <= self.tolerance
        return abs(e) <= self.tolerance


@dataclass(frozen=True)
class Series:
    """One curve of a plot: ``y`` over ``x`` (equal length, the plot's units)."""

    label: str
    x: tuple[float, ...]
    y: tuple[float, ...]
    style: str = "-o"

    def __post_init__(self) -> None:
        x = tuple(float(v) for v in np.ravel(self.x))
        y = tuple(float(v) for v in np.ravel(self.y))
        if len(x) != len(y):
            raise ValueError(f"series {self.label!r}: {len(x)} x values, {len(y)} y values")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)


@dataclass(frozen=True)
class Plot:
    """A figure of a case: curves compared, or a convergence study (log-log).

    The axis labels carry the units of the series' values (display units: the case chooses
    them, e.g. um and N/um for a transmission error and a mesh stiffness).
    """

    title: str
    xlabel: str
    ylabel: str
    series: tuple[Series, ...]
    loglog: bool = False


@dataclass(frozen=True)
class Convergence:
    """A convergence study: the quantity at each level and its measured rate.

    Attributes
    ----------
    level_name : what is refined, with its unit ("element size h [m]").
    levels : (n,) the level values (decreasing sizes), in that unit.
    quantity : the converging quantity, with its unit.
    values : (n,) the quantity at each level.
    errors : (n,) the error at each level (against an exact value, or the change from the
        previous level, as ``error_name`` says).
    error_name : what ``errors`` are.
    rate : the measured rate, the slope of log(error) over log(level).
    expected_rate : the rate the theory expects, with ``rate_reason`` saying which.
    """

    level_name: str
    levels: tuple[float, ...]
    quantity: str
    values: tuple[float, ...]
    errors: tuple[float, ...]
    error_name: str
    rate: float
    expected_rate: float
    rate_reason: str

    def __post_init__(self) -> None:
        for name in ("levels", "values", "errors"):
            object.__setattr__(self, name, tuple(float(v) for v in getattr(self, name)))


@dataclass(frozen=True)
class Outcome:
    """What a case function returns: its source, inputs and comparisons.

    Attributes
    ----------
    source : the citation (author year, table / figure / clause, or the exact solution).
    inputs : (name, value with its unit) pairs: what the case computes with.
    quantities : the compared quantities.
    convergence : the convergence study of a ``"convergence"`` case, else ``None``.
    plots : figures (curves compared, convergence).
    notes : anything the reader needs to judge the case (what the reference leaves out).
    """

    source: str
    inputs: tuple[tuple[str, str], ...]
    quantities: tuple[Quantity, ...]
    convergence: Convergence | None = None
    plots: tuple[Plot, ...] = ()
    notes: str = ""
