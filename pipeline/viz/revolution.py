"""The loaded contact through a revolution: transmission error, its order spectrum, the
worst tooth pair's pressure along the path."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pipeline.contact.revolution_results import LoadedRevolution, Spectrum
from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

_LABELLED = 12  # most peaks a spectrum labels


def plot_revolution_te(rev: LoadedRevolution, cycle_te: np.ndarray, title: str,
                       fig: Figure | None = None) -> Figure:
    """Loaded static TE over the span (um) against the pinion angle (deg), beside the
    error-free mesh cycle's TE ``cycle_te`` (m, one cycle) repeated and the runouts' gap."""
    if fig is None:
        fig = new_figure((10, 4.5), "constrained")
    ax = fig.subplots()
    deg = np.degrees(rev.contact.pinion_angle)
    ax.plot(deg, rev.transmission_error * 1e6, lw=0.8, label="with the errors")
    ax.plot(deg, np.tile(cycle_te, rev.mesh_cycles) * 1e6, lw=0.6, ls="--", color="0.4",
            label="without errors (the mesh cycle repeated)")
    if np.any(rev.runout_gap):
        ax.plot(deg, rev.runout_gap * 1e6, lw=0.8, ls=":", color="C3",
                label="runout's gap e sin(phi + theta), both gears")
    ax.set_xlabel("pinion angle [deg]")
    ax.set_ylabel("loaded static TE along the line of action [um]")
    ax.set_xlim(deg[0], deg[-1])
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.suptitle(title, fontsize=10)
    return fig


def _peak_label(order: float, z1: int, ratio: float) -> str:
    """``"2 z1"``, ``"z1 + 1"``, ``"z1 - z1/z2"`` or the order itself."""
    n = int(round(order / z1))
    rest = order - n * z1
    if n == 0 and ratio != 1.0:  # the gear's own orders: k turns of the gear per z2 / z1
        for k in (1, 2, 3):
            if abs(order - k * ratio) < 1e-9:
                return f"{k if k > 1 else ''} z1/z2".strip()
    head = "z1" if n == 1 else f"{n} z1"
    if n >= 1 and abs(rest) < 1e-9:
        return head
    for k in (1, 2, 3):
        if n >= 1 and abs(abs(rest) - k) < 1e-9:
            return f"{head} {'+' if rest > 0 else '-'} {k}"
        if n >= 1 and ratio != 1.0 and abs(abs(rest) - k * ratio) < 1e-9:
            return f"{head} {'+' if rest > 0 else '-'} {k if k > 1 else ''}z1/z2"
    return f"{order:.4g}"


def plot_revolution_spectrum(spectrum: Spectrum, gear_teeth: int, title: str,
                             fig: Figure | None = None) -> Figure:
    """TE amplitude (um, log scale) against the order per pinion revolution up to 4.5 mesh
    orders; the mesh orders dotted, the largest peaks labelled, apart from their
    neighbours (mesh orders ``n z1``, sidebands ``n z1 +- k`` of the pinion and ``n z1 +- k
    z1/z2`` of the gear)."""
    if fig is None:
        fig = new_figure((10, 4.5), "constrained")
    ax = fig.subplots()
    z1 = spectrum.mesh_order
    keep = (spectrum.order > 0) & (spectrum.order <= 4.5 * z1)
    o, a = spectrum.order[keep], spectrum.amplitude[keep] * 1e6
    top = float(a.max()) if a.size and a.max() > 0 else 1.0
    floor = top * 1e-5
    ax.vlines(o, floor, np.maximum(a, floor), lw=1.0)
    for n in range(1, 5):
        ax.axvline(n * z1, color="0.6", ls=":", lw=0.8)
    ratio = z1 / gear_teeth
    labelled: list[float] = []
    for i in np.argsort(a)[::-1]:
        if a[i] <= floor * 10 or len(labelled) == _LABELLED:
            break
        if any(abs(o[i] - x) < 0.04 * 4.5 * z1 for x in labelled):
            continue  # a neighbour's label is already there
        labelled.append(float(o[i]))
        ax.annotate(_peak_label(float(o[i]), z1, ratio), (o[i], a[i]), fontsize=7,
                    xytext=(2, 3), textcoords="offset points", rotation=60)
    ax.set_yscale("log")
    ax.set_ylim(floor, top * 8)
    ax.set_xlim(0, 4.5 * z1)
    ax.set_xlabel(f"order per pinion revolution [-] (mesh orders n z1, z1 = {z1}, dotted)")
    ax.set_ylabel("TE amplitude [um]")
    fig.suptitle(title, fontsize=10)
    return fig


def plot_worst_pair(rev: LoadedRevolution, title: str, fig: Figure | None = None) -> Figure:
    """Largest Hertz pressure across the face (MPa) and the load (N) of the worst tooth pair
    along the roll coordinate (mm), over the band every other pair spans."""
    if fig is None:
        fig = new_figure((9, 6.5), "constrained")
    ax = fig.subplots(2, 1, sharex=True)
    c, worst = rev.contact, rev.worst_pair()
    t1, t2 = rev.point_teeth()
    pair_id = t1.astype(np.int64) * int(rev.teeth[1]) + t2
    key = c.point_position.astype(np.int64) * (int(rev.teeth[0]) * int(rev.teeth[1])) + pair_id
    groups, inv = np.unique(key, return_inverse=True)
    pressure = np.zeros(groups.size)
    np.maximum.at(pressure, inv, c.point_pressure)
    load = np.bincount(inv, weights=c.point_normal_load, minlength=groups.size)
    s = np.zeros(groups.size)  # the pair's roll coordinate at z = 0 (one per group)
    s[inv] = rev.pair_roll()
    gid = pair_id[np.unique(inv, return_index=True)[1]]
    chosen = gid == worst["pinion_tooth"] * int(rev.teeth[1]) + worst["gear_tooth"]
    grid = np.unique(np.round(s * 1e9)) * 1e-9
    for a, v, unit, label in ((ax[0], pressure * 1e-6, "MPa", "largest Hertz pressure"),
                              (ax[1], load, "N", "normal load of the pair")):
        idx = np.searchsorted(grid, np.round(s * 1e9) * 1e-9).clip(0, grid.size - 1)
        hi = np.full(grid.size, -np.inf)
        lo = np.full(grid.size, np.inf)
        np.maximum.at(hi, idx[~chosen], v[~chosen])
        np.minimum.at(lo, idx[~chosen], v[~chosen])
        ok = np.isfinite(hi)
        a.fill_between(grid[ok] * 1e3, lo[ok], hi[ok], color="0.8",
                       label="every other tooth pair (range)")
        order = np.argsort(s[chosen])
        a.plot(s[chosen][order] * 1e3, v[chosen][order], "o-", ms=2.5, lw=1.0, color="C3",
               label=f"pinion tooth {worst['pinion_tooth']} / gear tooth {worst['gear_tooth']}")
        a.set_ylabel(f"{label} [{unit}]")
        a.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax[1].set_xlabel("roll coordinate s0 + k p_bt of the pair along the line of action [mm] "
                     "(at z = 0)")
    ax[0].set_title(f"the worst tooth pair: largest pressure {worst['pressure_Pa'] * 1e-6:.4g} "
                    "MPa over the span", fontsize=9)
    fig.suptitle(title, fontsize=10)
    return fig
