"""Plot units shared by every figure, so one quantity reads the same in all of them.

Mesh stiffness (and any other stiffness of a gear mesh: the friction stiffness, the
single-tooth and pair curves) is shown in N/um (= kN/mm = 1e6 N/m), the unit of
ISO 6336-1's c' and c_gamma in N/(mm um) times the face width in mm.
"""

from __future__ import annotations

import numpy as np

STIFFNESS_UNIT = "N/um"
"""Unit of every stiffness axis."""

_N_PER_UM = 1e6  # N/m per N/um


def stiffness_in_plot_unit(k_N_per_m) -> np.ndarray:
    """Stiffness ``k`` (N/m, any shape) in :data:`STIFFNESS_UNIT`."""
    return np.asarray(k_N_per_m, dtype=float) / _N_PER_UM


def stiffness_label(what: str = "mesh stiffness") -> str:
    """Axis label of a stiffness: ``"<what> [N/um]"``."""
    return f"{what} [{STIFFNESS_UNIT}]"
