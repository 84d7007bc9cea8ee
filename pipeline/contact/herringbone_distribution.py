"""Load distribution of each helical half of a herringbone mesh, from the contact through the
groove (:class:`~pipeline.contact.herringbone_results.HerringboneCycle`).

Each half's contact is a helical-half cycle carrying its own load ``P_h(t)``, which moves
over the mesh cycle, so :func:`~pipeline.contact.distribution.load_distribution` gives its
line load (N/m over the face of that half), K_Hbeta, the tooth-pair unit load ratio and
Hertz pressure as for a helical pair, with every per-position ratio taken at ``P_h(t)``. The
operating point of a half is the sun's torque through that half on one planet mesh at its
mean load, ``T_h = mean(P_h) r_b,sun`` (N m), at the sun's speed relative to the carrier
(the contact is solved in the carrier frame); the whole sun carries ``N T_h`` through the
half.

The **governing half** is the one with the larger maximum line load over the cycle (the
quantity the face load factor and the Hertz pressure grow with); ties go to the left.
Beside it, optionally, the **equal split**: one helical half solved on its own at half the
mesh load (``T / 2``, what a rating of one half at an even split assumes), against which
each half's maximum line load is compared.
Equilibrium: ``P_L(t) + P_R(t) = P`` at every position, and each half's line load
integrates over its face to ``P_h(t)`` (to the contact solver's tolerance).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.contact.analysis import line_of_action_load
from pipeline.contact.distribution import LoadDistribution, load_distribution, position_loads
from pipeline.contact.herringbone_results import SIDES, HerringboneCycle
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError


@dataclass(frozen=True)
class HalfDistribution:
    """One helical half of a herringbone mesh.

    Attributes
    ----------
    side : "left", "right", or "equal split" (one helical half at ``P / 2``).
    cycle : the half's contact over the mesh cycle (its ``load`` the mean of ``load``).
    operation : sun torque through this half on one planet mesh at the half's mean load,
        N m, and the sun's speed relative to the carrier, rad/s.
    load : (m,) P_h(t), the half's load along the transverse line of action, N.
    share : (m,) P_h(t) / P, the half's share of the mesh load (-).
    sun_torque : N T_h, sun torque through this half from all N planets, N m.
    distribution : line load, K_Hbeta, tooth-pair unit load ratio, Hertz pressure of the half.
    """

    side: str
    cycle: LoadedMeshCycle
    operation: OperatingPoint
    load: np.ndarray
    share: np.ndarray
    sun_torque: float
    distribution: LoadDistribution

    @property
    def max_line_load(self) -> float:
        """Largest line load of the half over its face and the cycle, N/m."""
        return self.distribution.line_load_max.value


@dataclass(frozen=True)
class HerringboneDistribution:
    """Both halves of a herringbone mesh (module docstring).

    Attributes
    ----------
    left, right : the halves.
    operation : the whole mesh: sun torque on one planet mesh (both halves), N m, and the
        sun's speed relative to the carrier, rad/s.
    load : P = P_L + P_R, N.
    n_planets : N.
    governing : the side with the larger maximum line load.
    equal_split : one helical half solved on its own at half the mesh load (``T / 2``;
        side "equal split", share 1/2), or None.
    """

    left: HalfDistribution
    right: HalfDistribution
    operation: OperatingPoint
    load: float
    n_planets: int
    governing: str
    equal_split: HalfDistribution | None = None

    def half(self, side: str) -> HalfDistribution:
        """The half ``side``: "left", "right" or "equal split" (KeyError without it)."""
        out = {"left": self.left, "right": self.right, "equal split": self.equal_split}[side]
        if out is None:
            raise KeyError(side)
        return out

    @property
    def other(self) -> str:
        """The side that does not govern."""
        return "right" if self.governing == "left" else "left"

    @property
    def line_load_ratio(self) -> float:
        """Maximum line load of the governing half over the other's (-)."""
        return self.half(self.governing).max_line_load / self.half(self.other).max_line_load

    def over_equal_split(self, side: str) -> float:
        """Maximum line load of ``side`` ("left", "right", "equal split") over the equal
        split's (-; NaN without it)."""
        if self.equal_split is None:
            return math.nan
        return self.half(side).max_line_load / self.equal_split.max_line_load

    def summary(self) -> dict[str, Any]:
        """Per half: torque, shares, line loads, load factors, Hertz pressure; which half
        governs (SI; units in keys)."""
        out: dict[str, Any] = {"load_N": self.load, "governing": self.governing,
                               "max_line_load_ratio": self.line_load_ratio}
        for side in SIDES:
            h = self.half(side)
            d = h.distribution
            out[side] = {"torque_per_planet_Nm": h.operation.torque,
                         "sun_torque_Nm": h.sun_torque,
                         "load_share_mean": float(h.share.mean()),
                         "load_share_min": float(h.share.min()),
                         "load_share_max": float(h.share.max()),
                         "mean_line_load_N_per_m": d.mean_line_load,
                         "max_line_load_N_per_m": d.line_load_max.value,
                         "max_line_load_over_equal_split": self.over_equal_split(side),
                         "K_Hbeta": d.k_hbeta, "pair_unit_load_ratio": d.pair_load_ratio,
                         "max_hertz_pressure_Pa": d.hertz_max.value}
        return out


def herringbone_distribution(cycle: HerringboneCycle, pair: GearPair,
                             operation: OperatingPoint, *,
                             equal_split: LoadedMeshCycle | None = None
                             ) -> HerringboneDistribution:
    """Load distribution of both halves of a herringbone mesh (module docstring).

    Parameters
    ----------
    cycle : the contact of both halves through the groove.
    pair : the helical-half pair it was solved on (sun = pinion).
    operation : the whole mesh's operating point: sun torque on one planet mesh (both
        halves, N m) at the sun's speed relative to the carrier (rad/s); its load must be
        the cycle's ``P``.
    equal_split : the contact of one helical half of ``pair`` solved on its own at ``P / 2``
        (optional).

    Returns
    -------
    HerringboneDistribution

    Raises
    ------
    InputError when ``operation`` is not the one the cycle was solved at, or the equal
    split not at half its load.
    """
    if operation.driver != "pinion":
        raise InputError("herringbone distribution: the sun (the pinion) drives the mesh")
    expected = line_of_action_load(pair, operation)
    if not math.isclose(cycle.load, expected, rel_tol=1e-9):
        raise InputError(f"herringbone distribution: the cycle was solved at P = "
                         f"{cycle.load:.6g} N, the operating point gives {expected:.6g} N "
                         f"(sun torque {operation.torque:.6g} N m per planet mesh)")
    if equal_split is not None and not math.isclose(equal_split.load, 0.5 * cycle.load,
                                                    rel_tol=1e-9):
        raise InputError(f"herringbone distribution: the equal split carries "
                         f"{equal_split.load:.6g} N, not half the mesh load P / 2 = "
                         f"{0.5 * cycle.load:.6g} N")

    def half(side: str, c: LoadedMeshCycle, p: np.ndarray) -> HalfDistribution:
        op = OperatingPoint(c.load * pair.pinion.base_radius, operation.speed, "pinion")
        return HalfDistribution(side, c, op, p, p / cycle.load, cycle.n_planets * op.torque,
                                load_distribution(c, pair, op))

    halves = {side: half(side, cycle.half(side), np.array(cycle.half_load(side), dtype=float))
              for side in SIDES}
    equal = None if equal_split is None else half("equal split", equal_split,
                                                  position_loads(equal_split))
    governing = ("right" if halves["right"].max_line_load > halves["left"].max_line_load
                 else "left")
    return HerringboneDistribution(halves["left"], halves["right"], operation,
                                   float(cycle.load), cycle.n_planets, governing, equal)
