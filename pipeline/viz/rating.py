"""Figure of the ISO 6336 rating: each gear's safety factors against the required minimum."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def plot_safety_factors(gears: Sequence[str], pitting: Sequence[float],
                        bending: Sequence[float], minimum_pitting: float,
                        minimum_bending: float, title: str) -> Figure:
    """S_H and S_F of each gear (bars, NaN for a gear not rated) beside the required S_Hmin
    and S_Fmin (dashed lines, labelled at the left); a bar below its minimum is red, with
    its value on top."""
    fig = new_figure((7.0, 3.4), "constrained")
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
        ax.set_title(name, fontsize=9)
        ax.grid(axis="y", alpha=0.3)
    fig.suptitle(title, fontsize=9)
    return fig
