"""Figures of the ISO 6336 rating: each gear's safety factors against the required minimum,
the local pitting safety over both flanks and the root stress along the face
(:mod:`pipeline.rating.local_safety`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.viz.canvas import TITLE_Y, Margins, new_figure, panels_with_colorbar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from pipeline.rating.local_safety import LocalSafety


def plot_safety_factors(gears: Sequence[str], pitting: Sequence[float],
                        bending: Sequence[float], minimum_pitting: float,
                        minimum_bending: float, title: str) -> Figure:
    """S_H and S_F of each gear (bars, NaN for a gear not rated) beside the required S_Hmin
    and S_Fmin (dashed lines, labelled at the left); a bar below its minimum is red, with
    its value on top."""
    fig = new_figure((7.0, 3.4), Margins(top=0.6))  # suptitle and panel titles
    panels = (("pitting: S_H", pitting, minimum_pitting, "S_Hmin"),
              ("tooth root: S_F", bending, minimum_bending, "S_Fmin"))
    top = max([v for _, vals, _, _ in panels for v in vals if not math.isnan(v)]
              + [minimum_pitting, minimum_bending])
    for i, (name, values, minimum, label) in enumerate(panels):
        ax = fig.add_subplot(1, 2, i + 1)
        x = range(len(gears))
        shown = [0.0 if math.isnan(v) else v for v in values]
        colours = ["C2" if v >= minimum else "C3" for v in shown]
        ax.bar(x, shown, width=0.6, color=colours)
        for xi, v in zip(x, values, strict=True):
            text = "not rated" if math.isnan(v) else f"{v:.3f}"
            ax.text(xi, (0.0 if math.isnan(v) else v) + 0.02 * top, text, ha="center",
                    va="bottom", fontsize=8)
        ax.axhline(minimum, color="k", ls="--", lw=1.0)
        ax.text(-0.45, minimum, f" {label} = {minimum:g}", ha="left", va="bottom", fontsize=8,
                bbox={"facecolor": "white", "edgecolor": "none", "pad": 1.0})
        ax.set_xticks(list(x), list(gears))
        ax.set_xlim(-0.5, len(gears) - 0.5)
        ax.set_ylim(0.0, 1.15 * top)
        ax.set_ylabel(f"safety factor {name.split(': ')[1]} [-]")
        ax.set_title(name, fontsize=9, y=TITLE_Y)
        ax.grid(axis="y", alpha=0.3)
    fig.suptitle(title, fontsize=9)
    return fig


def _safety_levels(maps: Sequence[np.ndarray], minimum: float) -> np.ndarray:
    """Colour levels of the local safety maps (round numbers): from just below the smallest
    value or the required minimum, whichever is lower, to twice the smallest value, so the
    colours resolve the flank near its weakest point and start red at the minimum; larger
    values take the top colour."""
    from matplotlib.ticker import MaxNLocator

    smin = min(float(np.nanmin(m)) for m in maps)
    smax = max(float(np.nanmax(m)) for m in maps)
    lo = min(smin, minimum) * 0.98
    hi = max(min(smax, 2.0 * smin), minimum * 1.02, lo * 1.05)
    return MaxNLocator(nbins=16).tick_values(lo, hi)


def plot_local_pitting_safety(local: LocalSafety, minimum: float, internal: bool,
                              title: str) -> Figure:
    """S_H,loc over the flank of each gear of ``local``
    (:class:`~pipeline.rating.local_safety.LocalSafety`): filled contours over the gear's
    diameter (mm, growing to the right; the x label says on which side the root is) and the
    face position (mm), the required ``minimum`` S_Hmin as a black contour line, the
    smallest value marked and written in the panel's title; white where the flank carries
    no load. ``internal``: the second gear is a ring."""
    from pipeline.viz.distribution import flank_axis_label

    # two-line suptitle and panel titles, the colour bar's label on the right
    fig = new_figure((10.0, 4.0), Margins(top=1.0, right=0.75, wspace=0.3))
    axes, bar_axes = panels_with_colorbar(fig)
    zz = local.z * 1e3
    levels = _safety_levels([p.safety for p in local.pitting], minimum)
    cmap = "RdYlGn"
    for k, (ax, p) in enumerate(zip(axes, local.pitting, strict=True)):
        d = p.diameter * 1e3
        order = np.argsort(d)
        values = np.ma.masked_invalid(p.safety[order].T)
        filled = ax.contourf(d[order], zz, values, levels=levels, cmap=cmap, extend="max")
        if np.nanmin(p.safety) < minimum < np.nanmax(p.safety):
            lines = ax.contour(d[order], zz, values, levels=[minimum], colors="k",
                               linewidths=1.2)
            ax.clabel(lines, fmt=f"S_Hmin {minimum:g}", fontsize=7)
        ax.plot(p.minimum_diameter * 1e3, p.minimum_z * 1e3, "P", ms=11, mfc="w", mec="k",
                mew=1.0)
        flag = f" < S_Hmin {minimum:g}" if p.minimum < minimum else ""
        ax.set_title(f"{p.gear} flank: smallest S_H,loc {p.minimum:.3f}{flag} at +\n"
                     f"(d = {p.minimum_diameter * 1e3:.1f} mm, b_z = {p.minimum_z * 1e3:.1f} "
                     "mm)", fontsize=9, y=TITLE_Y)
        ax.set_xlabel(flank_axis_label(p.gear, internal and k == 1))
        pad = 0.04 * (d.max() - d.min())
        ax.set_xlim(d.min() - pad, d.max() + pad)
    pad = 0.04 * (zz.max() - zz.min())
    axes[0].set_ylim(zz.min() - pad, zz.max() + pad)
    axes[0].set_ylabel("face position b_z [mm]")
    bar = fig.colorbar(filled, cax=bar_axes, label=f"local pitting safety S_H,loc [-]; black: "
                       f"S_Hmin = {minimum:g}")
    bar.ax.axhline(minimum, color="k", lw=1.2)
    fig.suptitle(f"{title}\nS_H,loc = sigma_HG / (p_H sqrt(K_A K_gamma K_v)), K_A K_gamma K_v"
                 f" = {local.load_factor:.3f}; p_H the loaded contact's envelope over the "
                 "cycle", fontsize=9)
    return fig


def plot_root_stress_along_face(local: LocalSafety, minimum: float, title: str) -> Figure:
    """The largest FE root stress over the cycle at each face position (MPa, left) and the
    local bending safety S_F,loc (right, with the required ``minimum`` S_Fmin dashed) of
    each gear of ``local`` (:class:`~pipeline.rating.local_safety.LocalSafety`, with its
    root stress); the largest stress and the smallest S_F,loc marked."""
    if local.bending is None:
        raise ValueError("plot_root_stress_along_face: the local safety has no root stress")
    fig = new_figure((10.0, 3.6), Margins(top=0.65, wspace=0.95))  # two-line suptitle
    a1, a2 = fig.subplots(1, 2, sharex=True)
    zz = local.z * 1e3
    for i, b in enumerate(local.bending):
        c = f"C{i}"
        top = float(b.stress.max())
        a1.plot(zz, b.stress * 1e-6, color=c, label=f"{b.gear}: max {top * 1e-6:.0f} MPa at "
                f"b_z = {b.minimum_z * 1e3:.1f} mm")
        a1.plot(b.minimum_z * 1e3, top * 1e-6, "o", color=c)
        if b.limit is None:
            a2.plot([], [], color=c, label=f"{b.gear}: not rated in bending")
            continue
        a2.plot(zz, b.safety, color=c, label=f"{b.gear}: min {b.minimum:.3f} at b_z = "
                f"{b.minimum_z * 1e3:.1f} mm")
        a2.plot(b.minimum_z * 1e3, b.minimum, "o", color=c)
    a1.set_ylabel("FE root stress, largest over the cycle [MPa]")
    a1.set_ylim(0.0, 1.25 * max(float(b.stress.max()) for b in local.bending) * 1e-6)
    a2.axhline(minimum, color="k", ls="--", lw=1.0, label=f"S_Fmin = {minimum:g}")
    rated = [b.safety for b in local.bending if b.limit is not None]
    top = max([float(np.nanmax(s)) for s in rated] + [minimum])
    a2.set_ylim(0.0, 1.3 * top)
    a2.set_ylabel("local bending safety S_F,loc [-]")
    for ax in (a1, a2):
        ax.set_xlabel("face position b_z [mm]")
        pad = 0.03 * (zz.max() - zz.min())  # a marker at a face end is not cut
        ax.set_xlim(zz.min() - pad, zz.max() + pad)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="best")
    fig.suptitle(f"{title}\nS_F,loc = sigma_FG / (sigma_FE K_A K_gamma K_v), K_A K_gamma K_v "
                 f"= {local.load_factor:.3f}: where along the face, not ISO's S_F", fontsize=9)
    return fig
