"""Pair geometry figures: line of action, contact lines, tooth profile (axes in mm).

The one-panel functions draw into ``ax`` when given one, otherwise into a new
:class:`~matplotlib.figure.Figure`, and return the Axes; the several-panel ones
(:func:`plot_line_of_action`, :func:`plot_profiles`) return the Figure. Geometry is drawn
at equal scale.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.geometry.profile import (
    FILLET,
    INVOLUTE,
    TIP_ROUNDING,
    ToothProfile,
    gear_outline,
)
from pipeline.geometry.transverse import TransverseLayout
from pipeline.viz.canvas import TITLE_Y, Margins, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


def plot_line_of_action(pair: GearPair, title: str = "", fig: Figure | None = None,
                        name: str = "") -> Figure:
    """The pair in its transverse plane and its path of contact on the line of action.

    Three panels, lengths in mm: the whole pair at equal scale (centres O1, O2, base, pitch
    and tip circles, the line of action tangent to both base circles at T1 and T2); the
    same at equal scale near the line of action, with the named points T1, T2, A, B, C, D,
    E (:class:`~pipeline.geometry.transverse.TransverseLayout`); and the roll coordinate
    s along the line of action with the zones of one and two tooth pairs in contact. For
    an internal pair T2 lies behind T1 (``s = -T1T2``), on the same side of the pitch
    point.
    """
    if fig is None:
        fig = new_figure((12.0, 8.5), "constrained")
    lay = TransverseLayout(pair)
    top, strip = fig.subfigures(2, 1, height_ratios=(2.6, 1.0))
    whole, near = top.subplots(1, 2, width_ratios=(1.0, 1.5))
    _draw_transverse(whole, lay)
    _name_centres(whole, lay)
    whole.set_title("whole pair, to scale", fontsize=9)
    _draw_transverse(near, lay)
    _name_points(near, lay)
    _zoom_to_line(near, lay)
    near.set_title("near the line of action, to scale", fontsize=9)
    handles, names = whole.get_legend_handles_labels()
    top.legend(handles, names, loc="outside lower center", ncol=4, fontsize=8)
    _draw_roll_strip(strip.subplots(), lay)
    handles, names = strip.axes[0].get_legend_handles_labels()
    strip.legend(handles, names, loc="outside lower center", ncol=4, fontsize=8)
    kind = "internal" if pair.gear.internal else "external"
    title = title or (f"{kind} pair: eps_alpha = {pair.transverse_contact_ratio:.3f}, "
                      f"eps_beta = {pair.overlap_ratio:.3f}, "
                      f"alpha_wt = {math.degrees(pair.operating_pressure_angle):.3f} deg, "
                      f"a_w = {pair.operating_centre_distance * 1e3:.3f} mm")
    fig.suptitle(f"{name}: {title}" if name else title)  # name: the case or mesh
    return fig


def _line_span(lay: TransverseLayout) -> tuple[float, float]:
    """Roll coordinates (m) from the first to the last of T1, T2, A, E, with a margin."""
    s = list(lay.rolls.values())
    lo, hi = min(s), max(s)
    pad = 0.08 * (hi - lo)
    return lo - pad, hi + pad


def _draw_transverse(ax: Axes, lay: TransverseLayout) -> None:
    """Centres, circles, radii to T1 and T2, the line of action and the path of contact (mm),
    equal axes."""
    pair = lay.pair
    mm = 1e3
    t = np.linspace(0.0, 2.0 * math.pi, 721)
    circle = np.column_stack([np.cos(t), np.sin(t)])
    r_w1, r_w2 = pair.operating_pitch_radii
    for i, (g, o, r_w) in enumerate(((pair.pinion, lay.pinion_centre, r_w1),
                                     (pair.gear, lay.gear_centre, r_w2))):
        for r, style, lw, what in ((g.base_radius, ":", 1.0, "base circle"),
                                   (r_w, "--", 0.8, "operating pitch circle"),
                                   (g.tip_radius_, "-", 0.6, "tip circle")):
            xy = (o + r * circle) * mm
            ax.plot(xy[:, 0], xy[:, 1], style, color=f"C{i}", lw=lw,
                    label=f"{'pinion' if i == 0 else 'gear'} {what}")
        ax.plot(*(o * mm), "+", color=f"C{i}", ms=9, mew=1.5)
    for o, t_pt in ((lay.pinion_centre, lay.t1), (lay.gear_centre, lay.points["T2"])):
        ax.plot([o[0] * mm, t_pt[0] * mm], [o[1] * mm, t_pt[1] * mm], color="0.5", lw=0.7)
    ends = lay.point(np.array(_line_span(lay))) * mm
    ax.plot(ends[:, 0], ends[:, 1], color="k", lw=0.9, label="line of action")
    path = lay.point(np.array([pair.s_start, pair.s_end])) * mm
    ax.plot(path[:, 0], path[:, 1], color="C2", lw=3.5, solid_capstyle="butt",
            label="path of contact A-E")
    c = lay.points["C"] * mm
    ax.plot(c[0], c[1], "o", color="k", ms=4, label="pitch point C")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y along the centre line [mm]")
    ax.grid(alpha=0.2)


def _label_offsets(n: int) -> list[tuple[float, float]]:
    """(side, distance in points) of ``n`` labels in the order of their points along a line:
    alternately on either side and, every second pair, further out, so that close
    neighbours (B, C, D can lie within 1 mm) do not print over each other."""
    return [((1.0, -1.0)[k % 2], (10.0, 10.0, 24.0, 24.0)[k % 4]) for k in range(n)]


def _name_points(ax: Axes, lay: TransverseLayout) -> None:
    """Dots and letters at T1, T2, A..E (alternately on either side of the line) and the
    centres O1, O2."""
    mm = 1e3
    u = lay.direction
    normal = np.array([-u[1], u[0]])
    named = sorted(lay.rolls.items(), key=lambda kv: kv[1])
    for (name, s), (side, dist) in zip(named, _label_offsets(len(named)), strict=True):
        xy = lay.point(s) * mm
        ax.plot(*xy, "o", color="k", ms=3)
        ax.annotate(name, xy, xytext=tuple(side * dist * normal), textcoords="offset points",
                    ha="center", va="center", fontsize=9)
    _name_centres(ax, lay)


def _name_centres(ax: Axes, lay: TransverseLayout) -> None:
    for name, o, i in (("O1", lay.pinion_centre, 0), ("O2", lay.gear_centre, 1)):
        ax.annotate(name, o * 1e3, xytext=(6, 6), textcoords="offset points", color=f"C{i}",
                    fontsize=9, annotation_clip=True)


def _zoom_to_line(ax: Axes, lay: TransverseLayout, height_ratio: float = 0.7) -> None:
    """Equal-scale limits around T1, T2 and the path of contact (mm): a margin of a quarter
    of its length, then the shorter side widened to ``height_ratio`` (height / width), so
    the axes box, shrunk to equal scale, nearly fills its panel."""
    xy = lay.point(np.array(_line_span(lay))) * 1e3
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    pad = 0.25 * float(np.hypot(*(hi - lo)))
    mid, half = (lo + hi) / 2.0, (hi - lo) / 2.0 + pad
    half = np.maximum(half, [half[1] / height_ratio, half[0] * height_ratio])
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlim(mid[0] - half[0], mid[0] + half[0])
    ax.set_ylim(mid[1] - half[1], mid[1] + half[1])


def _draw_roll_strip(ax: Axes, lay: TransverseLayout) -> None:
    """The roll coordinate s (mm): line of action, path of contact, contact zones, named
    points."""
    pair = lay.pair
    pb = pair.base_pitch
    s_a, s_e, s_c = pair.s_start * 1e3, pair.s_end * 1e3, pair.s_pitch * 1e3
    lo, hi = _line_span(lay)
    ax.plot([lo * 1e3, hi * 1e3], [0, 0], color="0.6", lw=1,
            label="line of action (tangent to both base circles)")
    ax.plot([s_a, s_e], [0, 0], color="C2", lw=6, solid_capstyle="butt",
            label="path of contact A-E")
    # zones: n + 1 pairs near both ends (length g_alpha - n p_b each), n between
    n = math.floor(pair.transverse_contact_ratio)
    extra = pair.path_length - n * pb
    where = " (in a transverse section)" if pair.overlap_ratio > 0 else ""
    ax.axvspan(s_a, s_a + extra * 1e3, color="C1", alpha=0.25,
               label=f"{n + 1} pairs in contact{where}")
    ax.axvspan(s_e - extra * 1e3, s_e, color="C1", alpha=0.25)
    ax.axvline(s_c, color="k", ls="--", lw=1, label="pitch point C")
    named = sorted(lay.rolls.items(), key=lambda kv: kv[1])
    for (name, s), (side, dist) in zip(named, _label_offsets(len(named)), strict=True):
        ax.annotate(name, (s * 1e3, 0), xytext=(0, side * dist), textcoords="offset points",
                    ha="center", va="center")
    ax.set_xlim(lo * 1e3, hi * 1e3)
    ax.set_xlabel("roll coordinate s along the line of action, from T1 [mm]")
    ax.set_yticks([])
    ax.set_ylim(-1.0, 1.0)


def plot_contact_lines(pair: GearPair, n_positions: int = 4, ax: Axes | None = None,
                       name: str = "") -> Axes:
    """Contact lines on the plane of action at a few positions over one mesh cycle.

    Axes in mm at equal scale (the plane of action as it is); the legend sits outside
    the plane, to the right, so it never covers a line. ``name`` (the case or mesh)
    starts the title.
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
    ax.set_ylabel("face position b_z [mm]")
    what = "contact lines on the plane of action"
    ax.set_title(f"{name}: {what}" if name else what[0].upper() + what[1:])
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
    for kind, color, label in ((FILLET, "tab:red", "fillet"), (INVOLUTE, "tab:green", "involute"),
                               (TIP_ROUNDING, "tab:purple", "tip rounding")):
        idx = np.flatnonzero(prof.kind == kind)
        if idx.size:  # each segment from the point where it begins: no line joins the
            idx = np.r_[idx[0] - 1, idx] if idx[0] > 0 else idx  # fillet to the tip
            ax.plot(prof.x[idx] * 1e3, prof.y[idx] * 1e3, "-", color=color, lw=2.2,
                    label=label)
    span = np.linspace(*np.arctan2(out[[-1, 0], 0], out[[-1, 0], 1]), 200)
    for r, style, name in ((g.root_radius, "--", "root"), (g.base_radius, ":", "base"),
                           (prof.form_radius, "-.", "form"), (g.tip_radius_, "-", "tip")):
        ax.plot(r * 1e3 * np.sin(span), r * 1e3 * np.cos(span), style, color="tab:blue",
                lw=0.6, label=f"{name} circle")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return ax


def profile_title(gear: GearSpec, prof: ToothProfile) -> str:
    """Title of a tooth-profile panel: name, kind, teeth and whether the flank is undercut."""
    kind = "internal" if gear.internal else "external"
    cut = "undercut" if prof.undercut else "no undercut"
    return f"{gear.name} ({kind}): z = {gear.teeth}, {cut}"


def plot_profiles(gears: tuple[GearSpec, ...], profiles: tuple[ToothProfile, ...]) -> Figure:
    """The tooth profiles of several gears (:func:`plot_profile`), one panel each, stacked.

    Each panel is as tall as the tallest drawing needs at equal scale over the panel width
    (1.5 to 6 in), so the panels are not separated by the empty bands an equal-scale
    drawing leaves in a taller slot."""
    margins = Margins(right=1.3, hspace=0.95)  # legends beside
    width = 9.0
    fig = new_figure((width, 4 * len(gears)), margins)
    axes = np.atleast_1d(fig.subplots(len(gears), 1))
    for ax, g, prof in zip(axes, gears, profiles, strict=True):
        plot_profile(prof, ax=ax)
        ax.set_title(profile_title(g, prof), y=TITLE_Y)
    panel_w = width - margins.left - margins.right
    ratio = max(ax.dataLim.height / ax.dataLim.width for ax in axes)
    panel_h = float(np.clip(panel_w * ratio, 1.5, 6.0))
    fig.set_size_inches(width, len(gears) * panel_h + margins.bottom + margins.top
                        + (len(gears) - 1) * margins.hspace)
    return fig
