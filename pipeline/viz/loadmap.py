"""Tooth-surface load map pictures: the 3D pinion tooth coloured by the unit load (pyvista)
and the 2D map over the plane of action (matplotlib).

The data (:class:`~pipeline.contact.loadmap.FlankLoadMap`, the flank surface and
the VTU file) live in :mod:`pipeline.contact.loadmap`. pyvista costs seconds to
import, so it is imported inside :func:`render_load_map` only.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from pipeline.contact.loadmap import FlankLoadMap, load_map_grid, tooth_body_grid
from pipeline.geometry.pair import GearPair


def render_load_map(pair: GearPair, load_map: FlankLoadMap, title: str = "",
                    window_size: tuple[int, int] = (1000, 800),
                    clim: tuple[float, float] | None = None,
                    view: tuple[float, float, float] = (1.0, 0.25, 0.6)):
    """Off-screen pyvista Plotter of the unit load on the 3D pinion tooth, colour bar in N/mm.

    ``clim`` fixes the colour range (N/mm), e.g. one scale for maps to be compared;
    ``view`` is the direction from the tooth to the camera (x, y, z).
    Save it with :func:`pipeline.viz.save` (which also closes it).
    """
    import pyvista as pv

    flank = load_map_grid(pair, load_map)
    gear = pair.pinion
    body = tooth_body_grid(gear, load_map.z)
    # lift the coloured flank a hair off the grey tooth so the two do not z-fight, away from
    # the tooth's centre line turned with the helix as the section is (else the lift of a
    # right-hand tooth points into the body at one face and the flank disappears there)
    hand = {"right": 1.0, "left": -1.0}.get(gear.hand, 0.0)
    phi = hand * flank.points[:, 2] * 1e-3 * math.tan(gear.helix_angle) / gear.reference_radius
    rf = gear.root_radius * 1e3
    d = flank.points - np.stack([-rf * np.sin(phi), rf * np.cos(phi), 0.0 * phi], axis=1)
    d[:, 2] = 0.0
    flank.points = flank.points + 2e-3 * gear.module * 1e3 * d / np.linalg.norm(
        d, axis=1, keepdims=True)
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    try:
        plotter.add_mesh(body, color="lightgrey", smooth_shading=True)
        plotter.add_mesh(flank, scalars="unit_load_N_per_mm", cmap="viridis", clim=clim,
                         scalar_bar_args={"title": "", "vertical": False,
                                          "position_x": 0.25, "position_y": 0.07,
                                          "width": 0.5, "height": 0.07, "fmt": "%.0f"})
        # the bar's own title collides with its labels above it: its unit goes below
        plotter.add_text("unit load p [N/mm]", position=(int(0.41 * window_size[0]), 12),
                         font_size=11)
        # x spans only the tooth thickness and is seen end-on: its title, no crowded labels
        plotter.show_bounds(xtitle="x", ytitle="y [mm]", ztitle="face z [mm]",
                            location="outer", grid=False, show_xlabels=False, n_ylabels=3,
                            fmt="%.0f")
        if title:
            plotter.add_text(title, font_size=10)
        plotter.view_vector(view, viewup=(0.0, 1.0, 0.0))
    except BaseException:
        plotter.close()
        raise
    return plotter


def plot_load_map_2d(load_map: FlankLoadMap, title: str = "", ax: Axes | None = None) -> Axes:
    """Map of the unit load over the plane of action (N/mm); returns the Axes."""
    if ax is None:
        ax = Figure(figsize=(7, 4.5)).subplots()
    mesh = ax.pcolormesh(load_map.z * 1e3, load_map.pinion_radius * 1e3,
                         load_map.unit_load * 1e-3, shading="gouraud", cmap="viridis")
    ax.figure.colorbar(mesh, ax=ax, label="unit load p [N/mm]")
    ax.set_xlabel("face position z [mm]")
    ax.set_ylabel("pinion contact radius [mm]")
    ax.set_title(title or "unit load over the pinion flank (one mesh cycle)")
    return ax
