"""Mesh stiffness figures: stiffness curves over a mesh cycle, friction coefficients.

Axes are labelled with units; every function draws into ``ax`` (or ``fig``) when
given one, otherwise into a new :class:`~matplotlib.figure.Figure`, and returns it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.viz.canvas import Margins, new_figure
from pipeline.viz.units import stiffness_in_plot_unit, stiffness_label

_PER_M_TO_PER_UM = 1e-6  # N m/m (a torque per metre of mesh deflection) -> N m/um

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


def plot_stiffness_curves(
    curves: Sequence[tuple[str, np.ndarray, np.ndarray]],
    xlabel: str = "pinion rotation over one mesh cycle [deg]",
    title: str = "",
    pairs: np.ndarray | None = None,
    pairs_x: np.ndarray | None = None,
    ax: Axes | None = None,
) -> Axes:
    """Overlay stiffness curves ``(label, x, k [N/m])``; optional per-pair curves of the first."""
    if ax is None:
        ax = new_figure((8, 4.2)).subplots()
    for i, (label, x, k) in enumerate(curves):
        ax.plot(x, stiffness_in_plot_unit(k), lw=1.6, color=f"C{i}", label=label)
    if pairs is not None and pairs_x is not None:
        for j in range(pairs.shape[1]):
            kj = np.where(pairs[:, j] > 0, pairs[:, j], np.nan)
            if np.any(np.isfinite(kj)):
                ax.plot(pairs_x, stiffness_in_plot_unit(kj), lw=0.8, ls=":", color="0.35",
                        label="single tooth pairs" if j == 0 else None)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(stiffness_label())
    ax.grid(alpha=0.3)
    ax.set_title(title)
    ax.legend(fontsize=8)
    return ax


def plot_friction_coefficients(x: np.ndarray, kf: np.ndarray, kt1: np.ndarray, kt2: np.ndarray,
                               title: str = "", fig: Figure | None = None) -> Figure:
    """Friction stiffness K_f (N/m in, N/um drawn) and friction torque coefficients KT_f1,
    KT_f2 of the pinion and the gear (N m/m in, N m/um drawn: the friction torque on each
    gear per unit mesh deflection, :mod:`pipeline.stiffness.friction`) over a mesh cycle."""
    if fig is None:
        fig = new_figure((10, 3.8), Margins(top=0.5, wspace=1.15))  # a two-line y label
    a1, a2 = fig.subplots(1, 2)
    a1.plot(x, stiffness_in_plot_unit(kf))
    a1.set_ylabel(stiffness_label("friction stiffness K_f"))
    a2.plot(x, kt1 * _PER_M_TO_PER_UM, label="pinion, KT_f1")
    a2.plot(x, kt2 * _PER_M_TO_PER_UM, label="gear, KT_f2")
    a2.set_ylabel("friction torque coefficient KT_f\n(torque per mesh deflection) [N m/um]")
    a2.legend(fontsize=8)
    for a in (a1, a2):
        a.set_xlabel("pinion rotation over one mesh cycle [deg]")
        a.grid(alpha=0.3)
    fig.suptitle(title)
    return fig
