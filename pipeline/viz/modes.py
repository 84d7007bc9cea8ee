"""Mode shapes drawn on the layout of the gears, a grid of panels per page.

Each panel shows one mode on the bodies' places (:mod:`pipeline.dynamics.layout`):
the grey circles are the bodies at rest (base circles, the carrier as the circle
through the planet centres); a body's translation is an arrow from its centre
(ring and carrier: from a point of their circle); its rotation is an arc along its
circle whose length is the rotation times the circle's radius (the tangential
displacement at the base circle); its axial translation ``z`` (along the gear axes,
normal to the drawing) is a circle beside the arrow's start whose *diameter* is ``|z|``,
with a dot inside for +z (out of the page, x-y-z right-handed) and a cross for -z.
Translations, rim displacements and axial translations share one scale per panel (the
largest is 90 % of the smallest gear's radius, so an axial circle fits inside the
smallest gear): the amplitude of a mode is arbitrary, its proportions are not. On a
schematic layout (unit circles) the marks are the kinetic-energy amplitudes sqrt(m) u,
sqrt(I) theta and sqrt(m) z instead, which compare translations and rotations without
a radius. Each panel's title gives the mode's kind and the shares of its kinetic energy
in in-plane translation, rotation and axial translation that the kind is read from
(:mod:`pipeline.dynamics.modal`). Herringbone halves are drawn in two colours (left,
right) and side by side, the left half's marks to the left.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.dynamics.layout import BodyPlace, ModelLayout
from pipeline.dynamics.results import ModalResult
from pipeline.viz.canvas import TITLE_Y, Margins, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

PER_PAGE = 12
"""Modes per page (3 rows of 4 panels)."""

_TRANSLATION = {"": "tab:blue", "L": "tab:blue", "R": "tab:cyan"}
_ROTATION = {"": "tab:red", "L": "tab:red", "R": "tab:orange"}
_AXIAL = {"": "tab:green", "L": "tab:green", "R": "tab:olive"}


def mode_pages(result: ModalResult, per_page: int = PER_PAGE, skip_rigid: bool = True,
               limit: int = 120) -> list[list[int]]:
    """Mode indices (as in ``modes.csv``) split into pages of ``per_page``.

    Rigid-body modes (0 Hz) are left out with ``skip_rigid``; at most ``limit`` modes.
    """
    idx = [k for k in range(result.frequencies.size)
           if not (skip_rigid and result.frequencies[k] == 0.0)][:limit]
    return [idx[i:i + per_page] for i in range(0, len(idx), per_page)]


def _motion(result: ModalResult, phi: np.ndarray, p: BodyPlace
            ) -> tuple[np.ndarray, float, float]:
    """(in-plane translation (2,) in the drawing frame, m; rim displacement r theta, m;
    axial translation z, m)."""
    idx = {n: i for i, n in enumerate(result.dof_names)}

    def q(d: str) -> float:
        i = idx.get(f"{p.name}.{d}")
        return 0.0 if i is None else float(phi[i])

    c, s = math.cos(p.frame_angle), math.sin(p.frame_angle)
    x, y = q("x"), q("y")
    return np.array([c * x - s * y, s * x + c * y]), p.radius * q("theta"), q("z")


def _anchor(p: BodyPlace, layout: ModelLayout) -> tuple[np.ndarray, float, float]:
    """Where a body's arrow starts, the radius its arc runs on and the arc's start angle."""
    centre = np.asarray(p.centre, float)
    if p.role == "ring":
        a = 0.75 * math.pi
        return centre + p.radius * np.array([math.cos(a), math.sin(a)]), p.radius, a
    if p.role == "carrier":
        planets = [q for q in layout.places if q.role == "planet"]
        n = max(len({q.centre for q in planets}), 1)
        a = (math.atan2(planets[0].centre[1], planets[0].centre[0]) if planets else 0.0) \
            + math.pi / n
        return centre + p.radius * np.array([math.cos(a), math.sin(a)]), p.radius, a
    return centre, 0.72 * p.radius, 0.5 * math.pi


def _axial_mark(ax: Axes, centre, z: float, scale: float, colour: str) -> None:
    """Circle of diameter ``scale |z|`` at ``centre`` with a dot inside for +z, a cross for
    -z; the dot and cross keep one size in points so that the sign of a small circle shows."""
    from matplotlib.patches import Circle

    ax.add_patch(Circle(tuple(centre), 0.5 * scale * abs(z), fill=False, ec=colour, lw=1.8))
    sign = dict(marker="o", ms=3.5, mew=0) if z > 0 else dict(marker="x", ms=5.5, mew=1.6)
    ax.plot([centre[0]], [centre[1]], ls="", color=colour, **sign)


def _arc(ax: Axes, centre, r: float, a0: float, span: float, colour: str) -> None:
    from matplotlib.patches import FancyArrowPatch

    span = float(np.clip(span, -1.9 * math.pi, 1.9 * math.pi))
    t = np.linspace(a0, a0 + span, max(8, int(abs(span) * 24)))
    x, y = centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)
    ax.plot(x[:-1], y[:-1], color=colour, lw=2.4, solid_capstyle="butt")
    ax.add_patch(FancyArrowPatch((x[-2], y[-2]), (x[-1], y[-1]), arrowstyle="-|>",
                                 mutation_scale=14, color=colour, lw=2.4, shrinkA=0,
                                 shrinkB=0))


def plot_mode_on_layout(result: ModalResult, layout: ModelLayout, k: int,
                        ax: Axes | None = None) -> Axes:
    """Draw mode ``k`` of ``result`` on ``layout`` (module docstring); returns the Axes."""
    from matplotlib.patches import Circle, FancyArrowPatch

    if ax is None:
        ax = new_figure((4, 4)).subplots()
    phi = result.real_shapes()[:, k]
    if layout.schematic and result.weights is not None:
        phi = phi * result.weights  # unit circles: compare kinetic-energy amplitudes instead
    motion = {p.name: _motion(result, phi, p) for p in layout.places}
    big = max([np.hypot(*u) for u, _, _ in motion.values()]
              + [max(abs(t), abs(z)) for _, t, z in motion.values()] + [0.0])
    gears = [p.radius for p in layout.places if p.role not in ("ring", "carrier")]
    smallest = min(gears or [p.radius for p in layout.places])
    scale = 0.9 * smallest / big if big > 0 else 0.0
    drawn = set()
    for p in layout.places:
        key = (p.centre, p.radius, p.role)
        if key not in drawn:
            drawn.add(key)
            ls = ":" if p.role == "carrier" else "-"
            ax.add_patch(Circle(p.centre, p.radius, fill=False, ec="0.6", lw=1.0, ls=ls))
            if layout.schematic or p.role in ("sun", "pinion", "gear", "planet", "drive", "load"):
                label = p.name[:-1] if p.side else p.name
                ax.annotate(label, p.centre, xytext=(0, -3), textcoords="offset points",
                            ha="center", va="top", fontsize=7, color="0.35")
    if layout.line_of_action is not None:
        (x1, y1), (x2, y2) = layout.line_of_action
        ax.plot([x1, x2], [y1, y2], color="0.6", lw=1.0, ls="-.")
        for xy, name in (((x1, y1), "T1"), ((x2, y2), "T2")):
            ax.annotate(name, xy, xytext=(0, 3), textcoords="offset points", ha="center",
                        va="bottom", fontsize=7, color="0.35")
    for p in layout.places:
        u, t, z = motion[p.name]
        colour = _TRANSLATION[p.side]
        start, rr, a0 = _anchor(p, layout)
        beside = start
        if p.side:  # the two halves of a herringbone member side by side, not on top
            shift = (-0.14 if p.side == "L" else 0.14) * p.radius
            beside = start + np.array([(-0.5 if p.side == "L" else 0.5) * smallest, 0.0])
            start = start + np.array([shift, 0.0])
            rr = rr * (0.8 if p.side == "L" else 1.0)
        du = scale * u
        if np.hypot(*du) > 1e-3 * scale * big:
            ax.add_patch(FancyArrowPatch(tuple(start), tuple(start + du), arrowstyle="-|>",
                                         mutation_scale=14, color=colour, lw=2.2,
                                         shrinkA=0, shrinkB=0))
        if abs(scale * t) > 1e-3 * scale * big:
            _arc(ax, p.centre, rr, a0, p.spin * scale * t / rr, _ROTATION[p.side])
        if abs(z) > 1e-3 * big:
            _axial_mark(ax, beside, z, scale, _AXIAL[p.side])
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_axis_off()
    sh = {g: float(v[k]) for g, v in result.energy_shares().items()}
    kind = f" {result.kinds[k]}" if result.kinds[k] else ""
    ax.set_title(f"mode {k}: {result.frequencies[k]:.1f} Hz{kind} (x{result.multiplicity[k]})"
                 f"\nenergy: in-plane {100 * sh['in-plane']:.0f} %, rotation "
                 f"{100 * sh['rotation']:.0f} %, axial {100 * sh['axial']:.0f} %",
                 fontsize=8, y=TITLE_Y)
    return ax


def plot_mode_shapes(result: ModalResult, layout: ModelLayout, modes: Sequence[int],
                     cols: int = 4, title: str = "", fig: Figure | None = None) -> Figure:
    """A grid of :func:`plot_mode_on_layout` panels for the mode indices ``modes``."""
    from matplotlib.lines import Line2D

    n = max(len(modes), 1)
    cols = min(cols, n)
    rows = math.ceil(n / cols)
    xs = [p.centre[0] for p in layout.places]
    ys = [p.centre[1] for p in layout.places]
    r = max(p.radius for p in layout.places)
    aspect = (max(xs) - min(xs) + 2 * r) / (max(ys) - min(ys) + 2 * r)
    w = 3.4 if aspect < 1.6 else 5.0
    sides = sorted({p.side for p in layout.places})
    prefix = {"": "", "L": "left half: ", "R": "right half: "}
    handles = [Line2D([], [], color=_TRANSLATION[s], lw=2.2,
                      label=f"{prefix[s]}translation (arrow)")
               for s in sides]
    handles += [Line2D([], [], color=_ROTATION[s], lw=2.4,
                       label=f"{prefix[s]}rotation (arc: r theta at the base circle)")
                for s in sides]
    axial = any(n.endswith(".z") for n in result.dof_names)
    if axial:
        handles += [Line2D([], [], color=_AXIAL[s], ls="", marker=r"$\odot$", ms=11,
                           label=f"{prefix[s]}axial z (circle: diameter |z|; "
                                 "dot +z out of the page, cross -z)")
                    for s in sides]
    marks = "arrows, arcs and circles" if axial else "arrows and arcs"
    handles += [Line2D([], [], color="0.6", lw=1.0,
                       label=f"bodies at rest; {marks} on one length scale")]
    if layout.line_of_action is not None:
        handles += [Line2D([], [], color="0.6", lw=1.0, ls="-.",
                           label="line of action T1 T2 (x)")]
    ncol = min(len(handles), 2 if axial else 3)
    suptitle = bool(title or layout.schematic)
    if fig is None:
        # fixed margins (in): the legend's rows below (0.2 each, font size 8), the suptitle
        # and each panel's two-line title above; panels without axes need no more
        panel_h = w / max(min(aspect, 3.0), 0.5)
        margins = Margins(left=0.1, right=0.1, wspace=0.25, hspace=0.45,
                          bottom=0.2 + 0.2 * math.ceil(len(handles) / ncol),
                          top=0.45 + (0.3 if suptitle else 0.0))
        fig = new_figure((w * cols, panel_h * rows + margins.top + margins.bottom
                          + margins.hspace * (rows - 1)), margins)
    axes = np.atleast_1d(fig.subplots(rows, cols, squeeze=False)).ravel()
    for a, k in zip(axes, modes, strict=False):
        plot_mode_on_layout(result, layout, k, ax=a)
    for a in axes[len(modes):]:
        a.set_axis_off()
    fig.legend(handles=handles, loc="outside lower center", ncol=ncol, fontsize=8)
    if suptitle:
        note = " (bodies placed on a grid: schematic layout)" if layout.schematic else ""
        fig.suptitle(f"{title}{note}", fontsize=10)
    return fig
