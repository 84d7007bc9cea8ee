"""How quantities are shown: display units (a value in its SI unit times a factor) and the
formatting of values, errors and tolerances in the report and the stderr lines."""

from __future__ import annotations

from pipeline.verification.model import Quantity


def display_unit(q: Quantity) -> tuple[str, float]:
    """(unit, factor) the quantity is shown in; a dimensionless "-" shows as ""."""
    unit, factor = q.display or (q.unit, 1.0)
    return ("" if unit == "-" else unit), factor


def format_value(q: Quantity, value: float) -> str:
    """``value`` (in the quantity's SI unit) in its display unit, 6 significant digits."""
    unit, factor = display_unit(q)
    return f"{value * factor:.6g} {unit}".rstrip()


def format_error(q: Quantity) -> str:
    """The error for display: a relative one in %, others in the display unit."""
    e = q.error
    if q.error_kind == "relative":
        return f"{e * 100:+.3g} %"
    unit, factor = display_unit(q)
    return f"{e * factor:+.3g} {unit}".rstrip()


def format_tolerance(q: Quantity) -> str:
    """The tolerance for display: +- the tolerance, or the bound on the value."""
    if q.error_kind == "relative":
        return f"+-{q.tolerance * 100:.3g} %"
    unit, factor = display_unit(q)
    if q.error_kind == "absolute":
        return f"+-{q.tolerance * factor:.3g} {unit}".rstrip()
    # a bound reads best as the bound on the value itself
    if q.error_kind == "lower_bound":
        return f"value >= {(q.reference - q.tolerance) * factor:.4g} {unit}".rstrip()
    return f"value <= {(q.reference + q.tolerance) * factor:.4g} {unit}".rstrip()


UM = ("um", 1e6)
"""Display of a length in m as um."""
MM = ("mm", 1e3)
N_PER_UM = ("N/um", 1e-6)
"""Display of a mesh stiffness in N/m as N/um."""
N_PER_MM2 = ("N/mm^2", 1e-6)
"""Display of a stress in Pa as N/mm^2."""
N_PER_MM_UM = ("N/(mm um)", 1e-9)
"""Display of a stiffness per face width in N/m^2 as N/(mm um) (ISO 6336-1)."""
PERCENT = ("%", 100.0)
"""Display of a fraction (a relative change) in %."""
