"""Life factor curves of ISO 6336-2 (Z_NT) and ISO 6336-3 (Y_NT): a material line given by
its table points (load cycles, factor), static below the first point, log-log between
points, the long-life branch down to its value at 10^10 cycles (1.0 under optimum
lubrication, material, manufacturing and experience), constant beyond."""

from __future__ import annotations

import math

from pipeline.validation import check_range


def life_factor_on(points: tuple[tuple[float, float], ...], cycles: float,
                   optimum: bool = False) -> float:
    """The life factor at ``cycles`` load cycles on the line ``points``."""
    check_range("rating.load_cycles", cycles, 0.0, math.inf, lo_open=True)
    pts = list(points)
    if optimum:
        pts[-1] = (pts[-1][0], 1.0)
    if cycles <= pts[0][0]:
        return pts[0][1]
    for (n0, y0), (n1, y1) in zip(pts[:-1], pts[1:], strict=True):
        if cycles <= n1:
            t = math.log(cycles / n0) / math.log(n1 / n0)
            return math.exp(math.log(y0) + t * math.log(y1 / y0))
    return pts[-1][1]
