"""The layout engine of :class:`pipeline.viz.canvas.Margins` (imports matplotlib)."""

from __future__ import annotations

from matplotlib.gridspec import GridSpec
from matplotlib.layout_engine import LayoutEngine

from pipeline.viz.canvas import Margins


class FixedLayout(LayoutEngine):
    """Places a figure's grid of panels by fixed margins in inches when it is drawn.

    The figure's subplot parameters are set from :class:`Margins` and its size: the
    fractions of the figure's width and height, and ``wspace`` / ``hspace`` as fractions
    of a panel's width / height on the grid with the most columns / rows. Colour bars take
    their room from their panel's grid slot (``colorbar_gridspec``), so they keep to the
    margins too; :meth:`~matplotlib.figure.Figure.subplots_adjust` may still be called.
    """

    _adjust_compatible = True
    _colorbar_gridspec = True

    def __init__(self, margins: Margins) -> None:
        super().__init__()
        self.margins = margins

    def execute(self, fig) -> None:
        """Set ``fig``'s subplot parameters from the margins (no text is measured)."""
        m = self.margins
        width, height = fig.get_size_inches()
        grids = [ax.get_subplotspec().get_topmost_subplotspec().get_gridspec()
                 for ax in fig.axes if ax.get_subplotspec() is not None]
        rows = max((g.nrows for g in grids if isinstance(g, GridSpec)), default=1)
        cols = max((g.ncols for g in grids if isinstance(g, GridSpec)), default=1)
        inner_w = width - m.left - m.right
        inner_h = height - m.bottom - m.top
        if inner_w <= 0 or inner_h <= 0:
            raise ValueError(f"figure of {width:g} x {height:g} in: no room for the panels "
                             f"inside its margins {m}")
        panel_w = (inner_w - (cols - 1) * m.wspace) / cols
        panel_h = (inner_h - (rows - 1) * m.hspace) / rows
        fig.subplots_adjust(left=m.left / width, right=1.0 - m.right / width,
                            bottom=m.bottom / height, top=1.0 - m.top / height,
                            wspace=m.wspace / panel_w, hspace=m.hspace / panel_h)
