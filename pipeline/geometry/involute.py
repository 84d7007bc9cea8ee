"""Involute function and its inverse (angles in rad)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike


def inv(alpha: ArrayLike) -> np.ndarray:
    """Involute function ``tan(alpha) - alpha``."""
    a = np.asarray(alpha, dtype=float)
    return np.tan(a) - a


def inv_inverse(value: ArrayLike, tol: float = 1e-15) -> np.ndarray:
    """Solve ``inv(alpha) = value`` for ``alpha`` in [0, pi/2) (Newton, vectorised).

    Starts from Cheng's approximation ``alpha ~ (3 v)^(1/3)`` and converges to
    machine precision in a handful of steps for ``0 <= v < 10``.
    """
    v = np.asarray(value, dtype=float)
    if np.any(v < 0):
        raise ValueError("inv_inverse: involute function values must be >= 0")
    a = np.cbrt(3.0 * v) / (1.0 + 0.2 * np.cbrt(3.0 * v) ** 2)
    a = np.where(v > 1.0, np.arctan(v + 1.0), a)
    for _ in range(60):
        t = np.tan(a)
        f = t - a - v
        step = f / (t * t)  # d(inv)/da = tan^2
        step = np.where(t == 0.0, 0.0, step)
        a = np.clip(a - step, 0.0, np.pi / 2 - 1e-12)
        if np.all(np.abs(f) <= tol * np.maximum(1.0, v)):
            break
    return a
