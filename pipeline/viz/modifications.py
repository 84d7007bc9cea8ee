"""The modification map of each flank: material removed over face position x roll length.

One panel per gear (:class:`~pipeline.contact.modifications.ModificationMap`): face position
``b_z`` [mm] (the gear's own face coordinate, face 1 left) across, roll length [mm] up (tip
up), the diameter [mm] on the right-hand axis; colour and labelled contour lines = material
removed [um] (positive: removed), each panel on its own colour scale.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.contact.modifications import ModificationMap
from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

MM = 1e3
UM = 1e6


def plot_modification_maps(maps: Sequence[ModificationMap], title: str,
                           internal: Sequence[bool] = ()) -> Figure:
    """The flanks' modification maps side by side (module docstring); ``internal`` says
    which gears are internal (their tip is the small diameter: the roll-length axis is
    inverted so that every tip is up)."""
    fig = new_figure((5.2 * len(maps), 4.4), "constrained")
    axes = fig.subplots(1, len(maps), squeeze=False)[0]
    for k, (ax, m) in enumerate(zip(axes, maps, strict=True)):
        plot_modification_map(m, f"{m.role} flank (active part)", ax=ax,
                              internal=k < len(internal) and internal[k])
    fig.suptitle(title, fontsize=9)
    return fig


def plot_modification_map(m: ModificationMap, title: str, *, ax: Axes | None = None,
                          internal: bool = False, diameters: bool = True) -> Axes:
    """One flank's map on ``ax`` (a new figure when None): filled contours and labelled
    lines of the material removed [um], its own colour bar; ``diameters`` adds the
    diameter [mm] axis on the right."""
    from matplotlib.ticker import MaxNLocator  # matplotlib only to draw (pipeline.viz.canvas)

    if ax is None:
        ax = new_figure((5.2, 4.4), "constrained").subplots()
    z, roll, w = m.face * MM, m.roll * MM, m.deviation * UM
    lo, hi = float(w.min()), float(w.max())
    if hi - lo < 1e-9:  # a flat map: a band around its value
        lo, hi = lo - 0.5, hi + 0.5
    levels = MaxNLocator(nbins=24).tick_values(lo, hi)  # round numbers of um
    filled = ax.contourf(z, roll, w.T, levels=levels, cmap="viridis")
    lines = ax.contour(z, roll, w.T, levels=levels[::2], colors="k", linewidths=0.5)
    ax.clabel(lines, fontsize=7, fmt="%g")
    ax.set_xlabel(f"{m.role} face position b_z [mm]")
    ax.set_ylabel(f"{m.role} roll length [mm]")
    if internal:
        ax.invert_yaxis()
    if diameters:
        rb = m.base_radius * MM
        right = ax.secondary_yaxis(
            "right", functions=(lambda r: 2.0 * np.sqrt(np.square(r) + rb * rb),
                                lambda d: np.sqrt(np.clip(np.square(d / 2.0) - rb * rb, 0.0,
                                                          None))))
        right.set_ylabel(f"{m.role} diameter [mm]")
    ax.set_title(title, fontsize=9)
    ax.figure.colorbar(filled, ax=ax, label="material removed [um]", shrink=0.9, pad=0.02)
    return ax
