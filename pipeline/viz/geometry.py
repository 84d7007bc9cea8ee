"""Pair geometry figures: line of action, contact lines, tooth profile (axes in mm).

Every function draws into ``ax`` when given one, otherwise into a new
:class:`~matplotlib.figure.Figure`, and returns the Axes.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.geometry.profile import INVOLUTE, ToothProfile, gear_outline
from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


def plot_line_of_action(pair: GearPair, title: str = "", ax: Axes | None = None) -> Axes:
    """Path of contact on the line of action: single/double contact zones and the pitch point."""
    if ax is None:
        ax = new_figure((8, 2.8)).subplots()
    pb = pair.base_pitch
    s_a, s_e, s_c = pair.s_start * 1e3, pair.s_end * 1e3, pair.s_pitch * 1e3
    ax.plot([0, pair.t1t2 * 1e3], [0, 0], color="0.6", lw=1, label="line of action T1-T2")
    ax.plot([s_a, s_e], [0, 0], color="C0", lw=6, solid_capstyle="butt", label="path of contact")
    # zones: double contact near both ends (length (eps-1) p_b each)
    n = math.floor(pair.transverse_contact_ratio)
    extra = pair.path_length - n * pb
    ax.axvspan(s_a, s_a + extra * 1e3, color="C1", alpha=0.25, label=f"{n + 1} pairs in contact")
    ax.axvspan(s_e - extra * 1e3, s_e, color="C1", alpha=0.25)
    ax.axvline(s_c, color="k", ls="--", lw=1, label="pitch point")
    for x, lab in ((0, "T1"), (pair.t1t2 * 1e3, "T2"), (s_a, "A"), (s_e, "E")):
        ax.annotate(lab, (x, 0), xytext=(0, 10), textcoords="offset points", ha="center")
    ax.set_xlabel("roll coordinate s along the line of action [mm]")
    ax.set_yticks([])
    ax.set_title(title or f"eps_alpha = {pair.transverse_contact_ratio:.3f}, "
                 f"eps_beta = {pair.overlap_ratio:.3f}, "
                 f"alpha_wt = {math.degrees(pair.operating_pressure_angle):.3f} deg")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.35), ncol=4, fontsize=8)
    return ax


def plot_contact_lines(pair: GearPair, n_positions: int = 4, ax: Axes | None = None) -> Axes:
    """Contact lines on the plane of action at a few positions over one mesh cycle.

    Axes in mm at equal scale (the plane of action as it is); the legend sits outside
    the plane, to the right, so it never covers a line.
    """
    if ax is None:
        length, b = pair.path_length, pair.face_width
        height = min(8.0, max(2.5, 5.5 * b / length))
        ax = new_figure((8.0, height + 1.2), "constrained").subplots()
    from matplotlib.patches import Rectangle

    b = pair.face_width * 1e3
    ax.add_patch(Rectangle((pair.s_start * 1e3, 0), pair.path_length * 1e3, b, fill=False,
                           ec="k", lw=1, label="path of contact x face width"))
    for i, s0 in enumerate(pair.mesh_cycle(n_positions)):
        for j, seg in enumerate(pair.contact_lines(float(s0))):
            ax.plot(seg[:, 0] * 1e3, seg[:, 1] * 1e3, color=f"C{i}", lw=2,
                    label=f"t = {i}/{n_positions} T_m" if j == 0 else None)
    ax.axvline(pair.s_pitch * 1e3, color="k", ls="--", lw=1, label="pitch point")
    ax.set_aspect("equal")
    ax.set_xlabel("roll coordinate s [mm]")
    ax.set_ylabel("face width position z [mm]")
    ax.set_title("Contact lines on the plane of action")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    return ax


def plot_profile(prof: ToothProfile, ax: Axes | None = None, teeth: int = 3) -> Axes:
    """Draw ``teeth`` teeth around +y (mm), the middle flank coloured by segment, and the circles.

    Circles: root (dashed), base (dotted), form (dash-dot), tip (thin).
    """
    if ax is None:
        ax = new_figure((5, 5)).subplots()
    g = prof.gear
    out = gear_outline(g, teeth) * 1e3
    ax.plot(out[:, 0], out[:, 1], color="0.3", lw=1.0, label="outline")
    inv = prof.kind == INVOLUTE
    ax.plot(prof.x[~inv] * 1e3, prof.y[~inv] * 1e3, "-", color="tab:red", lw=2.2, label="fillet")
    ax.plot(prof.x[inv] * 1e3, prof.y[inv] * 1e3, "-", color="tab:green", lw=2.2,
            label="involute")
    span = np.linspace(*np.arctan2(out[[-1, 0], 0], out[[-1, 0], 1]), 200)
    for r, style, name in ((g.root_radius, "--", "root"), (g.base_radius, ":", "base"),
                           (prof.form_radius, "-.", "form"), (g.tip_radius_, "-", "tip")):
        ax.plot(r * 1e3 * np.sin(span), r * 1e3 * np.cos(span), style, color="tab:blue",
                lw=0.6, label=f"{name} circle")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return ax


def plot_profiles(gears: tuple[GearSpec, ...], profiles: tuple[ToothProfile, ...]) -> Figure:
    """The tooth profiles of several gears (:func:`plot_profile`), one panel each, stacked."""
    fig = new_figure((9, 4 * len(gears)))
    axes = np.atleast_1d(fig.subplots(len(gears), 1))
    for ax, g, prof in zip(axes, gears, profiles, strict=True):
        plot_profile(prof, ax=ax)
        ax.set_title(f"{g.name}: z = {g.teeth}, undercut = {prof.undercut}")
    return fig
