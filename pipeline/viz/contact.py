"""Loaded tooth contact over a mesh cycle: stiffness, transmission error, load sharing."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pipeline.contact.results import LoadedMeshCycle, pairs_in_order_of_entry
from pipeline.viz.canvas import TITLE_Y, Margins, new_figure
from pipeline.viz.units import stiffness_in_plot_unit, stiffness_label

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def corner_shares(cyc: LoadedMeshCycle) -> np.ndarray:
    """(m, K) share of the load each tooth pair carries at a tip corner beyond the path of
    contact (-), columns ``cyc.pair_index``."""
    out = np.zeros_like(cyc.pair_loads)
    tip = cyc.point_corner > 0
    cols = np.searchsorted(cyc.pair_index, cyc.point_pair[tip])
    np.add.at(out, (cyc.point_position[tip], cols), cyc.point_load[tip])
    return out / cyc.load


def plot_contact_cycle(cyc: LoadedMeshCycle, k_slice: np.ndarray, title: str,
                       fig: Figure | None = None) -> Figure:
    """Mesh stiffness (against the slice method ``k_slice``, N/m), loaded static TE and
    load sharing over the cycle, three panels; returns the figure."""
    if fig is None:
        # legends beside the panels, a two-line suptitle, a title over the last panel
        fig = new_figure((9, 8), Margins(right=2.5, top=0.6, hspace=0.35))
    ax = fig.subplots(3, 1, sharex=True)
    deg = np.degrees(cyc.pinion_angle)
    k = stiffness_in_plot_unit
    ax[0].plot(deg, k(cyc.mesh_stiffness), label="LTCA tangent dP/dx")
    ax[0].plot(deg, k(cyc.mesh_stiffness_secant), "--", label="LTCA secant P/x")
    ax[0].plot(deg, k(k_slice), ":", label="analytical (potential energy, slices)")
    ax[0].set_ylabel(stiffness_label())
    ax[0].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax[1].plot(deg, cyc.transmission_error * 1e6)
    ax[1].set_ylabel("loaded static TE [um]")
    corner = corner_shares(cyc)
    marked = False
    for n, j in enumerate(pairs_in_order_of_entry(cyc.pair_loads), start=1):
        (line,) = ax[2].plot(deg, cyc.load_share[:, j], label=f"tooth pair {n}")
        tip = corner[:, j] > 0
        if tip.any():
            ax[2].plot(deg[tip], cyc.load_share[tip, j], "o", ms=4, mfc="none",
                       color=line.get_color(),
                       label=None if marked else "at a tip corner, beyond the path")
            marked = True
    ax[2].set_ylabel("load share [-]")
    ax[2].set_title("tooth pairs numbered in the order they take load in the cycle"
                    + ("; circles: the pair touches at a tip corner beyond the path of "
                       "contact" if marked else ""), fontsize=8, y=TITLE_Y)
    ax[2].set_xlabel("pinion angle [deg]")
    ax[2].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.suptitle(title, fontsize=10)  # the figure is wider than one axes title
    return fig
