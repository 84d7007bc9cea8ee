"""The nodes of a shaft's beam model: every place where something happens is a node.

Key points: the segments' ends, the seat's ends and centre, the bearings, the torque point
and any points the caller asks for (loads, seat points of a flexibility). Each interval
between neighbouring key points is split into equal elements no longer than the target
length, and into at least two, so every segment and every half of the seat has a few
elements. Points closer than :func:`merge_tolerance` are one node.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from pipeline.shaft.layout import ShaftLayout

#: elements per interval between key points, at least
MIN_ELEMENTS = 2
#: the default element-length target as a fraction of the shaft's length
DEFAULT_FRACTION = 1.0 / 24.0


def merge_tolerance(layout: ShaftLayout) -> float:
    """Points closer than this (m) are one node: 1e-7 of the shaft's length, at least the
    layout's own 1 nm joint tolerance (a shorter element would only add round-off)."""
    return max(1e-9, 1e-7 * layout.length)


def key_points(layout: ShaftLayout, extra: Iterable[float] = ()) -> np.ndarray:
    """The sorted, merged key points (m) of ``layout`` and ``extra``."""
    pts = [0.0, layout.length, *(s.end for s in layout.segments), *layout.seat,
           layout.gear_position, layout.torque_position,
           *(b.position for b in layout.bearings), *extra]
    pts = np.sort(np.asarray(pts, float))
    tol = merge_tolerance(layout)
    keep = np.concatenate([[True], np.diff(pts) > tol])
    return pts[keep]


def beam_nodes(layout: ShaftLayout, element_length: float | None = None,
               extra: Iterable[float] = ()) -> np.ndarray:
    """(n,) sorted node positions z (m) of the beam model.

    Parameters
    ----------
    layout : the shaft.
    element_length : the element-length target, m (default: the shaft's length / 24).
    extra : further points that must be nodes, m.
    """
    h = layout.length * DEFAULT_FRACTION if element_length is None else element_length
    kp = key_points(layout, extra)
    parts = []
    for a, b in zip(kp[:-1], kp[1:], strict=True):
        n = max(MIN_ELEMENTS, math.ceil((b - a) / h - 1e-9))
        parts.append(np.linspace(a, b, n + 1)[:-1])
    parts.append(kp[-1:])
    return np.concatenate(parts)


def node_index(z: np.ndarray, points: Iterable[float], tol: float) -> np.ndarray:
    """Indices of the nodes ``z`` (sorted) at ``points``; ``ValueError`` if one is not a
    node (within ``tol``, m)."""
    p = np.atleast_1d(np.asarray(list(points) if not isinstance(points, np.ndarray)
                                 else points, float))
    i = np.clip(np.searchsorted(z, p), 1, z.size - 1)
    i = np.where(np.abs(z[i - 1] - p) <= np.abs(z[i] - p), i - 1, i)
    bad = np.abs(z[i] - p) > tol
    if bad.any():
        raise ValueError(f"z = {p[bad][0]:.9g} m is not a node of the beam model; build it "
                         "with extra_nodes holding it")
    return i
