"""A pair in its transverse plane: centres, base tangent points, pitch point, contact points.

The frame (m) has the pinion centre O1 at the origin and the y-axis along the centre line
towards the pitch point C = (0, r_w1). The gear centre O2 lies on the same line, at
``(0, a_w)`` for an external pair (C between the centres) and at ``(0, -a_w)`` for an
internal one (the ring's centre on the far side of the pinion's, ``r_w2 - r_w1 = a_w``).

The transverse line of action crosses C at the operating pressure angle alpha_wt and
touches the pinion's base circle at T1 = r_b1 (-sin alpha_wt, cos alpha_wt). Its points are
``T1 + s u`` with ``u = (cos alpha_wt, sin alpha_wt)`` and ``s`` the roll coordinate of
:mod:`pipeline.geometry.pair`. The gear's base circle is touched at T2, at ``s = T1T2``
(external: beyond C) or ``s = -T1T2`` (internal: both tangent points on the same side of C,
T2 behind T1), ``T1T2 = a_w sin alpha_wt``. So the gear's radius of curvature at ``s``, the
distance from T2, is ``T1T2 - s`` or ``s + T1T2``, as :meth:`GearPair.curvature_radii`
says.

Named points on the path of contact (ISO 6336-2, clause 6; the pinion driving): A, where
the gear's tip circle cuts the line (start of contact); E, where the pinion's does (end);
C, the pitch point; and, for 1 <= eps_alpha < 2, the inner points of single contact
B = E - p_bt (lowest point of single contact on the pinion) and D = A + p_bt (highest).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.pair import GearPair


@dataclass(frozen=True)
class TransverseLayout:
    """Points of a pair in its transverse plane (frame in the module docstring), m.

    Attributes
    ----------
    pair : the pair drawn.
    """

    pair: GearPair

    @cached_property
    def pinion_centre(self) -> np.ndarray:
        """O1, shape (2,), m: the origin."""
        return np.zeros(2)

    @cached_property
    def gear_centre(self) -> np.ndarray:
        """O2, shape (2,), m: ``(0, a_w)`` external, ``(0, -a_w)`` internal."""
        return np.array([0.0, self.pair.sign * self.pair.operating_centre_distance])

    @cached_property
    def direction(self) -> np.ndarray:
        """Unit vector u of growing roll coordinate along the line of action, shape (2,)."""
        a = self.pair.operating_pressure_angle
        return np.array([math.cos(a), math.sin(a)])

    @cached_property
    def t1(self) -> np.ndarray:
        """T1, where the line of action touches the pinion's base circle, shape (2,), m."""
        a, rb1 = self.pair.operating_pressure_angle, self.pair.pinion.base_radius
        return rb1 * np.array([-math.sin(a), math.cos(a)])

    @cached_property
    def s_t2(self) -> float:
        """Roll coordinate of T2, m: ``+T1T2`` external, ``-T1T2`` internal."""
        return self.pair.sign * self.pair.t1t2

    def point(self, s: ArrayLike) -> np.ndarray:
        """Points ``T1 + s u`` of the line of action at roll coordinates ``s`` (m),
        shape ``s.shape + (2,)``, m."""
        return self.t1 + np.asarray(s, dtype=float)[..., None] * self.direction

    @cached_property
    def rolls(self) -> dict[str, float]:
        """Roll coordinates (m) of T1, T2, A, B, C, D, E (B and D only for
        1 <= eps_alpha < 2, where they are the inner points of single contact)."""
        p = self.pair
        out = {"T1": 0.0, "T2": self.s_t2, "A": p.s_start, "C": p.s_pitch, "E": p.s_end}
        if 1.0 <= p.transverse_contact_ratio < 2.0:
            out["B"] = p.s_end - p.base_pitch
            out["D"] = p.s_start + p.base_pitch
        return out

    @cached_property
    def points(self) -> dict[str, np.ndarray]:
        """The named points of :attr:`rolls` in the transverse plane, each shape (2,), m."""
        return {name: self.point(s) for name, s in self.rolls.items()}
