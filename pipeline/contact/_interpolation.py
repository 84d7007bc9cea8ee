"""Linear interpolation weights shared by the FE compliance sources' tables."""

from __future__ import annotations

import numpy as np


def linear_weights(nodes: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Left node index and weight of the right node for linear interpolation (linear
    extrapolation beyond the ends) of ``x`` on ascending ``nodes``."""
    x = np.asarray(x, dtype=float)
    if nodes.size == 1:
        return np.zeros(x.shape, dtype=int), np.zeros(x.shape)
    k = np.clip(np.searchsorted(nodes, x) - 1, 0, nodes.size - 2)
    return k, (x - nodes[k]) / (nodes[k + 1] - nodes[k])
