"""The closed-form shapes of flank modifications, as functions of one coordinate.

Every shape returns the material removed (m, positive) at a distance ``x`` (m) *into*
the modified zone, measured from where the modification starts (``x <= 0``: outside,
nothing removed), for an amount ``C`` (m) reached at ``x = L`` (m):

* ``"linear"``: ``C x / L``;
* ``"parabolic"``: ``C (x / L)^2`` (tangent to the unmodified flank at its start);
* ``"arc"``: a circular arc tangent to the unmodified flank at its start and through
  ``(L, C)``: radius ``R = (L^2 + C^2) / (2 C)``, deviation ``R - sqrt(R^2 - x^2)``,
  evaluated as ``x^2 / (R + sqrt(R^2 - x^2))`` (the same number without the cancellation
  of two nearly equal radii); ``x`` is held at ``L`` beyond it.

The unit of ``x`` is a roll length along the path of contact for profile modifications
(tip and root relief) and a face position for lead modifications (end relief); the
shapes do not care. Crowning and slope are centred on the middle of their range
``[0, L]``: crowning ``C (2 x / L - 1)^2`` (``C`` at both ends, 0 in the middle), slope
``f (x / L - 1/2)`` (``+f/2`` at ``x = L``, ``-f/2`` at ``x = 0``).
"""

from __future__ import annotations

import numpy as np

RELIEF_SHAPES = ("linear", "parabolic", "arc")
"""Shapes of a tip or root relief."""
END_RELIEF_SHAPES = ("linear", "parabolic")
"""Shapes of an end relief."""


def relief(x: np.ndarray, amount: float, length: float, shape: str) -> np.ndarray:
    """Material removed (m) at a distance ``x`` (m) into a relief of ``amount`` C (m) over
    ``length`` L (m) of the given ``shape`` (module docstring); zeros when ``amount`` is 0."""
    x = np.asarray(x, dtype=float)
    if amount == 0.0:
        return np.zeros_like(x)
    if shape == "arc":
        radius = (length * length + amount * amount) / (2.0 * amount)
        xc = np.clip(x, 0.0, length)
        return xc * xc / (radius + np.sqrt(radius * radius - xc * xc))
    power = 1 if shape == "linear" else 2
    return amount * np.clip(x / length, 0.0, None) ** power


def crowning(x: np.ndarray, amount: float, length: float) -> np.ndarray:
    """``C (2 x / L - 1)^2`` (m): ``amount`` C at both ends of ``[0, L]``, 0 in the middle."""
    return amount * (2.0 * np.asarray(x, dtype=float) / length - 1.0) ** 2


def slope(x: np.ndarray, amount: float, length: float) -> np.ndarray:
    """``f (x / L - 1/2)`` (m): ``amount`` f from ``x = 0`` to ``x = L``, 0 in the middle."""
    return amount * (np.asarray(x, dtype=float) / length - 0.5)
