"""Tooth profile figure: a few teeth of the exact outline with fillet, involute and key circles."""

from __future__ import annotations

import numpy as np

from pipeline.geometry.profile import INVOLUTE, ToothProfile, gear_outline
from pipeline.viz.pair_plots import _plt


def plot_profile(prof: ToothProfile, ax=None, teeth: int = 3):
    """Draw ``teeth`` teeth around +y (mm), the middle flank coloured by segment, and the circles.

    Returns the figure. Circles: root (dashed), base (dotted), form (dash-dot), tip (thin).
    """
    plt = _plt()
    if ax is None:
        _, ax = plt.subplots(figsize=(5, 5))
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
    return ax.figure
