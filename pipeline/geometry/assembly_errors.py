"""Spur/helical pair with displaced centres (assembly errors, the assembly-error paper).

The assembly-error paper's frame has its origin at the nominal pinion centre O_p, the y-axis
along the theoretical line of action and the x-axis normal to it; the nominal
gear centre is ``O_g = (a sin(phi), a cos(phi))`` with ``a`` the nominal centre
distance and ``phi`` the operating pressure angle. The installed centres are

    O'_p = (e_xp, e_yp),    O'_g = (e_xg + a sin(phi), e_yg + a cos(phi)).

The actual line of action is the common internal tangent of the two base
circles about the installed centres: its length ``T1'T2' = a' sin(alpha')`` with
``a' = |O'_g - O'_p|`` and ``cos(alpha') = (r_b1 + r_b2) / a'``. Its end points,
the start and end of contact (where it cuts the tip circles) and the pressure
angle ``alpha_i = acos(r_bi / R_Xi)`` at every contact point follow; the mesh
stiffness of the displaced pair is that of the pair at centre distance ``a'``,
with the mesh cycle shifted in pinion angle by the rotation of the line of
action (:attr:`AssembledPair.roll_offset`).

The paper's text places ``O_g`` at angle ``phi`` from its y-axis (so the error
vector is projected on ``(sin phi, cos phi)`` to change the centre distance);
we take those coordinates literally.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError, check_range


@dataclass(frozen=True)
class AssemblyErrors:
    """Centre displacements of the two gears (m), in the frame of the assembly-error model:
    y along the nominal line of action.

    Attributes
    ----------
    pinion : (e_x, e_y) of the pinion centre, m, each in [-5, 5] mm.
    gear : (e_x, e_y) of the gear centre, m, each in [-5, 5] mm.
    """

    pinion: tuple[float, float] = (0.0, 0.0)
    gear: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        for who in ("pinion", "gear"):
            e = tuple(float(v) for v in getattr(self, who))
            if len(e) != 2:
                raise InputError(f"assembly_error_{who} needs 2 values (e_x, e_y)")
            for i, v in enumerate(e):
                check_range(f"assembly_error_{who}[{i}]", v, -5e-3, 5e-3, unit="m")
            object.__setattr__(self, who, e)

    @property
    def is_zero(self) -> bool:
        return not any(self.pinion) and not any(self.gear)


@dataclass(frozen=True)
class AssembledPair:
    """A nominal pair and the actual pair after the centres are displaced.

    Attributes
    ----------
    nominal : the pair as designed.
    errors : the centre displacements (m, the assembly-error paper frame).
    """

    nominal: GearPair
    errors: AssemblyErrors

    def __post_init__(self) -> None:
        if self.nominal.gear.internal:
            raise InputError("assembly errors are modelled for external pairs only "
                             "(the assembly-error paper)")

    @cached_property
    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        """Installed centres (O'_p, O'_g) in the assembly-error paper frame, m, each shape (2,)."""
        a = self.nominal.operating_centre_distance
        phi = self.nominal.operating_pressure_angle
        op = np.array(self.errors.pinion, dtype=float)
        og = np.array(self.errors.gear, dtype=float) + [a * math.sin(phi), a * math.cos(phi)]
        return op, og

    @cached_property
    def centre_distance(self) -> float:
        """Actual centre distance a' in m."""
        op, og = self.centres
        return float(np.linalg.norm(og - op))

    @cached_property
    def actual(self) -> GearPair:
        """The pair at the actual centre distance (raises if the teeth lose contact)."""
        return GearPair(
            self.nominal.pinion, self.nominal.gear, centre_distance=self.centre_distance
        )

    @cached_property
    def centre_line_rotation(self) -> float:
        """Rotation of the centre line from nominal, rad (positive counter-clockwise)."""
        op, og = self.centres
        d = og - op
        phi = self.nominal.operating_pressure_angle
        return math.atan2(d[0], d[1]) * -1.0 + math.atan2(math.sin(phi), math.cos(phi))

    @cached_property
    def roll_offset(self) -> float:
        """Shift of the contact along the line of action at a fixed pinion angle, m.

        The pinion's base tangent point turns with the centre line and with the
        change of pressure angle: ``r_b1 (delta + alpha' - alpha)``.
        """
        da = self.actual.operating_pressure_angle - self.nominal.operating_pressure_angle
        return self.nominal.pinion.base_radius * (self.centre_line_rotation + da)

    def _frame(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Unit vectors of the actual centre line and line of action, and T1' (m)."""
        op, og = self.centres
        c = (og - op) / self.centre_distance
        alpha = self.actual.operating_pressure_angle
        # O'_p T1' makes the angle alpha' with the centre line; T2' = O'_g - r_b2 e, so the
        # line of action runs from T1' along u = sin(alpha) c - cos(alpha) n.
        n = np.array([c[1], -c[0]])  # centre line rotated by -90 deg
        e = math.cos(alpha) * c + math.sin(alpha) * n
        t1 = op + self.nominal.pinion.base_radius * e
        direction = math.sin(alpha) * c - math.cos(alpha) * n
        return c, direction, t1

    def line_of_action(self) -> tuple[np.ndarray, np.ndarray]:
        """End points T1' and T2' of the actual line of action, m, each shape (2,)."""
        _, u, t1 = self._frame()
        return t1, t1 + self.actual.t1t2 * u

    def contact_points(self, s: ArrayLike) -> np.ndarray:
        """Points on the actual line of action at roll coordinates ``s`` (m), shape (..., 2)."""
        _, u, t1 = self._frame()
        return t1 + np.asarray(s, dtype=float)[..., None] * u

    def contact_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """Start A' and end E' of contact (gear and pinion tip circles), m."""
        return self.contact_points(self.actual.s_start), self.contact_points(self.actual.s_end)

    def pressure_angles(self, s: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """alpha_i = acos(r_bi / |X - O'_i|) at contact points ``s`` on the actual line, rad."""
        x = self.contact_points(s)
        op, og = self.centres
        r1 = np.linalg.norm(x - op, axis=-1)
        r2 = np.linalg.norm(x - og, axis=-1)
        return (np.arccos(self.nominal.pinion.base_radius / r1),
                np.arccos(self.nominal.gear.base_radius / r2))

    def summary(self) -> dict[str, float]:
        act, nom = self.actual, self.nominal
        return {
            "centre_distance_m": self.centre_distance,
            "centre_distance_change_um": (self.centre_distance - nom.operating_centre_distance)
            * 1e6,
            "operating_pressure_angle_deg": math.degrees(act.operating_pressure_angle),
            "transverse_contact_ratio": act.transverse_contact_ratio,
            "nominal_contact_ratio": nom.transverse_contact_ratio,
            "double_contact_fraction": act.transverse_contact_ratio - 1.0,
            "roll_offset_um": self.roll_offset * 1e6,
        }


def assemble(pair: GearPair, errors: AssemblyErrors | None) -> AssembledPair | None:
    """The pair with its centres displaced by ``errors``, or ``None`` without errors."""
    return None if errors is None or errors.is_zero else AssembledPair(pair, errors)
