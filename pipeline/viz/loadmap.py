"""Tooth-surface load map pictures: the 3D pinion and gear teeth coloured by the unit load
(pyvista) and the 2D map over face position and pinion contact radius (matplotlib), both
from 0 N/mm.

The data (:class:`~pipeline.contact.loadmap.FlankLoadMap`, the flank surface and
the VTU file) live in :mod:`pipeline.contact.loadmap`. pyvista costs seconds to
import, so it is imported only when :func:`render_load_map` runs; its plotter comes from
:func:`~pipeline.viz._offscreen.offscreen_plotter`, which renders without a display.
"""

from __future__ import annotations

import math
import textwrap
from typing import TYPE_CHECKING

import numpy as np

from pipeline.contact.loadmap import (
    FlankLoadMap,
    flank_surface,
    load_map_grid,
    mapped_members,
    tooth_body_grid,
)
from pipeline.geometry.pair import GearPair
from pipeline.viz._offscreen import offscreen_plotter
from pipeline.viz.canvas import TITLE_Y, Margins, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes


def _fit_camera(plotter, bounds, aspect: float, margin: float = 1.08) -> None:
    """Parallel projection looking at the -x side (tip up, z to the right), scaled so the
    object fills a view of width/height ``aspect``, shifted left to leave the colour bar
    room on the right."""
    x0, x1, y0, y1, z0, z1 = bounds
    centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2])
    width, height = z1 - z0, y1 - y0
    plotter.enable_parallel_projection()
    cam = plotter.camera
    half = margin * max(height / 2, width / (2 * aspect))
    centre = centre + [0.0, 0.0, 0.06 * aspect * half]  # object left of the bar
    cam.focal_point = tuple(centre)
    cam.position = tuple(centre + np.array([-10.0 * max(width, height), 0.0, 0.0]))
    cam.up = (0.0, 1.0, 0.0)
    cam.parallel_scale = half
    plotter.reset_camera_clipping_range()


def _rulers(plotter, pair: GearPair, gear, z: np.ndarray, radius: np.ndarray,
            x_shift: float) -> None:
    """Face position ticks (mm) under the tooth and the contact radii of the loaded part
    of the flank (mm) at its left end: labels pinned to points, so they face the viewer."""
    b = pair.face_width * 1e3
    y_low = gear.root_radius * 1e3 - 0.18 * gear.module * 1e3
    ticks = np.linspace(0.0, b, 6)
    pts = np.column_stack([np.full(ticks.size, x_shift), np.full(ticks.size, y_low), ticks])
    plotter.add_point_labels(pts, [f"{t:.0f}" for t in ticks], show_points=False,
                             shape=None, font_size=14, always_visible=True,
                             justification_horizontal="center")
    plotter.add_point_labels(np.array([[x_shift, y_low - 0.55 * gear.module * 1e3, b / 2]]),
                             ["face position b_z [mm]"], show_points=False, shape=None,
                             font_size=14, always_visible=True,
                             justification_horizontal="center")
    r = np.array([radius.min(), radius.max()]) * 1e3
    pts = np.column_stack([np.full(2, x_shift), r, np.full(2, -0.012 * b)])
    plotter.add_point_labels(pts, [f"r = {v:.1f} mm" for v in r], show_points=False,
                             shape=None, font_size=13, always_visible=True,
                             justification_horizontal="right",
                             justification_vertical="center")


def _tip_corner_edge(plotter, pair: GearPair, load_map: FlankLoadMap, member: str,
                     clim: tuple[float, float]) -> str:
    """Where ``member``'s tip corner touches beyond the path of contact (its flank rows
    there all lie on the tip edge, a strip of no width): a tube along the tip edge coloured
    by the corner's largest unit load over the face, on the flank's colour scale; returns
    the caption's note ("" when the corner never touches)."""
    import pyvista as pv

    load = load_map.tip_corner_load(member) * 1e-3
    if not np.any(load > 0.0):
        return ""
    gear = pair.pinion if member == "pinion" else pair.gear
    r = load_map.radius(member)
    row = int(np.argmax(r)) if not gear.internal else int(np.argmin(r))
    edge = flank_surface(pair, load_map, member)[row] * 1e3  # (n_z, 3), mm
    line = pv.lines_from_points(edge)
    line["unit_load_N_per_mm"] = load
    plotter.add_mesh(line.tube(radius=0.06 * gear.module * 1e3), scalars="unit_load_N_per_mm",
                     cmap="viridis", clim=clim, show_scalar_bar=False)
    return f"; its tip corner touches beyond the path (the tube): up to {load.max():.0f} N/mm"


def prepare_rendering() -> None:
    """Import pyvista's plotting (0.5-1 s of CPU; it imports matplotlib's pyplot too) ahead
    of :func:`render_load_map`, for a drawing process with time on its hands
    (:meth:`pipeline.viz.figure_queue.FigureQueue.prepare`)."""
    import pyvista.plotting  # noqa: F401


def render_load_map(pair: GearPair, load_map: FlankLoadMap, title: str = "",
                    window_width: int = 1400, clim: tuple[float, float] | None = None):
    """Off-screen pyvista Plotter of the unit load on the 3D pinion tooth and, for an
    external gear, the gear tooth below it (one row each), colour bar in N/mm from 0.

    Each flank is seen from outside the tooth, tip up, face position b_z from left to
    right as in :func:`plot_load_map_2d`, at true scale (parallel projection fitted to
    its row). The radii of the loaded band (start and end of contact) are marked at its
    left end. The colour scale runs from 0 to the largest unit load of the cycle (both
    flanks carry the same load at a contact point), or over ``clim`` (N/mm) when given,
    e.g. one scale for maps to be compared. Save it with
    :func:`pipeline.viz.save` (which also closes it).
    """
    members = mapped_members(pair)
    clim = clim or (0.0, float(load_map.unit_load.max()) * 1e-3)
    b = pair.face_width * 1e3
    height = max((g.tip_radius_ - g.root_radius) * 1e3 + 1.6 * g.module * 1e3
                 for g in (pair.pinion, pair.gear))
    view = 0.78  # share of the row width the tooth may take (the colour bar takes the rest)
    aspect = float(np.clip(1.1 * b / height / view, 1.6, 7.0))  # row width / height
    row_h = int(window_width / aspect)
    title_h = 30 * (title.count("\n") + 1) if title else 0  # px per line at font size 9
    caption_h = 30  # each row's caption band above its tooth
    weights = [row_h + title_h + caption_h] + [row_h + caption_h] * (len(members) - 1)
    plotter = offscreen_plotter(shape=(len(members), 1), border=False, row_weights=weights,
                                window_size=[window_width, sum(weights)])
    if not pair.pinion.is_helical:
        # a spur tooth seen from the side has every edge parallel to the window's sides, so
        # no edge shows a staircase; multisampling (pyvista's 8 samples) only blended the
        # pixel row an edge crosses, for 0.7 s of the map's 1.5-1.7 s of CPU on the demo's
        # pair (software rendering; 0.2 % of the pixels changed by more than 32 of 255)
        plotter.disable_anti_aliasing()
    try:
        for i, member in enumerate(members):
            plotter.subplot(i, 0)
            gear = pair.pinion if member == "pinion" else pair.gear
            flank = load_map_grid(pair, load_map, member)
            body = tooth_body_grid(gear, load_map.z)
            # lift the coloured flank a hair off the grey tooth so the two do not z-fight,
            # away from the tooth's centre line turned with the helix as the section is
            # (else the lift of a helical tooth points into the body at one face)
            hand = {"right": 1.0, "left": -1.0}.get(gear.hand, 0.0)
            phi = (hand * flank.points[:, 2] * 1e-3 * math.tan(gear.helix_angle)
                   / gear.reference_radius)
            rf = gear.root_radius * 1e3
            d = flank.points - np.stack([-rf * np.sin(phi), rf * np.cos(phi), 0.0 * phi],
                                        axis=1)
            d[:, 2] = 0.0
            flank.points = flank.points + 2e-3 * gear.module * 1e3 * d / np.linalg.norm(
                d, axis=1, keepdims=True)
            plotter.add_mesh(body, color="lightgrey", smooth_shading=True)
            plotter.add_mesh(flank, scalars="unit_load_N_per_mm", cmap="viridis",
                             clim=clim, show_scalar_bar=False)
            tip = _tip_corner_edge(plotter, pair, load_map, member, clim)
            _rulers(plotter, pair, gear, load_map.z, load_map.radius(member),
                    body.bounds[0] - 1.0)
            name = "" if gear.name == member else f" ({gear.name})"
            note = "; the internal gear's flank is not drawn" if pair.gear.internal else ""
            _fit_camera(plotter, (*body.bounds[:2], body.bounds[2] - 1.3 * gear.module * 1e3,
                                  *body.bounds[3:]), window_width / row_h * view)
            # keep the bands above the tooth free: the title (first row) and the caption
            cam = plotter.camera
            grow = cam.parallel_scale * (weights[i] / row_h - 1.0)
            cam.parallel_scale += grow
            cam.focal_point = tuple(np.add(cam.focal_point, [0.0, grow, 0.0]))
            cam.position = tuple(np.add(cam.position, [0.0, grow, 0.0]))
            top = weights[i] - (title_h if i == 0 else 0)
            plotter.add_text(f"{member} flank{name}, z = {gear.teeth}{note}{tip}",
                             position=(8, top - caption_h + 4), font_size=10)
            if i == 0 and title_h:
                plotter.add_text(title, position="upper_edge", font_size=9)
        plotter.subplot(0, 0)
        plotter.add_scalar_bar(title="unit load p [N/mm]\n", vertical=True, n_labels=6,
                                     fmt="%.0f", position_x=0.85, position_y=0.06,
                                     width=0.06, height=0.62 * row_h / weights[0] + 0.2,
                                     title_font_size=14, label_font_size=12)
    except BaseException:
        plotter.close()
        raise
    return plotter


def load_map_title(title: str, modifications: str) -> str:
    """Title of the load maps: ``title``, then what the map shows and the modifications
    (wrapped at 120 characters: each gear's modifications can be a long list)."""
    return "\n".join([title, *textwrap.wrap(
        f"unit load, envelope over the mesh cycle; modifications: {modifications}", 120)])


def plot_load_map_2d(load_map: FlankLoadMap, title: str = "", ax: Axes | None = None) -> Axes:
    """Map of the unit load (N/mm, colour scale from 0) over the pinion flank: face position
    b_z (mm) to the right, pinion contact radius (mm) up, as :func:`render_load_map` shows the
    flank; returns the Axes."""
    if ax is None:
        # the colour bar takes its room from the panel, its label the right margin; the
        # title 0.16 in a line (font size 9)
        lines = (title or "x").count("\n") + 1
        ax = new_figure((7.5, 4.8), Margins(right=0.8, top=0.2 + 0.16 * lines)).subplots()
    p = load_map.unit_load * 1e-3
    flank = load_map.s <= load_map.s_end  # past it the pinion touches with its tip corner
    vmax = float(p.max())
    mesh = ax.pcolormesh(load_map.z * 1e3, load_map.pinion_radius[flank] * 1e3, p[flank],
                         shading="gouraud", cmap="viridis", vmin=0.0, vmax=vmax)
    ax.figure.colorbar(mesh, ax=ax, label="unit load p [N/mm]")
    tip = load_map.tip_corner_load("pinion") * 1e-3
    if tip.max() > 0.0:
        r = load_map.pinion_radius[flank]
        ra, h = float(load_map.pinion_radius.max()) * 1e3, 0.04 * float(np.ptp(r)) * 1e3
        ax.pcolormesh(load_map.z * 1e3, [ra, ra + h], np.vstack([tip, tip]),
                      shading="gouraud", cmap="viridis", vmin=0.0, vmax=vmax)
        ax.axhline(ra, color="w", lw=0.8)
        ax.text(0.01, ra + h, f"tip corner, beyond the path of contact: up to "
                f"{tip.max():.0f} N/mm", transform=ax.get_yaxis_transform(), va="bottom",
                fontsize=8)
        ax.set_ylim(top=ra + 3.0 * h)
    if load_map.s[0] < load_map.s_start:  # the gear's tip corner on the pinion's flank
        r0 = float(np.interp(load_map.s_start, load_map.s, load_map.pinion_radius)) * 1e3
        ax.axhline(r0, color="w", lw=0.8, ls="--")
        ax.text(0.01, r0, "start of the path of contact; below it the gear's tip corner "
                "touches", transform=ax.get_yaxis_transform(), va="bottom", fontsize=8,
                color="w")
    ax.set_xlabel("face position b_z [mm]")
    ax.set_ylabel("pinion contact radius [mm]")
    ax.set_title(title or "unit load over the pinion flank, envelope over the mesh cycle",
                 fontsize=9, y=TITLE_Y)
    return ax
