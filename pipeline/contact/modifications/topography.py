"""A measured or designed flank topography: a grid of deviations over face x profile.

The grid gives the material removed ``w`` (m, positive = removed, like every modification)
at face positions ``z_i`` (m, the gear's own face coordinate of
:mod:`~pipeline.contact.modifications.frame`) times profile positions, either roll lengths
``rho = sqrt(r^2 - r_b^2)`` (m) or diameters ``d`` (m). Between grid points it is
interpolated **bilinearly** in (z_i, profile coordinate): on a cell
``[z_0, z_1] x [p_0, p_1]`` with ``t = (z - z_0) / (z_1 - z_0)``, ``q = (p - p_0) / (p_1 - p_0)``,
``w = (1-t)(1-q) w_00 + (1-t) q w_01 + t (1-q) w_10 + t q w_11``, which reproduces any
function bilinear on each cell exactly (to round-off): linear reliefs with a grid line at
their start, slopes, a twist.

The grid must ascend strictly along both axes and cover the flank the mesh can touch:
face ``[0, b_i]`` and the active flank (:meth:`Topography.check_fits`), each to within
:data:`COVER_TOLERANCE` (a grid written to the micrometre), inside which the query is held
at the grid's edge.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.contact.modifications.frame import FlankFrame
from pipeline.contact.modifications.profile import MAX_AMOUNT
from pipeline.validation import InputError

AXES = ("roll_length", "diameter")
"""Profile coordinates of a grid."""
COVER_TOLERANCE = 1e-6
"""m: how far inside the flank a grid's edge may stop (the micrometre a file is written to)."""


@dataclass(frozen=True, eq=False)
class Topography:
    """A deviation grid over one gear's flank (module docstring).

    Attributes
    ----------
    face : (nf,) face positions z_i, m, strictly ascending, nf >= 2.
    profile : (np,) roll lengths or diameters (``axis``), m, strictly ascending, np >= 2.
    values : (nf, np) material removed, m, each of magnitude <= 1e-3.
    axis : "roll_length" or "diameter".
    source : where the grid came from (a file name), for messages.
    """

    face: np.ndarray
    profile: np.ndarray
    values: np.ndarray
    axis: str = "roll_length"
    source: str = "grid"

    def __post_init__(self) -> None:
        if self.axis not in AXES:
            raise InputError(f"{self.source}: profile axis {self.axis!r} is not one of "
                             f"{', '.join(map(repr, AXES))}")
        for name in ("face", "profile"):
            a = np.array(getattr(self, name), dtype=float).reshape(-1)
            if a.size < 2 or not np.all(np.isfinite(a)) or np.any(np.diff(a) <= 0.0):
                raise InputError(f"{self.source}: the {name} positions must be at least two "
                                 f"finite numbers, strictly ascending")
            a.setflags(write=False)
            object.__setattr__(self, name, a)
        v = np.array(self.values, dtype=float)
        if v.shape != (self.face.size, self.profile.size):
            raise InputError(f"{self.source}: {v.size} deviations for a grid of "
                             f"{self.face.size} face x {self.profile.size} profile positions")
        worst = float(np.nanmax(np.abs(v))) if v.size else 0.0
        if not np.all(np.isfinite(v)) or worst > MAX_AMOUNT:
            raise InputError(f"{self.source}: deviations must be finite numbers of magnitude at "
                             f"most {MAX_AMOUNT * 1e6:g} um (largest {worst * 1e6:.6g} um)")
        v.setflags(write=False)
        object.__setattr__(self, "values", v)

    def coordinate(self, frame: FlankFrame, s: np.ndarray) -> np.ndarray:
        """Its profile coordinate (roll length or diameter, m) at roll coordinates ``s``."""
        return frame.roll(s) if self.axis == "roll_length" else frame.diameter(s)

    def at(self, z: np.ndarray, p: np.ndarray) -> np.ndarray:
        """Bilinear interpolation (m) at face positions ``z`` and profile coordinates ``p``
        (m, broadcast together), held at the grid's edges."""
        z, p = np.broadcast_arrays(np.asarray(z, dtype=float), np.asarray(p, dtype=float))
        i, t = _cell(self.face, z)
        j, q = _cell(self.profile, p)
        v = self.values
        return ((1.0 - t) * ((1.0 - q) * v[i, j] + q * v[i, j + 1])
                + t * ((1.0 - q) * v[i + 1, j] + q * v[i + 1, j + 1]))

    def terms(self, frame: FlankFrame, s: np.ndarray, z: np.ndarray) -> dict[str, np.ndarray]:
        """Material removed (m) at a mesh's roll coordinates ``s`` and face positions ``z``."""
        zi = np.asarray(z, dtype=float) + frame.face_shift
        return {"topography": self.at(zi, self.coordinate(frame, s))}

    @property
    def varies_across_face(self) -> bool:
        return bool(np.any(self.values != self.values[:1]))

    def check_fits(self, frame: FlankFrame, mesh: str = "") -> None:
        """Refuse a grid that does not cover the face ``[0, b_i]`` and the active flank of
        ``frame`` (to :data:`COVER_TOLERANCE`), naming what is missing."""
        where = f" of the {mesh} mesh" if mesh else ""
        lo, hi = frame.active_roll if self.axis == "roll_length" else frame.active_diameter
        what = "roll lengths" if self.axis == "roll_length" else "diameters"
        for name, grid, need, span in (
                ("face positions", self.face, (0.0, frame.face_width),
                 f"the {frame.role}'s face width"),
                (what, self.profile, (lo, hi), f"the {frame.role}'s active flank{where}")):
            if grid[0] > need[0] + COVER_TOLERANCE or grid[-1] < need[1] - COVER_TOLERANCE:
                raise InputError(
                    f"{self.source}: {name} {grid[0] * 1e3:.6g} to {grid[-1] * 1e3:.6g} mm do "
                    f"not cover {span}, {need[0] * 1e3:.6g} to {need[1] * 1e3:.6g} mm")


def _cell(grid: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cell index (lower grid point) and position in the cell in [0, 1] of each ``x``."""
    xc = np.clip(x, grid[0], grid[-1])
    i = np.clip(np.searchsorted(grid, xc, side="right") - 1, 0, grid.size - 2)
    return i, (xc - grid[i]) / (grid[i + 1] - grid[i])
