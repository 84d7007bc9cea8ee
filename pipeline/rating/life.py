"""Life factor curves of ISO 6336-2 (Z_NT) and ISO 6336-3 (Y_NT), the limited-life range
of the influence factors and the S-N line (Woehler line) they make together.

Life factor: a material line given by its table points (load cycles, factor), static below
the first point ``N_0``, log-log between points, the long-life branch from the endurance
knee ``N_ref`` (the point where the factor is 1) down to its value at 10^10 cycles (1.0
under optimum lubrication, material, manufacturing and experience), constant beyond.

Limited life (method B, between ``N_0`` and ``N_ref``): the permissible stress without
``S_min`` (``sigma_HG``, ``sigma_FG``) runs log-log between its static value at ``N_0`` and
its endurance value at ``N_ref``, each with its own influence factors:
``sigma_G(N) = sigma_G,ref (N_ref / N)^(log(sigma_G,stat / sigma_G,ref) / log(N_ref / N_0))``.
The life factor runs log-log between the same two points, so the product ``I`` of the
influence factors goes ``I(N) = I_ref^(1 - w) I_stat^w`` with the weight
``w = ln(life factor(N)) / ln(life factor(N_0))`` (1 at and below ``N_0``, 0 at and beyond
``N_ref``; :func:`static_weight`), each factor alike (:func:`limited_life_value`). For a
line with an intermediate point (ISO 6336-2's line where some pitting is permitted: 1.6 at
6 x 10^5, 1.3 at 10^7, 1.0 at 10^9) the weight follows the table's points segment by
segment. Confirmed in DIN 3990-11 (the application standard of ISO 6336's method B; its
equations 4.04-4.10 and 5.04-5.06 as transcribed in the public repository
hanslhansl/din3990, ``din3990/din3990_11.py``): ``sigma_HG`` from ``sigma_HG,stat =
sigma_Hlim Z_NT,stat Z_LVR,stat Z_W Z_X,stat`` (``Z_LVR,stat = Z_X,stat = 1``) to
``sigma_HG,dauer`` with the exponent ``0.3705 log(sigma_HG,stat / sigma_HG,dauer)`` on
``(5 x 10^7 / N_L)`` for 10^5 < N_L <= 5 x 10^7 (``0.3705 = 1 / log(500)``), ``0.7686``
from 10^5 to 2 x 10^6 (nitrided), ``0.3705`` on ``3 x 10^8 / N_L`` and ``0.2791`` on
``10^9 / N_L`` where some pitting is permitted; ``sigma_FG`` from ``sigma_FE Y_NT,stat
Y_deltarelT,stat Y_RrelT,stat Y_X,stat`` (``Y_RrelT,stat = Y_X,stat = 1``) with ``0.4037``
from 10^4 (through-hardened) and ``0.2876`` from 10^3 (case-hardened, nitrided) to 3 x
10^6. KISSsoft's ISO 6336:2006 method B reports say the same of ISO 6336 ("the
logarithmically interpolated value taken from the values for the fatigue strength and the
static strength, based on the number of load cycles, is used for coefficients ZL, ZV, ZR,
ZW, ZX, YdrelT, YRrelT and YX": ``@NREL_5MW/stage_03.rtf`` of gfsReboucas/Drivetrain,
commit 4a88df34). The same two-point rule, written with ``ln`` instead of ``log10``, is in
that repository's ``MATISO_6336.m`` (``life_factor``).

:class:`StrengthCurve` is that S-N line for one gear and failure mode: ``sigma_G(N) =
limit x life factor(N) x I(N)``, and its inverse, the load cycles to failure at a stress,
which ISO 6336-6's Miner sum needs (:mod:`.spectrum`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.validation import InputError, check_range

Points = tuple[tuple[float, float], ...]


def _line(points: Points, optimum: bool) -> list[tuple[float, float]]:
    pts = list(points)
    if optimum:
        pts[-1] = (pts[-1][0], 1.0)
    return pts


def life_factor_on(points: Points, cycles: float, optimum: bool = False) -> float:
    """The life factor at ``cycles`` load cycles on the line ``points``."""
    check_range("rating.load_cycles", cycles, 0.0, math.inf, lo_open=True)
    pts = _line(points, optimum)
    if cycles <= pts[0][0]:
        return pts[0][1]
    for (n0, y0), (n1, y1) in zip(pts[:-1], pts[1:], strict=True):
        if cycles <= n1:
            t = math.log(cycles / n0) / math.log(n1 / n0)
            return math.exp(math.log(y0) + t * math.log(y1 / y0))
    return pts[-1][1]


def endurance_knee(points: Points) -> float:
    """``N_ref``: the load cycles where the line's factor reaches 1 (the endurance knee)."""
    return next(n for n, y in points if y == 1.0)


def static_weight(points: Points, cycles: float) -> float:
    """The weight ``w`` of the static values at ``cycles`` load cycles on the line
    ``points``: 1 at and below the static point ``N_0``, 0 at and beyond the knee,
    ``ln(factor(N)) / ln(factor(N_0))`` between (log-linear in ``N`` on each segment)."""
    check_range("rating.load_cycles", cycles, 0.0, math.inf, lo_open=True)
    if cycles >= endurance_knee(points):
        return 0.0
    static = points[0][1]
    return math.log(life_factor_on(points, cycles)) / math.log(static)


def limited_life_value(endurance: float, static: float, weight: float) -> float:
    """An influence factor in the limited-life range: ``endurance^(1 - w) static^w`` (its
    value at the knee, its static value, the :func:`static_weight` ``w``)."""
    return endurance ** (1.0 - weight) * static**weight


@dataclass(frozen=True)
class StrengthCurve:
    """The S-N line of one gear and failure mode: the permissible stress without the
    minimum safety factor (``sigma_HG`` of ISO 6336-2, ``sigma_FG`` of ISO 6336-3)
    against the load cycles.

    ``sigma_G(N) = limit x life(N) x influence^(1 - w(N)) x influence_static^w(N)`` with
    the life factor ``life`` on ``points`` and the weight ``w`` of :func:`static_weight`.

    Attributes
    ----------
    points : the life line, ((load cycles, factor), ...), as in ``pitting.LIFE_LINES``.
    limit : the allowable stress number, Pa (``sigma_Hlim``; ``sigma_Flim Y_ST Y_M``).
    influence : the product of the influence factors at and beyond the knee (-)
        (``Z_L Z_v Z_R Z_W Z_X``; ``Y_deltarelT Y_RrelT Y_X``).
    influence_static : their product at the static point (-) (1; ``Y_deltarelT,stat``);
        equal to ``influence`` for a line whose influence factors keep their endurance
        values, as ISO 6336-6's example of Annex C does.
    optimum : the long-life branch stays at 1 (optimum lubrication, material,
        manufacturing and experience) instead of falling to the line's value at 10^10.
    extend_static : above the static strength, continue the first segment's slope (the S-N
        line of ISO 6336-6's Annex C example, whose highest bins fail before 10^5 cycles)
        instead of the static limit of ISO 6336-2/-3 (a stress above it fails at once).
    """

    points: Points
    limit: float
    influence: float
    influence_static: float = 1.0
    optimum: bool = False
    extend_static: bool = False

    def __post_init__(self) -> None:
        check_range("rating.sigma_lim", self.limit, 0.0, math.inf, lo_open=True, unit="Pa")
        check_range("rating.influence_factors", self.influence, 0.1, 10.0)
        check_range("rating.influence_factors_static", self.influence_static, 0.1, 10.0)
        if len(self.points) < 2 or not any(y == 1.0 for _, y in self.points):
            raise InputError(f"rating: a life line needs two points or more and a knee "
                             f"(factor 1.0); got {self.points!r}")

    def strength(self, cycles: float) -> float:
        """``sigma_G`` at ``cycles`` load cycles, Pa."""
        w = static_weight(self.points, cycles)
        return (self.limit * life_factor_on(self.points, cycles, self.optimum)
                * limited_life_value(self.influence, self.influence_static, w))

    def _nodes(self) -> tuple[np.ndarray, np.ndarray]:
        """``ln N`` and ``ln sigma_G`` at the line's points, strictly decreasing stress: the
        curve is log-log linear between them (``ln`` of the life factor and ``w`` are
        linear in ``ln N`` on each segment); a flat tail (optimum) is dropped."""
        pts = _line(self.points, self.optimum)
        ln_n = [math.log(n) for n, _ in pts]
        ln_s = [math.log(self.strength(n)) for n, _ in pts]
        while len(ln_s) > 2 and ln_s[-1] >= ln_s[-2]:
            ln_n.pop()
            ln_s.pop()
        return np.array(ln_n), np.array(ln_s)

    def cycles_to_failure(self, stress: np.ndarray | float) -> np.ndarray:
        """The load cycles to failure at ``stress`` (Pa, any shape): the inverse of
        :meth:`strength`; ``inf`` at and below the line's lowest strength (its value from
        10^10 cycles on, or the endurance strength with ``optimum``), 0 above the static
        strength unless ``extend_static``."""
        ln_n, ln_s = self._nodes()
        s = np.log(np.asarray(stress, dtype=float))
        # np.interp wants increasing abscissae: walk the line from its lowest strength
        out = np.exp(np.interp(s, ln_s[::-1], ln_n[::-1]))
        out = np.where(s <= ln_s[-1], np.inf, out)
        above = s > ln_s[0]
        if self.extend_static:
            slope = (ln_n[1] - ln_n[0]) / (ln_s[1] - ln_s[0])
            out = np.where(above, np.exp(ln_n[0] + slope * (s - ln_s[0])), out)
        else:
            out = np.where(above, 0.0, out)
        return out
