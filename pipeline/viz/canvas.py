"""New matplotlib figures, importing matplotlib only when a figure is drawn.

Importing matplotlib costs about 0.5 s. A rerun takes most figures from the figure cache
(:mod:`pipeline.viz.figure_cache`), which needs the drawing functions but not
matplotlib, so the viz modules import it inside their drawing functions, through
:func:`new_figure`, and name its types for annotations only.

A figure is laid out by matplotlib's constrained layout, or by fixed :class:`Margins` in
inches given per figure kind. Constrained layout measures every axis's tick labels twice
before the figure is drawn (which measures them once more); on the 21 matplotlib figures of
the demo run it was a third of their drawing time (3.9 of 11.6 s under cProfile, one
process). Fixed margins cost nothing; they may be generous, since
:func:`pipeline.viz.saving.save` cuts the picture to what is drawn, and a figure whose
labels outgrow them is not cut: ``save`` finds its drawing at the canvas's edge and leaves
it to ``savefig(bbox_inches="tight")``, which grows the canvas. Only the space between
panels (``wspace``, ``hspace``) must be right for the figure's kind. With the cut to the
drawn pixels and drawing processes without the cyclic garbage collector, the demo run's
21 matplotlib figures took 2.9-3.3 s of CPU against 5.1-5.8 s with constrained layout and
the second layout pass for the tight box (one process, four runs each alternating, 2-core
machine at load 6-9).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.figure import Figure


TITLE_Y = 1.0
"""Height of a panel's title, in units of the panel's height: on its frame, where matplotlib
puts the title of a panel with nothing drawn above its frame. Given to ``set_title(y=...)``
by the figures whose panels have no axis on top, it spares matplotlib's check of that (it
measures every titled panel's y axis again when the figure is drawn): 0.15-0.25 s of CPU
on the demo run's 21 figures (one process), which came out the same byte for byte."""


@dataclass(frozen=True)
class Margins:
    """A fixed layout: the space round and between a figure's grid of panels, in inches.

    Attributes
    ----------
    left, right, bottom, top : in from the figure's edges to the panels' frames (in).
    wspace, hspace : between two columns / two rows of panels (in).
    """

    left: float = 0.85
    right: float = 0.2
    bottom: float = 0.6
    top: float = 0.4
    wspace: float = 0.9
    hspace: float = 0.9

    def __post_init__(self) -> None:
        for name in ("left", "right", "bottom", "top", "wspace", "hspace"):
            if not getattr(self, name) >= 0.0:
                raise ValueError(f"Margins.{name}: {getattr(self, name)} in; at least 0")


def new_figure(figsize: tuple[float, float], layout: str | Margins | None = None) -> Figure:
    """A pyplot-free :class:`~matplotlib.figure.Figure` of ``figsize`` (inches) laid out by
    ``layout``: ``"constrained"``, fixed :class:`Margins`, or ``None`` for matplotlib's
    default subplot parameters."""
    from matplotlib.figure import Figure

    if isinstance(layout, Margins):
        from pipeline.viz._layout import FixedLayout

        return Figure(figsize=figsize, layout=FixedLayout(layout))
    return Figure(figsize=figsize, layout=layout)


def panels_with_colorbar(fig: Figure, n: int = 2, bar_width: float = 0.045
                         ) -> tuple[list, object]:
    """``n`` panels side by side sharing their y axis (its tick labels on the first only) and
    a narrow axes on their right for one colour bar (``bar_width`` of a panel's width):
    ``(panels, bar axes)``. A grid slot of its own keeps the bar inside fixed
    :class:`Margins` (``fig.colorbar(ax=panels)`` would take the room from the panels'
    frames, which the layout then puts back)."""
    grid = fig.add_gridspec(1, n + 1, width_ratios=(*([1.0] * n), bar_width))
    first = fig.add_subplot(grid[0])
    panels = [first] + [fig.add_subplot(grid[i], sharey=first) for i in range(1, n)]
    for ax in panels[1:]:
        ax.tick_params(labelleft=False)
    return panels, fig.add_subplot(grid[n])


__all__ = ["TITLE_Y", "Margins", "new_figure", "panels_with_colorbar"]
