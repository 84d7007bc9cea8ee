"""The figures of the cases: a :class:`~pipeline.verification.model.Plot` drawn with
matplotlib (curves compared, or a convergence study on log-log axes)."""

from __future__ import annotations

import io
from typing import TYPE_CHECKING

from pipeline.verification.model import Plot
from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes


def plot_case(plot: Plot, ax: Axes | None = None) -> Axes:
    """Draw ``plot`` into ``ax`` (a new figure without one): every series with its label,
    the axis labels with their units, log-log for a convergence study."""
    if ax is None:
        ax = new_figure((9.0, 4.0), layout="constrained").add_subplot()
    for s in plot.series:
        ax.plot(s.x, s.y, s.style, label=s.label, markersize=4)
    if plot.loglog:
        ax.set_xscale("log")
        ax.set_yscale("log")
    ax.set_xlabel(plot.xlabel)
    ax.set_ylabel(plot.ylabel)
    ax.set_title(plot.title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if len(plot.series) > 1:  # beside the axes: never over the curves
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return ax


def png_bytes(plot: Plot, dpi: int = 110) -> bytes:
    """``plot`` as a PNG image (bytes)."""
    fig = plot_case(plot).figure
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()
