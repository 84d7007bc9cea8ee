"""Figure of the shafts' deflection and what it does to the line load across the face."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def plot_shaft_deflection(shafts: Sequence[tuple[str, np.ndarray, np.ndarray,
                                                 tuple[float, float], np.ndarray]],
                          z_face: np.ndarray, rigid: np.ndarray, coupled: np.ndarray,
                          gap: np.ndarray, title: str, face_reversed: bool = False) -> Figure:
    """Left: each shaft's deflection along the line of action, ``(name, z m, u_y m, (seat
    start, end) m, bearing positions m)``, in um over mm with the seat shaded and the
    bearings marked. Right: the cycle-mean line load across the face on rigid supports and
    with the shafts (N/mm), and the shafts' misalignment there (um, right axis), over the
    contact's face position; ``face_reversed``: it runs against the shafts' z (a right-hand
    helical pinion, :func:`pipeline.shaft.misalignment.seat_points`), which the label says."""
    fig = new_figure((9.0, 3.6), "constrained")
    ax = fig.add_subplot(1, 2, 1)
    for i, (name, z, uy, seat, bearings) in enumerate(shafts):
        colour = f"C{i}"
        ax.plot(np.asarray(z) * 1e3, np.asarray(uy) * 1e6, colour, lw=1.8, label=name)
        ax.axvspan(seat[0] * 1e3, seat[1] * 1e3, color=colour, alpha=0.15)
        ax.plot(np.asarray(bearings) * 1e3, np.zeros(len(bearings)), "^", color=colour,
                ms=8, label=f"{name}: bearings")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("position along the shaft z [mm]")
    ax.set_ylabel("deflection along the line of action [um]")
    ax.set_title("shafts (the gear's seat shaded)", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax2 = fig.add_subplot(1, 2, 2)
    zf = np.asarray(z_face) * 1e3
    ax2.plot(zf, np.asarray(rigid) * 1e-3, "k--", lw=1.4, label="rigid supports")
    ax2.plot(zf, np.asarray(coupled) * 1e-3, "C3", lw=2.0, label="with the shafts")
    ax2.set_xlabel("face position b_z [mm]" + (" (runs against the shaft's z)" if face_reversed
                                               else ""))
    ax2.set_ylabel("cycle-mean line load [N/mm]")
    top = max(float(np.max(rigid)), float(np.max(coupled))) * 1e-3
    ax2.set_ylim(0.0, 1.2 * top)
    ax2.grid(alpha=0.3)
    tw = ax2.twinx()
    tw.plot(zf, np.asarray(gap) * 1e6, "C0:", lw=1.4, label="misalignment (gap)")
    tw.set_ylabel("misalignment from the shafts [um]")
    lines = ax2.get_legend_handles_labels()
    more = tw.get_legend_handles_labels()
    ax2.legend(lines[0] + more[0], lines[1] + more[1], fontsize=8, loc="lower center")
    ax2.set_title("line load across the face", fontsize=9)
    fig.suptitle(title, fontsize=9)
    return fig


def plot_shaft_dynamics(frequencies: np.ndarray, with_shafts: np.ndarray,
                        rigid: np.ndarray, natural: Sequence[float],
                        natural_rigid: Sequence[float], mesh_frequency: float,
                        title: str) -> Figure:
    """The dynamic factor (-) over mesh frequency (Hz) with the shafts and on rigid
    supports, with each model's natural frequencies (Hz) marked on its own colour and the
    operating mesh frequency."""
    fig = new_figure((7.5, 3.6), "constrained")
    ax = fig.add_subplot(1, 1, 1)
    f = np.asarray(frequencies)
    ax.plot(f, with_shafts, "C3", lw=1.8, label="with the shafts")
    ax.plot(f, rigid, "k--", lw=1.4, label="rigid supports")
    for fn, colour, ls in ((natural, "C3", ":"), (natural_rigid, "k", "-.")):
        for x in fn:
            if f[0] <= x <= f[-1]:
                ax.axvline(x, color=colour, ls=ls, lw=0.8, alpha=0.6)
    ax.axvline(mesh_frequency, color="C2", lw=1.2, label="operating mesh frequency")
    ax.set_xlabel("mesh frequency [Hz]")
    ax.set_ylabel("dynamic factor (largest elastic / mean mesh force) [-]")
    ax.set_xlim(f[0], f[-1])
    ax.grid(alpha=0.3)
    ax.plot([], [], "C3:", lw=0.8, label="natural frequencies, with the shafts")
    ax.plot([], [], "k-.", lw=0.8, label="natural frequencies, rigid supports")
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return fig
