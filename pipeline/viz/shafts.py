"""Figure of the shafts' deflection and what it does to the line load across the face."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.viz.canvas import TITLE_Y, Margins, new_figure

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
    # the twin axis's label on the right
    fig = new_figure((9.0, 3.6), Margins(top=0.6, right=0.85, wspace=0.95))
    ax = fig.add_subplot(1, 2, 1)
    _shaft_panel(ax, [(*s, f"{s[0]}: bearings") for s in shafts],
                 "deflection along the line of action", "shafts (the gear's seat shaded)")
    _line_load_panel(fig.add_subplot(1, 2, 2), z_face, rigid, coupled, gap, face_reversed)
    fig.suptitle(title, fontsize=9)
    return fig


def plot_planetary_shaft_deflection(shafts: Sequence[tuple[str, np.ndarray, np.ndarray,
                                                           tuple[float, float], np.ndarray,
                                                           str]],
                                    z_face: np.ndarray, rigid: np.ndarray,
                                    coupled: np.ndarray, gap: np.ndarray, title: str
                                    ) -> Figure:
    """One mesh of a planetary set: a panel per shaft that moves its flanks, ``(name, z m,
    retreat m, (seat start, end) m, support positions m, the supports' name)``, each
    section's retreat along the mesh's line of action in um over mm on its own scale (the
    sun's wind-up from its torque point dwarfs a pin's bending), the seat shaded, the sun in
    C0 and a pin in C1 in every mesh's figure; then the line load panel of
    :func:`plot_shaft_deflection`."""
    n = len(shafts) + 1
    fig = new_figure((4.2 * n, 3.6), Margins(top=0.6, right=0.85, wspace=0.95))
    for i, s in enumerate(shafts):
        ax = fig.add_subplot(1, n, i + 1)
        _shaft_panel(ax, [s], "retreat along the line of action",
                     f"{s[0]} (the seat shaded)", colour=0 if s[0] == "sun" else 1)
    _line_load_panel(fig.add_subplot(1, n, n), z_face, rigid, coupled, gap, False)
    fig.suptitle(title, fontsize=9)
    return fig


def _shaft_panel(ax, shafts, ylabel: str, title: str, colour: int = 0) -> None:
    """Deflection lines ``(name, z, value, seat, supports, supports' name)`` in um over mm,
    the supports marked on their lines."""
    for i, (name, z, uy, seat, bearings, marks) in enumerate(shafts):
        c = f"C{colour + i}"
        ax.plot(np.asarray(z) * 1e3, np.asarray(uy) * 1e6, c, lw=1.8, label=name)
        ax.axvspan(seat[0] * 1e3, seat[1] * 1e3, color=c, alpha=0.15)
        # on the line: an elastic bearing gives by the shaft's deflection there
        at = np.interp(np.asarray(bearings, dtype=float), np.asarray(z), np.asarray(uy))
        ax.plot(np.asarray(bearings) * 1e3, at * 1e6, "^", color=c, ms=8, label=marks)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("position along the shaft z [mm]")
    ax.set_ylabel(f"{ylabel} [um]")
    ax.set_title(title, fontsize=9, y=TITLE_Y)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def _line_load_panel(ax2, z_face, rigid, coupled, gap, face_reversed: bool) -> None:
    """The cycle-mean line load (N/mm) on rigid supports and with the shafts, and the gap
    (um, right axis), over the face position (mm)."""
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
    ax2.set_title("line load across the face", fontsize=9, y=TITLE_Y)


def plot_shaft_dynamics(frequencies: np.ndarray, with_shafts: np.ndarray,
                        rigid: np.ndarray, natural: Sequence[float],
                        natural_rigid: Sequence[float], mesh_frequency: float,
                        title: str) -> Figure:
    """The dynamic factor (-) over mesh frequency (Hz) with the shafts and without them, with
    each model's natural frequencies (Hz) marked in its own colour and the operating mesh
    frequency."""
    fig = new_figure((9.5, 3.6), Margins(left=1.0, right=2.65))  # the legend beside
    ax = fig.add_subplot(1, 1, 1)
    f = np.asarray(frequencies)
    ax.plot(f, with_shafts, "C3", lw=1.8, label="with the shafts")
    ax.plot(f, rigid, "k--", lw=1.4, label="without the shafts")
    for fn, colour, ls in ((natural, "C3", ":"), (natural_rigid, "k", "-.")):
        for x in fn:
            if f[0] <= x <= f[-1]:
                ax.axvline(x, color=colour, ls=ls, lw=0.8, alpha=0.6)
    ax.axvline(mesh_frequency, color="C2", lw=1.2, label="operating mesh frequency")
    ax.set_xlabel("mesh frequency [Hz]")
    # two lines: in one, the label is longer than the axes are high
    ax.set_ylabel("dynamic factor [-]\n(largest elastic / mean mesh force)")
    ax.set_xlim(f[0], f[-1])
    ax.grid(alpha=0.3)
    ax.plot([], [], "C3:", lw=0.8, label="natural frequencies, with the shafts")
    ax.plot([], [], "k-.", lw=0.8, label="natural frequencies, without the shafts")
    # beside the axes: the resonance lines run through the whole height of the plot
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title(title, fontsize=9, y=TITLE_Y)
    return fig
