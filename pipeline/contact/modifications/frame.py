"""Where one gear's flank lies on the path of contact of one mesh (its flank frame).

Each gear's modifications are given in its own coordinates: the **roll length**
``rho = sqrt(r^2 - r_b^2)`` (m; ISO 21771 ``L_y``, the radius of curvature of the involute
at radius ``r``) or the **diameter** ``d = 2 r`` across the profile, and the **face
position** ``z_i`` (m) across its own face width ``b_i`` from its first face (the face on
the side of the pinion's reference face). A mesh locates contact by the roll coordinate
``s`` on the transverse line of action (from T1, :mod:`pipeline.geometry.pair`) and the
face position ``z`` in ``[0, b]`` over the common face width ``b``; then

* roll length: the pinion's ``rho_1 = s``; an external gear's ``rho_2 = T1T2 - s``, an
  internal gear's ``|rho_2| = T1T2 + s``: ``rho = roll_offset + roll_sign s``;
* the pinion's active tip is at ``s_end``, its start of active profile (the mate's tip)
  at ``s_start``; the gear's tip at ``s_start`` and its start of active profile at
  ``s_end``: ``toward_tip`` is +1 for the pinion and -1 for the gear (internal or not);
* the gears are taken centred on each other across the face: ``z_i = z + (b_i - b) / 2``
  (a herringbone gear's helical half is its face here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.geometry.pair import GearPair


@dataclass(frozen=True)
class FlankFrame:
    """One gear's flank on the path of contact of one mesh (module docstring; all m).

    Attributes
    ----------
    role : "pinion" or "gear" (of the mesh).
    base_radius : r_b, m.
    tip_s, root_s : roll coordinates s of its active tip and its start of active profile.
    toward_tip : +1 when s grows towards its tip (pinion), -1 (gear).
    roll_sign, roll_offset : its roll length is ``roll_offset + roll_sign s``.
    face_width : its own face width b_i (one helical half of a herringbone gear).
    face_shift : ``(b_i - b) / 2``: its face position is ``z + face_shift``.
    common_width : the mesh's common face width b (the narrower gear's).
    """

    role: str
    base_radius: float
    tip_s: float
    root_s: float
    toward_tip: int
    roll_sign: int
    roll_offset: float
    face_width: float
    face_shift: float
    common_width: float

    def roll(self, s: np.ndarray) -> np.ndarray:
        """Its roll length (m) at roll coordinates ``s`` (m) of the mesh."""
        return self.roll_offset + self.roll_sign * np.asarray(s, dtype=float)

    def diameter(self, s: np.ndarray) -> np.ndarray:
        """Its diameter (m) at roll coordinates ``s`` (m): ``2 sqrt(rho^2 + r_b^2)``."""
        return 2.0 * np.hypot(self.roll(s), self.base_radius)

    def s_at_roll(self, rho: float) -> float:
        """The mesh's roll coordinate s (m) where its roll length is ``rho`` (m)."""
        return self.roll_sign * (rho - self.roll_offset)

    def s_at_diameter(self, d: float) -> float:
        """The mesh's roll coordinate s (m) of its flank point of diameter ``d`` (m)
        (``d`` at least its base diameter)."""
        return self.s_at_roll(math.sqrt(max((0.5 * d) ** 2 - self.base_radius**2, 0.0)))

    def into(self, s: np.ndarray, start: float) -> np.ndarray:
        """Distance (m) along the path from ``start`` (an s, m) towards its tip."""
        return (np.asarray(s, dtype=float) - start) * self.toward_tip

    @property
    def active_length(self) -> float:
        """Length of its active flank along the path (the path of contact), m."""
        return abs(self.tip_s - self.root_s)

    @property
    def active_roll(self) -> tuple[float, float]:
        """Its active flank as roll lengths (smaller, larger), m."""
        a, b = float(self.roll(self.root_s)), float(self.roll(self.tip_s))
        return (a, b) if a <= b else (b, a)

    @property
    def active_diameter(self) -> tuple[float, float]:
        """Its active flank as diameters (smaller, larger), m."""
        a, b = float(self.diameter(self.root_s)), float(self.diameter(self.tip_s))
        return (a, b) if a <= b else (b, a)


def flank_frames(pair: GearPair) -> tuple[FlankFrame, FlankFrame]:
    """The pinion's and the gear's flank frames in the mesh ``pair``."""
    p, g, b = pair.pinion, pair.gear, pair.face_width
    pinion = FlankFrame("pinion", p.base_radius, pair.s_end, pair.s_start, 1, 1, 0.0,
                        p.half_width, 0.5 * (p.half_width - b), b)
    gear = FlankFrame("gear", g.base_radius, pair.s_start, pair.s_end, -1,
                      1 if g.internal else -1, pair.t1t2, g.half_width,
                      0.5 * (g.half_width - b), b)
    return pinion, gear
