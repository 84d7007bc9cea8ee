"""Figures of the herringbone sun-planet contact: against the groove stiffness (Xu et al. 2020,
Fig. 5), each half's mesh stiffness over a mesh cycle and the change of its maximum; in a
report, the line load over the face of each half."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from pipeline.contact.herringbone_distribution import HerringboneDistribution


def plot_groove_mesh_stiffness(
    Kj: Sequence[float], k_left: np.ndarray, k_right: np.ndarray,
    series_left: np.ndarray | None = None, series_right: np.ndarray | None = None,
    paper_Kj: tuple[float, float] = (5.2e7, 4.0e7),
    paper_change: tuple[float, float] = (0.0979, -0.1123), title: str = "",
) -> Figure:
    """Left/right sun-planet mesh stiffness over a mesh cycle per groove, and the change of
    the maximum from the stiffest groove beside Xu et al. (2020)'s published end points.

    Parameters
    ----------
    Kj : (K,) groove stiffnesses K_j, N m^2 (the first is the reference).
    k_left, k_right : (K, m) own mesh stiffness of each half at m equally spaced positions
        of one mesh cycle, N/m.
    series_left, series_right : (K, m) the same in series with the groove and support the
        half's load meets (N/m), drawn dashed in the left panels and in the change panel.
    paper_Kj : (K_1, K_5) of the paper, N m^2. paper_change : its changes of the maximum
        left and right stiffness from K_1 to K_5 (-).
    """
    Kj = np.asarray(Kj, dtype=float)
    fig = new_figure((12, 5.0), "constrained")
    ax = fig.subplots(1, 3)
    m = k_left.shape[1]
    x = np.arange(m) / m
    for j, kj in enumerate(Kj):
        for a, k, ks in ((ax[0], k_left, series_left), (ax[1], k_right, series_right)):
            line, = a.plot(x, k[j] * 1e-6, lw=1.2, label=f"K_j = {kj / 1e7:.2f}e7 N m^2")
            if ks is not None:
                a.plot(x, ks[j] * 1e-6, lw=1.0, ls="--", color=line.get_color())
    for a, side in ((ax[0], "left"), (ax[1], "right")):
        a.set_xlabel("mesh position [mesh cycles]")
        a.set_ylabel(f"{side} half mesh stiffness [N/um]")
        a.set_title(f"{side} sun-planet mesh")
        a.grid(alpha=0.3)
    ax[0].legend(fontsize=7, title="solid: own; dashed: with groove and axial support",
                 title_fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    for k, ks, side, c in ((k_left, series_left, "left", "C0"),
                           (k_right, series_right, "right", "C3")):
        for kk, ls, what in ((k, "o-", "own"), (ks, "^:", "with groove + support")):
            if kk is not None:
                change = (kk.max(axis=1) / kk[0].max() - 1.0) * 100.0
                ax[2].plot(Kj / 1e7, change, ls, color=c, label=f"{side}: {what}")
    for ch, side, c in ((paper_change[0], "left", "C0"), (paper_change[1], "right", "C3")):
        ax[2].plot(np.array(paper_Kj) / 1e7, [0.0, ch * 100.0], "s--", color=c, mfc="none",
                   label=f"{side}: Xu et al. (2020)")
    ax[2].set_xlabel("groove torsional stiffness K_j [1e7 N m^2]")
    ax[2].set_ylabel("change of max. mesh stiffness [%]")
    ax[2].invert_xaxis()
    ax[2].axhline(0.0, color="k", lw=0.6)
    ax[2].legend(fontsize=7)
    ax[2].grid(alpha=0.3)
    ax[2].set_title("from the stiffest groove")
    if title:
        fig.suptitle(title)
    return fig


def plot_half_line_loads(halves: HerringboneDistribution, title: str = "") -> Figure:
    """Line load over the face of each helical half of a herringbone mesh: its envelope
    (solid) and its mean over the mesh cycle (dashed), N/mm against mm, beside one helical
    half at an equal split of the load when the distribution has it.

    The halves are mirror images, so each is drawn over its own face coordinate z: equal
    z lie at equal distances from the groove.
    """
    from matplotlib.lines import Line2D

    fig = new_figure((7.0, 3.8), "constrained")
    ax = fig.add_subplot()
    sides = [("left", "C0"), ("right", "C3")]
    if halves.equal_split is not None:
        sides.append(("equal split", "0.45"))
    handles = []
    for side, colour in sides:
        h = halves.half(side)
        d = h.distribution
        z = d.z * 1e3
        ax.plot(z, d.envelope * 1e-3, color=colour, lw=2.0)
        ax.plot(z, d.cycle_mean * 1e-3, color=colour, lw=1.3, ls="--")
        label = (f"{side} half, {100 * h.share.mean():.1f} % of the load"
                 f"{' (governs)' if side == halves.governing else ''}"
                 if side != "equal split" else "one half at an equal split, 50 %")
        handles.append(Line2D([], [], color=colour, lw=2.0, label=label))
    handles += [Line2D([], [], color="k", lw=2.0, label="envelope over the cycle"),
                Line2D([], [], color="k", lw=1.3, ls="--", label="mean over the cycle")]
    top = max(float(halves.half(s).distribution.envelope.max()) for s, _ in sides) * 1e-3
    ax.set_xlabel("face position b_z in each half [mm] (mirror images: equal b_z, equal "
                  "distance from the groove)", fontsize=8)
    ax.set_ylabel("line load w [N/mm]")
    ax.set_xlim(0.0, halves.left.distribution.face_width * 1e3)
    ax.set_ylim(0.0, max(top * 1.4, 1e-9))
    ax.grid(alpha=0.3)
    ax.legend(handles=handles, fontsize=7, loc="upper center", ncol=3)
    ax.set_title(title, fontsize=9)
    return fig
