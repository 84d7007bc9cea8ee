"""Write a figure to a PNG file atomically: matplotlib figures and pyvista plotters alike.

The plotting functions of :mod:`pipeline.viz` only draw; the caller saves. A
matplotlib :class:`~matplotlib.figure.Figure` made without pyplot needs no
backend to be saved, and nothing here selects one (``MPLBACKEND=Agg`` in
``dev.sh`` serves pyplot users on a headless machine).
"""

from __future__ import annotations

from pathlib import Path

from pipeline.io import atomic_write


def save(fig, path: str | Path, dpi: int = 130) -> Path:
    """Write ``fig`` as PNG to ``path`` atomically; returns the path.

    Parameters
    ----------
    fig : matplotlib Figure, or an Axes (its figure is saved), or an off-screen
        pyvista Plotter (its screenshot is saved and the plotter closed).
    path : PNG file to write; parent folders are created.
    dpi : resolution of matplotlib figures, dots per inch (tight bounding box: a legend
        or title wider than the figure, which constrained layout does not fit, is kept).
    """
    if hasattr(fig, "screenshot"):  # pyvista Plotter: render once, then free the window
        try:
            return atomic_write(path, lambda p: fig.screenshot(p))
        finally:
            fig.close()
    if not hasattr(fig, "savefig"):  # an Axes
        fig = fig.figure
    return atomic_write(path, lambda p: fig.savefig(p, dpi=dpi, bbox_inches="tight",
                                                     format="png"))
