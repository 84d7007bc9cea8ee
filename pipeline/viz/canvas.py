"""New matplotlib figures, importing matplotlib only when a figure is drawn.

Importing matplotlib costs about 0.5 s. A rerun takes most figures from the figure cache
(:mod:`pipeline.viz.figure_cache`), which needs the drawing functions but not
matplotlib, so the viz modules import it inside their drawing functions, through
:func:`new_figure`, and name its types for annotations only.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def new_figure(figsize: tuple[float, float], layout: str | None = None) -> Figure:
    """A pyplot-free :class:`~matplotlib.figure.Figure` of ``figsize`` (inches) with the
    layout engine ``layout`` (``"constrained"``, or ``None`` for none)."""
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout=layout)
