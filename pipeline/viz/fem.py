"""2D FE figures: the sector mesh, a deformed sector coloured by |u|, tooth compliance.

Axes in mm. Every function draws into ``ax`` when given one, otherwise into a
new :class:`~matplotlib.figure.Figure`, and returns the Axes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from pipeline.fem.sector2d import SectorMesh2D


def plot_sector_mesh(sector: SectorMesh2D, title: str, ax: Axes | None = None) -> Axes:
    """Triangle mesh (vertices only) with the flank groups highlighted; axes in mm."""
    if ax is None:
        ax = new_figure((7, 7)).subplots()
    m = sector.mesh
    ax.triplot(m.p[0] * 1e3, m.p[1] * 1e3, m.t[:3].T, lw=0.2, color="0.4")
    for name, idx in sector.facets.items():
        e = m.facets[:, idx]
        colour = "C3" if name.startswith("right") else "C0" if name.startswith("left") else "C2"
        for a, b in e.T:
            ax.plot(m.p[0, [a, b]] * 1e3, m.p[1, [a, b]] * 1e3, color=colour, lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(title)
    return ax


def plot_deformed(sector: SectorMesh2D, displacement: np.ndarray, scale: float, title: str,
                  ax: Axes | None = None) -> Axes:
    """Deformed sector (displacement ``scale``-times magnified), colour = |u| in um.

    ``displacement`` is the (2 n_nodes,) interleaved nodal vector (m) of a P2 vector basis.
    """
    if ax is None:
        ax = new_figure((7, 7)).subplots()
    m = sector.mesh
    nv = m.p.shape[1]
    u = displacement.reshape(-1, 2)[:nv].T
    xy = (m.p + scale * u) * 1e3
    from matplotlib.tri import Triangulation

    tri = Triangulation(xy[0], xy[1], m.t[:3].T)
    pc = ax.tripcolor(tri, np.hypot(*u) * 1e6, shading="gouraud", cmap="viridis")
    ax.triplot(m.p[0] * 1e3, m.p[1] * 1e3, m.t[:3].T, lw=0.1, color="0.8")
    ax.figure.colorbar(pc, ax=ax, label="|u| [um]")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"{title} (deformation x{scale:.3g})")
    return ax


def plot_compliance(radius: np.ndarray, curves: list[tuple[str, np.ndarray]], title: str,
                    ax: Axes | None = None) -> Axes:
    """Single-tooth compliance (m^2/N -> um/(N/mm)) against the contact radius (mm)."""
    if ax is None:
        ax = new_figure((7, 4.5)).subplots()
    for label, c in curves:
        ax.plot(radius * 1e3, c * 1e9, label=label)
    ax.set_xlabel("contact radius [mm]")
    ax.set_ylabel("compliance per unit face width [um/(N/mm)]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend()
    return ax
