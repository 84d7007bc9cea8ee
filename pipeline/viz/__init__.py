"""Figures of every stage: each function draws, the caller saves with :func:`save`.

Matplotlib functions take ``ax=None`` (or ``fig=None`` when they draw several
panels) and return the Axes (or Figure); without one they draw into a new
:class:`matplotlib.figure.Figure`, which needs no pyplot and no backend. pyvista
renders return an off-screen Plotter (pyvista is imported inside them: it costs
seconds) that needs no display and makes VTK no warnings without one
(:mod:`._offscreen`). Nothing here calls ``matplotlib.use``.

- :mod:`.geometry` - line of action, contact lines, tooth profile.
- :mod:`.stiffness` - mesh stiffness curves, friction coefficients.
- :mod:`.fem` - 2D sector mesh, deformed sector, tooth compliance.
- :mod:`.contact` - loaded contact over a mesh cycle.
- :mod:`.loadmap` - tooth-surface load map (3D pyvista, 2D matplotlib).
- :mod:`.groove` - twisted herringbone sun body (pyvista).
- :mod:`.dynamics` - time histories, spectra, harmonic contributions, sweeps, mode shapes.
- :mod:`.saving` - :func:`save`, atomic PNG of a figure or a plotter.
"""

from pipeline.viz.saving import save

__all__ = ["save"]
