"""Peak of a sampled response curve, refined between the grid points."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.validation import InputError


@dataclass(frozen=True)
class Peak:
    """Largest value of a sampled curve in a window.

    Attributes
    ----------
    frequency : vertex of the parabola through the largest sample and its two
        neighbours, Hz (the grid value if the largest sample is at the window edge).
    value : the parabola's value there (same unit as the curve).
    grid_frequency : frequency of the largest sample, Hz.
    at_edge : the largest sample is the first or last one in the window (the true
        peak may lie outside).
    """

    frequency: float
    value: float
    grid_frequency: float
    at_edge: bool


def refined_peak(
    frequencies: np.ndarray, values: np.ndarray, lo: float = -np.inf, hi: float = np.inf
) -> Peak:
    """Peak of ``values`` over ``frequencies`` in ``[lo, hi]``, refined by a parabola.

    The three-point parabola recovers the vertex of a smooth peak to O(h^3) on a
    uniform grid of step h; on a resonance wider than a few grid steps it resolves
    shifts far below h.

    Parameters
    ----------
    frequencies : shape (F,), increasing, Hz.
    values : shape (F,), the curve (e.g. RMS mesh force, N).
    lo, hi : window, Hz.
    """
    f = np.asarray(frequencies, dtype=float)
    y = np.asarray(values, dtype=float)
    if f.ndim != 1 or f.shape != y.shape:
        raise InputError(f"frequencies {f.shape} and values {y.shape} must be equal 1-D shapes")
    idx = np.flatnonzero((f >= lo) & (f <= hi))
    if idx.size == 0:
        raise InputError(f"no frequencies in the window [{lo:.6g}, {hi:.6g}] Hz")
    i = idx[np.argmax(y[idx])]
    if i == idx[0] or i == idx[-1]:
        return Peak(float(f[i]), float(y[i]), float(f[i]), True)
    x0, x1, x2 = f[i - 1 : i + 2]
    y0, y1, y2 = y[i - 1 : i + 2]
    a, b, c = np.polyfit([x0 - x1, 0.0, x2 - x1], [y0, y1, y2], 2)
    if a >= 0:  # flat top: no curvature to refine with
        return Peak(float(x1), float(y1), float(x1), False)
    return Peak(float(x1 - b / (2 * a)), float(c - b * b / (4 * a)), float(x1), False)
